//! The internal geometry of a single-row tapered roller bearing estimated from its catalogue
//! data alone: envelope d × D × T (and the ring widths B and C), the basic dynamic load rating
//! C_r and the calculation factor e (and Y, C_0r, the roller count Z when known), in the
//! catalogues' own symbols, mm and N.
//!
//! The method (docs/model.md, "A bearing from its catalogue data"), rule by rule:
//! 1. Contact angle. ISO 281:2007 (clause 7.2, single-row radial roller bearings) defines
//!    e = 1.5 tan α: α = atan(e / 1.5), the cup angle, exactly. Y = 0.4 cot α is the same
//!    relation; a catalogue Y that disagrees with e by more than 10 % is refused.
//! 2. Pitch diameter D_pw = (d + D) / 2, the bearing's mean diameter d_m of ISO 15312 (thermal
//!    speed rating) and of the SKF frictional-moment model, used where the maker does not
//!    give D_pw.
//! 3. Roller mean diameter D_we = 0.235 (D − d), i.e. 0.47 of the radial section height
//!    H = (D − d)/2: the section holds the cup wall, the roller and the cone wall under it, and
//!    each wall keeps about a quarter of the section (case depth and fit stiffness; a thinner
//!    ring follows its housing's ovality). Published bearings lie at 0.23–0.25 (32008 of
//!    [L22]: 0.232, 32018 X of [D19]: 0.245).
//! 4. Roller count Z: as many rollers as fit on the pitch circle with a cage bar between
//!    neighbours at least 0.13 D_we wide, Z = ⌊π D_pw / (1.13 D_we)⌋ (fill factor
//!    Z D_we / (π D_pw) ≤ 0.885). A pressed-steel window cage's bar carries the roller's
//!    pull-out and the cage's own hoop load; it is about as wide as the sheet is thick, which is
//!    0.1–0.15 D_we. A catalogue Z, when given, is taken, and D_we shrinks if the rollers would
//!    not leave that bar.
//! 5. Roller effective length L_we: ISO 281's rating solved for it,
//!    C_r = b_m f_c (L_we cos α)^(7/9) Z^(3/4) D_we^(29/27), so that the geometry's C_r is the
//!    catalogue's (to rounding). A length whose roller does not fit the bearing width T, or
//!    reaches beyond the ring section, refuses C_r: no roller set of this envelope reaches it;
//!    so does a length under 0.8 D_we (a C_r below what the envelope's rollers carry), and an
//!    envelope with no room for a roller that long refuses T.
//! 6. One apex (the rollers roll without sliding along the line): the roller's half-cone angle
//!    a_h from tan a_h = (D_we / 2) sin a_r / (D_pw / 2) with the roller axis angle
//!    a_r = α − a_h, and the cone angle a_r − a_h.
//! 7. Roller end sphere radius R_s = 0.9 of the roller's apex distance (D_pw / 2) / sin a_r
//!    (the spherical end a little flatter than the apex sphere, so the rib contact stays on
//!    the end face). With the rib of rule 8 this gives R_s / rho_p ≈ 0.84 against the rib's
//!    circumferential radius of curvature rho_p (30206, 4T-32008X, 4T-32010X of
//!    `examples/bearings/`), at the low-friction end of the 0.85–0.95 rho_p that "Effects of
//!    Roller End/Rib Curvature Ratio on Friction and Accuracy in Tapered Roller Bearings"
//!    (Machines 13 (2025) 910, doi:10.3390/machines13100910) compares. Makers do not publish
//!    their ratio: the 0.9 is an engineering assumption, and the ratio sets the roller's skew
//!    (docs/dynamic.md, "The roller skew mode"): in the written file, `rollers.end_radius_ratio`
//!    in place of `rollers.end_radius_mm` sets another.
//! 8. Rib contact: at 0.6 of the large-end radius below the roller axis, i.e. 0.4 of that
//!    radius above the cone raceway: clear of the raceway's relief groove and of the end
//!    face's chamfer, low enough that the rib stays under half the roller diameter tall. The
//!    rib contact angle (normal to the radial plane) follows from R_s and that height.
//! 9. Crown: a circular crown whose drop at the roller ends is the contact approach at the
//!    cone (Palmgren's law of ISO/TS 16281, δ = (Q / (35948 L^(8/9)))^0.9 in N and mm) under the
//!    roller load that gives a Hertz pressure of 1000 MPa there, the pressure of a bearing at
//!    P ≈ 0.1–0.2 C_r, where rating-life designs sit: up to that load the contact spans the
//!    whole roller, above it the crown keeps the edge stress off the roller ends. (A maker's
//!    logarithmic profile is flat in the middle; the model's circular crown with a larger drop
//!    would shorten the contact at service loads.)
//! 10. Cage (pressed steel window cage): sheet thickness 0.1 D_we, rims 0.3 D_we wide on both
//!     sides of the windows, windows 0.95 of the roller's projected area; its mass from that
//!     sheet. Pocket clearance 0.04 D_we; guide clearance 0.005 D_pw; the guiding land at
//!     D_pw / 2 + 0.45 D_we, 0.22 L_we wide.
//!
//! Everything else a catalogue does not give is the documented default of [`defaults`].

