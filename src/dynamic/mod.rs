//! Dynamic bearing model, fidelity 1 (MODEL.md section 5) [W25, after Gupta 1984].
//!
//! Bodies and states (SI):
//! - cone: 3 translations (x, y, z) and their velocities; its spin `speed` about its own
//!   axis and its misalignment (`xi`, `zeta`, rotations about y and z through the origin)
//!   are imposed. In displacement preload x follows the input `axialDisplacement`.
//! - cage: radial translations (y, z), rotation about the bearing axis, their rates (the
//!   axial cage position is held by the roller ends); or, with `cage.dynamic` = false, a
//!   kinematic cage centred on the axis at the mean orbit of the rollers.
//! - the housing (`housing.mass` > 0, `crate::housing`): the cup's radial translations and
//!   their velocities; the turns of what carries local defects (`crate::defect`): the cup's,
//!   the cone's, and each defective roller's spin angle (`Layout`).
//! - each roller: centre of mass in cylindrical coordinates (axial x, radial offset dr from
//!   the pitch radius, azimuth psi) with rates; attitude as tilt theta (rotation of the axis
//!   in its axial plane, positive outwards) and skew phi (rotation about the in-plane normal
//!   m); angular velocity in the roller's azimuth frame (e_x, e_r, e_t). The spin angle
//!   itself does not enter (axisymmetric roller).
//!
//! Equations: translation m (x'', r'' - r psi'^2, r psi'' + 2 r' psi') = F (centrifugal and
//! Coriolis terms of the cylindrical frame); rotation from Euler's equations of the
//! axisymmetric roller in vector form, dH/dt = M with H = I_a (w.a) a + I_t (w - (w.a) a),
//! which gives w' = (M.a / I_a) a + [M - (M.a) a - (I_a - I_t)(w.a)(w x a)] / I_t (the last
//! term is the gyroscopic coupling of spin and orbit), written in the rotating azimuth frame.
//!
//! Contacts (`contacts.rs`): sliced roller/raceway contacts with the full 3-D position and
//! attitude of every slice (tilt and skew move the slice contact points), the spherical
//! roller end on the conical rib (Hertz point contact), cage pocket (hydrodynamic or
//! Hertz with restitution damping), cage on its guiding land (short journal bearing or
//! Hertz); traction from film thickness, film ratio and the boundary / mixed / full-film law
//! [W25], or dry Coulomb. Normal contacts carry a viscous damping of ratio `contact.damping`.
//!
//! The state starts from the quasi-static solution (seated rollers, epicyclic speeds), so no
//! start-up transient is simulated unless `startFromRest` asks for it. Integration:
//! `integrator.rs` (adaptive Dormand-Prince 5(4) honouring `tolerance`).

pub(crate) mod contacts;
pub mod integrator;
pub mod jacobian;
pub mod multistep;
pub mod rosenbrock;
pub mod run_in;
pub mod steady;
pub mod switching;

use crate::bearing::Bearing;
use crate::geometry::Geometry;
use crate::model::{Inputs, LoadCausality, ModelError, Outputs, Parameters, Preload};
use crate::quasi_static::QuasiStatic;
use integrator::{Counters, Dopri5, Failure, StepControl};
use jacobian::BlockSystem;
use multistep::MilneHamming;
use nalgebra::{Matrix3, Vector3};
use rosenbrock::RosenbrockW;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

type V3 = Vector3<f64>;

/// Offsets in the state vector.
pub(crate) const CONE: usize = 0; // x y z vx vy vz
pub(crate) const CAGE: usize = 6; // y z psi vy vz psi'
/// The base global states (cone and cage): the element's further global states follow them,
/// then the rollers (`Layout`).
const ROLLERS: usize = 12;
/// States per roller: x dr psi x' dr' psi' tilt skew w_x w_r w_t.
pub const PER_ROLLER: usize = 11;

/// Where the states sit in the state vector: the twelve base global states (cone, cage), the
/// element's further global states, then the rollers' eleven each. The further ones exist only
/// where the element needs them, so that a bearing without them integrates exactly the states
/// (and the bits) it did before they were added:
/// - the housing's u_y, u_z, u_y', u_z' (`housing.mass` > 0, `crate::housing`);
/// - the turns of the rings and rollers that carry defects: the cup's (with a cup defect; it
///   turns at `cupSpeed`), the cone's (with a cone defect), and the spin angle of each roller
///   that carries a defect, relative to its body frame; zero at t = 0.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Layout {
    /// Number of global states.
    pub globals: usize,
    /// First of the housing's four states.
    pub housing: Option<usize>,
    /// The cup's turn (at `cupSpeed`) and the cone's.
    pub cup_turn: Option<usize>,
    pub cone_turn: Option<usize>,
    /// Per roller that carries a defect (0-based, ascending): its spin angle's state.
    pub roller_spins: Vec<(usize, usize)>,
    pub z: usize,
}

impl Layout {
    /// For `z` rollers, a cup on its support where `housing`, and the local defects `defects`.
    pub fn new(housing: bool, defects: &crate::defect::LocalDefects, z: usize) -> Layout {
        let mut globals = ROLLERS;
        let mut take = |n: usize| {
            globals += n;
            globals - n
        };
        let housing = housing.then(|| take(4));
        let cup_turn = (!defects.cup.is_empty()).then(|| take(1));
        let cone_turn = (!defects.cone.is_empty()).then(|| take(1));
        let roller_spins = defects.defective_rollers().into_iter().map(|j| (j, take(1))).collect();
        Layout {
            globals,
            housing,
            cup_turn,
            cone_turn,
            roller_spins,
            z,
        }
    }

    /// The state of roller `j`'s spin angle, if it carries a defect.
    #[inline]
    pub fn spin_of(&self, j: usize) -> Option<usize> {
        self.roller_spins.iter().find(|(r, _)| *r == j).map(|(_, k)| *k)
    }

