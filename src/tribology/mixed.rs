//! Mixed lubrication: the share of a lubricated contact's friction that its asperities carry,
//! and their boundary coefficient (parameter `mixedLubrication`). Every lubricated contact,
//! raceway slice and roller end alike, takes mu = w mu_BL(s) + (1 - w) mu_film.
//!
//! - `mixedLubrication` = 0, by the film ratio ([W25] §2.2): each contact's own share from its
//!   film ratio Lambda = h / sigma, w = 1 below 0.01, 0 from 1.5 and
//!   ((Lambda - 1.5) / (0.01 - 1.5))^6 between (`rib::asperity_share`), with Kragelskii's
//!   boundary law of [W25], mu_BL(s) = (-0.1 + 22.28 s) exp(-181.46 s) + 0.1 (plateau 0.1).
//! - `mixedLubrication` = 1, SKF's weighting (SKF, "The SKF model for calculating the frictional
//!   moment of rolling bearings"; Rolling bearings catalogue 10000 EN): one share for the whole
//!   bearing, w = phi_bl = exp(-2.6e-8 (n nu)^1.4 d_m) (n the rings' relative speed in r/min,
//!   nu the operating kinematic viscosity in mm2/s, for grease the base oil's, d_m the mean
//!   diameter (d + D) / 2 in mm), and SKF's boundary coefficient mu_bl = 0.15 for sliding.
//!   SKF fitted phi_bl to the measured friction of whole bearings; it knows speed, viscosity
//!   and size but not the load, the roughness or the supply's starvation. Its mu_bl is a
//!   sliding coefficient, and the raceways roll: the product keeps the shape of [W25]'s law in
//!   the slide-to-roll ratio (zero at zero sliding, the traction building up with the creep)
//!   and scales it to SKF's value, mu_BL(s) 0.15 / 0.1.
//!
//! Both are continuous in every argument: the film-ratio share at its two regime bounds
//! (tested in `rib.rs`), SKF's share everywhere, 1 at standstill and 0 at high speed.

use super::boundary_mu;

/// SKF's boundary coefficient of sliding friction, "generally about 0.15".
pub const SKF_MU_BL: f64 = 0.15;
/// The plateau of [W25]'s boundary law at large slide-to-roll ratios, which SKF's weighting
/// scales to [`SKF_MU_BL`].
const W25_BOUNDARY_PLATEAU: f64 = 0.1;

/// Which law shares a contact between asperities and film (parameter `mixedLubrication`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum MixedLaw {
    /// Each contact by its own film ratio ([W25]).
    #[default]
    FilmRatio = 0,
    /// One share for the bearing by speed, viscosity and size (SKF's phi_bl).
    Skf = 1,
}

impl MixedLaw {
    /// The law of parameter value `v` (0 or 1).
    pub fn from_index(v: i64) -> Option<MixedLaw> {
        match v {
            0 => Some(MixedLaw::FilmRatio),
            1 => Some(MixedLaw::Skf),
            _ => None,
        }
    }
}

/// The share law at one operating point, as the contact laws take it.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub enum Mixed {
    /// Each contact's share from its film ratio, [W25]'s boundary law.
    #[default]
    FilmRatio,
    /// This share at every contact, SKF's boundary coefficient.
    Weight(f64),
}

impl Mixed {
    /// The asperities' share of a contact whose film ratio is `lambda`.
    #[inline(always)]
    pub fn share(self, lambda: f64) -> f64 {
        match self {
            Mixed::FilmRatio => super::asperity_share(lambda),
            Mixed::Weight(w) => w,
        }
    }

    /// The boundary coefficient at slide-to-roll ratio `slide_roll`.
    #[inline(always)]
    pub fn boundary_mu(self, slide_roll: f64) -> f64 {
        self.boundary_scale() * boundary_mu(slide_roll)
    }

    /// The factor on [W25]'s boundary law: 1, or SKF's coefficient over [W25]'s plateau.
    #[inline(always)]
    pub fn boundary_scale(self) -> f64 {
        match self {
            Mixed::FilmRatio => 1.0,
            Mixed::Weight(_) => SKF_MU_BL / W25_BOUNDARY_PLATEAU,
        }
    }
}

/// SKF's phi_bl for a bearing of mean diameter `d_m` (m) on an oil of kinematic viscosity `nu`
/// (m2/s), per speed: the constant 2.6e-8 nu^1.4 d_m (catalogue units) of
/// phi_bl = exp(-rate n^1.4), n in r/min.
pub fn skf_rate(nu: f64, d_m: f64) -> f64 {
    2.6e-8 * libm::pow((nu * 1e6).max(0.0), 1.4) * d_m * 1e3
}

/// SKF's phi_bl at relative ring speed `speed` (rad/s) with the constant `rate` of [`skf_rate`].
pub fn skf_weight(rate: f64, speed: f64) -> f64 {
    let rpm = speed.abs() * 30.0 / std::f64::consts::PI;
    libm::exp(-rate * libm::pow(rpm, 1.4))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// SKF's share is 1 at standstill, falls continuously and monotonically with speed to 0,
    /// and is the catalogue's formula: 32008 (d_m 54 mm) on 20 mm2/s at 1000 r/min,
    /// exp(-2.6e-8 (20000)^1.4 54).
    #[test]
    fn skf_share_falls_from_one_to_zero_with_speed() {
        let rate = skf_rate(20e-6, 0.054);
        assert_eq!(skf_weight(rate, 0.0), 1.0);
        let at_1000 = skf_weight(rate, 1000.0 * std::f64::consts::PI / 30.0);
        let by_hand = libm::exp(-2.6e-8 * libm::pow(1000.0 * 20.0, 1.4) * 54.0);
        assert!((at_1000 - by_hand).abs() < 1e-12 * by_hand, "{at_1000} vs {by_hand}");
        let mut last = 1.0;
        for k in 1..=400 {
            let w = skf_weight(rate, k as f64 * 2.0);
            assert!(w < last && w > 0.0);
            // continuous: no step between neighbouring speeds larger than the slope allows
            assert!(last - w < 0.02, "{k}: {last} -> {w}");
            last = w;
        }
        assert!(skf_weight(rate, 1000.0) < 1e-6);
    }

    /// The boundary coefficient of SKF's weighting is [W25]'s law scaled to SKF's 0.15: zero at
    /// pure rolling, 0.15 at large sliding; the film-ratio law's is [W25]'s.
    #[test]
    fn the_boundary_coefficients() {
        let skf = Mixed::Weight(0.3);
        assert!(skf.boundary_mu(0.0).abs() < 1e-15);
        assert!((skf.boundary_mu(1.0) - SKF_MU_BL).abs() < 1e-12);
        assert!((Mixed::FilmRatio.boundary_mu(1.0) - 0.1).abs() < 1e-12);
        assert_eq!(skf.share(0.0), 0.3);
        assert_eq!(skf.share(10.0), 0.3);
        assert_eq!(Mixed::FilmRatio.share(10.0), 0.0);
        assert_eq!(Mixed::FilmRatio.share(0.0), 1.0);
    }
}
