//! Scenario files for `trb simulate`: parsing, validation and input signals.
//!
//! # Format (JSON, SI units = the FMU's units)
//!
//! ```json
//! {
//!   "description": "free text (optional)",
//!   "bearing": "TRB130x230",
//!   "parameters": {"slices": 20, "skewModel": false, "roller[3].dD": 1.0e-6},
//!   "inputs": {
//!     "speed": 366.5191429188092,
//!     "Fx": 30000.0,
//!     "Fy": {"time": [0.0, 0.1, 0.2], "values": [0.0, 0.0, 20000.0]}
//!   },
//!   "start_time": 0.0,
//!   "stop_time": 0.2,
//!   "step": 0.001,
//!   "interpolate_inputs": false,
//!   "outputs": ["frictionTorque", "cone.x"]
//! }
//! ```
//!
//! - `bearing` (optional, default `TRB130x230`): a preset name, or the path of a bearing JSON
//!   file relative to the scenario file.
//! - `parameters` (optional): FMU parameter names; Real parameters take a number, Integer
//!   (and enumeration) parameters an integral number, Boolean parameters `true`/`false`.
//!   Parameters not named keep the bearing's defaults (the FMU's start values).
//! - `inputs` (optional): FMU input names; a number (constant) or a time table
//!   `{"time": [...], "values": [...]}` with strictly increasing times, interpolated linearly
//!   and held constant before the first and after the last point. Inputs not named keep
//!   their start values (the bearing's operating point).
//! - `start_time` (optional, default 0), `stop_time` (> start_time), `step` (> 0): the
//!   communication grid, see below.
//! - `interpolate_inputs` (optional, default false): ramp the inputs linearly over each
//!   step instead of holding them (FMI 2.0 input interpolation, see below).
//! - `outputs` (optional, default all): FMU output names to write.
//!
//! Unknown keys or variable names, wrong types, non-increasing tables or a step <= 0 are
//! rejected with a message naming the field (exit code 2).
//!
//! # Stepping semantics (what `trb simulate` does, in this order)
//!
//! With N = round((stop_time - start_time) / step), t_k = start_time + k * step for
//! k = 0..N-1 and t_N = stop_time exactly:
//! 1. set the parameters; set the inputs to u(t_0); `initialize(t_0)`;
//!    row 0 = (t_0, u(t_0), outputs).
//! 2. for k in 0..N: `do_step(t_k, t_{k+1} - t_k)` with the inputs held at u(t_k); set the
//!    inputs to u(t_{k+1}); read the outputs (re-solved for the new inputs) -> row k+1.
//!    With `interpolate_inputs`, each input's rate (u(t_{k+1}) - u(t_k)) / (t_{k+1} - t_k) is
//!    set before the step (`Simulation::set_real_derivative`), so the inputs follow the table
//!    between communication points as well.
//!
//! An FMI master doing the same calls (set parameters, set inputs, exit initialization mode,
//! get outputs; then per row [fmi2SetRealInputDerivatives of order 1 with those rates,]
//! `fmi2DoStep(t_k, t_{k+1} - t_k)`, set inputs, get outputs) with the time and input columns
//! of the CSV reproduces every output exactly.

use super::package::{load_bearing, LoadedBearing};
use super::CliError;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use trb::bearing::{DEFAULT_PRESET, PRESETS};
use trb::simulation::Simulation;
use trb::variables::{self, Causality, VarType, Variable};

