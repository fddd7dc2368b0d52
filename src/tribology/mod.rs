//! Lubrication and traction (MODEL.md section 4; friction-torque pieces of section 7). One
//! file per law family, each naming its sources:
//!
//! - `viscosity.rs`: the oil's viscosity against pressure (Barus, Roelands) and temperature;
//! - `film.rs`: Hamrock line-contact and Chittenden point-contact central films [W25], with
//!   the inlet shear-heating reduction of Gupta et al. (1992);
//! - `traction.rs`: full-film traction laws (parameter `traction`): the thermal Eyring film
//!   with elastic entry and limiting shear (default), or the isothermal Newtonian Eyring law;
//! - `pair.rs`: the raceway traction of two slices at once (x86-64, the dynamic model's);
//! - `rib.rs`: the roller end on the rib: asperity and film shares from the film ratio;
//! - `mixed.rs`: mixed lubrication, the asperities' share of a contact and their boundary
//!   coefficient: by each contact's film ratio [W25], or by SKF's weighting phi_bl;
//! - `supply.rs`: the lubricant supply: starved films and rolling resistance (Chevalier et al.
//!   1998, Damiens et al. 2004, SKF's replenishment factor);
//! - here: the boundary law of [W25] (Kragelskii), the [W25] sixth-power blend of the mixed
//!   regime, the EHL rolling resistance and dry Coulomb friction [D19].
//!
//! The full-film regression [W25] uses at the raceways (Wang, Yang & Wang, Tribotest 11, 2004)
//! has coefficients we cannot source; `traction.rs` takes its place with a physical law whose
//! constants are the oil's (documented defaults in docs/model.md, "Oil traction data").

#[cfg(target_arch = "x86_64")]
pub(crate) mod eyring_table;
pub mod film;
pub mod mixed;
#[cfg(target_arch = "x86_64")]
pub(crate) mod pair;
pub mod rib;
pub mod supply;
pub mod traction;
pub mod viscosity;

pub use film::{film_line, film_line_fast, film_line_log_constant, film_point, thermal_reduction};
pub use mixed::{Mixed, MixedLaw};
pub use rib::{asperity_share, flange_boundary_mu, flange_viscous_traction, flange_viscous_traction_with, rib_film_traction};
pub use supply::{Starvation, Supply, SupplyLaw};
pub use traction::{FilmContact, Rheology, TractionLaw};
pub use viscosity::{roelands_viscosity, roelands_viscosity_with, OilGrade, Piezoviscosity, ViscosityTable};

use crate::fastmath as fm;

/// Floor of the entrainment speed in the slide-to-roll ratio of the boundary law (m/s).
///
/// [W25]'s boundary law is a function of s = v_s / u_e; at (near) standstill u_e -> 0 and its
/// slope d(mu)/d(v_s) = 40.4 / u_e grows without bound (4e7 s/m at u_e = 1 um/s: steps of
/// ~1 ns, F11 in docs/robustness.md), and switching to another law below some u_e makes the
/// traction jump. With u_e floored at 0.04 m/s the law at standstill is a regularised Coulomb
/// law whose slope at zero sliding, 40.4 / 0.04 = 1e3 s/m, is that of the dry regularisation
/// (0.1 / 1e-4 s/m), peaking (mu 0.15) at 0.4 mm/s sliding; above 0.04 m/s nothing changes.
pub const MIN_BOUNDARY_ENTRAINMENT: f64 = 0.04;

/// What the lubricated contact laws of `traction` = 0 need of the oil and the surfaces, for
/// the raceway slices and the rib, shared by the quasi-static and the dynamic model.
#[derive(Debug, Clone)]
pub struct Lubricant {
    pub rheology: Rheology,
    /// Viscosity against pressure of the traction law.
    pub viscosity: ViscosityTable,
    /// beta eta0 / k: the inlet's thermal loading is this times u_e^2.
    pub inlet_heating: f64,
    /// Composite roughness of the raceway contacts and of the rib contact (m).
    pub sigma: f64,
    pub rib_sigma: f64,
    pub e_prime: f64,
}

