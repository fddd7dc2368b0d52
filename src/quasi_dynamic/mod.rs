//! Quasi-dynamic bearing model, fidelity 2: roller skew, spin and cage slip at the
//! communication step, without the rollers' contact vibrations.
//!
//! A drivetrain or rotor model stepping at a millisecond cannot see the rollers' raceway-normal
//! and tilt vibrations (40 kHz, `docs/performance.md`, "What sets the dynamic model's step"),
//! nor their skew ringing (about 500 Hz, decaying at 85 1/s). [W25] notes that the roller
//! misalignment "can be approximately predicted by the quasi-dynamic method". Here every fast
//! coordinate is in balance at every communication point, and only the slow motions are
//! integrated:
//!
//! - in balance, in the plane of each roller: its axial and radial seat and its tilt, with the
//!   cone's equilibrium (force causality) or the cone at its inputs (displacement causality),
//!   solved by the quasi-static model (`crate::quasi_static`, fidelity 0) with its centrifugal
//!   and gyroscopic loads;
//! - in balance, out of the plane: each roller's skew (moments about its in-plane normal m)
//!   and its place in its pocket (tangential forces, the d'Alembert force m r Ω' of the
//!   orbit), under the full contact laws of the dynamic model (`crate::dynamic`,
//!   `contacts::evaluate_roller`): raceway slices with traction, film, supply and mixed
//!   laws, the rib's normal force through the end-sphere centre and its friction, the cage
//!   pocket's films and walls, and the gyroscopic moment of spin and orbit (Euler's equations
//!   of the axisymmetric roller, its attitude moving at the step's tilt and skew rates);
//! - integrated by backward Euler over the communication step h: each roller's spin s about
//!   its axis, I_a s' = M.a, its pocket place and skew with their inertia, and the cage: its
//!   speed Ω (every roller orbits with it), J_c Ω' = the pocket and land moments, and its
//!   centre on the land, m_c c'' = the pocket and land forces (the cage floats on its land:
//!   held on the axis, its pockets press a skewed roller harder, 13 against 6 N on the [W25]
//!   bearing deflected by 0.004°, and the largest skew is 2.8e-4 against fidelity 1's
//!   1.8e-4 rad); the cage's angle follows, psi_c += h Ω at the step's start speed. The seat's
//!   own rates (axial, radial, tilt) and the free cone translations' are the backward
//!   differences of the seats at the step's ends. Backward Euler is L-stable: a loaded
//!   roller's spin relaxes to its traction balance within about 15 µs (the unloaded roller's
//!   drag sets the slowest spin eigenvalue, -2.3e3 1/s on the [W25] bearing) and its skew mode
//!   is damped within the step, so at a millisecond step the loaded rollers follow their
//!   balance and a lightly loaded roller skids as the traction lets it.
//!
//! The unknowns of one step: per roller (its offset in the pocket delta, its skew phi, its spin
//! s), and the cage's speed Ω and centre (c_y, c_z). The equations: per roller, the tangential
//! balance (psi'' = Ω'), the skew balance and the spin equation, read from the dynamic model's
//! right-hand side at a state where the roller moves as the step's rates say (its angular
//! velocity psi' x + s a + a x a'); for the cage, the backward Euler steps of its speed and
//! its centre's motion. Newton's method with each roller's 3 × 3 block by finite differences of
//! that roller's contacts alone and the couplings to the cage by differences of the whole
//! right-hand side, the cage's three unknowns eliminated by their Schur complement (O(Z) per
//! iteration). A step that does not converge within [`MAX_ITERATIONS`] is taken in halves,
//! down to 1/[`MAX_SUBSTEPS`] of the communication step; beyond that it is refused with its
//! largest correction, and the element stays where the step began.
//!
//! Held: a housing's motion (the cup is rigid; housing forces are reported, the cup's
//! acceleration is zero).
//! The in-plane balance is the quasi-static one: it leaves out the raceway tractions' share of
//! the roller's in-plane forces (the axial thrust of a skewed roller), tenths of a per cent of
//! the normal loads at the skews of lubricated running.

use crate::dynamic::contacts::{self, Frame};
use crate::dynamic::{Dynamic, DynamicState, RollerRecord, CAGE, CONE, PER_ROLLER};
use crate::model::{Inputs, ModelError};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::TAU;

type V3 = Vector3<f64>;

/// Newton iterations at most per step: a step whose balance has not converged by then is
/// refused.
pub const MAX_ITERATIONS: u32 = 30;

/// A communication step is taken in at most this many sub-steps (`QuasiDynamic::advance`).
const MAX_SUBSTEPS: f64 = 64.0;

/// The smallest share of a Newton step that the damping takes.
const MIN_DAMPING: f64 = 1.0 / 64.0;

/// The per-roller unknowns: offset in the pocket (rad of azimuth), skew (rad), spin (rad/s).
const UNKNOWNS: usize = 3;
/// The cage's unknowns: its speed (rad/s) and its centre's y and z (m).
const CAGE_UNKNOWNS: usize = 3;

/// Work space and constants of the quasi-dynamic balance.
#[derive(Debug, Clone)]
pub struct QuasiDynamic {
    /// The dynamic model: constants, contact evaluation and outputs (its integrator is not
    /// used).
    pub(crate) dynamic: Dynamic,
    /// The state being solved for, a perturbed copy, and their right-hand sides.
    y: Vec<f64>,
    dy: Vec<f64>,
    y_cage: Vec<f64>,
    dy_cage: Vec<f64>,
    /// One roller's derivatives.
    dy_roller: [f64; PER_ROLLER],
    /// Per roller: its seat's rates over the step, its residual, its block A, the block's
    /// coupling to the cage's unknowns B, the cage equations' columns for the roller C, the
    /// Newton step's A^-1 r and A^-1 B, and its last correction.
    rates: Vec<SeatRates>,
    residual: Vec<Vector3<f64>>,
    block: Vec<Matrix3<f64>>,
    to_cage: Vec<Matrix3<f64>>,
    cage_rows: Vec<Matrix3<f64>>,
    solved: Vec<(Vector3<f64>, Matrix3<f64>)>,
    correction: Vec<Vector3<f64>>,
    records: Vec<RollerRecord>,
    /// The cage equations' own derivatives D, the cage's last correction, and its unknowns
    /// at the step's start.
    d_cage: Matrix3<f64>,
    cage_start: [f64; CAGE_UNKNOWNS],
    /// The rollers' unknowns being solved for and those at the last full Newton step's start.
    unknowns: Vec<[f64; UNKNOWNS]>,
    base: Vec<[f64; UNKNOWNS]>,
    /// The state at a communication step's start and at a sub-step's, kept to return to
    /// (storage reused from step to step).
    scratch: Option<DynamicState>,
    scratch_step: Option<DynamicState>,
    /// The full Newton step last taken (a damped one takes a share of it).
    step_taken: Vec<Vector3<f64>>,
    cage_step_taken: Vector3<f64>,
    cage_correction: Vector3<f64>,
    /// The unknowns and residuals of the last evaluation, from which the next one updates
    /// the Jacobian (`secant_update`).
    evaluated: Vec<([f64; UNKNOWNS], Vector3<f64>)>,
    evaluated_cage: Option<([f64; CAGE_UNKNOWNS], Vector3<f64>)>,
}