    /// Every defect's turn state: the cup's, the cone's, then the rollers' spins.
    pub fn turns(&self) -> impl Iterator<Item = usize> + '_ {
        self.cup_turn
            .into_iter()
            .chain(self.cone_turn)
            .chain(self.roller_spins.iter().map(|(_, k)| *k))
    }

    /// Offset of roller `j`'s states.
    #[inline(always)]
    pub fn roller(&self, j: usize) -> usize {
        self.globals + PER_ROLLER * j
    }

    /// Number of states.
    pub fn len(&self) -> usize {
        self.roller(self.z)
    }
}

/// The evolving state of the dynamic model (serialised with the FMU state).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DynamicState {
    pub y: Vec<f64>,
    pub t: f64,
    /// The step-size controller's memory (next proposed step, last error).
    pub step: StepControl,
    pub counters: Counters,
    /// Derivative at (t, y) from the last accepted step and the inputs it was computed with.
    pub fsal: Vec<f64>,
    pub fsal_inputs: Option<Inputs>,
    /// Further integrator memory (Milne-Hamming history, Rosenbrock-W Jacobian); empty: none.
    pub memory: Vec<f64>,
    /// The automatic integrator's choice and its memory (`integrator` = 3).
    #[serde(default)]
    pub switch: switching::MethodSwitch,
}

impl DynamicState {
    /// Make this a copy of `other`, reusing this one's storage (no allocation once the
    /// vectors have their lengths): the element keeps the state at a step's start this way to
    /// return to it when the step fails.
    pub fn copy_from(&mut self, other: &DynamicState) {
        self.y.clone_from(&other.y);
        self.t = other.t;
        self.step = other.step;
        self.counters = other.counters;
        self.fsal.clone_from(&other.fsal);
        self.fsal_inputs = other.fsal_inputs;
        self.memory.clone_from(&other.memory);
        self.switch = other.switch;
    }
}

/// Per-roller results of one evaluation, for the outputs.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct RollerRecord {
    pub qi: f64,
    pub qo: f64,
    pub qf: f64,
    pub qc: f64,
    /// Moments about the roller's geometric centre from cone, cup, flange contacts.
    pub m_cone: V3,
    pub m_cup: V3,
    pub m_flange: V3,
    /// Tilt axis and skew axis of the roller now.
    pub tilt_axis: V3,
    pub skew_axis: V3,
    /// Force of the roller on the cone (raceway and flange), on the cage (pocket), and its
    /// moment on the cage about the bearing axis: the roller's share of the cone and cage
    /// equations (the block Jacobian separates the rollers with them).
    pub f_cone: V3,
    pub f_cage: V3,
    pub m_cage: f64,
    /// Force of the roller on the cup (raceway).
    pub f_cup: V3,
    /// Net sliding traction force on the roller: the magnitudes of the cone's and the cup's
    /// net tangential slice forces and of the rib's friction force, added.
    pub sliding: f64,
    /// The roller's shares of the totals: its moment on the cone about the origin, on the
    /// cone about the cone's axis from raceway and flange, on the cup about the bearing axis.
    pub m_cone_origin: V3,
    pub t_cone_raceway: f64,
    pub t_cone_flange: f64,
    pub t_cup: f64,
    /// Power dissipated at its raceways, flange and pocket (W).
    pub p_raceway: f64,
    pub p_flange: f64,
    pub p_cage: f64,
    /// A slice law was extrapolated beyond its table.
    pub extrapolated: bool,
    /// The roller's spin relative to its body frame (rad/s; the rate of its state in
    /// `Layout::roller_spins`), where it carries a defect; zero for the other rollers.
    pub defect_spin: f64,
}

/// Totals of one evaluation.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Totals {
    /// Force and moment (about the origin) of the rollers on the cone.
    pub f_cone: V3,
    pub m_cone: V3,
    /// Force and moment about the bearing axis of the rollers and land on the cage.
    pub f_cage: V3,
    pub m_cage: f64,
    /// Dissipated power by contact group (W).
    pub p_raceway: f64,
    pub p_flange: f64,
    pub p_cage: f64,
    /// Moment of raceway and flange forces on the cone about its own axis.
    pub t_cone_raceway: f64,
    pub t_cone_flange: f64,
    /// Moment of the roller contacts on the cup about the bearing axis.
    pub t_cup: f64,
    /// Force of the rollers and the cage land on the cup.
    pub f_cup: V3,
    /// The cup's acceleration on its support (zero where the housing is rigid).
    pub cup_acceleration: V3,
    pub extrapolated: bool,
}

/// Constants of the dynamic model for one bearing and parameter set.
#[derive(Debug, Clone)]
pub struct Dynamic {
    pub(crate) g: Geometry,
    pub(crate) p: Parameters,
    pub(crate) c: contacts::Constants,
    ig: Integrator,
    /// The run-in's integrator settings where the element's differ from its bearing's
    /// defaults (`run_in.rs`): the running state a start runs in to is a property of the
    /// operating point, the same whatever integrator the run then takes. With the element's
    /// reference speed for the tolerance scales.
    run_in_settings: Option<(Parameters, f64)>,
    /// The contacts' last evaluation, which the outputs come from.
    eval: Evaluation,
    /// ISO 281 / ISO/TS 16281 ratings (one lamina per slice).
    rating: crate::bearing::rating::BearingRating,
}

/// The contacts' last evaluation: per-roller records, slice loads (per roller: cone slices,
/// then cup slices) and totals at the state `y` with `inputs`. An integrator's last
/// right-hand side of a communication step is at the very state the outputs are wanted for,
/// so they are taken from it instead of from one more evaluation (the [W25] case with
/// Rosenbrock-W in steady running: one of five evaluations per 1 ms step). They are a
/// function of the state and the inputs alone (the parameters are fixed), so equal bits
/// give the same outputs whatever came before, restored FMU states included.
#[derive(Debug, Clone)]
struct Evaluation {
    records: Vec<RollerRecord>,
    slice_loads: Vec<f64>,
    totals: Totals,
    y: Vec<f64>,
    inputs: Option<Inputs>,
}

impl Evaluation {
    fn new(z: usize, slices: usize) -> Evaluation {
        Evaluation {
            records: vec![RollerRecord::default(); z],
            slice_loads: vec![0.0; 2 * slices * z],
            totals: Totals::default(),
            y: Vec::new(),
            inputs: None,
        }
    }

