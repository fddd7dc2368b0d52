//! Lubrication and traction (MODEL.md section 4; friction-torque pieces of section 7).
//!
//! - Film thickness: Hamrock central film for line contacts (raceway slices) and Chittenden
//!   et al. (1985) central film for the elliptical roller-end/flange contact [W25].
//! - Traction coefficient against slide-to-roll ratio and film ratio lambda: the boundary
//!   law of [W25], a full-film law, and the [W25] sixth-power blend in the mixed regime.
//!   The full-film regression of Wang, Yang & Wang (2004) is not available to us; in its
//!   place a physically based EHL traction is used: Eyring shear of the film at the
//!   Roelands viscosity of the mean Hertz pressure, capped by a limiting shear stress
//!   tau_L = 0.08 p (documented choice, see `full_film_mu`).
//! - Rolling resistance of an EHL line contact: Zhou & Hoeprich (1991),
//!   F = (4.318 / alpha) (G U)^0.658 W^0.3635 R l, the Harris-type regression used for
//!   tapered roller bearing torque (it replaces the garbled [L22] formula).
//! - Flange sliding [L22]: asperity share mu0 exp(-1.8 Lambda^1.2) of the rib load plus the
//!   viscous film traction integrated over the contact ellipse [W25].
//! - Dry Coulomb [D19]: mu regularised smoothly at zero sliding speed.

use crate::fastmath as fm;
use std::f64::consts::PI;

/// Hamrock central film thickness of a line contact.
/// `u_e` entrainment speed, `r_bar` equivalent radius, `w` load per unit length.
pub fn film_line(eta0: f64, alpha: f64, e_prime: f64, u_e: f64, r_bar: f64, w: f64) -> f64 {
    if u_e <= 0.0 || w <= 0.0 {
        return 0.0;
    }
    let u = eta0 * u_e / (e_prime * r_bar);
    let g = alpha * e_prime;
    let wd = w / (e_prime * r_bar);
    r_bar * 2.922 * fm::powf(u, 0.692) * fm::powf(g, 0.470) * fm::powf(wd, -0.166)
}

/// Chittenden et al. central film of an elliptical contact with entrainment along the
/// principal direction of radius `r_e` (side-leakage direction radius `r_s`), load `q`.
pub fn film_point(eta0: f64, alpha: f64, e_prime: f64, u_e: f64, r_e: f64, r_s: f64, q: f64) -> f64 {
    if u_e <= 0.0 || q <= 0.0 {
        return 0.0;
    }
    let u = eta0 * u_e / (e_prime * r_e);
    let g = alpha * e_prime;
    let w = q / (e_prime * r_e * r_e);
    let side = 1.0 - (-1.23 * fm::powf(r_s / r_e, 2.0 / 3.0)).exp();
    r_e * 4.31 * fm::powf(u, 0.68) * fm::powf(g, 0.49) * fm::powf(w, -0.073) * side
}

/// Roelands viscosity at pressure `p` (z0 = 0.4), as written in MODEL.md section 4.
pub fn roelands_viscosity(eta0: f64, p: f64) -> f64 {
    roelands_viscosity_with(eta0, fm::ln(eta0) + 9.67, p)
}

/// [`roelands_viscosity`] with `ln_eta0_967` = ln(eta0) + 9.67 precomputed.
#[inline]
pub fn roelands_viscosity_with(eta0: f64, ln_eta0_967: f64, p: f64) -> f64 {
    const Z0: f64 = 0.4;
    let p = p.max(0.0);
    let expo = ln_eta0_967 * (-1.0 + fm::powf(1.0 + 5.1e-9 * p, Z0));
    eta0 * fm::exp(expo.min(60.0))
}

/// Roelands viscosity tabulated in ln(eta) against pressure for one oil (step 1 MPa up to
/// 5 GPa, linear interpolation: relative error below 1e-5; the formula beyond the table).
#[derive(Debug, Clone)]
pub struct ViscosityTable {
    eta0: f64,
    ln_eta0_967: f64,
    /// ln eta at k STEP (fixed length: the interpolation needs no bounds checks).
    ln_eta: Box<[f64; ViscosityTable::N]>,
}

impl ViscosityTable {
    const STEP: f64 = 1e6;
    const N: usize = 5001;