/// The outcome of one step's balance.
#[derive(Debug, Clone, Copy, Default)]
pub struct Balance {
    pub iterations: u32,
    /// Roller contact evaluations spent (one roller each).
    pub roller_evaluations: u64,
    /// The largest correction of the last iteration, relative to its convergence limit.
    pub correction: f64,
    /// Jacobians taken (by differences).
    pub jacobians: u32,
}

/// How a step's balance begins.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Start {
    /// From the last step's Jacobian and extrapolated unknowns, the Jacobian refined by
    /// Broyden's updates while the corrections contract.
    Secant,
    /// From the last step's Jacobian and extrapolated unknowns, the Jacobian held.
    Chord,
    /// From the step's start with a Jacobian of its own.
    Afresh,
}

/// What a step keeps for the next in the state's memory (`DynamicState::memory`), so that a
/// restored state steps on with the same bits: the step's length and the unknowns it started
/// from (the next step extrapolates linearly in time from them and its own start), and the
/// Jacobian it used (the next step's Newton iterations hold it while it contracts their
/// corrections).
struct Memory {
    z: usize,
}

impl Memory {
    /// First a tag and the lengths of the remembered step and of the one before it; per roller
    /// its unknowns at the starts of those two steps, A, B and C; then the cage's unknowns at
    /// the two starts and D.
    const TAG: f64 = 3.0;
    const PER_ROLLER: usize = 2 * UNKNOWNS + 3 * 9;

    fn new(z: usize) -> Memory {
        Memory { z }
    }

    fn len(&self) -> usize {
        3 + self.z * Self::PER_ROLLER + 2 * CAGE_UNKNOWNS + 9
    }

    /// Read the Jacobian into `qd` and extrapolate the unknowns `u`, `g` (this step's start
    /// values, the end of the remembered step) over this step's length `h` (none: a steady
    /// solve, no extrapolation): quadratically through the two remembered starts where the
    /// three steps have the same length, else linearly; false where there is nothing to read.
    fn read(&self, m: &[f64], qd: &mut QuasiDynamic, h: Option<f64>, u: &mut [[f64; UNKNOWNS]], g: &mut [f64; CAGE_UNKNOWNS]) -> bool {
        if m.len() != self.len() || m[0] != Self::TAG {
            return false;
        }
        let ratio = match (h, m[1]) {
            (Some(h), previous) if previous.is_finite() && previous > 0.0 => h / previous,
            _ => 0.0,
        };
        let quadratic = ratio == 1.0 && m[2] == m[1];
        // the value at the next start from the values at this start (v), the last (v1) and the
        // one before (v2)
        let extrapolate = |v: f64, v1: f64, v2: f64| {
            if quadratic && v2.is_finite() {
                v + (v - v1) + ((v - v1) - (v1 - v2))
            } else {
                v + (v - v1) * ratio
            }
        };
        let mut k = 3;
        for j in 0..self.z {
            for i in 0..UNKNOWNS {
                u[j][i] = extrapolate(u[j][i], m[k + i], m[k + UNKNOWNS + i]);
            }
            k += 2 * UNKNOWNS;
            qd.block[j].copy_from_slice(&m[k..k + 9]);
            qd.to_cage[j].copy_from_slice(&m[k + 9..k + 18]);
            qd.cage_rows[j].copy_from_slice(&m[k + 18..k + 27]);
            k += 27;
        }
        if qd.dynamic.c.cage_dynamic {
            for i in 0..CAGE_UNKNOWNS {
                g[i] = extrapolate(g[i], m[k + i], m[k + CAGE_UNKNOWNS + i]);
            }
        }
        k += 2 * CAGE_UNKNOWNS;
        qd.d_cage.copy_from_slice(&m[k..k + 9]);
        true
    }

    /// Write the step's start unknowns (from `qd`'s rates and cage start), the remembered
    /// step's (from `m`, NaN where it holds none) and the step's Jacobian, in place.
    fn write(&self, m: &mut Vec<f64>, qd: &QuasiDynamic, h: Option<f64>) {
        let held = m.len() == self.len() && m[0] == Self::TAG;
        let previous_h = if held { m[1] } else { f64::NAN };
        m.resize(self.len(), f64::NAN);
        m[0] = Self::TAG;
        m[1] = h.unwrap_or(f64::INFINITY);
        m[2] = previous_h;
        let mut k = 3;
        let keep = |m: &mut Vec<f64>, k: usize, start: &[f64]| {
            let n = start.len();
            for i in 0..n {
                m[k + n + i] = if held { m[k + i] } else { f64::NAN };
                m[k + i] = start[i];
            }
        };
        for j in 0..self.z {
            keep(m, k, &qd.rates[j].start);
            k += 2 * UNKNOWNS;
            m[k..k + 9].copy_from_slice(qd.block[j].as_slice());
            m[k + 9..k + 18].copy_from_slice(qd.to_cage[j].as_slice());
            m[k + 18..k + 27].copy_from_slice(qd.cage_rows[j].as_slice());
            k += 27;
        }
        keep(m, k, &qd.cage_start);
        k += 2 * CAGE_UNKNOWNS;
        m[k..k + 9].copy_from_slice(qd.d_cage.as_slice());
    }
}

/// The roller's axis a and its skew axis m (the in-plane normal) in the azimuth frame's
/// components (x, e_r, e_t), for tilt `tilt` and skew `skew` (`contacts::roller_pose`).
fn axes(axis_angle: f64, tilt: f64, skew: f64) -> (V3, V3) {
    let (sb, cb) = libm::sincos(axis_angle - tilt);
    let (sf, cf) = libm::sincos(skew);
    (V3::new(cb * cf, -sb * cf, -sf), V3::new(sb, cb, 0.0))
}

