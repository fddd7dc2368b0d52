//! The fuzz targets' bodies, shared by the libFuzzer targets (`fuzz_targets/`, run by
//! cargo-fuzz), the stable seeded driver (`src/bin/drive.rs`) and the regression test of the
//! main crate (`tests/fuzz_regressions.rs` includes this file). Depends only on `trb` and std.
//!
//! A target returns normally for every input; a panic (or a failed assertion here) is a
//! finding.

use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::sync::OnceLock;
use trb::bearing::{Bearing, PRESETS};
use trb::fmi::*;
use trb::model_description;
use trb::simulation::Simulation;
use trb::variables::{self as var, VarType};

/// The names of the targets.
pub const TARGETS: [&str; 3] = ["bearing_json", "fmi_calls", "dynamic_jumps"];

/// Run target `name` on `data`.
pub fn run(name: &str, data: &[u8]) {
    match name {
        "bearing_json" => bearing_json(data),
        "fmi_calls" => fmi_calls(data),
        "dynamic_jumps" => dynamic_jumps(data),
        _ => panic!("unknown fuzz target {name}"),
    }
}

// ---------------------------------------------------------------------------------------
// Target 1: the bearing JSON parser (and, for a valid bearing, the model built from it)
// ---------------------------------------------------------------------------------------

/// Parse `data` as a bearing file. An error must name something; a bearing that validates
/// must give a model description and a first solve that either succeeds with finite outputs
/// or fails with a message.
pub fn bearing_json(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    match Bearing::from_json(text) {
        Err(e) => assert!(!e.to_string().trim().is_empty(), "empty bearing error"),
        Ok(bearing) => {
            let (xml, guid) = model_description::generate(&bearing);
            assert!(xml.contains(&guid));
            let mut sim = Simulation::new(bearing);
            match sim.initialize(0.0) {
                Ok(_) => {
                    let out = sim.outputs().expect("solved");
                    assert!(out.all_finite(), "non-finite outputs for a valid bearing");
                }
                Err(e) => assert!(e.to_string().len() > 10, "unclear error: {e}"),
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// Target 2: random FMI call sequences on one instance
// ---------------------------------------------------------------------------------------

/// Reads the fuzz input as a stream of choices; zeros once exhausted.
pub struct Reader<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Reader<'a> {
    pub fn new(data: &'a [u8]) -> Reader<'a> {
        Reader { data, pos: 0 }
    }
    pub fn done(&self) -> bool {
        self.pos >= self.data.len()
    }
    pub fn u8(&mut self) -> u8 {
        let b = self.data.get(self.pos).copied().unwrap_or(0);
        self.pos += 1;
        b
    }
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }
    pub fn bytes(&mut self, n: usize) -> &'a [u8] {
        let start = self.pos.min(self.data.len());
        let end = (start + n).min(self.data.len());
        self.pos = start + n;
        &self.data[start..end]
    }
    /// A number that is likely to matter: special values, physical magnitudes, raw bits.
    pub fn f64(&mut self) -> f64 {
        const SPECIAL: [f64; 16] = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
            5e-324,
            1e-300,
            1e300,
            f64::MAX,
            1e-3,
            1e-6,
            0.1,
            1e9,
        ];
        match self.u8() % 4 {
            0 => SPECIAL[(self.u8() % 16) as usize],
            // Loads, speeds, angles, displacements of a bearing.
            1 => {
                let scale = [1e5, 1e3, 1.0, 1e-2, 1e-5][(self.u8() % 5) as usize];
                (self.u8() as f64 - 128.0) / 64.0 * scale
            }
            2 => f64::from_bits(u64::from(self.u32()) << 32 | u64::from(self.u32())),
            _ => self.u8() as f64 * 1e-3,
        }
    }
}

#[derive(Default)]
struct Sink {
    count: std::sync::atomic::AtomicUsize,
}

extern "C" fn sink_logger(env: *mut c_void, instance: *const c_char, status: c_int, category: *const c_char, message: *const c_char) {
    assert!(!env.is_null() && !instance.is_null() && !category.is_null() && !message.is_null());
    assert!((0..=4).contains(&status), "logged status {status}");
    // The message is a printf format without arguments: every % is doubled.
    let m = unsafe { CStr::from_ptr(message) }.to_bytes();
    let mut i = 0;
    while i < m.len() {
        if m[i] == b'%' {
            assert!(m.get(i + 1) == Some(&b'%'), "unescaped % in a log message");
            i += 1;
        }
        i += 1;
    }
    let sink = unsafe { &*(env as *const Sink) };
    sink.count.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
}

fn logger() -> Fmi2CallbackLogger {
    type Plain = extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char);
    let f: Plain = sink_logger;
    // SAFETY: the FMU calls the logger with the message as the format and no variadic
    // arguments, ABI compatible with this non-variadic function on x86_64 / aarch64 Linux.
    unsafe { std::mem::transmute::<Plain, Fmi2CallbackLogger>(f) }
}

