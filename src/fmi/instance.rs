//! One FMU instance: the state machine around a [`Simulation`], value-reference dispatch,
//! time bookkeeping, FMU states and logging. Every method checks the calling state first
//! and returns an FMI status; the C ABI layer (`exports.rs`) only converts pointers.
//!
//! Hot path (doStep, get/set with logging off): no formatting, no allocation here.

use super::logging::{Category, Logger};
use super::machine::{mask, Machine, State};
use super::resources;
use super::snapshot::{Clock, Snapshot};
use super::types::*;
use crate::model::{ModelError, Severity, SolveReport};
use crate::model_description;
use crate::packaging::Packaging;
use crate::simulation::{AccessError, Simulation};
use crate::variables::{self as var, Causality, VarType, Variability};
use crate::warnings::Warning;
use std::ffi::CStr;
use std::os::raw::c_char;

/// Marks a live instance; checked on every call (best effort against foreign pointers).
pub const MAGIC: u64 = 0x5452_425f_464d_4932; // "TRB_FMI2"

pub struct Instance {
    magic: u64,
    pub log: Logger,
    pub machine: Machine,
    sim: Simulation,
    clock: Clock,
    /// FMU states handed out by this instance and not freed yet.
    snapshots: Vec<*mut Snapshot>,
    /// The warnings logged already (`warnings.rs`: each cause once per instance).
    warned: u32,
    /// The start values packaged into the FMU, set again by fmi2Reset.
    packaging: Packaging,
}

/// Rounding noise allowed when comparing communication points.
#[inline]
fn noise(t: f64) -> f64 {
    1e-9 * t.abs().max(1.0)
}

fn type_name(ty: VarType) -> &'static str {
    match ty {
        VarType::Real => "Real",
        VarType::Integer => "Integer",
        VarType::Boolean => "Boolean",
    }
}

impl Drop for Instance {
    fn drop(&mut self) {
        self.magic = 0;
        for p in self.snapshots.drain(..) {
            // SAFETY: every registered pointer came from Box::into_raw and was not freed
            // (fmi2FreeFMUstate unregisters before freeing).
            drop(unsafe { Box::from_raw(p) });
        }
    }
}

impl Instance {
    pub fn is_live(&self) -> bool {
        self.magic == MAGIC
    }

    // -----------------------------------------------------------------------------------
    // Creation
    // -----------------------------------------------------------------------------------

    /// fmi2Instantiate. None (NULL) with a logged reason when the instance cannot be made.
    pub fn instantiate(
        name: Option<&CStr>,
        fmu_type: Fmi2Type,
        guid: Option<&CStr>,
        resource_location: Option<&CStr>,
        callbacks: &Fmi2CallbackFunctions,
        visible: bool,
        logging_on: bool,
    ) -> Option<Box<Instance>> {
        let env = callbacks.component_environment;
        let Some(name) = name.filter(|n| !n.is_empty()) else {
            let log = Logger::new(callbacks.logger, env, c"?".to_owned(), logging_on);
            log.error(format_args!("fmi2Instantiate: missing instance name"));
            return None;
        };
        let log = Logger::new(callbacks.logger, env, name.to_owned(), logging_on);
        if fmu_type != FMI2_CO_SIMULATION {
            log.error(format_args!(
                "fmi2Instantiate: fmuType = {fmu_type}, but {} supports only fmi2CoSimulation",
                model_description::MODEL_IDENTIFIER
            ));
            return None;
        }
        let Some(guid) = guid.filter(|g| !g.is_empty()) else {
            log.error(format_args!("fmi2Instantiate: missing fmuGUID"));
            return None;
        };
        let location = match resource_location.map(CStr::to_str).transpose() {
            Ok(l) => l,
            Err(_) => {
                log.error(format_args!("fmi2Instantiate: fmuResourceLocation is not valid UTF-8"));
                return None;
            }
        };
        let loaded = match resources::load(location) {
            Ok(l) => l,
            Err(e) => {
                log.error(format_args!("fmi2Instantiate: {e}"));
                return None;
            }
        };
        if let Some(w) = &loaded.warning {
            log.warning(format_args!("fmi2Instantiate: {w}"));
        }
        let (bearing, packaging) = (loaded.bearing, loaded.packaging);
        let expected = match model_description::guid_with(&bearing, &packaging) {
            Ok(g) => g,
            Err(e) => {
                log.error(format_args!("fmi2Instantiate: resources/{}: {e}", crate::packaging::RESOURCE));
                return None;
            }
        };
        if guid.to_bytes() != expected.as_bytes() {
            log.error(format_args!(
                "fmi2Instantiate: fmuGUID \"{}\" does not match the model description of bearing {} (\"{expected}\")",
                guid.to_string_lossy(),
                bearing.name
            ));
            return None;
        }
        log.event(format_args!(
            "fmi2Instantiate: bearing {} ({} rollers), resources {}, visible = {visible}",
            bearing.name,
            bearing.roller_count,
            location.filter(|l| !l.is_empty()).unwrap_or("(none)")
        ));
        let mut sim = Simulation::new(bearing);
        // The same start values applied without error to the model description's element.
        let _ = packaging.apply(&mut sim);
        Some(Box::new(Instance {
            magic: MAGIC,
            log,
            machine: Machine::Alive(State::Instantiated),
            sim,
            packaging,
            clock: Clock::NEW,
            snapshots: Vec::new(),
            warned: 0,
        }))
    }

