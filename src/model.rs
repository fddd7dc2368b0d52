//! The element's parameters, inputs and outputs in SI units, and the errors a model step can
//! report. Shared by every fidelity level; knows nothing of FMI.

use crate::bearing::{Bearing, LubricationModel};
use crate::tribology::{Piezoviscosity, TractionLaw};
use serde::{Deserialize, Serialize};
use std::fmt;

/// Fidelity level (MODEL.md section 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Fidelity {
    QuasiStatic = 0,
    Dynamic = 1,
    /// Skew, spin and cage speed in balance or integrated at the communication step
    /// (`crate::quasi_dynamic`).
    QuasiDynamic = 2,
}

/// Lubrication model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Lubrication {
    /// Boundary / mixed / full-film EHL friction.
    Ehl = 0,
    /// One Coulomb coefficient `mu` at all contacts [D19].
    Dry = 1,
}

/// How the cone is loaded axially.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Preload {
    /// Axial force `Fx`.
    Force = 0,
    /// Prescribed axial displacement `axialDisplacement`.
    Displacement = 1,
}

/// Which quantities of the cone's translation are inputs (parameter `causality`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum LoadCausality {
    /// Forces `Fx`, `Fy`, `Fz` in (or the axial displacement with `preload` = 1), cone
    /// displacements out.
    Force = 0,
    /// Cone displacements relative to the cup `displacement.x/y/z` in, reactions out.
    Displacement = 1,
}

/// The default `integrator`: automatic (3), the cheaper of Dormand-Prince and Rosenbrock-W per
/// communication interval (`dynamic/switching.rs`). Measured at the presets' tolerance 1e-6 on
/// the benchmark scenarios (docs/performance.md): the fastest or within 20 % of the fastest
/// method in each, where Dormand-Prince alone is 9x slower in steady running
/// and 2.3x slower on the run-up from rest.
pub const AUTOMATIC_INTEGRATOR: u32 = 3;

/// Everything the user may set before initialization (FMU parameters).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Parameters {
    pub fidelity: Fidelity,
    pub lubrication: Lubrication,
    pub preload: Preload,
    /// Forces or displacements in (the tilts are always inputs).
    pub causality: LoadCausality,
    pub slices: usize,
    pub tolerance: f64,
    pub mu: f64,
    pub pocket_clearance: f64,
    pub eta0: f64,
    pub alpha: f64,
    pub roughness: f64,
    pub skew_model: bool,
    pub clearance: f64,
    pub outer_lobes: u32,
    pub outer_waveform: f64,
    pub cage_slip_rate: f64,
    pub cage_angle0: f64,
    pub crown_drop: f64,
    pub flange_mu0: f64,
    /// Coulomb friction coefficient of the rib contact at every fidelity, in place of the rib's
    /// lubricated law (or of `mu` when dry); negative (the default): that law.
    pub flange_mu: f64,
    pub gyroscopic: bool,
    pub centrifugal: bool,
    /// Full-film traction law (and with it the film and rib laws it belongs to).
    pub traction: TractionLaw,
    /// Viscosity against pressure in the traction law.
    pub piezoviscosity: Piezoviscosity,
    /// The oil's traction data: Eyring stress (Pa), limiting shear over pressure, film shear
    /// modulus (Pa), temperature-viscosity coefficient (1/K), thermal conductivity (W/(m K)).
    pub eyring_stress: f64,
    pub limiting_shear: f64,
    pub shear_modulus: f64,
    pub oil_beta: f64,
    pub oil_conductivity: f64,
    /// Composite roughness of roller end and rib (m).
    pub flange_roughness: f64,
    /// The oil's grade: kinematic viscosity at 40 and 100 degC (m2/s), density at 15 degC
    /// (kg/m3): the viscosity's dependence on `oilTemperature` (`tribology::OilGrade`).
    pub oil_nu40: f64,
    pub oil_nu100: f64,
    pub oil_density: f64,
    /// Diameter deviation of each roller (m), one per roller.
    pub roller_dd: Vec<f64>,
    /// Dynamic model: integrator (0 = adaptive Dormand-Prince 5(4), 1 = Gill + Milne-Hamming
    /// at the fixed step `max_step`, 2 = Rosenbrock-W ROS34PW2 with the block Jacobian,
    /// 3 = automatic: the cheaper of 0 and 2 per communication interval).
    pub integrator: u32,
    /// Dynamic model: 3-DOF cage (radial translations and rotation) driven by its contacts;
    /// false: kinematic cage centred at the mean roller orbit.
    pub cage_dynamic: bool,
    /// Dynamic model: damping ratio of raceway and flange contacts.
    pub contact_damping: f64,
    /// Dynamic model: mass of the cone and what moves with it (kg).
    pub cone_mass: f64,
    /// Dynamic model: start at rest instead of from the quasi-static solution.
    pub start_from_rest: bool,
    /// Dynamic model: largest integrator step (s); the fixed step of Gill/Milne-Hamming.
    /// Default 1 ms, the default communication step: the adaptive methods' error control sets
    /// the step below it (Dormand-Prince stays at its stability limit near 10 µs whatever the
    /// cap), and a settled Rosenbrock-W run takes the whole interval ([W25] case at
    /// tolerance 1e-5, 0.3 s: 1.46 s wall with 1 ms, 2.67 s with the former 0.1 ms, the same
    /// error 8.8e-4 against Dormand-Prince 1e-9).
    pub max_step: f64,
    /// Dynamic model: threads evaluating the rollers' contacts (1: the caller's only).
    pub threads: u32,
    /// Dynamic model: start in the steady running state when there is one (axisymmetric
    /// loads and bearing; `dynamic/steady.rs`) instead of at the quasi-static seat.
    #[serde(default = "yes")]
    pub start_steady: bool,
    /// Dynamic model: right-hand-side evaluations a doStep may spend per simulated second
    /// (`workBudget`; a step of length h gets `step_work_budget(h)`).
    pub work_budget: f64,
    /// ISO 281 contamination factor e_C of the modified rating life (`contamination.eC`).
    #[serde(default = "one")]
    pub contamination_ec: f64,
    /// The lubricant supply (`supply`) and the inlet oil layer over the flooded film
    /// (`supply.level`; 0: the supply's own, `tribology::supply`).
    #[serde(default)]
    pub supply: crate::tribology::Supply,
    #[serde(default)]
    pub supply_level: f64,
    /// How the lubricated contacts share their friction between asperities and film
    /// (`mixedLubrication`, `tribology::mixed`).
    #[serde(default)]
    pub mixed_lubrication: crate::tribology::MixedLaw,
    /// A local defect (`defect.*`, `crate::defect`) and up to three more (`defect[2].*` to
    /// `defect[4].*`).
    #[serde(default)]
    pub defect: crate::defect::DefectParameters,
    #[serde(default)]
    pub further_defects: [crate::defect::DefectParameters; crate::defect::FURTHER_DEFECTS],
    /// The cup's radial support (`housing.*`, `crate::housing`).
    #[serde(default)]
    pub housing: crate::housing::HousingParameters,
    /// The oil's kinematic viscosity at its temperature (m2/s), set with `eta0` by
    /// [`Parameters::at_oil_temperature`] (0 before: `eta0` over the density at 15 degC).
    #[serde(skip)]
    pub oil_nu: f64,
}