    pub fn new(eta0: f64) -> ViscosityTable {
        let ln_eta0_967 = eta0.ln() + 9.67;
        let ln_eta: Vec<f64> = (0..Self::N)
            .map(|k| roelands_viscosity_with(eta0, ln_eta0_967, k as f64 * Self::STEP).ln())
            .collect();
        let ln_eta = ln_eta.into_boxed_slice().try_into().expect("table length N");
        ViscosityTable { eta0, ln_eta0_967, ln_eta }
    }

    /// Viscosity at pressure `p` (Pa).
    #[inline]
    pub fn eta(&self, p: f64) -> f64 {
        let u = p.max(0.0) / Self::STEP;
        // also catches p = +inf or NaN (u as usize would saturate or be 0)
        if !(u < (Self::N - 1) as f64) {
            return roelands_viscosity_with(self.eta0, self.ln_eta0_967, p);
        }
        let k = u as usize;
        let f = u - k as f64;
        fm::exp(self.ln_eta[k] + f * (self.ln_eta[k + 1] - self.ln_eta[k]))
    }

    /// ln of [`ViscosityTable::eta`] (the interpolated logarithm itself inside the table).
    #[inline(always)]
    pub fn ln_eta(&self, p: f64) -> f64 {
        let u = p.max(0.0) * (1.0 / Self::STEP);
        // beyond the last interval (k + 1 >= N): the formula
        if !(u < (Self::N - 1) as f64) {
            return self.ln_eta_outside(p);
        }
        // SAFETY: 0 <= u < N - 1 (p.max(0.0) is never NaN), so the truncation is in range
        let k: usize = unsafe { u.to_int_unchecked() };
        let f = u - k as f64;
        let (a, b) = (self.ln_eta[k], self.ln_eta[(k + 1).min(Self::N - 1)]);
        a + f * (b - a)
    }

    /// [`ViscosityTable::ln_eta`] above the table (out of line, rare).
    #[cold]
    #[inline(never)]
    fn ln_eta_outside(&self, p: f64) -> f64 {
        fm::ln(roelands_viscosity_with(self.eta0, self.ln_eta0_967, p))
    }
}

/// Boundary traction coefficient of [W25]: (-0.1 + 22.28 s) exp(-181.46 s) + 0.1.
pub fn boundary_mu(slide_roll: f64) -> f64 {
    let s = slide_roll.abs();
    (-0.1 + 22.28 * s) * fm::exp(-181.46 * s) + 0.1
}

/// Film thickness from precomputed logarithms: the Hamrock line-contact film is
/// h = exp(ln_c + 0.692 ln u_e - 0.166 ln w) with ln_c = ln(2.922 (eta0/E')^0.692 (alpha E')^0.470 E'^0.166 R^0.474),
/// which [`film_line_log_constant`] gives per slice (same value as [`film_line`]).
#[inline]
pub fn film_line_fast(ln_c: f64, u_e: f64, w: f64) -> f64 {
    if u_e <= 0.0 || w <= 0.0 {
        return 0.0;
    }
    fm::exp(ln_c + 0.692 * fm::ln(u_e) - 0.166 * fm::ln(w))
}

/// The constant of [`film_line_fast`] for one slice.
pub fn film_line_log_constant(eta0: f64, alpha: f64, e_prime: f64, r_bar: f64) -> f64 {
    (2.922_f64).ln() + 0.692 * (eta0 / e_prime).ln() + 0.470 * (alpha * e_prime).ln() + 0.166 * e_prime.ln() + 0.474 * r_bar.ln()
}

/// Limiting shear stress coefficient: tau_L = LIMITING_SHEAR * p.
pub const LIMITING_SHEAR: f64 = 0.08;
/// Eyring stress of the oil (Pa), typical of mineral oils (Johnson & Tevaarwerk 1977: 2..10 MPa).
pub const EYRING_STRESS: f64 = 5.0e6;

/// Full-film traction coefficient (signed like `v_s`): mean shear stress of an Eyring film
/// over the mean Hertz pressure, smoothly capped at the limiting shear stress.
/// `v_s` sliding speed, `h` film thickness, `p_mean` mean contact pressure.
pub fn full_film_mu(eta0: f64, v_s: f64, h: f64, p_mean: f64) -> f64 {
    full_film_mu_with(eta0, fm::ln(eta0) + 9.67, v_s, h, p_mean)
}