    // -----------------------------------------------------------------------------------
    // Helpers
    // -----------------------------------------------------------------------------------

    /// Is `function` allowed in the current state? Logs the reason when not.
    #[inline]
    fn allowed(&self, state_mask: u8, function: &str) -> bool {
        if self.machine.allows(state_mask) {
            return true;
        }
        self.log.error(format_args!("{function} called in state {}", self.machine));
        false
    }

    fn null_argument(&self, function: &str, argument: &str) -> Fmi2Status {
        self.log.error(format_args!("{function}: argument {argument} must not be NULL"));
        FMI2_ERROR
    }

    /// Name of value reference `vr` for messages ("roller[3].tilt", or "?").
    fn var_name(&self, vr: u32) -> String {
        match var::lookup(vr, self.sim.n_rollers()) {
            Some((row, j)) => row.name_for(j + 1),
            None => "?".into(),
        }
    }

    /// Log why `vr` is not a variable of type `ty`.
    fn unknown(&self, function: &str, vr: u32, ty: &str) -> Fmi2Status {
        match var::lookup(vr, self.sim.n_rollers()) {
            Some((row, j)) => self.log.error(format_args!(
                "{function}: value reference {vr} is {} of type {}, not {ty}",
                row.name_for(j + 1),
                type_name(row.ty)
            )),
            None => self.log.error(format_args!("{function}: unknown value reference {vr}")),
        }
        FMI2_ERROR
    }

    fn access_error(&self, function: &str, e: &AccessError, ty: &str) -> Fmi2Status {
        match e {
            AccessError::UnknownReference(vr) => self.unknown(function, *vr, ty),
            AccessError::NotSettable(vr) => {
                self.log.error(format_args!(
                    "{function}: {} (value reference {vr}) is an output and cannot be set",
                    self.var_name(*vr)
                ));
                FMI2_ERROR
            }
            AccessError::BadValue { .. } | AccessError::Model(_) => {
                self.log.error(format_args!("{function}: {e}"));
                FMI2_ERROR
            }
        }
    }

    /// In StepComplete only inputs (and tunable parameters) may be set.
    fn settable_after_initialization(&self, function: &str, vr: u32) -> bool {
        if self.machine != Machine::Alive(State::StepComplete) {
            return true;
        }
        match var::lookup(vr, self.sim.n_rollers()) {
            Some((row, j)) if row.causality == Causality::Parameter && row.variability == Variability::Fixed => {
                self.log.error(format_args!(
                    "{function}: cannot set fixed parameter {} (value reference {vr}) after initialization",
                    row.name_for(j + 1)
                ));
                false
            }
            _ => true,
        }
    }

    /// Logs after a successful solve: solver statistics (logSolver) and, once per
    /// instance, the contact-law extrapolation warning.
    #[inline]
    fn after_solve(&mut self, report: SolveReport) {
        if self.log.enabled(Category::Solver) {
            self.log.log(
                FMI2_OK,
                Category::Solver,
                format_args!(
                    "t = {}: {} Newton iterations, relative residual {:e}",
                    self.clock.time, report.iterations, report.residual
                ),
            );
        }
        let new = self.sim.warnings() & !self.warned;
        if new != 0 {
            self.warned |= new;
            for w in Warning::ALL.into_iter().filter(|w| new & w.bit() != 0) {
                self.log.warning(format_args!("{}", self.sim.warning_message(w)));
            }
        }
    }