fn yes() -> bool {
    true
}

fn one() -> f64 {
    1.0
}

/// The default `workBudget`: right-hand-side evaluations per simulated second.
///
/// A co-simulation master waits for every doStep, so each one must end within a bound that
/// does not depend on the inputs. The bound is counted in evaluations of the dynamic model's
/// right-hand side (Jacobian columns included), not in seconds, so that whether a step
/// succeeds is the same on every machine and a restored state repeats it bit for bit. 2e8 per
/// simulated second is 200 000 evaluations for a 1 ms step: about 14 s of wall time for a
/// 17-roller bearing with 20 slices (70 µs per evaluation, one core of the reference
/// machine), twice what the costliest legal transient measured needs, 97 000: a load jump
/// within the static rating on a light cone (a 30206 from Fx 3 kN, Fy 2 kN to 20 kN each,
/// static safety 1.8), where the cone strikes the rollers and those on the unloaded side
/// leave and strike their raceways and rib again (steps of nanoseconds for the first 60 µs,
/// `docs/robustness.md`, "Bounded steps"). The run-up from rest takes about 10 000 in its
/// first millisecond, steady running under combined load 120 per millisecond.
pub const DEFAULT_WORK_BUDGET: f64 = 2e8;

/// The least budget of one doStep, whatever its length: a roller impact resolved in steps of
/// nanoseconds (about 10 000 evaluations in 2 µs at tolerance 1e-5), so that short
/// communication steps (sampling at 20-500 kHz) are not refused for being short.
pub const MIN_STEP_WORK: u64 = 20_000;

/// The right-hand-side evaluations a doStep of length `h` may spend with budget `rate` per
/// simulated second.
pub fn step_work_budget(rate: f64, h: f64) -> u64 {
    let n = rate * h;
    if n.is_finite() && n > MIN_STEP_WORK as f64 {
        n.min(u64::MAX as f64 / 2.0) as u64
    } else {
        MIN_STEP_WORK
    }
}

impl Parameters {
    /// `flange.mu` where set (not negative): the rib's Coulomb coefficient whatever the
    /// raceways' law; `None`: the rib takes the contacts' own law.
    pub fn rib_coulomb(&self) -> Option<f64> {
        (self.flange_mu >= 0.0).then_some(self.flange_mu)
    }

    /// The rib's Coulomb coefficient where the rib takes Coulomb friction: `flange.mu` where
    /// set, `mu` otherwise (dry contacts, the [D19] skew model).
    pub fn rib_mu(&self) -> f64 {
        self.rib_coulomb().unwrap_or(self.mu)
    }

    /// The roller's slice count and crown drop, what the geometry takes from the parameters.
    pub fn roller_profile(&self) -> crate::geometry::RollerProfile {
        crate::geometry::RollerProfile {
            slices: self.slices,
            crown_drop: self.crown_drop,
        }
    }

    /// The oil's viscosity against its bulk temperature.
    pub fn oil_grade(&self) -> crate::tribology::OilGrade {
        crate::tribology::OilGrade::new(self.oil_nu40, self.oil_nu100, self.oil_density)
    }

    /// The parameters with `eta0` the oil's viscosity at bulk temperature `t` (K): `eta0`
    /// scaled by the grade's viscosity ratio between `t` and the bearing's reference
    /// temperature `t_ref` (the start value of `oilTemperature`, where `eta0` holds), or, with
    /// `eta0` = 0, the grade's own viscosity at `t`. The contact laws take these.
    pub fn at_oil_temperature(&self, t: f64, t_ref: f64) -> Parameters {
        let grade = self.oil_grade();
        let eta = if self.eta0 > 0.0 {
            if t == t_ref {
                self.eta0
            } else {
                self.eta0 * grade.dynamic(t) / grade.dynamic(t_ref)
            }
        } else {
            grade.dynamic(t)
        };
        let oil_nu = eta / crate::tribology::viscosity::oil_density(self.oil_density, t);
        Parameters {
            eta0: eta,
            oil_nu,
            ..self.clone()
        }
    }

    /// The lubricant supply's law for bearing `b` at the oil's temperature.
    pub fn supply_law(&self, b: &Bearing) -> crate::tribology::SupplyLaw {
        let nu = if self.oil_nu > 0.0 {
            self.oil_nu
        } else {
            self.eta0 / self.oil_density
        };
        crate::tribology::SupplyLaw::new(
            self.supply,
            self.supply_level,
            self.mixed_lubrication,
            b.bore,
            b.outside_diameter,
            nu,
        )
    }

    /// The oil's traction data as the traction laws take them.
    pub fn rheology(&self) -> crate::tribology::Rheology {
        crate::tribology::Rheology::new(
            self.eyring_stress,
            self.limiting_shear,
            self.shear_modulus,
            self.oil_beta,
            self.oil_conductivity,
            self.eta0,
        )
    }

    /// The lubricated contact laws' data for a bearing of reduced modulus `e_prime`.
    pub fn lubricant(&self, e_prime: f64) -> crate::tribology::Lubricant {
        crate::tribology::Lubricant {
            rheology: self.rheology(),
            viscosity: crate::tribology::ViscosityTable::for_oil(self.eta0, self.alpha, self.piezoviscosity),
            inlet_heating: self.oil_beta * self.eta0 / self.oil_conductivity,
            sigma: self.roughness,
            rib_sigma: self.flange_roughness,
            e_prime,
        }
    }

