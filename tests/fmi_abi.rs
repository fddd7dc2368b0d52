//! The FMI 2.0 Co-Simulation C ABI, called in-process through the exported functions.
//!
//! The test logger is an ordinary `extern "C" fn(env, name, status, category, message)`
//! transmuted to the variadic `fmi2CallbackLogger` type (stable Rust cannot define a
//! variadic function). The FMU passes the message as the format string and no variadic
//! arguments, and on the targets below a call through a variadic pointer with only fixed
//! arguments is ABI compatible with the non-variadic definition (x86_64 SysV only adds the
//! %al vector-register count, which a non-variadic callee ignores; aarch64 Linux passes
//! fixed arguments of variadic calls in the same registers).
#![cfg(all(target_os = "linux", any(target_arch = "x86_64", target_arch = "aarch64")))]

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::path::{Path, PathBuf};
use std::ptr;
use std::sync::{Mutex, OnceLock};
use trb::bearing::Bearing;
use trb::fmi::*;
use trb::model_description;
use trb::variables::{self as var, Causality, VarType};

// ---------------------------------------------------------------------------------------
// Allocation counting (per thread), to show the adapter adds no allocation on the hot path
// ---------------------------------------------------------------------------------------

struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

fn count_allocation() {
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

fn allocations() -> u64 {
    ALLOCATIONS.with(|c| c.get())
}

unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count_allocation();
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count_allocation();
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, p: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count_allocation();
        unsafe { System.realloc(p, layout, new_size) }
    }
    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

// ---------------------------------------------------------------------------------------
// Recording logger
// ---------------------------------------------------------------------------------------

#[derive(Debug, Clone)]
struct Record {
    env: usize,
    instance: String,
    status: c_int,
    category: String,
    message: String,
}

#[derive(Default)]
struct Log {
    records: Mutex<Vec<Record>>,
}

impl Log {
    fn env(&self) -> *mut c_void {
        self as *const Log as *mut c_void
    }
    fn records(&self) -> Vec<Record> {
        self.records.lock().unwrap().clone()
    }
    fn clear(&self) {
        self.records.lock().unwrap().clear();
    }
    /// Messages as printf would print them (`%%` -> `%`, `##` -> `#` undone as well).
    fn messages(&self) -> Vec<String> {
        self.records().into_iter().map(|r| unescape(&r.message)).collect()
    }
    fn contains(&self, needle: &str) -> bool {
        self.messages().iter().any(|m| m.contains(needle))
    }
    fn assert_logged(&self, needle: &str) {
        assert!(
            self.contains(needle),
            "no log message contains {needle:?}; got {:#?}",
            self.messages()
        );
    }
}

fn unescape(m: &str) -> String {
    m.replace("%%", "%").replace("##", "#")
}

/// Every `%` and `#` of a message passed to the logger is doubled.
fn assert_escaped(message: &str) {
    let rest = message.replace("%%", "").replace("##", "");
    assert!(
        !rest.contains('%') && !rest.contains('#'),
        "unescaped % or # in log message {message:?}"
    );
}

extern "C" fn record_message(env: *mut c_void, instance: *const c_char, status: c_int, category: *const c_char, message: *const c_char) {
    let text = |p: *const c_char| {
        if p.is_null() {
            "<NULL>".to_string()
        } else {
            unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
        }
    };
    let record = Record {
        env: env as usize,
        instance: text(instance),
        status,
        category: text(category),
        message: text(message),
    };
    assert_escaped(&record.message);
    let log = unsafe { &*(env as *const Log) };
    log.records.lock().unwrap().push(record);
}

fn logger() -> Fmi2CallbackLogger {
    let f: extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char) = record_message;
    // SAFETY: see the module documentation.
    unsafe { std::mem::transmute::<extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char), Fmi2CallbackLogger>(f) }
}

fn callbacks(log: &Log) -> Fmi2CallbackFunctions {
    Fmi2CallbackFunctions {
        logger: Some(logger()),
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: log.env(),
    }
}

// ---------------------------------------------------------------------------------------
// Resources and instances
// ---------------------------------------------------------------------------------------

fn default_guid() -> &'static str {
    static GUID: OnceLock<String> = OnceLock::new();
    GUID.get_or_init(|| model_description::guid(&Bearing::default_preset()))
}

fn preset_text() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/TRB130x230.json")).unwrap()
}

/// A fresh `<tmp>/<name>/resources` directory holding `bearing.json` (if given).
fn resource_dir(name: &str, bearing_json: Option<&str>) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fmi_abi").join(name).join("resources");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    if let Some(text) = bearing_json {
        std::fs::write(dir.join("bearing.json"), text).unwrap();
    }
    dir
}

fn file_uri(dir: &Path) -> String {
    let path = dir.to_str().unwrap();
    assert!(path.is_ascii() && !path.contains(['%', '#', '?', ' ']), "test paths are plain");
    format!("file://{path}")
}

fn default_resources() -> String {
    static URI: OnceLock<String> = OnceLock::new();
    URI.get_or_init(|| file_uri(&resource_dir("default", Some(&preset_text())))).clone()
}

struct Fmu {
    c: Fmi2Component,
    log: Box<Log>,
}

impl Drop for Fmu {
    fn drop(&mut self) {
        unsafe { fmi2FreeInstance(self.c) };
    }
}

/// fmi2Instantiate with these arguments: the instance (owning the log it reports to,
/// which outlives it) or, for NULL, the log of the refusal.
fn instantiate(
    name: Option<&str>,
    fmu_type: Fmi2Type,
    guid: Option<&str>,
    resources: Option<&str>,
    logging_on: bool,
) -> Result<Fmu, Box<Log>> {
    let log = Box::<Log>::default();
    let cb = callbacks(&log);
    let name = name.map(|s| CString::new(s).unwrap());
    let guid = guid.map(|s| CString::new(s).unwrap());
    let resources = resources.map(|s| CString::new(s).unwrap());
    let p = |s: &Option<CString>| s.as_ref().map_or(ptr::null(), |s| s.as_ptr());
    let c = unsafe { fmi2Instantiate(p(&name), fmu_type, p(&guid), p(&resources), &cb, FMI2_FALSE, logging_on as c_int) };
    if c.is_null() {
        Err(log)
    } else {
        Ok(Fmu { c, log })
    }
}

/// The log of an instantiation that must fail.
fn refused(result: Result<Fmu, Box<Log>>) -> Box<Log> {
    match result {
        Ok(_) => panic!("fmi2Instantiate should have returned NULL"),
        Err(log) => log,
    }
}

impl Fmu {
    fn new() -> Fmu {
        Fmu::with_resources(Some(&default_resources()))
    }

    fn with_resources(resources: Option<&str>) -> Fmu {
        instantiate(Some("bearing"), FMI2_CO_SIMULATION, Some(default_guid()), resources, false)
            .unwrap_or_else(|log| panic!("fmi2Instantiate returned NULL: {:#?}", log.messages()))
    }

    /// Instantiated -> StepComplete at t = 0 with stop time `stop`.
    fn initialized(stop: Option<f64>) -> Fmu {
        let fmu = Fmu::new();
        fmu.init(stop);
        fmu
    }

    fn init(&self, stop: Option<f64>) {
        assert_eq!(self.setup(0.0, stop), FMI2_OK);
        assert_eq!(unsafe { fmi2EnterInitializationMode(self.c) }, FMI2_OK);
        assert_eq!(unsafe { fmi2ExitInitializationMode(self.c) }, FMI2_OK, "{:#?}", self.log.messages());
    }

    fn setup(&self, start: f64, stop: Option<f64>) -> Fmi2Status {
        unsafe { fmi2SetupExperiment(self.c, FMI2_FALSE, 0.0, start, stop.is_some() as c_int, stop.unwrap_or(0.0)) }
    }

    fn set_real(&self, vr: u32, value: f64) -> Fmi2Status {
        unsafe { fmi2SetReal(self.c, &vr, 1, &value) }
    }

    fn set_integer(&self, vr: u32, value: i32) -> Fmi2Status {
        unsafe { fmi2SetInteger(self.c, &vr, 1, &value) }
    }

    fn get_reals(&self, vrs: &[u32]) -> (Fmi2Status, Vec<f64>) {
        let mut values = vec![f64::NAN; vrs.len()];
        let status = unsafe { fmi2GetReal(self.c, vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) };
        (status, values)
    }