    /// Map a model error to a status and state, logging it.
    fn model_failure(&mut self, function: &str, e: &ModelError, discard_state: Machine) -> Fmi2Status {
        match e.severity() {
            Severity::Error => {
                self.log.error(format_args!("{function}: {e}"));
                self.machine = Machine::Alive(State::Error);
                FMI2_ERROR
            }
            Severity::Discard => {
                self.log.discard(format_args!("{function}: {e}"));
                self.machine = discard_state;
                FMI2_DISCARD
            }
        }
    }

    // -----------------------------------------------------------------------------------
    // Life cycle
    // -----------------------------------------------------------------------------------

    /// fmi2SetDebugLogging.
    ///
    /// # Safety
    /// Every non-NULL entry of `categories` points to a NUL-terminated string.
    pub unsafe fn set_debug_logging(&mut self, on: bool, categories: Option<&[*const c_char]>) -> Fmi2Status {
        const F: &str = "fmi2SetDebugLogging";
        if !self.allowed(mask::SET_DEBUG_LOGGING, F) {
            return FMI2_ERROR;
        }
        let Some(categories) = categories else {
            return self.null_argument(F, "categories[]");
        };
        if categories.is_empty() {
            self.log.set_all(on);
            return FMI2_OK;
        }
        let mut chosen = Vec::with_capacity(categories.len());
        for (i, &p) in categories.iter().enumerate() {
            if p.is_null() {
                self.log.error(format_args!("{F}: categories[{i}] is NULL"));
                return FMI2_ERROR;
            }
            // SAFETY: non-NULL entries are NUL-terminated strings (caller's contract).
            let name = unsafe { CStr::from_ptr(p) };
            match Category::from_name(name.to_bytes()) {
                Some(c) => chosen.push(c),
                None => {
                    let known: Vec<&str> = Category::ALL.iter().map(|c| c.name()).collect();
                    self.log.error(format_args!(
                        "{F}: unknown log category \"{}\" (categories are {})",
                        name.to_string_lossy(),
                        known.join(", ")
                    ));
                    return FMI2_ERROR;
                }
            }
        }
        for c in chosen {
            self.log.set_enabled(c, on);
        }
        FMI2_OK
    }

    /// fmi2SetupExperiment.
    pub fn setup_experiment(&mut self, tolerance_defined: bool, tolerance: f64, start: f64, stop_defined: bool, stop: f64) -> Fmi2Status {
        const F: &str = "fmi2SetupExperiment";
        if !self.allowed(mask::SETUP_EXPERIMENT, F) {
            return FMI2_ERROR;
        }
        if !start.is_finite() {
            self.log.error(format_args!("{F}: startTime must be finite, got {start}"));
            return FMI2_ERROR;
        }
        if stop_defined && !(stop.is_finite() && stop >= start) {
            self.log
                .error(format_args!("{F}: stopTime = {stop} must be finite and >= startTime = {start}"));
            return FMI2_ERROR;
        }
        if tolerance_defined {
            self.log.event(format_args!(
                "{F}: tolerance = {tolerance} ignored (the element's solver tolerance is the parameter `tolerance`)"
            ));
        }
        self.clock = Clock {
            start,
            stop: stop_defined.then_some(stop),
            time: start,
        };
        match self.clock.stop {
            Some(stop) => self.log.event(format_args!("{F}: startTime = {start}, stopTime = {stop}")),
            None => self.log.event(format_args!("{F}: startTime = {start}, no stop time")),
        }
        FMI2_OK
    }

    /// fmi2EnterInitializationMode.
    pub fn enter_initialization_mode(&mut self) -> Fmi2Status {
        if !self.allowed(mask::ENTER_INITIALIZATION_MODE, "fmi2EnterInitializationMode") {
            return FMI2_ERROR;
        }
        self.machine = Machine::Alive(State::InitializationMode);
        self.log.event(format_args!("fmi2EnterInitializationMode"));
        FMI2_OK
    }