    /// The bearing's local defects (`defect.*`, `defect[2].*` ...), those set.
    pub fn defects(&self) -> impl Iterator<Item = &crate::defect::DefectParameters> {
        std::iter::once(&self.defect)
            .chain(&self.further_defects)
            .filter(|d| d.ring != crate::defect::DefectRing::None)
    }

    /// Whether the bearing has a local defect.
    pub fn has_defect(&self) -> bool {
        self.defects().next().is_some()
    }

    /// The defaults a bearing description carries.
    pub fn from_bearing(b: &Bearing) -> Parameters {
        Parameters {
            fidelity: Fidelity::QuasiStatic,
            lubrication: match b.lubrication {
                LubricationModel::Ehl => Lubrication::Ehl,
                LubricationModel::Dry => Lubrication::Dry,
            },
            preload: if b.displacement_preload {
                Preload::Displacement
            } else {
                Preload::Force
            },
            causality: LoadCausality::Force,
            slices: b.slices,
            tolerance: b.tolerance,
            mu: b.mu,
            pocket_clearance: b.pocket_clearance,
            eta0: b.eta0,
            alpha: b.alpha,
            roughness: b.roughness,
            skew_model: false,
            clearance: b.clearance,
            outer_lobes: b.outer_lobes,
            outer_waveform: b.outer_waveform,
            cage_slip_rate: b.cage_slip_rate,
            cage_angle0: 0.0,
            crown_drop: b.crown_drop,
            flange_mu0: b.flange_mu0,
            flange_mu: -1.0,
            gyroscopic: true,
            centrifugal: true,
            traction: TractionLaw::ThermalEyring,
            piezoviscosity: b.oil_traction.piezoviscosity,
            eyring_stress: b.oil_traction.eyring_stress,
            limiting_shear: b.oil_traction.limiting_shear,
            shear_modulus: b.oil_traction.shear_modulus,
            oil_beta: b.oil_traction.beta,
            oil_conductivity: b.oil_traction.conductivity,
            flange_roughness: b.flange_roughness,
            oil_nu40: b.oil_nu40,
            oil_nu100: b.oil_nu100,
            oil_density: b.oil_density,
            roller_dd: vec![0.0; b.roller_count],
            integrator: AUTOMATIC_INTEGRATOR,
            cage_dynamic: true,
            contact_damping: 0.05,
            cone_mass: default_cone_mass(b),
            start_from_rest: false,
            start_steady: true,
            max_step: 1e-3,
            threads: 1,
            work_budget: DEFAULT_WORK_BUDGET,
            // normal cleanliness (ISO 281 Table 13: 0.6-0.5 for pitch diameters below 100 mm,
            // 0.8-0.6 from 100 mm; 0.6 lies in both), the class of a fine-filtered circulating
            // oil or a shielded bearing: a life a gearbox user can quote. Extreme cleanliness,
            // 1, is the laboratory's
            contamination_ec: 0.6,
            // every inlet full of oil, as [W25] and [L22] compute
            supply: crate::tribology::Supply::Flooded,
            supply_level: 0.0,
            // each contact by its own film ratio, as [W25] computes
            mixed_lubrication: crate::tribology::MixedLaw::FilmRatio,
            // a healthy bearing
            defect: crate::defect::DefectParameters::default(),
            further_defects: Default::default(),
            housing: crate::housing::HousingParameters::default(),
            oil_nu: 0.0,
        }
    }

