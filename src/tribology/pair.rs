//! The lubricated raceway traction of two slices at once (x86-64, `simd_math`): the inlet
//! heating factor ([`film::thermal_reduction_ln`]) and the coefficient of the thermal Eyring
//! law ([`Lubricant::raceway_mu_film`]: asperity share, Eyring film equation, elastic entry,
//! limiting shear) in both lanes, and the rib film's Gauss sum two rings at a time. The same
//! formulas in the same order as the scalar code, with fdlibm's ln and exp (< 1 ulp;
//! `fastmath`'s round differently), and the film equation solved by Halley's method (the
//! scalar law of the dynamic model takes Newton's: the same root to rounding, in about half
//! the evaluations): the values agree with the scalar ones to rounding. The film equation
//! runs until both lanes have converged, each lane keeping the value at its own stopping step.
//!
//! Lanes outside the range the two-lane kernels take (an exponential's argument beyond
//! +-700, a film equation that does not converge as the scalar solver does) are reported by
//! the mask, and the caller evaluates them with the scalar code.

use super::traction::{Rheology, LN_MIN_FILM, STEEL_CONDUCTIVITY, STEEL_DIFFUSIVITY};
use super::{film, rib, Lubricant, ViscosityTable};
use crate::fastmath as fm;
use crate::simd_math::{self as sm, F2, M2};
use std::f64::consts::PI;

/// Largest |argument| of the two-lane exponential the kernels pass without a check of their own.
const EXP_RANGE: f64 = 700.0;

/// Whether every argument `y` lies in the two-lane exponential's range.
#[inline(always)]
pub(crate) fn exp_range(y: F2) -> M2 {
    y.abs().lt(F2::splat(EXP_RANGE))
}

/// [`film::thermal_reduction_ln`] in both lanes for finite `ln_load`; valid where
/// |0.64 `ln_load`| < 700 (the mask).
#[inline(always)]
pub(crate) fn thermal_reduction_ln(ln_load: F2, ph_e: F2, ln_slide_roll: F2) -> (F2, M2) {
    let s083 = sm::exp(0.83 * ln_slide_roll.min(F2::splat(std::f64::consts::LN_2)).max(F2::splat(-700.0)));
    let num = 1.0 - 13.2 * ph_e * sm::exp(0.42 * ln_load);
    let den = 1.0 + 0.213 * (1.0 + 2.23 * s083) * sm::exp(0.64 * ln_load);
    ((num / den).max(F2::splat(film::MIN_THERMAL_FACTOR)), exp_range(0.64 * ln_load))
}

impl Lubricant {
    /// [`Lubricant::raceway_mu_film`] in both lanes, for `w`, `p_mean`, `u_e`, `v_s` > 0 (the
    /// film reduced by inlet heating `h`, its logarithm `ln_h`, ln `v_s`); the mask: the lanes
    /// whose value is valid.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn raceway_mu_film_pair(
        &self,
        w: F2,
        p_mean: F2,
        h: F2,
        ln_h: F2,
        u_e: F2,
        v_s: F2,
        ln_vs: F2,
        boundary_slide_roll: F2,
    ) -> (F2, M2) {
        let zero = F2::splat(0.0);
        let share = if self.sigma > 0.0 { asperity_share(h / self.sigma) } else { zero };
        // the film's stress, per lane its viscosity from the table
        let ln_eta = ln_eta(&self.viscosity, p_mean);
        let (stress, ok) = thermal_eyring_stress_ln(&self.rheology, p_mean, ln_eta, h, 0.5 * w / p_mean, u_e, v_s, ln_vs, ln_h);
        let film = share.lt(F2::splat(1.0)).select(stress / p_mean, zero);
        let asperities = share.gt(zero);
        let boundary = if asperities.any() {
            asperities.select(boundary_mu(boundary_slide_roll), zero)
        } else {
            zero
        };
        // a lane whose film does not enter (share 1) is valid whatever its film equation did
        let ok = ok | share.ge(F2::splat(1.0));
        (share * boundary + (1.0 - share) * film, ok)
    }
}

