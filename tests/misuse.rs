//! Robustness against misuse, through the FMU's C ABI in process and through
//! `Simulation`:
//! - every FMI function called in every reachable state, against the allowed-state table of
//!   the FMI 2.0 standard as the Reference FMUs implement it (`fmi2Functions.c`);
//! - NaN, infinities, negative and absurd values in every parameter and input, iterated from
//!   `modelDescription/variables.json`, and invalid enumeration values;
//! - hostile bearing files: every field removed or given the wrong type, absurd geometry,
//!   deep nesting, very long strings, huge counts; resource locations that do not exist;
//! - 16 instances on parallel threads against one, and FMU states serialized in every state
//!   and restored into other instances, all bitwise.
//!
//! The value sweeps, the parallel instances and the FMU states run at fidelity 0 and again at
//! fidelity 2 (the quasi-dynamic model: its own state, balance and refusals), on the smallest
//! preset where the fidelity-0 sweep takes two.
//!
//! tests/fmi_abi.rs covers the individual illegal calls with their messages; this file is
//! the systematic sweep.
#![cfg(all(target_os = "linux", any(target_arch = "x86_64", target_arch = "aarch64")))]

#[allow(dead_code)]
#[path = "../src/cli/stress/matrix.rs"]
mod matrix;

use matrix::Fmu;
use std::ffi::c_char;
use std::path::PathBuf;
use std::ptr;
use std::sync::OnceLock;
use trb::bearing::{Bearing, PRESETS};
use trb::fmi::*;
use trb::simulation::Simulation;
use trb::variables as var;

/// The preset most tests use: small and fast (23 rollers, 20 slices, 1000 rpm).
const PRESET: &str = "32008";

fn scratch() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("misuse")
}

fn uri(preset: &str) -> &'static str {
    static URIS: OnceLock<Vec<(String, String)>> = OnceLock::new();
    let all = URIS.get_or_init(|| {
        PRESETS
            .iter()
            .map(|(n, _)| (n.to_string(), matrix::resources_for(&scratch(), n).1))
            .collect()
    });
    &all.iter().find(|(n, _)| n == preset).expect("a preset").1
}

fn bearing(preset: &str) -> Bearing {
    Bearing::preset(preset).unwrap()
}

fn fmu(preset: &str) -> Fmu {
    Fmu::instantiate("misuse", &bearing(preset), uri(preset)).unwrap()
}

// ---------------------------------------------------------------------------------------
// 1. Every function in every state
// ---------------------------------------------------------------------------------------

/// The co-simulation states of FMI 2.0 this FMU can be in (it never returns fmi2Pending, so
/// StepInProgress and StepCanceled are unreachable), with their bit in the serialized state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum S {
    Instantiated = 1,
    InitializationMode = 2,
    StepComplete = 4,
    StepFailed = 16,
    Terminated = 64,
    Error = 128,
}

const STATES: [S; 6] = [
    S::Instantiated,
    S::InitializationMode,
    S::StepComplete,
    S::StepFailed,
    S::Terminated,
    S::Error,
];

/// Allowed states of each function, as in the Reference FMUs' fmi2Functions.c (masks of
/// the co-simulation states), written out here independently of src/fmi/machine.rs.
fn allowed(function: &str) -> &'static [S] {
    use S::*;
    const ALL: &[S] = &[Instantiated, InitializationMode, StepComplete, StepFailed, Terminated, Error];
    const GET: &[S] = &[InitializationMode, StepComplete, StepFailed, Terminated, Error];
    const SET: &[S] = &[Instantiated, InitializationMode, StepComplete];
    const STATUS: &[S] = &[StepComplete, StepFailed, Terminated];
    match function {
        "fmi2SetDebugLogging"
        | "fmi2Reset"
        | "fmi2GetFMUstate"
        | "fmi2SetFMUstate"
        | "fmi2FreeFMUstate"
        | "fmi2SerializedFMUstateSize"
        | "fmi2SerializeFMUstate"
        | "fmi2DeSerializeFMUstate" => ALL,
        "fmi2SetupExperiment" | "fmi2EnterInitializationMode" => &[Instantiated],
        "fmi2ExitInitializationMode" => &[InitializationMode],
        "fmi2Terminate" => &[StepComplete, StepFailed],
        "fmi2GetReal" | "fmi2GetInteger" | "fmi2GetBoolean" | "fmi2GetString" | "fmi2GetDirectionalDerivative" => GET,
        "fmi2SetReal" | "fmi2SetInteger" | "fmi2SetBoolean" | "fmi2SetString" | "fmi2SetRealInputDerivatives" => SET,
        "fmi2GetRealOutputDerivatives" => &[StepComplete, StepFailed, Terminated, Error],
        "fmi2DoStep" => &[StepComplete],
        "fmi2CancelStep" => &[],
        "fmi2GetStatus" | "fmi2GetRealStatus" | "fmi2GetIntegerStatus" | "fmi2GetBooleanStatus" | "fmi2GetStringStatus" => STATUS,
        other => panic!("no state table entry for {other}"),
    }
}