    /// Check every parameter against its valid range; the error names the parameter.
    pub fn validate(&self, b: &Bearing) -> Result<(), ModelError> {
        let bad = |name: &str, msg: String| {
            Err(ModelError::InvalidParameter {
                name: name.to_string(),
                message: msg,
            })
        };
        let d = b.roller_mean_diameter;
        if self.slices < 2 || self.slices > 200 {
            return bad(
                "slices",
                format!(
                    "must be in [2, 200] (one slice gives a roller no tilt stiffness), got {}",
                    self.slices
                ),
            );
        }
        if !(self.tolerance.is_finite() && self.tolerance >= 1e-14 && self.tolerance <= 0.1) {
            return bad("tolerance", format!("must be in [1e-14, 0.1], got {}", self.tolerance));
        }
        if !(self.mu.is_finite() && (0.0..=2.0).contains(&self.mu)) {
            return bad("mu", format!("must be in [0, 2], got {}", self.mu));
        }
        if !(self.pocket_clearance.is_finite() && self.pocket_clearance >= 0.0 && self.pocket_clearance <= 0.5 * d) {
            return bad(
                "cage.pocketClearance",
                format!("must be in [0, {:.3e}] m, got {}", 0.5 * d, self.pocket_clearance),
            );
        }
        if !(self.eta0.is_finite() && self.eta0 >= 0.0 && self.eta0 <= 100.0) {
            return bad(
                "oil.eta0",
                format!("must be in [0, 100] Pa s (0: the grade's own viscosity), got {}", self.eta0),
            );
        }
        for (name, v) in [("oil.nu40", self.oil_nu40), ("oil.nu100", self.oil_nu100)] {
            if !(v.is_finite() && (1e-7..=0.1).contains(&v)) {
                return bad(name, format!("must be in [1e-7, 0.1] m2/s (0.1 to 1e5 mm2/s), got {v}"));
            }
        }
        if self.oil_nu100 >= self.oil_nu40 {
            return bad(
                "oil.nu100",
                format!(
                    "must be below oil.nu40 ({}): viscosity falls with temperature, got {}",
                    self.oil_nu40, self.oil_nu100
                ),
            );
        }
        if !(self.oil_density.is_finite() && (500.0..=2000.0).contains(&self.oil_density)) {
            return bad("oil.density", format!("must be in [500, 2000] kg/m3, got {}", self.oil_density));
        }
        // The EHL rolling resistance grows as alpha^-0.342 towards 0 (and is 0 at 0): values
        // between 0 and 1e-10 1/Pa are no oil and overflow it.
        if !(self.alpha.is_finite() && (self.alpha == 0.0 || (1e-10..=1e-7).contains(&self.alpha))) {
            return bad("oil.alpha", format!("must be 0 or in [1e-10, 1e-7] 1/Pa, got {}", self.alpha));
        }
        if !(self.roughness.is_finite() && self.roughness >= 0.0 && self.roughness <= 1e-4) {
            return bad("roughness", format!("must be in [0, 1e-4] m, got {}", self.roughness));
        }
        if !(self.clearance.is_finite() && self.clearance.abs() <= 0.05 * d) {
            return bad(
                "clearance",
                format!(
                    "magnitude must not exceed {:.3e} m (5 % of the roller diameter), got {}",
                    0.05 * d,
                    self.clearance
                ),
            );
        }
        if self.outer_lobes > 64 {
            return bad("outer.lobes", format!("must be in [0, 64], got {}", self.outer_lobes));
        }
        if !(self.outer_waveform.is_finite() && self.outer_waveform >= 0.0 && self.outer_waveform <= 0.05 * d) {
            return bad(
                "outer.waveform",
                format!("must be in [0, {:.3e}] m, got {}", 0.05 * d, self.outer_waveform),
            );
        }
        if !(self.cage_slip_rate.is_finite() && (0.0..=1.0).contains(&self.cage_slip_rate)) {
            return bad("cageSlipRate", format!("must be in [0, 1], got {}", self.cage_slip_rate));
        }
        if !self.cage_angle0.is_finite() {
            return bad("cage.angle0", format!("must be finite, got {}", self.cage_angle0));
        }
        if !(self.crown_drop.is_finite() && self.crown_drop >= 0.0 && self.crown_drop <= 0.05 * d) {
            return bad(
                "roller.crownDrop",
                format!("must be in [0, {:.3e}] m, got {}", 0.05 * d, self.crown_drop),
            );
        }
        for (name, v, lo, hi, unit) in [
            ("oil.eyringStress", self.eyring_stress, 1e4, 1e8, " Pa"),
            ("oil.limitingShear", self.limiting_shear, 1e-3, 0.3, ""),
            ("oil.shearModulus", self.shear_modulus, 0.0, 1e11, " Pa"),
            ("oil.beta", self.oil_beta, 0.0, 0.2, " 1/K"),
            ("oil.conductivity", self.oil_conductivity, 0.01, 10.0, " W/(m K)"),
            ("flange.roughness", self.flange_roughness, 0.0, 1e-4, " m"),
        ] {
            if !(v.is_finite() && v >= lo && v <= hi) {
                return bad(name, format!("must be in [{lo:e}, {hi:e}]{unit}, got {v}"));
            }
        }
        if !(self.flange_mu0.is_finite() && (0.0..=2.0).contains(&self.flange_mu0)) {
            return bad("flange.mu0", format!("must be in [0, 2], got {}", self.flange_mu0));
        }
        if !(self.flange_mu.is_finite() && (-1.0..=2.0).contains(&self.flange_mu)) {
            return bad(
                "flange.mu",
                format!(
                    "must be in [0, 2], or negative down to -1 for the rib's lubricated law, got {}",
                    self.flange_mu
                ),
            );
        }
        for (j, dd) in self.roller_dd.iter().enumerate() {
            if !(dd.is_finite() && dd.abs() <= 0.01 * d) {
                return bad(
                    &format!("roller[{}].dD", j + 1),
                    format!(
                        "magnitude must not exceed {:.3e} m (1 % of the roller diameter), got {dd}",
                        0.01 * d
                    ),
                );
            }
        }
        if self.integrator > 3 {
            return bad(
                "integrator",
                format!(
                    "must be 0 (adaptive Dormand-Prince 5(4)), 1 (Gill + Milne-Hamming, fixed step maxStep), 2 (Rosenbrock-W ROS34PW2) or 3 (automatic: the cheaper of 0 and 2 per communication step), got {}",
                    self.integrator
                ),
            );
        }
        if !(self.contact_damping.is_finite() && (0.0..=1.0).contains(&self.contact_damping)) {
            return bad("contact.damping", format!("must be in [0, 1], got {}", self.contact_damping));
        }
        if !(self.cone_mass.is_finite() && self.cone_mass >= 1e-3 && self.cone_mass <= 1e5) {
            return bad("cone.mass", format!("must be in [0.001, 1e5] kg, got {}", self.cone_mass));
        }
        if !(1..=64).contains(&self.threads) {
            return bad("threads", format!("must be 1 to 64, got {}", self.threads));
        }
        if !(self.max_step.is_finite() && self.max_step >= 1e-9 && self.max_step <= 1.0) {
            return bad("maxStep", format!("must be in [1e-9, 1] s, got {}", self.max_step));
        }
        if !(self.work_budget.is_finite() && (1e3..=1e12).contains(&self.work_budget)) {
            return bad(
                "workBudget",
                format!("must be in [1e3, 1e12] evaluations per simulated second, got {}", self.work_budget),
            );
        }
        if !(self.contamination_ec.is_finite() && (0.0..=1.0).contains(&self.contamination_ec)) {
            return bad(
                "contamination.eC",
                format!("must be in [0, 1] (ISO 281's contamination factor), got {}", self.contamination_ec),
            );
        }
        if !(self.supply_level.is_finite() && (0.0..=1e6).contains(&self.supply_level)) {
            return bad(
                "supply.level",
                format!(
                    "must be in [0, 1e6] (the inlet oil layer over the flooded film; 0: the supply's own), got {}",
                    self.supply_level
                ),
            );
        }
        let every = std::iter::once(&self.defect).chain(&self.further_defects);
        let circumference = std::f64::consts::PI * b.pitch_diameter;
        for (p, names) in every.zip(&crate::defect::NAMES) {
            if let Err((name, message)) = crate::defect::validate(p, names, b.roller_length, circumference, d, b.roller_count) {
                return bad(name, message);
            }
        }
        if let Err((name, message)) = self.housing.validate() {
            return bad(name, message);
        }
        Ok(())
    }
}

/// Mass of the cone ring: steel annulus between the bore and the mid-roller cone contact
/// radius, over the bearing width (a documented default; add the shaft's share as needed).
pub fn default_cone_mass(b: &Bearing) -> f64 {
    let ri = 0.5 * b.pitch_diameter - b.roller_mean_radius() * libm::cos(b.roller_axis_angle());
    let ro = ri.max(0.5 * b.bore * 1.05);
    let ring = std::f64::consts::PI * (ro * ro - 0.25 * b.bore * b.bore) * b.width;
    (ring * b.ring_material.density).max(1e-3)
}

