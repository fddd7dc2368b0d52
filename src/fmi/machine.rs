//! The FMI 2.0 Co-Simulation state machine and the states each function may be called in,
//! as in the Reference FMUs' `fmi2Functions.c` (co-simulation states only; this FMU never
//! returns fmi2Pending, so StepInProgress is never entered).

use std::fmt;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum State {
    Instantiated = 1 << 0,
    InitializationMode = 1 << 1,
    StepComplete = 1 << 2,
    StepInProgress = 1 << 3,
    StepFailed = 1 << 4,
    StepCanceled = 1 << 5,
    Terminated = 1 << 6,
    Error = 1 << 7,
}

/// The Fatal state: no bit, so no mask admits it (only fmi2FreeInstance works).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Machine {
    Alive(State),
    Fatal,
}

impl Machine {
    #[inline]
    pub fn allows(self, mask: u8) -> bool {
        match self {
            Machine::Alive(s) => s as u8 & mask != 0,
            Machine::Fatal => false,
        }
    }

    /// One byte for serialized FMU states.
    pub fn to_byte(self) -> u8 {
        match self {
            Machine::Alive(s) => s as u8,
            Machine::Fatal => 0,
        }
    }

    pub fn from_byte(b: u8) -> Option<Machine> {
        use State::*;
        [
            Instantiated,
            InitializationMode,
            StepComplete,
            StepInProgress,
            StepFailed,
            StepCanceled,
            Terminated,
            Error,
        ]
        .into_iter()
        .find(|s| *s as u8 == b)
        .map(Machine::Alive)
    }
}

impl fmt::Display for Machine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Machine::Alive(s) => write!(f, "{s:?}"),
            Machine::Fatal => write!(f, "Fatal"),
        }
    }
}

pub mod mask {
    use super::State::*;

    const ALL_BUT_FATAL: u8 = Instantiated as u8
        | InitializationMode as u8
        | StepComplete as u8
        | StepInProgress as u8
        | StepFailed as u8
        | StepCanceled as u8
        | Terminated as u8
        | Error as u8;

    pub const SET_DEBUG_LOGGING: u8 = ALL_BUT_FATAL;
    pub const RESET: u8 = ALL_BUT_FATAL & !(StepInProgress as u8);
    pub const SETUP_EXPERIMENT: u8 = Instantiated as u8;
    pub const ENTER_INITIALIZATION_MODE: u8 = Instantiated as u8;
    pub const EXIT_INITIALIZATION_MODE: u8 = InitializationMode as u8;
    pub const TERMINATE: u8 = StepComplete as u8 | StepFailed as u8;
    pub const GET: u8 =
        InitializationMode as u8 | StepComplete as u8 | StepFailed as u8 | StepCanceled as u8 | Terminated as u8 | Error as u8;
    /// Parameters and inputs before initialization, inputs also in StepComplete (each
    /// variable's causality and variability are checked in addition).
    pub const SET: u8 = Instantiated as u8 | InitializationMode as u8 | StepComplete as u8;
    pub const FMU_STATE: u8 = RESET;
    pub const GET_DIRECTIONAL_DERIVATIVE: u8 = GET;
    pub const SET_REAL_INPUT_DERIVATIVES: u8 = Instantiated as u8 | InitializationMode as u8 | StepComplete as u8;
    pub const GET_REAL_OUTPUT_DERIVATIVES: u8 = StepComplete as u8 | StepFailed as u8 | StepCanceled as u8 | Terminated as u8 | Error as u8;
    pub const DO_STEP: u8 = StepComplete as u8;
    pub const CANCEL_STEP: u8 = StepInProgress as u8;
    pub const GET_STATUS: u8 = StepComplete as u8 | StepInProgress as u8 | StepFailed as u8 | Terminated as u8;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_round_trip() {
        for b in 0..=255u8 {
            if let Some(m) = Machine::from_byte(b) {
                assert_eq!(m.to_byte(), b);
            }
        }
        assert_eq!(
            Machine::from_byte(State::StepComplete as u8),
            Some(Machine::Alive(State::StepComplete))
        );
        assert_eq!(Machine::from_byte(0), None);
        assert!(!Machine::Fatal.allows(0xff));
    }
}