    /// All Real outputs and Integer outputs, as bits, asserting OK.
    fn outputs(&self) -> Vec<u64> {
        let (reals, ints) = output_vrs();
        let (status, values) = self.get_reals(&reals);
        assert_eq!(status, FMI2_OK, "{:#?}", self.log.messages());
        let mut integers = vec![0; ints.len()];
        assert_eq!(
            unsafe { fmi2GetInteger(self.c, ints.as_ptr(), ints.len(), integers.as_mut_ptr()) },
            FMI2_OK
        );
        values
            .iter()
            .map(|v| v.to_bits())
            .chain(integers.iter().map(|&i| i as u64))
            .collect()
    }

    fn step(&self, t: f64, h: f64) -> Fmi2Status {
        unsafe { fmi2DoStep(self.c, t, h, FMI2_TRUE) }
    }

    fn time(&self) -> f64 {
        let mut t = f64::NAN;
        assert_eq!(unsafe { fmi2GetRealStatus(self.c, FMI2_LAST_SUCCESSFUL_TIME, &mut t) }, FMI2_OK);
        t
    }

    fn get_state(&self) -> Fmi2FmuState {
        let mut s: Fmi2FmuState = ptr::null_mut();
        assert_eq!(unsafe { fmi2GetFMUstate(self.c, &mut s) }, FMI2_OK);
        assert!(!s.is_null());
        s
    }
}

/// Value references of all Real outputs and all Integer outputs of the default bearing.
fn output_vrs() -> (Vec<u32>, Vec<u32>) {
    let z = Bearing::default_preset().roller_count;
    let all = var::expanded(z);
    let pick = |ty| {
        all.iter()
            .filter(|(_, _, r)| r.causality == Causality::Output && r.ty == ty)
            .map(|(vr, _, _)| *vr)
            .collect()
    };
    (pick(VarType::Real), pick(VarType::Integer))
}

/// A load case that gives the rollers something to do.
fn load(fmu: &Fmu, step: usize) {
    assert_eq!(fmu.set_real(var::FY, 20_000.0 + 500.0 * step as f64), FMI2_OK);
    assert_eq!(fmu.set_real(var::XI, 5e-5), FMI2_OK);
}

/// Step `n` times from the FMU's time with `h`, changing the load; outputs after each step.
fn run(fmu: &Fmu, n: usize, h: f64) -> Vec<Vec<u64>> {
    let mut out = Vec::new();
    for i in 0..n {
        load(fmu, i);
        let t = fmu.time();
        assert_eq!(fmu.step(t, h), FMI2_OK, "{:#?}", fmu.log.messages());
        out.push(fmu.outputs());
    }
    out
}

fn finite(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}

// ---------------------------------------------------------------------------------------
// Tests
// ---------------------------------------------------------------------------------------

#[test]
fn platform_and_version() {
    assert_eq!(unsafe { CStr::from_ptr(fmi2GetTypesPlatform()) }.to_str().unwrap(), "default");
    assert_eq!(unsafe { CStr::from_ptr(fmi2GetVersion()) }.to_str().unwrap(), "2.0");
}

#[test]
fn full_life_cycle_with_the_default_bearing() {
    let fmu = instantiate(
        Some("bearing #1"),
        FMI2_CO_SIMULATION,
        Some(default_guid()),
        Some(&default_resources()),
        true,
    )
    .unwrap_or_else(|log| panic!("{:#?}", log.messages()));
    assert_eq!(fmu.setup(0.0, Some(0.005)), FMI2_OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(fmu.c) }, FMI2_OK);
    assert_eq!(fmu.set_integer(var::SLICES, 20), FMI2_OK);
    assert_eq!(fmu.set_real(var::FY, 10_000.0), FMI2_OK);
    // Outputs are available in initialization mode (direct feedthrough).
    let (status, torque) = fmu.get_reals(&[var::FRICTION_TORQUE]);
    assert_eq!(status, FMI2_OK);
    assert!(torque[0].is_finite() && torque[0] > 0.0);
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, FMI2_OK);
    let h = 0.001;
    for i in 0..5 {
        assert_eq!(fmu.step(i as f64 * h, h), FMI2_OK);
    }
    assert_eq!(fmu.time(), 0.005);
    let (reals, _) = output_vrs();
    let (status, values) = fmu.get_reals(&reals);
    assert_eq!(status, FMI2_OK);
    assert!(finite(&values));
    let mut b = [0, 0, 0];
    assert_eq!(
        unsafe {
            fmi2GetBoolean(
                fmu.c,
                [var::SKEW_MODEL, var::GYROSCOPIC, var::CENTRIFUGAL].as_ptr(),
                3,
                b.as_mut_ptr(),
            )
        },
        FMI2_OK
    );
    assert_eq!(b, [FMI2_FALSE, FMI2_TRUE, FMI2_TRUE]);
    let mut terminated = FMI2_TRUE;
    assert_eq!(unsafe { fmi2GetBooleanStatus(fmu.c, FMI2_TERMINATED, &mut terminated) }, FMI2_OK);
    assert_eq!(terminated, FMI2_FALSE);
    assert_eq!(unsafe { fmi2Terminate(fmu.c) }, FMI2_OK);
    // Outputs stay readable after termination.
    let (status, after) = fmu.get_reals(&reals);
    assert_eq!(status, FMI2_OK);
    assert_eq!(
        after.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
        values.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    );

    // With loggingOn every category is enabled: events and solver statistics arrive,
    // always with the declared category, the instance name and the environment unchanged.
    let records = fmu.log.records();
    assert!(!records.is_empty());
    let categories: Vec<&str> = model_description::LOG_CATEGORIES.iter().map(|(n, _)| *n).collect();
    for r in &records {
        assert_eq!(r.env, fmu.log.env() as usize, "componentEnvironment changed");
        assert_eq!(r.instance, "bearing #1");
        assert!(categories.contains(&r.category.as_str()), "undeclared category {}", r.category);
    }
    fmu.log.assert_logged("Newton iterations, relative residual");
    assert!(records
        .iter()
        .any(|r| r.category == "logSolver" && r.status == FMI2_OK && unescape(&r.message).starts_with("t = 0.005:")));
    assert!(records.iter().any(|r| r.category == "logEvents"));
}

#[test]
fn resource_location_variants_all_instantiate() {
    let text = preset_text();
    let plain = resource_dir("uri-plain", Some(&text));
    let path = plain.to_str().unwrap().to_string();
    let spaced = resource_dir("uri with space", Some(&text));
    let spaced_escaped = spaced.to_str().unwrap().replace(' ', "%20");
    let empty = resource_dir("uri-no-bearing-json", None);
    let cases: Vec<(String, Option<String>, bool)> = vec![
        ("file:///".into(), Some(format!("file://{path}")), false),
        ("trailing slash".into(), Some(format!("file://{path}/")), false),
        ("file:/".into(), Some(format!("file:{path}")), false),
        ("localhost".into(), Some(format!("file://localhost{path}")), false),
        ("percent-escaped space".into(), Some(format!("file://{spaced_escaped}")), false),
        ("NULL".into(), None, true),
        ("empty".into(), Some(String::new()), true),
        ("directory without bearing.json".into(), Some(file_uri(&empty)), true),
    ];
    for (what, uri, falls_back) in cases {
        let fmu = instantiate(Some("uri"), FMI2_CO_SIMULATION, Some(default_guid()), uri.as_deref(), false)
            .unwrap_or_else(|log| panic!("{what}: NULL, {:#?}", log.messages()));
        let warned = fmu
            .log
            .records()
            .iter()
            .any(|r| r.status == FMI2_WARNING && r.category == "logStatusWarning");
        assert_eq!(
            warned,
            falls_back,
            "{what}: fallback warning expected = {falls_back}: {:#?}",
            fmu.log.messages()
        );
        if falls_back {
            fmu.log.assert_logged("TRB130x230");
        }
        fmu.init(None);
        assert_eq!(fmu.step(0.0, 1e-3), FMI2_OK, "{what}");
    }
}

#[test]
fn wrong_guid_is_refused_with_both_guids_logged() {
    let log = refused(instantiate(
        Some("x"),
        FMI2_CO_SIMULATION,
        Some("{00000000-0000-0000-0000-000000000000}"),
        Some(&default_resources()),
        false,
    ));
    log.assert_logged("{00000000-0000-0000-0000-000000000000}");
    log.assert_logged(default_guid());
    assert!(log
        .records()
        .iter()
        .all(|r| r.status == FMI2_ERROR && r.category == "logStatusError"));

    // A GUID of another bearing does not fit the default bearing either.
    let other = model_description::guid(&Bearing::preset("32008").unwrap());
    let log = refused(instantiate(Some("x"), FMI2_CO_SIMULATION, Some(&other), None, false));
    log.assert_logged("does not match");
}

