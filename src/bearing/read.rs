//! Reading a bearing description: a preset or a bearing file parsed, validated and converted
//! to SI units once on load. A file that gives catalogue data instead of its internal
//! geometry is estimated first (`super::estimate`), and every section the file leaves out
//! takes its documented default (`super::estimate::defaults`).
//!
//! Errors name the offending field by its path in the file (for example
//! `rollers.length_mm: must be a finite number > 0, got -3`), every fault of a file in one
//! message.

use super::estimate::{self, defaults};
use super::file::*;
use super::rating::{basic_dynamic_load_rating, RatingGeometry};
use std::f64::consts::PI;
use std::fmt;

fn err(field: &str, message: impl Into<String>) -> BearingError {
    BearingError {
        field: field.to_string(),
        message: message.into(),
    }
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
            Some(g) => estimate::cage(g.z, g.mean_d / MM, g.length / MM, g.dm / MM),
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
                let rating = RatingGeometry {
                    z: g.z,
                    d_we: g.mean_d,
                    l_we: g.length,
                    d_pw: g.dm,
                    alpha: g.cup,
                };
                defaults::operating_point(basic_dynamic_load_rating(&rating), g.cup, g.dm / MM)
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
