//! Lubricant supply: how much oil reaches the inlets of the contacts, and what a starved inlet
//! does to the films and to the EHL rolling resistance (parameters `supply`, `supply.level`).
//!
//! - Starved film from the inlet oil layer (Chevalier, Lubrecht, Cann, Colin & Dalmaz, J.
//!   Tribol. 120 (1998) 126; Damiens, Venner, Cann & Lubrecht, J. Tribol. 126 (2004) 105; the
//!   closed form as Lugt, "Grease Lubrication in Rolling Bearings", Wiley 2013, Eq. 9.73,
//!   writes it): h / h_ff = r / (1 + r^gamma)^(1/gamma), with r the inlet layer over the fully
//!   flooded central film, mass-consistent (the layer's oil at the contact's density: r = 1 is
//!   exactly the oil a flooded contact passes). A thick layer gives the flooded film back
//!   (r -> inf), a thin one passes through (h -> r h_ff). The exponent grows with the contact's
//!   slenderness across the rolling direction: about 3 for circular contacts, up to about 15
//!   for wide ellipses (Damiens et al. 2004, as Lugt summarises them).
//!   - Roller end on the rib, a compact ellipse: [`GAMMA_RIB`] = 3, the circular value.
//!   - Raceway slices, line contacts: [`GAMMA_RACEWAY`] = 50. A line leaks no oil sideways. The
//!     numerical EHL line contact of `ehl_line.rs`, starved by moving its inlet meniscus, passes
//!     its layer through until the film is the flooded one: h / h_ff = min(r, 1), with a knee
//!     that 50 follows within 1.5 % and 15 within 4.5 % (`ehl_line.rs`,
//!     `the_starved_line_contact_follows_the_layer_law`).
//! - Rolling resistance: SKF's kinematic replenishment/starvation factor (SKF, "The SKF model
//!   for calculating the frictional moment"; Rolling bearings catalogue 10000 EN),
//!   phi_rs = exp(-K_rs nu n (d + D) sqrt(K_Z / (2 (D - d)))), nu in mm2/s, n in r/min, d and D
//!   in mm; K_rs = 3e-8 for a low-level oil bath or oil jet, 6e-8 for grease and oil-air;
//!   K_Z = 6 for single-row tapered roller bearings. SKF applies it to the rolling frictional
//!   moment, and so does the product, to the EHL rolling resistance. The rolling resistance does
//!   not follow the film: it is the inlet's Poiseuille shear, which a meniscus moving in cuts
//!   long before the film thins (the numerical line contact: the rolling force at 0.71-0.83 of
//!   the flooded one while the film is within 2.5 % of it).
//! - The layer a supply leaves (`supply.level` = 0):
//!   - oil bath, oil jet, oil-air: a full film. The replenishment SKF measures is, in the
//!     numerical line contact, a meniscus that leaves the film within 1-2.5 % of the flooded
//!     one (above), and no source gives these supplies' layers.
//!   - grease: the film half the flooded one: greased bearings in service ran on about 50 % of
//!     the flooded film, which starved almost at once and then held (Wilson 1979, as Lugt 2013,
//!     ch. 9, reports it; spindle bearings at high speed, down to 16-20 %: Barz 1996, ibid.).
//!     The films are the base oil's (`oil.nu40`, `oil.nu100` describe the base oil; SKF's
//!     viscosity ratio and ISO 281 take the base oil's viscosity for grease).
//! - `supply.level` > 0 sets r for every contact (a user who knows the inlet layer).
//!
//! Flooded (`supply` = 0) returns factors of exactly 1: the model's arithmetic is unchanged.

use super::mixed::{Mixed, MixedLaw};

/// The lubricant supply of the bearing (parameter `supply`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Supply {
    /// Every inlet full of oil (circulating oil, a deep bath): no starvation.
    #[default]
    Flooded = 0,
    /// Low-level oil bath or oil jet.
    OilBath = 1,
    /// Grease; the oil data are the base oil's.
    Grease = 2,
    /// Oil-air (oil-mist) lubrication.
    OilAir = 3,
}

impl Supply {
    /// The supply of parameter value `v` (0..=3).
    pub fn from_index(v: i64) -> Option<Supply> {
        match v {
            0 => Some(Supply::Flooded),
            1 => Some(Supply::OilBath),
            2 => Some(Supply::Grease),
            3 => Some(Supply::OilAir),
            _ => None,
        }
    }

    /// SKF's replenishment/starvation constant K_rs of the supply (catalogue units; 0 flooded).
    pub fn k_rs(self) -> f64 {
        match self {
            Supply::Flooded => 0.0,
            Supply::OilBath => 3.0e-8,
            Supply::Grease | Supply::OilAir => 6.0e-8,
        }
    }
}