#[test]
fn another_bearing_from_resources_instantiates_with_its_own_guid() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/32008.json")).unwrap();
    let uri = file_uri(&resource_dir("other-bearing", Some(&text)));
    let guid = model_description::guid(&Bearing::from_json(&text).unwrap());
    let fmu =
        instantiate(Some("x"), FMI2_CO_SIMULATION, Some(&guid), Some(&uri), false).unwrap_or_else(|log| panic!("{:#?}", log.messages()));
    fmu.init(None);
    assert_eq!(fmu.step(0.0, 1e-3), FMI2_OK);
    // The default GUID does not fit this bearing.
    refused(instantiate(Some("x"), FMI2_CO_SIMULATION, Some(default_guid()), Some(&uri), false));
}

#[test]
fn malformed_bearing_json_is_refused_with_the_field_named() {
    let mut missing: serde_json::Value = serde_json::from_str(&preset_text()).unwrap();
    missing.as_object_mut().unwrap().remove("pitch_diameter_mm");
    let mut wrong_type: serde_json::Value = serde_json::from_str(&preset_text()).unwrap();
    wrong_type["rollers"]["count"] = serde_json::Value::String("seventeen".into());
    let cases = [
        ("missing-field", missing.to_string(), "pitch_diameter_mm"),
        ("wrong-type", wrong_type.to_string(), "rollers.count"),
        ("not-json", "{ this is not json".to_string(), "bearing.json"),
    ];
    for (name, text, needle) in cases {
        let uri = file_uri(&resource_dir(name, Some(&text)));
        let log = refused(instantiate(Some("x"), FMI2_CO_SIMULATION, Some(default_guid()), Some(&uri), false));
        log.assert_logged(needle);
        assert!(log.records().iter().any(|r| r.status == FMI2_ERROR), "{name}");
    }
}

#[test]
fn bad_instantiate_arguments_give_null_with_a_reason() {
    let res = default_resources();
    let log = refused(instantiate(Some("x"), FMI2_MODEL_EXCHANGE, Some(default_guid()), Some(&res), false));
    log.assert_logged("fmi2CoSimulation");
    let log = refused(instantiate(None, FMI2_CO_SIMULATION, Some(default_guid()), Some(&res), false));
    log.assert_logged("missing instance name");
    let log = refused(instantiate(Some(""), FMI2_CO_SIMULATION, Some(default_guid()), Some(&res), false));
    log.assert_logged("missing instance name");
    let log = refused(instantiate(Some("x"), FMI2_CO_SIMULATION, None, Some(&res), false));
    log.assert_logged("missing fmuGUID");
    let log = refused(instantiate(
        Some("x"),
        FMI2_CO_SIMULATION,
        Some(default_guid()),
        Some("http://example.com/resources"),
        false,
    ));
    log.assert_logged("not a file URI");
    // NULL callbacks: NULL, no crash.
    let c = unsafe { fmi2Instantiate(c"x".as_ptr(), FMI2_CO_SIMULATION, ptr::null(), ptr::null(), ptr::null(), 0, 0) };
    assert!(c.is_null());
    // A NULL logger: works, never logs.
    let guid = CString::new(default_guid()).unwrap();
    let cb = Fmi2CallbackFunctions {
        logger: None,
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: ptr::null_mut(),
    };
    let c = unsafe { fmi2Instantiate(c"x".as_ptr(), FMI2_CO_SIMULATION, guid.as_ptr(), ptr::null(), &cb, 0, 1) };
    assert!(!c.is_null());
    assert_eq!(unsafe { fmi2DoStep(c, 0.0, 1.0, 0) }, FMI2_ERROR);
    unsafe { fmi2FreeInstance(c) };
}

#[test]
fn illegal_call_sequences_return_error_and_say_why() {
    let fmu = Fmu::new();
    let out = [var::FRICTION_TORQUE];
    // doStep and get before initialization.
    assert_eq!(fmu.step(0.0, 1e-3), FMI2_ERROR);
    fmu.log.assert_logged("fmi2DoStep called in state Instantiated");
    assert_eq!(fmu.get_reals(&out).0, FMI2_ERROR);
    fmu.log.assert_logged("fmi2GetReal called in state Instantiated");
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, FMI2_ERROR);
    assert_eq!(unsafe { fmi2Terminate(fmu.c) }, FMI2_ERROR);
    // Parameters and inputs may be set before initialization (as fmpy and the FMI
    // Compliance Checker do); outputs never.
    assert_eq!(fmu.set_real(var::MU, 0.2), FMI2_OK);
    assert_eq!(fmu.set_real(var::FY, 1000.0), FMI2_OK);
    assert_eq!(fmu.set_real(var::FRICTION_TORQUE, 1.0), FMI2_ERROR);
    fmu.log.assert_logged("frictionTorque (value reference 201) is an output");
    fmu.init(None);
    assert_eq!(unsafe { fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0) }, FMI2_ERROR);
    fmu.log.assert_logged("fmi2SetupExperiment called in state StepComplete");
    assert_eq!(unsafe { fmi2EnterInitializationMode(fmu.c) }, FMI2_ERROR);
    // Fixed parameters after initialization.
    assert_eq!(fmu.set_real(var::MU, 0.3), FMI2_ERROR);
    fmu.log
        .assert_logged("cannot set fixed parameter mu (value reference 6) after initialization");
    assert_eq!(fmu.set_integer(var::SLICES, 10), FMI2_ERROR);
    fmu.log.assert_logged("cannot set fixed parameter slices");
    let (vr, v) = (var::SKEW_MODEL, FMI2_TRUE);
    assert_eq!(unsafe { fmi2SetBoolean(fmu.c, &vr, 1, &v) }, FMI2_ERROR);
    fmu.log.assert_logged("cannot set fixed parameter skewModel");
    assert_eq!(fmu.set_real(var::ROLLER_D_D + 2, 1e-6), FMI2_ERROR);
    fmu.log.assert_logged("cannot set fixed parameter roller[3].dD");
    // Inputs still may be set; the instance is still usable.
    assert_eq!(fmu.set_real(var::FY, 2000.0), FMI2_OK);
    assert_eq!(fmu.step(0.0, 1e-3), FMI2_OK);
    // Unsupported functions.
    assert_eq!(
        unsafe { fmi2GetDirectionalDerivative(fmu.c, ptr::null(), 0, ptr::null(), 0, ptr::null(), ptr::null_mut()) },
        FMI2_ERROR
    );
    fmu.log.assert_logged("providesDirectionalDerivative");
    // Input derivatives (canInterpolateInputs): order 1 of Real inputs ramps them over the
    // next step; higher orders are not used (a warning); order 0, parameters, outputs, NaN
    // and NULL arrays are refused with the reason.
    let set_derivative = |vr: u32, order: i32, value: f64| unsafe { fmi2SetRealInputDerivatives(fmu.c, &vr, 1, &order, &value) };
    assert_eq!(set_derivative(var::FY, 2, 1.0), FMI2_WARNING);
    fmu.log.assert_logged("not used: the inputs are interpolated linearly");
    assert_eq!(set_derivative(var::FY, 0, 1.0), FMI2_ERROR);
    fmu.log.assert_logged("orders start at 1");
    assert_eq!(set_derivative(var::TOLERANCE, 1, 1.0), FMI2_ERROR);
    fmu.log.assert_logged("only Real inputs take time derivatives");
    assert_eq!(set_derivative(var::FY, 1, f64::NAN), FMI2_ERROR);
    fmu.log.assert_logged("must be finite");
    for (vr, order, value) in [(true, false, false), (false, true, false), (false, false, true)] {
        let status = unsafe {
            fmi2SetRealInputDerivatives(
                fmu.c,
                if vr { ptr::null() } else { &var::FY },
                1,
                if order { ptr::null() } else { &1 },
                if value { ptr::null() } else { &1.0 },
            )
        };
        assert_eq!(status, FMI2_ERROR);
        fmu.log.assert_logged("must not be NULL");
    }
    assert_eq!(set_derivative(var::FY, 1, 1e6), FMI2_OK);
    assert_eq!(fmu.step(1e-3, 1e-3), FMI2_OK);
    let (status, fy) = fmu.get_reals(&[var::FY]);
    assert_eq!((status, fy[0]), (FMI2_OK, 3000.0), "Fy ramped from 2 kN at 1 MN/s over 1 ms");
    assert_eq!(
        unsafe { fmi2GetRealOutputDerivatives(fmu.c, ptr::null(), 0, ptr::null(), ptr::null_mut()) },
        FMI2_ERROR
    );
    fmu.log.assert_logged("maxOutputDerivativeOrder");
    assert_eq!(unsafe { fmi2CancelStep(fmu.c) }, FMI2_ERROR);
    fmu.log.assert_logged("never returns fmi2Pending");
    // Status inquiries: available kinds OK, the others discard.
    let mut status = FMI2_OK;
    assert_eq!(unsafe { fmi2GetStatus(fmu.c, FMI2_DO_STEP_STATUS, &mut status) }, FMI2_DISCARD);
    let mut i = 0;
    assert_eq!(
        unsafe { fmi2GetIntegerStatus(fmu.c, FMI2_LAST_SUCCESSFUL_TIME, &mut i) },
        FMI2_DISCARD
    );
    let mut s: Fmi2String = ptr::null();
    assert_eq!(unsafe { fmi2GetStringStatus(fmu.c, FMI2_PENDING_STATUS, &mut s) }, FMI2_DISCARD);
    assert_eq!(unsafe { fmi2GetStatus(fmu.c, 99, &mut status) }, FMI2_ERROR);
    assert_eq!(fmu.time(), 2e-3);
    // After termination: no more steps, but getters work.
    assert_eq!(unsafe { fmi2Terminate(fmu.c) }, FMI2_OK);
    assert_eq!(fmu.step(2e-3, 1e-3), FMI2_ERROR);
    fmu.log.assert_logged("fmi2DoStep called in state Terminated");
    assert_eq!(fmu.set_real(var::FY, 0.0), FMI2_ERROR);
    assert_eq!(fmu.get_reals(&out).0, FMI2_OK);
    // Every error was logged as such.
    for r in fmu.log.records() {
        if r.status == FMI2_ERROR {
            assert_eq!(r.category, "logStatusError");
        }
    }
}