    /// fmi2ExitInitializationMode: solve at the start time. A discard (no equilibrium)
    /// leaves the instance in InitializationMode so the importer may change inputs.
    pub fn exit_initialization_mode(&mut self) -> Fmi2Status {
        const F: &str = "fmi2ExitInitializationMode";
        if !self.allowed(mask::EXIT_INITIALIZATION_MODE, F) {
            return FMI2_ERROR;
        }
        match self.sim.initialize(self.clock.start) {
            Ok(report) => {
                self.clock.time = self.clock.start;
                self.machine = Machine::Alive(State::StepComplete);
                self.log.event(format_args!("{F}: initialized at t = {}", self.clock.time));
                self.after_solve(report);
                FMI2_OK
            }
            Err(e) => self.model_failure(F, &e, Machine::Alive(State::InitializationMode)),
        }
    }

    /// fmi2Terminate.
    pub fn terminate(&mut self) -> Fmi2Status {
        if !self.allowed(mask::TERMINATE, "fmi2Terminate") {
            return FMI2_ERROR;
        }
        self.machine = Machine::Alive(State::Terminated);
        self.log.event(format_args!("fmi2Terminate at t = {}", self.clock.time));
        FMI2_OK
    }

    /// fmi2Reset: back to the state right after fmi2Instantiate (FMU states stay valid).
    pub fn reset(&mut self) -> Fmi2Status {
        if !self.allowed(mask::RESET, "fmi2Reset") {
            return FMI2_ERROR;
        }
        self.sim.reset();
        if let Err(e) = self.packaging.apply(&mut self.sim) {
            self.log.error(format_args!("fmi2Reset: {e}"));
            self.machine = Machine::Alive(State::Error);
            return FMI2_ERROR;
        }
        self.clock = Clock::NEW;
        self.machine = Machine::Alive(State::Instantiated);
        self.warned = 0;
        self.log.event(format_args!("fmi2Reset"));
        FMI2_OK
    }

    // -----------------------------------------------------------------------------------
    // Getters and setters
    // -----------------------------------------------------------------------------------

    /// Outputs may be (re-)solved only where inputs can change; elsewhere the last valid
    /// outputs are returned as they are.
    #[inline]
    fn may_solve(&self) -> bool {
        matches!(self.machine, Machine::Alive(State::InitializationMode | State::StepComplete))
    }

    pub fn get_real(&mut self, vrs: Option<&[u32]>, values: Option<&mut [f64]>) -> Fmi2Status {
        self.get_numbers("fmi2GetReal", "Real", vrs, values, Simulation::get_real, Simulation::last_real)
    }

    pub fn get_integer(&mut self, vrs: Option<&[u32]>, values: Option<&mut [i32]>) -> Fmi2Status {
        self.get_numbers(
            "fmi2GetInteger",
            "Integer",
            vrs,
            values,
            Simulation::get_integer,
            Simulation::last_integer,
        )
    }

    /// fmi2GetReal / fmi2GetInteger: outputs re-solve first where inputs may have changed
    /// (`get`); after a failed solve, and in states where no solve may happen, the values of
    /// the last successful solve are returned (`last`), never NaN.
    fn get_numbers<T: Copy>(
        &mut self,
        function: &'static str,
        ty: &'static str,
        vrs: Option<&[u32]>,
        values: Option<&mut [T]>,
        get: fn(&mut Simulation, u32) -> Result<T, AccessError>,
        last: fn(&Simulation, u32) -> Result<T, AccessError>,
    ) -> Fmi2Status {
        if !self.allowed(mask::GET, function) {
            return FMI2_ERROR;
        }
        let Some(vrs) = vrs else {
            return self.null_argument(function, "vr[]");
        };
        let Some(values) = values else {
            return self.null_argument(function, "value[]");
        };
        let mut status = FMI2_OK;
        let mut solve = self.may_solve();
        for (&vr, value) in vrs.iter().zip(values.iter_mut()) {
            if solve {
                match get(&mut self.sim, vr) {
                    Ok(v) => {
                        *value = v;
                        continue;
                    }
                    Err(AccessError::Model(e)) => {
                        self.log
                            .error(format_args!("{function}: {e}; returning the outputs of the last successful solve"));
                        status = FMI2_ERROR;
                        solve = false;
                    }
                    Err(e) => return self.access_error(function, &e, ty),
                }
            }
            match last(&self.sim, vr) {
                Ok(v) => *value = v,
                Err(_) => return self.unknown(function, vr, ty),
            }
        }
        status
    }

