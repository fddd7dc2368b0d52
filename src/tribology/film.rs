//! Film thickness of the lubricated contacts.
//!
//! - Raceway slices (line contacts): Hamrock's central film, as [W25] Eq. (5) writes it
//!   (Hamrock, Schmid & Jacobson, "Fundamentals of Fluid Film Lubrication", 2nd ed., 2004).
//! - Roller end on the rib (elliptical contact): Chittenden, Dowson, Dunn & Taylor (1985)
//!   central film with entrainment along the principal direction of radius `r_e` [W25].
//! - Inlet shear heating: the isothermal film is multiplied by the thermal reduction factor
//!   of Gupta, Cheng, Zhu, Forster & Schrand (1992, "Viscoelastic effects in MIL-L-7808-type
//!   lubricant, Part I", Tribology Transactions 35(2) 269-274):
//!   phi_T = (1 - 13.2 (p_h/E') L^0.42) / (1 + 0.213 (1 + 2.23 s^0.83) L^0.64), with the
//!   thermal loading L = beta eta0 u_e^2 / k (beta the temperature-viscosity coefficient, k the
//!   oil's thermal conductivity) and s the slide-to-roll ratio. [W25] and [L22] use isothermal
//!   films; `oil.beta` = 0 gives them back.

use crate::fastmath as fm;

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
    let side = 1.0 - libm::exp(-1.23 * fm::powf(r_s / r_e, 2.0 / 3.0));
    r_e * 4.31 * fm::powf(u, 0.68) * fm::powf(g, 0.49) * fm::powf(w, -0.073) * side
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
    libm::log(2.922_f64)
        + 0.692 * libm::log(eta0 / e_prime)
        + 0.470 * libm::log(alpha * e_prime)
        + 0.166 * libm::log(e_prime)
        + 0.474 * libm::log(r_bar)
}

/// Least value of the thermal reduction factor: the regression's numerator reaches zero at
/// contact pressures and speeds far beyond its data (p_h/E' L^0.42 = 0.076); a film never
/// vanishes by inlet heating alone.
pub const MIN_THERMAL_FACTOR: f64 = 0.05;

/// Inlet shear-heating reduction of the isothermal film (Gupta et al. 1992), for the
/// thermal loading `load` = beta eta0 u_e^2 / k, the Hertz pressure over E' `ph_e` and the
/// slide-to-roll ratio `slide_roll`. 1 at `load` = 0.
#[inline]
pub fn thermal_reduction(load: f64, ph_e: f64, slide_roll: f64) -> f64 {
    if !(load > 0.0) {
        return 1.0;
    }
    let ln_l = fm::ln(load);
    let s = slide_roll.abs().min(2.0);
    let s083 = if s > 0.0 { fm::exp(0.83 * fm::ln(s)) } else { 0.0 };
    let num = 1.0 - 13.2 * ph_e * fm::exp(0.42 * ln_l);
    let den = 1.0 + 0.213 * (1.0 + 2.23 * s083) * fm::exp(0.64 * ln_l);
    (num / den).max(MIN_THERMAL_FACTOR)
}

/// [`thermal_reduction`] from logarithms: `ln_load` = ln L (-inf: no heating), `ln_slide_roll`
/// = ln s (-inf: pure rolling); the same value, three exponentials.
#[inline(always)]
pub fn thermal_reduction_ln(ln_load: f64, ph_e: f64, ln_slide_roll: f64) -> f64 {
    if !(ln_load > f64::NEG_INFINITY) {
        return 1.0;
    }
    let s083 = fm::exp(0.83 * ln_slide_roll.min(std::f64::consts::LN_2).max(-700.0));
    let num = 1.0 - 13.2 * ph_e * fm::exp(0.42 * ln_load);
    let den = 1.0 + 0.213 * (1.0 + 2.23 * s083) * fm::exp(0.64 * ln_load);
    (num / den).max(MIN_THERMAL_FACTOR)
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn fast_film_equals_the_hamrock_formula() {
        let (eta0, alpha, e, r) = (0.033, 1.28e-8, 2.18e11, 0.012);
        let c = film_line_log_constant(eta0, alpha, e, r);
        for (u, w) in [(16.0, 3e5), (0.01, 1e3), (40.0, 1e7)] {
            let a = film_line_fast(c, u, w);
            let b = film_line(eta0, alpha, e, u, r, w);
            assert!((a - b).abs() < 1e-12 * b, "{a} {b}");
        }
    }

    /// The regression's own values: 1 without heating, falls with the thermal loading and
    /// with sliding, hand value at L = 2, p_h/E' = 3e-3, s = 0.1.
    #[test]
    fn thermal_reduction_of_the_film() {
        assert_eq!(thermal_reduction(0.0, 3e-3, 0.1), 1.0);
        let hand = (1.0 - 13.2 * 3e-3 * 2.0_f64.powf(0.42)) / (1.0 + 0.213 * (1.0 + 2.23 * 0.1_f64.powf(0.83)) * 2.0_f64.powf(0.64));
        let f = thermal_reduction(2.0, 3e-3, 0.1);
        assert!((f - hand).abs() < 1e-12, "{f} vs {hand}");
        assert!(f > 0.6 && f < 0.7, "{f}");
        let mut last = 1.0;
        for l in [0.01, 0.1, 1.0, 10.0, 100.0] {
            let f = thermal_reduction(l, 3e-3, 0.0);
            assert!(f < last, "falls with the thermal loading");
            assert!(thermal_reduction(l, 3e-3, 0.5) < f, "and with sliding");
            last = f;
        }
        // the floor beyond the regression's range
        assert_eq!(thermal_reduction(1e6, 1e-2, 1.0), MIN_THERMAL_FACTOR);
        // the logarithmic form gives the same value
        for (l, s) in [(2.0, 0.1), (0.03, 0.0), (40.0, 1.7), (5.0, 3.0)] {
            let a = thermal_reduction(l, 3e-3, s);
            let b = thermal_reduction_ln(f64::ln(l), 3e-3, f64::ln(s));
            assert!((a - b).abs() < 1e-13, "{l} {s}: {a} vs {b}");
        }
        assert_eq!(thermal_reduction_ln(f64::NEG_INFINITY, 3e-3, 0.0), 1.0);
    }
}