impl Lubricant {
    /// Traction coefficient |mu| of a raceway slice (`traction` = 0): the isothermal film
    /// `h_iso` reduced by inlet heating (Gupta et al. 1992), the [W25] regimes by its film
    /// ratio, in full film the thermal Eyring film's stress at the mean pressure `p_mean` over
    /// it (`traction.rs`). `w` load per length, `u_e` entrainment and `v_s` sliding speed;
    /// `boundary_slide_roll` the slide-to-roll ratio of the boundary law (the dynamic model
    /// floors its entrainment speed, `MIN_BOUNDARY_ENTRAINMENT`; the quasi-static model takes
    /// the kinematic ratio, finite at standstill).
    #[inline]
    pub fn raceway_mu(&self, w: f64, p_mean: f64, h_iso: f64, u_e: f64, v_s: f64, boundary_slide_roll: f64, mixed: Mixed) -> f64 {
        if !(w > 0.0) {
            return 0.0;
        }
        let slide_roll = if u_e > 0.0 { v_s / u_e } else { 0.0 };
        let heating = thermal_reduction(
            self.inlet_heating * u_e * u_e,
            4.0 / std::f64::consts::PI * p_mean / self.e_prime,
            slide_roll,
        );
        let h = heating * h_iso;
        let ln_h = if h > 0.0 { fm::ln(h) } else { f64::NEG_INFINITY };
        let ln_vs = if v_s > 0.0 { fm::ln(v_s) } else { f64::NEG_INFINITY };
        self.raceway_mu_film(w, p_mean, h, ln_h, u_e, v_s, ln_vs, boundary_slide_roll, mixed)
    }

    /// [`Lubricant::raceway_mu`] with the film `h` already reduced by inlet heating, its
    /// logarithm `ln_h` and ln |v_s| `ln_vs` known (the dynamic model's slice loop).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn raceway_mu_film(
        &self,
        w: f64,
        p_mean: f64,
        h: f64,
        ln_h: f64,
        u_e: f64,
        v_s: f64,
        ln_vs: f64,
        boundary_slide_roll: f64,
        mixed: Mixed,
    ) -> f64 {
        let stress = traction::thermal_eyring_stress_ln;
        self.raceway_mu_film_with(w, p_mean, h, ln_h, u_e, v_s, ln_vs, boundary_slide_roll, mixed, stress)
    }

    /// The coefficient of [`Lubricant::raceway_mu_film`] with the film stress law `stress`
    /// (the quasi-static model's: [`traction::thermal_eyring_stress_ln_halley`], the film
    /// equation solved by Halley's method, the same coefficient to rounding in fewer
    /// evaluations).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn raceway_mu_film_with(
        &self,
        w: f64,
        p_mean: f64,
        h: f64,
        ln_h: f64,
        u_e: f64,
        v_s: f64,
        ln_vs: f64,
        boundary_slide_roll: f64,
        mixed: Mixed,
        stress: fn(&Rheology, &FilmContact, f64, f64, f64) -> f64,
    ) -> f64 {
        let share = match mixed {
            Mixed::FilmRatio if !(self.sigma > 0.0) => 0.0,
            _ => mixed.share(h / self.sigma),
        };
        let film = if share < 1.0 && v_s > 0.0 {
            let contact = FilmContact {
                pressure: p_mean,
                ln_eta: self.viscosity.ln_eta(p_mean),
                film: h,
                half_width: 0.5 * w / p_mean,
                entrainment: u_e,
            };
            stress(&self.rheology, &contact, v_s, ln_vs, ln_h) / p_mean
        } else {
            0.0
        };
        let boundary = if share > 0.0 { mixed.boundary_mu(boundary_slide_roll) } else { 0.0 };
        share * boundary + (1.0 - share) * film
    }

    /// The rib's film ratio Λ = h / σ_rib as [`Lubricant::rib_force`] takes it: the isothermal
    /// point-contact film `h_iso` reduced by inlet shear heating, over the roller end / rib
    /// composite roughness (infinite without roughness).
    pub fn rib_film_ratio(&self, v_s: f64, u_e: f64, h_iso: f64, p_h: f64) -> f64 {
        let h = self.rib_film(v_s, u_e, h_iso, p_h);
        if self.rib_sigma > 0.0 {
            h / self.rib_sigma
        } else {
            f64::INFINITY
        }
    }

    /// The rib's film: the isothermal point-contact film `h_iso` reduced by inlet shear heating
    /// at sliding speed `v_s`, entrainment `u_e` and Hertz pressure `p_h`.
    #[inline(always)]
    fn rib_film(&self, v_s: f64, u_e: f64, h_iso: f64, p_h: f64) -> f64 {
        let slide_roll = if u_e > 0.0 { v_s / u_e } else { 2.0 };
        h_iso * thermal_reduction(self.inlet_heating * u_e * u_e, p_h / self.e_prime, slide_roll)
    }

    /// Friction force |F| (N) of the rib contact (`traction` = 0) at normal load `q`, sliding
    /// speed `v_s`, entrainment speed `u_e`, isothermal central film `h_iso` and Hertz ellipse
    /// (`a` along the entrainment, `b`, peak pressure `p_h`): asperity and film shares by the
    /// mixed law `mixed` (`mixed.rs`, by the film ratio against the rib roughness or SKF's
    /// weighting); `boundary_slide_roll` as in [`Lubricant::raceway_mu`]. The film's force is
    /// `film`: [`rib::rib_film_traction`], or the quasi-static model's
    /// [`rib::rib_film_traction_halley`] (the film equation solved by Halley's method, the same
    /// force to rounding).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn rib_force(
        &self,
        q: f64,
        v_s: f64,
        u_e: f64,
        boundary_slide_roll: f64,
        h_iso: f64,
        a: f64,
        b: f64,
        p_h: f64,
        mixed: Mixed,
        film: RibFilm,
    ) -> f64 {
        if !(q > 0.0) {
            return 0.0;
        }
        let h = self.rib_film(v_s, u_e, h_iso, p_h);
        let share = match mixed {
            Mixed::FilmRatio if !(self.rib_sigma > 0.0) => 0.0,
            _ => mixed.share(h / self.rib_sigma),
        };
        let boundary = if share > 0.0 {
            share * q * mixed.boundary_mu(boundary_slide_roll)
        } else {
            0.0
        };
        let film = if share < 1.0 && v_s > 0.0 {
            (1.0 - share) * film(&self.rheology, &self.viscosity, v_s, h, u_e, a, b, p_h)
        } else {
            0.0
        };
        boundary + film
    }
}