/// Continuous inputs (SI).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Inputs {
    /// Cone angular speed (rad/s).
    pub speed: f64,
    /// Cone misalignment about y (rad).
    pub xi: f64,
    /// Cone misalignment about z (rad).
    pub zeta: f64,
    pub fx: f64,
    pub fy: f64,
    pub fz: f64,
    /// Prescribed axial displacement (m) in displacement preload.
    pub axial_displacement: f64,
    /// Cup (outer ring) angular speed (rad/s), same sense as `speed`; 0: standing cup.
    #[serde(default)]
    pub cup_speed: f64,
    /// Cone displacement relative to the cup (x, y, z; m) in displacement causality.
    pub displacement: [f64; 3],
    /// Bulk oil temperature (K).
    pub oil_temperature: f64,
}

impl Inputs {
    /// The operating point a bearing description carries.
    pub fn from_bearing(b: &Bearing) -> Inputs {
        Inputs {
            speed: b.speed,
            xi: b.xi,
            zeta: b.zeta,
            fx: b.fx,
            fy: b.fy,
            fz: b.fz,
            axial_displacement: b.axial_displacement,
            cup_speed: 0.0,
            displacement: [b.axial_displacement, 0.0, 0.0],
            oil_temperature: b.oil_temperature,
        }
    }

    /// All rates zero: as time derivatives of the inputs (`ramped`), inputs held.
    pub fn held() -> Inputs {
        Inputs {
            speed: 0.0,
            xi: 0.0,
            zeta: 0.0,
            fx: 0.0,
            fy: 0.0,
            fz: 0.0,
            axial_displacement: 0.0,
            cup_speed: 0.0,
            displacement: [0.0; 3],
            oil_temperature: 0.0,
        }
    }

    /// The inputs `dt` after a communication point where they were `self`, changing at
    /// `rates` (each field the time derivative of the same field, per second): the
    /// first-order input interpolation of FMI 2.0 co-simulation (fmi2SetRealInputDerivatives).
    /// The oil temperature is held over the step: the lubricant's viscosity and the film
    /// heating limit are set for it once per step.
    pub fn ramped(&self, rates: &Inputs, dt: f64) -> Inputs {
        let at = |v: f64, r: f64| if r == 0.0 { v } else { v + r * dt };
        Inputs {
            speed: at(self.speed, rates.speed),
            xi: at(self.xi, rates.xi),
            zeta: at(self.zeta, rates.zeta),
            fx: at(self.fx, rates.fx),
            fy: at(self.fy, rates.fy),
            fz: at(self.fz, rates.fz),
            axial_displacement: at(self.axial_displacement, rates.axial_displacement),
            cup_speed: at(self.cup_speed, rates.cup_speed),
            displacement: std::array::from_fn(|k| at(self.displacement[k], rates.displacement[k])),
            oil_temperature: self.oil_temperature,
        }
    }

    /// Whether, as rates (`ramped`), these change an input the contacts see directly: a ring
    /// speed, a prescribed displacement or the misalignment. Those move the contact slips and
    /// deflections themselves, so their time derivative drives the stiff contact modes;
    /// loads act on the cone's mass and the oil temperature is held over a step.
    pub fn moves_contacts(&self) -> bool {
        self.speed != 0.0
            || self.cup_speed != 0.0
            || self.xi != 0.0
            || self.zeta != 0.0
            || self.axial_displacement != 0.0
            || self.displacement.iter().any(|d| *d != 0.0)
    }

    /// Speed of the cone relative to the cup (rad/s). Seen from the cup, a bearing with both
    /// rings turning is one with a standing cup and the cone at this speed: the rolling and
    /// sliding speeds, the traction and the friction follow it alone; only the inertial
    /// loads (centrifugal force, gyroscopic moment) see the absolute speeds.
    pub fn relative_speed(&self) -> f64 {
        self.speed - self.cup_speed
    }

    /// Reject NaN/inf, values outside the model's range and combinations the parameters `p`
    /// do not support, naming the input.
    pub fn validate(&self, b: &Bearing, p: &Parameters) -> Result<(), ModelError> {
        self.validate_ranges(b)?;
        self.validate_with(p)
    }

    /// Reject input combinations the parameters do not support: a turning cup with a lobed
    /// raceway (the lobes are modelled fixed in space; turning with the cup they would sweep
    /// past the rollers, which neither model follows).
    fn validate_with(&self, p: &Parameters) -> Result<(), ModelError> {
        if self.cup_speed != 0.0 && p.outer_lobes > 0 && p.outer_waveform > 0.0 {
            return Err(ModelError::InvalidInput {
                name: "cupSpeed",
                message: format!(
                    "is {:.6e} rad/s with a lobed cup (outer.lobes = {}): the lobes are modelled fixed in space, a turning lobed cup is not; set cupSpeed = 0 or outer.waveform = 0",
                    self.cup_speed, p.outer_lobes
                ),
            });
        }
        Ok(())
    }