// The catalogue data is a section of the bearing file (`super::file`), read with its types.
pub use super::file::Catalogue;
use super::file::{
    BearingFile, CageFile, ContactLaw, EnvelopeFile, FlangeFile, FrictionFile, Kind, LubricantFile, LubricationModel, MaterialFile,
    MaterialsFile, OperatingPointFile, PreloadFile, RacewayFile, RollersFile, SolverFile,
};
use super::rating::{basic_dynamic_load_rating, basic_static_load_rating, roller_length_for_rating, RatingGeometry};
use std::fmt;

/// Roller mean diameter over the ring section D − d (rule 3).
pub const ROLLER_DIAMETER_OVER_SECTION: f64 = 0.235;
/// Smallest cage bar width at the pitch circle over the roller diameter (rule 4).
pub const CAGE_BAR_OVER_ROLLER: f64 = 0.13;
/// Shortest roller the estimate makes, over its diameter (rule 5): a tapered roller shorter
/// than about its diameter tips in its pocket and skews freely; catalogue bearings' rollers
/// are 1.2–2.5 diameters long ([L22]'s 32008: 2.1, [D19]'s 32018 X: 1.7).
pub const MIN_LENGTH_OVER_DIAMETER: f64 = 0.8;
/// Roller end sphere radius over the roller's apex distance (rule 7: an engineering
/// assumption, R_s / rho_p ≈ 0.84 with rule 8's rib).
pub const END_RADIUS_OVER_APEX: f64 = 0.9;
/// Rib contact depth below the roller axis over the large-end radius (rule 8).
pub const RIB_CONTACT_DEPTH: f64 = 0.6;
/// Hertz pressure the crown is laid out for, Pa (rule 9).
pub const CROWN_DESIGN_PRESSURE: f64 = 1000e6;
/// The range of e the method takes: contact angles of 7.6–33.7 deg, the ISO 355 angle
/// series 2 to 7 (e = 0.2 .. 1.0 spans them with margin).
pub const E_RANGE: (f64, f64) = (0.2, 1.0);

/// One fault of catalogue data: the field by its catalogue symbol and what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct CatalogueError {
    pub field: &'static str,
    pub message: String,
}

impl CatalogueError {
    /// The field's key in a bearing file's `catalogue` block.
    pub fn file_key(&self) -> &'static str {
        match self.field {
            "d" => "d_mm",
            "D" => "D_mm",
            "T" => "T_mm",
            "B" => "B_mm",
            "C" => "C_mm",
            "Cr" => "Cr_N",
            "C0r" => "C0r_N",
            other => other,
        }
    }
}

impl fmt::Display for CatalogueError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.field, self.message)
    }
}

/// All faults of one set of catalogue data.
#[derive(Debug, Clone, PartialEq)]
pub struct CatalogueErrors(pub Vec<CatalogueError>);

impl fmt::Display for CatalogueErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let lines: Vec<String> = self.0.iter().map(|e| e.to_string()).collect();
        write!(f, "{}", lines.join("; "))
    }
}

impl std::error::Error for CatalogueErrors {}

