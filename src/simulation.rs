//! One running bearing element: parameters, inputs, outputs, time and the model state, with
//! access by value reference. The FMI adapter and the standalone `simulate` command both
//! drive this type with the same calls, so their results agree bit for bit.
//!
//! Semantics (co-simulation, sample and hold, or first-order input interpolation):
//! - `do_step(t, h)` advances the cage (and roller azimuths) over `[t, t+h]` with the inputs
//!   held at their current values, or ramped at the rates `set_real_derivative` gave for this
//!   step (FMI 2.0 `fmi2SetRealInputDerivatives`, order 1), then solves the element at `t + h`
//!   with the inputs it reached there. Rates apply to one step: the next holds its inputs
//!   unless rates are set again. The oil temperature follows its rate step by step (held
//!   within a step: the lubricant's viscosity is set once per step).
//! - Outputs are algebraic in the inputs at fidelity 0: reading an output after an input
//!   changed re-solves first (direct feedthrough), so `set inputs -> get outputs` is always
//!   consistent.

use crate::bearing::Bearing;
use crate::dynamic::{Dynamic, DynamicState};
use crate::model::{Fidelity, Inputs, LoadCausality, Lubrication, ModelError, Outputs, Parameters, Preload, SolveReport};
use crate::quasi_dynamic::QuasiDynamic;
use crate::quasi_static::{Linearisation, QuasiStatic};
use crate::tribology::{Piezoviscosity, TractionLaw};
use crate::variables::{self as var, Causality};
use bincode::Options as _;
use serde::{Deserialize, Serialize};
use std::fmt;

/// Why a variable access was refused.
#[derive(Debug, Clone, PartialEq)]
pub enum AccessError {
    /// No variable of this type has that value reference.
    UnknownReference(u32),
    /// The variable exists but may not be set (an output).
    NotSettable(u32),
    /// The value is not allowed for this variable (e.g. enumeration out of range).
    BadValue { vr: u32, message: String },
    /// Reading required a solve that failed.
    Model(ModelError),
}

impl fmt::Display for AccessError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AccessError::UnknownReference(vr) => write!(f, "unknown value reference {vr}"),
            AccessError::NotSettable(vr) => {
                write!(f, "variable with value reference {vr} cannot be set")
            }
            AccessError::BadValue { vr, message } => write!(f, "value reference {vr}: {message}"),
            AccessError::Model(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for AccessError {}

/// The physics of the chosen fidelity.
#[derive(Debug, Clone)]
enum Model {
    /// With the skew model, differences of the skew solve give the stiffness.
    QuasiStatic {
        qs: Box<QuasiStatic>,
        linear: Option<Box<Linearisation>>,
    },
    /// The dynamic model keeps its quasi-static sibling to start from its solution, and the
    /// quasi-static linearisation about its current state for the stiffness.
    Dynamic {
        qs: Box<QuasiStatic>,
        dynamic: Box<Dynamic>,
        linear: Box<Linearisation>,
    },
    /// The quasi-dynamic model solves its in-plane seat with its quasi-static sibling and
    /// keeps its state in the dynamic model's layout.
    QuasiDynamic {
        qs: Box<QuasiStatic>,
        qd: Box<QuasiDynamic>,
        linear: Box<Linearisation>,
    },
}

/// The serializable part of a simulation (everything but derived data).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct State {
    params: Parameters,
    inputs: Inputs,
    /// Time derivatives of the inputs over the next step (`Inputs::held()`: none).
    rates: Inputs,
    outputs: Outputs,
    time: f64,
    cage_angle: f64,
    /// Fidelity 0: the turns since the start of the cone, of the rollers' spin and of the
    /// cup, where their defects are (rad; `QuasiStatic::set_defect_turns`). Fidelity 1 keeps
    /// them in its state.
    #[serde(default)]
    defect_turns: [f64; 3],
    /// Inputs or parameters changed since the outputs were computed.
    dirty: bool,
    /// Warm start of the quasi-static solver (empty before the first solve).
    warm_start: Vec<f64>,
    report: SolveReport,
    /// State of the dynamic model (fidelity 1) or of the quasi-dynamic one (fidelity 2, in
    /// the dynamic model's layout), once initialised.
    dynamic: Option<DynamicState>,
}

/// A bearing element ready to be parameterised, initialised and stepped.
#[derive(Debug, Clone)]
pub struct Simulation {
    bearing: Bearing,
    state: State,
    model: Option<Model>,
    /// The oil temperature the model's viscosity was set for.
    model_oil_temperature: f64,
    /// The stiffness outputs are not yet those of the current state (`refresh_stiffness`).
    stiffness_stale: bool,
    /// The solve for the current inputs and parameters failed with this error: reading
    /// outputs again returns it instead of solving again (cleared by any change).
    failure: Option<ModelError>,
    /// The outputs before the current solve, restored if the solve produced non-finite values.
    backup: Outputs,
    /// The dynamic model's state at the start of the current step, restored if the step fails.
    dynamic_backup: Option<DynamicState>,
    /// At fidelity 1: the inputs last found within the model's range, and the quasi-static
    /// outputs that check computes.
    range_checked: Option<Inputs>,
    range_outputs: Outputs,
    /// The warm start at the start of the current step (fidelity 1), restored if it fails.
    warm_start_backup: Vec<f64>,
}

/// The stiffness outputs from the quasi-static linearisation about the cone position in `out`
/// (the dynamic model's state, the skew model's solution). Where the in-plane model finds no
/// equilibrium there (a state far outside the quasi-static one), the last stiffness is kept.
fn linearise(linear: &mut Linearisation, inputs: &Inputs, cage_angle: f64, out: &mut Outputs) {
    if let Ok(k) = linear.stiffness(inputs, [out.cone_x, out.cone_y, out.cone_z], cage_angle) {
        out.stiffness = k;
    }
}

