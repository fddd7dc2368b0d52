// The lane kernels of `pair.rs`, written once for the lane types `F` and `M` and their `ln`
// and `exp`, and included in `pair::x2` (two lanes, SSE2) and `pair::x4` (four, AVX2).

/// Largest |argument| of the two-lane exponential the kernels pass without a check of their own.
const EXP_RANGE: f64 = 700.0;

/// Whether every argument `y` lies in the two-lane exponential's range.
#[inline(always)]
pub(crate) fn exp_range(y: F) -> M {
    y.abs().lt(F::splat(EXP_RANGE))
}

/// [`film::thermal_reduction_ln`] in every lane for finite `ln_load`; valid where
/// |0.64 `ln_load`| < 700 (the mask).
#[inline(always)]
pub(crate) fn thermal_reduction_ln(ln_load: F, ph_e: F, ln_slide_roll: F) -> (F, M) {
    let s083 = exp(0.83 * ln_slide_roll.min(F::splat(std::f64::consts::LN_2)).max(F::splat(-700.0)));
    let num = 1.0 - 13.2 * ph_e * exp(0.42 * ln_load);
    let den = 1.0 + 0.213 * (1.0 + 2.23 * s083) * exp(0.64 * ln_load);
    ((num / den).max(F::splat(film::MIN_THERMAL_FACTOR)), exp_range(0.64 * ln_load))
}

/// [`Lubricant::raceway_mu_film`] of `lub` under the mixed law `mixed` in every lane, for `w`, `p_mean`, `u_e`, `v_s` > 0
/// (the film reduced by inlet heating `h`, its logarithm `ln_h`, ln `v_s`); the mask: the
/// lanes whose value is valid.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn raceway_mu_film(
    lub: &Lubricant,
    w: F,
    p_mean: F,
    h: F,
    ln_h: F,
    u_e: F,
    v_s: F,
    ln_vs: F,
    boundary_slide_roll: F,
    mixed: Mixed,
) -> (F, M) {
    let zero = F::splat(0.0);
    let share = match mixed {
        Mixed::FilmRatio if lub.sigma > 0.0 => asperity_share(h / lub.sigma),
        Mixed::FilmRatio => zero,
        Mixed::Weight(w) => F::splat(w),
    };
    // the film's stress, per lane its viscosity from the table
    let ln_eta = ln_eta(&lub.viscosity, p_mean);
    let (stress, ok) = thermal_eyring_stress_ln(&lub.rheology, p_mean, ln_eta, h, 0.5 * w / p_mean, u_e, v_s, ln_vs, ln_h);
    let film = share.lt(F::splat(1.0)).select(stress / p_mean, zero);
    let asperities = share.gt(zero);
    let boundary = if asperities.any() {
        asperities.select(mixed.boundary_scale() * boundary_mu(boundary_slide_roll), zero)
    } else {
        zero
    };
    // a lane whose film does not enter (share 1) is valid whatever its film equation did
    let ok = ok | share.ge(F::splat(1.0));
    (share * boundary + (1.0 - share) * film, ok)
}

