//! Full-film traction of an EHL contact: the shear stress of the oil film against the sliding
//! speed (parameter `traction`).
//!
//! 0 (default) — thermal Eyring film with elastic entry and limiting shear:
//! - viscous flow after Eyring (1936), tau = tau_0 asinh(eta gamma_dot / tau_0), at the
//!   viscosity of the contact's mean pressure (`viscosity.rs`; Barus by default). The Eyring
//!   stress tau_0 is the oil's (`oil.eyringStress`; Johnson & Tevaarwerk, Proc. R. Soc. A 356
//!   (1977) 215: 2-10 MPa for mineral and synthetic oils at 0.5-1.5 GPa). In the Eyring
//!   regime tau grows with ln(eta), i.e. linearly with the pressure, so the stress at the mean
//!   pressure is the mean stress over the Hertz zone.
//! - shear heating: the film's heat tau v_s per unit area leaves through both surfaces.
//!   Across the film the temperature is the parabola of steady conduction, its mid-plane
//!   rise dT_m = tau v_s h / (8 k_oil); each surface's mean flash temperature under a moving
//!   band source of half-width b is dT_s = 0.752 (tau v_s / 2) b / (K_s sqrt(Pe)),
//!   Pe = u_e b / (2 kappa_s) (Carslaw & Jaeger 1959 / Jaeger 1942 fast-source limit:
//!   a surface point is heated for 2 b / u_e). The viscosity falls as exp(-beta_p dT), with
//!   the oil's temperature-viscosity coefficient `oil.beta` raised by pressure as in Roelands'
//!   viscosity-temperature-pressure equation (Roelands 1966: d ln eta / dT = -S0 (ln eta +
//!   9.67) / (T - 138), so beta_p = beta (ln eta(p) + 9.67) / (ln eta0 + 9.67); about 2 beta
//!   at 0.55 GPa for the [W25] oil),
//!   and since the shear stress is uniform across the film, the sliding speed is the
//!   integral of the local shear rate: v_s = (tau_0 h / eta) sinh(tau / tau_0) exp(beta dT_s)
//!   M(beta dT_m), M(a) = integral over the film of exp(a 4 z (1 - z)). That equation is
//!   solved for tau (Newton, monotone). This is the thermal Eyring film of Johnson &
//!   Greenwood (Wear 61 (1980) 353) with the surface temperature of the moving heat source;
//!   it gives the falling branch of measured traction curves at large slide-to-roll ratios.
//! - elastic entry: the oil enters the contact unsheared and needs a relaxation time
//!   lambda = eta_eff / G to reach the viscous stress (Maxwell; Johnson & Tevaarwerk 1977);
//!   the mean stress over the transit time T = 2 b / u_e is
//!   tau (1 - (lambda / T)(1 - exp(-T / lambda))), with eta_eff = tau / gamma_dot the
//!   secant viscosity of the heated Eyring film and G the oil's shear modulus
//!   (`oil.shearModulus`). This sets the initial slope when the viscosity is high.
//! - limiting shear stress tau_L = Lambda p (Bair & Winer, J. Lubr. Technol. 101 (1979) 251:
//!   Lambda 0.03-0.1 measured for lubricants; `oil.limitingShear`), a smooth minimum
//!   tau tau_L / (tau^4 + tau_L^4)^(1/4).
//!
//! 1 — Newtonian Eyring (the law before 2026-11-24; isothermal): Eyring at the Roelands
//! viscosity (z = 0.4) of the mean pressure, capped smoothly at tau_L = Lambda p.
//!
//! The solids' thermal data are bearing steel's (AISI 52100: K_s = 46 W/(m K),
//! kappa_s = 1.27e-5 m^2/s; Harris & Kotzalas, Essential Concepts, 5th ed., Table 5.x).

use crate::fastmath as fm;