    /// Reject NaN/inf and values outside the model's range, naming the input.
    fn validate_ranges(&self, b: &Bearing) -> Result<(), ModelError> {
        let named = [
            ("speed", self.speed),
            ("xi", self.xi),
            ("zeta", self.zeta),
            ("Fx", self.fx),
            ("Fy", self.fy),
            ("Fz", self.fz),
            ("axialDisplacement", self.axial_displacement),
            ("cupSpeed", self.cup_speed),
            ("displacement.x", self.displacement[0]),
            ("displacement.y", self.displacement[1]),
            ("displacement.z", self.displacement[2]),
            ("oilTemperature", self.oil_temperature),
        ];
        for (name, v) in named {
            if !v.is_finite() {
                return Err(ModelError::InvalidInput {
                    name,
                    message: format!("is {v}; inputs must be finite"),
                });
            }
        }
        // Speed: n dm up to 1e7 mm/min, three times the fastest aero-engine bearings; beyond
        // it the centrifugal and friction terms overflow.
        let max_speed = 1e7 / (b.pitch_diameter * 1e3) * std::f64::consts::PI / 30.0;
        for (name, v) in [("speed", self.speed), ("cupSpeed", self.cup_speed)] {
            if v.abs() > max_speed {
                return Err(ModelError::InvalidInput {
                    name,
                    message: format!(
                        "{v:.6e} rad/s exceeds the model's range of +-{max_speed:.1} rad/s (n dm = 1e7 mm/min on a pitch diameter of {:.1} mm)",
                        b.pitch_diameter * 1e3
                    ),
                });
            }
        }
        // Forces: far beyond any bearing, and small enough that their squares stay finite.
        for (name, v) in [("Fx", self.fx), ("Fy", self.fy), ("Fz", self.fz)] {
            if v.abs() > 1e10 {
                return Err(ModelError::InvalidInput {
                    name,
                    message: format!("{v:.6e} N exceeds the model's range of +-1e10 N"),
                });
            }
        }
        // Misalignment: the small-angle ring kinematics hold far beyond what a bearing survives.
        let max_tilt = 0.5_f64.to_radians();
        for (name, v) in [("xi", self.xi), ("zeta", self.zeta)] {
            if v.abs() > max_tilt {
                return Err(ModelError::InvalidInput {
                    name,
                    message: format!(
                        "{:.4} deg exceeds the model's range of +-0.5 deg of shaft deflection",
                        v.to_degrees()
                    ),
                });
            }
        }
        let (lo, hi) = (crate::bearing::OIL_T_MIN_C + 273.15, crate::bearing::OIL_T_MAX_C + 273.15);
        if !(lo..=hi).contains(&self.oil_temperature) {
            return Err(ModelError::InvalidInput {
                name: "oilTemperature",
                message: format!(
                    "{} K ({:.1} degC) is outside the viscosity-temperature law's range [{lo}, {hi}] K ({} to {} degC)",
                    self.oil_temperature,
                    self.oil_temperature - 273.15,
                    crate::bearing::OIL_T_MIN_C,
                    crate::bearing::OIL_T_MAX_C
                ),
            });
        }
        // Displacement preload: more than 5 % of the roller diameter is not a bearing any more.
        let max_disp = 0.05 * b.roller_mean_diameter;
        for (name, v) in [
            ("axialDisplacement", self.axial_displacement),
            ("displacement.x", self.displacement[0]),
            ("displacement.y", self.displacement[1]),
            ("displacement.z", self.displacement[2]),
        ] {
            if v.abs() > max_disp {
                return Err(ModelError::InvalidInput {
                    name,
                    message: format!(
                        "{v:.3e} m exceeds the model's range of +-{max_disp:.3e} m (5 % of the roller diameter: the contact laws and the small-displacement kinematics end well before)"
                    ),
                });
            }
        }
        Ok(())
    }
}

/// Outputs of the element now. Per-roller arrays have one entry per roller.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Outputs {
    pub friction_torque: f64,
    pub friction_torque_raceway: f64,
    pub friction_torque_flange: f64,
    pub friction_torque_cage: f64,
    /// Torques each ring feels about the bearing axis ([L22] M_inner, M_outer).
    pub friction_torque_cone: f64,
    pub friction_torque_cup: f64,
    /// Largest total sliding friction force on one roller.
    pub sliding_friction_max: f64,
    /// Largest roller-cage pocket force (skew model).
    pub qc_max: f64,
    pub power_loss: f64,
    pub cone_x: f64,
    pub cone_y: f64,
    pub cone_z: f64,
    pub reaction_fx: f64,
    pub reaction_my: f64,
    pub reaction_mz: f64,
    /// Radial forces carried by the bearing (the opposite of the rollers' force on the cone).
    pub reaction_fy: f64,
    pub reaction_fz: f64,
    /// ISO 281 basic dynamic load rating (N).
    pub rating_c: f64,
    /// ISO 281 basic rating life and ISO/TS 16281 basic reference rating life (h).
    pub life_l10: f64,
    pub life_l10r: f64,
    /// ISO 76 basic static load rating (N), static safety factor C0/P0 of the carried loads,
    /// and the largest Hertz pressure over the raceway slices (Pa).
    pub rating_c0: f64,
    pub safety_s0: f64,
    pub pressure_max: f64,
    /// Smallest raceway film ratio (at the most heavily loaded slices) and the rib's (at the
    /// most heavily loaded rib contact).
    pub film_ratio_raceway: f64,
    pub film_ratio_flange: f64,
    /// ISO 281 modified rating life (h), its life modification factor and viscosity ratio.
    pub life_l10m: f64,
    pub life_a_iso: f64,
    pub oil_kappa: f64,
    /// Radial force of the bearing on its housing (N): the rollers' contact forces on the cup
    /// and, with a dynamic cage, the cage land's, resolved on y and z.
    pub housing_fy: f64,
    pub housing_fz: f64,
    /// The cup's radial acceleration on its support (m/s², `crate::housing`; 0 with a rigid
    /// housing).
    pub cup_ay: f64,
    pub cup_az: f64,
    /// Tangent stiffness d(reaction_i)/d(q_j), q = (x, y, z, xi, zeta), row-major.
    pub stiffness: [f64; 25],
    /// The oil's dynamic viscosity at the current oil temperature (Pa s).
    pub oil_viscosity: f64,
    pub tilt_max: f64,
    pub tilt_mean: f64,
    pub skew_max: f64,
    pub skew_mean: f64,
    pub qi_max: f64,
    pub qo_max: f64,
    pub qf_max: f64,
    pub loaded_rollers: i32,
    pub cage_speed: f64,
    pub solver_iterations: i32,
    pub solver_residual: f64,
    pub integrator_steps: i32,
    pub integrator_rhs: i32,
    pub integrator_rejected: i32,
    pub tilt: Vec<f64>,
    pub skew: Vec<f64>,
    pub qi: Vec<f64>,
    pub qo: Vec<f64>,
    pub qf: Vec<f64>,
    pub qc: Vec<f64>,
    pub azimuth: Vec<f64>,
    pub nit: Vec<f64>,
    pub not: Vec<f64>,
    pub nft: Vec<f64>,
    pub nis: Vec<f64>,
    pub nos: Vec<f64>,
    pub nfs: Vec<f64>,
    /// Total sliding friction force on each roller (cone + cup + flange).
    pub sliding_friction: Vec<f64>,
}