/// Exponent of the starved-film law for the raceway slices (line contacts).
pub const GAMMA_RACEWAY: f64 = 50.0;
/// Exponent of the starved-film law for the roller end on the rib (a compact ellipse).
pub const GAMMA_RIB: f64 = 3.0;
/// The film a greased bearing runs on, over the flooded one (Wilson 1979, in Lugt 2013).
pub const GREASE_FILM: f64 = 0.5;
/// SKF's geometry constant K_Z of single-row tapered roller bearings.
pub const K_Z_TAPERED: f64 = 6.0;

/// The starved central film over the flooded one for inlet layer `r` (over the flooded film)
/// and exponent `gamma`: r / (1 + r^gamma)^(1/gamma); 1 for an infinite layer, 0 for none.
pub fn starved_film(r: f64, gamma: f64) -> f64 {
    if r == f64::INFINITY {
        return 1.0;
    }
    if !(r > 0.0) {
        return 0.0;
    }
    // r / (1 + r^g)^(1/g) = 1 / (1 + r^-g)^(1/g): finite for every r > 0
    libm::pow(1.0 + libm::pow(r, -gamma), -1.0 / gamma)
}

/// The layer r that gives the starved film ratio `s` in (0, 1) under exponent `gamma`: the
/// inverse of [`starved_film`].
pub fn layer_for_film(s: f64, gamma: f64) -> f64 {
    if !(s < 1.0) {
        return f64::INFINITY;
    }
    if !(s > 0.0) {
        return 0.0;
    }
    libm::pow(libm::pow(s, -gamma) - 1.0, -1.0 / gamma)
}

/// What the supply does at one speed: factors on the flooded raceway film, the flooded rib film
/// and the EHL rolling resistance; with them the mixed-lubrication law at that speed
/// (`mixed.rs`), which SKF's weighting makes depend on the speed and the oil as well.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Starvation {
    pub raceway: f64,
    pub rib: f64,
    pub rolling: f64,
    pub mixed: Mixed,
}

impl Starvation {
    pub const FLOODED: Starvation = Starvation {
        raceway: 1.0,
        rib: 1.0,
        rolling: 1.0,
        mixed: Mixed::FilmRatio,
    };
}

/// A bearing's supply with what its starvation depends on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SupplyLaw {
    pub supply: Supply,
    /// Inlet layer over the flooded film; 0: the supply's own (from SKF's phi_rs).
    pub level: f64,
    /// K_rs nu (d + D) sqrt(K_Z / (2 (D - d))) per r/min (nu in mm2/s, d and D in mm): SKF's
    /// exponent of phi_rs per unit speed.
    rate_per_rpm: f64,
    /// SKF's phi_bl constant (`mixed::skf_rate`) under SKF's mixed law, None under the film
    /// ratio's.
    boundary_rate: Option<f64>,
}

impl SupplyLaw {
    /// The law of `supply` with layer `level` and mixed law `mixed` for a bearing of bore `d`
    /// and outside diameter `big_d` (m) running on an oil of kinematic viscosity `nu` (m2/s) at
    /// its temperature.
    pub fn new(supply: Supply, level: f64, mixed: MixedLaw, d: f64, big_d: f64, nu: f64) -> SupplyLaw {
        let (d_mm, big_d_mm, nu_mm2) = (d * 1e3, big_d * 1e3, nu * 1e6);
        let geometry = if big_d_mm > d_mm {
            (d_mm + big_d_mm) * (K_Z_TAPERED / (2.0 * (big_d_mm - d_mm))).sqrt()
        } else {
            0.0
        };
        SupplyLaw {
            supply,
            level,
            rate_per_rpm: supply.k_rs() * nu_mm2 * geometry,
            boundary_rate: match mixed {
                MixedLaw::FilmRatio => None,
                MixedLaw::Skf => Some(super::mixed::skf_rate(nu, 0.5 * (d + big_d))),
            },
        }
    }

    /// A flooded supply (every factor 1).
    pub fn flooded() -> SupplyLaw {
        SupplyLaw {
            supply: Supply::Flooded,
            level: 0.0,
            rate_per_rpm: 0.0,
            boundary_rate: None,
        }
    }

    /// SKF's phi_rs at shaft speed `speed` (rad/s, relative to the cup).
    pub fn replenishment(&self, speed: f64) -> f64 {
        let rpm = speed.abs() * 30.0 / std::f64::consts::PI;
        libm::exp(-self.rate_per_rpm * rpm)
    }

    /// The inlet layer over the flooded film: `supply.level`, else the supply's own (infinite:
    /// a full film).
    pub fn layer(&self) -> f64 {
        if self.level > 0.0 {
            self.level
        } else {
            match self.supply {
                Supply::Grease => layer_for_film(GREASE_FILM, GAMMA_RACEWAY),
                Supply::Flooded | Supply::OilBath | Supply::OilAir => f64::INFINITY,
            }
        }
    }