/// Serialized FMU state of a 32008 instance in state `s`.
fn serialized_in(s: S) -> Vec<c_char> {
    serialized_at(s, 0)
}

/// An FMU instance of `preset` at `fidelity` (set before anything else).
fn fmu_at(preset: &str, fidelity: i32) -> Fmu {
    let f = fmu(preset);
    if fidelity != 0 {
        let vr = var::FIDELITY;
        assert_eq!(unsafe { fmi2SetInteger(f.component(), &vr, 1, &fidelity) }, FMI2_OK);
    }
    f
}

/// Serialized FMU state of a 32008 instance at `fidelity` in state `s`.
fn serialized_at(s: S, fidelity: i32) -> Vec<c_char> {
    let f = fmu_at(PRESET, fidelity);
    let c = f.component();
    unsafe {
        if s != S::Instantiated {
            assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), FMI2_OK);
            assert_eq!(fmi2EnterInitializationMode(c), FMI2_OK);
        }
        if !matches!(s, S::Instantiated | S::InitializationMode) {
            assert_eq!(fmi2ExitInitializationMode(c), FMI2_OK, "{:?}", f.take_log());
        }
        match s {
            S::StepFailed => {
                // No axial force at speed: the cone is not seated, the step is discarded.
                let (vr, v) = (var::FX, 0.0);
                assert_eq!(fmi2SetReal(c, &vr, 1, &v), FMI2_OK);
                assert_eq!(fmi2DoStep(c, 0.0, 1e-3, 1), FMI2_DISCARD, "{:?}", f.take_log());
            }
            S::Terminated => assert_eq!(fmi2Terminate(c), FMI2_OK),
            S::Error => assert_eq!(fmi2DoStep(c, 0.0, -1.0, 1), FMI2_ERROR),
            _ => {}
        }
    }
    let bytes = serialize_now(c);
    assert_eq!(bytes[8] as u8, s as u8, "state byte of the serialized state");
    bytes
}

/// The serialized FMU state of `c` now (the state handle is freed again).
fn serialize_now(c: Fmi2Component) -> Vec<c_char> {
    unsafe {
        let mut state: Fmi2FmuState = ptr::null_mut();
        assert_eq!(fmi2GetFMUstate(c, &mut state), FMI2_OK);
        let mut size = 0;
        assert_eq!(fmi2SerializedFMUstateSize(c, state, &mut size), FMI2_OK);
        let mut bytes = vec![0 as c_char; size];
        assert_eq!(fmi2SerializeFMUstate(c, state, bytes.as_mut_ptr(), size), FMI2_OK);
        assert_eq!(fmi2FreeFMUstate(c, &mut state), FMI2_OK);
        bytes
    }
}

/// Put `c` into the serialized state `bytes`; returns the FMU state handle it keeps.
fn restore(c: Fmi2Component, bytes: &[c_char]) -> Fmi2FmuState {
    let mut own: Fmi2FmuState = ptr::null_mut();
    unsafe {
        assert_eq!(fmi2DeSerializeFMUstate(c, bytes.as_ptr(), bytes.len(), &mut own), FMI2_OK);
        assert_eq!(fmi2SetFMUstate(c, own), FMI2_OK);
    }
    own
}

/// The state-machine state of `c`, read from a fresh serialized FMU state.
fn state_of(c: Fmi2Component) -> u8 {
    serialize_now(c)[8] as u8
}

/// One call with valid arguments, on instance `c` holding FMU state `own`; `bytes` is a
/// serialized state of the same bearing.
type Call = fn(Fmi2Component, &mut Fmi2FmuState, &[c_char]) -> Fmi2Status;