/// The value references of each defect's parameters, the first's (`defect.*`) and the
/// further ones' (`defect[2].*` ...), in the order ring, roller, angle, length, width, depth,
/// edge.
const DEFECT_VRS: [[u32; 7]; 1 + crate::defect::FURTHER_DEFECTS] = [
    [
        var::DEFECT_RING,
        var::DEFECT_ROLLER,
        var::DEFECT_ANGLE,
        var::DEFECT_LENGTH,
        var::DEFECT_WIDTH,
        var::DEFECT_DEPTH,
        var::DEFECT_EDGE,
    ],
    [
        var::DEFECT_2_RING,
        var::DEFECT_2_ROLLER,
        var::DEFECT_2_ANGLE,
        var::DEFECT_2_LENGTH,
        var::DEFECT_2_WIDTH,
        var::DEFECT_2_DEPTH,
        var::DEFECT_2_EDGE,
    ],
    [
        var::DEFECT_3_RING,
        var::DEFECT_3_ROLLER,
        var::DEFECT_3_ANGLE,
        var::DEFECT_3_LENGTH,
        var::DEFECT_3_WIDTH,
        var::DEFECT_3_DEPTH,
        var::DEFECT_3_EDGE,
    ],
    [
        var::DEFECT_4_RING,
        var::DEFECT_4_ROLLER,
        var::DEFECT_4_ANGLE,
        var::DEFECT_4_LENGTH,
        var::DEFECT_4_WIDTH,
        var::DEFECT_4_DEPTH,
        var::DEFECT_4_EDGE,
    ],
];

/// Which defect (0: `defect.*`) and which of its parameters (`DEFECT_VRS`' order) the value
/// reference `vr` is.
fn defect_field(vr: u32) -> Option<(usize, usize)> {
    DEFECT_VRS
        .iter()
        .enumerate()
        .find_map(|(k, row)| row.iter().position(|v| *v == vr).map(|f| (k, f)))
}

/// Defect `k` of the parameters (0: `defect.*`, then `defect[2].*` ...).
fn defect(p: &Parameters, k: usize) -> &crate::defect::DefectParameters {
    if k == 0 {
        &p.defect
    } else {
        &p.further_defects[k - 1]
    }
}

fn defect_mut(p: &mut Parameters, k: usize) -> &mut crate::defect::DefectParameters {
    if k == 0 {
        &mut p.defect
    } else {
        &mut p.further_defects[k - 1]
    }
}

/// Magic and version of the serialized state format.
const STATE_MAGIC: &[u8; 8] = b"TRBSTAT6";

impl Simulation {
    /// A new element for `bearing`, parameters and inputs at the bearing's defaults.
    pub fn new(bearing: Bearing) -> Simulation {
        let z = bearing.roller_count;
        let params = Parameters::from_bearing(&bearing);
        let inputs = Inputs::from_bearing(&bearing);
        let cage_angle = params.cage_angle0;
        let mut outputs = Outputs::new(z);
        for j in 0..z {
            outputs.azimuth[j] = roller_azimuth(cage_angle, j, z);
        }
        Simulation {
            bearing,
            state: State {
                params,
                inputs,
                rates: Inputs::held(),
                outputs,
                time: 0.0,
                cage_angle,
                defect_turns: [0.0; 3],
                dirty: true,
                warm_start: Vec::new(),
                report: SolveReport::default(),
                dynamic: None,
            },
            model: None,
            model_oil_temperature: f64::NAN,
            stiffness_stale: false,
            failure: None,
            backup: Outputs::new(z),
            dynamic_backup: None,
            range_checked: None,
            range_outputs: Outputs::new(z),
            warm_start_backup: Vec::new(),
        }
    }

    pub fn bearing(&self) -> &Bearing {
        &self.bearing
    }
    pub fn n_rollers(&self) -> usize {
        self.bearing.roller_count
    }
    pub fn params(&self) -> &Parameters {
        &self.state.params
    }
    pub fn inputs(&self) -> &Inputs {
        &self.state.inputs
    }
    pub fn time(&self) -> f64 {
        self.state.time
    }
    pub fn last_report(&self) -> SolveReport {
        self.state.report
    }

    /// Back to the state right after `new` (fmi2Reset).
    pub fn reset(&mut self) {
        *self = Simulation::new(self.bearing.clone());
    }

    /// Check parameters and inputs, build the model, and solve at `start_time`
    /// (fmi2ExitInitializationMode).
    pub fn initialize(&mut self, start_time: f64) -> Result<SolveReport, ModelError> {
        self.state.time = start_time;
        self.state.cage_angle = self.state.params.cage_angle0;
        self.state.defect_turns = [0.0; 3];
        self.state.dirty = true;
        self.state.dynamic = None;
        self.model = None;
        self.failure = None;
        self.solve_if_dirty()
    }

    /// Advance from `t` to `t + h` with the inputs held, or ramped at the rates set for this
    /// step, then solve at `t + h`. The caller (FMI adapter) checks that `t` matches the
    /// current time.
    /// A step that fails leaves the element where the step began (its
    /// fmi2LastSuccessfulTime): time, inputs, outputs and the dynamic state, so that it can be
    /// read, saved or stepped again.
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<SolveReport, ModelError> {
        let st = &self.state;
        let start = (st.time, st.cage_angle, st.defect_turns, st.inputs, st.rates, st.dirty);
        // at fidelity 1 the range check's quasi-static solve moves the warm start (a solve
        // at fidelity 0 that fails leaves it as it was)
        let dynamic = self.state.params.fidelity != Fidelity::QuasiStatic;
        if dynamic {
            self.warm_start_backup.clone_from(&self.state.warm_start);
        }
        let result = self.step(t, h);
        if result.is_err() {
            let st = &mut self.state;
            (st.time, st.cage_angle, st.defect_turns, st.inputs, st.rates, st.dirty) = start;
            if dynamic {
                st.warm_start.clone_from(&self.warm_start_backup);
            }
            self.failure = None;
        }
        result
    }