/// Thermal conductivity of bearing steel (W/(m K)).
pub const STEEL_CONDUCTIVITY: f64 = 46.0;
/// Thermal diffusivity of bearing steel (m^2/s): 46 / (7850 kg/m^3 x 461 J/(kg K)).
pub const STEEL_DIFFUSIVITY: f64 = 1.27e-5;

/// Full-film traction law (parameter `traction`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum TractionLaw {
    /// Thermal Eyring film with elastic entry and limiting shear (default).
    ThermalEyring = 0,
    /// Isothermal Newtonian-Eyring at the Roelands viscosity, capped at the limiting shear.
    NewtonianEyring = 1,
}

/// The oil's traction data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rheology {
    /// Eyring stress tau_0 (Pa).
    pub eyring_stress: f64,
    /// Limiting shear stress over pressure, Lambda.
    pub limiting_shear: f64,
    /// Shear modulus of the oil film G (Pa).
    pub shear_modulus: f64,
    /// Temperature-viscosity coefficient beta (1/K).
    pub beta: f64,
    /// Thermal conductivity of the oil (W/(m K)).
    pub conductivity: f64,
    /// Viscosity at ambient pressure and the inlet temperature (Pa s).
    pub eta0: f64,
}

impl Rheology {
    /// Temperature-viscosity coefficient at a pressure where ln eta = `ln_eta` (Roelands'
    /// coupling, see the module's doc); never below the ambient value.
    #[inline]
    pub fn beta_at(&self, ln_eta: f64) -> f64 {
        let ambient = (fm::ln(self.eta0) + 9.67).max(1.0);
        self.beta * ((ln_eta + 9.67) / ambient).max(1.0)
    }
}

/// One contact as the traction law sees it.
#[derive(Debug, Clone, Copy)]
pub struct FilmContact {
    /// Mean contact pressure (Pa).
    pub pressure: f64,
    /// ln of the viscosity at that pressure (Pa s).
    pub ln_eta: f64,
    /// Film thickness (m).
    pub film: f64,
    /// Half-width of the contact along the rolling direction (m).
    pub half_width: f64,
    /// Entrainment speed (m/s).
    pub entrainment: f64,
}

/// Film shear stress |tau| (Pa) at sliding speed |`v_s`| with the thermal Eyring law.
#[inline]
pub fn thermal_eyring_stress(r: &Rheology, c: &FilmContact, v_s: f64) -> f64 {
    let v_s = v_s.abs();
    let h = c.film.max(1e-9);
    if !(v_s > 0.0) || !(c.pressure > 0.0) {
        return 0.0;
    }
    let tau0 = r.eyring_stress;
    // X = eta gamma_dot / tau_0
    let ln_x = c.ln_eta + fm::ln(v_s / (h * tau0));
    // heating per unit stress, scaled by beta tau_0: surface (uniform) and film mid-plane
    let b = c.half_width.max(0.0);
    let peclet = c.entrainment.abs() * b / (2.0 * STEEL_DIFFUSIVITY);
    let beta = r.beta_at(c.ln_eta);
    let b_s = beta * tau0 * 0.752 * 0.5 * v_s * b / (STEEL_CONDUCTIVITY * (peclet + 1.0).sqrt());
    let b_m = beta * tau0 * v_s * h / (8.0 * r.conductivity);
    let y = solve_thermal_eyring(ln_x, b_s, b_m);
    let mut tau = tau0 * y;
    // elastic entry (Maxwell): mean over the transit time T = 2 b / u_e
    if r.shear_modulus > 0.0 && c.entrainment.abs() > 0.0 && tau > 0.0 {
        let gamma_dot = v_s / h;
        let lambda = tau / (gamma_dot * r.shear_modulus);
        let ratio = 2.0 * b / (c.entrainment.abs() * lambda);
        tau *= maxwell_mean(ratio);
    }
    limit(tau, r.limiting_shear * c.pressure)
}