/// Every function that takes an instance, called with valid arguments, and the status it
/// returns when the state allows it.
fn calls() -> Vec<(&'static str, Call, fn(S) -> Fmi2Status)> {
    fn ok(_: S) -> Fmi2Status {
        FMI2_OK
    }
    fn error(_: S) -> Fmi2Status {
        FMI2_ERROR
    }
    fn discard(_: S) -> Fmi2Status {
        FMI2_DISCARD
    }
    /// Fixed parameters may be set before initialization only.
    fn fixed(s: S) -> Fmi2Status {
        if s == S::StepComplete {
            FMI2_ERROR
        } else {
            FMI2_OK
        }
    }
    unsafe {
        vec![
            ("fmi2SetDebugLogging", |c, _, _| fmi2SetDebugLogging(c, 1, 0, ptr::null()), ok),
            ("fmi2SetupExperiment", |c, _, _| fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), ok),
            ("fmi2EnterInitializationMode", |c, _, _| fmi2EnterInitializationMode(c), ok),
            ("fmi2ExitInitializationMode", |c, _, _| fmi2ExitInitializationMode(c), ok),
            ("fmi2Terminate", |c, _, _| fmi2Terminate(c), ok),
            ("fmi2Reset", |c, _, _| fmi2Reset(c), ok),
            ("fmi2GetReal", |c, _, _| fmi2GetReal(c, &var::QO_MAX, 1, &mut 0.0), ok),
            ("fmi2GetInteger", |c, _, _| fmi2GetInteger(c, &var::LOADED_ROLLERS, 1, &mut 0), ok),
            ("fmi2GetBoolean", |c, _, _| fmi2GetBoolean(c, &var::GYROSCOPIC, 1, &mut 0), ok),
            ("fmi2GetString", |c, _, _| fmi2GetString(c, ptr::null(), 0, ptr::null_mut()), ok),
            ("fmi2SetReal", |c, _, _| fmi2SetReal(c, &var::FY, 1, &100.0), ok),
            ("fmi2SetInteger", |c, _, _| fmi2SetInteger(c, &var::SLICES, 1, &10), fixed),
            ("fmi2SetBoolean", |c, _, _| fmi2SetBoolean(c, &var::GYROSCOPIC, 1, &0), fixed),
            ("fmi2SetString", |c, _, _| fmi2SetString(c, ptr::null(), 0, ptr::null()), ok),
            ("fmi2GetFMUstate", |c, _, _| fmi2GetFMUstate(c, &mut ptr::null_mut()), ok),
            ("fmi2SetFMUstate", |c, own, _| fmi2SetFMUstate(c, *own), ok),
            ("fmi2FreeFMUstate", |c, own, _| fmi2FreeFMUstate(c, own), ok),
            (
                "fmi2SerializedFMUstateSize",
                |c, own, _| fmi2SerializedFMUstateSize(c, *own, &mut 0),
                ok,
            ),
            (
                "fmi2SerializeFMUstate",
                |c, own, b| fmi2SerializeFMUstate(c, *own, vec![0; b.len()].as_mut_ptr(), b.len()),
                ok,
            ),
            (
                "fmi2DeSerializeFMUstate",
                |c, _, b| fmi2DeSerializeFMUstate(c, b.as_ptr(), b.len(), &mut ptr::null_mut()),
                ok,
            ),
            (
                "fmi2GetDirectionalDerivative",
                |c, _, _| fmi2GetDirectionalDerivative(c, &var::QO_MAX, 1, &var::FY, 1, &1.0, &mut 0.0),
                error,
            ),
            (
                "fmi2SetRealInputDerivatives",
                |c, _, _| fmi2SetRealInputDerivatives(c, &var::FY, 1, &1, &1.0),
                ok,
            ),
            (
                "fmi2GetRealOutputDerivatives",
                |c, _, _| fmi2GetRealOutputDerivatives(c, &var::QO_MAX, 1, &1, &mut 0.0),
                error,
            ),
            (
                "fmi2DoStep",
                |c, _, _| {
                    let mut t = 0.0;
                    fmi2GetRealStatus(c, FMI2_LAST_SUCCESSFUL_TIME, &mut t);
                    fmi2DoStep(c, t, 1e-3, 1)
                },
                ok,
            ),
            ("fmi2CancelStep", |c, _, _| fmi2CancelStep(c), error),
            ("fmi2GetStatus", |c, _, _| fmi2GetStatus(c, FMI2_DO_STEP_STATUS, &mut 0), discard),
            (
                "fmi2GetRealStatus",
                |c, _, _| fmi2GetRealStatus(c, FMI2_LAST_SUCCESSFUL_TIME, &mut 0.0),
                ok,
            ),
            (
                "fmi2GetIntegerStatus",
                |c, _, _| fmi2GetIntegerStatus(c, FMI2_LAST_SUCCESSFUL_TIME, &mut 0),
                discard,
            ),
            (
                "fmi2GetBooleanStatus",
                |c, _, _| fmi2GetBooleanStatus(c, FMI2_TERMINATED, &mut 0),
                ok,
            ),
            (
                "fmi2GetStringStatus",
                |c, _, _| fmi2GetStringStatus(c, FMI2_PENDING_STATUS, &mut ptr::null()),
                discard,
            ),
        ]
    }
}

#[test]
fn every_function_in_every_state_follows_the_fmi2_state_table() {
    let calls = calls();
    assert_eq!(
        calls.len() + 4,
        EXPORTED.len(),
        "every export but GetTypesPlatform, GetVersion, Instantiate, FreeInstance"
    );
    let serialized: Vec<(S, Vec<c_char>)> = STATES.iter().map(|s| (*s, serialized_in(*s))).collect();
    let mut checked = 0;
    for (s, bytes) in &serialized {
        for (name, call, expected) in &calls {
            // A fresh instance put into state `s` by restoring the serialized state.
            let f = fmu(PRESET);
            let c = f.component();
            let mut own = restore(c, bytes);
            assert_eq!(state_of(c), *s as u8);
            f.take_log();
            let status = call(c, &mut own, bytes);
            let log = f.take_log();
            let is_allowed = allowed(name).contains(s);
            let want = if is_allowed { expected(*s) } else { FMI2_ERROR };
            assert_eq!(status, want, "{name} in {s:?} (allowed: {is_allowed}); log {log:?}");
            if !is_allowed {
                assert!(
                    log.iter()
                        .any(|(st, m)| *st == FMI2_ERROR && m.contains(name) && m.contains("called in state")),
                    "{name} in {s:?}: no clear error logged: {log:?}"
                );
                assert_eq!(state_of(c), *s as u8, "{name} in {s:?} was refused but changed the state");
            } else if status != FMI2_OK {
                assert!(
                    log.iter().any(|(st, m)| *st == status && m.contains(name)),
                    "{name} in {s:?}: status {status} without a message naming the function: {log:?}"
                );
            }
            checked += 1;
        }
    }
    assert_eq!(checked, STATES.len() * calls.len());
}