    pub fn get_boolean(&mut self, vrs: Option<&[u32]>, values: Option<&mut [Fmi2Boolean]>) -> Fmi2Status {
        const F: &str = "fmi2GetBoolean";
        if !self.allowed(mask::GET, F) {
            return FMI2_ERROR;
        }
        let Some(vrs) = vrs else { return self.null_argument(F, "vr[]") };
        let Some(values) = values else {
            return self.null_argument(F, "value[]");
        };
        for (&vr, value) in vrs.iter().zip(values.iter_mut()) {
            match self.sim.get_boolean(vr) {
                Ok(v) => *value = v as Fmi2Boolean,
                Err(e) => return self.access_error(F, &e, "Boolean"),
            }
        }
        FMI2_OK
    }

    pub fn get_string(&mut self, vrs: Option<&[u32]>, values_present: bool) -> Fmi2Status {
        self.strings("fmi2GetString", mask::GET, vrs, values_present)
    }

    pub fn set_real(&mut self, vrs: Option<&[u32]>, values: Option<&[f64]>) -> Fmi2Status {
        self.set_values("fmi2SetReal", "Real", vrs, values, |sim, vr, v| sim.set_real(vr, v))
    }

    pub fn set_integer(&mut self, vrs: Option<&[u32]>, values: Option<&[i32]>) -> Fmi2Status {
        self.set_values("fmi2SetInteger", "Integer", vrs, values, |sim, vr, v| sim.set_integer(vr, v))
    }

    pub fn set_boolean(&mut self, vrs: Option<&[u32]>, values: Option<&[Fmi2Boolean]>) -> Fmi2Status {
        self.set_values("fmi2SetBoolean", "Boolean", vrs, values, |sim, vr, v| {
            sim.set_boolean(vr, v != FMI2_FALSE)
        })
    }

    /// fmi2SetReal / Integer / Boolean: every value reference must be settable in this state.
    fn set_values<T: Copy>(
        &mut self,
        function: &'static str,
        ty: &'static str,
        vrs: Option<&[u32]>,
        values: Option<&[T]>,
        set: impl Fn(&mut Simulation, u32, T) -> Result<(), AccessError>,
    ) -> Fmi2Status {
        if !self.allowed(mask::SET, function) {
            return FMI2_ERROR;
        }
        let Some(vrs) = vrs else {
            return self.null_argument(function, "vr[]");
        };
        let Some(values) = values else {
            return self.null_argument(function, "value[]");
        };
        for (&vr, &value) in vrs.iter().zip(values) {
            if !self.settable_after_initialization(function, vr) {
                return FMI2_ERROR;
            }
            if let Err(e) = set(&mut self.sim, vr, value) {
                return self.access_error(function, &e, ty);
            }
        }
        FMI2_OK
    }

    pub fn set_string(&mut self, vrs: Option<&[u32]>, values_present: bool) -> Fmi2Status {
        self.strings("fmi2SetString", mask::SET, vrs, values_present)
    }

    /// fmi2GetString / fmi2SetString: the FMU has no String variables, so any value
    /// reference is unknown (an empty request is fine).
    fn strings(&mut self, function: &'static str, allowed: u8, vrs: Option<&[u32]>, values_present: bool) -> Fmi2Status {
        if !self.allowed(allowed, function) {
            return FMI2_ERROR;
        }
        let Some(vrs) = vrs else {
            return self.null_argument(function, "vr[]");
        };
        if !values_present {
            return self.null_argument(function, "value[]");
        }
        match vrs.first() {
            Some(&vr) => self.unknown(function, vr, "String"),
            None => FMI2_OK,
        }
    }

    // -----------------------------------------------------------------------------------
    // Stepping
    // -----------------------------------------------------------------------------------