/// Mean over a transit of `ratio` relaxation times of the Maxwell stress rise 1 - exp(-t):
/// 1 - (1 - exp(-ratio)) / ratio.
#[inline]
fn maxwell_mean(ratio: f64) -> f64 {
    if ratio < 1e-4 {
        0.5 * ratio * (1.0 - ratio / 3.0)
    } else if ratio > 40.0 {
        1.0 - 1.0 / ratio
    } else {
        1.0 - (1.0 - fm::exp(-ratio)) / ratio
    }
}

/// Smooth minimum of a stress and the limiting shear stress: tau tau_L / (tau^4 + tau_L^4)^(1/4).
#[inline]
pub fn limit(tau: f64, tau_l: f64) -> f64 {
    if !(tau_l > 0.0) {
        return tau;
    }
    let (t2, l2) = (tau * tau, tau_l * tau_l);
    tau * tau_l / (t2 * t2 + l2 * l2).sqrt().sqrt()
}

/// y = tau / tau_0 solving y = asinh(X exp(-b_s y) / M(b_m y)), ln X = `ln_x` (Newton from
/// the isothermal value, which bounds it from above; the residual is monotone).
#[inline]
fn solve_thermal_eyring(ln_x: f64, b_s: f64, b_m: f64) -> f64 {
    let y_iso = asinh_exp(ln_x);
    if b_s <= 0.0 && b_m <= 0.0 {
        return y_iso;
    }
    let mut y = y_iso;
    let mut lo = 0.0;
    let mut hi = y_iso;
    for _ in 0..30 {
        let (ln_m, dln_m) = ln_film_mean(b_m * y);
        let g = ln_x - b_s * y - ln_m;
        let dg = -b_s - b_m * dln_m;
        let z = fm::exp(g.min(600.0));
        let f = y - asinh_exp(g);
        // d asinh(e^g)/dg = e^g / sqrt(1 + e^2g)
        let slope = 1.0 - z / (1.0 + z * z).sqrt() * dg;
        if f > 0.0 {
            hi = y;
        } else {
            lo = y;
        }
        let mut next = y - f / slope;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        let done = (next - y).abs() <= 4.0 * f64::EPSILON * y.max(1e-300);
        y = next;
        if done {
            break;
        }
    }
    y
}

/// asinh(exp(g)) without overflow: ln(e^g + sqrt(e^2g + 1)).
#[inline]
fn asinh_exp(g: f64) -> f64 {
    if g > 20.0 {
        // e^g + sqrt(e^2g + 1) = e^g (2 + e^-2g / 2 + ...)
        g + std::f64::consts::LN_2
    } else {
        let x = fm::exp(g);
        if x < 0.1 {
            let x2 = x * x;
            x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (3.0 / 40.0 + x2 * (-15.0 / 336.0 + x2 * (105.0 / 3456.0)))))
        } else {
            fm::ln(x + (x * x + 1.0).sqrt())
        }
    }
}

/// ln M(a) and its derivative, M(a) = integral over z in [0, 1] of exp(4 a z (1 - z))
/// = sum over n of (2a)^n / (2n + 1)!! = e^a sqrt(pi / a) erf(sqrt a) / 2.
#[inline]
fn ln_film_mean(a: f64) -> (f64, f64) {
    if a <= 0.0 {
        return (0.0, 2.0 / 3.0);
    }
    if a < 2.0 {
        // series: terms t_n = (2a)^n / (2n+1)!!, 24 terms: the remainder is below 1e-16
        let mut t = 1.0;
        let mut m = 1.0;
        let mut dm = 0.0;
        for n in 1..24 {
            t *= 2.0 * a / (2 * n + 1) as f64;
            m += t;
            dm += n as f64 * t / a;
        }
        (fm::ln(m), dm / m)
    } else {
        let r = a.sqrt();
        let e = erf(r);
        let ln_m = a + 0.5 * (std::f64::consts::PI / a).ln() + e.ln() - std::f64::consts::LN_2;
        let d = 1.0 + (-a).exp() / ((std::f64::consts::PI * a).sqrt() * e) - 0.5 / a;
        (ln_m, d)
    }
}

