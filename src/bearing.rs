//! Bearing description: the preset / bearing-file schema (millimetres, degrees, GPa as the
//! field names say), its validation, and the conversion to SI units done once on load.
//!
//! Data of the four shipped presets come from `../shared/data/bearings.md` ([W25], [D19],
//! [L22], [Y22]); values the studies do not give are documented defaults, listed in each
//! preset's `documented_defaults` and in the FMU documentation.
//!
//! Errors name the offending field by its path in the file (for example
//! `rollers.length_mm: must be a finite number > 0, got -3`), every fault of a file in one
//! message. A file may give catalogue data instead of its internal geometry (`catalogue`), and
//! may leave out every section with a documented default (`catalogue::defaults`).

use crate::catalogue::{defaults, Catalogue};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::fmt;

/// The presets compiled into the program and shipped in the FMU's `resources/`.
pub const PRESETS: &[(&str, &str)] = &[
    ("TRB130x230", include_str!("../presets/TRB130x230.json")),
    ("32018X", include_str!("../presets/32018X.json")),
    ("32008", include_str!("../presets/32008.json")),
    ("CRB-TRILOBE", include_str!("../presets/CRB-TRILOBE.json")),
    ("TRB130x230-W25", include_str!("../presets/TRB130x230-W25.json")),
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

fn err(field: &str, message: impl Into<String>) -> BearingError {
    BearingError {
        field: field.to_string(),
        message: message.into(),
    }
}

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
    /// One of the presets compiled into the program.
    pub fn preset(name: &str) -> Result<Bearing, BearingError> {
        let text = PRESETS
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
            .map(|(_, t)| *t)
            .ok_or_else(|| err("", format!("unknown preset `{name}`; presets are {}", preset_names())))?;
        Bearing::from_json(text)
    }

    /// The default bearing (`TRB130x230`).
    pub fn default_preset() -> Bearing {
        Bearing::preset(DEFAULT_PRESET).expect("the default preset is valid")
    }

    /// A preset name or a path to a bearing JSON file.
    pub fn from_name_or_file(arg: &str) -> Result<Bearing, BearingError> {
        if PRESETS.iter().any(|(n, _)| n.eq_ignore_ascii_case(arg)) {
            return Bearing::preset(arg);
        }
        let path = std::path::Path::new(arg);
        if path.exists() {
            let text = std::fs::read_to_string(path).map_err(|e| err("", format!("cannot read bearing file {arg}: {e}")))?;
            return Bearing::from_json(&text);
        }
        let names: Vec<&str> = PRESETS.iter().map(|(n, _)| *n).collect();
        Err(err(
            "",
            format!("`{arg}` is neither a preset ({}) nor an existing file", names.join(", ")),
        ))
    }

    /// Parse and validate a bearing JSON text.
    ///
    /// One run names every fault: a fault of the file's structure (an unknown field, a value
    /// of the wrong type) is taken out of the text and the rest read again, and the values are
    /// then checked section by section. Only a missing required field, or one whose removal
    /// leaves it missing, ends the reading.
    pub fn from_json(text: &str) -> Result<Bearing, BearingError> {
        let mut value: serde_json::Value = match serde_json::from_str(text) {
            Ok(v) => v,
            // not JSON (or a number beyond f64): where, by the file's fields
            Err(_) => {
                let de = &mut serde_json::Deserializer::from_str(text);
                return match serde_path_to_error::deserialize::<_, BearingFile>(de) {
                    Ok(file) => file.to_bearing(),
                    Err(e) => Err(fault_of(e)),
                };
            }
        };
        let mut faults = Faults::default();
        let mut removed: Vec<(Vec<String>, String)> = Vec::new();
        // sections taken out whole: their other faults are not reported (they would be the
        // section's absence)
        let mut sections_out: Vec<String> = Vec::new();
        for _ in 0..64 {
            let e = match serde_path_to_error::deserialize::<_, BearingFile>(&value) {
                Ok(file) => {
                    match file.to_bearing_or_faults() {
                        Ok(bearing) if faults.0.is_empty() => return Ok(bearing),
                        Ok(_) => {}
                        Err(more) => {
                            let inside = |field: &str| sections_out.iter().any(|s| field == s || field.starts_with(&format!("{s}.")));
                            faults.0.extend(more.0.into_iter().filter(|e| !inside(&e.field)));
                        }
                    }
                    break;
                }
                Err(e) => e,
            };
            let mut path: Vec<String> = e
                .path()
                .iter()
                .map(|s| match s {
                    serde_path_to_error::Segment::Map { key } => key.clone(),
                    serde_path_to_error::Segment::Seq { index } => index.to_string(),
                    other => other.to_string(),
                })
                .collect();
            let fault = fault_of(e);
            let message = fault.message.clone();
            // A field this loop took out is now missing: its fault is already named; take its
            // section out too (every section but the name and kind is optional) and go on.
            if let Some(key) = quoted_after(&message, "missing field `") {
                let ours = removed.iter().any(|(parent, k)| *parent == path && k == key);
                if !ours {
                    faults.push(fault);
                }
                let Some((section, parent)) = path.split_last() else {
                    break;
                };
                if !ours
                    || value_at(&mut value, parent)
                        .and_then(|v| v.as_object_mut())
                        .and_then(|o| o.remove(section))
                        .is_none()
                {
                    break;
                }
                sections_out.push(path.join("."));
                continue;
            }
            faults.push(fault);
            if let Some(key) = quoted_after(&message, "unknown field `") {
                if path.last().map(String::as_str) != Some(key) {
                    path.push(key.to_string());
                }
            }
            let Some((key, parent)) = path.split_last() else {
                break;
            };
            let taken = value_at(&mut value, parent)
                .and_then(|v| v.as_object_mut())
                .and_then(|object| object.remove(key));
            if taken.is_none() {
                break;
            }
            removed.push((parent.to_vec(), key.clone()));
        }
        Err(faults.into_result().expect_err("a file that reads and converts returns above"))
    }

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

fn finite(field: &str, v: f64) -> Result<f64, BearingError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(err(field, format!("must be a finite number, got {v}")))
    }
}

