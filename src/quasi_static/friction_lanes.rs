// `FrictionModel::raceway_tabulated` and `raceway_sliced` in lanes, written once for the lane
// types `F`, `M` and their `ln` and `exp`, and included in `friction::lanes2` (two lanes,
// SSE2) and `friction::lanes4` (four, AVX2).

/// [`FrictionModel::raceway_tabulated`] `F::N` slices at a time: the logarithm of each load,
/// its place on the table's grid, the four-node interpolation of ln(traction coefficient)
/// and of the rolling resistance, and the first's exponential, in the lanes; the nodes gathered (and
/// computed where missing, by the same law as the scalar read) lane by lane. Lanes the table
/// does not serve (no sliding, above `table_max`, off the grid, a law not finite at a node)
/// take the law directly, as the scalar read does. The sums gather slices k, k + 1 of every
/// pair in two lanes and add the pairs in slice order, so two and four lanes add the same
/// numbers in the same order (a pair without a loaded slice adds exact zeros).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn raceway_tabulated_lanes(
    model: &FrictionModel,
    line: &ContactLine,
    consts: &[SliceConst],
    lanes: &LineLanes,
    table: &mut LoadTable,
    first: usize,
    loads: &[f64],
    speed: f64,
) -> RacewayFriction {
    // every node a lane of this raceway's lines can read lies within the table (see
    // `TableRead::friction`)
    assert!(2 * (first + loads.len()) * LOAD_GRID_NODES <= table.flat().len(), "friction table shorter than its lines");
    // first every group's place on the grid, then the reads: the logarithms (a division each)
    // are independent of one another, and the reads' loads do not wait on them inside one
    // long loop body (TRB130x230 at constant load: 6 % less time per doStep on Zen 3)
    let mut grid = [F::splat(0.0); GRID_GROUPS];
    let precomputed = loads.len() <= GRID_GROUPS * F::N;
    if precomputed {
        for (g, x) in grid.iter_mut().enumerate().take(loads.len().div_ceil(F::N)) {
            *x = grid_coordinate(group_loads(loads, g * F::N));
        }
    }
    let mut read = TableRead {
        model,
        line,
        consts,
        table,
        first,
        grid: precomputed.then_some(&grid),
    };
    raceway_lanes(lanes, loads, speed, &mut read)
}

/// Groups of slices whose grid coordinates [`raceway_tabulated_lanes`] computes ahead (longer
/// lines: each group's in its own read).
const GRID_GROUPS: usize = 32;

/// The loads of slices k .. k + `F::N` (past the line's end: zero).
#[inline(always)]
fn group_loads(loads: &[f64], k: usize) -> F {
    let ns = loads.len();
    if k + F::N <= ns {
        F::load(&loads[k..])
    } else {
        F::from_fn(|i| if k + i < ns { loads[k + i] } else { 0.0 })
    }
}

/// Each lane's place on the friction table's grid, (ln q - first node) / step (unloaded lanes:
/// that of 1 N; the read does not use them).
#[inline(always)]
fn grid_coordinate(q: F) -> F {
    (ln(q.gt(F::splat(0.0)).select(q, F::splat(1.0))) - LOAD_GRID_FIRST) * (1.0 / LOAD_GRID_STEP)
}

/// The table read of [`raceway_tabulated_lanes`]: a raceway's line, its slices' constants and
/// its lines of the friction table (from line `first`, all of them within the table).
struct TableRead<'a> {
    model: &'a FrictionModel,
    line: &'a ContactLine,
    consts: &'a [SliceConst],
    table: &'a mut LoadTable,
    first: usize,
    /// Each group's grid coordinate, computed ahead (short lines).
    grid: Option<&'a [F; GRID_GROUPS]>,
}