/// The estimated internal geometry (mm, deg, kg, N as the names say).
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    pub z: usize,
    pub roller_mean_diameter_mm: f64,
    pub roller_length_mm: f64,
    pub pitch_diameter_mm: f64,
    pub cup_angle_deg: f64,
    pub cone_angle_deg: f64,
    pub half_cone_angle_deg: f64,
    pub end_radius_mm: f64,
    pub flange_contact_angle_deg: f64,
    /// Height of the rib contact above the cone raceway at the roller's large end.
    pub rib_contact_height_mm: f64,
    pub crown_drop_um: f64,
    /// Z D_we / (π D_pw).
    pub fill_factor: f64,
    /// Cage bar width at the pitch circle, π D_pw / Z − D_we.
    pub cage_bar_mm: f64,
    pub cage: CageFile,
    /// The roller's axial extent, L_we cos a_r + D_we sin a_r.
    pub roller_axial_extent_mm: f64,
    /// ISO 281 C_r and ISO 76 C_0r of the estimated geometry.
    pub c_r_geometry: f64,
    pub c_0r_geometry: f64,
}

const DEG: f64 = std::f64::consts::PI / 180.0;
const STEEL_E_GPA: f64 = 208.0;
const STEEL_NU: f64 = 0.3;
const STEEL_DENSITY: f64 = 7850.0;

fn check_positive(errors: &mut Vec<CatalogueError>, field: &'static str, v: f64) -> bool {
    if v.is_finite() && v > 0.0 {
        true
    } else {
        errors.push(CatalogueError {
            field,
            message: format!("must be a finite number > 0, got {v}"),
        });
        false
    }
}

/// A cone wider than the total width stands proud of the cup's back face: inch series do
/// so by a few per cent (the Timken LM501349 cone, B = 19.812 mm, on T = 19.558 mm), so the
/// cone is refused only beyond this share of T, where the figure is a typing error rather than
/// a bearing (a cone half as wide again as the assembly would stand clear of its cup's race).
const CONE_OVER_TOTAL_WIDTH: f64 = 1.5;

/// What is wrong with the ring width `v` of the ring `field` ("B" the cone, "C" the cup) on
/// the total width `t`: the cup lies inside the assembled width, the cone may stand proud of
/// it (`CONE_OVER_TOTAL_WIDTH`).
fn ring_width_fault(field: &str, v: f64, t: f64) -> Option<String> {
    match field {
        "C" if v > t => Some(format!("the total width T = {t} mm is below the cup width C = {v} mm")),
        "B" if v > CONE_OVER_TOTAL_WIDTH * t => Some(format!(
            "the cone width B = {v} mm is more than {CONE_OVER_TOTAL_WIDTH} times the total width T = {t} mm"
        )),
        _ => None,
    }
}

impl Catalogue {
    /// Every fault of the data at once (empty: the data can be estimated from).
    pub fn faults(&self) -> Vec<CatalogueError> {
        let mut errors = Vec::new();
        let ok_d = check_positive(&mut errors, "d", self.d);
        let ok_outside = check_positive(&mut errors, "D", self.outside_d);
        let ok_t = check_positive(&mut errors, "T", self.t);
        check_positive(&mut errors, "Cr", self.c_r);
        let ok_e = self.e.is_finite();
        if !ok_e || self.e < E_RANGE.0 || self.e > E_RANGE.1 {
            errors.push(CatalogueError {
                field: "e",
                message: format!(
                    "must lie in [{}, {}] (contact angles of 7.6 to 33.7 deg), got {}",
                    E_RANGE.0, E_RANGE.1, self.e
                ),
            });
        }
        for (field, v) in [("B", self.b), ("C", self.c), ("Y", self.y), ("C0r", self.c_0r)] {
            if let Some(v) = v {
                if check_positive(&mut errors, field, v) && ok_t {
                    if let Some(message) = ring_width_fault(field, v, self.t) {
                        errors.push(CatalogueError { field: "T", message });
                    }
                }
            }
        }
        if ok_d && ok_outside && self.outside_d <= self.d {
            errors.push(CatalogueError {
                field: "D",
                message: format!("the outside diameter {} mm must exceed the bore d = {} mm", self.outside_d, self.d),
            });
        }
        if let (Some(y), true) = (self.y, ok_e && self.e >= E_RANGE.0 && self.e <= E_RANGE.1) {
            // Y = 0.4 cot α = 0.6 / e for the same α
            let y_of_e = 0.6 / self.e;
            if y.is_finite() && y > 0.0 && (y / y_of_e - 1.0).abs() > 0.10 {
                errors.push(CatalogueError {
                    field: "Y",
                    message: format!(
                        "Y = {y} disagrees with e = {}: a single-row bearing has Y = 0.4 cot a = 0.6 / e = {y_of_e:.3}",
                        self.e
                    ),
                });
            }
        }
        if let Some(z) = self.z {
            if z < 3 || z as usize > crate::variables::MAX_ROLLERS {
                errors.push(CatalogueError {
                    field: "Z",
                    message: format!("must be an integer in [3, {}], got {z}", crate::variables::MAX_ROLLERS),
                });
            }
        }
        errors
    }