fn positive(field: &str, v: f64) -> Result<f64, BearingError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(err(field, format!("must be a finite number > 0, got {v}")))
    }
}

fn non_negative(field: &str, v: f64) -> Result<f64, BearingError> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(err(field, format!("must be a finite number >= 0, got {v}")))
    }
}

fn in_range(field: &str, v: f64, lo: f64, hi: f64) -> Result<f64, BearingError> {
    if v.is_finite() && v >= lo && v <= hi {
        Ok(v)
    } else {
        Err(err(field, format!("must lie in [{lo}, {hi}], got {v}")))
    }
}

fn material(field: &str, m: &MaterialFile) -> Result<Material, BearingError> {
    Ok(Material {
        e: in_range(&format!("{field}.E_GPa"), m.e_gpa, 0.1, 2000.0)? * 1e9,
        nu: in_range(&format!("{field}.nu"), m.nu, 0.0, 0.499)?,
        density: in_range(&format!("{field}.density_kg_m3"), m.density_kg_m3, 100.0, 30000.0)?,
    })
}

const MM: f64 = 1e-3;

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
const UM: f64 = 1e-6;

/// A deserialiser's error as a fault at its path (the file's root names no field).
fn fault_of<E: fmt::Display>(e: serde_path_to_error::Error<E>) -> BearingError {
    let field = e.path().to_string();
    err(if field == "." { "" } else { &field }, e.into_inner().to_string())
}

/// The text between `prefix` and the next backquote in `message`.
fn quoted_after<'a>(message: &'a str, prefix: &str) -> Option<&'a str> {
    let rest = &message[message.find(prefix)? + prefix.len()..];
    Some(&rest[..rest.find('`')?])
}

/// The JSON value at `path` (object keys, array indices).
fn value_at<'a>(v: &'a mut serde_json::Value, path: &[String]) -> Option<&'a mut serde_json::Value> {
    path.iter().try_fold(v, |v, key| match v {
        serde_json::Value::Object(m) => m.get_mut(key),
        serde_json::Value::Array(a) => a.get_mut(key.parse::<usize>().ok()?),
        _ => None,
    })
}

/// A required field, or the error naming it.
fn need<'a, T>(v: &'a Option<T>, field: &str) -> Result<&'a T, BearingError> {
    v.as_ref().ok_or_else(|| {
        err(
            field,
            format!("missing field `{field}` (give the internal geometry, or a `catalogue` block instead)"),
        )
    })
}

/// A section with a documented default: the file's, or the default with its note added.
fn or_default<T: Clone>(v: &Option<T>, default: impl FnOnce() -> T, note: &str, notes: &mut Vec<String>) -> T {
    match v {
        Some(v) => v.clone(),
        None => {
            notes.push(note.to_string());
            default()
        }
    }
}

/// The validated internal geometry of a bearing file (SI: m, rad).
struct InternalGeometry {
    bore: f64,
    od: f64,
    width: f64,
    z: usize,
    length: f64,
    mean_d: f64,
    half: f64,
    end_radius: f64,
    dm: f64,
    cone: f64,
    cup: f64,
    flange_angle: Option<f64>,
    crown: f64,
}

/// The faults of one bearing file, collected so that one run names them all.
#[derive(Default)]
struct Faults(Vec<BearingError>);

impl Faults {
    fn push(&mut self, e: BearingError) {
        self.0.push(e);
    }

    /// The value, or `None` with its fault recorded.
    fn take<T>(&mut self, r: Result<T, BearingError>) -> Option<T> {
        r.map_err(|e| self.push(e)).ok()
    }

    /// A checked number, or NaN with its fault recorded (NaN fails no later comparison, so a
    /// fault is not reported twice through the checks that use it).
    fn num(&mut self, r: Result<f64, BearingError>) -> f64 {
        self.take(r).unwrap_or(f64::NAN)
    }

    /// One error naming the first fault's field and listing every fault.
    fn into_result(self) -> Result<(), BearingError> {
        let mut all = self.0.into_iter();
        let Some(first) = all.next() else {
            return Ok(());
        };
        let mut message = first.message;
        for e in all {
            message.push_str(&format!("; field `{}`: {}", e.field, e.message));
        }
        Err(BearingError {
            field: first.field,
            message,
        })
    }
}

impl BearingFile {
    /// Validate and convert to SI: a `catalogue` block is estimated first
    /// ([`Catalogue::estimate`]); absent sections take their documented defaults.
    pub fn to_bearing(&self) -> Result<Bearing, BearingError> {
        self.to_bearing_or_faults().map_err(|f| f.into_result().expect_err("faults"))
    }

    /// [`BearingFile::to_bearing`] with its faults one by one.
    fn to_bearing_or_faults(&self) -> Result<Bearing, Faults> {
        match &self.catalogue {
            Some(c) => self.estimated(c).map_err(|e| Faults(vec![e]))?.validate(),
            None => self.validate(),
        }
    }