    fn step(&mut self, t: f64, h: f64) -> Result<SolveReport, ModelError> {
        self.failure = None;
        self.state.inputs.validate(&self.bearing, &self.state.params)?;
        let ramped = self.state.rates != Inputs::held();
        let end_inputs = self.end_of_step_inputs(h);
        if ramped {
            end_inputs.validate(&self.bearing, &self.state.params)?;
        }
        self.ensure_model()?;
        if self.state.dynamic.is_none() && matches!(self.model, Some(Model::Dynamic { .. } | Model::QuasiDynamic { .. })) {
            self.solve_if_dirty()?;
        }
        if matches!(self.model, Some(Model::Dynamic { .. })) {
            // the loads the step starts and ends with, refused before any integration where
            // the quasi-static model refuses them
            let start = self.state.inputs;
            self.check_dynamic_range(&start)?;
            if ramped {
                self.check_dynamic_range(&end_inputs)?;
            }
        }
        let st = &mut self.state;
        match self.model.as_mut().expect("model built") {
            Model::QuasiStatic { qs: m, .. } => {
                // the cage speed is linear in the ring speeds: its mean over the step is that
                // at the step's middle
                let middle = st.inputs.ramped(&st.rates, 0.5 * h);
                st.cage_angle = wrap_angle(st.cage_angle + m.cage_speed(&middle) * h);
                for (turn, rate) in st.defect_turns.iter_mut().zip(m.defect_turn_rates(&middle)) {
                    *turn = wrap_angle(*turn + rate * h);
                }
            }
            Model::Dynamic { dynamic, .. } => {
                let ds = st.dynamic.as_mut().expect("dynamic state initialised");
                let backup = self.dynamic_backup.get_or_insert_with(|| ds.clone());
                backup.copy_from(ds);
                if let Err(e) = dynamic.advance_ramped(ds, &st.inputs, ramped.then_some(&st.rates), t + h) {
                    ds.copy_from(backup);
                    return Err(e);
                }
                st.cage_angle = wrap_angle(dynamic.cage_angle(ds));
            }
            Model::QuasiDynamic { qs, qd, .. } => {
                // the seat at the step's end, where the cage has turned at its speed
                // the inputs ramp at their rates over the step (held: the same throughout)
                let ds = st.dynamic.as_mut().expect("quasi-dynamic state initialised");
                let (start, rates) = (st.inputs, st.rates);
                let inputs_at = |t: f64| if t >= h { end_inputs } else { start.ramped(&rates, t) };
                let balance = qd.advance(qs, &mut st.warm_start, &mut self.range_outputs, ds, &inputs_at, h)?;
                st.report.iterations = balance.iterations;
                st.report.seat_held = balance.seat_held;
                st.cage_angle = qd.cage_angle(ds);
            }
        }
        st.time = t + h;
        st.inputs = end_inputs;
        st.rates = Inputs::held();
        st.dirty = true;
        self.solve_if_dirty()
    }

    /// At fidelity 1: refuse `inputs` whose loads the quasi-static model finds beyond the
    /// model's range (`model::load_within_range`, or no equilibrium because the displacements
    /// run away), with its message. Other failures of the quasi-static solve do not refuse: the
    /// dynamic model follows states (a bearing not seated, rollers leaving their contacts)
    /// that have no static equilibrium. Inputs checked once are not checked again.
    fn check_dynamic_range(&mut self, inputs: &Inputs) -> Result<(), ModelError> {
        if self.range_checked.as_ref() == Some(inputs) {
            return Ok(());
        }
        let Some(Model::Dynamic { qs, .. }) = self.model.as_mut() else {
            return Ok(());
        };
        let st = &mut self.state;
        match qs.solve(inputs, st.cage_angle, &mut st.warm_start, &mut self.range_outputs) {
            Err(e @ ModelError::OutOfRange { .. }) => return Err(e),
            Ok(_) | Err(_) => {}
        }
        self.range_checked = Some(*inputs);
        Ok(())
    }

    /// The inputs at the end of a step of length `h` from now.
    fn end_of_step_inputs(&self, h: f64) -> Inputs {
        let (inputs, rates) = (&self.state.inputs, &self.state.rates);
        let mut end = inputs.ramped(rates, h);
        if rates.oil_temperature != 0.0 {
            end.oil_temperature = inputs.oil_temperature + rates.oil_temperature * h;
        }
        end
    }

    /// Time derivatives of the inputs set for the next step.
    pub fn input_rates(&self) -> &Inputs {
        &self.state.rates
    }

    /// Outputs now, solving first if inputs changed.
    pub fn outputs(&mut self) -> Result<&Outputs, ModelError> {
        self.solve_if_dirty()?;
        self.refresh_stiffness();
        Ok(&self.state.outputs)
    }

    /// The stiffness outputs where a quasi-static linearisation gives them (fidelity 1, the
    /// skew model): computed when first read after a solve, since each costs a quasi-static
    /// solve (about 1 ms) that a run which never reads them should not pay.
    fn refresh_stiffness(&mut self) {
        if !self.stiffness_stale || self.ensure_model().is_err() {
            return;
        }
        let st = &mut self.state;
        match self.model.as_mut() {
            Some(Model::QuasiStatic { linear: Some(linear), .. })
            | Some(Model::Dynamic { linear, .. })
            | Some(Model::QuasiDynamic { linear, .. }) => {
                linearise(linear, &st.inputs, st.cage_angle, &mut st.outputs);
            }
            _ => {}
        }
        self.stiffness_stale = false;
    }

    /// The warnings whose conditions hold now (`warnings.rs`), as a set of bits.
    pub fn warnings(&self) -> u32 {
        let st = &self.state;
        crate::warnings::active(&self.bearing, &st.params, &st.report, &st.outputs, &st.inputs)
    }

    /// The message of warning `w` with the numbers that hold now.
    pub fn warning_message(&self, w: crate::warnings::Warning) -> String {
        let st = &self.state;
        crate::warnings::message(w, st.time, &self.bearing, &st.outputs, &st.inputs)
    }

    /// Kinetic energy stored in the moving bodies (J): the dynamic model's rollers, cage,
    /// cone translation and a moving housing; 0 for the quasi-static model and before
    /// initialisation.
    pub fn kinetic_energy(&self) -> f64 {
        match (&self.model, &self.state.dynamic) {
            (Some(Model::Dynamic { dynamic, .. }), Some(st)) => dynamic.kinetic_energy(st),
            (Some(Model::QuasiDynamic { qd, .. }), Some(st)) => qd.kinetic_energy(st),
            _ => 0.0,
        }
    }

    /// The housing's books (`crate::housing`): the energy in its support's spring (J) and the
    /// power its damper dissipates (W); zero for a rigid housing and at fidelity 0.
    pub fn housing_books(&self) -> (f64, f64) {
        match (&self.model, &self.state.dynamic) {
            (Some(Model::Dynamic { dynamic, .. }), Some(st)) => dynamic.housing_books(st),
            _ => (0.0, 0.0),
        }
    }

    /// The outputs of the last successful solve, without solving.
    pub fn last_outputs(&self) -> &Outputs {
        &self.state.outputs
    }