/// The rib film's traction force as `rib::rib_film_traction` takes its arguments.
pub type RibFilm = fn(&Rheology, &ViscosityTable, f64, f64, f64, f64, f64, f64) -> f64;

/// Boundary traction coefficient of [W25]: (-0.1 + 22.28 s) exp(-181.46 s) + 0.1.
pub fn boundary_mu(slide_roll: f64) -> f64 {
    let s = slide_roll.abs();
    (-0.1 + 22.28 * s) * fm::exp(-181.46 * s) + 0.1
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

/// EHL rolling resistance of a line contact of length `l` on ONE of its two surfaces
/// (Zhou & Hoeprich, "Torque of tapered roller bearings", J. Tribol. 113 (1991) 590, Eq. 17,
/// isothermal): F = 29.2 (R / alpha) (G U)^0.648 W^0.246 l with G = alpha E',
/// U = eta0 u / (E' R) (u the rolling speed), W = w / (E' R), w = q / l the load per length.
/// Both surfaces feel it, so the contact dissipates 2 F u (the inlet's Poiseuille flow;
/// checked against a numerical EHL solution in `ehl_line.rs`: the fully flooded isothermal
/// force is 1.6 times this regression, which Zhou & Hoeprich fitted to a shorter inlet).
pub fn rolling_resistance(eta0: f64, alpha: f64, e_prime: f64, u: f64, r_bar: f64, q: f64, l: f64) -> f64 {
    if u <= 0.0 || q <= 0.0 || alpha <= 0.0 || l <= 0.0 {
        return 0.0;
    }
    let gu = alpha * eta0 * u / r_bar;
    let w = q / (e_prime * r_bar * l);
    29.2 * r_bar / alpha * fm::powf(gu, 0.648) * fm::powf(w, 0.246) * l
}

/// ln of the constant C of a slice's rolling couple 2 F R = C u^0.648 w^0.246 (F of
/// [`rolling_resistance`] on each of the two surfaces, R the equivalent radius: the couple
/// that dissipates 2 F u when the roller turns at u / R relative to the raceway), for a slice
/// of length `l`, w its load per length. Without a pressure-viscosity coefficient the law has
/// no rolling resistance: -inf, a zero couple.
pub fn rolling_couple_log_constant(eta0: f64, alpha: f64, e_prime: f64, r_bar: f64, l: f64) -> f64 {
    if !(alpha > 0.0) {
        return f64::NEG_INFINITY;
    }
    libm::log(2.0 * 29.2_f64) + 2.0 * libm::log(r_bar) - libm::log(alpha) + 0.648 * libm::log(alpha * eta0 / r_bar)
        - 0.246 * libm::log(e_prime * r_bar)
        + libm::log(l)
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

    /// The [W25] rib contact (Q_f 1.2 kN on the sphere, 5.2 m/s sliding at 14.7 m/s
    /// entrainment, 3 um isothermal film) as the rib roughness grows: full film (the film
    /// force alone) while the film ratio is at least 1.5, the boundary law on the whole load
    /// below 0.01, the asperity share w = ((lambda - 1.5)/(0.01 - 1.5))^6 between; continuous
    /// at both transitions, and the friction never falls as the film ratio falls.
    #[test]
    fn rib_regimes_follow_the_film_ratio() {
        let oil = |rib_sigma: f64| Lubricant {
            rheology: Rheology::new(5e6, 0.08, 1e9, 0.03, 0.13, 0.033),
            viscosity: ViscosityTable::for_oil(0.033, 1.28e-8, Piezoviscosity::Barus),
            inlet_heating: 0.03 * 0.033 / 0.13,
            sigma: 2e-7,
            rib_sigma,
            e_prime: 2.181e11,
        };
        let (q, vs, ue, h_iso, a, b, ph) = (1209.0, 5.2, 14.7, 3.06e-6, 1.23e-3, 1.04e-3, 4.5e8);
        let s = vs / ue;
        let heat = thermal_reduction(0.03 * 0.033 / 0.13 * ue * ue, ph / 2.181e11, s);
        let h = heat * h_iso;
        let film = rib_film_traction(&oil(0.0).rheology, &oil(0.0).viscosity, vs, h, ue, a, b, ph);
        let force = |lambda: f64| oil(h / lambda).rib_force(q, vs, ue, s, h_iso, a, b, ph, Mixed::FilmRatio, rib_film_traction);
        // full film
        assert!((force(1.5) - film).abs() < 1e-12 * film && (force(6.0) - film).abs() < 1e-12 * film);
        assert_eq!(
            oil(0.0).rib_force(q, vs, ue, s, h_iso, a, b, ph, Mixed::FilmRatio, rib_film_traction),
            film
        );
        // boundary
        let boundary = q * boundary_mu(s);
        assert!((force(0.009) - boundary).abs() < 1e-12 * boundary);
        assert!(
            (force(0.01 * (1.0 + 1e-9)) - boundary).abs() < 1e-6 * boundary,
            "continuous at 0.01"
        );
        // mixed, by hand at lambda = 0.5
        let w = ((0.5 - 1.5) / (0.01 - 1.5_f64)).powi(6);
        let hand = w * boundary + (1.0 - w) * film;
        assert!((force(0.5) - hand).abs() < 1e-12 * hand);
        // the full-film rib of this case runs at mu ~ 0.005-0.01 (SKF's full-film sliding
        // coefficient of tapered roller bearings: 0.002); boundary 0.1
        assert!(film / q > 0.002 && film / q < 0.02, "film mu {}", film / q);
        let mut last = 0.0;
        for k in 0..200 {
            let lambda = 3.0 * 0.97_f64.powi(k);
            let f = force(lambda);
            assert!(f >= last * (1.0 - 1e-12), "friction fell at lambda {lambda}");
            last = f;
        }
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
    fn dry_coulomb_is_smooth_and_saturates() {
        assert_eq!(dry_mu(0.3, 0.0), 0.0);
        assert!((dry_mu(0.3, 1.0) - 0.3).abs() < 1e-7);
        assert!((dry_mu(0.3, -1.0) + 0.3).abs() < 1e-7);
    }

    /// Zhou & Hoeprich's regression: its hand value at the [W25] contact (q = 6.7 kN over
    /// 42 mm, R = 9.3 mm, 16 m/s: 9.2 N per surface), its exponents, and the slice couple's
    /// logarithmic constant.
    #[test]
    fn rolling_resistance_hand_value_scaling_and_couple() {
        let (eta0, alpha, e, r, l) = (0.033, 1.28e-8, 2.181e11, 9.3e-3, 0.042);
        let f = rolling_resistance(eta0, alpha, e, 16.0, r, 6700.0, l);
        let hand = 29.2 * r / alpha * (alpha * eta0 * 16.0 / r).powf(0.648) * (6700.0 / l / (e * r)).powf(0.246) * l;
        assert!((f - hand).abs() < 1e-9 * hand && (f - 9.17).abs() < 0.05, "{f} vs {hand}");
        let f2 = rolling_resistance(eta0, alpha, e, 32.0, r, 6700.0, l);
        assert!(((f2 / f) - 2.0_f64.powf(0.648)).abs() < 1e-12);
        let f3 = rolling_resistance(eta0, alpha, e, 16.0, r, 2.0 * 6700.0, l);
        assert!(((f3 / f) - 2.0_f64.powf(0.246)).abs() < 1e-12);
        // one slice of a tenth of the line: couple 2 F R from the logarithmic constant
        let (ls, w) = (l / 10.0, 6700.0 / l);
        let c = rolling_couple_log_constant(eta0, alpha, e, r, ls);
        let couple = (c + 0.648 * 16.0_f64.ln() + 0.246 * w.ln()).exp();
        let direct = 2.0 * rolling_resistance(eta0, alpha, e, 16.0, r, w * ls, ls) * r;
        assert!((couple - direct).abs() < 1e-12 * direct, "{couple} vs {direct}");
        assert_eq!(rolling_resistance(eta0, 0.0, e, 16.0, r, 6700.0, l), 0.0);
    }
}