    /// This file with its catalogue block replaced by the estimated internal geometry.
    fn estimated(&self, catalogue: &Catalogue) -> Result<BearingFile, BearingError> {
        let geometry_given: Vec<&str> = [
            ("envelope", self.envelope.is_some()),
            ("rollers", self.rollers.is_some()),
            ("pitch_diameter_mm", self.pitch_diameter_mm.is_some()),
            ("cone_angle_deg", self.cone_angle_deg.is_some()),
            ("cup_angle_deg", self.cup_angle_deg.is_some()),
            ("flange", self.flange.is_some()),
        ]
        .iter()
        .filter(|(_, given)| *given)
        .map(|(name, _)| *name)
        .collect();
        if !geometry_given.is_empty() {
            return Err(err(
                "catalogue",
                format!(
                    "give either a catalogue block or the internal geometry, not both (the file also gives {})",
                    geometry_given.join(", ")
                ),
            ));
        }
        if self.kind != Kind::Tapered {
            return Err(err("kind", "a catalogue block describes a tapered roller bearing"));
        }
        let estimate = catalogue.estimate().map_err(|faults| {
            let field = format!("catalogue.{}", faults.0[0].file_key());
            let all: Vec<String> = faults
                .0
                .iter()
                .map(|f| format!("catalogue.{}: {}", f.file_key(), f.message))
                .collect();
            err(&field, all.join("; "))
        })?;
        let full = estimate.bearing_file(catalogue, &self.name);
        let mut notes = estimate.geometry_notes(catalogue);
        notes.extend(self.documented_defaults.iter().cloned());
        let cage = match &self.cage {
            Some(c) => Some(c.clone()),
            None => {
                notes.push(defaults::CAGE_NOTE.to_string());
                full.cage.clone()
            }
        };
        Ok(BearingFile {
            schema: None,
            name: self.name.clone(),
            description: if self.description.is_empty() {
                full.description
            } else {
                self.description.clone()
            },
            source: if self.source.is_empty() { full.source } else { self.source.clone() },
            kind: Kind::Tapered,
            catalogue: None,
            envelope: full.envelope,
            rollers: full.rollers,
            pitch_diameter_mm: full.pitch_diameter_mm,
            cone_angle_deg: full.cone_angle_deg,
            cup_angle_deg: full.cup_angle_deg,
            flange: full.flange,
            materials: self.materials.clone(),
            contact_law: self.contact_law,
            cage,
            lubricant: self.lubricant.clone(),
            friction: self.friction.clone(),
            raceway: self.raceway.clone(),
            solver: self.solver.clone(),
            operating_point: self.operating_point.clone(),
            documented_defaults: notes,
        })
    }