/// [`full_film_mu`] with ln(eta0) + 9.67 precomputed.
#[inline]
pub fn full_film_mu_with(eta0: f64, ln_eta0_967: f64, v_s: f64, h: f64, p_mean: f64) -> f64 {
    if p_mean <= 0.0 || v_s == 0.0 {
        return 0.0;
    }
    full_film_mu_at_viscosity(roelands_viscosity_with(eta0, ln_eta0_967, p_mean), v_s, h, p_mean)
}

/// [`full_film_mu`] with the film viscosity `eta` at the mean pressure already known.
#[inline]
pub fn full_film_mu_at_viscosity(eta: f64, v_s: f64, h: f64, p_mean: f64) -> f64 {
    if p_mean <= 0.0 || v_s == 0.0 {
        return 0.0;
    }
    let h = h.max(1e-9);
    let x = eta * v_s.abs() / (h * EYRING_STRESS);
    // asinh x = ln(x + sqrt(x^2 + 1)); below 0.1 its series to x^9 is exact to 1e-12
    let asinh = if x < 0.1 {
        let x2 = x * x;
        x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (3.0 / 40.0 + x2 * (-15.0 / 336.0 + x2 * (105.0 / 3456.0)))))
    } else {
        fm::ln(x + (x * x + 1.0).sqrt())
    };
    let tau_e = EYRING_STRESS * asinh;
    let tau_l = LIMITING_SHEAR * p_mean;
    // smooth minimum of the Eyring stress and the limiting shear stress
    let tau = tau_e * tau_l / (tau_e.powi(4) + tau_l.powi(4)).sqrt().sqrt();
    v_s.signum() * tau / p_mean
}

/// Traction coefficient over all regimes [W25]: boundary below lambda = 0.01, full film
/// above 1.5, and mu = (mu_BL - mu_FL) ((lambda - 1.5)/(0.01 - 1.5))^6 + mu_FL between.
pub fn traction_mu(lambda: f64, slide_roll: f64, mu_full_film: f64) -> f64 {
    let mu_bl = boundary_mu(slide_roll);
    if lambda < 0.01 {
        mu_bl
    } else if lambda >= 1.5 {
        mu_full_film
    } else {
        let w = ((lambda - 1.5) / (0.01 - 1.5)).powi(6);
        (mu_bl - mu_full_film) * w + mu_full_film
    }
}

/// Zhou & Hoeprich (1991) EHL rolling resistance of a line contact of length `l`:
/// F = (4.318 / alpha) (G U)^0.658 W^0.3635 R l with G = alpha E', U = eta0 u/(E' R),
/// W = q/(E' R l).
pub fn rolling_resistance(eta0: f64, alpha: f64, e_prime: f64, u: f64, r_bar: f64, q: f64, l: f64) -> f64 {
    if u <= 0.0 || q <= 0.0 || alpha <= 0.0 {
        return 0.0;
    }
    let gu = alpha * eta0 * u / r_bar;
    let w = q / (e_prime * r_bar * l);
    4.318 / alpha * fm::powf(gu, 0.658) * fm::powf(w, 0.3635) * r_bar * l
}

/// Asperity (boundary) friction share of the rib contact [L22]: mu0 exp(-1.8 Lambda^1.2).
pub fn flange_boundary_mu(mu0: f64, film_ratio: f64) -> f64 {
    mu0 * (-1.8 * film_ratio.max(0.0).powf(1.2)).exp()
}

/// Viscous traction of the roller-end/rib film [W25]: integral over the contact ellipse of
/// tau = eta(p) v_s / h, capped at the limiting shear stress 0.08 p, with the Hertz pressure
/// p = p_h sqrt(1 - x^2/a^2 - y^2/b^2). Integrated in polar coordinates of the unit disc
/// (Gauss-Legendre in the radius, the integrand does not depend on the angle).
pub fn flange_viscous_traction(eta0: f64, v_s: f64, h: f64, a: f64, b: f64, p_h: f64) -> f64 {
    flange_viscous_traction_with(eta0, fm::ln(eta0) + 9.67, v_s, h, a, b, p_h)
}