/// `traction::thermal_eyring_stress_ln` in every lane: film shear stress |tau| (Pa) at mean
/// pressure `pressure`, ln viscosity `ln_eta`, film `film` >= 1e-9 m, half-width, entrainment
/// speed, sliding speed `v_s` > 0 and the logarithms of `v_s` and of the film; the mask as
/// [`solve_thermal_eyring`]'s.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn thermal_eyring_stress_ln(
    r: &Rheology,
    pressure: F,
    ln_eta: F,
    film: F,
    half_width: F,
    entrainment: F,
    v_s: F,
    ln_vs: F,
    ln_h: F,
) -> (F, M) {
    let zero = F::splat(0.0);
    let tau0 = r.eyring_stress;
    let h = film.max(F::splat(1e-9));
    // X = eta gamma_dot / tau_0
    let ln_x = ln_eta + ln_vs - ln_h.max(F::splat(LN_MIN_FILM)) - r.ln_eyring_stress;
    // temperature rise per unit stress (surface flash + film mean), times beta_p tau_0
    let b = half_width.max(zero);
    let peclet = entrainment.abs() * b * (0.5 / STEEL_DIFFUSIVITY);
    let heat = 0.376 * b / (STEEL_CONDUCTIVITY * (peclet + 1.0).sqrt()) + h / (12.0 * r.conductivity);
    let beta = (r.beta_per_roelands * (ln_eta + 9.67)).max(F::splat(r.beta));
    let heating = beta * tau0 * v_s * heat;
    let (y, ok) = solve_thermal_eyring(ln_x, heating);
    let mut tau = tau0 * y;
    if r.shear_modulus > 0.0 {
        // elastic entry (Maxwell), where u_e > 0 and tau > 0
        let ratio = 2.0 * b * r.shear_modulus * v_s / (entrainment.abs() * tau * h);
        let entered = tau.gt(zero) & entrainment.abs().gt(zero);
        tau = entered.select(tau * maxwell_mean(ratio), tau);
    }
    // smooth minimum with the limiting shear stress (traction::limit)
    let tau_l = r.limiting_shear * pressure;
    let (t2, l2) = (tau * tau, tau_l * tau_l);
    (tau_l.gt(zero).select(tau * tau_l / (t2 * t2 + l2 * l2).sqrt().sqrt(), tau), ok)
}

/// `ViscosityTable::ln_eta` in every lane (Barus' law lane-wise, Roelands' table per lane).
#[inline(always)]
fn ln_eta(viscosity: &ViscosityTable, p: F) -> F {
    match viscosity.barus_law() {
        Some((ln_eta0, alpha)) => ln_eta0 + (alpha * p.max(F::splat(0.0))).min(F::splat(60.0)),
        None => {
            let p = p.to_array();
            F::from_fn(|i| viscosity.ln_eta(p[i]))
        }
    }
}

/// [`super::asperity_share`] in every lane.
#[inline(always)]
fn asperity_share(lambda: F) -> F {
    let x = (lambda - 1.5) / (0.01 - 1.5);
    let x2 = x * x;
    let blend = x2 * x2 * x2;
    lambda
        .lt(F::splat(0.01))
        .select(F::splat(1.0), lambda.ge(F::splat(1.5)).select(F::splat(0.0), blend))
}

/// [`super::boundary_mu`] in every lane (its exponential floored at e^-700, as good as 0).
#[inline(always)]
fn boundary_mu(slide_roll: F) -> F {
    let s = slide_roll.abs();
    (-0.1 + 22.28 * s) * exp((-181.46 * s).max(F::splat(-700.0))) + 0.1
}

/// `traction::maxwell_mean` in every lane (the exponential only where a lane needs it).
#[inline(always)]
fn maxwell_mean(ratio: F) -> F {
    let small = ratio.lt(F::splat(1e-4));
    let large = ratio.gt(F::splat(40.0));
    let mut mean = large.select(1.0 - 1.0 / ratio, 0.5 * ratio * (1.0 - ratio / 3.0));
    let mid = !(small | large);
    if mid.any() {
        mean = mid.select(1.0 - (1.0 - exp(-(ratio.min(F::splat(40.0))))) / ratio, mean);
    }
    mean
}