    /// fmi2DoStep: step from the instance's own time to `t + h` (`t` must match it within
    /// rounding noise; an end within noise of the stop time is clamped to it).
    pub fn do_step(&mut self, t: f64, h: f64) -> Fmi2Status {
        const F: &str = "fmi2DoStep";
        if !self.allowed(mask::DO_STEP, F) {
            return FMI2_ERROR;
        }
        let now = self.clock.time;
        if !(h > 0.0 && h.is_finite()) {
            self.log
                .error(format_args!("{F}: communication step size must be > 0 and finite, got {h}"));
            self.machine = Machine::Alive(State::Error);
            return FMI2_ERROR;
        }
        if !t.is_finite() || (t - now).abs() > noise(now) {
            self.log.error(format_args!(
                "{F}: currentCommunicationPoint = {t} does not match the FMU's time {now}"
            ));
            self.machine = Machine::Alive(State::Error);
            return FMI2_ERROR;
        }
        let mut end = t + h;
        if let Some(stop) = self.clock.stop {
            if end > stop {
                if end - stop <= noise(stop) {
                    end = stop;
                } else {
                    self.log
                        .error(format_args!("{F}: step from {t} to {end} goes past the stop time {stop}"));
                    self.machine = Machine::Alive(State::Error);
                    return FMI2_ERROR;
                }
            }
        }
        let step = end - now;
        if step <= 0.0 || !step.is_finite() {
            self.log.error(format_args!("{F}: nothing to step: from {now} to {end}"));
            self.machine = Machine::Alive(State::Error);
            return FMI2_ERROR;
        }
        match self.sim.do_step(now, step) {
            Ok(report) => {
                self.clock.time = self.sim.time();
                self.after_solve(report);
                FMI2_OK
            }
            Err(e) => {
                // the element is back where the step began (`Simulation::do_step`)
                let status = self.model_failure(F, &e, Machine::Alive(State::StepFailed));
                if status == FMI2_DISCARD {
                    self.log.discard(format_args!(
                        "{F}: the step from t = {now} to {end} is not taken; the FMU stays at t = {now} (fmi2LastSuccessfulTime), \
                         and fmi2SetFMUstate with an earlier state allows a retry"
                    ));
                }
                status
            }
        }
    }

    pub fn cancel_step(&mut self) -> Fmi2Status {
        self.log.error(format_args!(
            "fmi2CancelStep called in state {}: it is only allowed while fmi2DoStep is pending, \
             and this FMU never returns fmi2Pending",
            self.machine
        ));
        FMI2_ERROR
    }

    /// First derivatives ramp the inputs over the next step (`Simulation::set_real_derivative`);
    /// higher orders are accepted and not used (the interpolation is linear): a warning.
    pub fn set_real_input_derivatives(&mut self, vrs: Option<&[u32]>, orders: Option<&[i32]>, values: Option<&[f64]>) -> Fmi2Status {
        const F: &str = "fmi2SetRealInputDerivatives";
        if !self.allowed(mask::SET_REAL_INPUT_DERIVATIVES, F) {
            return FMI2_ERROR;
        }
        let (Some(vrs), Some(orders), Some(values)) = (vrs, orders, values) else {
            let missing = if vrs.is_none() {
                "vr[]"
            } else if orders.is_none() {
                "order[]"
            } else {
                "value[]"
            };
            return self.null_argument(F, missing);
        };
        let mut status = FMI2_OK;
        for ((&vr, &order), &value) in vrs.iter().zip(orders).zip(values) {
            if order < 1 {
                self.log
                    .error(format_args!("{F}: order {order} for value reference {vr}: orders start at 1"));
                return FMI2_ERROR;
            }
            let result = if order == 1 {
                self.sim.set_real_derivative(vr, value)
            } else {
                self.sim.real_input(vr).map(|_| {
                    self.log.warning(format_args!(
                        "{F}: the derivative of order {order} of value reference {vr} is not used: the inputs are interpolated linearly"
                    ));
                    status = FMI2_WARNING;
                })
            };
            if let Err(e) = result {
                return self.access_error(F, &e, "Real input");
            }
        }
        status
    }

    pub fn get_real_output_derivatives(&mut self) -> Fmi2Status {
        const F: &str = "fmi2GetRealOutputDerivatives";
        if self.allowed(mask::GET_REAL_OUTPUT_DERIVATIVES, F) {
            self.log.error(format_args!("{F}: not supported: maxOutputDerivativeOrder = 0"));
        }
        FMI2_ERROR
    }

    pub fn get_directional_derivative(&mut self) -> Fmi2Status {
        const F: &str = "fmi2GetDirectionalDerivative";
        if self.allowed(mask::GET_DIRECTIONAL_DERIVATIVE, F) {
            self.log
                .error(format_args!("{F}: not supported: providesDirectionalDerivative = false"));
        }
        FMI2_ERROR
    }

    // -----------------------------------------------------------------------------------
    // Status inquiry
    // -----------------------------------------------------------------------------------