    /// The estimated internal geometry, or every fault of the data.
    pub fn estimate(&self) -> Result<Estimate, CatalogueErrors> {
        let faults = self.faults();
        if !faults.is_empty() {
            return Err(CatalogueErrors(faults));
        }
        let alpha = libm::atan(self.e / 1.5);
        let dpw = 0.5 * (self.d + self.outside_d);
        let section = self.outside_d - self.d;
        // rules 3 and 4: roller diameter, then as many rollers as leave the cage bar
        let mut dw = ROLLER_DIAMETER_OVER_SECTION * section;
        let pitch_per_roller = |z: usize| std::f64::consts::PI * dpw / z as f64;
        let z = match self.z {
            Some(z) => {
                let z = z as usize;
                dw = dw.min(pitch_per_roller(z) / (1.0 + CAGE_BAR_OVER_ROLLER));
                z
            }
            None => (pitch_per_roller(1) / ((1.0 + CAGE_BAR_OVER_ROLLER) * dw)).floor() as usize,
        };
        if z < 3 {
            return Err(CatalogueErrors(vec![CatalogueError {
                field: "D",
                message: "the ring section leaves room for fewer than 3 rollers".into(),
            }]));
        }
        // rule 5: ISO 281's C_r solved for the effective length
        let rating_geometry = |l: f64| RatingGeometry {
            z,
            d_we: dw * 1e-3,
            l_we: l.max(0.0) * 1e-3,
            d_pw: dpw * 1e-3,
            alpha,
        };
        let rating_at = |l: f64| basic_dynamic_load_rating(&rating_geometry(l));
        let length = roller_length_for_rating(self.c_r, &rating_geometry(0.0)) * 1e3;
        // rule 6: one apex
        let mut half = 0.0;
        for _ in 0..60 {
            half = libm::atan(0.5 * dw * libm::sin(alpha - half) / (0.5 * dpw));
        }
        let axis = alpha - half;
        let extent = length * libm::cos(axis) + dw * libm::sin(axis);
        // The roller must fit the envelope: axially the width T, radially the ring section
        // about the pitch circle (the reader's checks, `read.rs`), with 0.1 % to spare.
        let l_max_axial = (self.t - dw * libm::sin(axis)) / libm::cos(axis);
        let l_max_radial = 2.0 * (0.999 * 0.25 * section - 0.5 * dw * libm::cos(axis)) / libm::sin(axis);
        let l_max = l_max_axial.min(l_max_radial);
        let l_min = MIN_LENGTH_OVER_DIAMETER * dw;
        if l_max < l_min {
            return Err(CatalogueErrors(vec![CatalogueError {
                field: "T",
                message: format!(
                    "a {} x {} x {} mm envelope leaves rollers of {dw:.2} mm diameter at most {:.2} mm of length, less than {MIN_LENGTH_OVER_DIAMETER} of their diameter: the width or the section does not make a tapered roller bearing",
                    self.d, self.outside_d, self.t, l_max.max(0.0)
                ),
            }]));
        }
        if length < l_min {
            return Err(CatalogueErrors(vec![CatalogueError {
                field: "Cr",
                message: format!(
                    "C_r = {} N would make {z} rollers of {dw:.2} mm diameter only {length:.2} mm long, less than {MIN_LENGTH_OVER_DIAMETER} of their diameter; a roller set of this envelope carries at least about {:.0} N",
                    self.c_r,
                    rating_at(l_min)
                ),
            }]));
        }
        if length > l_max {
            let reachable = rating_at(l_max);
            let limit = if l_max_axial <= l_max_radial {
                format!("spanning {extent:.2} mm of the {} mm width", self.t)
            } else {
                format!(
                    "reaching {:.2} mm from the pitch circle in a section of {:.2} mm each side",
                    0.5 * dw * libm::cos(axis) + 0.5 * length * libm::sin(axis),
                    0.25 * section
                )
            };
            return Err(CatalogueErrors(vec![CatalogueError {
                field: "Cr",
                message: format!(
                    "no roller set in a {} x {} x {} mm envelope reaches C_r = {} N: {z} rollers of {dw:.2} mm would need to be {length:.2} mm long, {limit} (about {reachable:.0} N at most)",
                    self.d, self.outside_d, self.t, self.c_r
                ),
            }]));
        }
        // rules 7 and 8: end sphere and rib contact
        let apex_distance = 0.5 * dpw / libm::sin(axis);
        let end_radius = END_RADIUS_OVER_APEX * apex_distance;
        let large_end_radius = 0.5 * dw + 0.5 * length * libm::tan(half);
        let depth = RIB_CONTACT_DEPTH * large_end_radius;
        let flange = 90.0 * DEG - axis + libm::asin(depth / end_radius);
        // rule 9: the crown
        let crown_um = crown_drop_mm(dw, length, dpw, alpha - 2.0 * half, half) * 1e3;
        // rule 10: the cage
        let cage = cage(z, dw, length, dpw);
        let geometry = rating_geometry(length);
        Ok(Estimate {
            z,
            roller_mean_diameter_mm: dw,
            roller_length_mm: length,
            pitch_diameter_mm: dpw,
            cup_angle_deg: alpha / DEG,
            cone_angle_deg: (axis - half) / DEG,
            half_cone_angle_deg: half / DEG,
            end_radius_mm: end_radius,
            flange_contact_angle_deg: flange / DEG,
            rib_contact_height_mm: large_end_radius - depth,
            crown_drop_um: crown_um,
            fill_factor: z as f64 * dw / (std::f64::consts::PI * dpw),
            cage_bar_mm: pitch_per_roller(z) - dw,
            cage,
            roller_axial_extent_mm: extent,
            c_r_geometry: basic_dynamic_load_rating(&geometry),
            c_0r_geometry: basic_static_load_rating(&geometry),
        })
    }
}

