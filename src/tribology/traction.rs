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
//!   Across the film the temperature is the parabola of steady conduction, its mean rise
//!   tau v_s h / (12 k_oil) (two thirds of the mid-plane rise); each surface's mean flash
//!   temperature under a moving band source of half-width b is
//!   dT_s = 0.752 (tau v_s / 2) b / (K_s sqrt(Pe)), Pe = u_e b / (2 kappa_s) (Carslaw & Jaeger
//!   1959 / Jaeger 1942 fast-source limit: a surface point is heated for 2 b / u_e; Pe + 1
//!   under the root keeps it finite at rest). The film flows at the viscosity of its mean
//!   temperature (the effective-temperature form of Crook 1961 and Olver & Spikes 1998),
//!   eta exp(-beta_p dT), with the oil's temperature-viscosity coefficient `oil.beta` raised by
//!   pressure as in Roelands' viscosity-temperature-pressure equation (Roelands 1966:
//!   d ln eta / dT = -S0 (ln eta + 9.67) / (T - 138), so beta_p = beta (ln eta(p) + 9.67) /
//!   (ln eta0 + 9.67); about 2 beta at 0.55 GPa for the [W25] oil). Since dT is proportional to
//!   tau, the stress solves tau = tau_0 asinh(X exp(-B tau / tau_0)), X = eta gamma_dot / tau_0,
//!   B = beta_p tau_0 dT / tau (Newton, monotone; Johnson & Greenwood, Wear 61 (1980) 353, solve
//!   the same thermal Eyring film across its thickness). This is the falling branch of measured
//!   traction curves at large slide-to-roll ratios.
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
//! 1 — Newtonian Eyring (isothermal, kept for comparison with the studies): Eyring at the Roelands
//! viscosity (z = 0.4) of the mean pressure, capped smoothly at 0.08 p, with its fixed
//! constants (`tribology::full_film_mu`, `EYRING_STRESS`, `LIMITING_SHEAR`).
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
    /// ln of the Eyring stress, and beta / (ln eta0 + 9.67) (Roelands' coupling), precomputed.
    pub ln_eyring_stress: f64,
    pub beta_per_roelands: f64,
}

impl Rheology {
    /// Temperature-viscosity coefficient at a pressure where ln eta = `ln_eta` (Roelands'
    /// coupling, see the module's doc); never below the ambient value.
    #[inline]
    pub fn beta_at(&self, ln_eta: f64) -> f64 {
        (self.beta_per_roelands * (ln_eta + 9.67)).max(self.beta)
    }

