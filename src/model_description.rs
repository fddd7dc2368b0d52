//! `modelDescription.xml` for a bearing, generated from the variable table
//! (`modelDescription/variables.json` via `variables::TABLE`) and the start values of a
//! freshly instantiated element of that bearing. The same function runs in the packager
//! and inside the FMU binary (which recomputes the GUID to check `fmuGUID`), so the XML,
//! the value references and the start values cannot drift apart.
//!
//! The GUID is derived from the XML content itself: it changes whenever the model
//! description changes.

use crate::bearing::Bearing;
use crate::packaging::{self, Packaging};
use crate::simulation::Simulation;
use crate::variables::{self, Causality, VarType, Variability};
use sha2::{Digest, Sha256};
use std::fmt::Write as _;

/// The model identifier of the default bearing's FMU (binary name; the exports carry no
/// prefix). Other bearings' FMUs get their own, see [`model_identifier`].
pub const MODEL_IDENTIFIER: &str = "TaperedRollerBearing";

/// The model identifier (and binary name) of `bearing`'s FMU: [`MODEL_IDENTIFIER`] for the
/// default preset, otherwise `TRB_` and the bearing's name with every character that may not
/// stand in a C identifier replaced by `_` (`32008` -> `TRB_32008`, `CRB-TRILOBE` ->
/// `TRB_CRB_TRILOBE`), so that FMUs of different bearings can be loaded side by side.
pub fn model_identifier(bearing: &Bearing) -> String {
    if *bearing == Bearing::default_preset() {
        return MODEL_IDENTIFIER.to_string();
    }
    let name: String = bearing
        .name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    format!("TRB_{name}")
}

/// Log categories the FMU declares and passes to the logger.
pub const LOG_CATEGORIES: &[(&str, &str)] = &[
    (
        "logStatusWarning",
        "Warnings: results outside a law's validity range, slow convergence",
    ),
    (
        "logStatusDiscard",
        "Steps the model could not complete (no equilibrium within tolerance)",
    ),
    ("logStatusError", "Errors: invalid inputs, parameters, calls in the wrong state"),
    ("logStatusFatal", "Fatal errors"),
    ("logEvents", "Life cycle: instantiation, initialization, reset, termination"),
    ("logSolver", "Newton iterations and residual of every solve (debug)"),
];

/// Copyright and license of the FMU (the crate's `license`).
pub const COPYRIGHT: &str = "Copyright (c) 2026 tapered-roller-bearing contributors";
pub const LICENSE: &str = "MIT License (documentation/LICENSE.txt)";
/// The source date of this build (`build.rs`: SOURCE_DATE_EPOCH, else the git commit time),
/// so that equal sources give equal model descriptions and GUIDs.
pub const GENERATION_DATE: &str = env!("TRB_SOURCE_DATE");