    /// Evaluate the contacts at `y` (and the derivatives into `dy` when given).
    #[allow(clippy::too_many_arguments)]
    fn run(&mut self, g: &Geometry, c: &contacts::Constants, inputs: &Inputs, y: &[f64], dy: Option<&mut [f64]>) {
        self.totals = contacts::evaluate(g, c, inputs, y, dy, &mut self.records, Some(&mut self.slice_loads));
        self.y.clear();
        self.y.extend_from_slice(y);
        self.inputs = Some(*inputs);
    }

    /// Whether this is the evaluation at `y` with `inputs`.
    fn holds(&self, inputs: &Inputs, y: &[f64]) -> bool {
        self.inputs.as_ref() == Some(inputs) && self.y == y
    }
}

/// The integrator selected by the parameter `integrator`.
#[derive(Debug, Clone)]
enum Integrator {
    /// 0: adaptive Dormand-Prince 5(4).
    Dopri5(Dopri5),
    /// 1: Gill's Runge-Kutta start, Milne-Hamming predictor-corrector at a fixed step [W25].
    MilneHamming(MilneHamming),
    /// 2: Rosenbrock-W ROS34PW2 with the block Jacobian.
    Rosenbrock(Box<RosenbrockW>),
    /// 3: the cheaper of the two per communication interval (`switching.rs`).
    Automatic { explicit: Dopri5, implicit: Box<RosenbrockW> },
}

/// The model as the integrators see it over one communication interval.
struct Model<'a> {
    g: &'a Geometry,
    c: &'a contacts::Constants,
    /// The inputs at the interval's start.
    inputs: &'a Inputs,
    /// The interval's start and the inputs' rates over it, where they ramp.
    ramp: Option<(f64, &'a Inputs)>,
    eval: &'a mut Evaluation,
}

impl BlockSystem for Model<'_> {
    fn stiffly_time_dependent(&self) -> bool {
        self.ramp.is_some_and(|(_, rates)| rates.moves_contacts())
    }
    /// The rings' relative surface speed at the pitch radius below 100 times the boundary
    /// law's entrainment floor (4 m/s): there the boundary law's slope at zero sliding,
    /// 40.4 / u_e, is still within a factor of 100 of its standstill value, and the slips of
    /// a bearing starting up move through the regularisation's curved part.
    fn near_standstill(&self) -> bool {
        self.inputs.relative_speed().abs() * self.g.center[1] < 100.0 * crate::tribology::MIN_BOUNDARY_ENTRAINMENT
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        match self.ramp {
            None => self.eval.run(self.g, self.c, self.inputs, y, Some(dy)),
            Some((t0, rates)) => {
                let now = self.inputs.ramped(rates, t - t0);
                self.eval.run(self.g, self.c, &now, y, Some(dy));
            }
        }
    }
    fn shares(&self, out: &mut [f64]) {
        for (j, r) in self.eval.records.iter().enumerate() {
            let ng = self.c.layout.globals;
            contacts::global_shares(self.c, j, r, &mut out[j * ng..(j + 1) * ng]);
        }
    }
}

/// The integrator of `params` (`integrator`, `tolerance`, `maxStep`) for the model of
/// geometry `g` and constants `c`, its tolerance scales at reference speed `speed` (rad/s).
fn integrator(g: &Geometry, c: &contacts::Constants, params: &Parameters, speed: f64) -> Integrator {
    let n = c.layout.len();
    let (atol, rtol) = tolerances(g, c, params, speed);
    let implicit = || {
        let scale = perturbation_scales(&atol, params, &c.layout);
        let active = moving_globals(g, params, &c.layout);
        let mut ig = RosenbrockW::new(g.z, atol.clone(), rtol.clone(), scale, active, params.max_step);
        ig.orbit = Some(rosenbrock::Orbit {
            state: c.layout.roller(0) + 2,
            turn: JACOBIAN_TURN,
            pitch: identical_rollers(params).then(|| TAU / g.z as f64),
        });
        Box::new(ig)
    };
    match params.integrator {
        1 => Integrator::MilneHamming(MilneHamming::new(n, params.max_step, atol, rtol)),
        2 => Integrator::Rosenbrock(implicit()),
        3 => Integrator::Automatic {
            implicit: implicit(),
            explicit: Dopri5::new(n, atol.clone(), rtol.clone(), params.max_step),
        },
        _ => Integrator::Dopri5(Dopri5::new(n, atol, rtol, params.max_step)),
    }
}

impl Dynamic {
    pub fn new(bearing: &Bearing, params: &Parameters) -> Result<Dynamic, ModelError> {
        let g = Geometry::new(bearing, &params.roller_profile());
        let c = contacts::Constants::new(bearing, params, &g);
        let speed = bearing.speed.abs().max(100.0);
        let ig = integrator(&g, &c, params, speed);
        let defaults = Parameters::from_bearing(bearing);
        let run_in_settings =
            (params.integrator != defaults.integrator || params.tolerance != defaults.tolerance || params.max_step != defaults.max_step)
                .then(|| {
                    let settings = Parameters {
                        integrator: defaults.integrator,
                        tolerance: defaults.tolerance,
                        max_step: defaults.max_step,
                        ..params.clone()
                    };
                    (settings, speed)
                });
        Ok(Dynamic {
            eval: Evaluation::new(g.z, params.slices),
            rating: crate::bearing::rating::BearingRating::new(bearing, params.slices),
            g,
            p: params.clone(),
            c,
            ig,
            run_in_settings,
        })
    }

    pub fn n_states(&self) -> usize {
        self.c.layout.len()
    }

