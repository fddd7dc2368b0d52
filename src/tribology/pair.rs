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
//!
//! The kernels are written once (`pair_lanes.rs`) for a lane type and compiled twice: [`x2`],
//! two lanes on SSE2, and [`x4`], four lanes on AVX2 for the CPUs that have it. Lane for lane
//! they do the same operations (`simd_math::x4`), so both give the same bits.

use super::traction::Rheology;
use super::ViscosityTable;
use crate::fastmath as fm;
use std::f64::consts::PI;

/// The kernels in two lanes (SSE2, every x86-64 CPU).
pub(crate) mod x2 {
    use super::super::traction::{Rheology, LN_MIN_FILM, STEEL_CONDUCTIVITY, STEEL_DIFFUSIVITY};
    use super::super::{film, rib, Lubricant, Mixed, ViscosityTable};
    use crate::simd_math::{exp, ln, F2 as F, M2 as M};
    include!("pair_lanes.rs");
}

/// The kernels in four lanes (AVX2: only inside functions compiled for it, `simd_math::x4`).
pub(crate) mod x4 {
    use super::super::traction::{Rheology, LN_MIN_FILM, STEEL_CONDUCTIVITY, STEEL_DIFFUSIVITY};
    use super::super::{film, rib, Lubricant, Mixed, ViscosityTable};
    use crate::simd_math::x4::{exp, ln, F4 as F, M4 as M};
    include!("pair_lanes.rs");
}

/// [`super::rib::rib_film_traction`] with the stress of two rings of its Gauss sum at a time:
/// the same force to rounding (the dynamic model's, through `Lubricant::rib_force`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn rib_film_traction(r: &Rheology, viscosity: &ViscosityTable, v_s: f64, h: f64, u_e: f64, a: f64, b: f64, p_h: f64) -> f64 {
    rib_film_with(r, viscosity, v_s, h, u_e, a, b, p_h, x2::rib_rings)
}

/// [`rib_film_traction`] four rings at a time where the CPU has AVX2, else two: the same bits.
#[allow(clippy::too_many_arguments)]
pub(crate) fn rib_film_traction_four(
    r: &Rheology,
    viscosity: &ViscosityTable,
    v_s: f64,
    h: f64,
    u_e: f64,
    a: f64,
    b: f64,
    p_h: f64,
) -> f64 {
    if !crate::simd_math::x4::available() {
        return rib_film_traction(r, viscosity, v_s, h, u_e, a, b, p_h);
    }
    /// # Safety
    /// The CPU has AVX2.
    #[target_feature(enable = "avx2")]
    #[allow(clippy::too_many_arguments)]
    unsafe fn rings(r: &Rheology, viscosity: &ViscosityTable, v: f64, h: f64, u_e: f64, a: f64, p_h: f64, ln_v: f64, ln_h: f64) -> f64 {
        x4::rib_rings(r, viscosity, v, h, u_e, a, p_h, ln_v, ln_h)
    }
    // SAFETY: AVX2 is present (checked above).
    rib_film_with(
        r,
        viscosity,
        v_s,
        h,
        u_e,
        a,
        b,
        p_h,
        |r, vis, v, h, u_e, a, p_h, ln_v, ln_h| unsafe { rings(r, vis, v, h, u_e, a, p_h, ln_v, ln_h) },
    )
}

/// The rib film's force with its Gauss sum by `rings`; outside the lane kernels' range
/// (non-finite or degenerate arguments), the scalar law.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn rib_film_with(
    r: &Rheology,
    viscosity: &ViscosityTable,
    v_s: f64,
    h: f64,
    u_e: f64,
    a: f64,
    b: f64,
    p_h: f64,
    rings: impl Fn(&Rheology, &ViscosityTable, f64, f64, f64, f64, f64, f64, f64) -> f64,
) -> f64 {
    if a <= 0.0 || b <= 0.0 || v_s == 0.0 {
        return 0.0;
    }
    let v = v_s.abs();
    if !(v > 0.0 && v < f64::INFINITY && h.is_finite() && u_e.is_finite() && p_h > 0.0 && p_h < f64::INFINITY) {
        return super::rib_film_traction(r, viscosity, v_s, h, u_e, a, b, p_h);
    }
    let (ln_v, ln_h) = (fm::ln(v), fm::ln(h.max(1e-9)));
    2.0 * PI * a * b * rings(r, viscosity, v, h, u_e, a, p_h, ln_v, ln_h)
}
