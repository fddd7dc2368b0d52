//! Bearing description: the preset / bearing-file schema (millimetres, degrees, GPa as the
//! field names say), with the catalogue data a file may give instead of its internal geometry,
//! and the validated bearing in SI units the rest of the model reads.
//!
//! Data of the four shipped presets come from `../shared/data/bearings.md` ([W25], [D19],
//! [L22], [Y22]); values the studies do not give are documented defaults, listed in each
//! preset's `documented_defaults` and in the FMU documentation. Reading a file (validation,
//! defaults, estimate, conversion to SI) is `super::read`'s.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::fmt;

/// The presets compiled into the program and shipped in the FMU's `resources/`.
pub const PRESETS: &[(&str, &str)] = &[
    ("TRB130x230", include_str!("../../presets/TRB130x230.json")),
    ("32018X", include_str!("../../presets/32018X.json")),
    ("32008", include_str!("../../presets/32008.json")),
    ("CRB-TRILOBE", include_str!("../../presets/CRB-TRILOBE.json")),
    ("TRB130x230-W25", include_str!("../../presets/TRB130x230-W25.json")),
];

/// The presets' names in table order, comma-separated, as help texts and error messages list
/// them.
pub fn preset_names() -> String {
    PRESETS.iter().map(|(name, _)| *name).collect::<Vec<_>>().join(", ")
}

/// The JSON Schema (draft 2020-12) of a bearing file, derived from the same structures that
/// read it; shipped as `presets/bearing.schema.json` (a test keeps the two equal).
pub fn bearing_file_schema() -> String {
    let schema = schemars::schema_for!(BearingFile);
    serde_json::to_string_pretty(&schema).expect("a schema serialises") + "\n"
}

/// Name of the default preset.
pub const DEFAULT_PRESET: &str = "TRB130x230";

/// A bearing file could not be used. `field` is the path of the offending field.
#[derive(Debug, Clone, PartialEq)]
pub struct BearingError {
    pub field: String,
    pub message: String,
}

impl fmt::Display for BearingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.field.is_empty() {
            write!(f, "invalid bearing description: {}", self.message)
        } else {
            write!(f, "invalid bearing description: field `{}`: {}", self.field, self.message)
        }
    }
}

impl std::error::Error for BearingError {}