    /// A status kind this FMU cannot report (the call is legal, the value is not available).
    fn status_not_available(&self, function: &str, kind: Fmi2StatusKind) -> Fmi2Status {
        let why = match kind {
            FMI2_DO_STEP_STATUS => "fmi2DoStepStatus is only available after fmi2DoStep returned fmi2Pending, which this FMU never does",
            FMI2_PENDING_STATUS => "fmi2PendingStatus is only available after fmi2DoStep returned fmi2Pending, which this FMU never does",
            FMI2_LAST_SUCCESSFUL_TIME => "fmi2LastSuccessfulTime is a Real status (fmi2GetRealStatus)",
            FMI2_TERMINATED => "fmi2Terminated is a Boolean status (fmi2GetBooleanStatus)",
            _ => {
                self.log.error(format_args!("{function}: unknown fmi2StatusKind {kind}"));
                return FMI2_ERROR;
            }
        };
        self.log.discard(format_args!("{function}: {why}"));
        FMI2_DISCARD
    }

    pub fn get_status(&mut self, function: &str, kind: Fmi2StatusKind) -> Fmi2Status {
        if !self.allowed(mask::GET_STATUS, function) {
            return FMI2_ERROR;
        }
        self.status_not_available(function, kind)
    }

    pub fn get_real_status(&mut self, kind: Fmi2StatusKind, value: Option<&mut f64>) -> Fmi2Status {
        const F: &str = "fmi2GetRealStatus";
        if !self.allowed(mask::GET_STATUS, F) {
            return FMI2_ERROR;
        }
        if kind != FMI2_LAST_SUCCESSFUL_TIME {
            return self.status_not_available(F, kind);
        }
        let Some(value) = value else {
            return self.null_argument(F, "value");
        };
        *value = self.clock.time;
        FMI2_OK
    }

    pub fn get_boolean_status(&mut self, kind: Fmi2StatusKind, value: Option<&mut Fmi2Boolean>) -> Fmi2Status {
        const F: &str = "fmi2GetBooleanStatus";
        if !self.allowed(mask::GET_STATUS, F) {
            return FMI2_ERROR;
        }
        if kind != FMI2_TERMINATED {
            return self.status_not_available(F, kind);
        }
        let Some(value) = value else {
            return self.null_argument(F, "value");
        };
        // The element never asks the master to end the simulation.
        *value = FMI2_FALSE;
        FMI2_OK
    }

    // -----------------------------------------------------------------------------------
    // FMU states
    // -----------------------------------------------------------------------------------

    fn owns(&self, p: Fmi2FmuState) -> bool {
        !p.is_null() && self.snapshots.iter().any(|&s| s.cast() == p)
    }

    fn snapshot_mut(&mut self, p: Fmi2FmuState) -> &mut Snapshot {
        debug_assert!(self.owns(p));
        // SAFETY: `p` is registered, so it is a live Box<Snapshot> owned by this instance.
        unsafe { &mut *p.cast::<Snapshot>() }
    }

    fn not_ours(&self, function: &str, p: Fmi2FmuState) -> Fmi2Status {
        self.log.error(format_args!(
            "{function}: FMUstate {p:p} is not a live FMU state of this instance (already freed, or from elsewhere)"
        ));
        FMI2_ERROR
    }

    fn register(&mut self, snapshot: Snapshot) -> Fmi2FmuState {
        let p = Box::into_raw(Box::new(snapshot));
        self.snapshots.push(p);
        p.cast()
    }

    /// fmi2GetFMUstate: a new snapshot if `*state` is NULL, else overwrite ours in place.
    pub fn get_fmu_state(&mut self, state: Option<&mut Fmi2FmuState>) -> Fmi2Status {
        const F: &str = "fmi2GetFMUstate";
        if !self.allowed(mask::FMU_STATE, F) {
            return FMI2_ERROR;
        }
        let Some(state) = state else {
            return self.null_argument(F, "FMUstate");
        };
        if state.is_null() {
            let snapshot = Snapshot {
                sim: self.sim.clone(),
                machine: self.machine,
                clock: self.clock,
                serialized: None,
            };
            *state = self.register(snapshot);
        } else if self.owns(*state) {
            let (machine, clock) = (self.machine, self.clock);
            // Split borrows: clone_from reads self.sim while writing the snapshot.
            let p = (*state).cast::<Snapshot>();
            // SAFETY: `p` is registered (live, ours) and distinct from `self`.
            let snapshot = unsafe { &mut *p };
            snapshot.sim.clone_from(&self.sim);
            snapshot.machine = machine;
            snapshot.clock = clock;
            snapshot.serialized = None;
        } else {
            return self.not_ours(F, *state);
        }
        FMI2_OK
    }