/// Rule 9: the drop (mm) of a circular crown that the cone contact closes under the roller
/// load giving `CROWN_DESIGN_PRESSURE` at the roller's middle. Cone contact: roller radius
/// D_we / 2 against the cone raceway's radius of curvature normal to the line,
/// r_cone / cos(cone angle) with r_cone the raceway's distance from the bearing axis.
fn crown_drop_mm(dw: f64, length: f64, dpw: f64, cone_angle: f64, half: f64) -> f64 {
    let axis = cone_angle + half;
    let r_roller = 0.5 * dw / libm::cos(half);
    let r_cone = (0.5 * dpw - 0.5 * dw * libm::cos(axis)) / libm::cos(cone_angle);
    let r_bar = r_roller * r_cone / (r_roller + r_cone);
    // Hertz line contact p0 = sqrt(w E* / (π R)): w = π R p0² / E* (N/mm with MPa, mm)
    let e_star = 0.5 * crate::contact::effective_modulus(STEEL_E_GPA * 1e3, STEEL_NU, STEEL_E_GPA * 1e3, STEEL_NU);
    let p0 = CROWN_DESIGN_PRESSURE * 1e-6;
    let q = std::f64::consts::PI * r_bar * p0 * p0 / e_star * length;
    libm::pow(q / (35948.0 * libm::pow(length, 8.0 / 9.0)), 0.9)
}

/// Rule 10: a pressed-steel window cage for `z` rollers of mean diameter `dw` and length
/// `length` on pitch diameter `dpw` (mm); the default of a bearing file without `cage`.
pub fn cage(z: usize, dw: f64, length: f64, dpw: f64) -> CageFile {
    let sheet = 0.1 * dw;
    let rim = 0.3 * dw;
    let band = std::f64::consts::PI * (dpw + dw) * (length + 2.0 * rim);
    let windows = 0.95 * z as f64 * length * dw;
    let volume_mm3 = sheet * (band - windows).max(0.0);
    CageFile {
        pocket_clearance_mm: significant(0.04 * dw),
        guide_clearance_mm: significant(0.005 * dpw),
        land_width_mm: significant(0.22 * length),
        land_radius_mm: significant(0.5 * dpw + 0.45 * dw),
        mass_kg: significant(volume_mm3 * 1e-9 * STEEL_DENSITY),
    }
}

