//! The 34 exported FMI 2.0 Co-Simulation functions. Each one converts its C arguments
//! (NULL-checked pointers to optional slices), runs the instance method inside
//! `catch_unwind` so that no panic crosses the C ABI (a panic returns fmi2Fatal, or NULL
//! from fmi2Instantiate, puts the instance in the Fatal state and is logged), and returns.
//!
//! Safety contract of every function: the importer follows the FMI 2.0 standard for the
//! pointers it passes (arrays valid for the given lengths, strings NUL-terminated, the
//! component one returned by fmi2Instantiate and not freed, one thread per instance at a
//! time). A NULL component, or a NULL array with a non-zero length, is reported as
//! fmi2Error instead.

#![allow(non_snake_case, clippy::missing_safety_doc)]

use super::instance::Instance;
use super::logging::Logger;
use super::machine::Machine;
use super::types::*;
use std::any::Any;
use std::ffi::CStr;
use std::os::raw::c_char;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::ptr;

// ---------------------------------------------------------------------------------------
// Argument conversion and the panic guard
// ---------------------------------------------------------------------------------------

/// `n` elements at `p`; None when `p` is NULL but `n > 0`.
unsafe fn slice<'a, T>(p: *const T, n: usize) -> Option<&'a [T]> {
    if n == 0 {
        Some(&[])
    } else if p.is_null() {
        None
    } else {
        Some(unsafe { std::slice::from_raw_parts(p, n) })
    }
}

unsafe fn slice_mut<'a, T>(p: *mut T, n: usize) -> Option<&'a mut [T]> {
    if n == 0 {
        Some(&mut [])
    } else if p.is_null() {
        None
    } else {
        Some(unsafe { std::slice::from_raw_parts_mut(p, n) })
    }
}

unsafe fn c_str<'a>(p: *const c_char) -> Option<&'a CStr> {
    if p.is_null() {
        None
    } else {
        Some(unsafe { CStr::from_ptr(p) })
    }
}

fn panic_message(payload: &(dyn Any + Send)) -> &str {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s
    } else {
        "unknown panic payload"
    }
}

/// Run `body` on the instance `c`, turning a panic into fmi2Fatal. NULL (or a pointer that
/// is not a live instance, as far as can be told) returns fmi2Error.
unsafe fn with_instance(c: Fmi2Component, function: &str, body: impl FnOnce(&mut Instance) -> Fmi2Status) -> Fmi2Status {
    if c.is_null() {
        return FMI2_ERROR;
    }
    let instance = c.cast::<Instance>();
    // SAFETY: the importer passes a component from fmi2Instantiate (see module docs).
    if !unsafe { (*instance).is_live() } {
        return FMI2_ERROR;
    }
    match catch_unwind(AssertUnwindSafe(|| body(unsafe { &mut *instance }))) {
        Ok(status) => status,
        Err(payload) => {
            // The closure and its borrow are gone; the instance memory is still ours.
            let instance = unsafe { &mut *instance };
            instance.machine = Machine::Fatal;
            let message = panic_message(&*payload);
            let _ = catch_unwind(AssertUnwindSafe(|| {
                instance.log.fatal(format_args!("{function}: internal error: {message}"))
            }));
            FMI2_FATAL
        }
    }
}

// ---------------------------------------------------------------------------------------
// Inquire platform and version
// ---------------------------------------------------------------------------------------

#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    catch_unwind(|| c"default".as_ptr()).unwrap_or(ptr::null())
}

#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    catch_unwind(|| c"2.0".as_ptr()).unwrap_or(ptr::null())
}

// ---------------------------------------------------------------------------------------
// Creation, destruction, logging
// ---------------------------------------------------------------------------------------