/// Largest number of communication steps a scenario may ask for.
pub const MAX_STEPS: usize = 100_000_000;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ScenarioFile {
    #[serde(default)]
    description: String,
    #[serde(default)]
    bearing: Option<String>,
    #[serde(default)]
    parameters: BTreeMap<String, serde_json::Value>,
    #[serde(default)]
    inputs: BTreeMap<String, serde_json::Value>,
    #[serde(default)]
    start_time: f64,
    stop_time: f64,
    step: f64,
    #[serde(default)]
    interpolate_inputs: bool,
    #[serde(default)]
    outputs: Option<Vec<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TableFile {
    time: Vec<f64>,
    values: Vec<f64>,
}

pub use trb::variables::Value;

/// An input signal u(t).
#[derive(Debug, Clone, PartialEq)]
pub enum Signal {
    Constant(f64),
    /// Strictly increasing `time`, same length `values` (at least one point).
    Table {
        time: Vec<f64>,
        values: Vec<f64>,
    },
}

impl Signal {
    /// Linear interpolation, held constant outside the table.
    pub fn at(&self, t: f64) -> f64 {
        match self {
            Signal::Constant(v) => *v,
            Signal::Table { time, values } => {
                let n = time.len();
                if t <= time[0] {
                    return values[0];
                }
                if t >= time[n - 1] {
                    return values[n - 1];
                }
                // First index with time > t; 1 <= i <= n - 1 here.
                let i = time.partition_point(|&ti| ti <= t);
                let (t0, t1, v0, v1) = (time[i - 1], time[i], values[i - 1], values[i]);
                if t == t0 {
                    v0
                } else {
                    v0 + (v1 - v0) * ((t - t0) / (t1 - t0))
                }
            }
        }
    }
}

/// One FMU variable as the scenario uses it.
#[derive(Debug, Clone)]
pub struct Var {
    pub vr: u32,
    pub name: String,
    pub ty: VarType,
}

/// A validated scenario.
#[derive(Debug, Clone)]
pub struct Scenario {
    pub description: String,
    pub bearing: LoadedBearing,
    pub parameters: Vec<(Var, Value)>,
    /// Every FMU input in modelDescription order, with its signal.
    pub inputs: Vec<(Var, Signal)>,
    /// The outputs to write, in the order requested (default: all, modelDescription order).
    pub outputs: Vec<Var>,
    pub start_time: f64,
    pub stop_time: f64,
    pub step: f64,
    /// Ramp the inputs over each step along the table instead of holding them.
    pub interpolate_inputs: bool,
    /// Number of communication steps N.
    pub n_steps: usize,
}

impl Scenario {
    /// Read and validate a scenario file; relative bearing paths are resolved against the
    /// file's directory.
    pub fn load(path: &Path) -> Result<Scenario, CliError> {
        let text = std::fs::read_to_string(path).map_err(|e| CliError::invalid(format!("cannot read scenario {}: {e}", path.display())))?;
        let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Scenario::from_json(&text, &base).map_err(|e| CliError::invalid(format!("scenario {}: {e}", path.display())))
    }

    /// Parse and validate scenario text. `base` is the directory relative bearing paths are
    /// resolved against. The error names the offending field.
    pub fn from_json(text: &str, base: &Path) -> Result<Scenario, String> {
        let de = &mut serde_json::Deserializer::from_str(text);
        let file: ScenarioFile = serde_path_to_error::deserialize(de).map_err(|e| {
            let path = e.path().to_string();
            let inner = e.into_inner();
            if path == "." {
                inner.to_string()
            } else {
                format!("field `{path}`: {inner}")
            }
        })?;

        // Bearing.
        let bearing_arg = file.bearing.clone().unwrap_or_else(|| DEFAULT_PRESET.to_string());
        let bearing_ref = if PRESETS.iter().any(|(n, _)| n.eq_ignore_ascii_case(&bearing_arg)) {
            bearing_arg.clone()
        } else {
            let p = PathBuf::from(&bearing_arg);
            let p = if p.is_absolute() { p } else { base.join(p) };
            p.to_string_lossy().into_owned()
        };
        let bearing = load_bearing(&bearing_ref).map_err(|e| format!("field `bearing`: {}", e.message))?;
        let z = bearing.bearing.roller_count;
        let bname = bearing.bearing.name.clone();

        // Time grid.
        if !file.start_time.is_finite() {
            return Err(format!("field `start_time`: must be a finite number, got {}", file.start_time));
        }
        if !file.stop_time.is_finite() || file.stop_time <= file.start_time {
            return Err(format!(
                "field `stop_time`: must be a finite number greater than start_time = {:?}, got {:?}",
                file.start_time, file.stop_time
            ));
        }
        if !file.step.is_finite() || file.step <= 0.0 {
            return Err(format!("field `step`: must be a finite number > 0, got {:?}", file.step));
        }
        let span = file.stop_time - file.start_time;
        let n = (span / file.step).round();
        if n < 1.0 {
            return Err(format!(
                "field `step`: {:?} is more than twice the simulated span stop_time - start_time = {:?}",
                file.step, span
            ));
        }
        if n > MAX_STEPS as f64 {
            return Err(format!(
                "field `step`: {:?} makes {n:e} steps over {:?} s; at most {MAX_STEPS} are allowed",
                file.step, span
            ));
        }
        let n_steps = n as usize;

        // Parameters.
        let mut parameters = Vec::new();
        for (name, value) in &file.parameters {
            let field = format!("parameters.{name}");
            let (vr, row) = find(name, z, &bname).map_err(|e| format!("field `{field}`: {e}"))?;
            if row.causality != Causality::Parameter {
                return Err(format!(
                    "field `{field}`: `{name}` is {}, not a parameter; put it under \"{}\"",
                    causality_article(row.causality),
                    section(row.causality)
                ));
            }
            let v = typed_value(row, value).map_err(|e| format!("field `{field}`: {e}"))?;
            parameters.push((
                Var {
                    vr,
                    name: name.clone(),
                    ty: row.ty,
                },
                v,
            ));
        }

        // Inputs: all FMU inputs, the named ones with their signal, the others at their start value.
        for name in file.inputs.keys() {
            let field = format!("inputs.{name}");
            let (_, row) = find(name, z, &bname).map_err(|e| format!("field `{field}`: {e}"))?;
            if row.causality != Causality::Input {
                return Err(format!(
                    "field `{field}`: `{name}` is {}, not an input; put it under \"{}\"",
                    causality_article(row.causality),
                    section(row.causality)
                ));
            }
        }
        let mut defaults = Simulation::new(bearing.bearing.clone());
        let mut inputs = Vec::new();
        for (vr, name, row) in variables::expanded(z) {
            if row.causality != Causality::Input {
                continue;
            }
            if row.ty != VarType::Real {
                return Err(format!("input `{name}` is not Real; scenarios support Real inputs only"));
            }
            let signal = match file.inputs.get(&name) {
                Some(value) => signal(value).map_err(|e| format!("field `inputs.{name}{e}"))?,
                None => Signal::Constant(defaults.get_real(vr).map_err(|e| format!("start value of input `{name}`: {e}"))?),
            };
            inputs.push((Var { vr, name, ty: row.ty }, signal));
        }

        // Outputs.
        let outputs = match &file.outputs {
            None => variables::expanded(z)
                .into_iter()
                .filter(|(_, _, row)| row.causality == Causality::Output)
                .map(|(vr, name, row)| Var { vr, name, ty: row.ty })
                .collect(),
            Some(names) => {
                let mut out: Vec<Var> = Vec::new();
                for (i, name) in names.iter().enumerate() {
                    let field = format!("outputs[{i}]");
                    let (vr, row) = find(name, z, &bname).map_err(|e| format!("field `{field}`: {e}"))?;
                    if row.causality != Causality::Output {
                        return Err(format!(
                            "field `{field}`: `{name}` is {}, not an output (inputs are always written)",
                            causality_article(row.causality)
                        ));
                    }
                    if out.iter().any(|v| v.vr == vr) {
                        return Err(format!("field `{field}`: output `{name}` is listed twice"));
                    }
                    out.push(Var {
                        vr,
                        name: name.clone(),
                        ty: row.ty,
                    });
                }
                out
            }
        };

        Ok(Scenario {
            description: file.description,
            bearing,
            parameters,
            inputs,
            outputs,
            start_time: file.start_time,
            stop_time: file.stop_time,
            step: file.step,
            interpolate_inputs: file.interpolate_inputs,
            n_steps,
        })
    }

    /// Set the parameter `name` to `value` as a `parameters` entry of the file would (same
    /// checks), replacing the file's value if it names one. For variants of a shipped case,
    /// e.g. the other `traction` law.
    pub fn set_parameter(&mut self, name: &str, value: serde_json::Value) -> Result<(), String> {
        let b = &self.bearing.bearing;
        let field = format!("parameters.{name}");
        let (vr, row) = find(name, b.roller_count, &b.name).map_err(|e| format!("field `{field}`: {e}"))?;
        if row.causality != Causality::Parameter {
            return Err(format!(
                "field `{field}`: `{name}` is {}, not a parameter",
                causality_article(row.causality)
            ));
        }
        let v = typed_value(row, &value).map_err(|e| format!("field `{field}`: {e}"))?;
        self.parameters.retain(|(p, _)| p.vr != vr);
        self.parameters.push((
            Var {
                vr,
                name: name.to_string(),
                ty: row.ty,
            },
            v,
        ));
        Ok(())
    }

    /// Hold the input `name` at `value` for the whole run (replacing the file's signal).
    pub fn set_input(&mut self, name: &str, value: f64) -> Result<(), String> {
        if !value.is_finite() {
            return Err(format!("field `inputs.{name}`: must be a finite number, got {value}"));
        }
        let slot = self
            .inputs
            .iter_mut()
            .find(|(v, _)| v.name == name)
            .ok_or_else(|| format!("field `inputs.{name}`: not an input of the FMU"))?;
        slot.1 = Signal::Constant(value);
        Ok(())
    }

    /// End the run at `stop_time`, on the same communication step.
    pub fn set_stop_time(&mut self, stop_time: f64) -> Result<(), String> {
        let n = ((stop_time - self.start_time) / self.step).round();
        if !stop_time.is_finite() || stop_time <= self.start_time || n < 1.0 || n > MAX_STEPS as f64 {
            return Err(format!(
                "field `stop_time`: {stop_time:?} does not give 1..{MAX_STEPS} steps of {:?} from {:?}",
                self.step, self.start_time
            ));
        }
        self.stop_time = stop_time;
        self.n_steps = n as usize;
        Ok(())
    }

    /// Communication point t_k (t_N = stop_time exactly).
    pub fn time(&self, k: usize) -> f64 {
        if k >= self.n_steps {
            self.stop_time
        } else {
            self.start_time + k as f64 * self.step
        }
    }

    /// The CSV header: `time`, every input, the selected outputs.
    /// The CSV header line (without its line end): `time`, the inputs, the outputs; RFC 4180
    /// quoting for names that hold a comma (`stiffness[1,2]`).
    pub fn header(&self) -> String {
        let names = std::iter::once("time")
            .chain(self.inputs.iter().map(|(v, _)| v.name.as_str()))
            .chain(self.outputs.iter().map(|v| v.name.as_str()));
        let mut w = csv::WriterBuilder::new()
            .terminator(csv::Terminator::Any(b'\n'))
            .from_writer(Vec::new());
        w.write_record(names).expect("writing to memory");
        let bytes = w.into_inner().expect("writing to memory");
        String::from_utf8(bytes)
            .expect("names are UTF-8")
            .trim_end_matches('\n')
            .to_string()
    }
}

fn find(name: &str, z: usize, bearing: &str) -> Result<(u32, &'static Variable), String> {
    if let Some(found) = variables::find(name, z) {
        return Ok(found);
    }
    // A per-roller name with a roller index this bearing does not have.
    if let Some(rest) = name.strip_prefix("roller[") {
        if let Some((j, tail)) = rest.split_once(']') {
            let pattern = format!("roller[{{j}}]{tail}");
            if variables::TABLE.iter().any(|v| v.per_roller && v.name == pattern) {
                return Err(format!(
                    "unknown variable `{name}`: bearing {bearing} has rollers 1..{z}, not `{j}`"
                ));
            }
        }
    }
    Err(format!(
        "unknown variable `{name}` (not an FMU variable of bearing {bearing}; names are case-sensitive)"
    ))
}

fn causality_article(c: Causality) -> &'static str {
    match c {
        Causality::Parameter => "a parameter",
        Causality::Input => "an input",
        Causality::Output => "an output",
    }
}