    /// The oil's traction data with the derived constants filled in.
    pub fn new(eyring_stress: f64, limiting_shear: f64, shear_modulus: f64, beta: f64, conductivity: f64, eta0: f64) -> Rheology {
        Rheology {
            eyring_stress,
            limiting_shear,
            shear_modulus,
            beta,
            conductivity,
            eta0,
            ln_eyring_stress: libm::log(eyring_stress),
            beta_per_roelands: beta / (libm::log(eta0) + 9.67).max(1.0),
        }
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
    if !(v_s > 0.0) || !(c.pressure > 0.0) {
        return 0.0;
    }
    thermal_eyring_stress_ln(r, c, v_s, fm::ln(v_s), fm::ln(c.film.max(1e-9)))
}

/// [`thermal_eyring_stress`] with ln |v_s| and ln h already known (the right-hand side keeps
/// the film in logarithms); `v_s` > 0, `c.film` >= 1e-9 m.
#[inline(always)]
pub fn thermal_eyring_stress_ln(r: &Rheology, c: &FilmContact, v_s: f64, ln_vs: f64, ln_h: f64) -> f64 {
    thermal_eyring_stress_with(r, c, v_s, ln_vs, ln_h, solve_thermal_eyring)
}

/// [`thermal_eyring_stress_ln`] with the film equation y = asinh(X exp(-B y)) solved by
/// Halley's method (cubic convergence) instead of Newton's, from the same start (the closed
/// forms of the two regimes). The same stress to rounding: both solvers stop once a step is
/// below 1e-9 y, i.e. at the root to machine precision; Halley's gets there in 2-3
/// evaluations of asinh(e^g) where Newton's takes 4-5 (the [W25] raceway slices). The
/// quasi-static model's, and the dynamic model's two-lane kernel's (`pair.rs`); the dynamic
/// model's scalar law (other architectures, the tests' reference) keeps Newton's.
#[inline(always)]
pub fn thermal_eyring_stress_ln_halley(r: &Rheology, c: &FilmContact, v_s: f64, ln_vs: f64, ln_h: f64) -> f64 {
    thermal_eyring_stress_with(r, c, v_s, ln_vs, ln_h, solve_thermal_eyring_halley)
}

/// The thermal Eyring stress with the film equation solved by `solve(ln X, B)`.
#[inline(always)]
fn thermal_eyring_stress_with(r: &Rheology, c: &FilmContact, v_s: f64, ln_vs: f64, ln_h: f64, solve: fn(f64, f64) -> f64) -> f64 {
    let tau0 = r.eyring_stress;
    let h = c.film.max(1e-9);
    // X = eta gamma_dot / tau_0
    let ln_x = c.ln_eta + ln_vs - ln_h.max(LN_MIN_FILM) - r.ln_eyring_stress;
    // temperature rise per unit stress (surface flash + film mean), times beta_p tau_0
    let b = c.half_width.max(0.0);
    let peclet = c.entrainment.abs() * b * (0.5 / STEEL_DIFFUSIVITY);
    let heat = 0.376 * b / (STEEL_CONDUCTIVITY * (peclet + 1.0).sqrt()) + h / (12.0 * r.conductivity);
    let heating = r.beta_at(c.ln_eta) * tau0 * v_s * heat;
    let y = solve(ln_x, heating);
    let mut tau = tau0 * y;
    // elastic entry (Maxwell): mean over the transit time T = 2 b / u_e
    if r.shear_modulus > 0.0 && c.entrainment.abs() > 0.0 && tau > 0.0 {
        // T / lambda = 2 b G gamma_dot / (u_e tau)
        let ratio = 2.0 * b * r.shear_modulus * v_s / (c.entrainment.abs() * tau * h);
        tau *= maxwell_mean(ratio);
    }
    limit(tau, r.limiting_shear * c.pressure)
}

/// ln(1e-9): the film thickness floor of the Eyring law.
pub const LN_MIN_FILM: f64 = -20.723_265_836_946_41;

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

/// y = tau / tau_0 solving y = asinh(X exp(-B y)), ln X = `ln_x`, B = `heating` >= 0:
/// Newton from the two regimes' closed forms (X e^(-B y) small: y = X / (1 + B X); large:
/// y = ln(2X) / (1 + B)). Newton converges quadratically here (the residual is monotone with
/// slope >= 1): once a step is below 1e-9 y, the stepped value is exact to rounding; a
/// bracket guards the first steps.
#[inline]
fn solve_thermal_eyring(ln_x: f64, heating: f64) -> f64 {
    solve_thermal_eyring_by(ln_x, heating, |y| {
        let (asinh, dz) = asinh_exp_and_slope(ln_x - heating * y);
        let f = y - asinh;
        // d asinh(e^g)/dy = -B e^g / sqrt(1 + e^2g)
        (f, f / (1.0 + heating * dz))
    })
}

/// [`solve_thermal_eyring`] by Halley's method, with the same start, bracket and stopping rule.
#[inline]
pub(crate) fn solve_thermal_eyring_halley(ln_x: f64, heating: f64) -> f64 {
    solve_thermal_eyring_by(ln_x, heating, |y| {
        let (asinh, dz, x) = asinh_exp_slope_and_x(ln_x - heating * y);
        let f = y - asinh;
        // f' = 1 + B dz, f'' = -B^2 dz / (1 + e^2g)  (d dz / dg = dz / (1 + e^2g))
        let d1 = 1.0 + heating * dz;
        let d2 = -heating * heating * dz / (1.0 + x * x);
        (f, 2.0 * f * d1 / (2.0 * d1 * d1 - f * d2))
    })
}

/// The film equation's iteration shared by both methods: start from the regimes' closed forms,
/// `residual_and_step(y)` = (f(y), the method's step), keep a bracket of the root, stop when a
/// step is below 1e-9 y.
#[inline(always)]
fn solve_thermal_eyring_by(ln_x: f64, heating: f64, mut residual_and_step: impl FnMut(f64) -> (f64, f64)) -> f64 {
    if !(heating > 0.0) {
        return asinh_exp(ln_x);
    }
    let mut y = if ln_x > 0.0 {
        (ln_x + std::f64::consts::LN_2) / (1.0 + heating)
    } else {
        let x = fm::exp(ln_x);
        x / (1.0 + heating * x)
    };
    let (mut lo, mut hi) = (0.0, f64::INFINITY);
    for _ in 0..60 {
        let (f, step) = residual_and_step(y);
        if f > 0.0 {
            hi = y;
        } else {
            lo = y;
        }
        if step.abs() <= 1e-9 * y.max(1e-300) {
            return y - step;
        }
        let next = y - step;
        y = if next > lo && next < hi {
            next
        } else {
            0.5 * (lo + hi.min(2.0 * y.max(lo)))
        };
    }
    y
}

/// [`asinh_exp_and_slope`] and e^g (infinite above g = 20, where the slope is 1).
#[inline(always)]
fn asinh_exp_slope_and_x(g: f64) -> (f64, f64, f64) {
    if g > 20.0 {
        return (g + std::f64::consts::LN_2, 1.0, f64::INFINITY);
    }
    let x = fm::exp(g);
    let root = (x * x + 1.0).sqrt();
    let asinh = if x < 0.1 {
        let x2 = x * x;
        x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (3.0 / 40.0 + x2 * (-15.0 / 336.0 + x2 * (105.0 / 3456.0)))))
    } else {
        fm::ln(x + root)
    };
    (asinh, x / root, x)
}