#[test]
fn platform_and_version_and_free_work_in_every_state() {
    for s in STATES {
        let bytes = serialized_in(s);
        let f = fmu(PRESET);
        let c = f.component();
        restore(c, &bytes);
        assert!(!fmi2GetTypesPlatform().is_null() && !fmi2GetVersion().is_null());
        // Dropping `f` frees the instance, and with it the FMU state still allocated.
    }
}

// ---------------------------------------------------------------------------------------
// 2. Bad values in every parameter and input, from modelDescription/variables.json
// ---------------------------------------------------------------------------------------

#[derive(Debug)]
struct Row {
    name: String,
    vr: u32,
    ty: String,
    causality: String,
    per_roller: bool,
    min: Option<f64>,
    max: Option<f64>,
}

fn variables_json() -> Vec<Row> {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/modelDescription/variables.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["variables"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| Row {
            name: r["name"].as_str().unwrap().to_string(),
            vr: r["vr"].as_u64().unwrap() as u32,
            ty: r["type"].as_str().unwrap().to_string(),
            causality: r["causality"].as_str().unwrap().to_string(),
            per_roller: r["per_roller"].as_bool().unwrap_or(false),
            min: r["min"].as_f64(),
            max: r["max"].as_f64(),
        })
        .collect()
}

/// The (value reference, name) pairs a row gives in a bearing of `z` rollers: scalars, and
/// the first and last roller of per-roller rows.
fn instances_of(row: &Row, z: usize) -> Vec<(u32, String)> {
    if row.per_roller {
        [1, z]
            .iter()
            .map(|j| (row.vr + *j as u32 - 1, row.name.replace("{j}", &j.to_string())))
            .collect()
    } else {
        vec![(row.vr, row.name.clone())]
    }
}

const BAD_REALS: [f64; 9] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    -1.0,
    -1e300,
    1e300,
    f64::MAX,
    -f64::MIN_POSITIVE,
    5e-324,
];

/// The outcome of setting one value and then initializing and stepping a Simulation at
/// `fidelity` (set first: a bad value of `fidelity` itself replaces it): `Ok(true)` where the
/// step succeeded, `Ok(false)` where the value was refused clearly.
fn bad_value_on_simulation(preset: &str, fidelity: i32, vr: u32, name: &str, value: matrix::Value) -> Result<bool, String> {
    let mut sim = Simulation::new(bearing(preset));
    sim.set_integer(var::FIDELITY, fidelity).expect("a fidelity");
    let set = match value {
        matrix::Value::Real(x) => sim.set_real(vr, x),
        matrix::Value::Integer(i) => sim.set_integer(vr, i),
        matrix::Value::Boolean(b) => sim.set_boolean(vr, b),
    };
    let clear = |m: String| -> Result<bool, String> {
        let short = name.split('[').next().unwrap();
        if m.contains(short) || matrix::clarity(&m).is_ok() {
            Ok(false)
        } else {
            Err(format!("{name} = {value:?}: unclear message: {m}"))
        }
    };
    if let Err(e) = set {
        return clear(e.to_string());
    }
    let result = sim.initialize(0.0).and_then(|_| sim.do_step(0.0, 1e-3));
    let out = sim.last_outputs();
    if !out.all_finite() {
        return Err(format!("{name} = {value:?}: non-finite outputs"));
    }
    match result {
        Ok(_) => Ok(true),
        Err(e) => clear(e.to_string()),
    }
}

#[test]
fn every_parameter_and_input_takes_bad_values_without_crash_or_nan() {
    bad_values_on_simulation(&["32008", "CRB-TRILOBE"], 0);
}

#[test]
fn every_parameter_and_input_takes_bad_values_at_fidelity_2_without_crash_or_nan() {
    bad_values_on_simulation(&[PRESET], 2);
}