impl SliceLaws for TableRead<'_> {
    /// Slices `idx` (from `k`, in `group`) with loads `q`, loaded where `live`.
    #[inline(always)]
    fn friction(&mut self, k: usize, idx: [usize; F::N], q: F, live: M, group: &LaneGroup) -> (F, F) {
        let TableRead {
            model,
            line,
            consts,
            first,
            grid,
            ..
        } = *self;
        let table = &mut *self.table;
        let zero = F::splat(0.0);
        // the table's lanes: sliding, within its load range, on its grid
        let x = match grid {
            Some(grid) => grid[k / F::N],
            None => grid_coordinate(live.select(q, zero)),
        };
        let read = live & q.le(group_lanes(&group.table_max, k)) & x.ge(F::splat(1.0)) & x.lt(F::splat((LOAD_GRID_NODES - 2) as f64));
        let (whole, _) = x.trunc_i32();
        let t = x - whole;
        // the nodes (node n, function c at offset 2 n + c from a lane's first node
        // 2 ((first + k + i) NODES + cell - 1); lanes that are not read point at the start),
        // computed where missing. A lane read is loaded, so k + i < ns, and its cell lies in
        // 1 ..= NODES - 3: its eight values end within line first + k + i, inside the table
        // (`raceway_tabulated_lanes`).
        let line_start = F::splat((2 * (first + k) * LOAD_GRID_NODES) as f64 - 2.0) + F::from_fn(|i| (2 * LOAD_GRID_NODES * i) as f64);
        let start = read.select(line_start + 2.0 * whole, zero);
        // SAFETY: as above; unread lanes at 0, the table is not empty (it holds these lines).
        let mut v = unsafe { F::gather8_at(table.flat(), start) };
        let missing = read & !v.iter().fold(zero, |a, &b| a + b).lt(F::splat(f64::INFINITY));
        if missing.any() {
            let (bits, cell) = (missing.bits(), whole.to_array());
            for i in 0..F::N {
                if bits & (1 << i) != 0 {
                    let (c, r_bar) = (&consts[idx[i]], line.r_bar[idx[i]]);
                    table.nodes(first + idx[i], cell[i] as usize, |qn| model.slice_node(c, r_bar, qn));
                }
            }
            // SAFETY: as above
            v = unsafe { F::gather8_at(table.flat(), start) };
        }
        // the scalar read's weights, lane by lane the same operations
        let w = crate::fastmath::lagrange4_weights(t);
        let ln_mu = w[0] * v[0] + w[1] * v[2] + w[2] * v[4] + w[3] * v[6];
        let roll = w[0] * v[1] + w[1] * v[3] + w[2] * v[5] + w[3] * v[7];
        let ok = read & finite(ln_mu) & finite(roll);
        let rolls = group_lanes(&group.rolls, k).gt(zero);
        let mu = ok.select(exp(ok.select(ln_mu, zero)), zero);
        let rolling = (ok & rolls).select(roll, zero);
        // the lanes the table does not serve: the laws themselves
        scalar_laws(model, line, consts, idx, q, live & !ok, mu, rolling)
    }
}

/// [`FrictionModel::raceway_sliced`] (Halley) with the laws themselves in lanes: per slice its
/// film, inlet heating, thermal Eyring traction (`tribology::pair`) and EHL rolling
/// resistance, the same formulas as [`FrictionModel::slice_friction`] (to rounding: the lane
/// logarithm and exponential round differently); lanes outside the lane kernels' range, or
/// without entrainment, by the scalar law. For a speed that changes every step, where the
/// table would be rebuilt every step.
#[inline(always)]
pub(super) fn raceway_direct_lanes(
    model: &FrictionModel,
    line: &ContactLine,
    consts: &[SliceConst],
    lanes: &LineLanes,
    loads: &[f64],
    speed: f64,
) -> RacewayFriction {
    raceway_lanes(lanes, loads, speed, &mut DirectLaws { model, line, consts })
}

/// The laws of [`raceway_direct_lanes`]: a raceway's line and its slices' constants.
struct DirectLaws<'a> {
    model: &'a FrictionModel,
    line: &'a ContactLine,
    consts: &'a [SliceConst],
}

impl SliceLaws for DirectLaws<'_> {
    /// Slices `idx` (from `k`, in `group`) with loads `q`, loaded where `live`.
    #[inline(always)]
    fn friction(&mut self, k: usize, idx: [usize; F::N], q: F, live: M, group: &LaneGroup) -> (F, F) {
        use std::f64::consts::PI;
        let DirectLaws { model, line, consts } = *self;
        let lub = &model.lubricant;
        let e_prime = lub.e_prime;
        let slice_len = model.slice_len;
        let zero = F::splat(0.0);
        let one = F::splat(1.0);
        let per = |f: fn(&SliceConst) -> f64| F::from_fn(|i| f(&consts[idx[i]]));
        let (u_e, v_s) = (per(|c| c.u_e), per(|c| c.v_s));
        let regular = live & u_e.gt(zero) & v_s.gt(zero);
        let q = regular.select(q, one);
        let (u_e, v_s) = (regular.select(u_e, one), regular.select(v_s, one));
        let r_bar = F::from_fn(|i| line.r_bar[idx[i]]);
        // contact::line_contact_half_width, the mean pressure
        let w = q / F::splat(slice_len);
        let b = (8.0 * w * r_bar / (PI * e_prime)).sqrt();
        let p_mean = w / (2.0 * b);
        let p_h = 4.0 / PI * p_mean;
        // FrictionModel::heating
        let heated = per(|c| if c.heated { 1.0 } else { 0.0 }).gt(zero);
        let num = 1.0 - 13.2 * (p_h / e_prime) * per(|c| c.l042);
        let heating = heated.select((num / per(|c| c.heat_den)).max(F::splat(tr::film::MIN_THERMAL_FACTOR)), one);
        // the film W^-0.166 law, its logarithm
        let ln_w_er = ln(w / per(|c| c.e_r));
        let h = heating * (per(|c| c.film_a) * exp(-0.166 * ln_w_er));
        let ln_h = ln(h);
        let ln_vs = per(|c| c.ln_vs);
        let (mu, mut ok) = pair::raceway_mu_film(lub, w, p_mean, h, ln_h, u_e, v_s, ln_vs, per(|c| c.boundary_slide_roll), consts[idx[0]].mixed);
        ok = ok & pair::exp_range(-0.166 * ln_w_er);
        let rolls = group_lanes(&group.rolls, k).gt(zero);
        let ln_qr = ln(q / per(|c| c.e_r_l));
        ok = ok & (!rolls | pair::exp_range(0.246 * ln_qr));
        let rolling = rolls.select(
            heating * (per(|c| c.roll_a) * exp(rolls.select(0.246 * ln_qr, zero)) * slice_len),
            zero,
        );
        let ok = regular & ok & finite(mu) & finite(rolling);
        let (mu, rolling) = (ok.select(mu, zero), ok.select(rolling, zero));
        scalar_laws(model, line, consts, idx, q, live & !ok, mu, rolling)
    }
}