/// The rate of the roller's axis in the azimuth frame for tilt and skew rates `tilt_dot`,
/// `skew_dot` (the derivatives of `axes`' a).
fn axis_rate(axis_angle: f64, tilt: f64, skew: f64, tilt_dot: f64, skew_dot: f64) -> V3 {
    let (sb, cb) = libm::sincos(axis_angle - tilt);
    let (sf, cf) = libm::sincos(skew);
    V3::new(sb * cf, cb * cf, 0.0) * tilt_dot + V3::new(-cb * sf, sb * sf, -cf) * skew_dot
}

/// One roller's motion over the step that its unknowns do not set: the rates of its in-plane
/// seat (backward differences of the seats at the step's ends), its unknowns at the step's
/// start, and 1 / h.
#[derive(Debug, Clone, Copy, Default)]
struct SeatRates {
    x_dot: f64,
    dr_dot: f64,
    tilt_dot: f64,
    start: [f64; UNKNOWNS],
    /// The rates of the offset in the pocket and of the skew at the step's start: backward
    /// Euler takes their accelerations (the roller's inertia in the pocket and about m).
    pocket_rate: f64,
    skew_rate: f64,
    inv_h: f64,
}

/// The cage over the step: its unknowns (speed, centre y, z) and their values at the step's
/// start, its centre's velocity there, and 1 / h.
#[derive(Debug, Clone, Copy)]
struct CageStep {
    start: [f64; CAGE_UNKNOWNS],
    velocity: [f64; 2],
    inv_h: f64,
    /// A cage that moves (`cage.dynamic`); a kinematic one holds its unknowns.
    free: bool,
    /// The unknowns held at their start values: all three for a kinematic cage; the centre
    /// in a steady solve, where nothing but the land's film would place it.
    held: [bool; CAGE_UNKNOWNS],
}

impl CageStep {
    /// The cage's acceleration (angular, then its centre's) that backward Euler gives its
    /// unknowns `g`.
    fn acceleration(&self, g: &[f64; CAGE_UNKNOWNS]) -> [f64; CAGE_UNKNOWNS] {
        let v = self.velocities(g);
        [
            (g[0] - self.start[0]) * self.inv_h,
            (v[0] - self.velocity[0]) * self.inv_h,
            (v[1] - self.velocity[1]) * self.inv_h,
        ]
    }

    /// The centre's velocity over the step.
    fn velocities(&self, g: &[f64; CAGE_UNKNOWNS]) -> [f64; 2] {
        [(g[1] - self.start[1]) * self.inv_h, (g[2] - self.start[2]) * self.inv_h]
    }

    /// Write the cage's unknowns into `y`.
    fn place(&self, g: &[f64; CAGE_UNKNOWNS], y: &mut [f64]) {
        let v = self.velocities(g);
        y[CAGE] = g[1];
        y[CAGE + 1] = g[2];
        y[CAGE + 3] = v[0];
        y[CAGE + 4] = v[1];
        y[CAGE + 5] = g[0];
    }

    /// The cage's residuals from the right-hand side `dy` at `g`: the backward Euler
    /// accelerations less those the forces and moments on it give (zero for a kinematic cage).
    fn residual(&self, g: &[f64; CAGE_UNKNOWNS], dy: &[f64]) -> Vector3<f64> {
        if !self.free {
            return Vector3::zeros();
        }
        let a = self.acceleration(g);
        Vector3::new(a[0] - dy[CAGE + 5], a[1] - dy[CAGE + 3], a[2] - dy[CAGE + 4])
    }
}

/// Limits of one Newton step's corrections and the sizes of its differences.
#[derive(Debug, Clone, Copy)]
struct Scales {
    perturb: [f64; UNKNOWNS],
    perturb_cage: [f64; CAGE_UNKNOWNS],
    limit: [f64; UNKNOWNS],
    limit_cage: [f64; CAGE_UNKNOWNS],
    /// Largest correction of the offset in the pocket (rad), the skew (rad) and the cage's
    /// centre (m) in one iteration.
    max_pocket: f64,
    max_skew: f64,
    max_centre: f64,
}

impl QuasiDynamic {
    pub fn new(dynamic: Dynamic) -> QuasiDynamic {
        let n = dynamic.n_states();
        let z = dynamic.g.z;
        QuasiDynamic {
            dynamic,
            y: vec![0.0; n],
            dy: vec![0.0; n],
            y_cage: vec![0.0; n],
            dy_cage: vec![0.0; n],
            dy_roller: [0.0; PER_ROLLER],
            rates: vec![SeatRates::default(); z],
            residual: vec![Vector3::zeros(); z],
            block: vec![Matrix3::zeros(); z],
            to_cage: vec![Matrix3::zeros(); z],
            cage_rows: vec![Matrix3::zeros(); z],
            solved: vec![(Vector3::zeros(), Matrix3::zeros()); z],
            correction: vec![Vector3::zeros(); z],
            records: vec![RollerRecord::default(); z],
            d_cage: Matrix3::identity(),
            cage_start: [0.0; CAGE_UNKNOWNS],
            unknowns: Vec::with_capacity(z),
            base: Vec::with_capacity(z),
            scratch: None,
            scratch_step: None,
            step_taken: vec![Vector3::zeros(); z],
            cage_step_taken: Vector3::zeros(),
            cage_correction: Vector3::zeros(),
            evaluated: vec![([0.0; UNKNOWNS], Vector3::zeros()); z],
            evaluated_cage: None,
        }
    }

    fn pitch(&self) -> f64 {
        TAU / self.dynamic.g.z as f64
    }

    /// Roller `j`'s unknowns (delta, phi, s) in state `y`: s is the spin about its axis relative
    /// to the azimuth frame, which orbits at psi'.
    fn unknowns(&self, y: &[f64], j: usize) -> [f64; UNKNOWNS] {
        let c = &self.dynamic.c;
        let o = c.layout.roller(j);
        let delta = y[o + 2] - (y[CAGE + 2] + self.pitch() * j as f64);
        let (a, _) = axes(self.dynamic.g.axis_angle, y[o + 6], y[o + 7]);
        // the spin relative to the orbiting azimuth frame: w.a less the orbit's share
        let spin = y[o + 8] * a[0] + y[o + 9] * a[1] + y[o + 10] * a[2] - y[o + 5] * a[0];
        [delta, y[o + 7], spin]
    }