/// `traction::solve_thermal_eyring` in every lane, by Halley's method: within the table's
/// range (`eyring_table`: ln X in [-12, 12.25), B in [0, 7]) one step from the table's
/// bicubic read, below it (B in range) one from the small-X closed form (both within 1e-14
/// of the root), elsewhere as `traction::solve_thermal_eyring_halley`
/// (the same root to rounding in 2-3 evaluations), from the regimes' closed forms with the
/// same bracket and stopping rule, until every lane stops; asinh(X) where B = `heating` is 0.
/// The mask: lanes that stopped as the scalar solver does (within 60 steps, exponentials in
/// range).
#[inline(always)]
fn solve_thermal_eyring(ln_x: F, heating: F) -> (F, M) {
    let zero = F::splat(0.0);
    let mut ok = ln_x.gt(F::splat(-EXP_RANGE));
    // without heating the closed form (asinh_exp)
    let isothermal = !heating.gt(zero);
    let mut active = ok & !isothermal;
    // the table's lanes, and those below it: one Halley step from its read or from the
    // small-X closed form (`eyring_table`)
    let (mut y, on, below) = table_start(ln_x, heating);
    let mut tabulated = active & (on | below);
    if (active & !on).any() {
        // start: ln(2X) / (1 + B) for X > 1, X / (1 + B X) below
        let large = ln_x.gt(zero);
        let mut start = (ln_x + std::f64::consts::LN_2) / (1.0 + heating);
        if !large.all() {
            let x0 = exp(ln_x.min(zero));
            start = large.select(start, x0 / (1.0 + heating * x0));
        }
        y = on.select(y, start);
    }
    let (mut lo, mut hi) = (zero, F::splat(f64::INFINITY));
    let mut out = y;
    if isothermal.any() {
        out = isothermal.select(asinh_exp_and_slope(ln_x).0, out);
    }
    for _ in 0..60 {
        if !active.any() {
            break;
        }
        let g = ln_x - heating * y;
        let (asinh, dz, x) = asinh_exp_slope_and_x(g);
        ok = ok & (g.gt(F::splat(-EXP_RANGE)) | !active);
        let f = y - asinh;
        // f' = 1 + B dz, f'' = -B^2 dz / (1 + e^2g)
        let d1 = 1.0 + heating * dz;
        let d2 = -(heating * heating) * dz / (1.0 + x * x);
        let step = 2.0 * f * d1 / (2.0 * d1 * d1 - f * d2);
        let above = f.gt(zero);
        hi = above.select(y, hi);
        lo = above.select(lo, y);
        let done = active & (tabulated | step.abs().le(1e-9 * y.max(F::splat(1e-300))));
        tabulated = M::splat(false);
        out = done.select(y - step, out);
        active = active & !done;
        let next = y - step;
        let inside = next.gt(lo) & next.lt(hi);
        y = inside.select(next, 0.5 * (lo + hi.min(2.0 * y.max(lo))));
    }
    (out, ok & !active)
}

/// The bicubic read of the table of the film equation's root (`eyring_table`), the lanes
/// where (ln X, B) lies in its range and the read is positive (others read 1), and the lanes
/// below its range in ln X with B in it.
#[inline(always)]
fn table_start(ln_x: F, heating: F) -> (F, M, M) {
    use super::super::eyring_table as t;
    let one = F::splat(1.0);
    let xg = (ln_x - t::FIRST_LN_X) * (1.0 / t::STEP_LN_X);
    let xc = (1.0 / (1.0 + heating) - t::FIRST_C) * (1.0 / t::STEP_C);
    let in_c = xc.ge(one) & xc.lt(F::splat((t::NODES_C - 2) as f64));
    let below = in_c & xg.lt(one);
    let on = in_c & xg.ge(one) & xg.lt(F::splat((t::NODES_LN_X - 2) as f64));
    if !on.any() {
        return (one, on, below);
    }
    let (xg, xc) = (on.select(xg, one), on.select(xc, one));
    let ((i, _), (j, _)) = (xg.trunc_i32(), xc.trunc_i32());
    let (wg, wc) = (crate::fastmath::lagrange4_weights(xg - i), crate::fastmath::lagrange4_weights(xc - j));
    // a lane's 16 values from 4 (j NODES_LN_X + i - 1): nodes i - 1 .. i + 2 in ln X, each
    // with its four in c
    let table = t::table();
    let start = 4.0 * (j * t::NODES_LN_X as f64 + i - 1.0);
    // SAFETY: 1 <= i <= NODES_LN_X - 3 and 1 <= j <= NODES_C - 3 (`on`; other lanes at node
    // (1, 1)), so 0 <= start and start + 16 <= 4 NODES_LN_X (NODES_C - 2) <= table.len()
    let (lo, hi) = unsafe { (F::gather8_at(table, start), F::gather8_at(table, start + 8.0)) };
    let column = |v: &[F; 8], h: usize| wc[0] * v[4 * h] + wc[1] * v[4 * h + 1] + wc[2] * v[4 * h + 2] + wc[3] * v[4 * h + 3];
    let read = wg[0] * column(&lo, 0) + wg[1] * column(&lo, 1) + wg[2] * column(&hi, 0) + wg[3] * column(&hi, 1);
    let on = on & read.gt(F::splat(0.0));
    (on.select(read, one), on, below)
}