    /// Validate a file that gives its internal geometry and convert it to SI. Every section is
    /// checked, so one run names every fault (the geometry's first: its checks build on each
    /// other).
    fn validate(&self) -> Result<Bearing, Faults> {
        let mut faults = Faults::default();
        if self.name.trim().is_empty() {
            faults.push(err("name", "must not be empty"));
        }
        let mut notes = self.documented_defaults.clone();
        let g = faults.take(self.geometry());
        let mean_d = g.as_ref().map_or(f64::NAN, |g| g.mean_d);
        let materials = or_default(&self.materials, defaults::materials, defaults::MATERIALS_NOTE, &mut notes);
        let roller_material = faults.take(material("materials.roller", &materials.roller));
        let ring_material = faults.take(material("materials.rings", &materials.rings));
        let cage_material = faults.take(material("materials.cage", &materials.cage));
        let contact_law = or_default(&self.contact_law, || ContactLaw::Palmgren, defaults::CONTACT_LAW_NOTE, &mut notes);
        let cage_default = || match &g {
            Some(g) => crate::catalogue::cage(g.z, g.mean_d / MM, g.length / MM, g.dm / MM),
            // no geometry to size it by: the geometry's fault is reported
            None => defaults::placeholder_cage(),
        };
        let c = &or_default(&self.cage, cage_default, defaults::CAGE_NOTE, &mut notes);
        let pocket = faults.num(non_negative("cage.pocket_clearance_mm", c.pocket_clearance_mm)) * MM;
        if pocket > 0.5 * mean_d {
            faults.push(err("cage.pocket_clearance_mm", "exceeds half the roller diameter"));
        }
        let guide = faults.num(non_negative("cage.guide_clearance_mm", c.guide_clearance_mm)) * MM;
        let land_width = faults.num(positive("cage.land_width_mm", c.land_width_mm)) * MM;
        let land_radius = faults.num(positive("cage.land_radius_mm", c.land_radius_mm)) * MM;
        let cage_mass = faults.num(positive("cage.mass_kg", c.mass_kg));
        let l = &or_default(&self.lubricant, defaults::lubricant, defaults::LUBRICANT_NOTE, &mut notes);
        let eta0 = faults.num(in_range("lubricant.eta0_Pa_s", l.eta0_pa_s, 1e-5, 100.0));
        let nu40 = faults.num(in_range("lubricant.nu40_mm2_s", l.nu40_mm2_s.unwrap_or(68.0), 0.1, 1e5)) * 1e-6;
        let nu100 = faults.num(in_range("lubricant.nu100_mm2_s", l.nu100_mm2_s.unwrap_or(8.6), 0.1, 1e5)) * 1e-6;
        if nu100 >= nu40 {
            faults.push(err(
                "lubricant.nu100_mm2_s",
                "must be below nu40_mm2_s (viscosity falls with temperature)",
            ));
        }
        let oil_density = faults.num(in_range("lubricant.density_kg_m3", l.density_kg_m3.unwrap_or(870.0), 500.0, 2000.0));
        let grade = crate::tribology::OilGrade::new(nu40, nu100, oil_density);
        let oil_temperature = match l.temperature_c {
            Some(c) => faults.num(in_range("lubricant.temperature_C", c, OIL_T_MIN_C, OIL_T_MAX_C)) + 273.15,
            // where the grade has eta0 (clamped to the law's range: eta0 holds at the reference
            // temperature whatever it is, the grade then only shapes the dependence)
            None => grade.temperature_for(eta0).clamp(OIL_T_MIN_C + 273.15, OIL_T_MAX_C + 273.15),
        };
        let alpha = faults.num(in_range("lubricant.alpha_per_Pa", l.alpha_per_pa, 0.0, 1e-7));
        let roughness = faults.num(in_range("lubricant.roughness_um", l.roughness_um, 0.0, 100.0)) * UM;
        let oil_traction = {
            let d = OilTraction::default();
            let t = l.traction.clone().unwrap_or_default();
            let or = |field: &str, v: Option<f64>, lo: f64, hi: f64, scale: f64, default: f64| -> Result<f64, BearingError> {
                match v {
                    Some(v) => Ok(in_range(field, v, lo, hi)? * scale),
                    None => Ok(default),
                }
            };
            OilTraction {
                eyring_stress: faults.num(or(
                    "lubricant.traction.eyring_stress_MPa",
                    t.eyring_stress_mpa,
                    0.01,
                    100.0,
                    1e6,
                    d.eyring_stress,
                )),
                limiting_shear: faults.num(or(
                    "lubricant.traction.limiting_shear",
                    t.limiting_shear,
                    0.001,
                    0.3,
                    1.0,
                    d.limiting_shear,
                )),
                shear_modulus: faults.num(or(
                    "lubricant.traction.shear_modulus_GPa",
                    t.shear_modulus_gpa,
                    0.0,
                    100.0,
                    1e9,
                    d.shear_modulus,
                )),
                beta: faults.num(or("lubricant.traction.beta_per_K", t.beta_per_k, 0.0, 0.2, 1.0, d.beta)),
                conductivity: faults.num(or(
                    "lubricant.traction.conductivity_W_mK",
                    t.conductivity_w_mk,
                    0.01,
                    10.0,
                    1.0,
                    d.conductivity,
                )),
                piezoviscosity: t.piezoviscosity.unwrap_or(d.piezoviscosity),
            }
        };
        let f = &or_default(&self.friction, defaults::friction, defaults::FRICTION_NOTE, &mut notes);
        let mu = faults.num(in_range("friction.mu", f.mu, 0.0, 2.0));
        let flange_mu0 = faults.num(in_range("friction.flange_mu0", f.flange_mu0, 0.0, 2.0));
        let slip = faults.num(in_range("friction.cage_slip_rate", f.cage_slip_rate, 0.0, 1.0));
        let flange_roughness = match f.flange_roughness_um {
            Some(v) => faults.num(in_range("friction.flange_roughness_um", v, 0.0, 100.0)) * UM,
            None => roughness,
        };
        let rw = &self.raceway;
        let clearance = faults.num(finite("raceway.clearance_um", rw.clearance_um)) * UM;
        if clearance.abs() > 0.05 * mean_d {
            faults.push(err("raceway.clearance_um", "magnitude exceeds 5 % of the roller diameter"));
        }
        if rw.outer_lobes < 0 || rw.outer_lobes > 64 {
            faults.push(err(
                "raceway.outer_lobes",
                format!("must be an integer in [0, 64], got {}", rw.outer_lobes),
            ));
        }
        let waveform = faults.num(non_negative("raceway.outer_waveform_um", rw.outer_waveform_um)) * UM;
        if waveform > 0.05 * mean_d {
            faults.push(err("raceway.outer_waveform_um", "exceeds 5 % of the roller diameter"));
        }
        let s = &or_default(&self.solver, defaults::solver, defaults::SOLVER_NOTE, &mut notes);
        if s.slices < 2 || s.slices > 200 {
            faults.push(err(
                "solver.slices",
                format!(
                    "must be an integer in [2, 200] (one slice gives a roller no tilt stiffness), got {}",
                    s.slices
                ),
            ));
        }
        let tolerance = faults.num(in_range("solver.tolerance", s.tolerance, 1e-14, 0.1));
        let op_default = || match &g {
            Some(g) => {
                let rating = crate::rating::RatingGeometry {
                    z: g.z,
                    d_we: g.mean_d,
                    l_we: g.length,
                    d_pw: g.dm,
                    alpha: g.cup,
                };
                defaults::operating_point(crate::rating::basic_dynamic_load_rating(&rating), g.cup, g.dm / MM)
            }
            // no geometry to take P = 0.1 C_r from: the geometry's fault is reported
            None => defaults::operating_point(0.0, 0.0, 1.0),
        };
        let op = &or_default(&self.operating_point, op_default, defaults::OPERATING_POINT_NOTE, &mut notes);
        let speed = faults.num(finite("operating_point.speed_rpm", op.speed_rpm)) * PI / 30.0;
        let fx = faults.num(finite("operating_point.Fx_N", op.fx_n));
        let fy = faults.num(finite("operating_point.Fy_N", op.fy_n));
        let fz = faults.num(finite("operating_point.Fz_N", op.fz_n));
        let xi = faults.num(in_range("operating_point.xi_deg", op.xi_deg, -5.0, 5.0)).to_radians();
        let zeta = faults
            .num(in_range("operating_point.zeta_deg", op.zeta_deg, -5.0, 5.0))
            .to_radians();
        let ad = faults.num(finite("operating_point.axial_displacement_um", op.axial_displacement_um)) * UM;
        if !faults.0.is_empty() {
            return Err(faults);
        }
        let g = g.expect("no fault: the geometry is valid");
        let (roller_material, ring_material, cage_material) = (
            roller_material.expect("no fault"),
            ring_material.expect("no fault"),
            cage_material.expect("no fault"),
        );
        Ok(Bearing {
            name: self.name.clone(),
            description: self.description.clone(),
            source: self.source.clone(),
            kind: self.kind,
            bore: g.bore,
            outside_diameter: g.od,
            width: g.width,
            roller_count: g.z,
            roller_length: g.length,
            roller_mean_diameter: g.mean_d,
            roller_half_angle: g.half,
            roller_end_radius: g.end_radius,
            pitch_diameter: g.dm,
            cone_angle: g.cone,
            cup_angle: g.cup,
            flange_angle: g.flange_angle,
            roller_material,
            ring_material,
            cage_material,
            contact_law,
            pocket_clearance: pocket,
            guide_clearance: guide,
            land_width,
            land_radius,
            cage_mass,
            eta0,
            oil_nu40: nu40,
            oil_nu100: nu100,
            oil_density,
            oil_temperature,
            alpha,
            roughness,
            oil_traction,
            flange_roughness,
            lubrication: f.model,
            mu,
            flange_mu0,
            cage_slip_rate: slip,
            crown_drop: g.crown,
            clearance,
            outer_lobes: rw.outer_lobes as u32,
            outer_waveform: waveform,
            slices: s.slices as usize,
            tolerance,
            speed,
            fx,
            fy,
            fz,
            xi,
            zeta,
            axial_displacement: ad,
            displacement_preload: op.preload == PreloadFile::Displacement,
            documented_defaults: notes,
        })
    }