/// Every bad value of every parameter and input on `presets` at `fidelity`
/// ([`bad_value_on_simulation`]).
fn bad_values_on_simulation(presets: &[&'static str], fidelity: i32) {
    let rows = variables_json();
    let settable: Vec<&Row> = rows.iter().filter(|r| r.causality != "output").collect();
    assert!(settable.len() >= 25, "only {} parameters and inputs", settable.len());
    let mut work = Vec::new();
    for &preset in presets {
        let z = bearing(preset).roller_count;
        for row in &settable {
            for (vr, name) in instances_of(row, z) {
                // The table and the compiled-in variables agree.
                let (found, _) = var::find(&name, z).unwrap_or_else(|| panic!("{name} of variables.json unknown to the FMU"));
                assert_eq!(found, vr, "{name}");
                let values: Vec<matrix::Value> = match row.ty.as_str() {
                    "Real" => BAD_REALS.iter().map(|v| matrix::Value::Real(*v)).collect(),
                    "Integer" => {
                        let (lo, hi) = (row.min.unwrap_or(i32::MIN as f64) as i64, row.max.unwrap_or(i32::MAX as f64) as i64);
                        [i32::MIN as i64, -1, lo - 1, lo, hi, hi + 1, i32::MAX as i64]
                            .iter()
                            .filter(|v| (i32::MIN as i64..=i32::MAX as i64).contains(*v))
                            .map(|v| matrix::Value::Integer(*v as i32))
                            .collect()
                    }
                    "Boolean" => vec![matrix::Value::Boolean(true), matrix::Value::Boolean(false)],
                    other => panic!("{name}: type {other}"),
                };
                for v in values {
                    work.push((preset, vr, name.clone(), v));
                }
            }
        }
    }
    let threads = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1);
    let results = matrix::parallel_map(&work, threads, |(preset, vr, name, v)| {
        std::panic::catch_unwind(|| bad_value_on_simulation(preset, fidelity, *vr, name, *v))
            .unwrap_or_else(|_| Err(format!("{preset} {name} = {v:?}: panic")))
    });
    // F3 of docs/robustness.md (reported): one slice has no equilibrium on a tapered bearing.
    let known = |f: &String| f.starts_with("slices = Integer(1): unclear message: no quasi-static equilibrium");
    let stepped = results.iter().filter(|r| matches!(r, Ok(true))).count();
    let failures: Vec<String> = results.into_iter().filter_map(|r| r.err()).filter(|f| !known(f)).collect();
    assert!(
        failures.is_empty(),
        "{} of {} bad values mishandled:\n{}",
        failures.len(),
        work.len(),
        failures.join("\n")
    );
    eprintln!(
        "{} bad values in {} parameters and inputs of {} presets at fidelity {fidelity}: all handled, {stepped} of them taken and stepped",
        work.len(),
        settable.len(),
        presets.len()
    );
    // the values a variable's range admits (-1, MIN_POSITIVE, the ends of the Integer ranges,
    // Booleans) are taken and stepped: the sweep exercises the fidelity's model, not only the
    // setters' checks
    assert!(stepped * 10 > work.len(), "only {stepped} of {} values stepped", work.len());
}

#[test]
fn bad_values_through_the_fmu_give_error_status_and_finite_outputs() {
    bad_values_through_the_fmu(0);
}

#[test]
fn bad_values_through_the_fmu_at_fidelity_2_give_error_status_and_finite_outputs() {
    bad_values_through_the_fmu(2);
}