#[test]
fn null_instance_and_null_arrays_return_error() {
    let null: Fmi2Component = ptr::null_mut();
    let vr = [var::FRICTION_TORQUE];
    let mut v = [0.0];
    let mut iv = [0];
    unsafe {
        assert_eq!(fmi2SetDebugLogging(null, 1, 0, ptr::null()), FMI2_ERROR);
        assert_eq!(fmi2SetupExperiment(null, 0, 0.0, 0.0, 0, 0.0), FMI2_ERROR);
        assert_eq!(fmi2EnterInitializationMode(null), FMI2_ERROR);
        assert_eq!(fmi2ExitInitializationMode(null), FMI2_ERROR);
        assert_eq!(fmi2Terminate(null), FMI2_ERROR);
        assert_eq!(fmi2Reset(null), FMI2_ERROR);
        assert_eq!(fmi2GetReal(null, vr.as_ptr(), 1, v.as_mut_ptr()), FMI2_ERROR);
        assert_eq!(fmi2GetInteger(null, vr.as_ptr(), 1, iv.as_mut_ptr()), FMI2_ERROR);
        assert_eq!(fmi2GetBoolean(null, vr.as_ptr(), 1, iv.as_mut_ptr()), FMI2_ERROR);
        assert_eq!(fmi2SetReal(null, vr.as_ptr(), 1, v.as_ptr()), FMI2_ERROR);
        assert_eq!(fmi2SetInteger(null, vr.as_ptr(), 1, iv.as_ptr()), FMI2_ERROR);
        assert_eq!(fmi2SetBoolean(null, vr.as_ptr(), 1, iv.as_ptr()), FMI2_ERROR);
        assert_eq!(fmi2GetString(null, vr.as_ptr(), 0, ptr::null_mut()), FMI2_ERROR);
        assert_eq!(fmi2SetString(null, vr.as_ptr(), 0, ptr::null()), FMI2_ERROR);
        let mut s: Fmi2FmuState = ptr::null_mut();
        assert_eq!(fmi2GetFMUstate(null, &mut s), FMI2_ERROR);
        assert_eq!(fmi2SetFMUstate(null, s), FMI2_ERROR);
        assert_eq!(fmi2FreeFMUstate(null, &mut s), FMI2_ERROR);
        let mut size = 0;
        assert_eq!(fmi2SerializedFMUstateSize(null, s, &mut size), FMI2_ERROR);
        assert_eq!(fmi2SerializeFMUstate(null, s, ptr::null_mut(), 0), FMI2_ERROR);
        assert_eq!(fmi2DeSerializeFMUstate(null, ptr::null(), 0, &mut s), FMI2_ERROR);
        assert_eq!(
            fmi2GetDirectionalDerivative(null, ptr::null(), 0, ptr::null(), 0, ptr::null(), ptr::null_mut()),
            FMI2_ERROR
        );
        assert_eq!(
            fmi2SetRealInputDerivatives(null, ptr::null(), 0, ptr::null(), ptr::null()),
            FMI2_ERROR
        );
        assert_eq!(
            fmi2GetRealOutputDerivatives(null, ptr::null(), 0, ptr::null(), ptr::null_mut()),
            FMI2_ERROR
        );
        assert_eq!(fmi2DoStep(null, 0.0, 1.0, 0), FMI2_ERROR);
        assert_eq!(fmi2CancelStep(null), FMI2_ERROR);
        let mut st = 0;
        let mut r = 0.0;
        let mut str_: Fmi2String = ptr::null();
        assert_eq!(fmi2GetStatus(null, 0, &mut st), FMI2_ERROR);
        assert_eq!(fmi2GetRealStatus(null, FMI2_LAST_SUCCESSFUL_TIME, &mut r), FMI2_ERROR);
        assert_eq!(fmi2GetIntegerStatus(null, 0, &mut st), FMI2_ERROR);
        assert_eq!(fmi2GetBooleanStatus(null, FMI2_TERMINATED, &mut st), FMI2_ERROR);
        assert_eq!(fmi2GetStringStatus(null, 0, &mut str_), FMI2_ERROR);
        fmi2FreeInstance(null);
    }

    let fmu = Fmu::initialized(None);
    unsafe {
        assert_eq!(fmi2GetReal(fmu.c, ptr::null(), 1, v.as_mut_ptr()), FMI2_ERROR);
        fmu.log.assert_logged("fmi2GetReal: argument vr[] must not be NULL");
        assert_eq!(fmi2GetReal(fmu.c, vr.as_ptr(), 1, ptr::null_mut()), FMI2_ERROR);
        fmu.log.assert_logged("fmi2GetReal: argument value[] must not be NULL");
        assert_eq!(fmi2SetReal(fmu.c, ptr::null(), 3, v.as_ptr()), FMI2_ERROR);
        assert_eq!(fmi2SetReal(fmu.c, vr.as_ptr(), 1, ptr::null()), FMI2_ERROR);
        assert_eq!(fmi2GetInteger(fmu.c, ptr::null(), 1, iv.as_mut_ptr()), FMI2_ERROR);
        assert_eq!(fmi2SetInteger(fmu.c, vr.as_ptr(), 1, ptr::null()), FMI2_ERROR);
        assert_eq!(fmi2GetBoolean(fmu.c, vr.as_ptr(), 1, ptr::null_mut()), FMI2_ERROR);
        assert_eq!(fmi2SetBoolean(fmu.c, ptr::null(), 1, iv.as_ptr()), FMI2_ERROR);
        assert_eq!(fmi2GetString(fmu.c, vr.as_ptr(), 1, ptr::null_mut()), FMI2_ERROR);
        assert_eq!(fmi2SetString(fmu.c, ptr::null(), 1, ptr::null()), FMI2_ERROR);
        assert_eq!(fmi2SetDebugLogging(fmu.c, 1, 2, ptr::null()), FMI2_ERROR);
        fmu.log.assert_logged("categories[] must not be NULL");
        let cats = [c"logEvents".as_ptr(), ptr::null()];
        assert_eq!(fmi2SetDebugLogging(fmu.c, 1, 2, cats.as_ptr()), FMI2_ERROR);
        fmu.log.assert_logged("categories[1] is NULL");
        let mut r = 0.0;
        assert_eq!(fmi2GetRealStatus(fmu.c, FMI2_LAST_SUCCESSFUL_TIME, ptr::null_mut()), FMI2_ERROR);
        assert_eq!(fmi2GetRealStatus(fmu.c, FMI2_LAST_SUCCESSFUL_TIME, &mut r), FMI2_OK);
        // n = 0 with NULL arrays is fine.
        assert_eq!(fmi2GetReal(fmu.c, ptr::null(), 0, ptr::null_mut()), FMI2_OK);
        assert_eq!(fmi2SetReal(fmu.c, ptr::null(), 0, ptr::null()), FMI2_OK);
        assert_eq!(fmi2GetString(fmu.c, ptr::null(), 0, ptr::null_mut()), FMI2_OK);
    }
    // Still alive and well.
    assert_eq!(fmu.step(0.0, 1e-3), FMI2_OK);
}