    /// Build the model for the parameters, with the oil's viscosity at the current oil
    /// temperature; a new oil temperature rebuilds it (the state, warm start and dynamic state,
    /// carries on).
    fn ensure_model(&mut self) -> Result<(), ModelError> {
        let oil_t = self.state.inputs.oil_temperature;
        if self.model.is_some() && self.model_oil_temperature.to_bits() != oil_t.to_bits() {
            self.model = None;
        }
        if self.model.is_none() {
            self.state.params.validate(&self.bearing)?;
            let p = self.state.params.at_oil_temperature(oil_t, self.bearing.oil_temperature);
            let qs = Box::new(QuasiStatic::new(&self.bearing, &p)?);
            self.model = Some(match p.fidelity {
                Fidelity::QuasiStatic => Model::QuasiStatic {
                    qs,
                    linear: match p.skew_model {
                        true => Some(Box::new(Linearisation::of_skew_model(&self.bearing, &p)?)),
                        false => None,
                    },
                },
                Fidelity::Dynamic => Model::Dynamic {
                    qs,
                    dynamic: Box::new(Dynamic::new(&self.bearing, &p)?),
                    linear: Box::new(Linearisation::new(&self.bearing, &p)?),
                },
                Fidelity::QuasiDynamic => Model::QuasiDynamic {
                    qs,
                    qd: Box::new(QuasiDynamic::new(Dynamic::new(&self.bearing, &p)?)),
                    linear: Box::new(Linearisation::new(&self.bearing, &p)?),
                },
            });
            self.model_oil_temperature = oil_t;
        }
        Ok(())
    }

    fn solve_if_dirty(&mut self) -> Result<SolveReport, ModelError> {
        if !self.state.dirty {
            return Ok(self.state.report);
        }
        if let Some(e) = &self.failure {
            return Err(e.clone());
        }
        let result = self.solve_now();
        if let Err(e) = &result {
            self.failure = Some(e.clone());
        }
        result
    }

    fn solve_now(&mut self) -> Result<SolveReport, ModelError> {
        self.state.inputs.validate(&self.bearing, &self.state.params)?;
        self.ensure_model()?;
        let z = self.bearing.roller_count;
        self.backup.copy_from(&self.state.outputs);
        let st = &mut self.state;
        let report = match self.model.as_mut().expect("model built") {
            Model::QuasiStatic { qs, linear } => {
                qs.set_defect_turns(st.defect_turns);
                // a refused solve may have written outputs: the last valid ones are kept
                let report = match qs.solve(&st.inputs, st.cage_angle, &mut st.warm_start, &mut st.outputs) {
                    Ok(report) => report,
                    Err(e) => {
                        st.outputs.copy_from(&self.backup);
                        return Err(e);
                    }
                };
                for j in 0..z {
                    st.outputs.azimuth[j] = roller_azimuth(st.cage_angle, j, z);
                }
                self.stiffness_stale = linear.is_some();
                report
            }
            Model::Dynamic { qs, dynamic, .. } => {
                let mut report = st.report;
                if st.dynamic.is_none() {
                    // Start from the quasi-static solution (seated rollers, epicyclic speeds).
                    report = match qs.solve(&st.inputs, st.cage_angle, &mut st.warm_start, &mut st.outputs) {
                        Ok(report) => report,
                        Err(e) => {
                            st.outputs.copy_from(&self.backup);
                            return Err(e);
                        }
                    };
                    self.range_checked = Some(st.inputs);
                    let mut start = dynamic.initial_state(qs, &st.warm_start, &st.inputs, st.cage_angle, st.time);
                    if st.params.start_steady && !st.params.start_from_rest && st.inputs.relative_speed() != 0.0 {
                        // in the steady running state when there is one (dynamic/steady.rs),
                        // else in the running state reached at the initial inputs (run_in.rs)
                        let steady = dynamic.runs_steadily(&st.inputs) && {
                            report.steady_start_failed = dynamic.settle(&mut start, &st.inputs).is_err();
                            !report.steady_start_failed
                        };
                        if !steady {
                            report.run_in_unbalanced = !dynamic.run_in(&mut start, &st.inputs).is_ok_and(|r| r.balanced);
                        }
                    }
                    st.dynamic = Some(start);
                }
                dynamic.write_outputs(st.dynamic.as_ref().expect("dynamic state"), &st.inputs, &mut st.outputs);
                st.outputs.film_ratio_raceway = qs.film_ratio_output(dynamic.slice_loads(), &st.inputs);
                self.stiffness_stale = true;
                report
            }
            Model::QuasiDynamic { qs, qd, .. } => {
                let mut report = st.report;
                if st.dynamic.is_none() {
                    qs.set_defect_turns(st.defect_turns);
                    report = match qd
                        .dynamic
                        .check_film_heating(&st.inputs)
                        .and_then(|_| qs.solve(&st.inputs, st.cage_angle, &mut st.warm_start, &mut st.outputs))
                    {
                        Ok(report) => report,
                        Err(e) => {
                            st.outputs.copy_from(&self.backup);
                            return Err(e);
                        }
                    };
                    let mut start = qd.dynamic.initial_state(qs, &st.warm_start, &st.inputs, st.cage_angle, st.time);
                    // in the steady running state at the initial inputs (every rate zero),
                    // unless started from rest; where none is found, at the seat with the
                    // epicyclic speeds
                    if st.params.start_steady && !st.params.start_from_rest && st.inputs.relative_speed() != 0.0 {
                        let mut steady = start.clone();
                        match qd.step(&mut steady, &st.warm_start, st.cage_angle, &st.inputs, f64::INFINITY) {
                            Ok(balance) => {
                                report.iterations = balance.iterations;
                                start = steady;
                            }
                            Err(_) => report.steady_start_failed = true,
                        }
                    } else {
                        qd.hold(&mut start, &st.warm_start, st.cage_angle);
                    }
                    st.dynamic = Some(start);
                }
                let ds = st.dynamic.as_ref().expect("quasi-dynamic state");
                qd.write_outputs(ds, &st.inputs, &mut st.outputs);
                st.outputs.film_ratio_raceway = qs.film_ratio_output(qd.dynamic.slice_loads(), &st.inputs);
                st.outputs.solver_iterations = report.iterations as i32;
                self.stiffness_stale = true;
                report
            }
        };
        let qs = match self.model.as_ref().expect("model built") {
            Model::QuasiStatic { qs, .. } | Model::Dynamic { qs, .. } | Model::QuasiDynamic { qs, .. } => qs,
        };
        st.outputs.oil_viscosity = qs.oil_viscosity();
        st.outputs.film_ratio_flange = qs.flange_film_ratio_output(&st.outputs.qf, &st.inputs);
        // ISO 281's modified rating life: the oil's kinematic viscosity at its temperature
        let nu = st.outputs.oil_viscosity / crate::tribology::viscosity::oil_density(st.params.oil_density, st.inputs.oil_temperature);
        let o = &mut st.outputs;
        let life = qs.rating().modified_life(
            o.life_l10,
            libm::hypot(o.reaction_fy, o.reaction_fz),
            o.reaction_fx,
            nu,
            st.inputs.relative_speed(),
            st.params.contamination_ec,
        );
        (o.life_l10m, o.life_a_iso, o.oil_kappa) = (life.l10m, life.a_iso, life.kappa);
        if !st.outputs.all_finite() {
            // Nothing that is not finite ever leaves the element: keep the last valid outputs.
            st.outputs.copy_from(&self.backup);
            return Err(ModelError::NoEquilibrium {
                message: format!(
                    "the model produced non-finite outputs at t = {} (Fx = {}, Fy = {}, Fz = {}, speed = {}); the last valid outputs are kept; the inputs are outside the model's numerical range",
                    st.time, st.inputs.fx, st.inputs.fy, st.inputs.fz, st.inputs.speed
                ),
            });
        }
        st.report = report;
        st.dirty = false;
        Ok(report)
    }