/// Error function for x >= 0 (Abramowitz & Stegun 7.1.26, absolute error below 1.5e-7; used
/// only where erf(x) > 0.95, i.e. relative error below 2e-7).
fn erf(x: f64) -> f64 {
    let t = 1.0 / (1.0 + 0.327_591_1 * x);
    let poly = t * (0.254_829_592 + t * (-0.284_496_736 + t * (1.421_413_741 + t * (-1.453_152_027 + t * 1.061_405_429))));
    1.0 - poly * (-x * x).exp()
}

/// Newtonian Eyring traction coefficient (law 1, signed like `v_s`): mean shear stress of an
/// isothermal Eyring film at viscosity `eta` over the mean pressure, smoothly capped at the
/// limiting shear stress `limiting_shear` p.
#[inline]
pub fn newtonian_eyring_mu(eta: f64, eyring_stress: f64, limiting_shear: f64, v_s: f64, h: f64, p_mean: f64) -> f64 {
    if p_mean <= 0.0 || v_s == 0.0 {
        return 0.0;
    }
    let h = h.max(1e-9);
    let x = eta * v_s.abs() / (h * eyring_stress);
    let tau_e = eyring_stress * asinh_exp(fm::ln(x));
    v_s.signum() * limit(tau_e, limiting_shear * p_mean) / p_mean
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The presets' oil at the [W25] raceway (0.55 GPa mean, Barus viscosity, 1.3 um film,
    /// b = 0.14 mm, u_e = 16 m/s).
    fn w25_slice(eta_law: f64) -> (Rheology, FilmContact) {
        let r = Rheology {
            eyring_stress: 5e6,
            limiting_shear: 0.08,
            shear_modulus: 1e9,
            beta: 0.03,
            conductivity: 0.13,
            eta0: 0.033,
        };
        let c = FilmContact {
            pressure: 5.5e8,
            ln_eta: eta_law.ln(),
            film: 1.3e-6,
            half_width: 1.4e-4,
            entrainment: 16.0,
        };
        (r, c)
    }

    #[test]
    fn zero_without_sliding_and_the_same_for_either_direction() {
        let (r, c) = w25_slice(0.033 * (1.28e-8_f64 * 5.5e8).exp());
        assert_eq!(thermal_eyring_stress(&r, &c, 0.0), 0.0);
        for v in [1e-6, 1e-3, 0.3, 3.0] {
            assert_eq!(thermal_eyring_stress(&r, &c, v), thermal_eyring_stress(&r, &c, -v));
            assert!(thermal_eyring_stress(&r, &c, v) > 0.0);
        }
    }

    /// Initial slope: at vanishing slip the film is a Newtonian, isothermal Maxwell liquid:
    /// tau = eta v_s / h (1 - (lambda/T)(1 - e^(-T/lambda))), lambda = eta / G.
    #[test]
    fn initial_slope_is_the_linear_viscoelastic_film() {
        let eta = 0.033 * (1.28e-8_f64 * 5.5e8).exp();
        for (eta, g) in [(eta, 1e9), (5e4, 1e8)] {
            let (mut r, mut c) = w25_slice(eta);
            r.shear_modulus = g;
            c.ln_eta = eta.ln();
            let v = 1e-7;
            let tau = thermal_eyring_stress(&r, &c, v);
            let newton = eta * v / c.film;
            let t = 2.0 * c.half_width / c.entrainment;
            let lambda = eta / g;
            let hand = newton * (1.0 - (lambda / t) * (1.0 - (-t / lambda).exp()));
            assert!((tau - hand).abs() < 1e-5 * hand, "{tau} vs {hand}");
        }
    }

    /// Plateau: with heating switched off and a huge shear rate the stress reaches the
    /// limiting shear stress Lambda p; the smooth minimum never exceeds it.
    #[test]
    fn plateau_is_the_limiting_shear_stress() {
        let (mut r, c) = w25_slice(1e12);
        r.beta = 0.0;
        let tau = thermal_eyring_stress(&r, &c, 50.0);
        let tau_l = r.limiting_shear * c.pressure;
        assert!(tau <= tau_l && tau > 0.99 * tau_l, "{tau} vs {tau_l}");
    }

    /// Shear heating: the heated film carries less stress than the isothermal one, more so at
    /// higher sliding speed, and the thermal curve falls past its peak (measured traction
    /// curves of bearing oils at a few per cent slide-to-roll).
    #[test]
    fn heating_lowers_the_stress_and_makes_a_falling_branch() {
        let eta = 0.033 * (1.28e-8_f64 * 5.5e8).exp();
        let (r, c) = w25_slice(eta);
        let iso = Rheology { beta: 0.0, ..r };
        let mut peak: f64 = 0.0;
        let mut last = 0.0;
        let mut fell = false;
        for k in 0..60 {
            let s = 1e-4 * 1.2_f64.powi(k);
            let v = s * c.entrainment;
            let hot = thermal_eyring_stress(&r, &c, v);
            let cold = thermal_eyring_stress(&iso, &c, v);
            assert!(hot <= cold * (1.0 + 1e-12), "{s}: {hot} > {cold}");
            if hot < last && s > 0.05 {
                fell = true;
            }
            peak = peak.max(hot / c.pressure);
            last = hot;
        }
        assert!(fell, "no falling branch");
        // the peak of this oil at these conditions: a few hundredths
        assert!(peak > 0.01 && peak < 0.08, "peak mu {peak}");
    }

    /// The thermal solution satisfies its own equation: v_s = (tau_0 h / eta) sinh(tau/tau_0)
    /// exp(beta dT_s) M(beta dT_m), M checked against quadrature.
    #[test]
    fn thermal_solution_satisfies_the_film_equation() {
        for a in [1e-3, 0.5, 1.9, 2.1, 7.0, 40.0] {
            let n = 20000;
            let quad: f64 = (0..n)
                .map(|i| {
                    let z = (i as f64 + 0.5) / n as f64;
                    (4.0 * a * z * (1.0 - z)).exp()
                })
                .sum::<f64>()
                / n as f64;
            let (ln_m, d) = ln_film_mean(a);
            assert!((ln_m - quad.ln()).abs() < 1e-6, "a={a}: {} vs {}", ln_m, quad.ln());
            let (ln_m2, _) = ln_film_mean(a * (1.0 + 1e-6));
            assert!(((ln_m2 - ln_m) / (a * 1e-6) - d).abs() < 1e-4 * d.max(1.0), "a={a}");
        }
        let (ln_x, b_s, b_m) = (3.0, 0.2, 0.7);
        let y = solve_thermal_eyring(ln_x, b_s, b_m);
        let (ln_m, _) = ln_film_mean(b_m * y);
        let rhs = asinh_exp(ln_x - b_s * y - ln_m);
        assert!((y - rhs).abs() < 1e-12 * y, "{y} vs {rhs}");
    }

    #[test]
    fn newtonian_law_is_smooth_odd_and_limited() {
        let eta = crate::tribology::roelands_viscosity(0.033, 1e9);
        let mu = |v: f64| newtonian_eyring_mu(eta, 5e6, 0.08, v, 1e-7, 1e9);
        assert_eq!(mu(0.0), 0.0);
        let (a, b) = (mu(1e-3), mu(1e-2));
        assert!(a > 0.0 && b > a);
        let tiny = mu(1e-9);
        assert!((tiny - eta * 1e-9 / 1e-7 / 1e9).abs() < 1e-6 * tiny);
        assert_eq!(mu(-1e-2), -b);
        let c = mu(100.0);
        assert!(c <= 0.08 && c > 0.03, "{c}");
    }
}