    /// Roller `j`'s rates of its offset in the pocket (its orbit's rate less the cage's) and
    /// of its skew (the axis' rate w_rel x a along the skew direction) in state `y`.
    fn pocket_and_skew_rates(&self, y: &[f64], j: usize) -> (f64, f64) {
        let o = self.dynamic.c.layout.roller(j);
        let axis_angle = self.dynamic.g.axis_angle;
        let (tilt, skew) = (y[o + 6], y[o + 7]);
        let (a, _) = axes(axis_angle, tilt, skew);
        let w_rel = V3::new(y[o + 8] - y[o + 5], y[o + 9], y[o + 10]);
        let along_skew = axis_rate(axis_angle, tilt, skew, 0.0, 1.0);
        (y[o + 5] - y[CAGE + 5], w_rel.cross(&a).dot(&along_skew))
    }

    /// Write roller `j`'s unknowns `u` into `y`, with the cage at angle `y[CAGE + 2]` turning
    /// at `omega`: the roller orbits at omega plus the rate of its place in the pocket, its
    /// seat moves at the rates `rates` give, its axis at the tilt rate and the skew's rate over
    /// the step, and it spins at s about its axis relative to the azimuth frame: angular
    /// velocity psi' x + s a + a x a'.
    fn place(&self, j: usize, u: &[f64; UNKNOWNS], omega: f64, y: &mut [f64]) {
        let (axis_angle, o, rates) = (self.dynamic.g.axis_angle, self.dynamic.c.layout.roller(j), &self.rates[j]);
        let delta_dot = (u[0] - rates.start[0]) * rates.inv_h;
        let skew_dot = (u[1] - rates.start[1]) * rates.inv_h;
        let psid = omega + delta_dot;
        y[o + 2] = y[CAGE + 2] + self.pitch() * j as f64 + u[0];
        y[o + 3] = rates.x_dot;
        y[o + 4] = rates.dr_dot;
        y[o + 5] = psid;
        y[o + 7] = u[1];
        let tilt = y[o + 6];
        let (a, _) = axes(axis_angle, tilt, u[1]);
        let a_dot = axis_rate(axis_angle, tilt, u[1], rates.tilt_dot, skew_dot);
        let w = V3::x() * psid + a * u[2] + a.cross(&a_dot);
        y[o + 8] = w[0];
        y[o + 9] = w[1];
        y[o + 10] = w[2];
    }

    /// Place every roller's unknowns `u` and the cage's `g` in `y`.
    fn place_all(&self, cage: &CageStep, u: &[[f64; UNKNOWNS]], g: &[f64; CAGE_UNKNOWNS], y: &mut [f64]) {
        cage.place(g, y);
        for (j, uj) in u.iter().enumerate() {
            self.place(j, uj, g[0], y);
        }
    }

    /// The seat of the in-plane balance: cone translation and each roller's axial and radial
    /// place and tilt from the quasi-static solution `x` (`Dynamic::initial_state`'s layout),
    /// at cage angle `cage_angle`; a housing's cup centred.
    fn seat(&self, x: &[f64], cage_angle: f64, y: &mut [f64]) {
        let d = &self.dynamic;
        y[CONE..CONE + 3].copy_from_slice(&x[..3]);
        y[CAGE + 2] = cage_angle;
        if let Some(hs) = d.c.layout.housing {
            y[hs..hs + 4].iter_mut().for_each(|v| *v = 0.0);
        }
        for j in 0..d.g.z {
            let o = d.c.layout.roller(j);
            let (ax, dr, tilt) = d.in_plane_state(x, j);
            y[o] = ax;
            y[o + 1] = dr;
            y[o + 6] = tilt;
        }
    }

    /// The per-roller residual (psi'' - Ω', skew balance, spin equation) of the unknowns `u`
    /// from the roller's derivatives `d`, with the cage's acceleration `omega_dot`: the
    /// angular velocity's rate in the azimuth frame that `place` implies, Ω' x + s' a + s a',
    /// less the one the moments give, along the skew axis m and the roller's axis a (its
    /// component along the tilt axis is the in-plane balance's).
    fn roller_residual(&self, j: usize, y: &[f64], d: &[f64], u: &[f64; UNKNOWNS], omega_dot: f64) -> Vector3<f64> {
        let (axis_angle, o, rates) = (self.dynamic.g.axis_angle, self.dynamic.c.layout.roller(j), &self.rates[j]);
        let (tilt, skew) = (y[o + 6], y[o + 7]);
        let (a, m) = axes(axis_angle, tilt, skew);
        let pocket_dot = (u[0] - rates.start[0]) * rates.inv_h;
        let pocket_ddot = (pocket_dot - rates.pocket_rate) * rates.inv_h;
        let skew_dot = (u[1] - rates.start[1]) * rates.inv_h;
        let skew_ddot = (skew_dot - rates.skew_rate) * rates.inv_h;
        let spin_dot = (u[2] - rates.start[2]) * rates.inv_h;
        let a_dot = axis_rate(axis_angle, tilt, skew, rates.tilt_dot, skew_dot);
        // the rate of a x a' is a x a'' = m skew'' (the tilt's acceleration is the in-plane
        // balance's)
        let rate = V3::new(d[8], d[9], d[10]) - V3::x() * omega_dot - a * spin_dot - a_dot * u[2] - m * skew_ddot;
        let residual = Vector3::new(d[5] - omega_dot - pocket_ddot, rate.dot(&m), rate.dot(&a));
        if self.dynamic.c.cage_dynamic {
            residual
        } else {
            // a kinematic cage: the roller keeps the middle of its pocket
            Vector3::new(0.0, residual[1], residual[2])
        }
    }

    /// Perturbations and convergence limits at the reference speed `speed` (rad/s, at least
    /// 100): the
    /// offset in the pocket to 1e-4 of the pocket's clearance in azimuth, the skew to 1e-8
    /// rad (1e-4 of the skews of lubricated running, 6e-4 of the 0.001° that a mean skew is
    /// compared to), the spin and the cage speed to 1e-6 and 1e-7 of the speed (a slip of
    /// 1e-6 changes a loaded roller's traction by a few thousandths of a per cent of its
    /// load), the cage's centre to 1e-3 of its land clearance.
    fn scales(&self, speed: f64) -> Scales {
        let c = &self.dynamic.c;
        let pocket = c.pocket_half.max(1e-6) / c.pitch_radius;
        let land = c.land.clearance;
        // at least the speed of 100 rad/s that the dynamic model's tolerance scales take: near
        // standstill the slips' own scale is the regularisation speed of the friction laws
        let w = speed.abs().max(100.0);
        Scales {
            perturb: [1e-4 * pocket, 1e-8, 1e-7 * w],
            perturb_cage: [1e-8 * w, 1e-4 * land, 1e-4 * land],
            limit: [1e-4 * pocket, 1e-8, 1e-6 * w],
            limit_cage: [1e-7 * w, 1e-3 * land, 1e-3 * land],
            max_pocket: 0.5 * pocket,
            max_skew: 0.02,
            max_centre: 0.25 * land,
        }
    }