fn section(c: Causality) -> &'static str {
    match c {
        Causality::Parameter => "parameters",
        Causality::Input => "inputs",
        Causality::Output => "outputs",
    }
}

fn json_kind(v: &serde_json::Value) -> &'static str {
    match v {
        serde_json::Value::Null => "null",
        serde_json::Value::Bool(_) => "a boolean",
        serde_json::Value::Number(_) => "a number",
        serde_json::Value::String(_) => "a string",
        serde_json::Value::Array(_) => "an array",
        serde_json::Value::Object(_) => "an object",
    }
}

fn typed_value(row: &Variable, value: &serde_json::Value) -> Result<Value, String> {
    match row.ty {
        VarType::Real => match value.as_f64() {
            Some(x) if x.is_finite() => Ok(Value::Real(x)),
            _ => Err(format!(
                "expected a number (Real, SI unit {}), got {}",
                row.unit.unwrap_or("1"),
                json_kind(value)
            )),
        },
        VarType::Integer => {
            let x = value
                .as_f64()
                .ok_or_else(|| format!("expected an integer, got {}", json_kind(value)))?;
            if x.fract() != 0.0 || x < i32::MIN as f64 || x > i32::MAX as f64 {
                return Err(format!("expected an integer, got {value}"));
            }
            if let Some(lo) = row.min.filter(|lo| x < *lo) {
                return Err(format!("must be at least {lo}, got {value}"));
            }
            if let Some(hi) = row.max.filter(|hi| x > *hi) {
                return Err(format!("must be at most {hi}, got {value}"));
            }
            Ok(Value::Integer(x as i32))
        }
        VarType::Boolean => match value {
            serde_json::Value::Bool(b) => Ok(Value::Boolean(*b)),
            _ => Err(format!("expected true or false, got {}", json_kind(value))),
        },
    }
}