/// [`flange_viscous_traction`] with ln(eta0) + 9.67 (`fastmath::ln`) precomputed: the same value.
pub fn flange_viscous_traction_with(eta0: f64, ln_eta0_967: f64, v_s: f64, h: f64, a: f64, b: f64, p_h: f64) -> f64 {
    if a <= 0.0 || b <= 0.0 || v_s == 0.0 {
        return 0.0;
    }
    const X: [f64; 8] = [
        0.019_855_071_751_231_856,
        0.101_666_761_293_186_63,
        0.237_233_795_041_835_5,
        0.408_282_678_752_175_1,
        0.591_717_321_247_824_9,
        0.762_766_204_958_164_5,
        0.898_333_238_706_813_4,
        0.980_144_928_248_768_2,
    ];
    const W: [f64; 8] = [
        0.050_614_268_145_188_13,
        0.111_190_517_226_687_24,
        0.156_853_322_938_943_64,
        0.181_341_891_689_180_99,
        0.181_341_891_689_180_99,
        0.156_853_322_938_943_64,
        0.111_190_517_226_687_24,
        0.050_614_268_145_188_13,
    ];
    let h = h.max(1e-9);
    let mut sum = 0.0;
    for k in 0..8 {
        let rho = X[k];
        let p = p_h * (1.0 - rho * rho).max(0.0).sqrt();
        let tau_visc = roelands_viscosity_with(eta0, ln_eta0_967, p) * v_s.abs() / h;
        let tau = tau_visc.min(LIMITING_SHEAR * p);
        sum += W[k] * tau * rho;
    }
    2.0 * PI * a * b * sum
}

/// Regularisation speed of dry Coulomb friction (m/s): below it friction fades smoothly to
/// zero with the sliding speed.
pub const DRY_REGULARISATION_SPEED: f64 = 1e-4;

