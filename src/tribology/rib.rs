//! Friction of the spherical roller end on the conical rib (flange).
//!
//! `traction` = 0: the contact's load is shared between asperities and film by the film
//! ratio Lambda = h_c / sigma_f, with sigma_f the composite roughness of roller end and rib
//! (`flange.roughness`): the [W25] regime law, as at the raceways ([W25] §2.2: "the friction
//! coefficient under ML and BL states is the same as that at the roller/raceway pair"),
//! mu = w mu_BL(s) + (1 - w) mu_film, w = 1 below Lambda = 0.01, 0 above 1.5 and
//! ((Lambda - 1.5) / (0.01 - 1.5))^6 between; mu_BL is Kragelskii's boundary law of [W25]; the
//! film part is the shear stress of the raceways' full-film law (`traction.rs`) integrated
//! over the Hertz ellipse, p = p_h sqrt(1 - x^2/a^2 - y^2/b^2) (the law at each pressure,
//! with its limiting shear and heating; Newtonian where pressure and shear are low).
//!
//! `traction` = 1 (the isothermal laws, kept for comparison with the studies): asperity share mu0 exp(-1.8 Lambda^1.2) of
//! the load [L22] plus the viscous film traction of [W25], tau = eta(p) v_s / h at the
//! Roelands viscosity (z = 0.4), capped at 0.08 p.

use super::traction::{self, FilmContact, Rheology};
use super::viscosity::{roelands_viscosity_with, ViscosityTable};
use crate::fastmath as fm;
use std::f64::consts::PI;

/// Gauss-Legendre nodes and weights on [0, 1] (8 points) for the radial integral over the
/// unit disc; the integrand depends on the radius only.
pub(crate) const X: [f64; 8] = [
    0.019_855_071_751_231_856,
    0.101_666_761_293_186_63,
    0.237_233_795_041_835_5,
    0.408_282_678_752_175_1,
    0.591_717_321_247_824_9,
    0.762_766_204_958_164_5,
    0.898_333_238_706_813_4,
    0.980_144_928_248_768_2,
];
pub(crate) const W: [f64; 8] = [
    0.050_614_268_145_188_13,
    0.111_190_517_226_687_24,
    0.156_853_322_938_943_64,
    0.181_341_891_689_180_99,
    0.181_341_891_689_180_99,
    0.156_853_322_938_943_64,
    0.111_190_517_226_687_24,
    0.050_614_268_145_188_13,
];

/// Asperity (boundary) friction share of the rib contact [L22]: mu0 exp(-1.8 Lambda^1.2).
pub fn flange_boundary_mu(mu0: f64, film_ratio: f64) -> f64 {
    mu0 * libm::exp(-1.8 * libm::pow(film_ratio.max(0.0), 1.2))
}

/// Viscous traction of the roller-end/rib film [W25]: integral over the contact ellipse of
/// tau = eta(p) v_s / h, capped at the limiting shear stress 0.08 p, with the Hertz pressure
/// p = p_h sqrt(1 - x^2/a^2 - y^2/b^2). Integrated in polar coordinates of the unit disc
/// (Gauss-Legendre in the radius, the integrand does not depend on the angle).
pub fn flange_viscous_traction(eta0: f64, v_s: f64, h: f64, a: f64, b: f64, p_h: f64) -> f64 {
    flange_viscous_traction_with(eta0, crate::fastmath::ln(eta0) + 9.67, v_s, h, a, b, p_h)
}

/// [`flange_viscous_traction`] with ln(eta0) + 9.67 (`fastmath::ln`) precomputed: the same value.
pub fn flange_viscous_traction_with(eta0: f64, ln_eta0_967: f64, v_s: f64, h: f64, a: f64, b: f64, p_h: f64) -> f64 {
    if a <= 0.0 || b <= 0.0 || v_s == 0.0 {
        return 0.0;
    }
    let h = h.max(1e-9);
    let mut sum = 0.0;
    for k in 0..8 {
        let rho = X[k];
        let p = p_h * (1.0 - rho * rho).max(0.0).sqrt();
        let tau_visc = roelands_viscosity_with(eta0, ln_eta0_967, p) * v_s.abs() / h;
        let tau = tau_visc.min(super::LIMITING_SHEAR * p);
        sum += W[k] * tau * rho;
    }
    2.0 * PI * a * b * sum
}

/// The rib film's traction force |F| (N) with the thermal Eyring law of the raceways, over
/// the Hertz ellipse of semi-axes `a`, `b` (a along the entrainment) and peak pressure `p_h`,
/// film `h`, sliding speed `v_s`, entrainment speed `u_e`.
#[allow(clippy::too_many_arguments)]
pub fn rib_film_traction(rheology: &Rheology, viscosity: &ViscosityTable, v_s: f64, h: f64, u_e: f64, a: f64, b: f64, p_h: f64) -> f64 {
    rib_film_traction_with(rheology, viscosity, v_s, h, u_e, a, b, p_h, traction::thermal_eyring_stress_ln)
}

/// [`rib_film_traction`] with the film equation solved by Halley's method
/// ([`traction::thermal_eyring_stress_ln_halley`]: the same force to rounding; the
/// quasi-static model's).
#[allow(clippy::too_many_arguments)]
pub fn rib_film_traction_halley(
    rheology: &Rheology,
    viscosity: &ViscosityTable,
    v_s: f64,
    h: f64,
    u_e: f64,
    a: f64,
    b: f64,
    p_h: f64,
) -> f64 {
    rib_film_traction_with(
        rheology,
        viscosity,
        v_s,
        h,
        u_e,
        a,
        b,
        p_h,
        traction::thermal_eyring_stress_ln_halley,
    )
}

