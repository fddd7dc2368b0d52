//! How an FMU was packaged beyond its bearing: parameters' start values chosen at packaging
//! (`trb fmu --set NAME=VALUE`) and whether its Enumeration parameters are declared as
//! Integers (`trb fmu --enumerations-as-integers`).
//!
//! Both change `modelDescription.xml` (and so its GUID), and the start values change what a
//! fresh instance simulates. The packager writes them to `resources/packaging.json`, which
//! every instance reads at `fmi2Instantiate` (and applies again at `fmi2Reset`), so the binary
//! starts from the start values its model description declares and recomputes the same GUID.
//! An FMU packaged without either option has no such file, and a missing file means neither.
//!
//! The file (JSON; values in SI units, enumerations by their number, as FMI sets them):
//!
//! ```json
//! {"enumerations_as_integers": true, "start": {"fidelity": 2, "supply": 2, "mu": 0.1}}
//! ```

use crate::simulation::Simulation;
use crate::variables::{self, Causality, VarType, Variable};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The file's name in the FMU's `resources/`.
pub const RESOURCE: &str = "packaging.json";

pub use crate::variables::Value;

/// A parameter's start value: its name, value reference and value.
#[derive(Debug, Clone, PartialEq)]
pub struct Start {
    pub name: String,
    pub vr: u32,
    pub value: Value,
}

/// The packaging options that shape an FMU beyond its bearing (default: none).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Packaging {
    /// Declare every Enumeration parameter as an Integer (same value reference, start and
    /// range; the items' meanings in its description).
    pub enumerations_as_integers: bool,
    /// Start values of parameters, in name order, one per parameter.
    pub start: Vec<Start>,
}

/// `resources/packaging.json` as written.
#[derive(Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    enumerations_as_integers: bool,
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    start: BTreeMap<String, serde_json::Value>,
}

impl Packaging {
    /// No option: the FMU as packaged by a plain `trb fmu`.
    pub fn is_default(&self) -> bool {
        *self == Packaging::default()
    }

    /// Set (or replace) the start value of a parameter, keeping name order.
    pub fn set(&mut self, start: Start) {
        self.start.retain(|s| s.vr != start.vr);
        let at = self.start.partition_point(|s| s.name < start.name);
        self.start.insert(at, start);
    }

    /// The text of `resources/packaging.json`.
    pub fn to_json(&self) -> String {
        let file = File {
            enumerations_as_integers: self.enumerations_as_integers,
            start: self.start.iter().map(|s| (s.name.clone(), json_value(s.value))).collect(),
        };
        serde_json::to_string_pretty(&file).expect("packaging options serialise") + "\n"
    }

    /// Read `resources/packaging.json` of an FMU of a bearing with `n_rollers` rollers; every
    /// start value is checked as `start_value` checks the command line's.
    pub fn from_json(text: &str, n_rollers: usize) -> Result<Packaging, String> {
        let file: File = serde_json::from_str(text).map_err(|e| e.to_string())?;
        let mut packaging = Packaging {
            enumerations_as_integers: file.enumerations_as_integers,
            start: Vec::new(),
        };
        for (name, value) in &file.start {
            let (vr, row) = parameter(name, n_rollers)?;
            let value =
                from_json_value(row, value).ok_or_else(|| format!("start value of `{name}`: expected {}, got {value}", kind(row)))?;
            check(name, row, value)?;
            packaging.set(Start {
                name: name.clone(),
                vr,
                value,
            });
        }
        Ok(packaging)
    }

    /// Set the start values in a fresh element (before initialization).
    pub fn apply(&self, sim: &mut Simulation) -> Result<(), String> {
        for s in &self.start {
            let result = match s.value {
                Value::Real(x) => sim.set_real(s.vr, x),
                Value::Integer(k) => sim.set_integer(s.vr, k),
                Value::Boolean(b) => sim.set_boolean(s.vr, b),
            };
            result.map_err(|e| format!("start value of `{}`: {e}", s.name))?;
        }
        Ok(())
    }
}

/// The start value `text` of parameter `name` in a bearing with `n_rollers` rollers: a Real
/// in SI units, an Integer, `true`/`false`, or an enumeration item by name or number. Checked
/// against the variable's type and range; errors name the variable.
pub fn start_value(name: &str, text: &str, n_rollers: usize) -> Result<Start, String> {
    let (vr, row) = parameter(name, n_rollers)?;
    let text = text.trim();
    let value = parse(row, text).ok_or_else(|| format!("`{name}`: expected {}, got `{text}`", kind(row)))?;
    check(name, row, value)?;
    Ok(Start {
        name: name.to_string(),
        vr,
        value,
    })
}

/// The value reference and row of parameter `name`, or why it is none.
fn parameter(name: &str, n_rollers: usize) -> Result<(u32, &'static Variable), String> {
    let (vr, row) = variables::find(name, n_rollers).ok_or_else(|| {
        format!("unknown variable `{name}` (not a variable of this bearing's FMU with {n_rollers} rollers; names are case-sensitive)")
    })?;
    match row.causality {
        Causality::Parameter => Ok((vr, row)),
        Causality::Input => Err(format!("`{name}` is an input, not a parameter; set inputs in the importer")),
        Causality::Output => Err(format!("`{name}` is an output, not a parameter")),
    }
}