/// Dry Coulomb coefficient, smooth in the sliding speed: mu v / sqrt(v^2 + v_eps^2).
pub fn dry_mu(mu: f64, v_s: f64) -> f64 {
    mu * v_s / (v_s * v_s + DRY_REGULARISATION_SPEED * DRY_REGULARISATION_SPEED).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boundary_law_is_zero_without_sliding_and_tends_to_point_one() {
        assert!(boundary_mu(0.0).abs() < 1e-15);
        assert!((boundary_mu(1.0) - 0.1).abs() < 1e-6);
        // peak of the boundary curve near s = 0.0 .. 0.02
        let peak = (0..1000).map(|i| boundary_mu(i as f64 * 1e-4)).fold(0.0, f64::max);
        assert!(peak > 0.1 && peak < 0.2, "peak {peak}");
    }

    #[test]
    fn mixed_law_blends_continuously() {
        let (s, fl) = (0.05, 0.03);
        assert!((traction_mu(0.01, s, fl) - boundary_mu(s)).abs() < 1e-12);
        assert!((traction_mu(1.5 - 1e-12, s, fl) - fl).abs() < 1e-9);
        assert_eq!(traction_mu(2.0, s, fl), fl);
    }

    #[test]
    fn film_thickness_hand_value_and_exponents() {
        let (eta0, alpha, e, u, r, w) = (0.033, 1.28e-8, 2.18e11, 10.0, 0.01, 1e6);
        let h = film_line(eta0, alpha, e, u, r, w);
        let hand = 2.922 * (eta0 * u).powf(0.692) * alpha.powf(0.470) * r.powf(0.474) * e.powf(-0.056) * w.powf(-0.166);
        assert!((h - hand).abs() < 1e-12 * hand, "{h} vs {hand}");
        assert!(h > 1e-7 && h < 5e-6, "h = {h}");
        let h2 = film_line(eta0, alpha, e, 2.0 * u, r, w);
        assert!(((h2 / h) - 2.0_f64.powf(0.692)).abs() < 1e-12);
        let hp = film_point(eta0, alpha, e, u, 0.2, 0.15, 1000.0);
        let hand = 4.31
            * (eta0 * u).powf(0.68)
            * alpha.powf(0.49)
            * 0.2_f64.powf(0.466)
            * e.powf(-0.117)
            * 1000.0_f64.powf(-0.073)
            * (1.0 - (-1.23 * (0.15_f64 / 0.2).powf(2.0 / 3.0)).exp());
        assert!((hp - hand).abs() < 1e-12 * hand);
    }

    #[test]
    fn viscosity_table_matches_roelands() {
        let t = ViscosityTable::new(0.033);
        for p in [0.0, 3.3e5, 1.7e8, 9.99e8, 2.5e9, 4.99e9, 6e9] {
            let (a, b) = (t.eta(p), roelands_viscosity(0.033, p));
            assert!((a - b).abs() < 1e-5 * b, "{p}: {a} vs {b}");
        }
    }

    /// A diverging state (an unstable fixed-step integrator) can produce an infinite pressure:
    /// the table must fall back to the formula, not index out of bounds.
    #[test]
    fn viscosity_table_survives_infinite_and_nan_pressure() {
        let t = ViscosityTable::new(0.033);
        assert_eq!(t.eta(f64::INFINITY), roelands_viscosity(0.033, f64::INFINITY));
        assert!(t.ln_eta(f64::INFINITY) >= t.ln_eta(5e9));
        assert_eq!(t.eta(f64::NAN), t.eta(0.0), "NaN pressure reads as zero");
        assert_eq!(t.eta(f64::NEG_INFINITY), t.eta(0.0));
    }

    #[test]
    fn eyring_series_and_logarithm_meet() {
        // the asinh series below x = 0.1 and the logarithm above agree at the switch
        let (eta, h, p) = (20.0, 1e-6, 1e9);
        let v = 0.1 * h * EYRING_STRESS / eta;
        let below = full_film_mu_at_viscosity(eta, v * (1.0 - 1e-12), h, p);
        let above = full_film_mu_at_viscosity(eta, v * (1.0 + 1e-12), h, p);
        assert!((below - above).abs() < 1e-10 * above, "{below} {above}");
    }

    #[test]
    fn fast_film_equals_the_hamrock_formula() {
        let (eta0, alpha, e, r) = (0.033, 1.28e-8, 2.18e11, 0.012);
        let c = film_line_log_constant(eta0, alpha, e, r);
        for (u, w) in [(16.0, 3e5), (0.01, 1e3), (40.0, 1e7)] {
            let a = film_line_fast(c, u, w);
            let b = film_line(eta0, alpha, e, u, r, w);
            assert!((a - b).abs() < 1e-12 * b, "{a} {b}");
        }
    }

    #[test]
    fn full_film_traction_is_smooth_odd_and_limited() {
        assert_eq!(full_film_mu(0.033, 0.0, 1e-7, 1e9), 0.0);
        let a = full_film_mu(0.033, 1e-3, 1e-7, 1e9);
        let b = full_film_mu(0.033, 1e-2, 1e-7, 1e9);
        assert!(a > 0.0 && b > a);
        // Newtonian limit at small shear: mu = eta(p) v / (h p)
        let eta = roelands_viscosity(0.033, 1e9);
        let tiny = full_film_mu(0.033, 1e-9, 1e-7, 1e9);
        assert!((tiny - eta * 1e-9 / 1e-7 / 1e9).abs() < 1e-6 * tiny);
        // odd in the sliding speed
        assert_eq!(full_film_mu(0.033, -1e-2, 1e-7, 1e9), -b);
        // heavy shear: Eyring's logarithmic growth, below the limiting shear stress
        let c = full_film_mu(0.033, 100.0, 1e-7, 1e9);
        assert!(c <= LIMITING_SHEAR && c > 0.03, "{c}");
    }

    #[test]
    fn flange_traction_capped_by_limiting_shear() {
        // Very thin film, huge shear rate: traction equals the limiting-shear integral
        // 0.08 * Q (the mean of 0.08 p over the Hertz ellipse).
        let (a, b, ph) = (1e-3, 5e-4, 1e9);
        let q = 2.0 / 3.0 * PI * a * b * ph;
        let f = flange_viscous_traction(0.033, 10.0, 1e-12, a, b, ph);
        assert!((f - LIMITING_SHEAR * q).abs() < 1e-3 * f, "{f} vs {}", LIMITING_SHEAR * q);
    }

    #[test]
    fn dry_coulomb_is_smooth_and_saturates() {
        assert_eq!(dry_mu(0.3, 0.0), 0.0);
        assert!((dry_mu(0.3, 1.0) - 0.3).abs() < 1e-7);
        assert!((dry_mu(0.3, -1.0) + 0.3).abs() < 1e-7);
    }

    #[test]
    fn rolling_resistance_scaling() {
        let f1 = rolling_resistance(0.033, 1.28e-8, 2.18e11, 10.0, 0.012, 5000.0, 0.04);
        let f2 = rolling_resistance(0.033, 1.28e-8, 2.18e11, 20.0, 0.012, 5000.0, 0.04);
        assert!(f1 > 0.01 && f1 < 10.0, "{f1}");
        assert!(((f2 / f1) - 2.0_f64.powf(0.658)).abs() < 1e-12);
    }
}