/// `traction::thermal_eyring_stress_ln` in both lanes: film shear stress |tau| (Pa) at mean
/// pressure `pressure`, ln viscosity `ln_eta`, film `film` >= 1e-9 m, half-width, entrainment
/// speed, sliding speed `v_s` > 0 and the logarithms of `v_s` and of the film; the mask as
/// [`solve_thermal_eyring`]'s.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn thermal_eyring_stress_ln(
    r: &Rheology,
    pressure: F2,
    ln_eta: F2,
    film: F2,
    half_width: F2,
    entrainment: F2,
    v_s: F2,
    ln_vs: F2,
    ln_h: F2,
) -> (F2, M2) {
    let zero = F2::splat(0.0);
    let tau0 = r.eyring_stress;
    let h = film.max(F2::splat(1e-9));
    // X = eta gamma_dot / tau_0
    let ln_x = ln_eta + ln_vs - ln_h.max(F2::splat(LN_MIN_FILM)) - r.ln_eyring_stress;
    // temperature rise per unit stress (surface flash + film mean), times beta_p tau_0
    let b = half_width.max(zero);
    let peclet = entrainment.abs() * b * (0.5 / STEEL_DIFFUSIVITY);
    let heat = 0.376 * b / (STEEL_CONDUCTIVITY * (peclet + 1.0).sqrt()) + h / (12.0 * r.conductivity);
    let beta = (r.beta_per_roelands * (ln_eta + 9.67)).max(F2::splat(r.beta));
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

/// [`super::rib::rib_film_traction`] with the stress of two rings of its Gauss sum at a time:
/// the same force to rounding (the dynamic model's, through `Lubricant::rib_force_with`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn rib_film_traction(r: &Rheology, viscosity: &ViscosityTable, v_s: f64, h: f64, u_e: f64, a: f64, b: f64, p_h: f64) -> f64 {
    if a <= 0.0 || b <= 0.0 || v_s == 0.0 {
        return 0.0;
    }
    let v = v_s.abs();
    if !(v > 0.0 && v < f64::INFINITY && h.is_finite() && u_e.is_finite() && p_h > 0.0 && p_h < f64::INFINITY) {
        return super::rib_film_traction(r, viscosity, v_s, h, u_e, a, b, p_h);
    }
    let (ln_v, ln_h) = (fm::ln(v), fm::ln(h.max(1e-9)));
    let mut sum = 0.0;
    for k in (0..8).step_by(2) {
        let (rho0, rho1) = (rib::X[k], rib::X[k + 1]);
        let root = F2::new((1.0 - rho0 * rho0).max(0.0).sqrt(), (1.0 - rho1 * rho1).max(0.0).sqrt());
        let p = p_h * root;
        let ln_eta = ln_eta(viscosity, p);
        let (tau, ok) = thermal_eyring_stress_ln(
            r,
            p,
            ln_eta,
            F2::splat(h),
            a * root,
            F2::splat(u_e),
            F2::splat(v),
            F2::splat(ln_v),
            F2::splat(ln_h),
        );
        let [mut ta, mut tb] = tau.lanes();
        let bits = ok.bits();
        let ring =
            |p: f64, root: f64| super::traction::thermal_eyring_stress_ln(r, &rib::ring(viscosity, p, root, h, a, u_e), v, ln_v, ln_h);
        if bits != 3 {
            let ([pa, pb], [ra, rb]) = (p.lanes(), root.lanes());
            if bits & 1 == 0 {
                ta = ring(pa, ra);
            }
            if bits & 2 == 0 {
                tb = ring(pb, rb);
            }
        }
        sum += rib::W[k] * ta * rho0;
        sum += rib::W[k + 1] * tb * rho1;
    }
    2.0 * PI * a * b * sum
}

/// `ViscosityTable::ln_eta` in both lanes (Barus' law lane-wise, Roelands' table per lane).
#[inline(always)]
fn ln_eta(viscosity: &ViscosityTable, p: F2) -> F2 {
    match viscosity.barus_law() {
        Some((ln_eta0, alpha)) => ln_eta0 + (alpha * p.max(F2::splat(0.0))).min(F2::splat(60.0)),
        None => {
            let [a, b] = p.lanes();
            F2::new(viscosity.ln_eta(a), viscosity.ln_eta(b))
        }
    }
}

/// [`super::asperity_share`] in both lanes.
#[inline(always)]
fn asperity_share(lambda: F2) -> F2 {
    let x = (lambda - 1.5) / (0.01 - 1.5);
    let x2 = x * x;
    let blend = x2 * x2 * x2;
    lambda
        .lt(F2::splat(0.01))
        .select(F2::splat(1.0), lambda.ge(F2::splat(1.5)).select(F2::splat(0.0), blend))
}

/// [`super::boundary_mu`] in both lanes (its exponential floored at e^-700, as good as 0).
#[inline(always)]
fn boundary_mu(slide_roll: F2) -> F2 {
    let s = slide_roll.abs();
    (-0.1 + 22.28 * s) * sm::exp((-181.46 * s).max(F2::splat(-700.0))) + 0.1
}