/// What the slice loop of both lane reads asks per group of slices: (traction coefficient,
/// rolling resistance) of slices `idx` (from `k`, in the four of `group`) at loads `q`,
/// loaded where `live`.
trait SliceLaws {
    fn friction(&mut self, k: usize, idx: [usize; F::N], q: F, live: M, group: &LaneGroup) -> (F, F);
}

/// Slices k .. k + `F::N` of one of a [`LaneGroup`]'s arrays (k a multiple of `F::N`).
#[inline(always)]
fn group_lanes(values: &[f64; 4], k: usize) -> F {
    if F::N == 4 {
        F::load(values)
    } else {
        F::load(&values[k % 4..])
    }
}

/// Whether each lane is finite (x - x is 0; NaN for inf and NaN).
#[inline(always)]
fn finite(x: F) -> M {
    (x - x).ge(F::splat(0.0))
}

/// (traction coefficient, rolling resistance) with the lanes `scalar` replaced by
/// [`FrictionModel::slice_friction`] (Halley) at their loads `q`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn scalar_laws(
    model: &FrictionModel,
    line: &ContactLine,
    consts: &[SliceConst],
    idx: [usize; F::N],
    q: F,
    scalar: M,
    mu: F,
    rolling: F,
) -> (F, F) {
    if !scalar.any() {
        return (mu, rolling);
    }
    let bits = scalar.bits();
    let (qa, mut ma, mut ra) = (q.to_array(), mu.to_array(), rolling.to_array());
    for i in 0..F::N {
        if bits & (1 << i) != 0 {
            (ma[i], ra[i]) = model.slice_friction::<true>(&consts[idx[i]], line.r_bar[idx[i]], qa[i]);
        }
    }
    (F::from_fn(|i| ma[i]), F::from_fn(|i| ra[i]))
}

/// The slice loop of both lane reads: `F::N` slices at a time, `law`
/// giving the loaded slices' (traction coefficient, rolling resistance); the sums gather
/// slices k, k + 1 of every pair in two lanes and add the pairs in slice order, so two and
/// four lanes add the same numbers in the same order (a pair without a loaded slice adds
/// exact zeros).
#[inline(always)]
fn raceway_lanes(lanes: &LineLanes, loads: &[f64], speed: f64, law: &mut impl SliceLaws) -> RacewayFriction {
    use crate::simd_math::F2;
    const N: usize = F::N;
    let sign = if speed < 0.0 { -1.0 } else { 1.0 };
    let zero = F::splat(0.0);
    let (mut torque, mut skew, mut slide_force, mut rolling_sum) = (F2::splat(0.0), F2::splat(0.0), F2::splat(0.0), F2::splat(0.0));
    let ns = loads.len();
    let mut k = 0;
    while k < ns {
        // past the last slice, lanes repeat it with no load
        let idx: [usize; N] = std::array::from_fn(|i| (k + i).min(ns - 1));
        let q = group_loads(loads, k);
        let live = q.gt(zero);
        if !live.any() {
            k += N;
            continue;
        }
        let group = &lanes.groups[k / 4];
        let (mu, rolling) = law.friction(k, idx, q, live, group);
        // the slices' shares (unloaded lanes: zero), as `raceway_tabulated` forms them
        let pick = |v: &[f64; 4]| group_lanes(v, k);
        let mq = live.select(mu * q, zero);
        let rolling = live.select(rolling, zero);
        let torque_k = mq * pick(&group.slide) + 2.0 * rolling * pick(&group.entrain);
        let skew_k = mq * sign * pick(&group.skew);
        let slide_k = mq * sign * pick(&group.sign);
        for h in 0..N / 2 {
            torque = torque + torque_k.half(h);
            skew = skew + skew_k.half(h);
            slide_force = slide_force + slide_k.half(h);
            rolling_sum = rolling_sum + rolling.half(h);
        }
        k += N;
    }
    RacewayFriction {
        torque: torque.lane_sum(),
        skew: skew.lane_sum(),
        slide_force: slide_force.lane_sum(),
        rolling: rolling_sum.lane_sum(),
    }
}