    /// A dynamic model of `bearing` and its state at t = 0 started from the quasi-static
    /// solution for `inputs` (cage angle 0): what kernels, benchmarks and tests need to
    /// evaluate the right-hand side directly.
    pub fn at_quasi_static_start(bearing: &Bearing, params: &Parameters, inputs: &Inputs) -> Result<(Dynamic, DynamicState), ModelError> {
        let mut qs = QuasiStatic::new(bearing, params)?;
        let mut out = Outputs::new(bearing.roller_count);
        let mut x = Vec::new();
        qs.solve(inputs, 0.0, &mut x, &mut out)?;
        let d = Dynamic::new(bearing, params)?;
        let st = d.initial_state(&qs, &x, inputs, 0.0, 0.0);
        Ok((d, st))
    }

    /// Initial state from a converged quasi-static solution `x` (cone dx, dy, dz; per roller
    /// a, rho, theta L_s) at cage angle `cage_angle`, with epicyclic speeds; or at rest.
    pub fn initial_state(&self, qs: &QuasiStatic, x: &[f64], inputs: &Inputs, cage_angle: f64, t0: f64) -> DynamicState {
        let g = &self.g;
        let z = g.z;
        let mut y = vec![0.0; self.n_states()];
        let rest = self.p.start_from_rest;
        let (relative, cup) = if rest {
            (0.0, 0.0)
        } else {
            (inputs.relative_speed(), inputs.cup_speed)
        };
        // epicyclic speeds of pure rolling (the quasi-static cage slip rate is a parameter
        // of its torque model, not of the dynamics): the cage orbits at the cup's speed plus
        // its share of the cone's speed relative to the cup, the rollers spin relative to the
        // cage with that relative speed
        let wc = self.c.cage_ratio * relative + cup;
        let w_spin = self.c.spin_ratio * relative;
        let _ = qs;
        y[CONE] = x[0];
        y[CONE + 1] = x[1];
        y[CONE + 2] = x[2];
        y[CAGE + 2] = cage_angle;
        y[CAGE + 5] = wc;
        let axis0 = V3::new(g.axis[0], g.axis[1], 0.0); // (x, r, t) components
        for j in 0..z {
            let o = self.c.layout.roller(j);
            let (ax, dr, tilt) = self.in_plane_state(x, j);
            let beta = g.axis_angle - tilt;
            let axis = V3::new(libm::cos(beta), -libm::sin(beta), 0.0);
            let psi = cage_angle + TAU * j as f64 / z as f64;
            y[o] = ax;
            y[o + 1] = dr;
            y[o + 2] = psi;
            y[o + 5] = wc;
            y[o + 6] = tilt;
            y[o + 7] = 0.0;
            // inertial angular velocity: orbit about x plus spin about the axis (x, r, t comps)
            let w = V3::new(wc, 0.0, 0.0) + axis * w_spin;
            y[o + 8] = w[0];
            y[o + 9] = w[1];
            y[o + 10] = w[2];
            let _ = axis0;
        }
        // a housing on its support carries the load from the start (force inputs; under
        // displacement inputs the cup starts centred)
        if self.p.causality == LoadCausality::Force {
            contacts::seat_on_support(g, &self.c, inputs, &mut y);
        }
        DynamicState {
            y,
            t: t0,
            step: StepControl::default(),
            counters: Counters::default(),
            fsal: Vec::new(),
            fsal_inputs: None,
            memory: Vec::new(),
            switch: switching::MethodSwitch::default(),
        }
    }

    /// Roller `j`'s axial place and radial offset of its centre of mass and its tilt, the
    /// states `x`, `dr` and `tilt`, from a quasi-static solution `x` (cone dx, dy, dz; per
    /// roller a, rho, theta L_s).
    pub(crate) fn in_plane_state(&self, x: &[f64], j: usize) -> (f64, f64, f64) {
        let g = &self.g;
        let (a, rho, tilt) = (x[3 + 3 * j], x[4 + 3 * j], x[5 + 3 * j] / (0.5 * g.length));
        // attitude: nominal axis tilted by theta in the axial plane; the state point is the
        // centre of mass, cm_offset along the axis from the centre
        let beta = g.axis_angle - tilt;
        let axis = V3::new(libm::cos(beta), -libm::sin(beta), 0.0);
        (g.center[0] + a + g.cm_offset * axis[0], rho + g.cm_offset * axis[1], tilt)
    }

    /// The per-roller records of the last evaluation.
    pub(crate) fn records(&self) -> &[RollerRecord] {
        &self.eval.records
    }

    /// Whether the bearing runs steadily, seen from the cage, with `inputs` held: loads and
    /// bearing axisymmetric (no radial load or displacement, no misalignment, identical
    /// rollers, round rings, no local defect), rollers and cage moving (not `startFromRest`), a dynamic cage.
    /// Then every roller runs in the same state relative to its pocket, and that state is
    /// the one the model settles to; otherwise the running state is periodic in the orbit.
    pub fn runs_steadily(&self, inputs: &Inputs) -> bool {
        let radial = match self.p.causality {
            LoadCausality::Force => inputs.fy != 0.0 || inputs.fz != 0.0,
            LoadCausality::Displacement => inputs.displacement[1] != 0.0 || inputs.displacement[2] != 0.0,
        };
        !radial
            && inputs.xi == 0.0
            && inputs.zeta == 0.0
            && identical_rollers(&self.p)
            && self.c.lobes == 0
            && !self.p.has_defect()
            && self.p.cage_dynamic
            && !self.p.start_from_rest
    }