/// `v` (> 0) to three significant digits, the double nearest that decimal.
fn significant(v: f64) -> f64 {
    let digits = 2 - libm::floor(libm::log10(v)) as i32;
    if digits > 0 {
        let scale = 10f64.powi(digits);
        (v * scale).round() / scale
    } else {
        let scale = 10f64.powi(-digits);
        (v / scale).round() * scale
    }
}

/// `v` to a multiple of `step` (0.001, 0.1, 10, ...), the double nearest that decimal.
fn round_to(v: f64, step: f64) -> f64 {
    if step < 1.0 {
        let per_unit = (1.0 / step).round();
        (v * per_unit).round() / per_unit
    } else {
        (v / step).round() * step
    }
}

/// Numbers written to a bearing file: rounded to what a drawing gives (1 µm, 1e-6 deg), so
/// the file reads cleanly and the geometry stays on apex well inside the reader's 0.02 deg.
fn mm(v: f64) -> f64 {
    round_to(v, 1e-3)
}
fn deg(v: f64) -> f64 {
    round_to(v, 1e-6)
}

/// The documented defaults of everything a catalogue does not give (docs/model.md, "A bearing
/// from its catalogue data"); each comes with the sentence a bearing file carries.
pub mod defaults {
    use super::*;

    pub fn materials() -> MaterialsFile {
        let steel = MaterialFile {
            e_gpa: STEEL_E_GPA,
            nu: STEEL_NU,
            density_kg_m3: STEEL_DENSITY,
        };
        MaterialsFile {
            roller: steel.clone(),
            rings: steel.clone(),
            cage: steel,
        }
    }
    pub const MATERIALS_NOTE: &str = "Rings and rollers of through-hardened bearing steel (100Cr6: E 208 GPa, nu 0.3, 7850 kg/m3); pressed-steel cage of the same steel.";

    pub fn lubricant() -> LubricantFile {
        LubricantFile {
            eta0_pa_s: 0.033,
            alpha_per_pa: 1.28e-8,
            roughness_um: 0.2,
            nu40_mm2_s: Some(68.0),
            nu100_mm2_s: Some(8.6),
            density_kg_m3: Some(870.0),
            temperature_c: None,
            traction: None,
        }
    }
    pub const LUBRICANT_NOTE: &str = "Oil ISO VG 68 mineral oil (nu40 68 mm2/s, nu100 8.6 mm2/s, VI 100, 870 kg/m3), eta0 = 0.033 Pa s at 52.2 degC (the default oilTemperature), pressure-viscosity coefficient 1.28e-8 1/Pa, as the presets; composite roughness 0.2 um (ground raceways and rollers, Ra 0.1-0.15 um each), roller end / rib 0.35 um (superfinished end, ground rib).";

    pub fn friction() -> FrictionFile {
        FrictionFile {
            model: LubricationModel::Ehl,
            mu: 0.1,
            flange_mu0: 0.1,
            cage_slip_rate: 0.0005,
            flange_roughness_um: Some(0.35),
        }
    }
    pub const FRICTION_NOTE: &str = "Friction: the EHL traction laws (docs/model.md); boundary coefficient 0.1 at the raceways and the rib; cage slip rate 0.05 % for the quasi-static torque model, as [L22].";

    pub fn solver() -> SolverFile {
        SolverFile {
            slices: 20,
            tolerance: 1e-5,
        }
    }
    pub const SOLVER_NOTE: &str = "20 slices per contact line and solver tolerance 1e-5, as the presets.";

    /// Operating point: pure axial load with P = 0.1 C_r (an L10 of 2150 million revolutions,
    /// a design point of industrial gearing), at 1500 rpm or at the speed where n d_m reaches
    /// 2.5e5 mm/min, whichever is lower (well inside oil-lubricated tapered bearings' range).
    pub fn operating_point(c_r: f64, alpha: f64, dpw_mm: f64) -> OperatingPointFile {
        // a cylindrical bearing (alpha = 0) carries the same P as radial load
        let (fx_n, fy_n) = if alpha > 0.0 {
            (round_to(0.1 * c_r * libm::tan(alpha) / 0.4, 10.0), 0.0)
        } else {
            (0.0, round_to(0.1 * c_r, 10.0))
        };
        OperatingPointFile {
            speed_rpm: round_to((2.5e5 / dpw_mm).min(1500.0), 10.0),
            fx_n,
            fy_n,
            fz_n: 0.0,
            xi_deg: 0.0,
            zeta_deg: 0.0,
            axial_displacement_um: 10.0,
            preload: PreloadFile::Force,
        }
    }
    pub const OPERATING_POINT_NOTE: &str = "Default operating point: pure axial load with P = Y Fa = 0.1 C_r (L10 = 2150 million revolutions; a cylindrical bearing: radial load 0.1 C_r), at 1500 rpm or n d_m = 2.5e5 mm/min if lower.";