    /// The internal geometry of a file that gives it, validated (SI).
    fn geometry(&self) -> Result<InternalGeometry, BearingError> {
        let envelope = need(&self.envelope, "envelope")?;
        let rollers = need(&self.rollers, "rollers")?;
        let pitch_diameter_mm = *need(&self.pitch_diameter_mm, "pitch_diameter_mm")?;
        let cone_angle_deg = *need(&self.cone_angle_deg, "cone_angle_deg")?;
        let cup_angle_deg = *need(&self.cup_angle_deg, "cup_angle_deg")?;
        let bore = positive("envelope.bore_mm", envelope.bore_mm)? * MM;
        let od = positive("envelope.outside_diameter_mm", envelope.outside_diameter_mm)? * MM;
        let width = positive("envelope.width_mm", envelope.width_mm)? * MM;
        if od <= bore {
            return Err(err("envelope.outside_diameter_mm", "must exceed the bore"));
        }
        let z = rollers.count;
        if z < 3 || z as usize > crate::variables::MAX_ROLLERS {
            return Err(err(
                "rollers.count",
                format!("must be an integer in [3, {}], got {z}", crate::variables::MAX_ROLLERS),
            ));
        }
        let z = z as usize;
        let length = positive("rollers.length_mm", rollers.length_mm)? * MM;
        let cone = in_range("cone_angle_deg", cone_angle_deg, 0.0, 45.0)?.to_radians();
        let cup = in_range("cup_angle_deg", cup_angle_deg, 0.0, 60.0)?.to_radians();
        if cup < cone {
            return Err(err("cup_angle_deg", "must not be smaller than cone_angle_deg"));
        }
        let half_from_angles = 0.5 * (cup - cone);
        let half = match rollers.half_cone_angle_deg {
            Some(h) => {
                let h = in_range("rollers.half_cone_angle_deg", h, 0.0, 20.0)?.to_radians();
                if (h - half_from_angles).abs() > 0.02_f64.to_radians() {
                    return Err(err(
                        "rollers.half_cone_angle_deg",
                        format!(
                            "{:.4} deg disagrees with (cup_angle_deg - cone_angle_deg)/2 = {:.4} deg",
                            h.to_degrees(),
                            half_from_angles.to_degrees()
                        ),
                    ));
                }
                h
            }
            None => half_from_angles,
        };
        match self.kind {
            Kind::Cylindrical => {
                if cone != 0.0 || cup != 0.0 {
                    return Err(err("cone_angle_deg", "a cylindrical bearing has zero raceway angles"));
                }
                if self.flange.is_some() {
                    return Err(err(
                        "flange",
                        "a cylindrical roller bearing carries no flange load here; remove the field",
                    ));
                }
            }
            Kind::Tapered => {
                if cup <= 0.0 {
                    return Err(err("cup_angle_deg", "a tapered bearing needs a cup angle > 0"));
                }
            }
        }
        // Roller diameters: mean, or large end, or both ends.
        let tan_h = libm::tan(half);
        let r = rollers;
        let mean_d = match (r.mean_diameter_mm, r.large_end_diameter_mm, r.small_end_diameter_mm) {
            (Some(m), None, None) => positive("rollers.mean_diameter_mm", m)? * MM,
            (None, Some(l), None) => positive("rollers.large_end_diameter_mm", l)? * MM - length * tan_h,
            (None, None, Some(s)) => positive("rollers.small_end_diameter_mm", s)? * MM + length * tan_h,
            (None, Some(l), Some(s)) => {
                let l = positive("rollers.large_end_diameter_mm", l)? * MM;
                let s = positive("rollers.small_end_diameter_mm", s)? * MM;
                if s > l {
                    return Err(err("rollers.small_end_diameter_mm", "exceeds the large-end diameter"));
                }
                let implied = libm::atan((l - s) / (2.0 * length));
                if (implied - half).abs() > 0.05_f64.to_radians() {
                    return Err(err(
                        "rollers.small_end_diameter_mm",
                        format!(
                            "end diameters imply a half-cone angle of {:.4} deg, the raceways {:.4} deg",
                            implied.to_degrees(),
                            half.to_degrees()
                        ),
                    ));
                }
                0.5 * (l + s)
            }
            _ => {
                return Err(err(
                    "rollers.mean_diameter_mm",
                    "give exactly one of mean_diameter_mm, large_end_diameter_mm, or both end diameters",
                ))
            }
        };
        if mean_d <= 0.0 || length * tan_h >= mean_d {
            return Err(err("rollers.length_mm", "roller would have a non-positive small-end diameter"));
        }
        let dm = positive("pitch_diameter_mm", pitch_diameter_mm)? * MM;
        if dm <= bore || dm >= od {
            return Err(err(
                "pitch_diameter_mm",
                format!("{:.3} mm must lie between the bore and the outside diameter", dm / MM),
            ));
        }
        let axis = cone + half;
        // The roller must fit axially inside the bearing width (a cylindrical roller of any
        // length passes the radial check below; 1e308 mm gave non-finite outputs).
        let axial_extent = length * libm::cos(axis) + mean_d * libm::sin(axis);
        if axial_extent > width {
            return Err(err(
                "rollers.length_mm",
                format!(
                    "a roller of length {:.3} mm and diameter {:.3} mm spans {:.3} mm axially, more than the bearing width {:.3} mm",
                    length / MM,
                    mean_d / MM,
                    axial_extent / MM,
                    width / MM
                ),
            ));
        }
        // The roller must fit radially inside the envelope and the rollers on the pitch circle.
        let radial_extent = 0.5 * mean_d * libm::cos(axis) + 0.5 * length * libm::sin(axis);
        if 0.5 * dm - radial_extent <= 0.5 * bore || 0.5 * dm + radial_extent >= 0.5 * od {
            return Err(err(
                "rollers.mean_diameter_mm",
                format!(
                    "a roller of diameter {:.3} mm and length {:.3} mm on pitch diameter {:.3} mm does not fit between bore {:.3} mm and outside diameter {:.3} mm",
                    mean_d / MM,
                    length / MM,
                    dm / MM,
                    bore / MM,
                    od / MM
                ),
            ));
        }
        if PI * dm / (z as f64) <= mean_d {
            return Err(err(
                "rollers.count",
                format!(
                    "{z} rollers of mean diameter {:.3} mm do not fit on a pitch circle of {:.3} mm",
                    mean_d / MM,
                    dm / MM
                ),
            ));
        }
        // Flange
        let flange_angle = match (&self.flange, self.kind) {
            (None, Kind::Tapered) => return Err(err("flange", "a tapered roller bearing needs its flange (rib) geometry")),
            (None, Kind::Cylindrical) => None,
            (Some(f), _) => {
                let given = [
                    f.contact_angle_deg.is_some(),
                    f.opening_angle_deg.is_some(),
                    f.face_to_roller_axis_rad.is_some(),
                ];
                if given.iter().filter(|g| **g).count() != 1 {
                    return Err(err(
                        "flange",
                        "give exactly one of contact_angle_deg, opening_angle_deg, face_to_roller_axis_rad",
                    ));
                }
                let a = if let Some(a) = f.contact_angle_deg {
                    in_range("flange.contact_angle_deg", a, 45.0, 90.0)?.to_radians()
                } else if let Some(o) = f.opening_angle_deg {
                    (90.0 - in_range("flange.opening_angle_deg", o, 0.0, 45.0)?).to_radians()
                } else {
                    let x = in_range("flange.face_to_roller_axis_rad", f.face_to_roller_axis_rad.unwrap(), 1.0, PI / 2.0)?;
                    PI / 2.0 - axis + (PI / 2.0 - x)
                };
                Some(a)
            }
        };
        let large_r = 0.5 * mean_d + 0.5 * length * tan_h;
        // Distance of the flange contact from the bearing axis for end radius rs (the rib
        // normal n_f = (sin af, -cos af), sphere centre on the roller axis at rs from the end):
        // r_f = dm/2 + (l/2) sin(axis) + rs (cos af - sin(axis)).
        let rib_radius = |af: f64, rs: f64| 0.5 * dm + 0.5 * length * libm::sin(axis) + rs * (libm::cos(af) - libm::sin(axis));
        if r.end_radius_mm.is_some() && r.end_radius_ratio.is_some() {
            return Err(err(
                "rollers.end_radius_ratio",
                "give at most one of end_radius_mm and end_radius_ratio",
            ));
        }
        let ratio = match r.end_radius_ratio {
            Some(k) => {
                let k = in_range("rollers.end_radius_ratio", k, 0.0, MAX_END_RADIUS_RATIO)?;
                if k <= 0.0 {
                    return Err(err("rollers.end_radius_ratio", "must be positive"));
                }
                k
            }
            None => DEFAULT_END_RADIUS_RATIO,
        };
        let end_radius = match (flange_angle, r.end_radius_mm) {
            (None, _) => 0.0,
            (Some(_), Some(rs)) => positive("rollers.end_radius_mm", rs)? * MM,
            (Some(af), None) => {
                // R_s = k rho_p with rho_p = r_f / cos(af) the rib's circumferential radius
                // of curvature (k given, or `DEFAULT_END_RADIUS_RATIO`). r_f is linear in R_s,
                // so R_s = k r_f(R_s) / cos(af) is solved directly.
                let c = ratio / libm::cos(af);
                let r0 = rib_radius(af, 0.0);
                let slope = libm::cos(af) - libm::sin(axis);
                let rs = c * r0 / (1.0 - c * slope);
                if !(rs.is_finite() && rs > 0.0) {
                    return Err(err(
                        "rollers.end_radius_ratio",
                        format!("{ratio} gives no end radius on this rib (R_s = {rs:e} m)"),
                    ));
                }
                rs
            }
        };
        if let Some(af) = flange_angle {
            let rho_p = rib_radius(af, end_radius) / libm::cos(af);
            if end_radius > MAX_END_RADIUS_RATIO * rho_p {
                return Err(err(
                    "rollers.end_radius_mm",
                    format!(
                        "roller end radius {:.3} mm exceeds the rib's radius of curvature {:.3} mm: the end would touch the rib at its edges",
                        end_radius / MM,
                        rho_p / MM
                    ),
                ));
            }
        }
        if let Some(af) = flange_angle {
            // The flange contact point must lie on the roller end face, on the cone side.
            let offset = af - (PI / 2.0 - axis);
            let h = end_radius * libm::sin(offset);
            if offset <= 0.0 || h >= large_r {
                return Err(err(
                    "flange",
                    format!(
                        "flange contact at {:.3} mm from the roller axis falls outside the roller end face (0 .. {:.3} mm on the cone side); check the flange angle and rollers.end_radius_mm",
                        h / MM,
                        large_r / MM
                    ),
                ));
            }
        }
        let crown = non_negative("rollers.crown_drop_um", r.crown_drop_um)? * UM;
        if crown > 0.05 * mean_d {
            return Err(err("rollers.crown_drop_um", "is larger than 5 % of the roller diameter"));
        }
        Ok(InternalGeometry {
            bore,
            od,
            width,
            z,
            length,
            mean_d,
            half,
            end_radius,
            dm,
            cone,
            cup,
            flange_angle,
            crown,
        })
    }
}

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
            include_str!("../presets/bearing.schema.json"),
            bearing_file_schema(),
            "presets/bearing.schema.json is stale: cargo run -- bearing schema --out presets/bearing.schema.json"
        );
    }

    #[test]
    fn all_presets_load() {
        for (name, _) in PRESETS {
            let b = Bearing::preset(name).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(&b.name, name);
        }
    }

    #[test]
    fn trb130_values_are_the_published_ones_in_si() {
        let b = Bearing::preset("TRB130x230-W25").unwrap();
        assert_eq!(b.roller_count, 17);
        assert!((b.roller_length - 42.06e-3).abs() < 1e-12);
        assert!((b.roller_mean_diameter - 21.37e-3).abs() < 1e-12);
        assert!((b.pitch_diameter - 177.91e-3).abs() < 1e-12);
        assert!((b.cup_angle.to_degrees() - 15.0).abs() < 1e-12);
        assert!((b.cone_angle.to_degrees() - 5.0).abs() < 1e-12);
        assert!((b.flange_angle.unwrap().to_degrees() - 83.0).abs() < 1e-12);
        assert!((b.roller_end_radius - 153.95e-3).abs() < 1e-12);
        assert!((b.roller_material.e - 201e9).abs() < 1.0);
        assert!((b.speed - 3500.0 * PI / 30.0).abs() < 1e-12);
        assert_eq!(b.fx, 30_000.0);
    }

    #[test]
    fn published_roller_angles_are_consistent() {
        let b = Bearing::preset("32008").unwrap();
        assert!((b.roller_half_angle - 0.0262).abs() < 2e-4);
        let b = Bearing::preset("32018X").unwrap();
        assert!((b.roller_axis_angle().to_degrees() - 14.25).abs() < 1e-9);
    }

    fn default_json() -> serde_json::Value {
        serde_json::from_str(PRESETS[0].1).unwrap()
    }

    fn error_of(v: serde_json::Value) -> BearingError {
        Bearing::from_json(&v.to_string()).expect_err("must be rejected")
    }

    fn preset_text(name: &str) -> &'static str {
        PRESETS.iter().find(|(n, _)| *n == name).expect("a preset").1
    }

    /// R_s / rho_p of a loaded bearing, rho_p = r_f / cos(a_f) from the geometry's rib contact.
    fn end_radius_over_rib(b: &Bearing) -> f64 {
        let g = crate::geometry::Geometry::new(b, &crate::model::Parameters::from_bearing(b));
        let f = g.flange.as_ref().expect("a rib");
        b.roller_end_radius / (f.rib_radius / libm::cos(b.flange_angle.unwrap()))
    }

    #[test]
    fn the_end_radius_follows_its_ratio_to_the_rib() {
        // 32008 gives neither: the default ratio
        let b = Bearing::preset("32008").unwrap();
        assert!((end_radius_over_rib(&b) - DEFAULT_END_RADIUS_RATIO).abs() < 1e-12);
        let mut v: serde_json::Value = serde_json::from_str(preset_text("32008")).unwrap();
        let mut last = 0.0;
        for k in [0.75, 0.85, 0.9, 0.95] {
            v["rollers"]["end_radius_ratio"] = serde_json::json!(k);
            let b = Bearing::from_json(&v.to_string()).unwrap();
            assert!((end_radius_over_rib(&b) - k).abs() < 1e-12, "{k}");
            assert!(b.roller_end_radius > last);
            last = b.roller_end_radius;
            if k == 0.9 {
                let d = Bearing::preset("32008").unwrap();
                assert_eq!(b.roller_end_radius.to_bits(), d.roller_end_radius.to_bits());
            }
        }
    }

    #[test]
    fn the_end_radius_is_given_once_and_in_range() {
        let mut v: serde_json::Value = serde_json::from_str(preset_text("32008")).unwrap();
        v["rollers"]["end_radius_ratio"] = serde_json::json!(0.8);
        v["rollers"]["end_radius_mm"] = serde_json::json!(100.0);
        let e = error_of(v.clone());
        assert_eq!(e.field, "rollers.end_radius_ratio", "{e}");
        assert!(e.to_string().contains("at most one"), "{e}");
        v["rollers"].as_object_mut().unwrap().remove("end_radius_mm");
        for bad in [0.0, -0.5, 1.2] {
            v["rollers"]["end_radius_ratio"] = serde_json::json!(bad);
            let e = error_of(v.clone());
            assert_eq!(e.field, "rollers.end_radius_ratio", "{bad}: {e}");
        }
    }

    #[test]
    fn missing_field_is_named() {
        let mut v = default_json();
        v["rollers"].as_object_mut().unwrap().remove("length_mm");
        let e = error_of(v);
        assert!(e.to_string().contains("length_mm"), "{e}");
    }

    #[test]
    fn wrong_type_is_named() {
        let mut v = default_json();
        v["rollers"]["count"] = serde_json::json!("seventeen");
        let e = error_of(v);
        assert_eq!(e.field, "rollers.count", "{e}");
    }

    #[test]
    fn invalid_values_are_named() {
        for (path, value) in [
            (vec!["rollers", "count"], serde_json::json!(0)),
            (vec!["rollers", "length_mm"], serde_json::json!(-3.0)),
            (vec!["pitch_diameter_mm"], serde_json::json!(1000.0)),
            (vec!["rollers", "mean_diameter_mm"], serde_json::json!(90.0)),
            (vec!["materials", "roller", "nu"], serde_json::json!(0.7)),
            (vec!["solver", "slices"], serde_json::json!(0)),
            (vec!["lubricant", "eta0_Pa_s"], serde_json::json!(-1.0)),
        ] {
            let mut v = default_json();
            let mut cur = &mut v;
            for p in &path[..path.len() - 1] {
                cur = &mut cur[*p];
            }
            cur[*path.last().unwrap()] = value;
            let e = error_of(v);
            let want = path.join(".");
            assert!(e.field.starts_with(&want) || e.to_string().contains(&want), "{want}: {e}");
        }
    }

    /// One run names every fault of a file, section by section (the geometry's first).
    #[test]
    fn every_fault_of_a_file_is_named_at_once() {
        let mut v = default_json();
        v["rollers"]["count"] = serde_json::json!(1);
        v["lubricant"]["eta0_Pa_s"] = serde_json::json!(-1.0);
        v["lubricant"]["alpha_per_Pa"] = serde_json::json!(1.0);
        v["friction"]["mu"] = serde_json::json!(5.0);
        v["solver"]["slices"] = serde_json::json!(1);
        v["cage"]["mass_kg"] = serde_json::json!(0.0);
        v["operating_point"]["xi_deg"] = serde_json::json!(9.0);
        let e = error_of(v);
        assert_eq!(e.field, "rollers.count", "{e}");
        for field in [
            "rollers.count",
            "lubricant.eta0_Pa_s",
            "lubricant.alpha_per_Pa",
            "friction.mu",
            "solver.slices",
            "cage.mass_kg",
            "operating_point.xi_deg",
        ] {
            assert!(e.to_string().contains(&format!("`{field}`")), "{field} not named: {e}");
        }
    }

    /// Faults of the file's structure too: unknown fields and values of the wrong type in
    /// several sections, with a value fault elsewhere, all in one message.
    #[test]
    fn structural_faults_are_named_at_once() {
        let mut v = default_json();
        v["lubricant"]["colour"] = serde_json::json!("amber");
        v["lubricant"]["eta0_Pa_s"] = serde_json::json!("thick");
        v["solver"]["method"] = serde_json::json!("newton");
        v["rollers"]["count"] = serde_json::json!("seventeen");
        v["friction"]["mu"] = serde_json::json!(5.0);
        let e = error_of(v);
        for field in [
            "lubricant.colour",
            "lubricant.eta0_Pa_s",
            "solver.method",
            "rollers.count",
            "friction.mu",
        ] {
            assert!(e.to_string().contains(&format!("`{field}`")), "{field} not named: {e}");
        }
        // the sections taken out for their faults are not reported missing
        assert!(!e.to_string().contains("missing field `rollers`"), "{e}");
    }

    #[test]
    fn unknown_field_and_bad_json_are_rejected() {
        let mut v = default_json();
        v["rollers"]["lenght_mm"] = serde_json::json!(3.0);
        let e = error_of(v);
        assert!(e.to_string().contains("lenght_mm"), "{e}");
        assert!(Bearing::from_json("{ not json").is_err());
        assert!(Bearing::from_json("").is_err());
        assert!(Bearing::from_name_or_file("/no/such/file.json").is_err());
    }
}