/// `traction::maxwell_mean` in both lanes (the exponential only where a lane needs it).
#[inline(always)]
fn maxwell_mean(ratio: F2) -> F2 {
    let small = ratio.lt(F2::splat(1e-4));
    let large = ratio.gt(F2::splat(40.0));
    let mut mean = large.select(1.0 - 1.0 / ratio, 0.5 * ratio * (1.0 - ratio / 3.0));
    let mid = !(small | large);
    if mid.any() {
        mean = mid.select(1.0 - (1.0 - sm::exp(-(ratio.min(F2::splat(40.0))))) / ratio, mean);
    }
    mean
}

/// `traction::solve_thermal_eyring` in both lanes, by Halley's method as
/// `traction::solve_thermal_eyring_halley` (the same root to rounding in 2-3 evaluations
/// where Newton's takes 4-5), from the regimes' closed forms with the same bracket and
/// stopping rule, until both lanes stop; asinh(X) where B = `heating` is 0. The mask: lanes
/// that stopped as the scalar solver does (within 60 steps, exponentials in range).
#[inline(always)]
fn solve_thermal_eyring(ln_x: F2, heating: F2) -> (F2, M2) {
    let zero = F2::splat(0.0);
    // start: ln(2X) / (1 + B) for X > 1, X / (1 + B X) below
    let large = ln_x.gt(zero);
    let mut y = (ln_x + std::f64::consts::LN_2) / (1.0 + heating);
    if !large.all() {
        let x0 = sm::exp(ln_x.min(zero));
        y = large.select(y, x0 / (1.0 + heating * x0));
    }
    let mut ok = ln_x.gt(F2::splat(-EXP_RANGE));
    let (mut lo, mut hi) = (zero, F2::splat(f64::INFINITY));
    // without heating the closed form (asinh_exp)
    let isothermal = !heating.gt(zero);
    let mut out = y;
    if isothermal.any() {
        out = isothermal.select(asinh_exp_and_slope(ln_x).0, out);
    }
    let mut active = ok & !isothermal;
    for _ in 0..60 {
        if !active.any() {
            break;
        }
        let g = ln_x - heating * y;
        let (asinh, dz, x) = asinh_exp_slope_and_x(g);
        ok = ok & (g.gt(F2::splat(-EXP_RANGE)) | !active);
        let f = y - asinh;
        // f' = 1 + B dz, f'' = -B^2 dz / (1 + e^2g)
        let d1 = 1.0 + heating * dz;
        let d2 = -(heating * heating) * dz / (1.0 + x * x);
        let step = 2.0 * f * d1 / (2.0 * d1 * d1 - f * d2);
        let above = f.gt(zero);
        hi = above.select(y, hi);
        lo = above.select(lo, y);
        let done = active & step.abs().le(1e-9 * y.max(F2::splat(1e-300)));
        out = done.select(y - step, out);
        active = active & !done;
        let next = y - step;
        let inside = next.gt(lo) & next.lt(hi);
        y = inside.select(next, 0.5 * (lo + hi.min(2.0 * y.max(lo))));
    }
    (out, ok & !active)
}

/// asinh(e^g) and its slope in g (`traction::asinh_exp_and_slope`) in both lanes.
#[inline(always)]
fn asinh_exp_and_slope(g: F2) -> (F2, F2) {
    let (asinh, dz, _) = asinh_exp_slope_and_x(g);
    (asinh, dz)
}

/// `traction::asinh_exp_slope_and_x` in both lanes: asinh(e^g), its slope and e^g (infinite
/// above g = 20; e^g floored at e^-700: the caller checks g).
#[inline(always)]
fn asinh_exp_slope_and_x(g: F2) -> (F2, F2, F2) {
    let big = g.gt(F2::splat(20.0));
    let x = sm::exp(g.min(F2::splat(20.0)).max(F2::splat(-EXP_RANGE)));
    let root = (x * x + 1.0).sqrt();
    // the series below x = 0.1, the logarithm above, each only where a lane needs it
    let small = x.lt(F2::splat(0.1));
    let mut asinh = big.select(g + std::f64::consts::LN_2, F2::splat(0.0));
    if small.any() {
        let x2 = x * x;
        let series = x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (3.0 / 40.0 + x2 * (-15.0 / 336.0 + x2 * (105.0 / 3456.0)))));
        asinh = small.select(series, asinh);
    }
    let log = !(small | big);
    if log.any() {
        asinh = log.select(sm::ln(x + root), asinh);
    }
    let inf = F2::splat(f64::INFINITY);
    (asinh, big.select(F2::splat(1.0), x / root), big.select(inf, x))
}