    /// The model as the integrators and the steady solver see it with `inputs`, and the
    /// integrator, borrowed apart from it.
    fn model<'a>(&'a mut self, inputs: &'a Inputs, ramp: Option<(f64, &'a Inputs)>) -> (Model<'a>, &'a mut Integrator) {
        let model = Model {
            g: &self.g,
            c: &self.c,
            inputs,
            ramp,
            eval: &mut self.eval,
        };
        (model, &mut self.ig)
    }

    /// Move `state` to the steady running state for `inputs`, seen from the cage
    /// (`steady.rs`). Returns the Newton iterations and right-hand sides it took; on failure
    /// `state` is unchanged.
    pub fn settle(&mut self, state: &mut DynamicState, inputs: &Inputs) -> Result<(u32, u64), steady::NoSteadyState> {
        // scales at the running speed (the integrators' are set once, at the preset's speed)
        let (atol, _) = tolerances(&self.g, &self.c, &self.p, inputs.relative_speed().abs().max(100.0));
        let tol = self.p.tolerance.max(MIN_TOLERANCE);
        let scale: Vec<f64> = atol.iter().map(|a| a / tol).collect();
        let perturbation = perturbation_scales(&atol, &self.p, &self.c.layout);
        let active = moving_globals(&self.g, &self.p, &self.c.layout);
        let mut solver = steady::SteadySolver::new(self.g.z, self.c.layout.globals);
        let (mut model, _) = self.model(inputs, None);
        let mut y = state.y.clone();
        let done = solver.solve(&mut model, &mut y, &scale, &perturbation, &active)?;
        state.y = y;
        state.fsal.clear();
        state.memory.clear();
        Ok(done)
    }

    /// Integrate from `state.t` to `t_end` with `inputs` held.
    pub fn advance(&mut self, state: &mut DynamicState, inputs: &Inputs, t_end: f64) -> Result<(), ModelError> {
        self.advance_ramped(state, inputs, None, t_end)
    }

    /// Integrate from `state.t` to `t_end` with the inputs `inputs` at `state.t`, changing at
    /// `rates` over the interval (`Inputs::ramped`; `None` or all zero: held).
    pub fn advance_ramped(
        &mut self,
        state: &mut DynamicState,
        inputs: &Inputs,
        rates: Option<&Inputs>,
        t_end: f64,
    ) -> Result<(), ModelError> {
        let rates = rates.filter(|r| **r != Inputs::held());
        self.check_film_heating(inputs)?;
        let end_inputs = rates.map(|r| inputs.ramped(r, t_end - state.t));
        if let Some(end) = &end_inputs {
            self.check_film_heating(end)?;
        }
        let jumped = state.fsal_inputs.as_ref() != Some(inputs);
        if jumped {
            // the right-hand side changed: the stored derivative no longer applies
            state.fsal.clear();
            state.fsal_inputs = Some(*inputs);
        }
        // Nor does an implicit integrator's Jacobian, where the inputs jumped: one from other
        // inputs hides errors behind the filtered error estimate. Inputs that ramp over the
        // interval and move the contacts cap its age instead (`rosenbrock::RAMPED_MAX_AGE`):
        // in the [W25] run-up with the speed ramped at tolerance 1e-4, a Jacobian kept from
        // standstill holds the cage stuck until 11 ms instead of 0.7 ms (skew error 390 %);
        // a refresh at every ramped interval without the cap still lets the run-up lose 38 %
        // at 1e-4 within its first interval, and with the cap it only adds cost.
        if jumped {
            if let Integrator::Rosenbrock(_) | Integrator::Automatic { .. } = self.ig {
                rosenbrock::mark_jacobian_stale(&mut state.memory);
            }
        }
        // prescribed cone translations jump to their inputs, and move at their rates (the
        // right-hand side takes their positions from the ramped inputs)
        let speeds = contacts::prescribed_cone(&self.c, rates.unwrap_or(&Inputs::held()));
        for (k, v) in contacts::prescribed_cone(&self.c, inputs).iter().enumerate() {
            if let (Some(v), Some(speed)) = (*v, speeds[k]) {
                if state.y[CONE + k] != v || state.y[CONE + 3 + k] != speed {
                    state.y[CONE + k] = v;
                    state.y[CONE + 3 + k] = speed;
                    state.fsal.clear();
                }
            }
        }
        let t0 = state.t;
        let budget = crate::model::step_work_budget(self.p.work_budget, t_end - t0);
        let (mut model, ig) = self.model(inputs, rates.map(|r| (t0, r)));
        let mut t = state.t;
        let result = match ig {
            Integrator::Dopri5(ig) => {
                ig.rhs_budget = budget;
                run_explicit(ig, &mut model, &mut t, state, t_end)
            }
            Integrator::MilneHamming(ig) => {
                ig.rhs_budget = budget;
                ig.integrate(
                    |t, y, dy| model.rhs(t, y, dy),
                    &mut t,
                    &mut state.y,
                    t_end,
                    &mut state.counters,
                    &mut state.fsal,
                    &mut state.memory,
                )
            }
            Integrator::Rosenbrock(ig) => {
                ig.rhs_budget = budget;
                run_implicit(ig, &mut model, &mut t, state, t_end)
            }
            Integrator::Automatic { explicit, implicit } => run_automatic(explicit, implicit, &mut model, &mut t, state, t_end, budget),
        };
        state.t = t;
        if let (Some(end), Ok(())) = (end_inputs, &result) {
            // the derivative the integrators carry on is that at the interval's end
            state.fsal_inputs = Some(end);
        }
        result.map_err(|f| {
            state.fsal.clear();
            let message = match f {
                Failure::StepTooSmall { t, h } => format!(
                    "the step size fell to {h:.3e} s at t = {t:.9} s without meeting the tolerance {:.1e}; the contacts are too stiff or the state left the model's range",
                    self.p.tolerance.max(MIN_TOLERANCE)
                ),
                Failure::NotFinite { t } => format!("the state became non-finite at t = {t:.9} s"),
                Failure::TooManySteps { t, steps } => format!("more than {steps} steps in one communication interval (t = {t:.9} s)"),
                Failure::OverBudget { t, h } => format!(
                    "the work budget of {budget} right-hand-side evaluations for this step (workBudget = {:.3e} per simulated second) ran out at t = {t:.9} s, {:.1} % of the way from {t0:.9} s to {t_end:.9} s, with the integrator at steps of {h:.3e} s: the transient is too stiff or too fast to follow at tolerance {:.1e}; a restored earlier state retried with shorter communication steps, inputs ramped over the step, a larger workBudget or a looser tolerance can pass it",
                    self.p.work_budget,
                    100.0 * (t - t0) / (t_end - t0),
                    self.p.tolerance.max(MIN_TOLERANCE)
                ),
                Failure::FixedStepTooLong { t, h, estimate } => format!(
                    "the fixed step {h:.3e} s (maxStep) is unstable or too long: the local error estimate (Milne) is {estimate:.1e} times the tolerance {:.1e} at t = {t:.9} s; reduce maxStep",
                    self.p.tolerance.max(MIN_TOLERANCE)
                ),
            };
            ModelError::IntegratorFailure { message }
        })
    }

    /// Fill `out` from `state`.
    pub fn write_outputs(&mut self, state: &DynamicState, inputs: &Inputs, out: &mut Outputs) {
        if !self.eval.holds(inputs, &state.y) {
            self.eval.run(&self.g, &self.c, inputs, &state.y, None);
        }
        let g = &self.g;
        let totals = self.eval.totals;
        let y = &state.y;
        let z = g.z;
        for j in 0..z {
            let o = self.c.layout.roller(j);
            let r = &self.eval.records[j];
            out.tilt[j] = y[o + 6];
            out.skew[j] = y[o + 7];
            out.azimuth[j] = y[o + 2].rem_euclid(TAU);
            out.qi[j] = r.qi;
            out.qo[j] = r.qo;
            out.qf[j] = r.qf;
            out.qc[j] = r.qc;
            out.nit[j] = r.m_cone.dot(&r.tilt_axis);
            out.not[j] = r.m_cup.dot(&r.tilt_axis);
            out.nft[j] = r.m_flange.dot(&r.tilt_axis);
            out.nis[j] = r.m_cone.dot(&r.skew_axis);
            out.nos[j] = r.m_cup.dot(&r.skew_axis);
            out.nfs[j] = r.m_flange.dot(&r.skew_axis);
            out.sliding_friction[j] = r.sliding;
        }
        let held = contacts::prescribed_cone(&self.c, inputs);
        out.cone_x = held[0].unwrap_or(y[CONE]);
        out.cone_y = held[1].unwrap_or(y[CONE + 1]);
        out.cone_z = held[2].unwrap_or(y[CONE + 2]);
        out.reaction_fx = if g.axial { -totals.f_cone[0] } else { 0.0 };
        out.reaction_my = -totals.m_cone[1];
        out.reaction_mz = -totals.m_cone[2];
        out.reaction_fy = -totals.f_cone[1];
        out.reaction_fz = -totals.f_cone[2];
        (out.housing_fy, out.housing_fz) = (totals.f_cup[1], totals.f_cup[2]);
        (out.cup_ay, out.cup_az) = (totals.cup_acceleration[1], totals.cup_acceleration[2]);
        out.rating_c = self.rating.c_r;
        let fr = libm::hypot(totals.f_cone[1], totals.f_cone[2]);
        out.life_l10 = self.rating.life_l10(fr, out.reaction_fx, inputs.speed, inputs.cup_speed);
        out.life_l10r = self.rating.life_l10r(&self.eval.slice_loads, inputs.speed, inputs.cup_speed);
        out.rating_c0 = self.rating.c_0r;
        out.safety_s0 = self.rating.static_safety(fr, out.reaction_fx);
        out.pressure_max = g.max_raceway_pressure(&self.eval.slice_loads);
        out.cage_speed = contacts::cage_speed(g, &self.c, y);
        // Torque needed to drive the cone: minus the moment of the roller forces about its axis.
        // With the cup turning too it is the torque between the rings: in steady running the
        // cup is driven the opposite way, and the power loss (all contacts' dissipation, from
        // the velocities relative to each ring) equals it times speed - cupSpeed.
        let total = -(totals.t_cone_raceway + totals.t_cone_flange);
        out.friction_torque = total;
        // the ring torques of [L22] (docs/model.md): the moments of the contact forces about
        // the bearing axis, the cone's as the torque driving it, the cup's as it feels it
        out.friction_torque_cone = total;
        out.friction_torque_cup = totals.t_cup;
        out.power_loss = totals.p_raceway + totals.p_flange + totals.p_cage;
        // Its parts split it in proportion to the power dissipated at the raceways, the flange
        // and the cage, so they always add up to it (without dissipation: the moments of the
        // raceway and flange forces).
        if out.power_loss > 0.0 {
            let share = total / out.power_loss;
            out.friction_torque_raceway = totals.p_raceway * share;
            out.friction_torque_flange = totals.p_flange * share;
            out.friction_torque_cage = totals.p_cage * share;
        } else {
            out.friction_torque_raceway = -totals.t_cone_raceway;
            out.friction_torque_flange = -totals.t_cone_flange;
            out.friction_torque_cage = 0.0;
        }
        out.solver_iterations = 0;
        out.solver_residual = 0.0;
        out.integrator_steps = state.counters.steps.min(i32::MAX as u64) as i32;
        out.integrator_rhs = state.counters.rhs.min(i32::MAX as u64) as i32;
        out.integrator_rejected = state.counters.rejected.min(i32::MAX as u64) as i32;
        out.summarize();
    }

    /// The validity range of the isothermal oil films (cage pockets and land, EHL traction):
    /// the Couette (Brinkman) temperature rise eta0 u^2 / (8 k) of a film sheared at the
    /// cone's surface speed u relative to the cup (every film is sheared at a speed relative
    /// to a ring or the cage, all of them following that relative speed), must stay below
    /// `MAX_FILM_HEATING`. Beyond it the viscous drag of a cold film brakes cage and rollers
    /// with megawatts that no real oil would carry (F16: 100 Pa s at 40 000 rpm) and thermal
    /// effects, not modelled, decide the result.
    pub fn check_film_heating(&self, inputs: &Inputs) -> Result<(), ModelError> {
        let u = inputs.relative_speed().abs() * self.g.pitch_contact_radii().0;
        let rise = self.p.eta0 * u * u / (8.0 * OIL_CONDUCTIVITY);
        if rise > MAX_FILM_HEATING {
            return Err(ModelError::InvalidInput {
                name: if inputs.cup_speed == 0.0 { "speed" } else { "cupSpeed" },
                message: format!(
                    "{}{:.6e} rad/s with oil.eta0 = {} Pa s is outside the dynamic model's range: its isothermal oil films would heat by eta0 u^2 / (8 k) = {rise:.3e} K at the cone's surface speed u = {u:.3} m/s (k = {OIL_CONDUCTIVITY} W/(m K), limit {MAX_FILM_HEATING} K; thermal effects are not modelled); lower the speed or the viscosity",
                    if inputs.cup_speed == 0.0 { "" } else { "speed - cupSpeed = " },
                    inputs.relative_speed(),
                    self.p.eta0
                ),
            });
        }
        Ok(())
    }

    /// Kinetic energy of rollers, cage, cone translation and a moving housing in `state` (J).
    pub fn kinetic_energy(&self, state: &DynamicState) -> f64 {
        contacts::kinetic_energy(&self.g, &self.c, &state.y)
    }

    /// The housing's books in `state` (`crate::housing`): the support's spring energy (J)
    /// and the power its damper dissipates (W); zero for a rigid housing.
    pub fn housing_books(&self, state: &DynamicState) -> (f64, f64) {
        contacts::housing_books(&self.c, &state.y)
    }

    /// Cage angle now (roller 1's pocket).
    pub fn cage_angle(&self, state: &DynamicState) -> f64 {
        contacts::cage_angle(&self.g, &self.c, &state.y)
    }

    /// The slice loads of the last evaluation (per roller the cone's slices, then the cup's).
    pub fn slice_loads(&self) -> &[f64] {
        &self.eval.slice_loads
    }

    /// Right-hand side at `state` (for tests and benchmarks).
    pub fn rhs(&mut self, inputs: &Inputs, y: &[f64], dy: &mut [f64]) {
        self.eval.run(&self.g, &self.c, inputs, y, Some(dy));
    }
}