#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    instanceName: Fmi2String,
    fmuType: Fmi2Type,
    fmuGUID: Fmi2String,
    fmuResourceLocation: Fmi2String,
    functions: *const Fmi2CallbackFunctions,
    visible: Fmi2Boolean,
    loggingOn: Fmi2Boolean,
) -> Fmi2Component {
    if functions.is_null() {
        return ptr::null_mut();
    }
    // The struct is copied: the importer need not keep it alive.
    let callbacks = unsafe { *functions };
    let (name, guid, location) = unsafe { (c_str(instanceName), c_str(fmuGUID), c_str(fmuResourceLocation)) };
    let result = catch_unwind(AssertUnwindSafe(|| {
        Instance::instantiate(
            name,
            fmuType,
            guid,
            location,
            &callbacks,
            visible != FMI2_FALSE,
            loggingOn != FMI2_FALSE,
        )
    }));
    match result {
        Ok(Some(instance)) => Box::into_raw(instance).cast(),
        Ok(None) => ptr::null_mut(),
        Err(payload) => {
            let _ = catch_unwind(AssertUnwindSafe(|| {
                let name = name.filter(|n| !n.is_empty()).unwrap_or(c"?").to_owned();
                let log = Logger::new(callbacks.logger, callbacks.component_environment, name, false);
                log.fatal(format_args!("fmi2Instantiate: internal error: {}", panic_message(&*payload)));
            }));
            ptr::null_mut()
        }
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: Fmi2Component) {
    if c.is_null() {
        return;
    }
    let instance = c.cast::<Instance>();
    if !unsafe { (*instance).is_live() } {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: a live instance made by Box::into_raw in fmi2Instantiate, freed only here.
        let instance = unsafe { Box::from_raw(instance) };
        instance.log.event(format_args!("fmi2FreeInstance"));
        drop(instance);
    }));
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: Fmi2Component,
    loggingOn: Fmi2Boolean,
    nCategories: usize,
    categories: *const Fmi2String,
) -> Fmi2Status {
    unsafe {
        with_instance(c, "fmi2SetDebugLogging", |i| {
            i.set_debug_logging(loggingOn != FMI2_FALSE, slice(categories, nCategories))
        })
    }
}

// ---------------------------------------------------------------------------------------
// Initialization, termination, reset
// ---------------------------------------------------------------------------------------

#[no_mangle]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: Fmi2Component,
    toleranceDefined: Fmi2Boolean,
    tolerance: Fmi2Real,
    startTime: Fmi2Real,
    stopTimeDefined: Fmi2Boolean,
    stopTime: Fmi2Real,
) -> Fmi2Status {
    unsafe {
        with_instance(c, "fmi2SetupExperiment", |i| {
            i.setup_experiment(
                toleranceDefined != FMI2_FALSE,
                tolerance,
                startTime,
                stopTimeDefined != FMI2_FALSE,
                stopTime,
            )
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: Fmi2Component) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2EnterInitializationMode", |i| i.enter_initialization_mode()) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: Fmi2Component) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2ExitInitializationMode", |i| i.exit_initialization_mode()) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Terminate(c: Fmi2Component) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2Terminate", |i| i.terminate()) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: Fmi2Component) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2Reset", |i| i.reset()) }
}

// ---------------------------------------------------------------------------------------
// Getting and setting variable values
// ---------------------------------------------------------------------------------------

#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(c: Fmi2Component, vr: *const Fmi2ValueReference, nvr: usize, value: *mut Fmi2Real) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2GetReal", |i| i.get_real(slice(vr, nvr), slice_mut(value, nvr))) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetInteger(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *mut Fmi2Integer,
) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2GetInteger", |i| i.get_integer(slice(vr, nvr), slice_mut(value, nvr))) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *mut Fmi2Boolean,
) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2GetBoolean", |i| i.get_boolean(slice(vr, nvr), slice_mut(value, nvr))) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetString(c: Fmi2Component, vr: *const Fmi2ValueReference, nvr: usize, value: *mut Fmi2String) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2GetString", |i| i.get_string(slice(vr, nvr), nvr == 0 || !value.is_null())) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetReal(c: Fmi2Component, vr: *const Fmi2ValueReference, nvr: usize, value: *const Fmi2Real) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2SetReal", |i| i.set_real(slice(vr, nvr), slice(value, nvr))) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetInteger(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *const Fmi2Integer,
) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2SetInteger", |i| i.set_integer(slice(vr, nvr), slice(value, nvr))) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *const Fmi2Boolean,
) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2SetBoolean", |i| i.set_boolean(slice(vr, nvr), slice(value, nvr))) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetString(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *const Fmi2String,
) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2SetString", |i| i.set_string(slice(vr, nvr), nvr == 0 || !value.is_null())) }
}

// ---------------------------------------------------------------------------------------
// FMU state
// ---------------------------------------------------------------------------------------

