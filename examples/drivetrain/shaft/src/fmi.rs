//! Minimal hand-written FMI 2.0 Co-Simulation adapter of the shaft (the Reference FMUs'
//! style): the 34 exported functions, each inside `catch_unwind` (a panic returns fmi2Fatal
//! or NULL, never unwinds into the importer), a small state machine, Real variables only.

#![allow(non_snake_case, clippy::missing_safety_doc)]

use crate::model::{Shaft, M5, V5};
use crate::variables::*;
use std::ffi::{c_char, c_int, c_uint, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::ptr;

pub type Status = c_int;
pub const OK: Status = 0;
pub const WARNING: Status = 1;
pub const ERROR: Status = 3;
pub const FATAL: Status = 4;

/// The model description's GUID (the packager writes the same constant).
pub const GUID: &str = "{6c1f3f0e-5d1a-4a49-9d51-3a7e0c2b9f14}";

type Logger = unsafe extern "C" fn(*mut c_void, *const c_char, Status, *const c_char, *const c_char, ...);

#[repr(C)]
#[derive(Clone, Copy)]
pub struct Callbacks {
    logger: Option<Logger>,
    allocate: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    free: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: Option<unsafe extern "C" fn(*mut c_void, Status)>,
    env: *mut c_void,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum State {
    Instantiated,
    Initialization,
    StepComplete,
    Terminated,
    Error,
}

const MAGIC: u64 = 0x5348_4146_5446_4d55;

pub struct Instance {
    magic: u64,
    name: CString,
    callbacks: Callbacks,
    logging: bool,
    state: State,
    values: Vec<f64>,
    kind: Vec<Option<Causality>>,
    start: Vec<f64>,
    /// The shaft displacement of the last outputs.
    q: V5,
    time: f64,
}

impl Instance {
    fn new(name: CString, callbacks: Callbacks, logging: bool) -> Instance {
        let mut values = vec![0.0; N_VR];
        let mut kind = vec![None; N_VR];
        for v in variables() {
            values[v.vr as usize] = v.start;
            kind[v.vr as usize] = Some(v.causality);
        }
        let start = values.clone();
        let mut i = Instance {
            magic: MAGIC,
            name,
            callbacks,
            logging,
            state: State::Instantiated,
            values,
            kind,
            start,
            q: [0.0; 5],
            time: 0.0,
        };
        i.write_outputs(0.0, None);
        i
    }

    fn log(&self, status: Status, message: &str) {
        if !self.logging && status < ERROR {
            return;
        }
        if let Some(logger) = self.callbacks.logger {
            let msg = CString::new(message.replace('\0', " ")).unwrap_or_default();
            let category = if status >= ERROR { c"logStatusError" } else { c"logEvents" };
            // SAFETY: the importer's logger, called with a "%s" format and one string.
            unsafe {
                logger(
                    self.callbacks.env,
                    self.name.as_ptr(),
                    status,
                    category.as_ptr(),
                    c"%s".as_ptr(),
                    msg.as_ptr(),
                )
            };
        }
    }

    fn fail(&mut self, message: &str) -> Status {
        self.log(ERROR, message);
        self.state = State::Error;
        ERROR
    }

    fn shaft(&self) -> Shaft {
        let p = |vr: u32| self.values[vr as usize];
        // Thermal interference: the shaft's axial growth between the bearings separates the
        // cones of an O pair (less preload), the cones' radial growth presses them into
        // their cups (more).
        let thermal = p(P_ALPHA) * p(IN_DELTA_T) * (p(P_RADIAL_LENGTH) - (p(P_POS_B) - p(P_POS_A)));
        Shaft {
            pos: [p(P_POS_A), p(P_POS_B)],
            preload: p(P_PRELOAD) + thermal,
            mesh_pos: p(P_MESH_POS),
            mesh_radius: p(P_MESH_RADIUS),
            mesh_force: [p(P_MESH_FA), p(P_MESH_FR), p(P_MESH_FT)],
            modulation: p(P_MESH_MOD),
            frequency: p(P_MESH_FREQ),
            ramp: p(P_RAMP),
            relaxation: p(P_RELAX),
            max_step: [p(P_MAX_TRANSLATION), p(P_MAX_TILT)],
        }
    }

    fn inputs(&self) -> ([V5; 2], [M5; 2], [[f64; 3]; 2]) {
        let mut r = [[0.0; 5]; 2];
        let mut k = [[[0.0; 5]; 5]; 2];
        let mut c = [[0.0; 3]; 2];
        for (i, base) in [IN_A, IN_B].into_iter().enumerate() {
            let at = |off: u32| self.values[(base + off) as usize];
            for m in 0..5 {
                r[i][m] = at(IN_REACTION + m as u32);
                for n in 0..5 {
                    k[i][m][n] = at(IN_STIFFNESS + (5 * m + n) as u32);
                }
            }
            for m in 0..3 {
                c[i][m] = at(IN_CONE + m as u32);
            }
        }
        (r, k, c)
    }

    /// Outputs for the current q at time t; the residual if it was computed.
    fn write_outputs(&mut self, t: f64, residual: Option<(V5, f64)>) {
        let s = self.shaft();
        for (i, base) in [OUT_A, OUT_B].into_iter().enumerate() {
            let d = s.bearing_input(i, &self.q);
            for m in 0..5 {
                self.values[base as usize + m] = d[m];
            }
        }
        let f = s.mesh_force(t);
        for m in 0..3 {
            self.values[OUT_MESH as usize + m] = f[m];
        }
        self.values[OUT_TORQUE as usize] = s.mesh_radius * f[2];
        if let Some((r, rel)) = residual {
            for m in 0..5 {
                self.values[OUT_RESIDUAL as usize + m] = r[m];
            }
            self.values[OUT_RESIDUAL_REL as usize] = rel;
        }
        for m in 0..5 {
            self.values[OUT_Q as usize + m] = self.q[m];
        }
        self.values[OUT_SPEED as usize] = self.values[P_SPEED as usize];
    }

    fn check_parameters(&self) -> Result<(), String> {
        let s = self.shaft();
        let finite = variables()
            .iter()
            .filter(|v| v.causality == Causality::Parameter)
            .all(|v| self.values[v.vr as usize].is_finite());
        if !finite {
            return Err("a parameter is not finite".into());
        }
        if s.pos[1] <= s.pos[0] {
            return Err(format!(
                "bearingB.position ({}) must be greater than bearingA.position ({})",
                s.pos[1], s.pos[0]
            ));
        }
        if !(s.relaxation > 0.0 && s.relaxation <= 1.0) {
            return Err(format!("relaxation = {} must be in (0, 1]", s.relaxation));
        }
        if !(s.max_step[0] > 0.0 && s.max_step[1] > 0.0) {
            return Err("maxStep.translation and maxStep.tilt must be > 0".into());
        }
        if s.ramp < 0.0 || s.frequency < 0.0 {
            return Err("mesh.rampTime and mesh.frequency must be >= 0".into());
        }
        Ok(())
    }

    fn set_real(&mut self, vr: &[c_uint], value: &[f64]) -> Status {
        if matches!(self.state, State::Terminated | State::Error) {
            return self.fail(&format!("fmi2SetReal not allowed in state {:?}", self.state));
        }
        for (&r, &x) in vr.iter().zip(value) {
            match self.kind.get(r as usize).copied().flatten() {
                None => return self.fail(&format!("fmi2SetReal: unknown value reference {r}")),
                Some(Causality::Output) => return self.fail(&format!("fmi2SetReal: value reference {r} is an output")),
                Some(Causality::Parameter) if self.state == State::StepComplete => {
                    return self.fail(&format!("fmi2SetReal: parameter {r} is fixed after initialization"))
                }
                Some(Causality::Input) if !x.is_finite() => return self.fail(&format!("fmi2SetReal: input {r} = {x} is not finite")),
                _ => self.values[r as usize] = x,
            }
        }
        OK
    }

    fn get_real(&mut self, vr: &[c_uint], value: &mut [f64]) -> Status {
        if self.state == State::Instantiated {
            // Outputs from the start values, as an importer may ask before initialization.
            self.write_outputs(self.time, None);
        }
        for (&r, x) in vr.iter().zip(value.iter_mut()) {
            match self.kind.get(r as usize).copied().flatten() {
                None => return self.fail(&format!("fmi2GetReal: unknown value reference {r}")),
                Some(_) => *x = self.values[r as usize],
            }
        }
        OK
    }

    fn exit_initialization(&mut self) -> Status {
        if self.state != State::Initialization {
            return self.fail("fmi2ExitInitializationMode outside initialization mode");
        }
        if let Err(e) = self.check_parameters() {
            return self.fail(&e);
        }
        self.q = [0.0; 5];
        self.write_outputs(self.time, None);
        self.state = State::StepComplete;
        OK
    }

    fn do_step(&mut self, t: f64, h: f64) -> Status {
        if self.state != State::StepComplete {
            return self.fail(&format!("fmi2DoStep in state {:?}", self.state));
        }
        if !(h > 0.0 && h.is_finite() && t.is_finite()) {
            return self.fail(&format!("fmi2DoStep: step size {h} at {t}"));
        }
        let s = self.shaft();
        let (r, k, cones) = self.inputs();
        // The state the bearing outputs belong to, its residual at the load now.
        let q_in = s.q_from_cones(&cones);
        let residual = s.residual(t, &r);
        let rel = s.relative(&residual, &s.applied(t), &r);
        let status = match s.newton(&q_in, t + h, &r, &k) {
            Some(q) if q.iter().all(|x| x.is_finite()) => {
                self.q = q;
                OK
            }
            _ => {
                self.log(
                    WARNING,
                    &format!("fmi2DoStep at t = {t}: the bearings' stiffness is singular (unloaded?): shaft held"),
                );
                WARNING
            }
        };
        self.time = t + h;
        self.write_outputs(self.time, Some((residual, rel)));
        status
    }
}

unsafe fn slice<'a, T>(p: *const T, n: usize) -> Option<&'a [T]> {
    if n == 0 {
        Some(&[])
    } else if p.is_null() {
        None
    } else {
        Some(unsafe { std::slice::from_raw_parts(p, n) })
    }
}

/// Run `body` on a live instance, a panic becoming fmi2Fatal.
unsafe fn with(c: *mut c_void, body: impl FnOnce(&mut Instance) -> Status) -> Status {
    if c.is_null() {
        return ERROR;
    }
    let inst = c.cast::<Instance>();
    // SAFETY: the importer passes a component from fmi2Instantiate.
    if unsafe { (*inst).magic } != MAGIC {
        return ERROR;
    }
    match catch_unwind(AssertUnwindSafe(|| body(unsafe { &mut *inst }))) {
        Ok(s) => s,
        Err(_) => {
            let inst = unsafe { &mut *inst };
            inst.state = State::Error;
            let _ = catch_unwind(AssertUnwindSafe(|| inst.log(FATAL, "internal error (panic)")));
            FATAL
        }
    }
}

#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    name: *const c_char,
    kind: c_int,
    guid: *const c_char,
    _resources: *const c_char,
    functions: *const Callbacks,
    _visible: c_int,
    logging_on: c_int,
) -> *mut c_void {
    if functions.is_null() {
        return ptr::null_mut();
    }
    let callbacks = unsafe { *functions };
    let r = catch_unwind(AssertUnwindSafe(|| {
        let name = if name.is_null() {
            c"shaft".to_owned()
        } else {
            unsafe { CStr::from_ptr(name) }.to_owned()
        };
        let inst = Instance::new(name, callbacks, logging_on != 0);
        if kind != 1 {
            inst.log(ERROR, "fmi2Instantiate: only Co-Simulation (fmi2CoSimulation) is supported");
            return ptr::null_mut();
        }
        let guid_ok = !guid.is_null() && unsafe { CStr::from_ptr(guid) }.to_str() == Ok(GUID);
        if !guid_ok {
            inst.log(ERROR, &format!("fmi2Instantiate: wrong GUID (expected {GUID})"));
            return ptr::null_mut();
        }
        Box::into_raw(Box::new(inst)).cast::<c_void>()
    }));
    r.unwrap_or(ptr::null_mut())
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: *mut c_void) {
    if c.is_null() || unsafe { (*c.cast::<Instance>()).magic } != MAGIC {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: made by Box::into_raw in fmi2Instantiate.
        let mut b = unsafe { Box::from_raw(c.cast::<Instance>()) };
        b.magic = 0;
    }));
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(c: *mut c_void, on: c_int, _n: usize, _cats: *const *const c_char) -> Status {
    unsafe {
        with(c, |i| {
            i.logging = on != 0;
            OK
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: *mut c_void,
    _tol_defined: c_int,
    _tol: f64,
    start: f64,
    _stop_defined: c_int,
    _stop: f64,
) -> Status {
    unsafe {
        with(c, |i| {
            if i.state != State::Instantiated {
                return i.fail("fmi2SetupExperiment after instantiation");
            }
            i.time = start;
            OK
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: *mut c_void) -> Status {
    unsafe {
        with(c, |i| {
            if i.state != State::Instantiated {
                return i.fail("fmi2EnterInitializationMode twice");
            }
            i.state = State::Initialization;
            OK
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: *mut c_void) -> Status {
    unsafe { with(c, |i| i.exit_initialization()) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Terminate(c: *mut c_void) -> Status {
    unsafe {
        with(c, |i| {
            i.state = State::Terminated;
            OK
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: *mut c_void) -> Status {
    unsafe {
        with(c, |i| {
            i.values = i.start.clone();
            i.q = [0.0; 5];
            i.time = 0.0;
            i.state = State::Instantiated;
            i.write_outputs(0.0, None);
            OK
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(c: *mut c_void, vr: *const c_uint, n: usize, value: *mut f64) -> Status {
    unsafe {
        with(c, |i| match (slice(vr, n), (n == 0 || !value.is_null())) {
            (Some(vr), true) => {
                let out = if n == 0 {
                    &mut [][..]
                } else {
                    std::slice::from_raw_parts_mut(value, n)
                };
                i.get_real(vr, out)
            }
            _ => i.fail("fmi2GetReal: NULL array"),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetReal(c: *mut c_void, vr: *const c_uint, n: usize, value: *const f64) -> Status {
    unsafe {
        with(c, |i| match (slice(vr, n), slice(value, n)) {
            (Some(vr), Some(v)) => i.set_real(vr, v),
            _ => i.fail("fmi2SetReal: NULL array"),
        })
    }
}

/// Integer, Boolean and String variables: there are none; n = 0 is a no-op.
unsafe fn none_of_type(c: *mut c_void, n: usize, what: &str) -> Status {
    unsafe {
        with(c, |i| {
            if n == 0 {
                OK
            } else {
                i.fail(&format!("{what}: the shaft has no variables of this type"))
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetInteger(c: *mut c_void, _vr: *const c_uint, n: usize, _v: *mut c_int) -> Status {
    unsafe { none_of_type(c, n, "fmi2GetInteger") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2SetInteger(c: *mut c_void, _vr: *const c_uint, n: usize, _v: *const c_int) -> Status {
    unsafe { none_of_type(c, n, "fmi2SetInteger") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBoolean(c: *mut c_void, _vr: *const c_uint, n: usize, _v: *mut c_int) -> Status {
    unsafe { none_of_type(c, n, "fmi2GetBoolean") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2SetBoolean(c: *mut c_void, _vr: *const c_uint, n: usize, _v: *const c_int) -> Status {
    unsafe { none_of_type(c, n, "fmi2SetBoolean") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2GetString(c: *mut c_void, _vr: *const c_uint, n: usize, _v: *mut *const c_char) -> Status {
    unsafe { none_of_type(c, n, "fmi2GetString") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2SetString(c: *mut c_void, _vr: *const c_uint, n: usize, _v: *const *const c_char) -> Status {
    unsafe { none_of_type(c, n, "fmi2SetString") }
}

unsafe fn unsupported(c: *mut c_void, what: &str) -> Status {
    // An error for this call only: the instance stays usable.
    unsafe {
        with(c, |i| {
            i.log(ERROR, &format!("{what} is not supported by the shaft FMU"));
            ERROR
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(c: *mut c_void, _s: *mut *mut c_void) -> Status {
    unsafe { unsupported(c, "fmi2GetFMUstate") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: *mut c_void, _s: *mut c_void) -> Status {
    unsafe { unsupported(c, "fmi2SetFMUstate") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(c: *mut c_void, _s: *mut *mut c_void) -> Status {
    unsafe { unsupported(c, "fmi2FreeFMUstate") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(c: *mut c_void, _s: *mut c_void, _n: *mut usize) -> Status {
    unsafe { unsupported(c, "fmi2SerializedFMUstateSize") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(c: *mut c_void, _s: *mut c_void, _b: *mut c_char, _n: usize) -> Status {
    unsafe { unsupported(c, "fmi2SerializeFMUstate") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(c: *mut c_void, _b: *const c_char, _n: usize, _s: *mut *mut c_void) -> Status {
    unsafe { unsupported(c, "fmi2DeSerializeFMUstate") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: *mut c_void,
    _u: *const c_uint,
    _nu: usize,
    _z: *const c_uint,
    _nz: usize,
    _dz: *const f64,
    _du: *mut f64,
) -> Status {
    unsafe { unsupported(c, "fmi2GetDirectionalDerivative") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: *mut c_void,
    _vr: *const c_uint,
    _n: usize,
    _o: *const c_int,
    _v: *const f64,
) -> Status {
    unsafe { unsupported(c, "fmi2SetRealInputDerivatives") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: *mut c_void,
    _vr: *const c_uint,
    _n: usize,
    _o: *const c_int,
    _v: *mut f64,
) -> Status {
    unsafe { unsupported(c, "fmi2GetRealOutputDerivatives") }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(c: *mut c_void, t: f64, h: f64, _no_prior: c_int) -> Status {
    unsafe { with(c, |i| i.do_step(t, h)) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: *mut c_void) -> Status {
    unsafe { unsupported(c, "fmi2CancelStep") }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(c: *mut c_void, _k: c_int, _v: *mut c_int) -> Status {
    unsafe { unsupported(c, "fmi2GetStatus") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(c: *mut c_void, k: c_int, v: *mut f64) -> Status {
    unsafe {
        with(c, |i| {
            // fmi2LastSuccessfulTime
            if k == 2 && !v.is_null() {
                *v = i.time;
                OK
            } else {
                i.fail("fmi2GetRealStatus: only fmi2LastSuccessfulTime")
            }
        })
    }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2GetIntegerStatus(c: *mut c_void, _k: c_int, _v: *mut c_int) -> Status {
    unsafe { unsupported(c, "fmi2GetIntegerStatus") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(c: *mut c_void, _k: c_int, _v: *mut c_int) -> Status {
    unsafe { unsupported(c, "fmi2GetBooleanStatus") }
}
#[no_mangle]
pub unsafe extern "C" fn fmi2GetStringStatus(c: *mut c_void, _k: c_int, _v: *mut *const c_char) -> Status {
    unsafe { unsupported(c, "fmi2GetStringStatus") }
}