/// Every Real parameter and input of a 32008 instance at `fidelity` set to NaN, inf and
/// -1e300, then initialized and stepped: statuses up to fmi2Error, finite outputs, and a
/// message for every status that is not OK.
fn bad_values_through_the_fmu(fidelity: i32) {
    let z = bearing(PRESET).roller_count;
    let (reals, _) = matrix::output_vrs(z);
    for row in variables_json().iter().filter(|r| r.causality != "output" && r.ty == "Real") {
        for (vr, name) in instances_of(row, z) {
            for bad in [f64::NAN, f64::INFINITY, -1e300] {
                let f = fmu_at(PRESET, fidelity);
                let c = f.component();
                unsafe {
                    let set = fmi2SetReal(c, &vr, 1, &bad);
                    assert!(set == FMI2_OK || set == FMI2_ERROR, "{name}");
                    fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0);
                    fmi2EnterInitializationMode(c);
                    let exit = fmi2ExitInitializationMode(c);
                    let step = fmi2DoStep(c, 0.0, 1e-3, 1);
                    let mut values = vec![0.0; reals.len()];
                    fmi2GetReal(c, reals.as_ptr(), reals.len(), values.as_mut_ptr());
                    assert!(values.iter().all(|v| v.is_finite()), "{name} = {bad}: non-finite outputs");
                    let log = f.take_log();
                    if set != FMI2_OK || exit != FMI2_OK || step != FMI2_OK {
                        let short = name.split('[').next().unwrap();
                        assert!(
                            log.iter()
                                .any(|(s, m)| *s >= FMI2_DISCARD && (m.contains(short) || matrix::clarity(m).is_ok())),
                            "{name} = {bad}: statuses {set}/{exit}/{step} without a clear message: {log:?}"
                        );
                    }
                    assert!(set <= FMI2_ERROR && exit <= FMI2_ERROR && step <= FMI2_ERROR);
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// 3. Hostile bearing files and resource locations
// ---------------------------------------------------------------------------------------

/// Every path to a leaf or object of `v` (object keys only).
fn paths(v: &serde_json::Value, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    if let Some(map) = v.as_object() {
        for (k, child) in map {
            prefix.push(k.clone());
            out.push(prefix.clone());
            paths(child, prefix, out);
            prefix.pop();
        }
    }
}

fn at_mut<'a>(v: &'a mut serde_json::Value, path: &[String]) -> &'a mut serde_json::Value {
    path.iter().fold(v, |v, k| &mut v[k.as_str()])
}

/// Parse `text`; a refusal must be an error naming something (not a panic).
fn parse(text: &str) -> Result<Bearing, String> {
    match std::panic::catch_unwind(|| Bearing::from_json(text)) {
        Ok(Ok(b)) => Ok(b),
        Ok(Err(e)) => Err(e.to_string()),
        Err(_) => panic!("Bearing::from_json panicked on {}", &text[..text.len().min(200)]),
    }
}

#[test]
fn every_field_removed_or_mistyped_is_refused_naming_the_field() {
    use serde_json::json;
    let mut n = 0;
    for (preset, text) in PRESETS {
        let original: serde_json::Value = serde_json::from_str(text).unwrap();
        let mut all = Vec::new();
        paths(&original, &mut Vec::new(), &mut all);
        for path in &all {
            let field = path.last().unwrap();
            // Removed: fine when the field is optional, else refused naming it.
            let mut v = original.clone();
            at_mut(&mut v, &path[..path.len() - 1]).as_object_mut().unwrap().remove(field);
            if let Err(e) = parse(&v.to_string()) {
                assert!(
                    e.contains(field.as_str()) || e.contains(&path[0]),
                    "{preset}: removing {path:?}: {e}"
                );
            }
            n += 1;
            // Wrong types and absurd values.
            for bad in [
                json!("text"),
                json!(null),
                json!([1, 2]),
                json!({"x": 1}),
                json!(true),
                json!(-1),
                json!(0),
                json!(1e308),
                json!(-1e308),
                json!(4294967296u64),
                json!(i64::MIN),
            ] {
                let mut v = original.clone();
                *at_mut(&mut v, path) = bad.clone();
                if let Err(e) = parse(&v.to_string()) {
                    // The field itself, or (a consistency check between fields) the field
                    // where the inconsistency shows.
                    let named = path.iter().any(|p| e.contains(p.as_str())) || e.contains("field `");
                    assert!(named, "{preset}: {path:?} = {bad}: error does not name a field: {e}");
                } else if let Ok(b) = parse(&v.to_string()) {
                    // Accepted (free text, optional numbers): the model must still be safe.
                    let mut sim = Simulation::new(b);
                    let _ = sim.initialize(0.0);
                    assert!(sim.last_outputs().all_finite(), "{preset}: {path:?} = {bad}");
                }
                n += 1;
            }
        }
    }
    eprintln!("{n} mutated bearing files");
}

#[test]
fn absurd_geometry_and_hostile_text_are_refused_clearly() {
    let base: serde_json::Value = serde_json::from_str(PRESETS[0].1).unwrap();
    let with = |edits: &[(&str, serde_json::Value)]| {
        let mut v = base.clone();
        for (path, value) in edits {
            let path: Vec<String> = path.split('.').map(String::from).collect();
            *at_mut(&mut v, &path) = value.clone();
        }
        v.to_string()
    };
    use serde_json::json;
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "roller larger than the bearing",
            with(&[("rollers.mean_diameter_mm", json!(500.0))]),
            "rollers",
        ),
        (
            "roller longer than the bearing",
            with(&[("rollers.length_mm", json!(1e6))]),
            "rollers",
        ),
        ("zero rollers", with(&[("rollers.count", json!(0))]), "rollers.count"),
        (
            "cylindrical roller longer than the bearing (fuzzer find)",
            PRESETS[3].1.replace("\"length_mm\": 9.0", "\"length_mm\": 1e308"),
            "rollers.length_mm",
        ),
        ("two rollers", with(&[("rollers.count", json!(2))]), "rollers.count"),
        (
            "huge roller count",
            with(&[("rollers.count", json!(1_000_000_000))]),
            "rollers.count",
        ),
        ("roller count beyond i64", with(&[("rollers.count", json!(1e30))]), "rollers.count"),
        ("fractional roller count", with(&[("rollers.count", json!(17.5))]), "rollers.count"),
        (
            "too many rollers for the pitch circle",
            with(&[("rollers.count", json!(400))]),
            "rollers.count",
        ),
        (
            "bore larger than the outside",
            with(&[("envelope.bore_mm", json!(300.0))]),
            "envelope",
        ),
        (
            "pitch outside the envelope",
            with(&[("pitch_diameter_mm", json!(10.0))]),
            "pitch_diameter_mm",
        ),
        ("cup angle 89 deg", with(&[("cup_angle_deg", json!(89.0))]), "cup_angle_deg"),
        ("negative modulus", with(&[("materials.roller.E_GPa", json!(-201.0))]), "E_GPa"),
        ("slices 0", with(&[("solver.slices", json!(0))]), "slices"),
        ("slices 1e9", with(&[("solver.slices", json!(1_000_000_000))]), "slices"),
        ("unknown contact law", with(&[("contact_law", json!("hertzian"))]), "contact_law"),
        ("unknown kind", with(&[("kind", json!("spherical"))]), "kind"),
        (
            "unknown lubrication",
            with(&[("friction.model", json!("grease"))]),
            "friction.model",
        ),
        ("unknown preload", with(&[("operating_point.preload", json!("spring"))]), "preload"),
        ("lobes -1", with(&[("raceway.outer_lobes", json!(-1))]), "outer_lobes"),
        ("empty name", with(&[("name", json!(""))]), "name"),
        (
            "number too large for f64",
            PRESETS[0].1.replace("177.91", "1e999"),
            "pitch_diameter_mm",
        ),
        (
            "deeply nested junk",
            format!("{}{}", "[".repeat(100_000), "]".repeat(100_000)),
            "invalid bearing",
        ),
        (
            "deeply nested junk in a field",
            with(&[("source", json!(0))]).replace("\"source\":0", &format!("\"source\":{}1{}", "[".repeat(5000), "]".repeat(5000))),
            "source",
        ),
        (
            "unknown field",
            with(&[("rollers.count", json!(17))]).replacen('{', "{\"evil\":1,", 1),
            "evil",
        ),
        (
            "not UTF-8 text",
            String::from_utf8_lossy(&[0xff, 0xfe, b'{']).into_owned(),
            "invalid bearing",
        ),
        ("empty", String::new(), "invalid bearing"),
        ("a number", "42".into(), "invalid bearing"),
        ("truncated", PRESETS[0].1[..PRESETS[0].1.len() / 2].to_string(), "invalid bearing"),
    ];
    for (what, text, needle) in &cases {
        let e = parse(text).expect_err(what);
        assert!(e.contains(needle), "{what}: error does not mention {needle:?}: {e}");
        assert!(e.len() < 2000, "{what}: error message of {} bytes", e.len());
    }
    // A 10 MB name is accepted as text (it is free text) and handled.
    let long = with(&[("name", json!("x".repeat(10_000_000)))]);
    let b = parse(&long).expect("a long name is still a name");
    assert_eq!(b.name.len(), 10_000_000);
    let mut sim = Simulation::new(b);
    sim.initialize(0.0).unwrap();

    // Through the FMU: a hostile resources/bearing.json makes fmi2Instantiate return NULL
    // with the reason logged.
    for (what, text, needle) in cases.iter().take(6) {
        let dir = scratch().join(format!("hostile-{}", what.replace(' ', "-"))).join("resources");
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("bearing.json"), text).unwrap();
        let uri = url::Url::from_directory_path(&dir).unwrap().to_string();
        match Fmu::instantiate("hostile", &bearing("TRB130x230"), &uri) {
            Ok(_) => panic!("{what}: instantiated"),
            Err(e) => assert!(e.contains(needle) && e.contains("bearing.json"), "{what}: {e}"),
        }
    }
}