#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(c: Fmi2Component, FMUstate: *mut Fmi2FmuState) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2GetFMUstate", |i| i.get_fmu_state(FMUstate.as_mut())) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: Fmi2Component, FMUstate: Fmi2FmuState) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2SetFMUstate", |i| i.set_fmu_state(FMUstate)) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(c: Fmi2Component, FMUstate: *mut Fmi2FmuState) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2FreeFMUstate", |i| i.free_fmu_state(FMUstate.as_mut())) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(c: Fmi2Component, FMUstate: Fmi2FmuState, size: *mut usize) -> Fmi2Status {
    unsafe {
        with_instance(c, "fmi2SerializedFMUstateSize", |i| {
            i.serialized_fmu_state_size(FMUstate, size.as_mut())
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: Fmi2Component,
    FMUstate: Fmi2FmuState,
    serializedState: *mut Fmi2Byte,
    size: usize,
) -> Fmi2Status {
    unsafe {
        with_instance(c, "fmi2SerializeFMUstate", |i| {
            i.serialize_fmu_state(FMUstate, serializedState, size)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: Fmi2Component,
    serializedState: *const Fmi2Byte,
    size: usize,
    FMUstate: *mut Fmi2FmuState,
) -> Fmi2Status {
    unsafe {
        with_instance(c, "fmi2DeSerializeFMUstate", |i| {
            i.deserialize_fmu_state(slice(serializedState.cast::<u8>(), size), FMUstate.as_mut())
        })
    }
}

// ---------------------------------------------------------------------------------------
// Not supported (capability flags say so)
// ---------------------------------------------------------------------------------------

#[no_mangle]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: Fmi2Component,
    _vUnknown_ref: *const Fmi2ValueReference,
    _nUnknown: usize,
    _vKnown_ref: *const Fmi2ValueReference,
    _nKnown: usize,
    _dvKnown: *const Fmi2Real,
    _dvUnknown: *mut Fmi2Real,
) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2GetDirectionalDerivative", |i| i.get_directional_derivative()) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    order: *const Fmi2Integer,
    value: *const Fmi2Real,
) -> Fmi2Status {
    unsafe {
        with_instance(c, "fmi2SetRealInputDerivatives", |i| {
            i.set_real_input_derivatives(slice(vr, nvr), slice(order, nvr), slice(value, nvr))
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: Fmi2Component,
    _vr: *const Fmi2ValueReference,
    _nvr: usize,
    _order: *const Fmi2Integer,
    _value: *mut Fmi2Real,
) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2GetRealOutputDerivatives", |i| i.get_real_output_derivatives()) }
}

// ---------------------------------------------------------------------------------------
// Co-simulation: stepping and status
// ---------------------------------------------------------------------------------------

#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(
    c: Fmi2Component,
    currentCommunicationPoint: Fmi2Real,
    communicationStepSize: Fmi2Real,
    _noSetFMUStatePriorToCurrentPoint: Fmi2Boolean,
) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2DoStep", |i| i.do_step(currentCommunicationPoint, communicationStepSize)) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: Fmi2Component) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2CancelStep", |i| i.cancel_step()) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(c: Fmi2Component, s: Fmi2StatusKind, value: *mut Fmi2Status) -> Fmi2Status {
    let _ = value;
    unsafe { with_instance(c, "fmi2GetStatus", |i| i.get_status("fmi2GetStatus", s)) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(c: Fmi2Component, s: Fmi2StatusKind, value: *mut Fmi2Real) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2GetRealStatus", |i| i.get_real_status(s, value.as_mut())) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetIntegerStatus(c: Fmi2Component, s: Fmi2StatusKind, value: *mut Fmi2Integer) -> Fmi2Status {
    let _ = value;
    unsafe { with_instance(c, "fmi2GetIntegerStatus", |i| i.get_status("fmi2GetIntegerStatus", s)) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(c: Fmi2Component, s: Fmi2StatusKind, value: *mut Fmi2Boolean) -> Fmi2Status {
    unsafe { with_instance(c, "fmi2GetBooleanStatus", |i| i.get_boolean_status(s, value.as_mut())) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStringStatus(c: Fmi2Component, s: Fmi2StatusKind, value: *mut Fmi2String) -> Fmi2Status {
    let _ = value;
    unsafe { with_instance(c, "fmi2GetStringStatus", |i| i.get_status("fmi2GetStringStatus", s)) }
}

/// The names of all exported functions (for tests and the packager).
pub const EXPORTED: [&str; 34] = [
    "fmi2GetTypesPlatform",
    "fmi2GetVersion",
    "fmi2SetDebugLogging",
    "fmi2Instantiate",
    "fmi2FreeInstance",
    "fmi2SetupExperiment",
    "fmi2EnterInitializationMode",
    "fmi2ExitInitializationMode",
    "fmi2Terminate",
    "fmi2Reset",
    "fmi2GetReal",
    "fmi2GetInteger",
    "fmi2GetBoolean",
    "fmi2GetString",
    "fmi2SetReal",
    "fmi2SetInteger",
    "fmi2SetBoolean",
    "fmi2SetString",
    "fmi2GetFMUstate",
    "fmi2SetFMUstate",
    "fmi2FreeFMUstate",
    "fmi2SerializedFMUstateSize",
    "fmi2SerializeFMUstate",
    "fmi2DeSerializeFMUstate",
    "fmi2GetDirectionalDerivative",
    "fmi2SetRealInputDerivatives",
    "fmi2GetRealOutputDerivatives",
    "fmi2DoStep",
    "fmi2CancelStep",
    "fmi2GetStatus",
    "fmi2GetRealStatus",
    "fmi2GetIntegerStatus",
    "fmi2GetBooleanStatus",
    "fmi2GetStringStatus",
];