struct Fixture {
    guid: CString,
    uri: CString,
    reals: Vec<u32>,
    ints: Vec<u32>,
    bools: Vec<u32>,
    /// Every value reference, plus some that do not exist.
    all: Vec<u32>,
}

/// The 32008 preset (small and fast) in a resources directory of this process.
fn fixture() -> &'static Fixture {
    static F: OnceLock<Fixture> = OnceLock::new();
    F.get_or_init(|| {
        let text = PRESETS.iter().find(|(n, _)| *n == "32008").expect("preset").1;
        let bearing = Bearing::from_json(text).expect("valid");
        let dir = std::env::temp_dir()
            .join(format!("trb-fuzz-{}", std::process::id()))
            .join("resources");
        std::fs::create_dir_all(&dir).expect("resources directory");
        std::fs::write(dir.join("bearing.json"), text).expect("bearing.json");
        let uri = format!("file://{}", dir.display());
        let all_vars = var::expanded(bearing.roller_count);
        let pick = |ty| {
            all_vars
                .iter()
                .filter(|(_, _, r)| r.ty == ty)
                .map(|(vr, _, _)| *vr)
                .collect::<Vec<u32>>()
        };
        let mut all: Vec<u32> = all_vars.iter().map(|(vr, _, _)| *vr).collect();
        all.extend([0, 999, 4242, u32::MAX, var::ROLLER_TILT + bearing.roller_count as u32]);
        Fixture {
            guid: CString::new(model_description::guid(&bearing)).expect("no NUL"),
            uri: CString::new(uri).expect("no NUL"),
            reals: pick(VarType::Real),
            ints: pick(VarType::Integer),
            bools: pick(VarType::Boolean),
            all,
        }
    })
}

fn pick<'a>(r: &mut Reader, from: &'a [u32]) -> &'a [u32] {
    let n = from.len();
    let start = r.u8() as usize % n;
    let len = (r.u8() as usize % 4).min(n - start);
    &from[start..start + len]
}

/// The callbacks of an instance whose log goes to `sink`.
fn callbacks(sink: &Sink) -> Fmi2CallbackFunctions {
    Fmi2CallbackFunctions {
        logger: Some(logger()),
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: (sink as *const Sink).cast_mut().cast(),
    }
}