/// asinh(e^g) and its slope in g (`traction::asinh_exp_and_slope`) in every lane.
#[inline(always)]
fn asinh_exp_and_slope(g: F) -> (F, F) {
    let (asinh, dz, _) = asinh_exp_slope_and_x(g);
    (asinh, dz)
}

/// `traction::asinh_exp_slope_and_x` in every lane: asinh(e^g), its slope and e^g (infinite
/// above g = 20; e^g floored at e^-700: the caller checks g).
#[inline(always)]
fn asinh_exp_slope_and_x(g: F) -> (F, F, F) {
    let big = g.gt(F::splat(20.0));
    let x = exp(g.min(F::splat(20.0)).max(F::splat(-EXP_RANGE)));
    let root = (x * x + 1.0).sqrt();
    // the series below x = 0.1, the logarithm above, each only where a lane needs it
    let small = x.lt(F::splat(0.1));
    let mut asinh = big.select(g + std::f64::consts::LN_2, F::splat(0.0));
    if small.any() {
        let x2 = x * x;
        let series = x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (3.0 / 40.0 + x2 * (-15.0 / 336.0 + x2 * (105.0 / 3456.0)))));
        asinh = small.select(series, asinh);
    }
    let log = !(small | big);
    if log.any() {
        asinh = log.select(ln(x + root), asinh);
    }
    let inf = F::splat(f64::INFINITY);
    (asinh, big.select(F::splat(1.0), x / root), big.select(inf, x))
}

/// The Gauss sum of the rib film's stress over its 8 rings (`rib::X`, `rib::W`), `F::N` rings
/// at a time, added ring by ring in order (sliding speed `v` > 0, film `h`, entrainment
/// `u_e`, half-width `a`, peak pressure `p_h`, ln `v`, ln `h`); a ring outside the lane
/// kernels' range by the scalar law.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn rib_rings(r: &Rheology, viscosity: &ViscosityTable, v: f64, h: f64, u_e: f64, a: f64, p_h: f64, ln_v: f64, ln_h: f64) -> f64 {
    let mut sum = 0.0;
    for k in (0..8).step_by(F::N) {
        let root = F::from_fn(|i| (1.0 - rib::X[k + i] * rib::X[k + i]).max(0.0).sqrt());
        let p = p_h * root;
        let ln_eta = ln_eta(viscosity, p);
        let (tau, ok) = thermal_eyring_stress_ln(
            r,
            p,
            ln_eta,
            F::splat(h),
            a * root,
            F::splat(u_e),
            F::splat(v),
            F::splat(ln_v),
            F::splat(ln_h),
        );
        let mut tau = tau.to_array();
        let bits = ok.bits();
        if bits != M::FULL {
            let (p, root) = (p.to_array(), root.to_array());
            for i in 0..F::N {
                if bits & (1 << i) == 0 {
                    tau[i] = super::super::traction::thermal_eyring_stress_ln(r, &rib::ring(viscosity, p[i], root[i], h, a, u_e), v, ln_v, ln_h);
                }
            }
        }
        for (i, t) in tau.iter().enumerate() {
            sum += rib::W[k + i] * t * rib::X[k + i];
        }
    }
    sum
}