    /// Advance `state` over a communication step of length `h`: the inputs at both ends
    /// checked against the isothermal films' range (`Dynamic::check_film_heating`), the cage
    /// turned on at its speed, the defects at their rates, the quasi-static seat `qs` solved at the step's end
    /// (its warm start `warm`, its outputs into `seat_outputs`), then `step`. The inputs at a
    /// time `t` into the step are `inputs_at(t)`. Where a step's balance does not converge,
    /// it is taken in halves, down to 1/64 of `h` (the shorter step's inertia terms condition
    /// the Newton iterations better); beyond that the step is refused and `state` is as it
    /// began. Returns the last sub-step's balance with the iterations of all of them.
    #[allow(clippy::too_many_arguments)]
    pub fn advance(
        &mut self,
        qs: &mut crate::quasi_static::QuasiStatic,
        warm: &mut Vec<f64>,
        seat_outputs: &mut crate::model::Outputs,
        state: &mut DynamicState,
        inputs_at: &dyn Fn(f64) -> Inputs,
        h: f64,
    ) -> Result<Balance, ModelError> {
        // the isothermal films' range, at both ends of the step, as at fidelity 1
        self.dynamic.check_film_heating(&inputs_at(0.0))?;
        self.dynamic.check_film_heating(&inputs_at(h))?;
        let mut start = self.scratch.take().unwrap_or_else(|| state.clone());
        let mut before = self.scratch_step.take().unwrap_or_else(|| state.clone());
        start.copy_from(state);
        let mut done = 0.0;
        let mut sub = h;
        let mut total = Balance::default();
        while done < h {
            let hs = sub.min(h - done);
            let end = if done + hs >= h { h } else { done + hs };
            let inputs = inputs_at(end);
            before.copy_from(state);
            let cage_angle = (self.cage_angle(state) + hs * self.cage_speed(state)).rem_euclid(TAU);
            let turns = self.advance_defect_turns(state, &inputs_at(done), hs);
            qs.set_defect_turns(turns);
            let result = qs
                .solve_seat(&inputs, cage_angle, warm, seat_outputs)
                .and_then(|_| self.step(state, warm, cage_angle, &inputs, hs));
            match result {
                Ok(balance) => {
                    total.iterations += balance.iterations;
                    total.roller_evaluations += balance.roller_evaluations;
                    total.jacobians += balance.jacobians;
                    total.correction = balance.correction;
                    done = end;
                }
                Err(e) => {
                    state.copy_from(&before);
                    if sub <= h / MAX_SUBSTEPS || !hs.is_finite() {
                        state.copy_from(&start);
                        (self.scratch, self.scratch_step) = (Some(start), Some(before));
                        return Err(e);
                    }
                    sub *= 0.5;
                }
            }
        }
        (self.scratch, self.scratch_step) = (Some(start), Some(before));
        Ok(total)
    }

    /// One step: the in-plane seat `x` (the quasi-static solution at the cage angle
    /// `cage_angle` the step ends at), then the balance of skew, pocket, spin and cage with
    /// backward Euler over `h` (`h` infinite: the steady running state, every rate zero).
    /// `state.y` holds the result; on failure it is unchanged.
    pub fn step(&mut self, state: &mut DynamicState, x: &[f64], cage_angle: f64, inputs: &Inputs, h: f64) -> Result<Balance, ModelError> {
        // from the remembered Jacobian and the extrapolated unknowns, refined by secant
        // updates; where that fails, with the remembered Jacobian kept as it is (a chord
        // iteration, slower but surer far from the balance); where that fails too (an input
        // that jumped, a roller meeting its pocket's wall), once more from the step's start
        // with a Jacobian of its own
        // (a steady solve has no secant updates: its first attempt is the chord's)
        let first = if h.is_finite() { Start::Secant } else { Start::Chord };
        self.solve(state, x, cage_angle, inputs, h, first)
            .or_else(|e| {
                if first == Start::Secant {
                    self.solve(state, x, cage_angle, inputs, h, Start::Chord)
                } else {
                    Err(e)
                }
            })
            .or_else(|_| self.solve(state, x, cage_angle, inputs, h, Start::Afresh))
    }