#[test]
fn unknown_value_references_are_named() {
    let fmu = Fmu::initialized(None);
    let (status, _) = fmu.get_reals(&[var::FRICTION_TORQUE, 123_456]);
    assert_eq!(status, FMI2_ERROR);
    fmu.log.assert_logged("fmi2GetReal: unknown value reference 123456");
    // Roller 18 does not exist in a 17-roller bearing.
    assert_eq!(fmu.get_reals(&[var::ROLLER_TILT + 17]).0, FMI2_ERROR);
    fmu.log.assert_logged(&format!("unknown value reference {}", var::ROLLER_TILT + 17));
    // A value reference of another type.
    assert_eq!(fmu.get_reals(&[var::LOADED_ROLLERS]).0, FMI2_ERROR);
    fmu.log
        .assert_logged("value reference 219 is loadedRollers of type Integer, not Real");
    assert_eq!(fmu.set_real(999, 1.0), FMI2_ERROR);
    fmu.log.assert_logged("fmi2SetReal: unknown value reference 999");
    assert_eq!(fmu.set_integer(777, 1), FMI2_ERROR);
    fmu.log.assert_logged("fmi2SetInteger: unknown value reference 777");
    let mut i = [0];
    assert_eq!(
        unsafe { fmi2GetInteger(fmu.c, [var::SPEED].as_ptr(), 1, i.as_mut_ptr()) },
        FMI2_ERROR
    );
    fmu.log.assert_logged("value reference 101 is speed of type Real, not Integer");
    let mut s: [Fmi2String; 1] = [ptr::null()];
    assert_eq!(unsafe { fmi2GetString(fmu.c, [5].as_ptr(), 1, s.as_mut_ptr()) }, FMI2_ERROR);
    fmu.log.assert_logged("value reference 5 is tolerance of type Real, not String");
    assert_eq!(
        unsafe { fmi2SetString(fmu.c, [4242].as_ptr(), 1, [c"x".as_ptr()].as_ptr()) },
        FMI2_ERROR
    );
    fmu.log.assert_logged("fmi2SetString: unknown value reference 4242");
    // Out-of-range enumeration before initialization.
    let fresh = Fmu::new();
    assert_eq!(fresh.set_integer(var::FIDELITY, 7), FMI2_ERROR);
    fresh.log.assert_logged("fidelity must be in [0, 2], got 7");
    assert_eq!(fresh.set_real(var::MU, f64::NAN), FMI2_ERROR);
    fresh.log.assert_logged("mu must be finite");
}

#[test]
fn communication_points_are_checked() {
    let h = 1e-3;
    // Mismatched and non-increasing communication points.
    for t in [0.5e-3, 2e-3, -1e-3, f64::NAN] {
        let fmu = Fmu::initialized(None);
        assert_eq!(fmu.step(0.0, h), FMI2_OK);
        assert_eq!(fmu.step(t, h), FMI2_ERROR, "t = {t}");
        fmu.log.assert_logged("does not match the FMU's time 0.001");
    }
    // Step size must be > 0.
    for step in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let fmu = Fmu::initialized(None);
        assert_eq!(fmu.step(0.0, step), FMI2_ERROR, "h = {step}");
        fmu.log.assert_logged("communication step size must be > 0");
    }
    // Rounding noise in t is accepted: the master accumulates t, the FMU steps from its
    // own time. 0.1 + 0.2 != 0.3 in binary.
    let fmu = Fmu::initialized(None);
    let mut t = 0.0;
    for _ in 0..10 {
        assert_eq!(fmu.step(t, 0.1), FMI2_OK);
        t += 0.1;
    }
    assert_ne!(t, 1.0);
    assert!((fmu.time() - 1.0).abs() < 1e-12);
    let now = fmu.time();
    assert_eq!(fmu.step(now * (1.0 + 1e-12), h), FMI2_OK);
    assert_eq!(fmu.step(fmu.time() - 2e-10, h), FMI2_OK);

    // Stop time: a step ending past it fails; one ending within rounding noise is clamped.
    let fmu = Fmu::initialized(Some(0.3));
    let mut t = 0.0;
    for _ in 0..3 {
        assert_eq!(fmu.step(t, 0.1), FMI2_OK);
        t += 0.1;
    }
    assert!(t > 0.3);
    assert_eq!(fmu.time(), 0.3, "clamped to the stop time");
    assert_eq!(fmu.step(0.3, 0.1), FMI2_ERROR);
    fmu.log.assert_logged("goes past the stop time 0.3");
    let fmu = Fmu::initialized(Some(0.3));
    assert_eq!(fmu.step(0.0, 0.31), FMI2_ERROR);

    // SetupExperiment checks its arguments and sets the start time.
    let fmu = Fmu::new();
    assert_eq!(fmu.setup(1.0, Some(0.5)), FMI2_ERROR);
    assert_eq!(fmu.setup(f64::NAN, None), FMI2_ERROR);
    assert_eq!(unsafe { fmi2SetupExperiment(fmu.c, FMI2_TRUE, 1e-6, 2.0, FMI2_TRUE, 3.0) }, FMI2_OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(fmu.c) }, FMI2_OK);
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, FMI2_OK);
    assert_eq!(fmu.time(), 2.0);
    assert_eq!(fmu.step(0.0, h), FMI2_ERROR);
    let fmu = Fmu::new();
    assert_eq!(
        unsafe { fmi2SetupExperiment(fmu.c, FMI2_TRUE, 1e-6, 2.0, FMI2_FALSE, 0.0) },
        FMI2_OK
    );
    assert_eq!(unsafe { fmi2EnterInitializationMode(fmu.c) }, FMI2_OK);
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, FMI2_OK);
    assert_eq!(fmu.step(2.0, h), FMI2_OK);
    assert_eq!(fmu.time(), 2.0 + h);
}

#[test]
fn nan_and_infinite_inputs_are_refused_naming_the_input() {
    let (reals, _) = output_vrs();
    for (vr, name) in [(var::FY, "Fy"), (var::SPEED, "speed"), (var::XI, "xi"), (var::FX, "Fx")] {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let fmu = Fmu::initialized(None);
            load(&fmu, 0);
            assert_eq!(fmu.step(0.0, 1e-3), FMI2_OK);
            let good = fmu.outputs();
            // Setting an input is fine; using it is not.
            assert_eq!(fmu.set_real(vr, bad), FMI2_OK);
            // Direct feedthrough: reading outputs re-solves, which fails; values are the
            // last valid ones.
            let (status, values) = fmu.get_reals(&reals);
            assert_eq!(status, FMI2_ERROR);
            assert!(finite(&values));
            fmu.log.assert_logged(&format!("input {name} is {bad}"));
            fmu.log.clear();
            assert_eq!(fmu.step(1e-3, 1e-3), FMI2_ERROR, "{name} = {bad}");
            fmu.log.assert_logged(&format!("fmi2DoStep: input {name} is {bad}"));
            assert!(fmu
                .log
                .records()
                .iter()
                .any(|r| r.status == FMI2_ERROR && r.category == "logStatusError"));
            // Error state: outputs readable, finite, unchanged; no more steps.
            assert_eq!(fmu.outputs(), good);
            assert_eq!(fmu.step(1e-3, 1e-3), FMI2_ERROR);
            assert_eq!(unsafe { fmi2Reset(fmu.c) }, FMI2_OK);
        }
    }
}