/// What a value of `row` looks like, for messages.
fn kind(row: &Variable) -> String {
    match (row.ty, row.enumeration) {
        (VarType::Real, _) => format!("a number (Real, SI unit {})", row.unit.unwrap_or("1")),
        (VarType::Integer, Some(e)) => format!("an item of {}: {}", e.name, items(row)),
        (VarType::Integer, None) => "an integer".to_string(),
        (VarType::Boolean, _) => "true or false".to_string(),
    }
}

/// The items of an enumeration parameter with their values: `0 quasiStatic, 1 dynamic`.
pub fn items(row: &Variable) -> String {
    let Some(e) = row.enumeration else { return String::new() };
    let first = row.min.unwrap_or(0.0) as i64;
    let list: Vec<String> = e
        .items
        .iter()
        .enumerate()
        .map(|(k, (item, _))| format!("{} {item}", first + k as i64))
        .collect();
    list.join(", ")
}

fn parse(row: &Variable, text: &str) -> Option<Value> {
    match row.ty {
        VarType::Real => text.parse::<f64>().ok().filter(|x| x.is_finite()).map(Value::Real),
        VarType::Integer => {
            let by_name = row.enumeration.and_then(|e| {
                let first = row.min.unwrap_or(0.0) as i32;
                e.items.iter().position(|(item, _)| *item == text).map(|k| first + k as i32)
            });
            by_name.or_else(|| text.parse::<i32>().ok()).map(Value::Integer)
        }
        VarType::Boolean => text.parse::<bool>().ok().map(Value::Boolean),
    }
}

/// The value within the variable's range (`min`, `max` of the variable table).
fn check(name: &str, row: &Variable, value: Value) -> Result<(), String> {
    let x = match value {
        Value::Real(x) => x,
        Value::Integer(k) => k as f64,
        Value::Boolean(_) => return Ok(()),
    };
    let unit = match row.unit {
        Some(u) if u != "1" => format!(" {u}"),
        _ => String::new(),
    };
    let below = row.min.is_some_and(|lo| x < lo);
    let above = row.max.is_some_and(|hi| x > hi);
    if !(below || above) {
        return Ok(());
    }
    let range = match (row.min, row.max) {
        (Some(lo), Some(hi)) => format!("[{lo}, {hi}]{unit}"),
        (Some(lo), None) => format!("at least {lo}{unit}"),
        (None, Some(hi)) => format!("at most {hi}{unit}"),
        (None, None) => return Ok(()),
    };
    let items = if row.enumeration.is_some() {
        format!(" ({})", items(row))
    } else {
        String::new()
    };
    Err(format!("`{name}` = {x} is out of range: it must be {range}{items}"))
}

fn json_value(value: Value) -> serde_json::Value {
    match value {
        Value::Real(x) => serde_json::Value::from(x),
        Value::Integer(k) => serde_json::Value::from(k),
        Value::Boolean(b) => serde_json::Value::from(b),
    }
}

fn from_json_value(row: &Variable, value: &serde_json::Value) -> Option<Value> {
    match row.ty {
        VarType::Real => value.as_f64().filter(|x| x.is_finite()).map(Value::Real),
        VarType::Integer => value.as_i64().and_then(|k| i32::try_from(k).ok()).map(Value::Integer),
        VarType::Boolean => value.as_bool().map(Value::Boolean),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn start_values_by_number_and_item_name_round_trip_through_the_file() {
        let mut p = Packaging::default();
        p.set(start_value("supply", "grease", 17).unwrap());
        p.set(start_value("fidelity", "2", 17).unwrap());
        p.set(start_value("mu", "0.1", 17).unwrap());
        p.set(start_value("skewModel", "false", 17).unwrap());
        p.set(start_value("roller[17].dD", "1e-6", 17).unwrap());
        p.set(start_value("fidelity", "quasiStatic", 17).unwrap());
        let names: Vec<&str> = p.start.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["fidelity", "mu", "roller[17].dD", "skewModel", "supply"]);
        assert_eq!(p.start[0].value, Value::Integer(0));
        assert_eq!(p.start[4].value, Value::Integer(2));
        let back = Packaging::from_json(&p.to_json(), 17).unwrap();
        assert_eq!(back, p);
        assert!(Packaging::from_json("{}", 17).unwrap().is_default());
    }

    #[test]
    fn bad_start_values_are_refused_naming_the_variable() {
        for (name, text, want) in [
            ("nonsense", "1", "unknown variable `nonsense`"),
            ("speed", "1", "`speed` is an input"),
            ("frictionTorque", "1", "`frictionTorque` is an output"),
            ("mu", "abc", "`mu`: expected a number"),
            ("mu", "inf", "`mu`: expected a number"),
            ("mu", "3", "`mu` = 3 is out of range: it must be [0, 2]"),
            (
                "fidelity",
                "5",
                "`fidelity` = 5 is out of range: it must be [0, 2] (0 quasiStatic, 1 dynamic, 2 quasiDynamic)",
            ),
            ("fidelity", "fast", "`fidelity`: expected an item of Fidelity: 0 quasiStatic"),
            ("slices", "2.5", "`slices`: expected an integer"),
            ("skewModel", "1", "`skewModel`: expected true or false"),
            ("roller[18].dD", "0", "unknown variable `roller[18].dD`"),
        ] {
            let e = start_value(name, text, 17).unwrap_err();
            assert!(e.contains(want), "{name}={text}: {e}");
        }
        assert!(Packaging::from_json(r#"{"start": {"fidelity": 1.5}}"#, 17)
            .unwrap_err()
            .contains("fidelity"));
        assert!(Packaging::from_json(r#"{"starts": {}}"#, 17).is_err());
    }
}