/// Interpret `data` as a sequence of FMI calls on one instance (at most 48), of the fidelity
/// the first byte's bits 1-3 choose: 7 the dynamic model (1 in 8 inputs: its initialization
/// costs most), other odd values the quasi-dynamic one (2), even values the quasi-static one
/// (0); the calls may set another. Every call must return a status in 0..=3 (fmi2Fatal means
/// a caught panic), and every value read must be finite whatever the status.
pub fn fmi_calls(data: &[u8]) {
    let f = fixture();
    let sink = Box::<Sink>::default();
    let cb = callbacks(&sink);
    let mut r = Reader::new(data);
    let first = r.u8();
    let logging_on = first & 1;
    let fidelity = match (first >> 1) & 7 {
        7 => 1,
        odd if odd & 1 == 1 => 2,
        _ => 0,
    };
    let c = unsafe {
        fmi2Instantiate(
            c"fuzz".as_ptr(),
            FMI2_CO_SIMULATION,
            f.guid.as_ptr(),
            f.uri.as_ptr(),
            &cb,
            0,
            logging_on as c_int,
        )
    };
    assert!(!c.is_null(), "instantiation failed");
    if fidelity != 0 {
        let vr = var::FIDELITY;
        assert_eq!(unsafe { fmi2SetInteger(c, &vr, 1, &fidelity) }, FMI2_OK, "fmi2SetInteger fidelity");
    }
    let mut states: [Fmi2FmuState; 3] = [std::ptr::null_mut(); 3];
    let mut bytes: Vec<c_char> = Vec::new();
    let mut time = 0.0f64;
    let ok = |s: Fmi2Status, what: &str| assert!((0..=3).contains(&s), "{what} returned {s}");
    for _ in 0..48 {
        if r.done() {
            break;
        }
        let op = r.u8() % 24;
        unsafe {
            match op {
                0 | 1 => {
                    let vrs = pick(&mut r, if op == 0 { &f.reals } else { &f.all });
                    let values: Vec<f64> = vrs.iter().map(|_| r.f64()).collect();
                    ok(fmi2SetReal(c, vrs.as_ptr(), vrs.len(), values.as_ptr()), "fmi2SetReal");
                }
                2 => {
                    let vrs = pick(&mut r, &f.ints);
                    let values: Vec<i32> = vrs
                        .iter()
                        .map(|_| [0, 1, 2, -1, 200, 201, i32::MIN, 20][(r.u8() % 8) as usize])
                        .collect();
                    ok(fmi2SetInteger(c, vrs.as_ptr(), vrs.len(), values.as_ptr()), "fmi2SetInteger");
                }
                3 => {
                    let vrs = pick(&mut r, &f.bools);
                    let values: Vec<i32> = vrs.iter().map(|_| r.u8() as i32 - 1).collect();
                    ok(fmi2SetBoolean(c, vrs.as_ptr(), vrs.len(), values.as_ptr()), "fmi2SetBoolean");
                }
                4 | 5 => {
                    let vrs = pick(&mut r, if op == 4 { &f.reals } else { &f.all });
                    let mut values = vec![0.0; vrs.len()];
                    ok(fmi2GetReal(c, vrs.as_ptr(), vrs.len(), values.as_mut_ptr()), "fmi2GetReal");
                    assert!(values.iter().all(|v| v.is_finite()), "fmi2GetReal gave {values:?}");
                }
                6 => {
                    let vrs = pick(&mut r, &f.ints);
                    let mut values = vec![0; vrs.len()];
                    ok(fmi2GetInteger(c, vrs.as_ptr(), vrs.len(), values.as_mut_ptr()), "fmi2GetInteger");
                    let mut b = vec![0; 1];
                    ok(fmi2GetBoolean(c, f.bools.as_ptr(), 1, b.as_mut_ptr()), "fmi2GetBoolean");
                }
                7 | 8 | 9 => {
                    let h = if r.u8() & 1 == 0 {
                        [1e-6, 1e-3, 0.1, 1.0][(r.u8() % 4) as usize]
                    } else {
                        r.f64()
                    };
                    let t = if r.u8() % 8 == 0 { r.f64() } else { time };
                    ok(fmi2DoStep(c, t, h, r.u8() as i32 & 1), "fmi2DoStep");
                }
                10 => {
                    let (start, stop) = (if r.u8() & 1 == 0 { 0.0 } else { r.f64() }, r.f64());
                    ok(
                        fmi2SetupExperiment(c, r.u8() as i32 & 1, r.f64(), start, r.u8() as i32 & 1, stop),
                        "fmi2SetupExperiment",
                    );
                }
                11 => ok(fmi2EnterInitializationMode(c), "fmi2EnterInitializationMode"),
                12 | 13 => ok(fmi2ExitInitializationMode(c), "fmi2ExitInitializationMode"),
                14 => ok(fmi2Terminate(c), "fmi2Terminate"),
                15 => ok(fmi2Reset(c), "fmi2Reset"),
                16 => {
                    let k = (r.u8() % 3) as usize;
                    ok(fmi2GetFMUstate(c, &mut states[k]), "fmi2GetFMUstate");
                }
                17 => {
                    let k = (r.u8() % 3) as usize;
                    ok(fmi2SetFMUstate(c, states[k]), "fmi2SetFMUstate");
                }
                18 => {
                    // A stale copy of a freed handle must be refused, not used.
                    let k = (r.u8() % 3) as usize;
                    let mut copy = states[k];
                    ok(fmi2FreeFMUstate(c, &mut states[k]), "fmi2FreeFMUstate");
                    if r.u8() & 1 == 0 {
                        ok(fmi2FreeFMUstate(c, &mut copy), "fmi2FreeFMUstate (again)");
                    }
                }
                19 => {
                    let k = (r.u8() % 3) as usize;
                    let mut size = 0usize;
                    if fmi2SerializedFMUstateSize(c, states[k], &mut size) == FMI2_OK {
                        bytes = vec![0; size];
                        ok(
                            fmi2SerializeFMUstate(c, states[k], bytes.as_mut_ptr(), size),
                            "fmi2SerializeFMUstate",
                        );
                    }
                }
                20 => {
                    // Deserialize the last serialized bytes, mutated by the input.
                    let k = (r.u8() % 3) as usize;
                    let mut b = bytes.clone();
                    for _ in 0..(r.u8() % 4) {
                        if !b.is_empty() {
                            let i = r.u32() as usize % b.len();
                            b[i] = r.u8() as c_char;
                        }
                    }
                    if r.u8() % 4 == 0 {
                        b.truncate(r.u32() as usize % (b.len() + 1));
                    }
                    ok(
                        fmi2DeSerializeFMUstate(c, b.as_ptr(), b.len(), &mut states[k]),
                        "fmi2DeSerializeFMUstate",
                    );
                }
                21 => {
                    let kind = [0, 1, 2, 3, -1, 99][(r.u8() % 6) as usize];
                    let (mut st, mut re, mut i, mut b) = (0, 0.0, 0, 0);
                    let mut s: Fmi2String = std::ptr::null();
                    ok(fmi2GetStatus(c, kind, &mut st), "fmi2GetStatus");
                    ok(fmi2GetRealStatus(c, kind, &mut re), "fmi2GetRealStatus");
                    assert!(re.is_finite());
                    ok(fmi2GetIntegerStatus(c, kind, &mut i), "fmi2GetIntegerStatus");
                    ok(fmi2GetBooleanStatus(c, kind, &mut b), "fmi2GetBooleanStatus");
                    ok(fmi2GetStringStatus(c, kind, &mut s), "fmi2GetStringStatus");
                }
                22 => {
                    let junk = CString::new(r.bytes(8).iter().map(|b| b.max(&1)).copied().collect::<Vec<u8>>()).expect("no NUL");
                    let cats = [c"logEvents".as_ptr(), c"logSolver".as_ptr(), junk.as_ptr()];
                    let n = (r.u8() % 4) as usize;
                    ok(fmi2SetDebugLogging(c, r.u8() as i32 & 1, n, cats.as_ptr()), "fmi2SetDebugLogging");
                }
                _ => {
                    ok(fmi2CancelStep(c), "fmi2CancelStep");
                    let vr = [var::SPEED];
                    let mut v = [0.0];
                    ok(
                        fmi2GetDirectionalDerivative(c, vr.as_ptr(), 1, vr.as_ptr(), 1, vr.as_ptr().cast(), v.as_mut_ptr()),
                        "fmi2GetDirectionalDerivative",
                    );
                    ok(fmi2GetReal(c, vr.as_ptr(), 1, std::ptr::null_mut()), "fmi2GetReal(NULL)");
                    let mut s: [Fmi2String; 1] = [std::ptr::null()];
                    ok(fmi2GetString(c, vr.as_ptr(), 1, s.as_mut_ptr()), "fmi2GetString");
                }
            }
            // Follow the instance's time (steps, restored states, resets).
            let mut now = 0.0;
            if fmi2GetRealStatus(c, FMI2_LAST_SUCCESSFUL_TIME, &mut now) == FMI2_OK {
                assert!(now.is_finite());
                time = now;
            }
        }
    }
    unsafe { fmi2FreeInstance(c) };
    drop(sink);
}