#[test]
fn resource_locations_that_do_not_exist_are_reported() {
    let b = bearing("TRB130x230");
    // A directory that does not exist: the compiled-in default bearing, with a warning
    // naming the path (the GUID still has to match it).
    let f = Fmu::instantiate("missing", &b, "file:///no/such/directory/resources").unwrap();
    let log = f.take_log();
    assert!(
        log.iter()
            .any(|(s, m)| *s == FMI2_WARNING && m.contains("/no/such/directory/resources")),
        "{log:?}"
    );
    // With the GUID of another bearing the fallback cannot be used: NULL and why.
    let e = Fmu::instantiate("missing", &bearing("32008"), "file:///no/such/directory/resources")
        .err()
        .unwrap();
    assert!(e.contains("fmuGUID") && e.contains("no/such/directory"), "{e}");
    // Not a URI, another scheme, another host, a file instead of a directory.
    for (loc, needle) in [
        ("relative/path", "not a file URI"),
        ("http://example.com/resources", "not a file URI"),
        ("file://otherhost/resources", "does not name a local directory"),
        ("file:///%zz", "bearing.json"),
    ] {
        match Fmu::instantiate("bad-uri", &b, loc) {
            Ok(f) => {
                let log = f.take_log();
                assert!(log.iter().any(|(_, m)| m.contains(needle)), "{loc}: {log:?}");
            }
            Err(e) => assert!(e.contains(needle), "{loc}: {e}"),
        }
    }
    let file = scratch().join("a-file");
    std::fs::create_dir_all(scratch()).unwrap();
    std::fs::write(&file, "x").unwrap();
    let loc = url::Url::from_file_path(&file).unwrap().to_string();
    let e = Fmu::instantiate("file", &b, &loc)
        .err()
        .expect("a file is not a resources directory");
    assert!(e.contains("bearing.json"), "{e}");
}

// ---------------------------------------------------------------------------------------
// 4. Concurrency and FMU states
// ---------------------------------------------------------------------------------------