#[test]
fn a_step_without_equilibrium_is_discarded() {
    let fmu = Fmu::initialized(None);
    assert_eq!(fmu.step(0.0, 1e-3), FMI2_OK);
    let good = fmu.outputs();
    let state = fmu.get_state();
    // No axial force: a tapered roller bearing is not seated; the solver finds no equilibrium.
    assert_eq!(fmu.set_real(var::FX, 0.0), FMI2_OK);
    assert_eq!(fmu.step(1e-3, 1e-3), FMI2_DISCARD);
    assert!(fmu
        .log
        .records()
        .iter()
        .any(|r| r.status == FMI2_DISCARD && r.category == "logStatusDiscard"));
    fmu.log.assert_logged("no quasi-static equilibrium");
    // StepFailed: last successful time and outputs are those before the step.
    assert_eq!(fmu.time(), 1e-3);
    assert_eq!(fmu.outputs(), good);
    assert_eq!(fmu.step(1e-3, 1e-3), FMI2_ERROR);
    fmu.log.assert_logged("fmi2DoStep called in state StepFailed");
    // Roll back and continue with a valid load.
    assert_eq!(unsafe { fmi2SetFMUstate(fmu.c, state) }, FMI2_OK);
    assert_eq!(fmu.step(1e-3, 1e-3), FMI2_OK);
    // Terminate is allowed from StepFailed.
    assert_eq!(fmu.set_real(var::FX, 0.0), FMI2_OK);
    assert_eq!(fmu.step(2e-3, 1e-3), FMI2_DISCARD);
    assert_eq!(unsafe { fmi2Terminate(fmu.c) }, FMI2_OK);
}

#[test]
fn fmu_state_get_step_set_step_is_bitwise_identical() {
    let fmu = Fmu::initialized(None);
    run(&fmu, 3, 1e-3);
    let mut state = fmu.get_state();
    let first = run(&fmu, 4, 1e-3);
    assert_eq!(unsafe { fmi2SetFMUstate(fmu.c, state) }, FMI2_OK);
    assert_eq!(fmu.time(), 3e-3);
    let second = run(&fmu, 4, 1e-3);
    assert_eq!(first, second);
    // Overwrite in place: same handle, new content.
    let before = state;
    assert_eq!(unsafe { fmi2GetFMUstate(fmu.c, &mut state) }, FMI2_OK);
    assert_eq!(state, before);
    let third = run(&fmu, 2, 1e-3);
    assert_eq!(unsafe { fmi2SetFMUstate(fmu.c, state) }, FMI2_OK);
    assert_eq!(run(&fmu, 2, 1e-3), third);
    // The state machine state is part of the FMU state: back from Terminated to StepComplete.
    assert_eq!(unsafe { fmi2Terminate(fmu.c) }, FMI2_OK);
    assert_eq!(unsafe { fmi2SetFMUstate(fmu.c, state) }, FMI2_OK);
    assert_eq!(fmu.step(fmu.time(), 1e-3), FMI2_OK);
    assert_eq!(unsafe { fmi2FreeFMUstate(fmu.c, &mut state) }, FMI2_OK);
    assert!(state.is_null());
    // Freeing the instance frees states still allocated.
    let _leaked = fmu.get_state();
}

#[test]
fn fmu_state_misuse_is_detected() {
    let fmu = Fmu::initialized(None);
    let other = Fmu::initialized(None);
    let mut state = fmu.get_state();
    let copy = state;
    // Foreign pointers: a local variable, another instance's state.
    let mut local = 0u64;
    let foreign: Fmi2FmuState = (&mut local as *mut u64).cast();
    let mut theirs = other.get_state();
    unsafe {
        assert_eq!(fmi2SetFMUstate(fmu.c, foreign), FMI2_ERROR);
        fmu.log.assert_logged("is not a live FMU state of this instance");
        assert_eq!(fmi2SetFMUstate(fmu.c, theirs), FMI2_ERROR);
        assert_eq!(fmi2SetFMUstate(fmu.c, ptr::null_mut()), FMI2_ERROR);
        let mut f = foreign;
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut f), FMI2_ERROR);
        assert_eq!(fmi2GetFMUstate(fmu.c, &mut f), FMI2_ERROR, "non-NULL *FMUstate that is not ours");
        let mut size = 0;
        assert_eq!(fmi2SerializedFMUstateSize(fmu.c, foreign, &mut size), FMI2_ERROR);
        assert_eq!(fmi2SerializeFMUstate(fmu.c, foreign, ptr::null_mut(), 0), FMI2_ERROR);
        assert_eq!(fmi2GetFMUstate(fmu.c, ptr::null_mut()), FMI2_ERROR);
        // Free, then double free through a copy of the pointer.
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut state), FMI2_OK);
        assert!(state.is_null());
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut state), FMI2_OK, "*FMUstate == NULL is ignored");
        let mut dangling = copy;
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut dangling), FMI2_ERROR);
        assert_eq!(fmi2SetFMUstate(fmu.c, copy), FMI2_ERROR);
        assert_eq!(fmi2FreeFMUstate(other.c, &mut theirs), FMI2_OK);
    }
    assert_eq!(local, 0);
    assert_eq!(fmu.step(0.0, 1e-3), FMI2_OK);
}

#[test]
fn serialized_state_restores_into_a_second_instance() {
    let a = Fmu::initialized(None);
    run(&a, 3, 1e-3);
    let mut state = a.get_state();
    let mut size = 0usize;
    assert_eq!(unsafe { fmi2SerializedFMUstateSize(a.c, state, &mut size) }, FMI2_OK);
    assert!(size > 100);
    let mut bytes = vec![0 as c_char; size];
    assert_eq!(unsafe { fmi2SerializeFMUstate(a.c, state, bytes.as_mut_ptr(), size) }, FMI2_OK);
    assert_eq!(
        unsafe { fmi2SerializeFMUstate(a.c, state, bytes.as_mut_ptr(), size - 1) },
        FMI2_ERROR
    );
    assert_eq!(unsafe { fmi2FreeFMUstate(a.c, &mut state) }, FMI2_OK);

    // A fresh instance, not even initialized, takes the serialized state.
    let b = Fmu::new();
    let mut restored: Fmi2FmuState = ptr::null_mut();
    assert_eq!(
        unsafe { fmi2DeSerializeFMUstate(b.c, bytes.as_ptr(), size, &mut restored) },
        FMI2_OK
    );
    assert_eq!(unsafe { fmi2SetFMUstate(b.c, restored) }, FMI2_OK);
    assert_eq!(b.time(), a.time());
    assert_eq!(b.outputs(), a.outputs());
    assert_eq!(run(&a, 3, 1e-3), run(&b, 3, 1e-3));

    // Serializing the restored state gives the same bytes (bitwise round trip).
    let mut size2 = 0usize;
    assert_eq!(unsafe { fmi2SerializedFMUstateSize(b.c, restored, &mut size2) }, FMI2_OK);
    let mut bytes2 = vec![0 as c_char; size2];
    assert_eq!(unsafe { fmi2SerializeFMUstate(b.c, restored, bytes2.as_mut_ptr(), size2) }, FMI2_OK);
    assert_eq!(bytes, bytes2);
    // Deserialize into an existing handle overwrites it in place.
    let before = restored;
    assert_eq!(
        unsafe { fmi2DeSerializeFMUstate(b.c, bytes.as_ptr(), size, &mut restored) },
        FMI2_OK
    );
    assert_eq!(restored, before);

    // Corrupt and truncated bytes are refused.
    let mut bad: Fmi2FmuState = ptr::null_mut();
    let mut corrupt = bytes.clone();
    corrupt[0] ^= 1;
    assert_eq!(
        unsafe { fmi2DeSerializeFMUstate(b.c, corrupt.as_ptr(), size, &mut bad) },
        FMI2_ERROR
    );
    b.log.assert_logged("bad header");
    assert_eq!(
        unsafe { fmi2DeSerializeFMUstate(b.c, bytes.as_ptr(), size / 2, &mut bad) },
        FMI2_ERROR
    );
    assert_eq!(unsafe { fmi2DeSerializeFMUstate(b.c, bytes.as_ptr(), 3, &mut bad) }, FMI2_ERROR);
    let mut bad_machine = bytes.clone();
    bad_machine[8] = 0x55;
    assert_eq!(
        unsafe { fmi2DeSerializeFMUstate(b.c, bad_machine.as_ptr(), size, &mut bad) },
        FMI2_ERROR
    );
    assert!(bad.is_null());

    // A state of another bearing does not fit.
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/32008.json")).unwrap();
    let uri = file_uri(&resource_dir("serialize-other-bearing", Some(&text)));
    let guid = model_description::guid(&Bearing::from_json(&text).unwrap());
    let c = instantiate(Some("x"), FMI2_CO_SIMULATION, Some(&guid), Some(&uri), false).unwrap_or_else(|_| panic!("NULL"));
    assert_eq!(unsafe { fmi2DeSerializeFMUstate(c.c, bytes.as_ptr(), size, &mut bad) }, FMI2_ERROR);
    c.log.assert_logged("serialized state is for bearing TRB130x230");
}