// ---------------------------------------------------------------------------------------
// File schema (units in the field names)
// ---------------------------------------------------------------------------------------

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BearingFile {
    /// The JSON Schema an editor validates the file against (for example
    /// `"bearing.schema.json"`, shipped beside the presets); not read otherwise.
    #[serde(rename = "$schema", default, skip_serializing_if = "Option::is_none")]
    pub schema: Option<String>,
    pub name: String,
    #[serde(default)]
    pub description: String,
    #[serde(default)]
    pub source: String,
    /// `tapered` or `cylindrical`.
    pub kind: Kind,
    /// Catalogue data of a tapered roller bearing (`catalogue::Catalogue`), given instead of the
    /// internal geometry (envelope, rollers, pitch diameter, raceway angles, flange): the
    /// geometry is then estimated from it as `trb bearing estimate` does.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub catalogue: Option<Catalogue>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub envelope: Option<EnvelopeFile>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rollers: Option<RollersFile>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pitch_diameter_mm: Option<f64>,
    /// Cone (inner raceway) contact angle to the bearing axis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cone_angle_deg: Option<f64>,
    /// Cup (outer raceway) contact angle to the bearing axis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cup_angle_deg: Option<f64>,
    /// Flange (rib) geometry; absent for bearings without a loaded flange (cylindrical).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flange: Option<FlangeFile>,
    // The sections below have documented defaults (`catalogue::defaults`) when absent; the
    // bearing then lists each default it took in its `documented_defaults`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub materials: Option<MaterialsFile>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_law: Option<ContactLaw>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cage: Option<CageFile>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lubricant: Option<LubricantFile>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<FrictionFile>,
    #[serde(default)]
    pub raceway: RacewayFile,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solver: Option<SolverFile>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub operating_point: Option<OperatingPointFile>,
    /// Human-readable notes: which values are documented defaults and why.
    #[serde(default)]
    pub documented_defaults: Vec<String>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    Tapered,
    Cylindrical,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ContactLaw {
    /// Johnson's line contact (Contact Mechanics, 1985) in the slice form of [W25], with the
    /// contact modulus E* of the book (`contact::LineLaw::johnson`).
    Johnson,
    /// [W25] Eq. (1) as printed: the same form with Ē, 1/Ē = ½ Σ (1 − ν²)/E, i.e. 2 E*: twice
    /// as stiff as Johnson's (`docs/model.md`, "Contact laws").
    #[serde(rename = "johnson-w25")]
    JohnsonW25,
    /// Palmgren slices [D19, Y22, L22].
    Palmgren,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct EnvelopeFile {
    pub bore_mm: f64,
    pub outside_diameter_mm: f64,
    pub width_mm: f64,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RollersFile {
    pub count: i64,
    /// Effective contact length, measured along the roller axis.
    pub length_mm: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mean_diameter_mm: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub large_end_diameter_mm: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub small_end_diameter_mm: Option<f64>,
    /// Half-cone angle; if absent, (cup angle - cone angle)/2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub half_cone_angle_deg: Option<f64>,
    /// Radius R_s of the spherical large end. Give it, or `end_radius_ratio`, or neither
    /// (then R_s = 0.9 of the rib's circumferential radius of curvature rho_p).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub end_radius_mm: Option<f64>,
    /// The end radius as the ratio R_s / rho_p to the rib's circumferential radius of curvature
    /// rho_p = r_f / cos(flange contact angle), in (0, 1.05]; designs use 0.75-0.95. Instead of
    /// `end_radius_mm`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub end_radius_ratio: Option<f64>,
    #[serde(default)]
    pub crown_drop_um: f64,
}

/// Flange (rib) geometry in one of the conventions the studies use.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FlangeFile {
    /// Angle between the flange contact normal and the radial plane (Harris; [W25] 83 deg).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_angle_deg: Option<f64>,
    /// Angle between the rib face normal and the bearing axis ([D19] "flange opening angle").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub opening_angle_deg: Option<f64>,
    /// Angle between the rib face and the roller axis ([L22] "flange angle", rad).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub face_to_roller_axis_rad: Option<f64>,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialFile {
    #[serde(rename = "E_GPa")]
    pub e_gpa: f64,
    pub nu: f64,
    pub density_kg_m3: f64,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialsFile {
    pub roller: MaterialFile,
    pub rings: MaterialFile,
    pub cage: MaterialFile,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CageFile {
    pub pocket_clearance_mm: f64,
    pub guide_clearance_mm: f64,
    pub land_width_mm: f64,
    pub land_radius_mm: f64,
    pub mass_kg: f64,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LubricantFile {
    #[serde(rename = "eta0_Pa_s")]
    pub eta0_pa_s: f64,
    #[serde(rename = "alpha_per_Pa")]
    pub alpha_per_pa: f64,
    pub roughness_um: f64,
    /// The oil's grade: kinematic viscosity at 40 and 100 degC (mm2/s) and density at 15 degC
    /// (kg/m3); when absent an ISO VG 68 mineral oil (68 and 8.6 mm2/s, VI 100, 870 kg/m3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nu40_mm2_s: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nu100_mm2_s: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density_kg_m3: Option<f64>,
    /// Bulk oil temperature (degC) at which `eta0_Pa_s` holds; when absent, the temperature at
    /// which the grade's viscosity is eta0.
    #[serde(default, skip_serializing_if = "Option::is_none", rename = "temperature_C")]
    pub temperature_c: Option<f64>,
    /// Traction data of the oil (docs/model.md, "Oil traction data"); defaults when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub traction: Option<OilTractionFile>,
}

/// The oil's traction data in a bearing file: every field optional, with the documented
/// defaults of [`OilTraction::default`].
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OilTractionFile {
    #[serde(rename = "eyring_stress_MPa", default, skip_serializing_if = "Option::is_none")]
    pub eyring_stress_mpa: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limiting_shear: Option<f64>,
    #[serde(rename = "shear_modulus_GPa", default, skip_serializing_if = "Option::is_none")]
    pub shear_modulus_gpa: Option<f64>,
    #[serde(rename = "beta_per_K", default, skip_serializing_if = "Option::is_none")]
    pub beta_per_k: Option<f64>,
    #[serde(rename = "conductivity_W_mK", default, skip_serializing_if = "Option::is_none")]
    pub conductivity_w_mk: Option<f64>,
    /// "barus" or "roelands".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub piezoviscosity: Option<crate::tribology::Piezoviscosity>,
}

/// The oil's traction data (SI) with the defaults the presets use unless they say otherwise
/// (sources in docs/model.md, "Oil traction data").
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OilTraction {
    /// Eyring stress tau_0 (Pa): 5 MPa, mid-range of Johnson & Tevaarwerk (1977), 2-10 MPa.
    pub eyring_stress: f64,
    /// Limiting shear stress over pressure: 0.08 (Bair & Winer 1979 range 0.03-0.1).
    pub limiting_shear: f64,
    /// Shear modulus of the film (Pa): 1 GPa (Johnson & Tevaarwerk 1977: 0.3-3 GPa).
    pub shear_modulus: f64,
    /// Temperature-viscosity coefficient (1/K): 0.03, ln(nu40/nu100)/60 K of a MIL-PRF-23699
    /// aviation oil (25 and 5 mm^2/s).
    pub beta: f64,
    /// Thermal conductivity of the oil (W/(m K)): 0.13, mineral and ester oils.
    pub conductivity: f64,
    pub piezoviscosity: crate::tribology::Piezoviscosity,
}

impl Default for OilTraction {
    fn default() -> OilTraction {
        OilTraction {
            eyring_stress: 5e6,
            limiting_shear: 0.08,
            shear_modulus: 1e9,
            beta: 0.03,
            conductivity: 0.13,
            piezoviscosity: crate::tribology::Piezoviscosity::Barus,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum LubricationModel {
    Ehl,
    Dry,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FrictionFile {
    pub model: LubricationModel,
    pub mu: f64,
    pub flange_mu0: f64,
    pub cage_slip_rate: f64,
    /// Composite RMS roughness of roller end and rib (um); the raceway roughness when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flange_roughness_um: Option<f64>,
}

#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RacewayFile {
    #[serde(default)]
    pub clearance_um: f64,
    #[serde(default)]
    pub outer_lobes: i64,
    #[serde(default)]
    pub outer_waveform_um: f64,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolverFile {
    pub slices: i64,
    pub tolerance: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum PreloadFile {
    Force,
    Displacement,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OperatingPointFile {
    pub speed_rpm: f64,
    #[serde(rename = "Fx_N")]
    pub fx_n: f64,
    #[serde(rename = "Fy_N", default)]
    pub fy_n: f64,
    #[serde(rename = "Fz_N", default)]
    pub fz_n: f64,
    #[serde(default)]
    pub xi_deg: f64,
    #[serde(default)]
    pub zeta_deg: f64,
    #[serde(default)]
    pub axial_displacement_um: f64,
    pub preload: PreloadFile,
}

// The `catalogue` block: what `super::estimate` builds the internal geometry from.
/// Catalogue data of a single-row tapered roller bearing (mm, N), the catalogues' symbols.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Catalogue {
    /// Bore diameter d, mm.
    #[serde(rename = "d_mm")]
    pub d: f64,
    /// Outside diameter D, mm.
    #[serde(rename = "D_mm")]
    pub outside_d: f64,
    /// Total width T, mm.
    #[serde(rename = "T_mm")]
    pub t: f64,
    /// Cone (inner ring) width B, mm (it may exceed T, as in inch series, up to 1.5 T).
    #[serde(rename = "B_mm", default, skip_serializing_if = "Option::is_none")]
    pub b: Option<f64>,
    /// Cup (outer ring) width C, mm (at most T).
    #[serde(rename = "C_mm", default, skip_serializing_if = "Option::is_none")]
    pub c: Option<f64>,
    /// Basic dynamic radial load rating C_r, N.
    #[serde(rename = "Cr_N")]
    pub c_r: f64,
    /// Calculation factor e (ISO 281: e = 1.5 tan α).
    pub e: f64,
    /// Axial load factor Y (ISO 281: Y = 0.4 cot α), checked against e.
    #[serde(rename = "Y", default, skip_serializing_if = "Option::is_none")]
    pub y: Option<f64>,
    /// Basic static radial load rating C_0r, N (reported against the geometry's).
    #[serde(rename = "C0r_N", default, skip_serializing_if = "Option::is_none")]
    pub c_0r: Option<f64>,
    /// Number of rollers, when the maker gives it.
    #[serde(rename = "Z", default, skip_serializing_if = "Option::is_none")]
    pub z: Option<i64>,
}

// ---------------------------------------------------------------------------------------
// SI bearing
// ---------------------------------------------------------------------------------------

/// Elastic and mass properties of a material (SI).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Material {
    pub e: f64,
    pub nu: f64,
    pub density: f64,
}

/// A validated bearing in SI units (m, rad, Pa, kg). Angles of the raceways are measured
/// from the bearing axis; the flange contact angle from the radial plane (Harris).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Bearing {
    pub name: String,
    pub description: String,
    pub source: String,
    pub kind: Kind,
    pub bore: f64,
    pub outside_diameter: f64,
    pub width: f64,
    pub roller_count: usize,
    pub roller_length: f64,
    pub roller_mean_diameter: f64,
    pub roller_half_angle: f64,
    /// Spherical roller-end radius (0 when the bearing has no loaded flange).
    pub roller_end_radius: f64,
    pub pitch_diameter: f64,
    pub cone_angle: f64,
    pub cup_angle: f64,
    /// Flange contact angle (normal to radial plane); `None` = no flange contact.
    pub flange_angle: Option<f64>,
    pub roller_material: Material,
    pub ring_material: Material,
    pub cage_material: Material,
    pub contact_law: ContactLaw,
    pub pocket_clearance: f64,
    pub guide_clearance: f64,
    pub land_width: f64,
    pub land_radius: f64,
    pub cage_mass: f64,
    pub eta0: f64,
    /// The oil's grade (m2/s, m2/s, kg/m3) and the bulk temperature (K) at which eta0 holds.
    pub oil_nu40: f64,
    pub oil_nu100: f64,
    pub oil_density: f64,
    pub oil_temperature: f64,
    pub alpha: f64,
    pub roughness: f64,
    pub oil_traction: OilTraction,
    /// Composite roughness of roller end and rib (m).
    pub flange_roughness: f64,
    pub lubrication: LubricationModel,
    pub mu: f64,
    pub flange_mu0: f64,
    pub cage_slip_rate: f64,
    pub crown_drop: f64,
    pub clearance: f64,
    pub outer_lobes: u32,
    pub outer_waveform: f64,
    pub slices: usize,
    pub tolerance: f64,
    pub speed: f64,
    pub fx: f64,
    pub fy: f64,
    pub fz: f64,
    pub xi: f64,
    pub zeta: f64,
    pub axial_displacement: f64,
    pub displacement_preload: bool,
    pub documented_defaults: Vec<String>,
}

impl Bearing {
    /// Mean roller radius.
    pub fn roller_mean_radius(&self) -> f64 {
        0.5 * self.roller_mean_diameter
    }

    /// Roller axis angle to the bearing axis.
    pub fn roller_axis_angle(&self) -> f64 {
        self.cone_angle + self.roller_half_angle
    }

    /// Whether the roller and cone have axial stiffness (a tapered bearing or a flange).
    pub fn has_axial_stiffness(&self) -> bool {
        self.kind == Kind::Tapered
    }
}

/// Roller end radius over the rib's circumferential radius of curvature, R_s / rho_p, where
/// the bearing file gives neither `rollers.end_radius_mm` nor `rollers.end_radius_ratio`.
/// Makers grind the roller's large end flatter than the rib's circumferential curvature so
/// that the contact stays on the end face and the rib contact is non-conformal. "Effects of
/// Roller End/Rib Curvature Ratio on Friction and Accuracy in Tapered Roller Bearings"
/// (Machines 13 (2025) 910, doi:10.3390/machines13100910) compares 0.85, 0.90 and
/// 0.95 rho_p and finds 0.85 the least friction, 0.95 the best running accuracy and 0.90 the
/// compromise. 0.9 is that compromise, an engineering choice where a maker gives no value.
/// The ratio also sets the roller's skew (docs/dynamic.md, "The roller skew mode").
pub const DEFAULT_END_RADIUS_RATIO: f64 = 0.9;

/// Largest accepted R_s / rho_p: above 1 the sphere touches the rib at its edges; 32018X's
/// published ratio is 1.0003 ([D19]), so a few per cent above 1 are read as conformal.
pub const MAX_END_RADIUS_RATIO: f64 = 1.05;

/// The bulk oil temperatures the viscosity-temperature law is used over (degC): Walther's
/// equation holds for mineral and ester oils from their pour point to about 150 degC; the
/// range admits -40..200 degC and refuses beyond.
pub const OIL_T_MIN_C: f64 = -40.0;
pub const OIL_T_MAX_C: f64 = 200.0;

#[cfg(test)]
mod tests {
    use super::*;

    /// Bearing and scenario files give their numbers as the doubles nearest to them (Cargo.toml:
    /// serde_json's `float_roundtrip`): 3500 rpm written out to 17 digits is 3500 pi / 30 to
    /// the bit, and every shortest round-trip form reads back as itself.
    #[test]
    fn json_numbers_read_as_the_nearest_double() {
        let speed: f64 = serde_json::from_str("366.51914291880917").unwrap();
        assert_eq!(speed.to_bits(), (3500.0 * std::f64::consts::PI / 30.0).to_bits());
        let mut v = 1.234_567_890_123_456_7e-9_f64;
        for _ in 0..2000 {
            let back: f64 = serde_json::from_str(&format!("{v:?}")).unwrap();
            assert_eq!(back.to_bits(), v.to_bits(), "{v:?}");
            v *= 1.013_7;
        }
    }

    /// The shipped schema is the one the reader's structures give (after a change of the file
    /// format: `cargo run -- bearing schema --out presets/bearing.schema.json`).
    #[test]
    fn the_shipped_schema_is_the_readers() {
        assert_eq!(
            include_str!("../../presets/bearing.schema.json"),
            bearing_file_schema(),
            "presets/bearing.schema.json is stale: cargo run -- bearing schema --out presets/bearing.schema.json"
        );
    }
}