    /// The balance of `step`, begun as `start` says.
    fn solve(
        &mut self,
        state: &mut DynamicState,
        x: &[f64],
        cage_angle: f64,
        inputs: &Inputs,
        h: f64,
        start: Start,
    ) -> Result<Balance, ModelError> {
        let remember = start != Start::Afresh;
        let z = self.dynamic.g.z as u64;
        let mut y = std::mem::take(&mut self.y);
        let mut u = std::mem::take(&mut self.unknowns);
        let mut base_u = std::mem::take(&mut self.base);
        let (cage, mut g) = self.prepare(state, x, cage_angle, inputs, h, &mut y, &mut u);
        let scales = self.scales(inputs.relative_speed());
        // the last step's Jacobian and its unknowns, which predict this step's
        let memory = Memory::new(self.dynamic.g.z);
        let mut fresh = false;
        // the secant updates serve time steps whose first guess is close: not the steady
        // solve from the seat, and not past a correction that grew
        let mut secant = start == Start::Secant && h.is_finite();
        let mut have_jacobian = remember && memory.read(&state.memory, self, h.is_finite().then_some(h), &mut u, &mut g);
        let mut balance = Balance::default();
        let mut last = f64::INFINITY;
        // the last full Newton step's start and the share of it taken (damped where the
        // corrections grow: Deuflhard's natural monotonicity test on the scaled corrections)
        let mut base: Option<[f64; CAGE_UNKNOWNS]> = None;
        let mut lambda = 1.0;
        self.evaluated_cage = None;
        let result = loop {
            let cage_residual = self.residuals(inputs, &cage, &u, &g, &mut y);
            balance.roller_evaluations += z;
            if have_jacobian && secant {
                self.secant_update(&u, &g, &cage_residual, &cage, &scales);
            }
            if balance.iterations >= MAX_ITERATIONS {
                break Err(balance.correction);
            }
            balance.iterations += 1;
            let mut correction = None;
            if have_jacobian {
                correction = self.newton_correction(&cage_residual, &cage, &scales);
            }
            // a Jacobian kept from before that no longer contracts the corrections by a
            // factor of two is taken anew here
            let slow = correction.is_some_and(|c| c > 1.0 && c > 0.5 * last);
            if !have_jacobian || correction.is_none() || (slow && !fresh) {
                self.blocks(inputs, &cage, &u, &g, &scales, &mut y);
                balance.roller_evaluations += UNKNOWNS as u64 * z;
                self.d_cage = if cage.free {
                    balance.roller_evaluations += CAGE_UNKNOWNS as u64 * z;
                    self.cage_coupling(inputs, &cage, &u, &g, &scales, &cage_residual, &y)
                } else {
                    Matrix3::identity()
                };
                have_jacobian = true;
                fresh = true;
                balance.jacobians += 1;
                self.secant_base(&u, &g, &cage_residual);
                correction = self.newton_correction(&cage_residual, &cage, &scales);
            } else {
                fresh = false;
            }
            let Some(correction) = correction else {
                break Err(f64::INFINITY);
            };
            balance.correction = correction;
            if !correction.is_finite() {
                break Err(correction);
            }
            if correction <= 1.0 {
                // converged at the state just evaluated, which the outputs read
                break Ok(());
            }
            if correction > last {
                secant = false;
            }
            if correction > last && lambda > MIN_DAMPING {
                if let Some(g0) = &base {
                    // back along the last step: half of what was taken
                    lambda *= 0.5;
                    for (uj, (u0j, dj)) in u.iter_mut().zip(base_u.iter().zip(&self.step_taken)) {
                        for k in 0..UNKNOWNS {
                            uj[k] = u0j[k] + lambda * dj[k];
                        }
                    }
                    for k in 0..CAGE_UNKNOWNS {
                        g[k] = g0[k] + lambda * self.cage_step_taken[k];
                    }
                    continue;
                }
            }
            base_u.clone_from(&u);
            base = Some(g);
            lambda = (2.0 * lambda).min(1.0);
            self.take_step();
            self.apply_correction(&mut u, &mut g, lambda);
            last = correction;
        };
        let outcome = match result {
            Ok(()) => {
                state.y.copy_from_slice(&y);
                memory.write(&mut state.memory, self, h.is_finite().then_some(h));
                if h.is_finite() {
                    state.t += h;
                }
                state.counters.steps += 1;
                state.counters.rhs += balance.roller_evaluations / z;
                state.counters.jacobians += balance.jacobians as u64;
                Ok(balance)
            }
            Err(correction) => Err(ModelError::NoEquilibrium {
                message: format!(
                    "the quasi-dynamic balance of skew, pocket, spin and cage did not converge in {} Newton iterations (largest correction {correction:.3e} times its limit)",
                    balance.iterations
                ),
            }),
        };
        (self.y, self.unknowns, self.base) = (y, u, base_u);
        outcome
    }

    /// Seat the rollers for the step into `y` (from `state`, the seat `x` at `cage_angle`),
    /// with their seat rates over `h`; write the rollers' unknowns to start from into `u` and
    /// return the cage's step and unknowns (those of `state`; with a kinematic cage, the
    /// epicyclic speed, the cage on the axis and the rollers in their pockets' middle).
    #[allow(clippy::too_many_arguments)]
    fn prepare(
        &mut self,
        state: &DynamicState,
        x: &[f64],
        cage_angle: f64,
        inputs: &Inputs,
        h: f64,
        y: &mut [f64],
        u: &mut Vec<[f64; UNKNOWNS]>,
    ) -> (CageStep, [f64; CAGE_UNKNOWNS]) {
        let z = self.dynamic.g.z;
        let inv_h = if h.is_finite() { 1.0 / h } else { 0.0 };
        y.copy_from_slice(&state.y);
        self.seat(x, cage_angle, y);
        let c = &self.dynamic.c;
        let free = c.cage_dynamic;
        for k in 0..3 {
            // a free cone translation moves at its backward difference over the step
            y[CONE + 3 + k] = if c.prescribed[k] {
                0.0
            } else {
                (y[CONE + k] - state.y[CONE + k]) * inv_h
            };
        }
        let g = if free {
            [state.y[CAGE + 5], state.y[CAGE], state.y[CAGE + 1]]
        } else {
            [c.cage_ratio * inputs.relative_speed() + inputs.cup_speed, 0.0, 0.0]
        };
        self.cage_start = g;
        let cage = CageStep {
            start: g,
            velocity: if free { [state.y[CAGE + 3], state.y[CAGE + 4]] } else { [0.0; 2] },
            inv_h,
            free,
            held: [!free, !free || !h.is_finite(), !free || !h.is_finite()],
        };
        u.clear();
        for j in 0..z {
            let o = c.layout.roller(j);
            let mut start = self.unknowns(&state.y, j);
            if !free {
                start[0] = 0.0;
            }
            let (pocket_rate, skew_rate) = self.pocket_and_skew_rates(&state.y, j);
            self.rates[j] = SeatRates {
                x_dot: (y[o] - state.y[o]) * inv_h,
                dr_dot: (y[o + 1] - state.y[o + 1]) * inv_h,
                tilt_dot: (y[o + 6] - state.y[o + 6]) * inv_h,
                start,
                pocket_rate: if free { pocket_rate } else { 0.0 },
                skew_rate,
                inv_h,
            };
            u.push(start);
        }
        (cage, g)
    }

    /// Place the unknowns `u` and `g` in `y`, evaluate the contacts there (the dynamic
    /// model's evaluation, which the outputs read) and write each roller's residual; return
    /// the cage's.
    fn residuals(
        &mut self,
        inputs: &Inputs,
        cage: &CageStep,
        u: &[[f64; UNKNOWNS]],
        g: &[f64; CAGE_UNKNOWNS],
        y: &mut [f64],
    ) -> Vector3<f64> {
        self.place_all(cage, u, g, y);
        self.dynamic.rhs(inputs, y, &mut self.dy);
        let omega_dot = cage.acceleration(g)[0];
        for (j, uj) in u.iter().enumerate() {
            let o = self.dynamic.c.layout.roller(j);
            self.residual[j] = self.roller_residual(j, y, &self.dy[o..o + PER_ROLLER], uj, omega_dot);
        }
        cage.residual(g, &self.dy)
    }