    /// The starvation factors and the mixed law at speed `speed` (rad/s); factors exactly 1
    /// when flooded.
    pub fn starvation(&self, speed: f64) -> Starvation {
        let mixed = match self.boundary_rate {
            None => Mixed::FilmRatio,
            Some(rate) => Mixed::Weight(super::mixed::skf_weight(rate, speed)),
        };
        if self.supply == Supply::Flooded {
            return Starvation {
                mixed,
                ..Starvation::FLOODED
            };
        }
        let r = self.layer();
        Starvation {
            raceway: starved_film(r, GAMMA_RACEWAY),
            rib: starved_film(r, GAMMA_RIB),
            rolling: self.replenishment(speed),
            mixed,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The law's limits, its monotony and continuity in the layer, and its inverse.
    #[test]
    fn the_starved_film_tends_to_the_flooded_one() {
        for gamma in [GAMMA_RIB, GAMMA_RACEWAY] {
            assert_eq!(starved_film(f64::INFINITY, gamma), 1.0);
            assert_eq!(starved_film(0.0, gamma), 0.0);
            // a thin layer passes through, a thick one gives the flooded film
            assert!((starved_film(1e-3, gamma) / 1e-3 - 1.0).abs() < 1e-8);
            assert!(1.0 - starved_film(1e3, gamma) < 1e-8);
            // at r = 1 the film is 2^(-1/gamma) of the flooded one
            assert!((starved_film(1.0, gamma) - 2f64.powf(-1.0 / gamma)).abs() < 1e-14);
            let mut last = 0.0;
            let mut r = 1e-4;
            while r < 1e4 {
                let s = starved_film(r, gamma);
                assert!(
                    s >= last && s <= 1.0 && s <= r * (1.0 + 1e-12) && (s > last || s == 1.0),
                    "monotone and below both limits at r = {r}"
                );
                // continuous: its slope is at most 1 (to rounding)
                assert!((starved_film(r * (1.0 + 1e-9), gamma) - s).abs() <= 1.001e-9 * r);
                if s < 1.0 - 1e-6 {
                    // (closer to 1 the flooded film is reached to rounding: no inverse)
                    assert!((layer_for_film(s, gamma) / r - 1.0).abs() < 1e-6, "inverse at r = {r}");
                }
                last = s;
                r *= 1.1;
            }
        }
        // the rib (compact ellipse) starves more than a line at the same layer
        assert!(starved_film(0.8, GAMMA_RIB) < starved_film(0.8, GAMMA_RACEWAY));
        // the raceway law is within 1.5 % of its line limit min(r, 1) everywhere
        assert!((starved_film(1.0, GAMMA_RACEWAY) - 1.0).abs() < 0.015);
        assert!((starved_film(0.8, GAMMA_RACEWAY) - 0.8).abs() < 1e-6);
    }

    /// SKF's phi_rs on the rolling resistance (hand value), the supplies' own layers, flooded
    /// exactly 1, a level set by the user.
    #[test]
    fn each_supply_starves_as_its_sources_say() {
        // 32008 (d 40, D 68 mm), 20 mm2/s, 3000 r/min, grease: by hand
        let law = SupplyLaw::new(Supply::Grease, 0.0, MixedLaw::FilmRatio, 0.040, 0.068, 20e-6);
        let hand = (-6e-8 * 20.0 * 3000.0 * 108.0 * (6.0 / 56.0f64).sqrt()).exp();
        let speed = 3000.0 * std::f64::consts::PI / 30.0;
        assert!(
            (law.replenishment(speed) - hand).abs() < 1e-12,
            "{} vs {hand}",
            law.replenishment(speed)
        );
        let s = law.starvation(speed);
        assert!((s.rolling - hand).abs() < 1e-12);
        assert!(
            (s.raceway - GREASE_FILM).abs() < 1e-12,
            "grease: half the flooded film, {}",
            s.raceway
        );
        assert!(s.rib < s.raceway && s.rib > 0.45, "the rib starves more: {}", s.rib);
        // faster: the rolling resistance more starved, the grease film the same
        let faster = law.starvation(2.0 * speed);
        assert!(faster.rolling < s.rolling && faster.raceway == s.raceway);
        // an oil bath: full films, SKF's replenishment on the rolling resistance
        let bath = SupplyLaw::new(Supply::OilBath, 0.0, MixedLaw::FilmRatio, 0.040, 0.068, 20e-6).starvation(speed);
        assert_eq!((bath.raceway, bath.rib), (1.0, 1.0));
        assert!(
            bath.rolling > s.rolling && bath.rolling < 1.0,
            "oil bath replenishes better than grease"
        );
        assert_eq!(
            SupplyLaw::new(Supply::Flooded, 0.0, MixedLaw::FilmRatio, 0.040, 0.068, 20e-6).starvation(speed),
            Starvation::FLOODED
        );
        // at standstill nothing needs replenishing
        assert_eq!(law.starvation(0.0).rolling, 1.0);
        // a level set by the user replaces the supply's own
        let set = SupplyLaw::new(Supply::OilAir, 0.3, MixedLaw::FilmRatio, 0.040, 0.068, 20e-6).starvation(speed);
        assert_eq!(set.raceway, starved_film(0.3, GAMMA_RACEWAY));
        assert_eq!(set.rib, starved_film(0.3, GAMMA_RIB));
    }
}