/// One interval of Dormand–Prince on the model.
fn run_explicit(ig: &mut Dopri5, model: &mut Model, t: &mut f64, state: &mut DynamicState, t_end: f64) -> Result<(), Failure> {
    ig.integrate(
        |t, y, dy| model.rhs(t, y, dy),
        t,
        &mut state.y,
        t_end,
        &mut state.step,
        &mut state.counters,
        &mut state.fsal,
    )
}

/// One interval of Rosenbrock-W on the model.
fn run_implicit(ig: &mut RosenbrockW, model: &mut Model, t: &mut f64, state: &mut DynamicState, t_end: f64) -> Result<(), Failure> {
    ig.integrate(
        model,
        t,
        &mut state.y,
        t_end,
        &mut state.step,
        &mut state.counters,
        &mut state.fsal,
        &mut state.memory,
    )
}

/// One interval of the automatic integrator (`switching.rs`): Rosenbrock-W on its budget
/// while it is the chosen method, Dormand–Prince for the rest of the interval where it runs
/// over or fails, or for the whole interval when it is the chosen one; the choice for the next
/// interval from the cost of this one. Both together spend at most `budget` right-hand sides.
fn run_automatic(
    explicit: &mut Dopri5,
    implicit: &mut RosenbrockW,
    model: &mut Model,
    t: &mut f64,
    state: &mut DynamicState,
    t_end: f64,
    budget: u64,
) -> Result<(), Failure> {
    let mut result = Ok(());
    let rhs_at_start = state.counters.rhs;
    if state.switch.implicit {
        let (t0, rhs0) = (*t, state.counters.rhs);
        let own = state.switch.implicit_budget(t_end - *t);
        implicit.rhs_budget = own.min(budget);
        result = run_implicit(implicit, model, t, state, t_end);
        if let Err(Failure::OverBudget { .. }) = result {
            if own >= budget {
                // the step's whole budget is spent: nothing is left for the explicit method
                return result;
            }
        }
        let sw = &mut state.switch;
        if sw.rho_jacobians != state.counters.jacobians {
            sw.rho = implicit.spectral_radius();
            sw.rho_jacobians = state.counters.jacobians;
        }
        let leave = match result {
            // over budget, or failed: the explicit method finishes the interval from the last
            // accepted step (a failed Rosenbrock-W step changes nothing of the state)
            Err(Failure::OverBudget { .. } | Failure::StepTooSmall { .. } | Failure::NotFinite { .. } | Failure::TooManySteps { .. }) => {
                result = Ok(());
                sw.give_up_implicit();
                true
            }
            Ok(()) if *t > t0 => sw.after_interval((state.counters.rhs - rhs0) as f64 / (*t - t0)),
            _ => false,
        };
        if leave {
            sw.switch(&mut state.step);
        }
    }
    if !state.switch.implicit && *t < t_end && result.is_ok() {
        let (t0, rhs0) = (*t, state.counters.rhs);
        explicit.rhs_budget = budget.saturating_sub(rhs0 - rhs_at_start);
        result = run_explicit(explicit, model, t, state, t_end);
        if result.is_ok() && state.switch.after_interval((state.counters.rhs - rhs0) as f64 / (*t - t0)) {
            state.switch.switch(&mut state.step);
            rosenbrock::mark_jacobian_stale(&mut state.memory);
        }
    }
    result
}