    pub fn set_fmu_state(&mut self, state: Fmi2FmuState) -> Fmi2Status {
        const F: &str = "fmi2SetFMUstate";
        if !self.allowed(mask::FMU_STATE, F) {
            return FMI2_ERROR;
        }
        if !self.owns(state) {
            return self.not_ours(F, state);
        }
        // SAFETY: registered, live, ours, distinct from `self`.
        let snapshot = unsafe { &*state.cast::<Snapshot>() };
        self.sim.clone_from(&snapshot.sim);
        self.machine = snapshot.machine;
        self.clock = snapshot.clock;
        FMI2_OK
    }

    /// fmi2FreeFMUstate: `*state` NULL is ignored; a state that is not ours is an error.
    pub fn free_fmu_state(&mut self, state: Option<&mut Fmi2FmuState>) -> Fmi2Status {
        const F: &str = "fmi2FreeFMUstate";
        if !self.allowed(mask::FMU_STATE, F) {
            return FMI2_ERROR;
        }
        let Some(state) = state else {
            return self.null_argument(F, "FMUstate");
        };
        if state.is_null() {
            return FMI2_OK;
        }
        let Some(i) = self.snapshots.iter().position(|&s| s.cast() == *state) else {
            return self.not_ours(F, *state);
        };
        let p = self.snapshots.swap_remove(i);
        // SAFETY: it was registered (so from Box::into_raw, not freed) and is now unregistered.
        drop(unsafe { Box::from_raw(p) });
        *state = std::ptr::null_mut();
        FMI2_OK
    }

    pub fn serialized_fmu_state_size(&mut self, state: Fmi2FmuState, size: Option<&mut usize>) -> Fmi2Status {
        const F: &str = "fmi2SerializedFMUstateSize";
        if !self.allowed(mask::FMU_STATE, F) {
            return FMI2_ERROR;
        }
        if !self.owns(state) {
            return self.not_ours(F, state);
        }
        let Some(size) = size else { return self.null_argument(F, "size") };
        *size = self.snapshot_mut(state).bytes().len();
        FMI2_OK
    }

    /// # Safety
    /// `buffer`, if not NULL, is writable for `size` bytes.
    pub unsafe fn serialize_fmu_state(&mut self, state: Fmi2FmuState, buffer: *mut Fmi2Byte, size: usize) -> Fmi2Status {
        const F: &str = "fmi2SerializeFMUstate";
        if !self.allowed(mask::FMU_STATE, F) {
            return FMI2_ERROR;
        }
        if !self.owns(state) {
            return self.not_ours(F, state);
        }
        let bytes = self.snapshot_mut(state).bytes();
        let needed = bytes.len();
        if size < needed {
            self.log
                .error(format_args!("{F}: size = {size} is too small, the state needs {needed} bytes"));
            return FMI2_ERROR;
        }
        if buffer.is_null() {
            return self.null_argument(F, "serializedState");
        }
        // SAFETY: `buffer` is writable for `size >= needed` bytes (caller's contract) and
        // cannot overlap the snapshot's own vector.
        unsafe { std::ptr::copy_nonoverlapping(bytes.as_ptr(), buffer.cast::<u8>(), needed) };
        FMI2_OK
    }

    pub fn deserialize_fmu_state(&mut self, bytes: Option<&[u8]>, state: Option<&mut Fmi2FmuState>) -> Fmi2Status {
        const F: &str = "fmi2DeSerializeFMUstate";
        if !self.allowed(mask::FMU_STATE, F) {
            return FMI2_ERROR;
        }
        let Some(bytes) = bytes else {
            return self.null_argument(F, "serializedState");
        };
        let Some(state) = state else {
            return self.null_argument(F, "FMUstate");
        };
        if !state.is_null() && !self.owns(*state) {
            return self.not_ours(F, *state);
        }
        let snapshot = match Snapshot::from_bytes(&self.sim, bytes) {
            Ok(s) => s,
            Err(e) => {
                self.log.error(format_args!("{F}: {e}"));
                return FMI2_ERROR;
            }
        };
        if state.is_null() {
            *state = self.register(snapshot);
        } else {
            *self.snapshot_mut(*state) = snapshot;
        }
        FMI2_OK
    }
}