impl Outputs {
    /// Copy every output of `o` into `self` without reallocating the per-roller arrays (the
    /// element keeps a backup of the outputs every step; a derived `clone_from` allocates).
    pub fn copy_from(&mut self, o: &Outputs) {
        // destructured without `..`: a new output that is not copied here does not compile
        let Outputs {
            friction_torque,
            friction_torque_raceway,
            friction_torque_flange,
            friction_torque_cage,
            friction_torque_cone,
            friction_torque_cup,
            sliding_friction_max,
            qc_max,
            power_loss,
            cone_x,
            cone_y,
            cone_z,
            reaction_fx,
            reaction_my,
            reaction_mz,
            reaction_fy,
            reaction_fz,
            rating_c,
            life_l10,
            life_l10r,
            rating_c0,
            safety_s0,
            pressure_max,
            film_ratio_raceway,
            film_ratio_flange,
            life_l10m,
            life_a_iso,
            oil_kappa,
            housing_fy,
            housing_fz,
            cup_ay,
            cup_az,
            stiffness,
            oil_viscosity,
            tilt_max,
            tilt_mean,
            skew_max,
            skew_mean,
            qi_max,
            qo_max,
            qf_max,
            loaded_rollers,
            cage_speed,
            solver_iterations,
            solver_residual,
            integrator_steps,
            integrator_rhs,
            integrator_rejected,
            tilt,
            skew,
            qi,
            qo,
            qf,
            qc,
            azimuth,
            nit,
            not,
            nft,
            nis,
            nos,
            nfs,
            sliding_friction,
        } = o;
        self.friction_torque.clone_from(friction_torque);
        self.friction_torque_raceway.clone_from(friction_torque_raceway);
        self.friction_torque_flange.clone_from(friction_torque_flange);
        self.friction_torque_cage.clone_from(friction_torque_cage);
        self.friction_torque_cone.clone_from(friction_torque_cone);
        self.friction_torque_cup.clone_from(friction_torque_cup);
        self.sliding_friction_max.clone_from(sliding_friction_max);
        self.qc_max.clone_from(qc_max);
        self.power_loss.clone_from(power_loss);
        self.cone_x.clone_from(cone_x);
        self.cone_y.clone_from(cone_y);
        self.cone_z.clone_from(cone_z);
        self.reaction_fx.clone_from(reaction_fx);
        self.reaction_my.clone_from(reaction_my);
        self.reaction_mz.clone_from(reaction_mz);
        self.reaction_fy.clone_from(reaction_fy);
        self.reaction_fz.clone_from(reaction_fz);
        self.rating_c.clone_from(rating_c);
        self.life_l10.clone_from(life_l10);
        self.life_l10r.clone_from(life_l10r);
        self.rating_c0.clone_from(rating_c0);
        self.safety_s0.clone_from(safety_s0);
        self.pressure_max.clone_from(pressure_max);
        self.film_ratio_raceway.clone_from(film_ratio_raceway);
        self.film_ratio_flange.clone_from(film_ratio_flange);
        self.life_l10m.clone_from(life_l10m);
        self.life_a_iso.clone_from(life_a_iso);
        self.oil_kappa.clone_from(oil_kappa);
        self.housing_fy.clone_from(housing_fy);
        self.housing_fz.clone_from(housing_fz);
        self.cup_ay.clone_from(cup_ay);
        self.cup_az.clone_from(cup_az);
        self.stiffness.clone_from(stiffness);
        self.oil_viscosity.clone_from(oil_viscosity);
        self.tilt_max.clone_from(tilt_max);
        self.tilt_mean.clone_from(tilt_mean);
        self.skew_max.clone_from(skew_max);
        self.skew_mean.clone_from(skew_mean);
        self.qi_max.clone_from(qi_max);
        self.qo_max.clone_from(qo_max);
        self.qf_max.clone_from(qf_max);
        self.loaded_rollers.clone_from(loaded_rollers);
        self.cage_speed.clone_from(cage_speed);
        self.solver_iterations.clone_from(solver_iterations);
        self.solver_residual.clone_from(solver_residual);
        self.integrator_steps.clone_from(integrator_steps);
        self.integrator_rhs.clone_from(integrator_rhs);
        self.integrator_rejected.clone_from(integrator_rejected);
        self.tilt.clone_from(tilt);
        self.skew.clone_from(skew);
        self.qi.clone_from(qi);
        self.qo.clone_from(qo);
        self.qf.clone_from(qf);
        self.qc.clone_from(qc);
        self.azimuth.clone_from(azimuth);
        self.nit.clone_from(nit);
        self.not.clone_from(not);
        self.nft.clone_from(nft);
        self.nis.clone_from(nis);
        self.nos.clone_from(nos);
        self.nfs.clone_from(nfs);
        self.sliding_friction.clone_from(sliding_friction);
    }
    /// Zero outputs with per-roller arrays of length `z`.
    pub fn new(z: usize) -> Outputs {
        let v = || vec![0.0; z];
        Outputs {
            tilt: v(),
            skew: v(),
            qi: v(),
            qo: v(),
            qf: v(),
            qc: v(),
            azimuth: v(),
            nit: v(),
            not: v(),
            nft: v(),
            nis: v(),
            nos: v(),
            nfs: v(),
            sliding_friction: v(),
            ..Default::default()
        }
    }

    /// Fill the over-all-rollers statistics from the per-roller arrays.
    pub fn summarize(&mut self) {
        let z = self.tilt.len().max(1) as f64;
        self.tilt_max = self.tilt.iter().fold(0.0, |m, t| m.max(t.abs()));
        self.tilt_mean = self.tilt.iter().sum::<f64>() / z;
        self.skew_max = self.skew.iter().fold(0.0, |m, t| m.max(t.abs()));
        self.skew_mean = self.skew.iter().sum::<f64>() / z;
        self.qi_max = self.qi.iter().fold(0.0, |m, q| m.max(*q));
        self.qo_max = self.qo.iter().fold(0.0, |m, q| m.max(*q));
        self.qf_max = self.qf.iter().fold(0.0, |m, q| m.max(*q));
        self.sliding_friction_max = self.sliding_friction.iter().fold(0.0, |m, q| m.max(*q));
        self.qc_max = self.qc.iter().fold(0.0, |m, q| m.max(*q));
        self.loaded_rollers = self.qi.iter().zip(&self.qo).filter(|(a, b)| **a > 0.0 && **b > 0.0).count() as i32;
    }