    /// Each roller's 3 x 3 block and its columns of the cage equations by forward differences
    /// of its own contacts (the frame of cone and cage unchanged), about the state `y` the last
    /// `residuals` evaluated.
    fn blocks(&mut self, inputs: &Inputs, cage: &CageStep, u: &[[f64; UNKNOWNS]], g: &[f64; CAGE_UNKNOWNS], sc: &Scales, y: &mut [f64]) {
        let frame = contacts::frame(&self.dynamic.g, &self.dynamic.c, inputs, y);
        self.records.copy_from_slice(self.dynamic.records());
        let (j_cage, m_cage) = (self.dynamic.c.j_cage, self.dynamic.c.m_cage);
        let omega_dot = cage.acceleration(g)[0];
        for (j, uj) in u.iter().enumerate() {
            let o = self.dynamic.c.layout.roller(j);
            let saved: [f64; PER_ROLLER] = std::array::from_fn(|i| y[o + i]);
            for k in 0..UNKNOWNS {
                let mut v = *uj;
                v[k] += sc.perturb[k];
                self.place(j, &v, g[0], y);
                let rec = self.evaluate_one(inputs, &frame, y, j);
                let r = self.roller_residual(j, y, &self.dy_roller, &v, omega_dot);
                let base = &self.records[j];
                self.block[j].set_column(k, &((r - self.residual[j]) / sc.perturb[k]));
                let cage_column = Vector3::new(
                    -(rec.m_cage - base.m_cage) / j_cage,
                    -(rec.f_cage[1] - base.f_cage[1]) / m_cage,
                    -(rec.f_cage[2] - base.f_cage[2]) / m_cage,
                );
                self.cage_rows[j].set_column(k, &(cage_column / sc.perturb[k]));
            }
            y[o..o + PER_ROLLER].copy_from_slice(&saved);
            if !cage.free {
                // the place in the pocket held: its row and column the identity
                self.block[j].row_mut(0).fill(0.0);
                self.block[j].column_mut(0).fill(0.0);
                self.block[j][(0, 0)] = 1.0;
                self.cage_rows[j].fill(0.0);
            }
        }
    }

    /// The rollers' residuals' derivatives with respect to the cage's unknowns (into
    /// `to_cage`), by forward differences of the whole right-hand side; returns the cage
    /// equations' own derivatives.
    #[allow(clippy::too_many_arguments)]
    fn cage_coupling(
        &mut self,
        inputs: &Inputs,
        cage: &CageStep,
        u: &[[f64; UNKNOWNS]],
        g: &[f64; CAGE_UNKNOWNS],
        sc: &Scales,
        cage_residual: &Vector3<f64>,
        y: &[f64],
    ) -> Matrix3<f64> {
        let mut d_cage = Matrix3::zeros();
        let mut y1 = std::mem::take(&mut self.y_cage);
        let mut dy1 = std::mem::take(&mut self.dy_cage);
        for k in 0..CAGE_UNKNOWNS {
            let mut g1 = *g;
            g1[k] += sc.perturb_cage[k];
            y1.copy_from_slice(y);
            self.place_all(cage, u, &g1, &mut y1);
            self.dynamic.rhs(inputs, &y1, &mut dy1);
            let omega_dot = cage.acceleration(&g1)[0];
            for (j, uj) in u.iter().enumerate() {
                let o = self.dynamic.c.layout.roller(j);
                let r = self.roller_residual(j, &y1, &dy1[o..o + PER_ROLLER], uj, omega_dot);
                self.to_cage[j].set_column(k, &((r - self.residual[j]) / sc.perturb_cage[k]));
            }
            d_cage.set_column(k, &((cage.residual(&g1, &dy1) - cage_residual) / sc.perturb_cage[k]));
        }
        self.y_cage = y1;
        self.dy_cage = dy1;
        d_cage
    }

    /// The Newton correction of the rollers' unknowns and the cage's (into `correction` and
    /// `cage_correction`) with the Jacobian held, the cage's eliminated by their Schur
    /// complement D - sum C_j A_j^-1 B_j; returns the largest correction relative to its
    /// limit, `None` where a matrix is singular.
    fn newton_correction(&mut self, cage_residual: &Vector3<f64>, cage: &CageStep, sc: &Scales) -> Option<f64> {
        let (mut schur, mut rhs) = (self.d_cage, -cage_residual);
        for j in 0..self.residual.len() {
            let inv = regularised_inverse(&self.block[j])?;
            self.solved[j] = (inv * self.residual[j], inv * self.to_cage[j]);
            let (ar, ab) = &self.solved[j];
            schur -= self.cage_rows[j] * ab;
            rhs += self.cage_rows[j] * ar;
        }
        for k in 0..CAGE_UNKNOWNS {
            if cage.held[k] {
                schur.row_mut(k).fill(0.0);
                schur[(k, k)] = 1.0;
                rhs[k] = 0.0;
            }
        }
        let mut dg = if cage.free {
            regularised_inverse(&schur)? * rhs
        } else {
            Vector3::zeros()
        };
        for k in 1..CAGE_UNKNOWNS {
            dg[k] = dg[k].clamp(-sc.max_centre, sc.max_centre);
        }
        let mut largest: f64 = 0.0;
        for k in 0..CAGE_UNKNOWNS {
            largest = largest.max((dg[k] / sc.limit_cage[k]).abs());
        }
        self.cage_correction = dg;
        for j in 0..self.residual.len() {
            let (ar, ab) = &self.solved[j];
            let mut du = -(ar + ab * dg);
            du[0] = du[0].clamp(-sc.max_pocket, sc.max_pocket);
            du[1] = du[1].clamp(-sc.max_skew, sc.max_skew);
            for k in 0..UNKNOWNS {
                largest = largest.max((du[k] / sc.limit[k]).abs());
            }
            self.correction[j] = du;
        }
        Some(largest)
    }