    fn parameter_changed(&mut self) {
        self.failure = None;
        self.range_checked = None;
        self.model = None;
        self.state.dynamic = None;
        self.state.warm_start.clear();
        self.state.dirty = true;
    }

    // ---------------------------------------------------------------------------------
    // Access by value reference
    // ---------------------------------------------------------------------------------

    /// The causality of value reference `vr`, if it exists.
    pub fn causality(&self, vr: u32) -> Option<Causality> {
        var::lookup(vr, self.n_rollers()).map(|(v, _)| v.causality)
    }

    /// Real value of `vr`; outputs are re-solved first if inputs changed (direct feedthrough).
    pub fn get_real(&mut self, vr: u32) -> Result<f64, AccessError> {
        if self.causality(vr) == Some(Causality::Output) {
            self.solve_if_dirty().map_err(AccessError::Model)?;
            if (var::STIFFNESS_1_1..=var::STIFFNESS_5_5).contains(&vr) {
                self.refresh_stiffness();
            }
        }
        self.last_real(vr)
    }

    /// Real value of `vr` without solving: parameters and inputs as set, outputs of the last
    /// successful solve.
    pub fn last_real(&self, vr: u32) -> Result<f64, AccessError> {
        let (row, j) = var::lookup(vr, self.n_rollers()).ok_or(AccessError::UnknownReference(vr))?;
        if row.ty != var::VarType::Real {
            return Err(AccessError::UnknownReference(vr));
        }
        let p = &self.state.params;
        let i = &self.state.inputs;
        let o = &self.state.outputs;
        Ok(match row.vr {
            var::TOLERANCE => p.tolerance,
            var::MU => p.mu,
            var::CAGE_POCKET_CLEARANCE => p.pocket_clearance,
            var::OIL_ETA0 => p.eta0,
            var::OIL_ALPHA => p.alpha,
            var::ROUGHNESS => p.roughness,
            var::CLEARANCE => p.clearance,
            var::OUTER_WAVEFORM => p.outer_waveform,
            var::CAGE_SLIP_RATE => p.cage_slip_rate,
            var::CAGE_ANGLE0 => p.cage_angle0,
            var::ROLLER_CROWN_DROP => p.crown_drop,
            var::FLANGE_MU0 => p.flange_mu0,
            var::FLANGE_MU => p.flange_mu,
            var::OIL_EYRING_STRESS => p.eyring_stress,
            var::OIL_LIMITING_SHEAR => p.limiting_shear,
            var::OIL_SHEAR_MODULUS => p.shear_modulus,
            var::OIL_BETA => p.oil_beta,
            var::OIL_CONDUCTIVITY => p.oil_conductivity,
            var::FLANGE_ROUGHNESS => p.flange_roughness,
            var::OIL_NU40 => p.oil_nu40,
            var::OIL_NU100 => p.oil_nu100,
            var::OIL_DENSITY => p.oil_density,
            var::CONTACT_DAMPING => p.contact_damping,
            var::CONE_MASS => p.cone_mass,
            var::MAX_STEP => p.max_step,
            var::WORK_BUDGET => p.work_budget,
            var::CONTAMINATION_E_C => p.contamination_ec,
            var::SUPPLY_LEVEL => p.supply_level,
            v if defect_field(v).is_some() => {
                let (k, field) = defect_field(v).expect("checked");
                let d = defect(p, k);
                [0.0, 0.0, d.angle, d.length, d.width, d.depth, 0.0][field]
            }
            var::HOUSING_MASS => p.housing.mass,
            var::HOUSING_STIFFNESS => p.housing.stiffness,
            var::HOUSING_DAMPING => p.housing.damping,
            var::ROLLER_D_D => p.roller_dd[j],
            var::SPEED => i.speed,
            var::XI => i.xi,
            var::ZETA => i.zeta,
            var::FX => i.fx,
            var::FY => i.fy,
            var::FZ => i.fz,
            var::AXIAL_DISPLACEMENT => i.axial_displacement,
            var::CUP_SPEED => i.cup_speed,
            var::DISPLACEMENT_X => i.displacement[0],
            var::DISPLACEMENT_Y => i.displacement[1],
            var::DISPLACEMENT_Z => i.displacement[2],
            var::OIL_TEMPERATURE => i.oil_temperature,
            var::FRICTION_TORQUE => o.friction_torque,
            var::FRICTION_TORQUE_RACEWAY => o.friction_torque_raceway,
            var::FRICTION_TORQUE_FLANGE => o.friction_torque_flange,
            var::FRICTION_TORQUE_CAGE => o.friction_torque_cage,
            var::FRICTION_TORQUE_CONE => o.friction_torque_cone,
            var::FRICTION_TORQUE_CUP => o.friction_torque_cup,
            var::SLIDING_FRICTION_MAX => o.sliding_friction_max,
            var::QC_MAX => o.qc_max,
            var::POWER_LOSS => o.power_loss,
            var::CONE_X => o.cone_x,
            var::CONE_Y => o.cone_y,
            var::CONE_Z => o.cone_z,
            var::REACTION_FX => o.reaction_fx,
            var::REACTION_MY => o.reaction_my,
            var::REACTION_MZ => o.reaction_mz,
            var::REACTION_FY => o.reaction_fy,
            var::REACTION_FZ => o.reaction_fz,
            var::RATING_C => o.rating_c,
            var::LIFE_L10 => o.life_l10,
            var::LIFE_L10R => o.life_l10r,
            var::RATING_C0 => o.rating_c0,
            var::SAFETY_S0 => o.safety_s0,
            var::PRESSURE_MAX => o.pressure_max,
            var::FILM_RATIO_RACEWAY => o.film_ratio_raceway,
            var::FILM_RATIO_FLANGE => o.film_ratio_flange,
            var::HOUSING_FY => o.housing_fy,
            var::HOUSING_FZ => o.housing_fz,
            var::CUP_AY => o.cup_ay,
            var::CUP_AZ => o.cup_az,
            var::LIFE_L10M => o.life_l10m,
            var::LIFE_A_ISO => o.life_a_iso,
            var::OIL_KAPPA => o.oil_kappa,
            var::OIL_VISCOSITY => o.oil_viscosity,
            v @ var::STIFFNESS_1_1..=var::STIFFNESS_5_5 => o.stiffness[(v - var::STIFFNESS_1_1) as usize],
            var::TILT_MAX => o.tilt_max,
            var::TILT_MEAN => o.tilt_mean,
            var::SKEW_MAX => o.skew_max,
            var::SKEW_MEAN => o.skew_mean,
            var::QI_MAX => o.qi_max,
            var::QO_MAX => o.qo_max,
            var::QF_MAX => o.qf_max,
            var::CAGE_SPEED => o.cage_speed,
            var::SOLVER_RESIDUAL => o.solver_residual,
            var::ROLLER_TILT => o.tilt[j],
            var::ROLLER_SKEW => o.skew[j],
            var::ROLLER_QI => o.qi[j],
            var::ROLLER_QO => o.qo[j],
            var::ROLLER_QF => o.qf[j],
            var::ROLLER_QC => o.qc[j],
            var::ROLLER_AZIMUTH => o.azimuth[j],
            var::ROLLER_NIT => o.nit[j],
            var::ROLLER_NOT => o.not[j],
            var::ROLLER_NFT => o.nft[j],
            var::ROLLER_NIS => o.nis[j],
            var::ROLLER_NOS => o.nos[j],
            var::ROLLER_NFS => o.nfs[j],
            var::ROLLER_SLIDING_FRICTION => o.sliding_friction[j],
            _ => return Err(AccessError::UnknownReference(vr)),
        })
    }

