//! The C types of the FMI 2.0 API (`fmi2TypesPlatform.h`, `fmi2FunctionTypes.h`), written
//! by hand for the "default" platform.

use std::os::raw::{c_char, c_int, c_uint, c_void};

/// `fmi2Status`.
pub type Fmi2Status = c_int;
pub const FMI2_OK: Fmi2Status = 0;
pub const FMI2_WARNING: Fmi2Status = 1;
pub const FMI2_DISCARD: Fmi2Status = 2;
pub const FMI2_ERROR: Fmi2Status = 3;
pub const FMI2_FATAL: Fmi2Status = 4;
pub const FMI2_PENDING: Fmi2Status = 5;

/// `fmi2Type`.
pub type Fmi2Type = c_int;
pub const FMI2_MODEL_EXCHANGE: Fmi2Type = 0;
pub const FMI2_CO_SIMULATION: Fmi2Type = 1;

/// `fmi2StatusKind`.
pub type Fmi2StatusKind = c_int;
pub const FMI2_DO_STEP_STATUS: Fmi2StatusKind = 0;
pub const FMI2_PENDING_STATUS: Fmi2StatusKind = 1;
pub const FMI2_LAST_SUCCESSFUL_TIME: Fmi2StatusKind = 2;
pub const FMI2_TERMINATED: Fmi2StatusKind = 3;

pub type Fmi2Component = *mut c_void;
pub type Fmi2ComponentEnvironment = *mut c_void;
pub type Fmi2FmuState = *mut c_void;
pub type Fmi2ValueReference = c_uint;
pub type Fmi2Real = f64;
pub type Fmi2Integer = c_int;
pub type Fmi2Boolean = c_int;
pub type Fmi2Char = c_char;
pub type Fmi2String = *const c_char;
pub type Fmi2Byte = c_char;

pub const FMI2_TRUE: Fmi2Boolean = 1;
pub const FMI2_FALSE: Fmi2Boolean = 0;

/// `fmi2CallbackLogger`: `void (*)(fmi2ComponentEnvironment, fmi2String instanceName,
/// fmi2Status, fmi2String category, fmi2String message, ...)`. `message` is a printf format.
pub type Fmi2CallbackLogger = unsafe extern "C" fn(Fmi2ComponentEnvironment, Fmi2String, Fmi2Status, Fmi2String, Fmi2String, ...);
/// `fmi2CallbackAllocateMemory`.
pub type Fmi2CallbackAllocateMemory = unsafe extern "C" fn(usize, usize) -> *mut c_void;
/// `fmi2CallbackFreeMemory`.
pub type Fmi2CallbackFreeMemory = unsafe extern "C" fn(*mut c_void);
/// `fmi2StepFinished`.
pub type Fmi2StepFinished = unsafe extern "C" fn(Fmi2ComponentEnvironment, Fmi2Status);

/// `fmi2CallbackFunctions`. Every function pointer may be NULL (`None`).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct Fmi2CallbackFunctions {
    pub logger: Option<Fmi2CallbackLogger>,
    pub allocate_memory: Option<Fmi2CallbackAllocateMemory>,
    pub free_memory: Option<Fmi2CallbackFreeMemory>,
    pub step_finished: Option<Fmi2StepFinished>,
    pub component_environment: Fmi2ComponentEnvironment,
}