    /// True when every output is finite.
    pub fn all_finite(&self) -> bool {
        let scalars = [
            self.friction_torque,
            self.friction_torque_raceway,
            self.friction_torque_flange,
            self.friction_torque_cage,
            self.friction_torque_cone,
            self.friction_torque_cup,
            self.sliding_friction_max,
            self.qc_max,
            self.power_loss,
            self.cone_x,
            self.cone_y,
            self.cone_z,
            self.reaction_fx,
            self.reaction_my,
            self.reaction_mz,
            self.reaction_fy,
            self.reaction_fz,
            self.rating_c,
            self.life_l10,
            self.life_l10r,
            self.rating_c0,
            self.safety_s0,
            self.pressure_max,
            self.film_ratio_raceway,
            self.film_ratio_flange,
            self.life_l10m,
            self.life_a_iso,
            self.oil_kappa,
            self.housing_fy,
            self.housing_fz,
            self.cup_ay,
            self.cup_az,
            self.oil_viscosity,
            self.tilt_max,
            self.tilt_mean,
            self.skew_max,
            self.skew_mean,
            self.qi_max,
            self.qo_max,
            self.qf_max,
            self.cage_speed,
            self.solver_residual,
        ];
        scalars.iter().all(|v| v.is_finite())
            && self.stiffness.iter().all(|v| v.is_finite())
            && [
                &self.tilt,
                &self.skew,
                &self.qi,
                &self.qo,
                &self.qf,
                &self.qc,
                &self.azimuth,
                &self.nit,
                &self.not,
                &self.nft,
                &self.nis,
                &self.nos,
                &self.nfs,
                &self.sliding_friction,
            ]
            .iter()
            .all(|a| a.iter().all(|v| v.is_finite()))
    }
}

/// How serious a model error is, in FMI terms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// The step could not be completed with these inputs; the master may retry (fmi2Discard).
    Discard,
    /// The inputs or parameters are invalid (fmi2Error).
    Error,
}

/// What went wrong in a model evaluation. Messages say why, in the user's terms.
#[derive(Debug, Clone, PartialEq)]
pub enum ModelError {
    InvalidParameter {
        name: String,
        message: String,
    },
    InvalidInput {
        name: &'static str,
        message: String,
    },
    /// The Newton solver found no equilibrium within its iteration budget.
    NoEquilibrium {
        message: String,
    },
    /// The dynamic integrator could not meet its tolerance (step size underflow, NaN).
    IntegratorFailure {
        message: String,
    },
    /// The loads are beyond the model's validity (`load_within_range`); the same refusal at
    /// every fidelity.
    OutOfRange {
        message: String,
    },
}

/// Contact pressures above this multiple of the ISO 76 static limit (4000 MPa) are beyond
/// the model's range. At twice the limit, 8000 MPa, the load is four times the static rating
/// (the pressure of a line contact grows with the root of its load), the contact half-width of
/// steel on steel (E* = 114 GPa) is b = 2 p0 R / E* = 14 % of the relative radius of
/// curvature, where Hertz's half-space solution that every contact law here rests on is no
/// longer small against the bodies, and the pressure is above the indentation hardness of
/// bearing steel (about 7 GPa at 60 HRC): the rings yield through, which no elastic law
/// describes.
pub const PRESSURE_RANGE: f64 = 2.0;

/// Refuse a solution whose loads are beyond the model's validity: a contact pressure more
/// than [`PRESSURE_RANGE`] times the ISO 76 static limit, or a slice interference beyond the
/// line-contact law's range. Both models check their solutions with it (the dynamic model
/// the quasi-static solution for its inputs, before it integrates), so both refuse the
/// same loads with the same message.
pub fn load_within_range(out: &Outputs, report: &SolveReport) -> Result<(), ModelError> {
    let limit = PRESSURE_RANGE * crate::bearing::rating::STATIC_LIMIT_STRESS;
    if out.pressure_max > limit {
        return Err(ModelError::OutOfRange {
            message: format!(
                "the largest contact pressure is {:.0} MPa, more than {PRESSURE_RANGE} times the static limit of {:.0} MPa of ISO 76 (static safety factor s0 = {:.3}); the contact laws are elastic and rest on Hertz's half-space, which ends there (docs/model.md, \"The model's range\"); reduce the load",
                out.pressure_max * 1e-6,
                crate::bearing::rating::STATIC_LIMIT_STRESS * 1e-6,
                out.safety_s0
            ),
        });
    }
    if report.contact_law_extrapolated {
        return Err(ModelError::OutOfRange {
            message: "a slice interference is beyond the validity range of the line-contact law (Johnson: ln(8 R / delta) - 1 < 3, delta > 0.15 R); reduce the load or the interference".to_string(),
        });
    }
    Ok(())
}

impl ModelError {
    pub fn severity(&self) -> Severity {
        match self {
            ModelError::InvalidParameter { .. } | ModelError::InvalidInput { .. } => Severity::Error,
            ModelError::NoEquilibrium { .. } | ModelError::IntegratorFailure { .. } | ModelError::OutOfRange { .. } => Severity::Discard,
        }
    }
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ModelError::InvalidParameter { name, message } => {
                write!(f, "parameter {name} {message}")
            }
            ModelError::InvalidInput { name, message } => write!(f, "input {name} {message}"),
            ModelError::NoEquilibrium { message } => {
                write!(f, "no quasi-static equilibrium: {message}")
            }
            ModelError::IntegratorFailure { message } => write!(f, "dynamic integration failed: {message}"),
            ModelError::OutOfRange { message } => write!(f, "the load is beyond the model's range: {message}"),
        }
    }
}

impl std::error::Error for ModelError {}

/// Diagnostics of one quasi-static solve (no allocation).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct SolveReport {
    pub iterations: u32,
    /// Residual relative to the reference force.
    pub residual: f64,
    /// Some slice interference exceeded the validity range of the line-contact law.
    pub contact_law_extrapolated: bool,
    /// The dynamic model was to start in its steady running state (`startSteady`) but the
    /// Newton solve found none: it started at the quasi-static seat.
    #[serde(default)]
    pub steady_start_failed: bool,
    /// The dynamic model was to start in its running state (`startSteady`), but the run-in at
    /// the initial inputs did not bring input power and dissipation together (or failed).
    #[serde(default)]
    pub run_in_unbalanced: bool,
    /// The quasi-dynamic model's last step kept the rollers' seats and the cone at the
    /// quasi-static seat: its balance with them free did not converge.
    #[serde(default)]
    pub seat_held: bool,
}