/// Absolute and relative tolerances per state component: positions to `tol` of a 10 um
/// reference displacement, angles to the angle that moves a roller end by that much, speeds
/// relative to the orbital surface speed and the spin.
/// The dynamic integrators' tolerance floor: below it the error estimates are round-off of
/// the state (positions of ~1e-5 m carried to 16 digits), and steps shrink without end.
pub const MIN_TOLERANCE: f64 = 1e-10;

/// Rosenbrock-W: the orbit of roller 1 (rad) after which the Jacobian is recomputed
/// (`RosenbrockW::orbit`). The blocks coupling a roller to the ring and cage
/// translations go with the cosine and sine of its azimuth: after 0.5 rad they are off by up to
/// about half their size, i.e. by what a W-method tolerates. Measured on the [W25] case, 0.3 s at
/// tolerance 1e-5 and maxStep 1e-3 (wall time, largest output error against Dormand-Prince
/// 1e-9): no refresh by orbit 2.07 s, 3.2e-3 (`reaction.Mz`); 0.35 rad 1.59 s, 8.8e-4; 0.5 rad
/// 1.46 s, 8.8e-4; 0.7 rad 1.82 s, 5.3e-3 (`reaction.My`). With identical rollers the
/// Jacobian is first renumbered by the whole pitches turned (`BlockJacobian::shift_rollers`;
/// exact for a state periodic in the pitch) and recomputed only if that leaves more than
/// this turn: the same run 1.16 s, the same error; at tolerance 1e-4 1.04 → 0.71 s.
pub const JACOBIAN_TURN: f64 = 0.5;