    /// Set a Real parameter or input. NaN/inf inputs are stored and rejected by the next
    /// step or solve (with the input named); NaN/inf parameters are rejected here.
    pub fn set_real(&mut self, vr: u32, value: f64) -> Result<(), AccessError> {
        let (row, j) = var::lookup(vr, self.n_rollers()).ok_or(AccessError::UnknownReference(vr))?;
        if row.ty != var::VarType::Real {
            return Err(AccessError::UnknownReference(vr));
        }
        match row.causality {
            Causality::Output => return Err(AccessError::NotSettable(vr)),
            Causality::Parameter => {
                if !value.is_finite() {
                    return Err(AccessError::BadValue {
                        vr,
                        message: format!("{} must be finite, got {value}", row.name_for(j + 1)),
                    });
                }
            }
            Causality::Input => {}
        }
        let p = &mut self.state.params;
        let i = &mut self.state.inputs;
        let slot: &mut f64 = match row.vr {
            var::TOLERANCE => &mut p.tolerance,
            var::MU => &mut p.mu,
            var::CAGE_POCKET_CLEARANCE => &mut p.pocket_clearance,
            var::OIL_ETA0 => &mut p.eta0,
            var::OIL_ALPHA => &mut p.alpha,
            var::ROUGHNESS => &mut p.roughness,
            var::CLEARANCE => &mut p.clearance,
            var::OUTER_WAVEFORM => &mut p.outer_waveform,
            var::CAGE_SLIP_RATE => &mut p.cage_slip_rate,
            var::CAGE_ANGLE0 => &mut p.cage_angle0,
            var::ROLLER_CROWN_DROP => &mut p.crown_drop,
            var::FLANGE_MU0 => &mut p.flange_mu0,
            var::FLANGE_MU => &mut p.flange_mu,
            var::OIL_EYRING_STRESS => &mut p.eyring_stress,
            var::OIL_LIMITING_SHEAR => &mut p.limiting_shear,
            var::OIL_SHEAR_MODULUS => &mut p.shear_modulus,
            var::OIL_BETA => &mut p.oil_beta,
            var::OIL_CONDUCTIVITY => &mut p.oil_conductivity,
            var::FLANGE_ROUGHNESS => &mut p.flange_roughness,
            var::OIL_NU40 => &mut p.oil_nu40,
            var::OIL_NU100 => &mut p.oil_nu100,
            var::OIL_DENSITY => &mut p.oil_density,
            var::CONTACT_DAMPING => &mut p.contact_damping,
            var::CONE_MASS => &mut p.cone_mass,
            var::MAX_STEP => &mut p.max_step,
            var::WORK_BUDGET => &mut p.work_budget,
            var::CONTAMINATION_E_C => &mut p.contamination_ec,
            var::SUPPLY_LEVEL => &mut p.supply_level,
            v if defect_field(v).is_some() => {
                let (k, field) = defect_field(v).expect("checked");
                let d = defect_mut(p, k);
                match field {
                    2 => &mut d.angle,
                    3 => &mut d.length,
                    4 => &mut d.width,
                    _ => &mut d.depth,
                }
            }
            var::HOUSING_MASS => &mut p.housing.mass,
            var::HOUSING_STIFFNESS => &mut p.housing.stiffness,
            var::HOUSING_DAMPING => &mut p.housing.damping,
            var::ROLLER_D_D => &mut p.roller_dd[j],
            _ => input_slot(i, row.vr).ok_or(AccessError::UnknownReference(vr))?,
        };
        if slot.to_bits() != value.to_bits() {
            *slot = value;
            if row.vr == var::CAGE_ANGLE0 {
                // Parameters are set before initialization: the cage starts there.
                self.state.cage_angle = value;
            }
            if row.causality == Causality::Parameter {
                self.parameter_changed();
            } else {
                self.state.dirty = true;
                self.failure = None;
            }
        }
        Ok(())
    }