/// A signal from its JSON value; errors start with the rest of the field path (`` ` `` closes
/// the field name when the error is about the value itself).
fn signal(value: &serde_json::Value) -> Result<Signal, String> {
    match value {
        serde_json::Value::Number(_) => match value.as_f64() {
            Some(x) if x.is_finite() => Ok(Signal::Constant(x)),
            _ => Err(format!("`: must be a finite number, got {value}")),
        },
        serde_json::Value::Object(_) => {
            let table: TableFile = serde_path_to_error::deserialize(value).map_err(|e| {
                let path = e.path().to_string();
                let inner = e.into_inner();
                if path == "." {
                    format!("`: {inner}")
                } else {
                    format!(".{path}`: {inner}")
                }
            })?;
            let TableFile { time, values } = table;
            if time.is_empty() {
                return Err(".time`: must have at least one point".into());
            }
            if time.len() != values.len() {
                return Err(format!(
                    "`: `time` has {} points but `values` has {}; they must have the same length",
                    time.len(),
                    values.len()
                ));
            }
            for (i, t) in time.iter().enumerate() {
                if !t.is_finite() {
                    return Err(format!(".time[{i}]`: must be finite, got {t}"));
                }
            }
            for (i, v) in values.iter().enumerate() {
                if !v.is_finite() {
                    return Err(format!(".values[{i}]`: must be finite, got {v}"));
                }
            }
            for i in 1..time.len() {
                if time[i] <= time[i - 1] {
                    return Err(format!(
                        ".time`: must be strictly increasing, but time[{i}] = {:?} follows time[{}] = {:?}",
                        time[i],
                        i - 1,
                        time[i - 1]
                    ));
                }
            }
            Ok(Signal::Table { time, values })
        }
        other => Err(format!(
            "`: expected a number or a table {{\"time\": [...], \"values\": [...]}}, got {}",
            json_kind(other)
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Scenario, String> {
        Scenario::from_json(text, Path::new("."))
    }

    #[test]
    fn tables_interpolate_linearly_and_hold_outside() {
        let s = Signal::Table {
            time: vec![0.0, 1.0, 3.0],
            values: vec![0.0, 10.0, 30.0],
        };
        assert_eq!(s.at(-1.0), 0.0);
        assert_eq!(s.at(0.0), 0.0);
        assert_eq!(s.at(0.5), 5.0);
        assert_eq!(s.at(1.0), 10.0);
        assert_eq!(s.at(2.0), 20.0);
        assert_eq!(s.at(3.0), 30.0);
        assert_eq!(s.at(7.0), 30.0);
        let one = Signal::Table {
            time: vec![2.0],
            values: vec![4.0],
        };
        assert_eq!(one.at(0.0), 4.0);
        assert_eq!(one.at(9.0), 4.0);
    }

    #[test]
    fn grid_ends_exactly_at_stop_time() {
        let s = parse(r#"{"stop_time": 0.3, "step": 0.1}"#).unwrap();
        assert_eq!(s.n_steps, 3);
        assert_eq!(s.time(0), 0.0);
        assert_eq!(s.time(3), 0.3);
        let inputs: Vec<&str> = variables::TABLE
            .iter()
            .filter(|v| v.causality == Causality::Input)
            .map(|v| v.name)
            .collect();
        assert_eq!(s.inputs.len(), inputs.len());
        assert!(s.header().starts_with(&format!("time,{},frictionTorque", inputs.join(","))));
    }

    #[test]
    fn variants_replace_parameters_inputs_and_the_stop_time() {
        let mut s = parse(r#"{"stop_time": 0.05, "step": 0.0002, "parameters": {"traction": 0, "slices": 10}, "inputs": {"Fy": {"time": [0, 1], "values": [0, 5]}}}"#).unwrap();
        s.set_parameter("traction", serde_json::json!(1)).unwrap();
        s.set_parameter("mu", serde_json::json!(0.3)).unwrap();
        assert_eq!(s.parameters.iter().filter(|(v, _)| v.name == "traction").count(), 1);
        assert!(s.parameters.iter().any(|(v, x)| v.name == "traction" && *x == Value::Integer(1)));
        assert!(s.parameters.iter().any(|(v, x)| v.name == "mu" && *x == Value::Real(0.3)));
        assert!(s
            .set_parameter("traction", serde_json::json!(7))
            .unwrap_err()
            .contains("parameters.traction"));
        assert!(s
            .set_parameter("Fy", serde_json::json!(1.0))
            .unwrap_err()
            .contains("not a parameter"));
        s.set_input("Fy", 3.0).unwrap();
        let fy = s.inputs.iter().find(|(v, _)| v.name == "Fy").unwrap();
        assert_eq!(fy.1, Signal::Constant(3.0));
        assert!(s.set_input("slices", 3.0).is_err());
        s.set_stop_time(0.01).unwrap();
        assert_eq!((s.n_steps, s.time(50)), (50, 0.01));
        assert!(s.set_stop_time(0.0).is_err());
    }

    #[test]
    fn errors_name_the_field() {
        let cases = [
            (r#"{"stop_time": 1, "step": 0}"#, "`step`"),
            (r#"{"stop_time": 1, "step": -1}"#, "`step`"),
            (r#"{"step": 0.1}"#, "stop_time"),
            (r#"{"stop_time": 1, "step": 0.1, "inputs": {"Fq": 1}}"#, "inputs.Fq"),
            (r#"{"stop_time": 1, "step": 0.1, "inputs": {"slices": 1}}"#, "inputs.slices"),
            (r#"{"stop_time": 1, "step": 0.1, "inputs": {"Fy": "x"}}"#, "inputs.Fy"),
            (
                r#"{"stop_time": 1, "step": 0.1, "inputs": {"Fy": {"time": [0, 0], "values": [1, 2]}}}"#,
                "inputs.Fy.time",
            ),
            (
                r#"{"stop_time": 1, "step": 0.1, "inputs": {"Fy": {"time": [0, 1], "values": [1]}}}"#,
                "inputs.Fy",
            ),
            (
                r#"{"stop_time": 1, "step": 0.1, "inputs": {"Fy": {"time": [0, "a"], "values": [1, 2]}}}"#,
                "inputs.Fy.time[1]",
            ),
            (
                r#"{"stop_time": 1, "step": 0.1, "parameters": {"slices": 2.5}}"#,
                "parameters.slices",
            ),
            (
                r#"{"stop_time": 1, "step": 0.1, "parameters": {"skewModel": 1}}"#,
                "parameters.skewModel",
            ),
            (
                r#"{"stop_time": 1, "step": 0.1, "parameters": {"roller[18].dD": 0}}"#,
                "parameters.roller[18].dD",
            ),
            (r#"{"stop_time": 1, "step": 0.1, "parameters": {"mu": true}}"#, "parameters.mu"),
            (r#"{"stop_time": 1, "step": 0.1, "outputs": ["nope"]}"#, "outputs[0]"),
            (r#"{"stop_time": 1, "step": 0.1, "bearing": "NOPE"}"#, "bearing"),
            (r#"{"stop_time": 1, "step": 0.1, "stepsize": 1}"#, "stepsize"),
        ];
        for (text, needle) in cases {
            let e = parse(text).expect_err(text);
            assert!(e.contains(needle), "{text}: error `{e}` does not name {needle}");
        }
    }
}