/// A run with changing loads and speed through the C ABI at `fidelity`: the output bits
/// after each step.
fn run_bits(preset: &str, fidelity: i32, steps: usize) -> Vec<u64> {
    let f = fmu_at(preset, fidelity);
    let c = f.component();
    let z = bearing(preset).roller_count;
    let (reals, _) = matrix::output_vrs(z);
    let mut out = Vec::new();
    let mut values = vec![0.0; reals.len()];
    unsafe {
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), FMI2_OK);
        assert_eq!(fmi2EnterInitializationMode(c), FMI2_OK);
        assert_eq!(fmi2ExitInitializationMode(c), FMI2_OK);
        for k in 0..steps {
            let u = [2000.0 + 100.0 * k as f64, 5000.0, 5e-5 * (k as f64).sin(), 100.0 + k as f64];
            let vrs = [var::FY, var::FX, var::XI, var::SPEED];
            assert_eq!(fmi2SetReal(c, vrs.as_ptr(), 4, u.as_ptr()), FMI2_OK);
            assert_eq!(fmi2DoStep(c, k as f64 * 1e-3, 1e-3, 1), FMI2_OK, "{:?}", f.take_log());
            assert_eq!(fmi2GetReal(c, reals.as_ptr(), reals.len(), values.as_mut_ptr()), FMI2_OK);
            out.extend(values.iter().map(|v| v.to_bits()));
        }
    }
    out
}

#[test]
fn sixteen_instances_on_parallel_threads_agree_bitwise_with_one() {
    parallel_instances_agree(0);
}

#[test]
fn sixteen_instances_at_fidelity_2_on_parallel_threads_agree_bitwise_with_one() {
    parallel_instances_agree(2);
}

/// 16 instances of two presets at `fidelity` on parallel threads, each as the single one.
fn parallel_instances_agree(fidelity: i32) {
    let presets = ["32008", "TRB130x230"];
    let reference: Vec<Vec<u64>> = presets.iter().map(|p| run_bits(p, fidelity, 12)).collect();
    let results: Vec<(usize, Vec<u64>)> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..16)
            .map(|i| s.spawn(move || (i % 2, run_bits(presets[i % 2], fidelity, 12))))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for (i, (p, bits)) in results.iter().enumerate() {
        assert!(
            bits == &reference[*p],
            "thread {i} ({}) differs from the single instance",
            presets[*p]
        );
    }
}

#[test]
fn fmu_states_serialized_in_every_state_round_trip_bitwise_across_instances() {
    states_round_trip(0);
}

#[test]
fn fmu_states_at_fidelity_2_round_trip_bitwise_across_instances() {
    states_round_trip(2);
}

/// FMU states of a 32008 instance at `fidelity` serialized in every state, restored into 16
/// instances on parallel threads: each serializes it again to the same bytes, and stepping on
/// from a restored StepComplete state gives the same output bits every time.
fn states_round_trip(fidelity: i32) {
    for s in STATES {
        let bytes = serialized_at(s, fidelity);
        // Restore into 16 instances on parallel threads; each serializes it again.
        let again: Vec<Vec<c_char>> = std::thread::scope(|scope| {
            let handles: Vec<_> = (0..16)
                .map(|_| {
                    let bytes = &bytes;
                    scope.spawn(move || {
                        let f = fmu(PRESET);
                        let c = f.component();
                        restore(c, bytes);
                        serialize_now(c)
                    })
                })
                .collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        for (i, a) in again.iter().enumerate() {
            assert!(a == &bytes, "{s:?}: instance {i} serialized the restored state differently");
        }
    }
    // Continuing from a restored StepComplete state gives the same outputs as the original.
    let bytes = serialized_at(S::StepComplete, fidelity);
    let continue_from = |bytes: &[c_char]| {
        let f = fmu(PRESET);
        let c = f.component();
        let (reals, _) = matrix::output_vrs(bearing(PRESET).roller_count);
        let mut v = vec![0.0; reals.len()];
        restore(c, bytes);
        unsafe {
            // the state carries the fidelity into an instance of the default one
            let mut f_read = -1;
            assert_eq!(fmi2GetInteger(c, &var::FIDELITY, 1, &mut f_read), FMI2_OK);
            assert_eq!(f_read, fidelity);
            assert_eq!(fmi2SetReal(c, &var::FY, 1, &3000.0), FMI2_OK);
            assert_eq!(fmi2DoStep(c, 0.0, 1e-3, 1), FMI2_OK);
            assert_eq!(fmi2GetReal(c, reals.as_ptr(), reals.len(), v.as_mut_ptr()), FMI2_OK);
        }
        v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>()
    };
    let restored = continue_from(&bytes);
    assert_eq!(restored, continue_from(&bytes));
    // and the instance that was never serialized steps on to the same bits
    let f = fmu_at(PRESET, fidelity);
    let c = f.component();
    let (reals, _) = matrix::output_vrs(bearing(PRESET).roller_count);
    let mut v = vec![0.0; reals.len()];
    unsafe {
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), FMI2_OK);
        assert_eq!(fmi2EnterInitializationMode(c), FMI2_OK);
        assert_eq!(fmi2ExitInitializationMode(c), FMI2_OK);
        assert_eq!(fmi2SetReal(c, &var::FY, 1, &3000.0), FMI2_OK);
        assert_eq!(fmi2DoStep(c, 0.0, 1e-3, 1), FMI2_OK);
        assert_eq!(fmi2GetReal(c, reals.as_ptr(), reals.len(), v.as_mut_ptr()), FMI2_OK);
    }
    assert!(restored == v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>());
}