/// Thermal conductivity of a bearing oil, W/(m K) (mineral and ester oils 0.12..0.15).
pub const OIL_CONDUCTIVITY: f64 = 0.13;

/// Largest Couette temperature rise of the isothermal oil films the dynamic model accepts, K.
pub const MAX_FILM_HEATING: f64 = 1000.0;

fn tolerances(g: &Geometry, c: &contacts::Constants, p: &Parameters, speed_ref: f64) -> (Vec<f64>, Vec<f64>) {
    let tol = p.tolerance.max(MIN_TOLERANCE);
    let n = c.layout.len();
    let l_ref = 1e-5;
    let r_p = g.center[1];
    let wc_ref = c.cage_ratio.abs() * speed_ref;
    let v_ref = (wc_ref * r_p).max(0.1);
    let spin_ref = (c.spin_ratio.abs() * speed_ref).max(10.0);
    let ang_ref = l_ref / (0.5 * g.length);
    let mut atol = vec![0.0; n];
    let mut rtol = vec![0.0; n];
    let mut set = |i: usize, a: f64, r: f64| {
        atol[i] = tol * a;
        rtol[i] = r * tol;
    };
    for k in 0..3 {
        set(CONE + k, l_ref, 0.0);
        set(CONE + 3 + k, l_ref * 1e3, 0.0);
    }
    set(CAGE, l_ref, 0.0);
    set(CAGE + 1, l_ref, 0.0);
    set(CAGE + 2, l_ref / r_p, 0.0);
    set(CAGE + 3, v_ref * 1e-3, 0.0);
    set(CAGE + 4, v_ref * 1e-3, 0.0);
    set(CAGE + 5, wc_ref.max(1.0) * 1e-3, 1.0);
    if let Some(h) = c.layout.housing {
        // the cup's translations and velocities as the cone's
        for k in 0..2 {
            set(h + k, l_ref, 0.0);
            set(h + 2 + k, l_ref * 1e3, 0.0);
        }
    }
    for a in c.layout.turns() {
        // an angle that moves a point of the pitch circle by the reference length
        set(a, l_ref / r_p, 0.0);
    }
    for j in 0..g.z {
        let o = c.layout.roller(j);
        set(o, l_ref, 0.0);
        set(o + 1, l_ref, 0.0);
        set(o + 2, l_ref / r_p, 0.0);
        set(o + 3, v_ref * 1e-3, 0.0);
        set(o + 4, v_ref * 1e-3, 0.0);
        set(o + 5, wc_ref.max(1.0) * 1e-3, 1.0);
        set(o + 6, ang_ref, 0.0);
        set(o + 7, ang_ref, 0.0);
        for k in 8..11 {
            set(o + k, spin_ref * 1e-3, 1.0);
        }
    }
    (atol, rtol)
}

/// The floors of the finite differences' perturbations, per state (the perturbation of state
/// i is sqrt(eps) max(|y_i|, floor_i)): the tolerance scales, except for the azimuths of the
/// rollers and the cage, angles of order one whatever their magnitude, floored at 1 rad. With
/// the tolerance scale (1e-4 rad) an azimuth at 0 — the cage and roller 1 at t = 0 — would be
/// perturbed by 2e-12 rad and its Jacobian column be round-off: Rosenbrock-W from the steady
/// [W25] state at tolerance 1e-5 would take 137 steps in 20 ms where one per 1 ms interval
/// holds the tolerance (31 steps with the floor).
fn perturbation_scales(atol: &[f64], p: &Parameters, layout: &Layout) -> Vec<f64> {
    let tol = p.tolerance.max(MIN_TOLERANCE);
    let mut scale: Vec<f64> = atol.iter().map(|a| a / tol).collect();
    scale[CAGE + 2] = 1.0;
    for a in layout.turns() {
        scale[a] = 1.0;
    }
    for j in 0..layout.z {
        scale[layout.roller(j) + 2] = 1.0;
    }
    scale
}

/// Whether the rollers are interchangeable: the same diameter deviation, none with a defect.
fn identical_rollers(p: &Parameters) -> bool {
    p.roller_dd.iter().all(|d| *d == p.roller_dd[0]) && !p.defects().any(|d| d.ring == crate::defect::DefectRing::Roller)
}

/// The global states that move: the cone's translations under force inputs (axially only
/// in force preload), the cage's if it is dynamic, the housing's and the defect's turn where
/// the element has them. The others are prescribed or unused.
fn moving_globals(g: &Geometry, p: &Parameters, layout: &Layout) -> Vec<bool> {
    let force = p.causality == LoadCausality::Force;
    let moving_x = g.axial && p.preload == Preload::Force && force;
    (0..layout.globals)
        .map(|k| match k {
            0 | 3 => moving_x,
            1 | 2 | 4 | 5 => force,
            6..ROLLERS => p.cage_dynamic,
            _ => true,
        })
        .collect()
}

/// Rotation matrix of the small rotation vector (0, xi, zeta) (Rodrigues), the cone's
/// misalignment about the origin.
pub(crate) fn cone_rotation(xi: f64, zeta: f64) -> Matrix3<f64> {
    let v = V3::new(0.0, xi, zeta);
    let angle = v.norm();
    if angle == 0.0 {
        return Matrix3::identity();
    }
    let k = v / angle;
    let kx = Matrix3::new(0.0, -k[2], k[1], k[2], 0.0, -k[0], -k[1], k[0], 0.0);
    Matrix3::identity() + kx * libm::sin(angle) + kx * kx * (1.0 - libm::cos(angle))
}

#[cfg(test)]
mod spectrum;
#[cfg(test)]
mod tests;