/// asinh(e^g) and its derivative in g, e^g / sqrt(1 + e^2g), with one exponential.
#[inline(always)]
fn asinh_exp_and_slope(g: f64) -> (f64, f64) {
    if g > 20.0 {
        return (g + std::f64::consts::LN_2, 1.0);
    }
    let x = fm::exp(g);
    let root = (x * x + 1.0).sqrt();
    let asinh = if x < 0.1 {
        let x2 = x * x;
        x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (3.0 / 40.0 + x2 * (-15.0 / 336.0 + x2 * (105.0 / 3456.0)))))
    } else {
        fm::ln(x + root)
    };
    (asinh, x / root)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The presets' oil at the [W25] raceway (0.55 GPa mean, Barus viscosity, 1.3 um film,
    /// b = 0.14 mm, u_e = 16 m/s).
    fn w25_slice(eta_law: f64) -> (Rheology, FilmContact) {
        let r = Rheology::new(5e6, 0.08, 1e9, 0.03, 0.13, 0.033);
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
        let (r, c) = w25_slice(1e12);
        let r = Rheology::new(r.eyring_stress, r.limiting_shear, r.shear_modulus, 0.0, r.conductivity, r.eta0);
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
        let iso = Rheology::new(r.eyring_stress, r.limiting_shear, r.shear_modulus, 0.0, r.conductivity, r.eta0);
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

    /// The thermal solution satisfies its own equation y = asinh(X exp(-B y)) to machine
    /// precision in both regimes, and is the isothermal Eyring stress without heating.
    #[test]
    fn thermal_solution_satisfies_the_film_equation() {
        for ln_x in [-25.0, -3.0, 0.0, 0.7, 3.0, 12.0, 40.0] {
            for heating in [0.0, 1e-6, 0.05, 0.7, 6.0, 80.0] {
                let y = solve_thermal_eyring(ln_x, heating);
                let rhs = asinh_exp(ln_x - heating * y);
                assert!((y - rhs).abs() <= 1e-13 * y.max(1e-300), "ln X {ln_x}, B {heating}: {y} vs {rhs}");
            }
            assert_eq!(solve_thermal_eyring(ln_x, 0.0), asinh_exp(ln_x));
        }
        // Halley's solver meets the same root
        for ln_x in [-25.0, -3.0, -0.5, 0.0, 0.7, 3.0, 12.0, 40.0] {
            for heating in [0.0, 1e-6, 0.02, 0.05, 0.3, 0.7, 6.0, 80.0] {
                let newton = solve_thermal_eyring(ln_x, heating);
                let y = solve_thermal_eyring_halley(ln_x, heating);
                assert!(
                    (y - newton).abs() <= 4e-16 * newton.max(1e-300),
                    "ln X {ln_x}, B {heating}: {y} vs {newton}"
                );
            }
        }
    }
}