    /// Broyden's update of the held Jacobian from the last evaluation to this one (unknowns
    /// `u`, `g`, the residuals just evaluated): each roller's block A_j takes the change of
    /// its residual that its own step and the cage's (through B_j) leave unexplained, the
    /// cage's D the change of its residual that the rollers' steps (through C_j) and its own
    /// leave; each along its step in the scaled unknowns (the convergence limits: the least
    /// change of the block in that norm, Broyden's good update). The chord iteration
    /// converges superlinearly with it at no evaluation of its own.
    fn secant_update(
        &mut self,
        u: &[[f64; UNKNOWNS]],
        g: &[f64; CAGE_UNKNOWNS],
        cage_residual: &Vector3<f64>,
        cage: &CageStep,
        sc: &Scales,
    ) {
        let Some((g0, rc0)) = self.evaluated_cage else {
            self.secant_base(u, g, cage_residual);
            return;
        };
        let s_cage = Vector3::from_fn(|k, _| if cage.held[k] { 0.0 } else { g[k] - g0[k] });
        let mut unexplained_cage = cage_residual - rc0 - self.d_cage * s_cage;
        for (j, uj) in u.iter().enumerate() {
            let (u0, r0) = &self.evaluated[j];
            let s = Vector3::from_fn(|k, _| uj[k] - u0[k]);
            unexplained_cage -= self.cage_rows[j] * s;
            let w = Vector3::from_fn(|k, _| s[k] / (sc.limit[k] * sc.limit[k]));
            let ws = w.dot(&s);
            if ws > 0.0 && ws.is_finite() {
                let y = self.residual[j] - r0 - self.to_cage[j] * s_cage;
                let update = (y - self.block[j] * s) * w.transpose() / ws;
                if update.iter().all(|v| v.is_finite()) {
                    self.block[j] += update;
                }
            }
        }
        if cage.free {
            let w = Vector3::from_fn(|k, _| s_cage[k] / (sc.limit_cage[k] * sc.limit_cage[k]));
            let ws = w.dot(&s_cage);
            if ws > 0.0 && ws.is_finite() {
                let update = unexplained_cage * w.transpose() / ws;
                if update.iter().all(|v| v.is_finite()) {
                    self.d_cage += update;
                }
            }
        }
        self.secant_base(u, g, cage_residual);
    }

    /// Keep the unknowns and residuals just evaluated for the next secant update.
    fn secant_base(&mut self, u: &[[f64; UNKNOWNS]], g: &[f64; CAGE_UNKNOWNS], cage_residual: &Vector3<f64>) {
        for (e, (uj, rj)) in self.evaluated.iter_mut().zip(u.iter().zip(&self.residual)) {
            *e = (*uj, *rj);
        }
        self.evaluated_cage = Some((*g, *cage_residual));
    }

    /// Keep the last Newton correction as the step taken (a damped step applies a share of
    /// it).
    fn take_step(&mut self) {
        self.step_taken.clone_from(&self.correction);
        self.cage_step_taken = self.cage_correction;
    }

    /// Apply the share `lambda` of the last Newton correction to `u` and `g`.
    fn apply_correction(&self, u: &mut [[f64; UNKNOWNS]], g: &mut [f64; CAGE_UNKNOWNS], lambda: f64) {
        for k in 0..CAGE_UNKNOWNS {
            g[k] += lambda * self.cage_correction[k];
        }
        for (uj, du) in u.iter_mut().zip(&self.correction) {
            for k in 0..UNKNOWNS {
                uj[k] += lambda * du[k];
            }
        }
    }

    /// The cage's angle (roller 1's pocket) and speed in `state`.
    pub fn cage_angle(&self, state: &DynamicState) -> f64 {
        state.y[CAGE + 2]
    }
    pub fn cage_speed(&self, state: &DynamicState) -> f64 {
        state.y[CAGE + 5]
    }

    /// Turn the defects of `state` on by `h` at their rates (the cup's and the cone's speeds,
    /// a defective roller's spin relative to its body), and return the turns the quasi-static
    /// seat places them at: the cone's, the first defective roller's, the cup's.
    pub fn advance_defect_turns(&mut self, state: &mut DynamicState, inputs: &Inputs, h: f64) -> [f64; 3] {
        let (cup, cone) = (self.dynamic.c.layout.cup_turn, self.dynamic.c.layout.cone_turn);
        if let Some(k) = cup {
            state.y[k] += h * inputs.cup_speed;
        }
        if let Some(k) = cone {
            state.y[k] += h * inputs.speed;
        }
        if !self.dynamic.c.layout.roller_spins.is_empty() {
            self.dynamic.rhs(inputs, &state.y, &mut self.dy);
            for &(j, k) in &self.dynamic.c.layout.roller_spins {
                state.y[k] += h * self.dynamic.records()[j].defect_spin;
            }
        }
        let first_roller = self.dynamic.c.layout.roller_spins.first().map(|(_, k)| *k);
        let turn = |k: Option<usize>| k.map_or(0.0, |k| state.y[k]);
        [turn(cone), turn(first_roller), turn(cup)]
    }

    /// Put `state` on the seat `x` at `cage_angle` without solving the balance (a start from
    /// rest keeps its speeds).
    pub fn hold(&self, state: &mut DynamicState, x: &[f64], cage_angle: f64) {
        let mut y = state.y.clone();
        self.seat(x, cage_angle, &mut y);
        state.y = y;
    }

    /// Fill `out` from `state`: the dynamic model's outputs of the balanced state, with the
    /// cup held (its acceleration zero).
    pub fn write_outputs(&mut self, state: &DynamicState, inputs: &Inputs, out: &mut crate::model::Outputs) {
        self.dynamic.write_outputs(state, inputs, out);
        out.cup_ay = 0.0;
        out.cup_az = 0.0;
    }

    /// Kinetic energy of rollers and cage in `state` (J).
    pub fn kinetic_energy(&self, state: &DynamicState) -> f64 {
        self.dynamic.kinetic_energy(state)
    }

    /// Roller `j`'s contacts at `y` in `frame`, its derivatives into `dy_roller`.
    fn evaluate_one(&mut self, inputs: &Inputs, frame: &Frame, y: &[f64], j: usize) -> RollerRecord {
        let d = &self.dynamic;
        contacts::evaluate_roller(&d.g, &d.c, inputs, frame, y, j, Some(&mut self.dy_roller), None)
    }
}

/// The inverse of a roller's block; where it is singular (a roller that touches nothing has
/// no skew or pocket stiffness), with its diagonal raised by 1e-9 of its largest entry (the
/// Jacobian is regularised, never the residual, so a converged balance is exact).
fn regularised_inverse(m: &Matrix3<f64>) -> Option<Matrix3<f64>> {
    if let Some(inv) = m.try_inverse().filter(|i| i.iter().all(|v| v.is_finite())) {
        return Some(inv);
    }
    let scale = m.amax().max(1e-300);
    (m + Matrix3::identity() * (1e-9 * scale))
        .try_inverse()
        .filter(|i| i.iter().all(|v| v.is_finite()))
}