#[test]
fn reset_then_reinitialize_reproduces_the_first_run() {
    let fmu = Fmu::new();
    let go = |fmu: &Fmu| {
        assert_eq!(fmu.set_real(var::CAGE_SLIP_RATE, 0.001), FMI2_OK);
        fmu.init(Some(1.0));
        let mut out = vec![fmu.outputs()];
        out.extend(run(fmu, 5, 1e-3));
        out
    };
    let first = go(&fmu);
    assert_eq!(unsafe { fmi2Reset(fmu.c) }, FMI2_OK);
    // Back to start values: a parameter changed before the first run is at its default again.
    assert_eq!(unsafe { fmi2EnterInitializationMode(fmu.c) }, FMI2_OK);
    let (_, slip) = fmu.get_reals(&[var::CAGE_SLIP_RATE]);
    assert_eq!(slip[0], Bearing::default_preset().cage_slip_rate);
    assert_eq!(unsafe { fmi2Reset(fmu.c) }, FMI2_OK);
    assert_eq!(go(&fmu), first);
    // Reset also from the Error state.
    assert_eq!(fmu.step(0.0, 1e-3), FMI2_ERROR);
    assert_eq!(unsafe { fmi2Reset(fmu.c) }, FMI2_OK);
    assert_eq!(go(&fmu), first);
}

#[test]
fn initialization_errors_are_reported_with_the_parameter() {
    let fmu = Fmu::new();
    // Too much clearance: the message contains "5 %", which must arrive escaped.
    assert_eq!(fmu.set_real(var::CLEARANCE, 0.01), FMI2_OK);
    assert_eq!(fmu.setup(0.0, None), FMI2_OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(fmu.c) }, FMI2_OK);
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, FMI2_ERROR);
    fmu.log.assert_logged("parameter clearance magnitude must not exceed");
    let raw: Vec<String> = fmu.log.records().into_iter().map(|r| r.message).collect();
    assert!(raw.iter().any(|m| m.contains("(5 %% of the roller diameter)")), "{raw:#?}");
    assert_eq!(fmu.step(0.0, 1e-3), FMI2_ERROR);
    fmu.log.assert_logged("fmi2DoStep called in state Error");
    assert_eq!(unsafe { fmi2Reset(fmu.c) }, FMI2_OK);
    fmu.init(None);
    assert_eq!(fmu.step(0.0, 1e-3), FMI2_OK);
}

#[test]
fn log_messages_are_escaped_and_categories_controlled() {
    let fmu = Fmu::initialized(None);
    // An unknown category is an error; its name, with % and #, comes back escaped.
    let cats = [c"50%#x".as_ptr()];
    assert_eq!(unsafe { fmi2SetDebugLogging(fmu.c, FMI2_TRUE, 1, cats.as_ptr()) }, FMI2_ERROR);
    let raw: Vec<String> = fmu.log.records().into_iter().map(|r| r.message).collect();
    assert!(raw.iter().any(|m| m.contains("\"50%%##x\"")), "{raw:#?}");

    // loggingOn = false: no solver messages; enabling logSolver alone turns them on.
    fmu.log.clear();
    assert_eq!(fmu.step(0.0, 1e-3), FMI2_OK);
    assert!(fmu.log.records().is_empty());
    let cats = [c"logSolver".as_ptr()];
    assert_eq!(unsafe { fmi2SetDebugLogging(fmu.c, FMI2_TRUE, 1, cats.as_ptr()) }, FMI2_OK);
    assert_eq!(fmu.step(1e-3, 1e-3), FMI2_OK);
    let records = fmu.log.records();
    assert_eq!(records.len(), 1, "{records:#?}");
    assert_eq!(records[0].category, "logSolver");
    assert!(records[0].message.starts_with("t = 0.002: "), "{records:#?}");
    // All off, errors included (like the Reference FMUs), then all on.
    fmu.log.clear();
    assert_eq!(unsafe { fmi2SetDebugLogging(fmu.c, FMI2_FALSE, 0, ptr::null()) }, FMI2_OK);
    assert_eq!(fmu.step(2e-3, 1e-3), FMI2_OK);
    assert_eq!(fmu.set_real(var::MU, 1.0), FMI2_ERROR);
    assert!(fmu.log.records().is_empty());
    assert_eq!(unsafe { fmi2SetDebugLogging(fmu.c, FMI2_TRUE, 0, ptr::null()) }, FMI2_OK);
    assert_eq!(fmu.set_real(var::MU, 1.0), FMI2_ERROR);
    assert_eq!(fmu.step(3e-3, 1e-3), FMI2_OK);
    let categories: Vec<String> = fmu.log.records().into_iter().map(|r| r.category).collect();
    assert!(categories.contains(&"logStatusError".to_string()) && categories.contains(&"logSolver".to_string()));
    // Every declared category can be named.
    let all: Vec<CString> = model_description::LOG_CATEGORIES
        .iter()
        .map(|(n, _)| CString::new(*n).unwrap())
        .collect();
    let ptrs: Vec<*const c_char> = all.iter().map(|c| c.as_ptr()).collect();
    assert_eq!(
        unsafe { fmi2SetDebugLogging(fmu.c, FMI2_FALSE, ptrs.len(), ptrs.as_ptr()) },
        FMI2_OK
    );
    fmu.log.clear();
    assert_eq!(fmu.set_real(var::MU, 1.0), FMI2_ERROR);
    assert!(fmu.log.records().is_empty());
}