    /// Set the first time derivative of the Real input `vr` for the next step (FMI 2.0
    /// `fmi2SetRealInputDerivatives` with order 1): the input ramps from its value at the
    /// step's start at `rate` per second over that step. Non-finite rates are refused here.
    pub fn set_real_derivative(&mut self, vr: u32, rate: f64) -> Result<(), AccessError> {
        let (row, j) = self.real_input(vr)?;
        if !rate.is_finite() {
            return Err(AccessError::BadValue {
                vr,
                message: format!("the derivative of {} must be finite, got {rate}", row.name_for(j + 1)),
            });
        }
        let slot = input_slot(&mut self.state.rates, row.vr).ok_or(AccessError::UnknownReference(vr))?;
        *slot = rate;
        Ok(())
    }

    /// The table row and roller index of `vr` if it is a Real input, whose time derivatives
    /// may be set.
    pub fn real_input(&self, vr: u32) -> Result<(&'static var::Variable, usize), AccessError> {
        match var::lookup(vr, self.n_rollers()) {
            None => Err(AccessError::UnknownReference(vr)),
            Some((row, j)) if row.ty != var::VarType::Real || row.causality != Causality::Input => Err(AccessError::BadValue {
                vr,
                message: format!(
                    "{} (value reference {vr}) is not a Real input: only Real inputs take time derivatives",
                    row.name_for(j + 1)
                ),
            }),
            Some(found) => Ok(found),
        }
    }

    /// Integer value of `vr`; outputs are re-solved first if inputs changed.
    pub fn get_integer(&mut self, vr: u32) -> Result<i32, AccessError> {
        if self.causality(vr) == Some(Causality::Output) {
            self.solve_if_dirty().map_err(AccessError::Model)?;
        }
        self.last_integer(vr)
    }

    /// Integer value of `vr` without solving.
    pub fn last_integer(&self, vr: u32) -> Result<i32, AccessError> {
        let (row, _) = var::lookup(vr, self.n_rollers()).ok_or(AccessError::UnknownReference(vr))?;
        if row.ty != var::VarType::Integer {
            return Err(AccessError::UnknownReference(vr));
        }
        let p = &self.state.params;
        Ok(match row.vr {
            var::FIDELITY => p.fidelity as i32,
            var::LUBRICATION => p.lubrication as i32,
            var::PRELOAD => p.preload as i32,
            var::CAUSALITY => p.causality as i32,
            var::SLICES => p.slices as i32,
            var::OUTER_LOBES => p.outer_lobes as i32,
            var::INTEGRATOR => p.integrator as i32,
            var::THREADS => p.threads as i32,
            var::TRACTION => p.traction as i32,
            var::OIL_PIEZOVISCOSITY => p.piezoviscosity as i32,
            var::SUPPLY => p.supply as i32,
            var::MIXED_LUBRICATION => p.mixed_lubrication as i32,
            v if defect_field(v).is_some() => {
                let (k, field) = defect_field(v).expect("checked");
                let d = defect(p, k);
                [d.ring as i32, d.roller as i32, 0, 0, 0, 0, d.edge as i32][field]
            }
            var::LOADED_ROLLERS => self.state.outputs.loaded_rollers,
            var::SOLVER_ITERATIONS => self.state.outputs.solver_iterations,
            var::INTEGRATOR_STEPS => self.state.outputs.integrator_steps,
            var::INTEGRATOR_RHS => self.state.outputs.integrator_rhs,
            var::INTEGRATOR_REJECTED => self.state.outputs.integrator_rejected,
            _ => return Err(AccessError::UnknownReference(vr)),
        })
    }

    pub fn set_integer(&mut self, vr: u32, value: i32) -> Result<(), AccessError> {
        let (row, _) = var::lookup(vr, self.n_rollers()).ok_or(AccessError::UnknownReference(vr))?;
        if row.ty != var::VarType::Integer {
            return Err(AccessError::UnknownReference(vr));
        }
        if row.causality == Causality::Output {
            return Err(AccessError::NotSettable(vr));
        }
        let (lo, hi) = (row.min.unwrap_or(i32::MIN as f64), row.max.unwrap_or(i32::MAX as f64));
        if (value as f64) < lo || (value as f64) > hi {
            return Err(AccessError::BadValue {
                vr,
                message: format!("{} must be in [{lo}, {hi}], got {value}", row.name),
            });
        }
        let p = &mut self.state.params;
        let old = p.clone();
        match row.vr {
            var::FIDELITY => {
                p.fidelity = match value {
                    0 => Fidelity::QuasiStatic,
                    1 => Fidelity::Dynamic,
                    _ => Fidelity::QuasiDynamic,
                }
            }
            var::LUBRICATION => p.lubrication = if value == 0 { Lubrication::Ehl } else { Lubrication::Dry },
            var::PRELOAD => p.preload = if value == 0 { Preload::Force } else { Preload::Displacement },
            var::CAUSALITY => {
                p.causality = if value == 0 {
                    LoadCausality::Force
                } else {
                    LoadCausality::Displacement
                }
            }
            var::SLICES => p.slices = value as usize,
            var::OUTER_LOBES => p.outer_lobes = value as u32,
            var::INTEGRATOR => p.integrator = value as u32,
            var::SUPPLY => p.supply = crate::tribology::Supply::from_index(value as i64).unwrap_or(p.supply),
            v if defect_field(v).is_some() => {
                let (k, field) = defect_field(v).expect("checked");
                let d = defect_mut(p, k);
                match field {
                    0 => d.ring = crate::defect::DefectRing::from_index(value).unwrap_or(d.ring),
                    1 => d.roller = value as u32,
                    _ => {
                        d.edge = if value == 0 {
                            crate::defect::Edge::Sharp
                        } else {
                            crate::defect::Edge::Rounded
                        }
                    }
                }
            }
            var::MIXED_LUBRICATION => {
                p.mixed_lubrication = crate::tribology::MixedLaw::from_index(value as i64).unwrap_or(p.mixed_lubrication)
            }
            var::THREADS => p.threads = value.max(0) as u32,
            var::TRACTION => {
                p.traction = if value == 0 {
                    TractionLaw::ThermalEyring
                } else {
                    TractionLaw::NewtonianEyring
                }
            }
            var::OIL_PIEZOVISCOSITY => {
                p.piezoviscosity = if value == 0 {
                    Piezoviscosity::Barus
                } else {
                    Piezoviscosity::Roelands
                }
            }
            _ => return Err(AccessError::UnknownReference(vr)),
        }
        if *p != old {
            self.parameter_changed();
        }
        Ok(())
    }

