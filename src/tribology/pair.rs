//! The lubricated raceway traction of two slices at once (x86-64, `simd_math`): the inlet
//! heating factor ([`film::thermal_reduction_ln`]) and the coefficient of the thermal Eyring
//! law ([`Lubricant::raceway_mu_film`]: asperity share, Eyring film equation solved by
//! Newton's method, elastic entry, limiting shear) in both lanes. The same formulas in the
//! same order as the scalar code, with fdlibm's ln and exp (< 1 ulp; `fastmath`'s round
//! differently): the values agree with the scalar ones to rounding. The film equation runs
//! until both lanes have converged, each lane keeping the value at its own stopping step.
//!
//! Lanes outside the range the two-lane kernels take (an exponential's argument beyond
//! +-700, a film equation that does not converge as the scalar solver does) are reported by
//! the mask, and the caller evaluates them with the scalar code.

use super::traction::{LN_MIN_FILM, STEEL_CONDUCTIVITY, STEEL_DIFFUSIVITY};
use super::{film, Lubricant};
use crate::simd_math::{self as sm, F2, M2};

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
        // the film's stress (thermal_eyring_stress_with), per lane its viscosity from the table
        let r = &self.rheology;
        let [p0, p1] = p_mean.lanes();
        let ln_eta = F2::new(self.viscosity.ln_eta(p0), self.viscosity.ln_eta(p1));
        let half_width = 0.5 * w / p_mean;
        let tau0 = r.eyring_stress;
        let hf = h.max(F2::splat(1e-9));
        let ln_x = ln_eta + ln_vs - ln_h.max(F2::splat(LN_MIN_FILM)) - r.ln_eyring_stress;
        let b = half_width.max(zero);
        let peclet = u_e.abs() * b * (0.5 / STEEL_DIFFUSIVITY);
        let heat = 0.376 * b / (STEEL_CONDUCTIVITY * (peclet + 1.0).sqrt()) + hf / (12.0 * r.conductivity);
        let beta = (r.beta_per_roelands * (ln_eta + 9.67)).max(F2::splat(r.beta));
        let heating = beta * tau0 * v_s * heat;
        let (y, ok) = solve_thermal_eyring(ln_x, heating);
        let mut tau = tau0 * y;
        if r.shear_modulus > 0.0 {
            // elastic entry (Maxwell), where tau > 0 (u_e > 0 here)
            let ratio = 2.0 * b * r.shear_modulus * v_s / (u_e.abs() * tau * hf);
            tau = tau.gt(zero).select(tau * maxwell_mean(ratio), tau);
        }
        // smooth minimum with the limiting shear stress (traction::limit)
        let stress = if r.limiting_shear > 0.0 {
            let tau_l = r.limiting_shear * p_mean;
            let (t2, l2) = (tau * tau, tau_l * tau_l);
            tau * tau_l / (t2 * t2 + l2 * l2).sqrt().sqrt()
        } else {
            tau
        };
        let film = share.lt(F2::splat(1.0)).select(stress / p_mean, zero);
        let boundary = share.gt(zero).select(boundary_mu(boundary_slide_roll), zero);
        // a lane whose film does not enter (share 1) is valid whatever its film equation did
        let ok = ok | share.ge(F2::splat(1.0));
        (share * boundary + (1.0 - share) * film, ok)
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

/// `traction::maxwell_mean` in both lanes.
#[inline(always)]
fn maxwell_mean(ratio: F2) -> F2 {
    let small = 0.5 * ratio * (1.0 - ratio / 3.0);
    let large = 1.0 - 1.0 / ratio;
    let mid = 1.0 - (1.0 - sm::exp(-(ratio.min(F2::splat(40.0))))) / ratio;
    ratio
        .lt(F2::splat(1e-4))
        .select(small, ratio.gt(F2::splat(40.0)).select(large, mid))
}

/// `traction::solve_thermal_eyring` in both lanes: Newton from the regimes' closed forms with
/// the same bracket and stopping rule, until both lanes stop; asinh(X) where B = `heating` is
/// 0. The mask: lanes that stopped as the scalar solver does (within 60 steps, exponentials
/// in range).
#[inline(always)]
fn solve_thermal_eyring(ln_x: F2, heating: F2) -> (F2, M2) {
    let zero = F2::splat(0.0);
    let x0 = sm::exp(ln_x.min(zero));
    let mut y = ln_x
        .gt(zero)
        .select((ln_x + std::f64::consts::LN_2) / (1.0 + heating), x0 / (1.0 + heating * x0));
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
        let (asinh, dz) = asinh_exp_and_slope(g);
        ok = ok & (g.gt(F2::splat(-EXP_RANGE)) | !active);
        let f = y - asinh;
        let step = f / (1.0 + heating * dz);
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

/// `traction::asinh_exp_and_slope` in both lanes (e^g floored at e^-700: the caller checks g).
#[inline(always)]
fn asinh_exp_and_slope(g: F2) -> (F2, F2) {
    let big = g.gt(F2::splat(20.0));
    let x = sm::exp(g.min(F2::splat(20.0)).max(F2::splat(-EXP_RANGE)));
    let root = (x * x + 1.0).sqrt();
    let x2 = x * x;
    let series = x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (3.0 / 40.0 + x2 * (-15.0 / 336.0 + x2 * (105.0 / 3456.0)))));
    let asinh = big.select(g + std::f64::consts::LN_2, x.lt(F2::splat(0.1)).select(series, sm::ln(x + root)));
    (asinh, big.select(F2::splat(1.0), x / root))
}