/// Units with their SI base-unit exponents (kg, m, s, rad, K), the factor of the unit to its
/// base units (1 for SI units; an hour is 3600 s) and display units (name, factor, offset).
type UnitRow = (&'static str, [i32; 5], f64, &'static [(&'static str, f64, f64)]);
const UNITS: &[UnitRow] = &[
    ("1", [0, 0, 0, 0, 0], 1.0, &[]),
    ("m", [0, 1, 0, 0, 0], 1.0, &[]),
    ("kg", [1, 0, 0, 0, 0], 1.0, &[]),
    ("s", [0, 0, 1, 0, 0], 1.0, &[]),
    ("h", [0, 0, 1, 0, 0], 3600.0, &[]),
    ("N", [1, 1, -2, 0, 0], 1.0, &[]),
    ("N.m", [1, 2, -2, 0, 0], 1.0, &[]),
    ("N/m", [1, 0, -2, 0, 0], 1.0, &[]),
    ("N/rad", [1, 1, -2, -1, 0], 1.0, &[]),
    ("N.m/rad", [1, 2, -2, -1, 0], 1.0, &[]),
    ("W", [1, 2, -3, 0, 0], 1.0, &[]),
    ("rad", [0, 0, 0, 1, 0], 1.0, &[("deg", 57.295_779_513_082_32, 0.0)]),
    ("rad/s", [0, 0, -1, 1, 0], 1.0, &[("rpm", 9.549_296_585_513_72, 0.0)]),
    ("Pa.s", [1, -1, -1, 0, 0], 1.0, &[]),
    ("m2/s", [0, 2, -1, 0, 0], 1.0, &[("cSt", 1e6, 0.0)]),
    ("kg/m3", [1, -3, 0, 0, 0], 1.0, &[]),
    ("1/Pa", [-1, 1, 2, 0, 0], 1.0, &[]),
    ("Pa", [1, -1, -2, 0, 0], 1.0, &[]),
    ("K", [0, 0, 0, 0, 1], 1.0, &[("degC", 1.0, -273.15)]),
    ("1/K", [0, 0, 0, 0, -1], 1.0, &[]),
    ("W/(m.K)", [1, 1, -3, 0, -1], 1.0, &[]),
    ("1/s", [0, 0, -1, 0, 0], 1.0, &[]),
    ("N.s/m", [1, 0, -1, 0, 0], 1.0, &[]),
    ("m/s2", [0, 1, -2, 0, 0], 1.0, &[]),
];

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A real number as XML text that parses back to the same bits.
fn real(v: f64) -> String {
    format!("{v:?}")
}

/// Generate the model description for `bearing` as a plain `trb fmu` packages it. Returns
/// (xml, guid).
pub fn generate(bearing: &Bearing) -> (String, String) {
    generate_with(bearing, &Packaging::default()).expect("no start values to refuse")
}

/// Generate the model description for `bearing` packaged with `packaging` (start values,
/// Enumerations declared as Integers). Returns (xml, guid), or why a start value is refused.
pub fn generate_with(bearing: &Bearing, packaging: &Packaging) -> Result<(String, String), String> {
    let mut sim = Simulation::new(bearing.clone());
    packaging.apply(&mut sim)?;
    let body = render(bearing, packaging.enumerations_as_integers, &mut sim, "@GUID@");
    let digest = Sha256::digest(body.as_bytes());
    let h: Vec<String> = digest[..16].iter().map(|b| format!("{b:02x}")).collect();
    let h = h.concat();
    let guid = format!("{{{}-{}-{}-{}-{}}}", &h[0..8], &h[8..12], &h[12..16], &h[16..20], &h[20..32]);
    Ok((body.replace("@GUID@", &guid), guid))
}

/// Just the GUID of `bearing`'s model description.
pub fn guid(bearing: &Bearing) -> String {
    generate(bearing).1
}

/// Just the GUID of `bearing`'s model description packaged with `packaging`.
pub fn guid_with(bearing: &Bearing, packaging: &Packaging) -> Result<String, String> {
    generate_with(bearing, packaging).map(|(_, guid)| guid)
}

/// The model description of `bearing` with the start values of `sim` (a fresh element).
fn render(bearing: &Bearing, enumerations_as_integers: bool, sim: &mut Simulation, guid: &str) -> String {
    let z = bearing.roller_count;
    let id = model_identifier(bearing);
    let mut x = String::new();
    let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        x,
        r#"<fmiModelDescription fmiVersion="2.0" modelName="{id}" guid="{guid}" description="{}" author="tapered-roller-bearing contributors" version="{}" copyright="{COPYRIGHT}" license="{LICENSE}" generationTool="tapered-roller-bearing {}" generationDateAndTime="{GENERATION_DATE}" variableNamingConvention="flat" numberOfEventIndicators="0">"#,
        xml_escape(&format!(
            "Tapered roller bearing element (quasi-static and dynamic), bearing {}: {}",
            bearing.name, bearing.description
        )),
        env!("CARGO_PKG_VERSION"),
        env!("CARGO_PKG_VERSION"),
    );
    let _ = writeln!(
        x,
        r#"  <CoSimulation modelIdentifier="{id}" needsExecutionTool="false" canHandleVariableCommunicationStepSize="true" canInterpolateInputs="true" maxOutputDerivativeOrder="0" canRunAsynchronuously="false" canBeInstantiatedOnlyOncePerProcess="false" canNotUseMemoryManagementFunctions="true" canGetAndSetFMUstate="true" canSerializeFMUstate="true" providesDirectionalDerivative="false"/>"#
    );
    let _ = writeln!(x, "  <UnitDefinitions>");
    for (name, [kg, m, s, rad, k], factor, displays) in UNITS {
        let mut base = String::new();
        for (sym, e) in [("kg", kg), ("m", m), ("s", s), ("rad", rad), ("K", k)] {
            if *e != 0 {
                let _ = write!(base, r#" {sym}="{e}""#);
            }
        }
        if *factor != 1.0 {
            let _ = write!(base, r#" factor="{}""#, real(*factor));
        }
        if displays.is_empty() {
            let _ = writeln!(x, r#"    <Unit name="{}"><BaseUnit{base}/></Unit>"#, xml_escape(name));
        } else {
            let _ = writeln!(x, r#"    <Unit name="{}">"#, xml_escape(name));
            let _ = writeln!(x, r#"      <BaseUnit{base}/>"#);
            for (d, f, offset) in displays.iter() {
                let offset = if *offset != 0.0 {
                    format!(r#" offset="{}""#, real(*offset))
                } else {
                    String::new()
                };
                let _ = writeln!(x, r#"      <DisplayUnit name="{d}" factor="{}"{offset}/>"#, real(*f));
            }
            let _ = writeln!(x, "    </Unit>");
        }
    }
    let _ = writeln!(x, "  </UnitDefinitions>");
    if !enumerations_as_integers {
        write_type_definitions(&mut x);
    }
    let _ = writeln!(x, "  <LogCategories>");
    for (name, desc) in LOG_CATEGORIES {
        let _ = writeln!(x, r#"    <Category name="{name}" description="{}"/>"#, xml_escape(desc));
    }
    let _ = writeln!(x, "  </LogCategories>");
    let tolerance = sim.get_real(variables::TOLERANCE).expect("start value of the tolerance");
    let _ = writeln!(
        x,
        r#"  <DefaultExperiment startTime="0.0" stopTime="0.1" tolerance="{}" stepSize="0.001"/>"#,
        real(tolerance)
    );
    let _ = writeln!(x, "  <ModelVariables>");
    let expanded = variables::expanded(z);
    for (vr, name, row) in &expanded {
        let vr = *vr;
        let j = if row.per_roller { (vr - row.vr) as usize + 1 } else { 0 };
        let causality = match row.causality {
            Causality::Parameter => "parameter",
            Causality::Input => "input",
            Causality::Output => "output",
        };
        let variability = match row.variability {
            Variability::Fixed => "fixed",
            Variability::Tunable => "tunable",
            Variability::Discrete => "discrete",
            Variability::Continuous => "continuous",
        };
        let as_integer = enumerations_as_integers && row.enumeration.is_some();
        let mut description = row.description_for(j);
        if as_integer {
            let _ = write!(description, " (values: {})", packaging::items(row));
        }
        let _ = writeln!(
            x,
            r#"    <ScalarVariable name="{}" valueReference="{vr}" description="{}" causality="{causality}" variability="{variability}">"#,
            xml_escape(&name),
            xml_escape(&description)
        );
        let start = row.causality != Causality::Output;
        let _ = writeln!(x, "      {}", type_element(row, vr, start, as_integer, sim));
        let _ = writeln!(x, "    </ScalarVariable>");
    }
    let _ = writeln!(x, "  </ModelVariables>");
    write_model_structure(&mut x, &expanded);
    let _ = writeln!(x, "</fmiModelDescription>");
    x
}

/// The type element of variable `vr` (`<Real unit=... start=.../>`), its start value read from
/// `sim` when `start`; an enumeration as `<Integer>` when `as_integer`.
fn type_element(row: &variables::Variable, vr: u32, start: bool, as_integer: bool, sim: &mut Simulation) -> String {
    let mut attrs = String::new();
    let integer_range = |attrs: &mut String| {
        if let Some(m) = row.min {
            let _ = write!(attrs, r#" min="{}""#, m as i64);
        }
        if let Some(m) = row.max {
            let _ = write!(attrs, r#" max="{}""#, m as i64);
        }
    };
    match row.ty {
        VarType::Real => {
            if let Some(u) = row.unit {
                let _ = write!(attrs, r#" unit="{}""#, xml_escape(u));
            }
            if let Some(d) = row.display_unit {
                let _ = write!(attrs, r#" displayUnit="{d}""#);
            }
            if let Some(m) = row.min {
                let _ = write!(attrs, r#" min="{}""#, real(m));
            }
            if let Some(m) = row.max {
                let _ = write!(attrs, r#" max="{}""#, real(m));
            }
            if start {
                let v = sim.get_real(vr).expect("start value of a real variable");
                let _ = write!(attrs, r#" start="{}""#, real(v));
            }
            format!("<Real{attrs}/>")
        }
        VarType::Integer => {
            let tag = match row.enumeration {
                Some(e) if !as_integer => {
                    let _ = write!(attrs, r#" declaredType="{}""#, e.name);
                    "Enumeration"
                }
                _ => "Integer",
            };
            integer_range(&mut attrs);
            if start {
                let v = sim.get_integer(vr).expect("start value of an integer variable");
                let _ = write!(attrs, r#" start="{v}""#);
            }
            format!("<{tag}{attrs}/>")
        }
        VarType::Boolean => {
            if start {
                let v = sim.get_boolean(vr).expect("start value of a boolean variable");
                let _ = write!(attrs, r#" start="{v}""#);
            }
            format!("<Boolean{attrs}/>")
        }
    }
}

/// `<TypeDefinitions>`: one Enumeration type per mode (parameters may share one).
fn write_type_definitions(x: &mut String) {
    let _ = writeln!(x, "  <TypeDefinitions>");
    // a type several parameters share (`defect.ring`, `defect[2].ring`, ...) once, described
    // by the first of them
    let mut written: Vec<&str> = Vec::new();
    for row in variables::TABLE {
        let Some(e) = row.enumeration else { continue };
        if written.contains(&e.name) {
            continue;
        }
        written.push(e.name);
        let first = row.min.unwrap_or(0.0) as i64;
        let _ = writeln!(
            x,
            r#"    <SimpleType name="{}" description="{}">"#,
            e.name,
            xml_escape(row.description)
        );
        let _ = writeln!(x, "      <Enumeration>");
        for (k, (item, description)) in e.items.iter().enumerate() {
            let _ = writeln!(
                x,
                r#"        <Item name="{item}" value="{}" description="{}"/>"#,
                first + k as i64,
                xml_escape(description)
            );
        }
        let _ = writeln!(x, "      </Enumeration>");
        let _ = writeln!(x, "    </SimpleType>");
    }
    let _ = writeln!(x, "  </TypeDefinitions>");
}

/// `<ModelStructure>`: every output with the inputs it depends on directly at communication
/// points, and in initialization mode the inputs and parameters it depends on (the table's
/// `depends_on` and `initial_depends_on`; without them, all of them: the quasi-static model
/// is an algebraic function of every input and parameter).
fn write_model_structure(x: &mut String, expanded: &[(u32, String, &'static variables::Variable)]) {
    // 1-based ScalarVariable indices of the knowns
    let index_of = |name: &str| {
        expanded
            .iter()
            .position(|(_, n, _)| n == name)
            .map(|i| i + 1)
            .unwrap_or_else(|| panic!("dependency {name} is not a variable"))
    };
    let of_causality = |c: Causality| -> Vec<usize> {
        (0..expanded.len())
            .filter(|&i| expanded[i].2.causality == c)
            .map(|i| i + 1)
            .collect()
    };
    let inputs = of_causality(Causality::Input);
    let mut knowns_at_init = inputs.clone();
    knowns_at_init.extend(of_causality(Causality::Parameter));
    knowns_at_init.sort_unstable();
    let list = |declared: Option<&[&str]>, all: &[usize]| -> String {
        let mut ix: Vec<usize> = match declared {
            Some(names) => names.iter().map(|n| index_of(n)).collect(),
            None => all.to_vec(),
        };
        ix.sort_unstable();
        ix.iter().map(|i| i.to_string()).collect::<Vec<_>>().join(" ")
    };
    let outputs: Vec<usize> = of_causality(Causality::Output);
    let _ = writeln!(x, "  <ModelStructure>");
    let _ = writeln!(x, "    <Outputs>");
    for &i in &outputs {
        let deps = list(expanded[i - 1].2.depends_on, &inputs);
        let _ = writeln!(x, r#"      <Unknown index="{i}" dependencies="{deps}"/>"#);
    }
    let _ = writeln!(x, "    </Outputs>");
    let _ = writeln!(x, "    <InitialUnknowns>");
    for &i in &outputs {
        let deps = list(expanded[i - 1].2.initial_depends_on, &knowns_at_init);
        let _ = writeln!(x, r#"      <Unknown index="{i}" dependencies="{deps}"/>"#);
    }
    let _ = writeln!(x, "    </InitialUnknowns>");
    let _ = writeln!(x, "  </ModelStructure>");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guid_is_stable_and_depends_on_the_bearing() {
        let a = Bearing::default_preset();
        let (x1, g1) = generate(&a);
        let (x2, g2) = generate(&a);
        assert_eq!(x1, x2);
        assert_eq!(g1, g2);
        let b = Bearing::preset("32008").unwrap();
        assert_ne!(guid(&b), g1);
        assert!(x1.contains(&g1));
    }

    #[test]
    fn every_table_row_appears_with_its_value_reference() {
        let b = Bearing::default_preset();
        let (xml, _) = generate(&b);
        for (vr, name, _) in variables::expanded(b.roller_count) {
            let needle = format!(r#"name="{}" valueReference="{vr}""#, xml_escape(&name));
            assert!(xml.contains(&needle), "missing {needle}");
        }
        assert!(xml.contains(r#"name="roller[17].Nfs""#));
        assert!(!xml.contains(r#"name="roller[18].Nfs""#));
    }

    #[test]
    fn model_identifiers_are_c_identifiers_of_their_own() {
        let default = Bearing::default_preset();
        assert_eq!(model_identifier(&default), MODEL_IDENTIFIER);
        let mut ids: Vec<String> = crate::bearing::PRESETS
            .iter()
            .map(|(name, _)| model_identifier(&Bearing::preset(name).unwrap()))
            .collect();
        assert_eq!(ids[1..], ["TRB_32018X", "TRB_32008", "TRB_CRB_TRILOBE", "TRB_TRB130x230_W25"]);
        // the default preset changed keeps its name but not its identifier
        let mut changed = default.clone();
        changed.roller_count -= 1;
        ids.push(model_identifier(&changed));
        assert_eq!(ids.last().unwrap(), "TRB_TRB130x230");
        let unique: std::collections::BTreeSet<&String> = ids.iter().collect();
        assert_eq!(unique.len(), ids.len());
        for id in &ids {
            assert!(id.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') && !id.starts_with(|c: char| c.is_ascii_digit()));
        }
        let (xml, _) = generate(&Bearing::preset("32008").unwrap());
        assert!(xml.contains(r#"modelIdentifier="TRB_32008""#));
    }

    #[test]
    fn every_unit_used_is_defined() {
        let b = Bearing::default_preset();
        let (xml, _) = generate(&b);
        for v in variables::TABLE {
            if let Some(u) = v.unit {
                assert!(
                    xml.contains(&format!(r#"<Unit name="{}">"#, xml_escape(u))),
                    "unit {u} of {} is not defined",
                    v.name
                );
            }
        }
    }

    #[test]
    fn start_values_round_trip_exactly() {
        let b = Bearing::default_preset();
        let (xml, _) = generate(&b);
        let mut sim = Simulation::new(b.clone());
        let line = xml.lines().skip_while(|l| !l.contains(r#"name="speed""#)).nth(1).unwrap();
        let start = line.split("start=\"").nth(1).unwrap().split('"').next().unwrap();
        let v: f64 = start.parse().unwrap();
        assert_eq!(v.to_bits(), sim.get_real(variables::SPEED).unwrap().to_bits());
    }
}