    /// A cage that stands in where the geometry to size one by is itself at fault (the
    /// bearing is refused; the cage's own checks still run).
    pub fn placeholder_cage() -> CageFile {
        CageFile {
            pocket_clearance_mm: 0.0,
            guide_clearance_mm: 0.0,
            land_width_mm: 1.0,
            land_radius_mm: 1.0,
            mass_kg: 1.0,
        }
    }

    pub const CAGE_NOTE: &str = "Pressed-steel window cage: sheet 0.1 D_we thick, pocket clearance 0.04 D_we, guide clearance 0.005 D_pw, guiding land at D_pw/2 + 0.45 D_we and 0.22 L_we wide, mass from the sheet (docs/model.md, A bearing from its catalogue data).";

    pub const CONTACT_LAW_NOTE: &str =
        "Contact law: Palmgren's roller load-deflection, the one ISO/TS 16281 uses (and MESYS, MASTA and KISSsoft with it).";
}

impl Estimate {
    /// The notes a bearing file carries on its estimated geometry.
    pub fn geometry_notes(&self, catalogue: &Catalogue) -> Vec<String> {
        let mut notes = vec![
            format!(
                "Internal geometry estimated from catalogue data (d {} mm, D {} mm, T {} mm, C_r {} N, e {}) by the method of docs/model.md, A bearing from its catalogue data: not the maker's drawing.",
                catalogue.d, catalogue.outside_d, catalogue.t, catalogue.c_r, catalogue.e
            ),
            format!(
                "Cup angle atan(e / 1.5) = {:.4} deg (ISO 281); pitch diameter (d + D)/2; roller mean diameter 0.235 (D - d); {} rollers with a cage bar of at least 0.13 D_we (fill factor {:.3}); roller length from ISO 281's C_r solved for it ({:.0} N from the geometry).",
                self.cup_angle_deg, self.z, self.fill_factor, self.c_r_geometry
            ),
            format!(
                "One apex: half-cone angle {:.4} deg, cone angle {:.4} deg; roller end radius 0.9 of the apex distance ({:.2} mm); rib contact 0.6 of the large-end radius below the roller axis (contact angle {:.3} deg).",
                self.half_cone_angle_deg, self.cone_angle_deg, self.end_radius_mm, self.flange_contact_angle_deg
            ),
            format!(
                "Circular crown of {:.1} um drop: the cone contact's approach (ISO/TS 16281) under a Hertz pressure of 1000 MPa.",
                self.crown_drop_um
            ),
        ];
        if let Some(z) = catalogue.z {
            notes.push(format!("Roller count {z} as the catalogue gives it."));
        }
        notes
    }