    pub fn get_boolean(&mut self, vr: u32) -> Result<bool, AccessError> {
        let (row, _) = var::lookup(vr, self.n_rollers()).ok_or(AccessError::UnknownReference(vr))?;
        if row.ty != var::VarType::Boolean {
            return Err(AccessError::UnknownReference(vr));
        }
        let p = &self.state.params;
        Ok(match row.vr {
            var::SKEW_MODEL => p.skew_model,
            var::GYROSCOPIC => p.gyroscopic,
            var::CENTRIFUGAL => p.centrifugal,
            var::CAGE_DYNAMIC => p.cage_dynamic,
            var::START_FROM_REST => p.start_from_rest,
            var::START_STEADY => p.start_steady,
            _ => return Err(AccessError::UnknownReference(vr)),
        })
    }

    pub fn set_boolean(&mut self, vr: u32, value: bool) -> Result<(), AccessError> {
        let (row, _) = var::lookup(vr, self.n_rollers()).ok_or(AccessError::UnknownReference(vr))?;
        if row.ty != var::VarType::Boolean {
            return Err(AccessError::UnknownReference(vr));
        }
        if row.causality == Causality::Output {
            return Err(AccessError::NotSettable(vr));
        }
        let p = &mut self.state.params;
        let slot = match row.vr {
            var::SKEW_MODEL => &mut p.skew_model,
            var::GYROSCOPIC => &mut p.gyroscopic,
            var::CENTRIFUGAL => &mut p.centrifugal,
            var::CAGE_DYNAMIC => &mut p.cage_dynamic,
            var::START_FROM_REST => &mut p.start_from_rest,
            var::START_STEADY => &mut p.start_steady,
            _ => return Err(AccessError::UnknownReference(vr)),
        };
        if *slot != value {
            *slot = value;
            self.parameter_changed();
        }
        Ok(())
    }

    // ---------------------------------------------------------------------------------
    // FMU state
    // ---------------------------------------------------------------------------------

    /// Serialize the full state (bitwise exact round trip).
    pub fn serialize_state(&self) -> Vec<u8> {
        let mut out = STATE_MAGIC.to_vec();
        let body = state_codec()
            .serialize(&SerializedState {
                bearing: &self.bearing.name,
                z: self.n_rollers(),
                state: &self.state,
            })
            .expect("state serializes");
        out.extend_from_slice(&body);
        out
    }

    /// Restore a state produced by `serialize_state` of an element of the same bearing.
    pub fn deserialize_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        let body = bytes
            .strip_prefix(STATE_MAGIC.as_slice())
            .ok_or_else(|| "not a serialized state of this FMU (bad magic)".to_string())?;
        let s: OwnedSerializedState = state_codec()
            .deserialize(body)
            .map_err(|e| format!("corrupt serialized state: {e}"))?;
        if s.bearing != self.bearing.name || s.z != self.n_rollers() {
            return Err(format!(
                "serialized state is for bearing {} with {} rollers, this instance is {} with {}",
                s.bearing,
                s.z,
                self.bearing.name,
                self.n_rollers()
            ));
        }
        if s.state.params.roller_dd.len() != self.n_rollers() || s.state.outputs.tilt.len() != self.n_rollers() {
            return Err("corrupt serialized state: per-roller arrays of the wrong length".into());
        }
        let same_params = s.state.params == self.state.params;
        self.state = s.state;
        self.failure = None;
        self.range_checked = None;
        if !same_params {
            self.model = None;
        }
        // a linearised stiffness is recomputed from the restored state when read
        self.stiffness_stale = true;
        Ok(())
    }
}

/// The field of `inputs` (values or rates) that the input `vr` sets.
fn input_slot(inputs: &mut Inputs, vr: u32) -> Option<&mut f64> {
    let i = inputs;
    Some(match vr {
        var::SPEED => &mut i.speed,
        var::XI => &mut i.xi,
        var::ZETA => &mut i.zeta,
        var::FX => &mut i.fx,
        var::FY => &mut i.fy,
        var::FZ => &mut i.fz,
        var::AXIAL_DISPLACEMENT => &mut i.axial_displacement,
        var::CUP_SPEED => &mut i.cup_speed,
        var::DISPLACEMENT_X => &mut i.displacement[0],
        var::DISPLACEMENT_Y => &mut i.displacement[1],
        var::DISPLACEMENT_Z => &mut i.displacement[2],
        var::OIL_TEMPERATURE => &mut i.oil_temperature,
        _ => return None,
    })
}

/// bincode with a size limit, so a hostile byte string cannot make us allocate without bound.
fn state_codec() -> impl bincode::Options {
    use bincode::Options;
    bincode::DefaultOptions::new().with_fixint_encoding().with_limit(1 << 26)
}

#[derive(Serialize)]
struct SerializedState<'a> {
    bearing: &'a str,
    z: usize,
    state: &'a State,
}

#[derive(Deserialize)]
struct OwnedSerializedState {
    bearing: String,
    z: usize,
    state: State,
}

/// Azimuth of roller `j` (0-based) when roller 1 sits at `cage_angle`, wrapped to [0, 2 pi).
pub fn roller_azimuth(cage_angle: f64, j: usize, z: usize) -> f64 {
    wrap_angle(cage_angle + std::f64::consts::TAU * j as f64 / z as f64)
}

fn wrap_angle(a: f64) -> f64 {
    let w = a.rem_euclid(std::f64::consts::TAU);
    if w.is_finite() {
        w
    } else {
        0.0
    }
}