#[test]
fn parallel_instances_agree_bitwise_with_one_instance() {
    let reference = {
        let fmu = Fmu::initialized(None);
        run(&fmu, 6, 1e-3)
    };
    let results: Vec<Vec<Vec<u64>>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..8)
            .map(|_| {
                s.spawn(|| {
                    let fmu = Fmu::initialized(None);
                    run(&fmu, 6, 1e-3)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for r in results {
        assert_eq!(r, reference);
    }
}

#[test]
fn hot_path_adds_no_allocation_to_the_physics() {
    use trb::simulation::Simulation;
    let (reals, _) = output_vrs();
    let inputs = [var::FY, var::XI, var::FX];
    let h = 1e-3;
    let n = 10;

    // The FMU, with a logger but logging off.
    let fmu = Fmu::initialized(None);
    let mut values = vec![0.0; reals.len()];
    let step_fmu = |i: usize, values: &mut [f64]| {
        let u = [10_000.0 + i as f64, 5e-5, 30_000.0];
        assert_eq!(unsafe { fmi2SetReal(fmu.c, inputs.as_ptr(), 3, u.as_ptr()) }, FMI2_OK);
        assert_eq!(unsafe { fmi2DoStep(fmu.c, i as f64 * h, h, FMI2_TRUE) }, FMI2_OK);
        assert_eq!(
            unsafe { fmi2GetReal(fmu.c, reals.as_ptr(), reals.len(), values.as_mut_ptr()) },
            FMI2_OK
        );
    };
    // The same calls on a Simulation directly.
    let mut sim = Simulation::new(Bearing::default_preset());
    sim.initialize(0.0).unwrap();
    let mut step_sim = |i: usize, values: &mut [f64]| {
        let u = [10_000.0 + i as f64, 5e-5, 30_000.0];
        for (vr, v) in inputs.iter().zip(u) {
            sim.set_real(*vr, v).unwrap();
        }
        sim.do_step(i as f64 * h, h).unwrap();
        for (vr, v) in reals.iter().zip(values.iter_mut()) {
            *v = sim.get_real(*vr).unwrap();
        }
    };
    for i in 0..3 {
        step_fmu(i, &mut values);
        step_sim(i, &mut values);
    }
    let a0 = allocations();
    let t0 = std::time::Instant::now();
    for i in 3..3 + n {
        step_fmu(i, &mut values);
    }
    let fmu_time = t0.elapsed();
    let fmu_allocations = allocations() - a0;
    let a0 = allocations();
    let t0 = std::time::Instant::now();
    for i in 3..3 + n {
        step_sim(i, &mut values);
    }
    let sim_time = t0.elapsed();
    let sim_allocations = allocations() - a0;
    assert_eq!(fmu_allocations, sim_allocations, "the FMI layer allocates on the hot path");
    eprintln!(
        "{n} steps: FMU {:?}/step, Simulation {:?}/step, {} allocations/step in both",
        fmu_time / n as u32,
        sim_time / n as u32,
        sim_allocations / n as u64
    );

    // Get/set without solving: the adapter's own cost per call.
    let m = 200_000;
    let vr = var::SPEED;
    let t0 = std::time::Instant::now();
    let a0 = allocations();
    for i in 0..m {
        let v = 300.0 + (i & 1) as f64;
        unsafe { fmi2SetReal(fmu.c, &vr, 1, &v) };
        let mut out = 0.0;
        unsafe { fmi2GetReal(fmu.c, &vr, 1, &mut out) };
        std::hint::black_box(out);
    }
    let per_call = t0.elapsed() / (2 * m);
    assert_eq!(allocations() - a0, 0);
    eprintln!("fmi2SetReal/fmi2GetReal of an input: {per_call:?} per call, no allocation");
}

#[test]
fn shared_library_exports_all_34_functions() {
    assert_eq!(EXPORTED.len(), 34);
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    let candidates = [deps.join("libtrb.so"), deps.parent().unwrap().join("libtrb.so")];
    let Some(lib) = candidates.iter().find(|p| p.exists()) else {
        panic!("libtrb.so not found in {candidates:?}");
    };
    let output = match std::process::Command::new("nm").args(["-D", "--defined-only"]).arg(lib).output() {
        Ok(o) if o.status.success() => o,
        other => {
            eprintln!("skipping the symbol check: nm unavailable ({other:?})");
            return;
        }
    };
    let text = String::from_utf8_lossy(&output.stdout);
    let exported: Vec<&str> = text
        .lines()
        .filter_map(|l| {
            let mut parts = l.split_whitespace().rev();
            let name = parts.next()?;
            let kind = parts.next()?;
            (kind == "T").then_some(name)
        })
        .collect();
    for name in EXPORTED {
        assert!(exported.contains(&name), "{name} is not exported by {}", lib.display());
    }
    let fmi: Vec<&&str> = exported.iter().filter(|n| n.starts_with("fmi2")).collect();
    assert_eq!(fmi.len(), 34, "{fmi:?}");
}

/// The bytes of FMU state `state` of `fmu`.
fn serialize(fmu: &Fmu, state: Fmi2FmuState) -> Vec<c_char> {
    let mut size = 0usize;
    assert_eq!(unsafe { fmi2SerializedFMUstateSize(fmu.c, state, &mut size) }, FMI2_OK);
    let mut bytes = vec![0 as c_char; size];
    assert_eq!(unsafe { fmi2SerializeFMUstate(fmu.c, state, bytes.as_mut_ptr(), size) }, FMI2_OK);
    bytes
}

/// Deserialize `bytes` into a new state of `fmu` and set it.
fn restore(fmu: &Fmu, bytes: &[c_char]) {
    let mut state: Fmi2FmuState = ptr::null_mut();
    assert_eq!(
        unsafe { fmi2DeSerializeFMUstate(fmu.c, bytes.as_ptr(), bytes.len(), &mut state) },
        FMI2_OK,
        "{:#?}",
        fmu.log.messages()
    );
    assert_eq!(unsafe { fmi2SetFMUstate(fmu.c, state) }, FMI2_OK);
    assert_eq!(unsafe { fmi2FreeFMUstate(fmu.c, &mut state) }, FMI2_OK);
}

/// serialize -> deserialize -> step replays the uninterrupted run bit for bit (every output,
/// the integrator's step and right-hand-side counters among them), at both fidelities and
/// with every integrator: into the same instance after it stepped on, and into a fresh,
/// uninitialised instance. The step-size controller's memory (last error of the PI
/// controller) is part of the state; before, it lived in the integrator object and a
/// restored run drifted by up to 2e-6 relative with different step counts.
#[test]
fn serialized_state_replays_bit_for_bit_at_every_fidelity_and_integrator() {
    let h = 1e-4;
    for (fidelity, integrator) in [(0, 0), (1, 0), (1, 1), (1, 2), (1, 3), (2, 3)] {
        let configure = |fmu: &Fmu| {
            assert_eq!(fmu.set_integer(var::FIDELITY, fidelity), FMI2_OK);
            assert_eq!(fmu.set_integer(var::INTEGRATOR, integrator), FMI2_OK);
            if integrator == 1 {
                // the fixed step must resolve the contact modes (the default 0.1 ms does not)
                assert_eq!(fmu.set_real(var::MAX_STEP, 1e-6), FMI2_OK);
            }
        };
        let a = Fmu::new();
        configure(&a);
        a.init(None);
        run(&a, 3, h);
        let mut state = a.get_state();
        let bytes = serialize(&a, state);
        assert_eq!(unsafe { fmi2FreeFMUstate(a.c, &mut state) }, FMI2_OK);
        let reference = run(&a, 4, h);
        let case = format!("fidelity {fidelity}, integrator {integrator}");

        // The same instance, after it stepped on.
        restore(&a, &bytes);
        assert_eq!(run(&a, 4, h), reference, "{case}: same instance");

        // A fresh instance (default parameters until the state sets them).
        let b = Fmu::new();
        restore(&b, &bytes);
        assert_eq!(run(&b, 4, h), reference, "{case}: fresh instance");
        if fidelity == 1 {
            let (_, ints) = output_vrs();
            assert!(ints.contains(&var::INTEGRATOR_STEPS), "step counter among the compared outputs");
        }
    }
}

#[test]
fn packaged_start_values_are_where_an_instance_starts_and_resets_to() {
    let dir = resource_dir("packaged-starts", Some(&preset_text()));
    let mut packaging = trb::packaging::Packaging::default();
    packaging.set(trb::packaging::start_value("supply", "grease", 17).unwrap());
    packaging.set(trb::packaging::start_value("cageSlipRate", "0.002", 17).unwrap());
    std::fs::write(dir.join(trb::packaging::RESOURCE), packaging.to_json()).unwrap();
    let uri = file_uri(&dir);
    let bearing = Bearing::default_preset();
    let guid = model_description::guid_with(&bearing, &packaging).unwrap();
    // The plain FMU's GUID does not describe these start values.
    refused(instantiate(Some("x"), FMI2_CO_SIMULATION, Some(default_guid()), Some(&uri), false)).assert_logged("does not match");
    let fmu =
        instantiate(Some("x"), FMI2_CO_SIMULATION, Some(&guid), Some(&uri), false).unwrap_or_else(|log| panic!("{:#?}", log.messages()));
    // The start values, read in initialization mode.
    let starts = |fmu: &Fmu| {
        assert_eq!(fmu.setup(0.0, Some(1.0)), FMI2_OK);
        assert_eq!(unsafe { fmi2EnterInitializationMode(fmu.c) }, FMI2_OK);
        let mut supply = -1;
        assert_eq!(unsafe { fmi2GetInteger(fmu.c, &var::SUPPLY, 1, &mut supply) }, FMI2_OK);
        (supply, fmu.get_reals(&[var::CAGE_SLIP_RATE]).1[0])
    };
    assert_eq!(starts(&fmu), (2, 0.002));
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, FMI2_OK, "{:#?}", fmu.log.messages());
    // The same run as an instance of the plain FMU with those values set.
    let explicit = Fmu::new();
    assert_eq!(explicit.set_integer(var::SUPPLY, 2), FMI2_OK);
    assert_eq!(explicit.set_real(var::CAGE_SLIP_RATE, 0.002), FMI2_OK);
    explicit.init(Some(1.0));
    assert_eq!(fmu.outputs(), explicit.outputs());
    assert_eq!(run(&fmu, 3, 1e-3), run(&explicit, 3, 1e-3));
    // fmi2Reset returns to the packaged start values, not the bearing's defaults.
    assert_eq!(fmu.set_integer(var::SUPPLY, 0), FMI2_ERROR, "fixed after initialization");
    assert_eq!(unsafe { fmi2Reset(fmu.c) }, FMI2_OK);
    assert_eq!(starts(&fmu), (2, 0.002));

    // A packaging file with a value out of range is refused, naming it.
    std::fs::write(dir.join(trb::packaging::RESOURCE), r#"{"start": {"supply": 7}}"#).unwrap();
    refused(instantiate(Some("x"), FMI2_CO_SIMULATION, Some(&guid), Some(&uri), false)).assert_logged("supply");
}