    /// The complete bearing file of this estimate (the presets' format), every default
    /// written out and documented.
    pub fn bearing_file(&self, catalogue: &Catalogue, name: &str) -> BearingFile {
        let mut notes = self.geometry_notes(catalogue);
        notes.extend(
            [
                defaults::CAGE_NOTE,
                defaults::MATERIALS_NOTE,
                defaults::CONTACT_LAW_NOTE,
                defaults::LUBRICANT_NOTE,
                defaults::FRICTION_NOTE,
                defaults::SOLVER_NOTE,
                defaults::OPERATING_POINT_NOTE,
            ]
            .iter()
            .map(|s| s.to_string()),
        );
        let alpha = self.cup_angle_deg * DEG;
        BearingFile {
            schema: None,
            name: name.to_string(),
            description: format!(
                "Tapered roller bearing {name} ({} x {} x {} mm), {} rollers: internal geometry estimated from catalogue data.",
                catalogue.d, catalogue.outside_d, catalogue.t, self.z
            ),
            source: "Catalogue data (envelope, C_r, e) and the estimate of docs/model.md, A bearing from its catalogue data.".to_string(),
            kind: Kind::Tapered,
            catalogue: None,
            envelope: Some(EnvelopeFile {
                bore_mm: catalogue.d,
                outside_diameter_mm: catalogue.outside_d,
                width_mm: catalogue.t,
            }),
            rollers: Some(RollersFile {
                count: self.z as i64,
                length_mm: mm(self.roller_length_mm),
                mean_diameter_mm: Some(mm(self.roller_mean_diameter_mm)),
                large_end_diameter_mm: None,
                small_end_diameter_mm: None,
                half_cone_angle_deg: Some(deg(self.half_cone_angle_deg)),
                end_radius_mm: Some(mm(self.end_radius_mm)),
                end_radius_ratio: None,
                crown_drop_um: round_to(self.crown_drop_um, 0.1),
            }),
            pitch_diameter_mm: Some(mm(self.pitch_diameter_mm)),
            cone_angle_deg: Some(deg(self.cone_angle_deg)),
            cup_angle_deg: Some(deg(self.cup_angle_deg)),
            flange: Some(FlangeFile {
                contact_angle_deg: Some(deg(self.flange_contact_angle_deg)),
                opening_angle_deg: None,
                face_to_roller_axis_rad: None,
            }),
            materials: Some(defaults::materials()),
            contact_law: Some(ContactLaw::Palmgren),
            cage: Some(self.cage.clone()),
            lubricant: Some(defaults::lubricant()),
            friction: Some(defaults::friction()),
            raceway: RacewayFile::default(),
            solver: Some(defaults::solver()),
            operating_point: Some(defaults::operating_point(self.c_r_geometry, alpha, self.pitch_diameter_mm)),
            documented_defaults: notes,
        }
    }

    /// The short table `trb bearing estimate` prints.
    pub fn table(&self, catalogue: &Catalogue) -> String {
        let mut rows: Vec<(String, String)> = vec![
            ("rollers Z".into(), format!("{}", self.z)),
            (
                "roller mean diameter D_we".into(),
                format!("{:.3} mm", self.roller_mean_diameter_mm),
            ),
            ("roller effective length L_we".into(), format!("{:.3} mm", self.roller_length_mm)),
            ("pitch diameter D_pw".into(), format!("{:.3} mm", self.pitch_diameter_mm)),
            ("cup angle (contact angle)".into(), format!("{:.4} deg", self.cup_angle_deg)),
            ("cone angle".into(), format!("{:.4} deg", self.cone_angle_deg)),
            ("roller half-cone angle".into(), format!("{:.4} deg", self.half_cone_angle_deg)),
            ("roller end radius".into(), format!("{:.2} mm", self.end_radius_mm)),
            ("rib contact angle".into(), format!("{:.3} deg", self.flange_contact_angle_deg)),
            (
                "rib contact above cone raceway".into(),
                format!("{:.2} mm", self.rib_contact_height_mm),
            ),
            ("crown drop".into(), format!("{:.1} um", self.crown_drop_um)),
            (
                "roller axial extent (width T)".into(),
                format!("{:.2} mm ({} mm)", self.roller_axial_extent_mm, catalogue.t),
            ),
            ("fill factor Z D_we / (pi D_pw)".into(), format!("{:.3}", self.fill_factor)),
            ("cage bar at pitch circle".into(), format!("{:.2} mm", self.cage_bar_mm)),
            ("cage mass".into(), format!("{:.3} kg", self.cage.mass_kg)),
            (
                "C_r from geometry (catalogue)".into(),
                format!(
                    "{:.0} N ({} N, {:+.2} %)",
                    self.c_r_geometry,
                    catalogue.c_r,
                    100.0 * (self.c_r_geometry / catalogue.c_r - 1.0)
                ),
            ),
            (
                "e = 1.5 tan(cup angle) (catalogue)".into(),
                format!("{:.4} ({})", 1.5 * libm::tan(self.cup_angle_deg * DEG), catalogue.e),
            ),
        ];
        rows.push((
            "C_0r from geometry (catalogue)".into(),
            match catalogue.c_0r {
                Some(c0) => format!(
                    "{:.0} N ({c0} N, {:+.1} %)",
                    self.c_0r_geometry,
                    100.0 * (self.c_0r_geometry / c0 - 1.0)
                ),
                None => format!("{:.0} N", self.c_0r_geometry),
            },
        ));
        let width = rows.iter().map(|(k, _)| k.len()).max().unwrap_or(0);
        rows.iter().map(|(k, v)| format!("  {k:<width$}  {v}\n")).collect()
    }
}
