// `FrictionModel::raceway_tabulated` in lanes, written once for the lane types `F`, `M` and
// their `ln` and `exp`, and included in `friction::lanes2` (two lanes, SSE2) and
// `friction::lanes4` (four, AVX2).

/// [`FrictionModel::raceway_tabulated`] `F::N` slices at a time: the logarithm of each load,
/// its place on the table's grid, the four-node interpolation of ln(traction coefficient) and
/// ln(rolling resistance / load) and their exponentials in the lanes; the nodes gathered (and
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
        let q = if k + N <= ns {
            F::load(&loads[k..])
        } else {
            F::from_fn(|i| if k + i < ns { loads[k + i] } else { 0.0 })
        };
        let live = q.gt(zero);
        if !live.any() {
            k += N;
            continue;
        }
        // the padded per-slice arrays (`LineLanes`)
        let pick = |v: &[f64]| F::load(&v[k..]);
        // the table's lanes: sliding, within its load range, on its grid
        let table_max = pick(&lanes.table_max);
        let x = (ln(live.select(q, F::splat(1.0))) - LOAD_GRID_FIRST) * (1.0 / LOAD_GRID_STEP);
        let read = live & q.le(table_max) & x.ge(F::splat(1.0)) & x.lt(F::splat((LOAD_GRID_NODES - 2) as f64));
        let read_bits = read.bits();
        let (whole, cell) = x.trunc_i32();
        let t = x - whole;
        // the nodes (node n, function c at offset 2 n + c from a lane's first node; lanes
        // that are not read point at the start), computed where missing
        let start: [usize; N] = std::array::from_fn(|i| {
            if read_bits & (1 << i) != 0 {
                2 * ((first + idx[i]) * LOAD_GRID_NODES + cell[i] as usize - 1)
            } else {
                0
            }
        });
        let mut v = gather_nodes(table.flat(), start);
        let missing = read & !v.iter().fold(zero, |a, &b| a + b).lt(F::splat(f64::INFINITY));
        if missing.any() {
            let bits = missing.bits();
            for i in 0..N {
                if bits & (1 << i) != 0 {
                    let (c, r_bar) = (&consts[idx[i]], line.r_bar[idx[i]]);
                    table.nodes(first + idx[i], cell[i] as usize, |qn| model.slice_node(c, r_bar, qn));
                }
            }
            v = gather_nodes(table.flat(), start);
        }
        // `LoadTable::weights`, lane by lane the same operations
        let (tm, t1, t2) = (t + 1.0, t - 1.0, t - 2.0);
        let w = [
            -t * t1 * t2 * (1.0 / 6.0),
            tm * t1 * t2 * 0.5,
            -tm * t * t2 * 0.5,
            tm * t * t1 * (1.0 / 6.0),
        ];
        let node = |j: usize| v[j];
        let ln_mu = w[0] * node(0) + w[1] * node(2) + w[2] * node(4) + w[3] * node(6);
        let ln_roll = w[0] * node(1) + w[1] * node(3) + w[2] * node(5) + w[3] * node(7);
        // finite: x - x is 0 (NaN for inf and NaN)
        let ok = read & (ln_mu - ln_mu).ge(zero) & (ln_roll - ln_roll).ge(zero);
        let rolls = pick(&lanes.rolls).gt(zero);
        let mut mu = ok.select(exp(ok.select(ln_mu, zero)), zero);
        let mut rolling = (ok & rolls).select(exp((ok & rolls).select(ln_roll, zero)) * q, zero);
        // the lanes the table does not serve: the laws themselves
        let direct = live & !ok;
        if direct.any() {
            let bits = direct.bits();
            let (qa, mut ma, mut ra) = (q.to_array(), mu.to_array(), rolling.to_array());
            for i in 0..N {
                if bits & (1 << i) != 0 {
                    (ma[i], ra[i]) = model.slice_friction::<true>(&consts[idx[i]], line.r_bar[idx[i]], qa[i]);
                }
            }
            (mu, rolling) = (F::from_fn(|i| ma[i]), F::from_fn(|i| ra[i]));
        }
        // the slices' shares (unloaded lanes: zero), as `raceway_tabulated` forms them
        let mq = live.select(mu * q, zero);
        let rolling = live.select(rolling, zero);
        let torque_k = mq * pick(&lanes.slide) + 2.0 * rolling * pick(&lanes.entrain);
        let skew_k = mq * sign * pick(&lanes.skew);
        let slide_k = mq * sign * pick(&lanes.sign);
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

/// The eight values from `start[i]` on (the four nodes' two functions) of every lane.
#[inline(always)]
fn gather_nodes(flat: &[f64], start: [usize; F::N]) -> [F; 8] {
    assert!(start.iter().all(|&s| s + 8 <= flat.len()));
    // SAFETY: every lane's eight values lie within the table (above).
    unsafe { F::gather8(flat, start) }
}