// ---------------------------------------------------------------------------------------
// Target 3: random input jumps on a dynamic instance, each doStep bounded
// ---------------------------------------------------------------------------------------

/// Wall-clock bound of one doStep (s): the work budget stops a 1 ms step after 200 000
/// right-hand sides, about 10 s for the 32008 on one core of the reference machine; the bound
/// leaves a factor of 4 for a slower or busier machine. A step that takes longer is a
/// finding: the budget did not hold.
pub const STEP_WALL_BOUND: f64 = 40.0;

/// Read a value from 10^lo to 10^hi times `scale`, log-uniformly, with a sign.
fn magnitude(r: &mut Reader, scale: f64, lo: f64, hi: f64) -> f64 {
    let x = r.u8() as f64 / 255.0;
    let sign = if r.u8() & 1 == 0 { 1.0 } else { -1.0 };
    sign * scale * 10f64.powf(lo + (hi - lo) * x)
}

/// Interpret `data` as up to three input jumps on a fidelity-1 or fidelity-2 instance of the
/// 32008 preset (the first byte's bit 1 chooses fidelity 2; its integrator, used at fidelity
/// 1, and its slice count from the input): loads from 0.01 to 100 times C_r in any
/// direction, speeds up to twice the limiting speed either way, shaft deflections up to
/// 0.3 deg, each held over a doStep of 0.1 or 1 ms. Every doStep must return within
/// [`STEP_WALL_BOUND`] with OK, Warning or Discard; after a Discard the instance is still at
/// the step's start (fmi2LastSuccessfulTime) and the state saved after the last good step
/// restores it; every output is finite, whatever the status.
pub fn dynamic_jumps(data: &[u8]) {
    let f = fixture();
    let bearing = Bearing::from_json(PRESETS.iter().find(|(n, _)| *n == "32008").expect("preset").1).expect("valid");
    let c_r = trb::rating::BearingRating::new(&bearing, bearing.slices).c_r;
    let n_lim = trb::warnings::limiting_speed(&bearing);
    let sink = Box::<Sink>::default();
    let cb = callbacks(&sink);
    let mut r = Reader::new(data);
    let first = r.u8();
    let logging_on = (first & 1) as c_int;
    let fidelity = 1 + ((first >> 1) & 1) as i32;
    let c = unsafe {
        fmi2Instantiate(
            c"jumps".as_ptr(),
            FMI2_CO_SIMULATION,
            f.guid.as_ptr(),
            f.uri.as_ptr(),
            &cb,
            0,
            logging_on,
        )
    };
    assert!(!c.is_null(), "instantiation failed");
    let finite_outputs = |c: Fmi2Component| {
        let mut values = vec![0.0; f.reals.len()];
        let status = unsafe { fmi2GetReal(c, f.reals.as_ptr(), f.reals.len(), values.as_mut_ptr()) };
        assert!((0..=2).contains(&status), "fmi2GetReal returned {status}");
        assert!(values.iter().all(|v| v.is_finite()), "non-finite outputs");
    };
    unsafe {
        let set_i = |vr: u32, v: i32| assert_eq!(fmi2SetInteger(c, &vr, 1, &v), FMI2_OK);
        set_i(var::FIDELITY, fidelity);
        set_i(var::INTEGRATOR, (r.u8() % 4) as i32);
        set_i(var::SLICES, [5, 10, 20][(r.u8() % 3) as usize]);
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), FMI2_OK);
        assert_eq!(fmi2EnterInitializationMode(c), FMI2_OK);
        let status = fmi2ExitInitializationMode(c);
        assert!((0..=3).contains(&status), "fmi2ExitInitializationMode returned {status}");
        if status > FMI2_WARNING {
            fmi2FreeInstance(c);
            return;
        }
        let mut saved: Fmi2FmuState = std::ptr::null_mut();
        assert_eq!(fmi2GetFMUstate(c, &mut saved), FMI2_OK);
        for _ in 0..3 {
            if r.done() {
                break;
            }
            let inputs = [
                (var::FX, magnitude(&mut r, c_r, -2.0, 2.0).abs()),
                (var::FY, magnitude(&mut r, c_r, -2.0, 2.0)),
                (var::FZ, if r.u8() & 1 == 0 { 0.0 } else { magnitude(&mut r, c_r, -2.0, 2.0) }),
                (var::SPEED, 2.0 * n_lim * (r.u8() as f64 - 127.5) / 127.5),
                (var::XI, 0.3f64.to_radians() * (r.u8() as f64 - 127.5) / 127.5),
            ];
            for (vr, v) in inputs {
                assert_eq!(fmi2SetReal(c, &vr, 1, &v), FMI2_OK, "fmi2SetReal {vr} = {v}");
            }
            let mut t = 0.0;
            assert_eq!(fmi2GetRealStatus(c, FMI2_LAST_SUCCESSFUL_TIME, &mut t), FMI2_OK);
            let h = [1e-4, 1e-3][(r.u8() & 1) as usize];
            let started = std::time::Instant::now();
            let status = fmi2DoStep(c, t, h, 1);
            let wall = started.elapsed().as_secs_f64();
            assert!(
                wall < STEP_WALL_BOUND,
                "a doStep of {h} s took {wall:.1} s (status {status}) with inputs {inputs:?}"
            );
            assert!((0..=2).contains(&status), "fmi2DoStep returned {status} with inputs {inputs:?}");
            finite_outputs(c);
            if status == FMI2_DISCARD {
                let mut now = f64::NAN;
                assert_eq!(fmi2GetRealStatus(c, FMI2_LAST_SUCCESSFUL_TIME, &mut now), FMI2_OK);
                assert_eq!(now, t, "a refused step moved the time");
                assert_eq!(fmi2SetFMUstate(c, saved), FMI2_OK, "restoring the last good state");
            } else {
                assert_eq!(fmi2GetFMUstate(c, &mut saved), FMI2_OK);
            }
        }
        assert_eq!(fmi2FreeFMUstate(c, &mut saved), FMI2_OK);
        fmi2FreeInstance(c);
    }
    drop(sink);
}