/// The Gauss sum of [`rib_film_traction`] with the stress law `stress(rheology, contact, |v_s|,
/// ln |v_s|, ln h)`; ln |v_s|, ln h and the rings' sqrt(1 - rho^2) once for all rings (the
/// values `traction::thermal_eyring_stress` computed at each ring).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn rib_film_traction_with<S: Fn(&Rheology, &FilmContact, f64, f64, f64) -> f64>(
    rheology: &Rheology,
    viscosity: &ViscosityTable,
    v_s: f64,
    h: f64,
    u_e: f64,
    a: f64,
    b: f64,
    p_h: f64,
    stress: S,
) -> f64 {
    if a <= 0.0 || b <= 0.0 || v_s == 0.0 {
        return 0.0;
    }
    let v = v_s.abs();
    let (ln_v, ln_h) = if v > 0.0 { (fm::ln(v), fm::ln(h.max(1e-9))) } else { (0.0, 0.0) };
    let mut sum = 0.0;
    for k in 0..8 {
        let rho = X[k];
        let root = (1.0 - rho * rho).max(0.0).sqrt();
        let p = p_h * root;
        let tau = if v > 0.0 && p > 0.0 {
            stress(rheology, &ring(viscosity, p, root, h, a, u_e), v, ln_v, ln_h)
        } else {
            0.0
        };
        sum += W[k] * tau * rho;
    }
    2.0 * PI * a * b * sum
}

/// The film of the Gauss ring at pressure `p` = p_h `root` of an ellipse with semi-axis `a`
/// along the entrainment (speed `u_e`), film `h`.
#[inline(always)]
pub(crate) fn ring(viscosity: &ViscosityTable, p: f64, root: f64, h: f64, a: f64, u_e: f64) -> FilmContact {
    FilmContact {
        pressure: p,
        ln_eta: viscosity.ln_eta(p),
        film: h,
        // the chord along the entrainment through this ring of the ellipse
        half_width: a * root,
        entrainment: u_e,
    }
}

/// Share of the load carried by asperities in the [W25] regime law at film ratio `lambda`:
/// 1 below 0.01, 0 from 1.5, ((lambda - 1.5) / (0.01 - 1.5))^6 between.
#[inline]
pub fn asperity_share(lambda: f64) -> f64 {
    if lambda < 0.01 {
        1.0
    } else if lambda >= 1.5 {
        0.0
    } else {
        ((lambda - 1.5) / (0.01 - 1.5)).powi(6)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flange_traction_capped_by_limiting_shear() {
        // Very thin film, huge shear rate: traction equals the limiting-shear integral
        // 0.08 * Q (the mean of 0.08 p over the Hertz ellipse).
        let (a, b, ph) = (1e-3, 5e-4, 1e9);
        let q = 2.0 / 3.0 * PI * a * b * ph;
        let f = flange_viscous_traction(0.033, 10.0, 1e-12, a, b, ph);
        assert!(
            (f - super::super::LIMITING_SHEAR * q).abs() < 1e-3 * f,
            "{f} vs {}",
            super::super::LIMITING_SHEAR * q
        );
    }

    /// The thermal rib film: at low pressure and shear it is the Newtonian integral of
    /// eta(p) v_s / h over the ellipse; at a huge shear rate without heating the limiting
    /// shear stress Lambda p integrated, Lambda Q.
    #[test]
    fn rib_film_is_newtonian_at_low_shear_and_limited_at_high() {
        let visc = ViscosityTable::for_oil(0.033, 1.28e-8, super::super::Piezoviscosity::Barus);
        let r = Rheology::new(5e6, 0.08, 1e9, 0.03, 0.13, 0.033);
        let (a, b, ph, h, ue) = (1.2e-3, 1.0e-3, 4.5e8, 2e-6, 15.0);
        let v = 1e-6;
        let f = rib_film_traction(&r, &visc, v, h, ue, a, b, ph);
        // Newtonian integral by brute force over the disc (polar, fine grid)
        let n = 4000;
        let newton: f64 = (0..n)
            .map(|i| {
                let rho = (i as f64 + 0.5) / n as f64;
                let p = ph * (1.0 - rho * rho).sqrt();
                visc.eta(p) * v / h * rho / n as f64
            })
            .sum::<f64>()
            * 2.0
            * PI
            * a
            * b;
        assert!((f - newton).abs() < 2e-3 * newton, "{f} vs {newton}");
        let cold = Rheology::new(5e6, 0.08, 1e9, 0.0, 0.13, 0.033);
        let q = 2.0 / 3.0 * PI * a * b * ph;
        let f = rib_film_traction(
            &cold,
            &ViscosityTable::for_oil(0.033, 1e-7, super::super::Piezoviscosity::Barus),
            100.0,
            1e-8,
            ue,
            a,
            b,
            ph,
        );
        // (8-point quadrature of p rho: 6e-4 relative)
        assert!(f <= 0.08 * q * (1.0 + 1e-3) && f > 0.97 * 0.08 * q, "{f} vs {}", 0.08 * q);
    }

    #[test]
    fn asperity_share_is_continuous() {
        assert_eq!(asperity_share(0.0), 1.0);
        assert!((asperity_share(0.01) - 1.0).abs() < 1e-12);
        assert!(asperity_share(1.5 - 1e-9) < 1e-12);
        assert_eq!(asperity_share(2.0), 0.0);
    }
}
