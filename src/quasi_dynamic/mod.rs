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
//! - in balance, each roller's contact coordinates: its axial and radial seat and its tilt
//!   (forces along the axis and the radius, the moment about the tilt axis a x m), its skew
//!   (moments about its in-plane normal m) and its place in its pocket (tangential forces,
//!   the d'Alembert force m r Ω' of the orbit), with the cone's equilibrium (force
//!   causality) or the cone at its inputs (displacement causality), all under the full
//!   contact laws of the dynamic model (`crate::dynamic`, `contacts::evaluate_roller`):
//!   raceway slices with traction, film, supply and mixed laws (so a skewed roller's axial
//!   thrust moves its seat), the rib's normal force through the end-sphere centre and its
//!   friction, the cage pocket's films and walls, the centrifugal force, and the gyroscopic
//!   moment of spin and orbit (Euler's equations of the axisymmetric roller);
//! - integrated by backward Euler over the communication step h: each roller's spin s about
//!   its axis, I_a s' = M.a, and the cage: its speed Ω (every roller orbits with it),
//!   J_c Ω' = the pocket and land moments, and its centre on the land, m_c c'' = the pocket
//!   and land forces (the cage floats on its land: held on the axis, its pockets press a
//!   skewed roller harder, 13 against 6 N on the [W25] bearing deflected by 0.004°, and the
//!   largest skew is 2.8e-4 against fidelity 1's 1.8e-4 rad); the cage's angle follows,
//!   psi_c += h Ω at the step's start speed. The contact coordinates keep their inertia in
//!   the same backward Euler step (their rates and accelerations are the backward
//!   differences over the step), which at a millisecond step is the quasi-static balance:
//!   the raceway-normal modes (40 kHz) and the skew mode (about 570 Hz) have h ω of 250 and
//!   3.6, and backward Euler, L-stable, damps them within the step. A loaded roller's spin
//!   relaxes to its traction balance within about 15 µs (the unloaded roller's drag sets the
//!   slowest spin eigenvalue, -2.3e3 1/s on the [W25] bearing), so at a millisecond step the
//!   loaded rollers follow their balance and a lightly loaded roller skids as the traction
//!   lets it.
//!
//! The unknowns of one step: per roller (its offset in the pocket delta, its skew phi, its spin
//! s, its axial place x, its radial offset dr, its tilt theta), and the globals: the cage's
//! speed Ω and centre (c_y, c_z) and the cone's free translations. The equations: per roller,
//! its six equations of motion with the accelerations backward Euler gives (psi'' = Ω' plus
//! the pocket offset's), read from the dynamic model's right-hand side at a state where the
//! roller moves as the step's rates say (its angular velocity psi' x + s a + a x a'); for the
//! cage and the cone, the backward Euler steps of their motion. The quasi-static model
//! (`crate::quasi_static`, fidelity 0) places the seat the Newton iterations start from: each
//! step solves it at the cage angle the step ends at and adds the offsets of the balanced
//! contact coordinates from the seat that the last step found at the roller's new place (the
//! tractions' share). Under steady running the balance is a pattern fixed in the housing (the
//! load zone's) that the rollers pass through, so each roller starts from the state the last
//! step found where it now stands, interpolated between the two rollers that bracket that
//! place; only its place in the pocket, which follows the cage (a floating cage's whirl
//! carries that pattern round), starts from its own history. Which of the two each
//! out-of-plane unknown takes is chosen by which came closer on the last step. Newton's method
//! with each roller's 6 × 6 block by finite differences of that roller's contacts alone and the couplings to the globals by differences of the whole
//! right-hand side, the globals eliminated by their Schur complement (O(Z) per iteration). A
//! step that does not converge within [`MAX_ITERATIONS`] is taken in halves, down to
//! 1/[`MAX_SUBSTEPS`] of the communication step; beyond that it is refused with its largest
//! correction, and the element stays where the step began.
//!
//! Held: a housing's motion (the cup is rigid; housing forces are reported, the cup's
//! acceleration is zero).

use crate::dynamic::contacts::{self, Frame};
use crate::dynamic::{Dynamic, DynamicState, RollerRecord, CAGE, CONE, PER_ROLLER};
use crate::model::{Inputs, ModelError};
use nalgebra::{SMatrix, SVector, Vector3};
use std::f64::consts::TAU;

type V3 = Vector3<f64>;

/// Newton iterations at most per step: a step whose balance has not converged by then is
/// refused.
pub const MAX_ITERATIONS: u32 = 30;

/// A communication step is taken in at most this many sub-steps (`QuasiDynamic::advance`).
const MAX_SUBSTEPS: f64 = 64.0;

/// A step whose balance converges only on held seats (`Start::Staged`) is first halved down
/// to this share of the communication step.
const HELD_SEAT_STEP: f64 = 0.25;

/// The smallest share of a Newton step that the damping takes.
const MIN_DAMPING: f64 = 1.0 / 64.0;

/// The per-roller unknowns: offset in the pocket (rad of azimuth), skew (rad), spin (rad/s),
/// then the contact coordinates in the roller's axial plane: axial place of the centre of
/// mass (m), its radial offset from the pitch radius (m), tilt (rad).
const UNKNOWNS: usize = 6;
/// The per-roller unknowns out of the axial plane (extrapolated in time from step to step);
/// those from `SEAT` on are the in-plane seat (predicted as the quasi-static seat plus the
/// offset the last step found).
const OUT_OF_PLANE: usize = 3;
const SEAT: usize = 3;
/// Which prediction of the out-of-plane unknowns (1: the state at the roller's place, 0: its
/// own history) a step takes before any step has compared them: the pocket offset follows the
/// cage (a floating cage's whirl carries its pattern round with it), skew and spin follow the
/// load zone.
const PLACE_FIRST: [f64; OUT_OF_PLANE] = [0.0, 1.0, 1.0];
/// The global unknowns: the cage's speed (rad/s) and its centre's y and z (m), then the
/// cone's translations x, y, z (m; held where the inputs prescribe them).
const GLOBALS: usize = 6;
const CONE_AT: usize = 3;

/// A roller's or the globals' unknowns, residuals and their Jacobian blocks.
type Col = SVector<f64, UNKNOWNS>;
type Block = SMatrix<f64, UNKNOWNS, UNKNOWNS>;

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
    /// Per roller: its motion over the step, its residual, its block A, the block's coupling
    /// to the global unknowns B, the global equations' columns for the roller C, the Newton
    /// step's A^-1 r and A^-1 B, and its last correction.
    rates: Vec<RollerStep>,
    residual: Vec<Col>,
    block: Vec<Block>,
    to_cage: Vec<Block>,
    cage_rows: Vec<Block>,
    solved: Vec<(Col, Block)>,
    correction: Vec<Col>,
    records: Vec<RollerRecord>,
    /// Per roller, its in-plane seat (axial place, radial offset, tilt) from the quasi-static
    /// solution at the step's end, and the cone's translations there.
    seats: Vec<[f64; 3]>,
    cone_seat: [f64; 3],
    /// The global equations' own derivatives D, and the globals at the step's start.
    d_cage: Block,
    cage_start: [f64; GLOBALS],
    /// The rollers' unknowns being solved for and those at the last full Newton step's start.
    unknowns: Vec<[f64; UNKNOWNS]>,
    base: Vec<[f64; UNKNOWNS]>,
    /// The state at a communication step's start and at a sub-step's, kept to return to
    /// (storage reused from step to step).
    scratch: Option<DynamicState>,
    scratch_step: Option<DynamicState>,
    /// The full Newton step last taken (a damped one takes a share of it).
    step_taken: Vec<Col>,
    cage_step_taken: Col,
    cage_correction: Col,
    /// The unknowns and residuals of the last evaluation, from which the next one updates
    /// the Jacobian (`secant_update`).
    evaluated: Vec<([f64; UNKNOWNS], Col)>,
    evaluated_cage: Option<([f64; GLOBALS], Col)>,
    /// A staged step's balance on the held seats: state, rollers' unknowns and globals
    /// (storage reused from step to step).
    held_y: Vec<f64>,
    held_u: Vec<[f64; UNKNOWNS]>,
    held_g: [f64; GLOBALS],
    /// The rollers' unknowns at a step's start, from which `Memory::read` predicts, its two
    /// predictions of each out-of-plane unknown (the roller's own history, the state at its
    /// place), and whether this step has them.
    field: Vec<[f64; UNKNOWNS]>,
    predicted: Vec<[[f64; 2]; OUT_OF_PLANE]>,
    have_prediction: bool,
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
    /// The step kept the rollers' seats and the cone at the quasi-static seat: the balance
    /// with them released did not converge (the tractions' share of the seat is left out).
    pub seat_held: bool,
}

/// How a step's balance begins.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Start {
    /// From the last step's Jacobian and predicted unknowns, the Jacobian refined by
    /// Broyden's updates while the corrections contract.
    Secant,
    /// From the last step's Jacobian and predicted unknowns, the Jacobian held.
    Chord,
    /// From the step's start with a Jacobian of its own.
    Afresh,
    /// As `Afresh`, the seats first held at the quasi-static one (the balance of skew, pocket,
    /// spin and cage alone), then released: a continuation for an input that jumped, where
    /// Newton's iterations on every unknown at once meet rollers entering and leaving their
    /// contacts. Where the released seats do not converge, the held balance stands.
    Staged,
}

/// What a step keeps for the next in the state's memory (`DynamicState::memory`), so that a
/// restored state steps on with the same bits: the step's length, the out-of-plane unknowns
/// it started from (the next step extrapolates in time from them and its own start), the
/// offsets of the balanced seat from the quasi-static one (the next step adds them to its
/// own quasi-static seat), the Jacobian it used (the next step's Newton iterations hold
/// it while it contracts their corrections), and which of its two predictions came closer.
struct Memory {
    z: usize,
}

impl Memory {
    /// First a tag and the lengths of the remembered step and of the one before it; per roller
    /// its out-of-plane unknowns at the starts of those two steps, its seat's offsets, A, B and
    /// C; then the cage's unknowns at the two starts, the cone's offsets and D; last, per
    /// out-of-plane unknown, the prediction the next step takes (1: at the roller's place, 0:
    /// its own history).
    const TAG: f64 = 5.0;
    const BLOCK: usize = UNKNOWNS * UNKNOWNS;
    const PER_ROLLER: usize = 2 * OUT_OF_PLANE + (UNKNOWNS - SEAT) + 3 * Self::BLOCK;

    fn new(z: usize) -> Memory {
        Memory { z }
    }

    fn len(&self) -> usize {
        3 + self.z * Self::PER_ROLLER + 2 * CONE_AT + (GLOBALS - CONE_AT) + Self::BLOCK + OUT_OF_PLANE
    }

    /// Read the Jacobian into `qd` and predict the unknowns `u`, `g` (this step's start
    /// values out of the plane, the quasi-static seat in it) over this step's length `h`
    /// (none: a steady solve, no extrapolation), the cage having turned by `shift` pitches
    /// since the step's start: each roller takes the balanced state the last step found at
    /// the azimuth it moves to (between the two rollers that bracket it there): in the plane
    /// its seat's offsets, and its Jacobian's blocks; out of the plane either that state plus
    /// the rollers' mean change over the last step or its own history extrapolated in time,
    /// whichever the memory says came closer on the last step (both are kept in `qd` for
    /// `write` to compare). Under steady running
    /// the balance is a field fixed in the housing's frame that the rollers pass through (the
    /// load zone's), so a roller entering or leaving its load zone starts from the state its
    /// neighbour had there, not from a time extrapolation of its own history (which
    /// overshoots where its spin or skew just jumped). The globals extrapolate in time,
    /// quadratically through the two remembered starts where the three steps have the same
    /// length, else linearly. False where there is nothing to read.
    fn read(
        &self,
        m: &[f64],
        qd: &mut QuasiDynamic,
        h: Option<f64>,
        shift: f64,
        u: &mut [[f64; UNKNOWNS]],
        g: &mut [f64; GLOBALS],
    ) -> bool {
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
        let b = Self::BLOCK;
        let at = |j: usize| 3 + j * Self::PER_ROLLER;
        let offsets = 2 * OUT_OF_PLANE;
        let blocks = offsets + UNKNOWNS - SEAT;
        // the rollers' mean change of their out-of-plane unknowns over the last step
        let mut trend = [0.0; OUT_OF_PLANE];
        for (j, uj) in u.iter().enumerate() {
            for i in 0..OUT_OF_PLANE {
                trend[i] += (uj[i] - m[at(j) + i]) * ratio / self.z as f64;
            }
        }
        let trend = trend.map(|t| if t.is_finite() { t } else { 0.0 });
        qd.field.copy_from_slice(u);
        let shift = if h.is_some() && shift.is_finite() { shift } else { 0.0 };
        let choice = &m[m.len() - OUT_OF_PLANE..];
        for (j, uj) in u.iter_mut().enumerate() {
            let (p, q, w) = bracket(self.z, j, shift);
            let blend = |a: f64, b: f64| a + w * (b - a);
            for i in 0..OUT_OF_PLANE {
                let own = extrapolate(qd.field[j][i], m[at(j) + i], m[at(j) + OUT_OF_PLANE + i]);
                let place = blend(qd.field[p][i], qd.field[q][i]) + trend[i];
                qd.predicted[j][i] = [own, place];
                uj[i] = if choice[i] == 1.0 { place } else { own };
            }
            for i in SEAT..UNKNOWNS {
                uj[i] += blend(m[at(p) + offsets + i - SEAT], m[at(q) + offsets + i - SEAT]);
            }
            let read_block = |into: &mut Block, from: usize| {
                let (mp, mq) = (&m[at(p) + from..at(p) + from + b], &m[at(q) + from..at(q) + from + b]);
                for (v, (x, y)) in into.iter_mut().zip(mp.iter().zip(mq)) {
                    *v = blend(*x, *y);
                }
            };
            read_block(&mut qd.block[j], blocks);
            read_block(&mut qd.to_cage[j], blocks + b);
            read_block(&mut qd.cage_rows[j], blocks + 2 * b);
        }
        let mut k = at(self.z);
        if qd.dynamic.c.cage_dynamic {
            for i in 0..CONE_AT {
                g[i] = extrapolate(g[i], m[k + i], m[k + CONE_AT + i]);
            }
        }
        k += 2 * CONE_AT;
        for i in CONE_AT..GLOBALS {
            if !qd.dynamic.c.prescribed[i - CONE_AT] {
                g[i] += m[k + i - CONE_AT];
            }
        }
        k += GLOBALS - CONE_AT;
        qd.d_cage.copy_from_slice(&m[k..k + b]);
        qd.have_prediction = h.is_some();
        true
    }

    /// Write the step's start unknowns out of the plane (from `qd`'s rates and cage start),
    /// the remembered step's (from `m`, NaN where it holds none), the balanced unknowns' `u`,
    /// `g` offsets from the step's quasi-static seat (kept as they were after a step on held
    /// seats, `seat_held`) and the step's Jacobian, in place.
    fn write(
        &self,
        m: &mut Vec<f64>,
        qd: &QuasiDynamic,
        h: Option<f64>,
        u: &[[f64; UNKNOWNS]],
        g: &[f64; GLOBALS],
        seat_held: bool,
        limit: &[f64; UNKNOWNS],
    ) {
        let held = m.len() == self.len() && m[0] == Self::TAG;
        let previous_h = if held { m[1] } else { f64::NAN };
        m.resize(self.len(), f64::NAN);
        m[0] = Self::TAG;
        m[1] = h.unwrap_or(f64::INFINITY);
        m[2] = previous_h;
        let b = Self::BLOCK;
        let mut k = 3;
        let keep = |m: &mut Vec<f64>, k: usize, start: &[f64]| {
            let n = start.len();
            for i in 0..n {
                m[k + n + i] = if held { m[k + i] } else { f64::NAN };
                m[k + i] = start[i];
            }
        };
        for j in 0..self.z {
            keep(m, k, &qd.rates[j].start[..OUT_OF_PLANE]);
            k += 2 * OUT_OF_PLANE;
            for i in SEAT..UNKNOWNS {
                // a step on held seats keeps the offsets the last balanced one found
                if !(seat_held && held) {
                    m[k + i - SEAT] = if seat_held { 0.0 } else { u[j][i] - qd.seats[j][i - SEAT] };
                }
            }
            k += UNKNOWNS - SEAT;
            m[k..k + b].copy_from_slice(qd.block[j].as_slice());
            m[k + b..k + 2 * b].copy_from_slice(qd.to_cage[j].as_slice());
            m[k + 2 * b..k + 3 * b].copy_from_slice(qd.cage_rows[j].as_slice());
            k += 3 * b;
        }
        keep(m, k, &qd.cage_start[..CONE_AT]);
        k += 2 * CONE_AT;
        for i in CONE_AT..GLOBALS {
            if !(seat_held && held) {
                m[k + i - CONE_AT] = if qd.dynamic.c.prescribed[i - CONE_AT] || seat_held {
                    0.0
                } else {
                    g[i] - qd.cone_seat[i - CONE_AT]
                };
            }
        }
        k += GLOBALS - CONE_AT;
        m[k..k + b].copy_from_slice(qd.d_cage.as_slice());
        k += b;
        // per out-of-plane unknown, the prediction that came closer to this step's balance
        // (its scaled squared error summed over the rollers) serves the next step
        for i in 0..OUT_OF_PLANE {
            m[k + i] = if qd.have_prediction {
                let error = |a: usize| -> f64 {
                    u.iter()
                        .zip(&qd.predicted)
                        .map(|(uj, pj)| ((uj[i] - pj[i][a]) / limit[i]).powi(2))
                        .sum()
                };
                if error(1) < error(0) {
                    1.0
                } else {
                    0.0
                }
            } else if held {
                m[k + i]
            } else {
                PLACE_FIRST[i]
            };
        }
    }
}

/// The two rollers whose places bracket roller `j`'s after the cage turned by `shift`
/// pitches (of `z` rollers), and the weight of the second: roller j then stands where
/// roller j + shift stood.
fn bracket(z: usize, j: usize, shift: f64) -> (usize, usize, f64) {
    let whole = shift.floor();
    let p = (j as i64 + whole as i64).rem_euclid(z as i64) as usize;
    (p, (p + 1) % z, shift - whole)
}

/// The roller's axis a and its skew axis m (the in-plane normal) in the azimuth frame's
/// components (x, e_r, e_t), for tilt `tilt` and skew `skew` (`contacts::roller_pose`).
/// The tilt turns a about cos(skew) a x m (da/dtilt = cos(skew) m), the skew about m.
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

/// One roller over the step: its unknowns at the step's start and the rates there (backward
/// Euler takes the accelerations from them: the roller's inertia in its pocket, about m and
/// in its axial plane), and 1 / h.
#[derive(Debug, Clone, Copy, Default)]
struct RollerStep {
    start: [f64; UNKNOWNS],
    /// The rates of the offset in the pocket, the skew, the axial place, the radial offset
    /// and the tilt at the step's start.
    pocket_rate: f64,
    skew_rate: f64,
    x_rate: f64,
    dr_rate: f64,
    tilt_rate: f64,
    inv_h: f64,
}

impl RollerStep {
    /// The rates of the unknowns `u` over the step (backward differences).
    fn rates(&self, u: &[f64; UNKNOWNS]) -> [f64; UNKNOWNS] {
        std::array::from_fn(|i| (u[i] - self.start[i]) * self.inv_h)
    }
}

/// The globals over the step: their values at the step's start, the cage centre's and the
/// cone's velocities there, and 1 / h.
#[derive(Debug, Clone, Copy)]
struct CageStep {
    start: [f64; GLOBALS],
    velocity: [f64; 2],
    cone_velocity: [f64; 3],
    inv_h: f64,
    /// A cage that moves (`cage.dynamic`); a kinematic one holds its unknowns.
    free: bool,
    /// The unknowns held at their start values: the cage's three for a kinematic cage, its
    /// centre in a steady solve (where nothing but the land's film would place it), the
    /// cone's translations that the inputs prescribe.
    held: [bool; GLOBALS],
    /// The rollers' seats held at the quasi-static one (and the cone with them): the steady
    /// solve, where no rate places a roller that only its centrifugal force presses on the
    /// cup (the time steps' inertia and damping do).
    seat_held: bool,
    /// The cone's translations that the inputs prescribe.
    prescribed: [bool; 3],
}

impl CageStep {
    /// The cage's acceleration (angular, then its centre's) that backward Euler gives its
    /// unknowns `g`.
    fn acceleration(&self, g: &[f64; GLOBALS]) -> [f64; 3] {
        let v = self.velocities(g);
        [
            (g[0] - self.start[0]) * self.inv_h,
            (v[0] - self.velocity[0]) * self.inv_h,
            (v[1] - self.velocity[1]) * self.inv_h,
        ]
    }

    /// The centre's velocity over the step.
    fn velocities(&self, g: &[f64; GLOBALS]) -> [f64; 2] {
        [(g[1] - self.start[1]) * self.inv_h, (g[2] - self.start[2]) * self.inv_h]
    }

    /// The cone's velocity along `k` over the step.
    fn cone_velocity(&self, g: &[f64; GLOBALS], k: usize) -> f64 {
        (g[CONE_AT + k] - self.start[CONE_AT + k]) * self.inv_h
    }

    /// Write the globals `g` into `y` (a prescribed cone translation stays at its input).
    fn place(&self, g: &[f64; GLOBALS], y: &mut [f64]) {
        let v = self.velocities(g);
        y[CAGE] = g[1];
        y[CAGE + 1] = g[2];
        y[CAGE + 3] = v[0];
        y[CAGE + 4] = v[1];
        y[CAGE + 5] = g[0];
        for k in 0..3 {
            if !self.prescribed[k] {
                y[CONE + k] = g[CONE_AT + k];
                y[CONE + 3 + k] = self.cone_velocity(g, k);
            }
        }
    }

    /// Hold the rollers' seats and the cone's free translations where `held`, or release
    /// them (the cone's prescribed translations stay held).
    fn hold_seats(&mut self, held: bool) {
        self.seat_held = held;
        for k in 0..3 {
            self.held[CONE_AT + k] = held || self.prescribed[k];
        }
    }

    /// A roller's residual `r` with the rows of what is held zero.
    fn mask(&self, mut r: Col) -> Col {
        if self.seat_held {
            r.fixed_rows_mut::<{ UNKNOWNS - SEAT }>(SEAT).fill(0.0);
        }
        r
    }

    /// The global residuals from the right-hand side `dy` at `g`: the backward Euler
    /// accelerations less those the forces and moments give (zero for what is held).
    fn residual(&self, g: &[f64; GLOBALS], dy: &[f64]) -> Col {
        let mut r = Col::zeros();
        if self.free {
            let a = self.acceleration(g);
            r[0] = a[0] - dy[CAGE + 5];
            r[1] = a[1] - dy[CAGE + 3];
            r[2] = a[2] - dy[CAGE + 4];
        }
        for k in 0..3 {
            if !self.held[CONE_AT + k] {
                r[CONE_AT + k] = (self.cone_velocity(g, k) - self.cone_velocity[k]) * self.inv_h - dy[CONE + 3 + k];
            }
        }
        r
    }
}

/// Limits of one Newton step's corrections and the sizes of its differences, per roller
/// unknown and per global.
#[derive(Debug, Clone, Copy)]
struct Scales {
    perturb: [f64; UNKNOWNS],
    perturb_cage: [f64; GLOBALS],
    limit: [f64; UNKNOWNS],
    limit_cage: [f64; GLOBALS],
    /// Largest correction of each unknown in one iteration.
    max_step: [f64; UNKNOWNS],
    max_step_cage: [f64; GLOBALS],
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
            rates: vec![RollerStep::default(); z],
            residual: vec![Col::zeros(); z],
            block: vec![Block::zeros(); z],
            to_cage: vec![Block::zeros(); z],
            cage_rows: vec![Block::zeros(); z],
            solved: vec![(Col::zeros(), Block::zeros()); z],
            correction: vec![Col::zeros(); z],
            records: vec![RollerRecord::default(); z],
            seats: vec![[0.0; 3]; z],
            cone_seat: [0.0; 3],
            d_cage: Block::identity(),
            cage_start: [0.0; GLOBALS],
            unknowns: Vec::with_capacity(z),
            base: Vec::with_capacity(z),
            scratch: None,
            scratch_step: None,
            step_taken: vec![Col::zeros(); z],
            cage_step_taken: Col::zeros(),
            cage_correction: Col::zeros(),
            evaluated: vec![([0.0; UNKNOWNS], Col::zeros()); z],
            evaluated_cage: None,
            held_y: vec![0.0; n],
            held_u: Vec::with_capacity(z),
            held_g: [0.0; GLOBALS],
            field: vec![[0.0; UNKNOWNS]; z],
            predicted: vec![[[0.0; 2]; OUT_OF_PLANE]; z],
            have_prediction: false,
        }
    }

    fn pitch(&self) -> f64 {
        TAU / self.dynamic.g.z as f64
    }

    /// Roller `j`'s unknowns (delta, phi, s, x, dr, theta) in state `y`: s is the spin about
    /// its axis relative to the azimuth frame, which orbits at psi'.
    fn unknowns(&self, y: &[f64], j: usize) -> [f64; UNKNOWNS] {
        let c = &self.dynamic.c;
        let o = c.layout.roller(j);
        let delta = y[o + 2] - (y[CAGE + 2] + self.pitch() * j as f64);
        let (a, _) = axes(self.dynamic.g.axis_angle, y[o + 6], y[o + 7]);
        // the spin relative to the orbiting azimuth frame: w.a less the orbit's share
        let spin = y[o + 8] * a[0] + y[o + 9] * a[1] + y[o + 10] * a[2] - y[o + 5] * a[0];
        [delta, y[o + 7], spin, y[o], y[o + 1], y[o + 6]]
    }

    /// Roller `j`'s rates of its offset in the pocket (its orbit's rate less the cage's), of
    /// its skew and of its tilt (the axis' rate w_rel x a along da/dphi and da/dtheta) in
    /// state `y`.
    fn attitude_rates(&self, y: &[f64], j: usize) -> (f64, f64, f64) {
        let o = self.dynamic.c.layout.roller(j);
        let axis_angle = self.dynamic.g.axis_angle;
        let (tilt, skew) = (y[o + 6], y[o + 7]);
        let (a, m) = axes(axis_angle, tilt, skew);
        let w_rel = V3::new(y[o + 8] - y[o + 5], y[o + 9], y[o + 10]);
        let a_dot = w_rel.cross(&a);
        let along_skew = axis_rate(axis_angle, tilt, skew, 0.0, 1.0);
        let cf = libm::cos(skew);
        (y[o + 5] - y[CAGE + 5], a_dot.dot(&along_skew), a_dot.dot(&m) / cf)
    }

    /// Write roller `j`'s unknowns `u` into `y`, with the cage at angle `y[CAGE + 2]` turning
    /// at `omega`: the roller orbits at omega plus the rate of its place in the pocket, its
    /// seat moves at its rates over the step, its axis at the tilt's and the skew's rates,
    /// and it spins at s about its axis relative to the azimuth frame: angular velocity
    /// psi' x + s a + a x a'.
    fn place(&self, j: usize, u: &[f64; UNKNOWNS], omega: f64, y: &mut [f64]) {
        let (axis_angle, o, step) = (self.dynamic.g.axis_angle, self.dynamic.c.layout.roller(j), &self.rates[j]);
        let rate = step.rates(u);
        let psid = omega + rate[0];
        y[o] = u[3];
        y[o + 1] = u[4];
        y[o + 2] = y[CAGE + 2] + self.pitch() * j as f64 + u[0];
        y[o + 3] = rate[3];
        y[o + 4] = rate[4];
        y[o + 5] = psid;
        y[o + 6] = u[5];
        y[o + 7] = u[1];
        let (a, _) = axes(axis_angle, u[5], u[1]);
        let a_dot = axis_rate(axis_angle, u[5], u[1], rate[5], rate[1]);
        let w = V3::x() * psid + a * u[2] + a.cross(&a_dot);
        y[o + 8] = w[0];
        y[o + 9] = w[1];
        y[o + 10] = w[2];
    }

    /// Place every roller's unknowns `u` and the globals `g` in `y`.
    fn place_all(&self, cage: &CageStep, u: &[[f64; UNKNOWNS]], g: &[f64; GLOBALS], y: &mut [f64]) {
        cage.place(g, y);
        for (j, uj) in u.iter().enumerate() {
            self.place(j, uj, g[0], y);
        }
    }

    /// The quasi-static seat: cone translation and each roller's axial and radial place and
    /// tilt from the quasi-static solution `x` (`Dynamic::initial_state`'s layout), at cage
    /// angle `cage_angle`, into `y` and `seats`; a housing's cup centred.
    fn seat(&mut self, x: &[f64], cage_angle: f64, y: &mut [f64]) {
        let d = &self.dynamic;
        y[CONE..CONE + 3].copy_from_slice(&x[..3]);
        self.cone_seat.copy_from_slice(&x[..3]);
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
            self.seats[j] = [ax, dr, tilt];
        }
    }

    /// The per-roller residual of the unknowns `u` from the roller's derivatives `d`, with the
    /// cage's acceleration `omega_dot`: psi'' - Ω' less the pocket offset's acceleration; the
    /// angular velocity's rate in the azimuth frame that `place` implies,
    /// Ω' x + s' a + s a' + a x a'' (a x a'' = m phi'' + cos(phi) (a x m) theta'', the
    /// products of rates dropped), less the one the moments give, along the skew axis m, the
    /// roller's axis a and the tilt axis a x m; and x'', dr'' less the accelerations backward
    /// Euler gives them.
    fn roller_residual(&self, j: usize, d: &[f64], u: &[f64; UNKNOWNS], omega_dot: f64) -> Col {
        let (axis_angle, step) = (self.dynamic.g.axis_angle, &self.rates[j]);
        let (tilt, skew) = (u[5], u[1]);
        let (a, m) = axes(axis_angle, tilt, skew);
        let rate = step.rates(u);
        let accel = |rate: f64, start: f64| (rate - start) * step.inv_h;
        let pocket_ddot = accel(rate[0], step.pocket_rate);
        let skew_ddot = accel(rate[1], step.skew_rate);
        let tilt_ddot = accel(rate[5], step.tilt_rate);
        let a_dot = axis_rate(axis_angle, tilt, skew, rate[5], rate[1]);
        let t = a.cross(&m);
        let w_rate = V3::new(d[8], d[9], d[10])
            - V3::x() * omega_dot
            - a * rate[2]
            - a_dot * u[2]
            - m * skew_ddot
            - t * (libm::cos(skew) * tilt_ddot);
        let pocket = if self.dynamic.c.cage_dynamic {
            d[5] - omega_dot - pocket_ddot
        } else {
            // a kinematic cage: the roller keeps the middle of its pocket
            0.0
        };
        Col::from([
            pocket,
            w_rate.dot(&m),
            w_rate.dot(&a),
            d[3] - accel(rate[3], step.x_rate),
            d[4] - accel(rate[4], step.dr_rate),
            w_rate.dot(&t),
        ])
    }

    /// Perturbations and convergence limits at the reference speed `speed` (rad/s, at least
    /// 100): the offset in the pocket to 1e-4 of the pocket's clearance in azimuth, the skew
    /// to 1e-8 rad (1e-4 of the skews of lubricated running, 6e-4 of the 0.001° that a mean
    /// skew is compared to), the spin and the cage speed to 1e-6 and 1e-7 of the speed (a slip
    /// of 1e-6 changes a loaded roller's traction by a few thousandths of a per cent of its
    /// load), the cage's centre to 1e-3 of its land clearance; the seat's places and the
    /// cone's translations to 1e-10 m (1e-5 of the micrometres of a contact's approach, a
    /// tenth of a newton on its stiffness of about 1e9 N/m) and the tilt to 1e-9 rad (1e-4 of
    /// the tilts of a deflected shaft, 2e-11 m at the roller's ends).
    fn scales(&self, speed: f64) -> Scales {
        let c = &self.dynamic.c;
        let pocket = c.pocket_half.max(1e-6) / c.pitch_radius;
        let land = c.land.clearance;
        // at least the speed of 100 rad/s that the dynamic model's tolerance scales take: near
        // standstill the slips' own scale is the regularisation speed of the friction laws
        let w = speed.abs().max(100.0);
        let (seat, tilt) = (1e-10, 1e-9);
        Scales {
            perturb: [1e-4 * pocket, 1e-8, 1e-7 * w, 10.0 * seat, 10.0 * seat, 10.0 * tilt],
            perturb_cage: [1e-8 * w, 1e-4 * land, 1e-4 * land, 10.0 * seat, 10.0 * seat, 10.0 * seat],
            limit: [1e-4 * pocket, 1e-8, 1e-6 * w, seat, seat, tilt],
            limit_cage: [1e-7 * w, 1e-3 * land, 1e-3 * land, seat, seat, seat],
            max_step: [0.5 * pocket, 0.02, f64::INFINITY, 2e-6, 2e-6, 2e-4],
            max_step_cage: [f64::INFINITY, 0.25 * land, 0.25 * land, 5e-6, 5e-6, 5e-6],
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
                // a balance on held seats is taken only on a step no longer than
                // `HELD_SEAT_STEP` of the communication step: on a shorter step the free seats'
                // balance is closer to its start
                Ok(balance) if balance.seat_held && sub > h * HELD_SEAT_STEP && hs.is_finite() => {
                    restore_keeping_counters(state, &before);
                    sub *= 0.5;
                }
                Ok(balance) => {
                    total.iterations += balance.iterations;
                    total.roller_evaluations += balance.roller_evaluations;
                    total.jacobians += balance.jacobians;
                    total.seat_held |= balance.seat_held;
                    total.correction = balance.correction;
                    done = end;
                }
                Err(e) => {
                    restore_keeping_counters(state, &before);
                    if sub <= h / MAX_SUBSTEPS || !hs.is_finite() {
                        restore_keeping_counters(state, &start);
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
        // with a Jacobian of its own; last, so again with the seats held first and released
        // once the rest is in balance: where the released seats do not converge, the step
        // keeps the balance on the held ones and says so (`Balance::seat_held`)
        // (a steady solve has no secant updates: its first attempt is the chord's; it holds
        // the seats throughout)
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
            .or_else(|e| {
                if h.is_finite() {
                    self.solve(state, x, cage_angle, inputs, h, Start::Staged)
                } else {
                    Err(e)
                }
            })
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
        let remember = !matches!(start, Start::Afresh | Start::Staged);
        let z = self.dynamic.g.z as u64;
        let mut y = std::mem::take(&mut self.y);
        let mut u = std::mem::take(&mut self.unknowns);
        let mut base_u = std::mem::take(&mut self.base);
        let (mut cage, mut g) = self.prepare(state, x, cage_angle, inputs, h, &mut y, &mut u);
        let mut limit = MAX_ITERATIONS;
        if start == Start::Staged {
            cage.hold_seats(true);
            limit *= 2;
        }
        let scales = self.scales(inputs.relative_speed());
        // the last step's Jacobian and its unknowns, which predict this step's
        let memory = Memory::new(self.dynamic.g.z);
        let mut fresh = false;
        // the secant updates serve time steps whose first guess is close: not the steady
        // solve from the seat, and not past a correction that grew
        let mut secant = start == Start::Secant && h.is_finite();
        let turned = (cage_angle - self.cage_angle(state) + 0.5 * TAU).rem_euclid(TAU) - 0.5 * TAU;
        let shift = turned / self.pitch();
        self.have_prediction = false;
        let mut have_jacobian = remember && memory.read(&state.memory, self, h.is_finite().then_some(h), shift, &mut u, &mut g);
        let mut balance = Balance::default();
        let mut last = f64::INFINITY;
        // the last full Newton step's start and the share of it taken (damped where the
        // corrections grow: Deuflhard's natural monotonicity test on the scaled corrections)
        let mut base: Option<[f64; GLOBALS]> = None;
        let mut lambda = 1.0;
        // a new Jacobian is due at the next point (a held one's step went too far)
        let mut refresh = false;
        self.evaluated_cage = None;
        let result = loop {
            let cage_residual = self.residuals(inputs, &cage, &u, &g, &mut y);
            balance.roller_evaluations += z;
            if have_jacobian && secant {
                self.secant_update(&u, &g, &cage_residual, &cage, &scales);
            }
            if balance.iterations >= limit {
                break Err(balance.correction);
            }
            balance.iterations += 1;
            let mut correction = None;
            if have_jacobian {
                correction = self.newton_correction(&cage_residual, &cage, &scales);
            }
            // the natural monotonicity test, with the Jacobian that gave the last step: where
            // this point's correction is larger than the last, the step went too far and is
            // taken back by half. On a predicted step (`Start::Secant`, close to its balance),
            // a step from a Jacobian kept from before or updated by secants also says that the
            // Jacobian is stale: it is taken anew where the step is taken back to (a new
            // Jacobian's corrections are not comparable with the last, so on a predicted step
            // the test comes before it)
            let predicted = start == Start::Secant;
            if let Some(c) = correction.filter(|&c| predicted && c > 1.0 && c > last) {
                secant = false;
                refresh |= !fresh;
                if self.take_back(&mut u, &mut g, &base_u, &base, &mut lambda) {
                    balance.correction = c;
                    continue;
                }
            }
            // a Jacobian kept from before that no longer contracts the corrections by a
            // factor of two is taken anew here
            let slow = correction.is_some_and(|c| c > 1.0 && c > 0.5 * last);
            if !have_jacobian || correction.is_none() || (slow && !fresh) || refresh {
                self.blocks(inputs, &cage, &u, &g, &scales, &mut y);
                let perturbed = if cage.seat_held { SEAT } else { UNKNOWNS } - usize::from(!cage.free);
                balance.roller_evaluations += perturbed as u64 * z;
                let (d_cage, spent) = self.cage_coupling(inputs, &cage, &u, &g, &scales, &cage_residual, &y);
                self.d_cage = d_cage;
                balance.roller_evaluations += spent * z;
                have_jacobian = true;
                fresh = true;
                refresh = false;
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
                if start == Start::Staged && cage.seat_held {
                    // the rest in balance on the held seats: keep it, and release them
                    self.held_y.copy_from_slice(&y);
                    self.held_u.clone_from(&u);
                    self.held_g = g;
                    cage.hold_seats(false);
                    (have_jacobian, last, base, lambda) = (false, f64::INFINITY, None, 1.0);
                    self.evaluated_cage = None;
                    continue;
                }
                // converged at the state just evaluated, which the outputs read
                break Ok(());
            }
            // the other starts (far from the balance) test after any new Jacobian
            if !predicted && correction > last {
                secant = false;
                if self.take_back(&mut u, &mut g, &base_u, &base, &mut lambda) {
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
        let result = match result {
            Err(_) if start == Start::Staged && !cage.seat_held => {
                // the released seats did not converge: the balance on the held ones stands
                y.copy_from_slice(&self.held_y);
                u.clone_from(&self.held_u);
                g = self.held_g;
                balance.seat_held = true;
                Ok(())
            }
            other => other,
        };
        // the work counts whether or not the balance converged (a step's failed attempts
        // are its cost too); an attempt that failed counts as a rejected step
        state.counters.rhs += balance.roller_evaluations.div_ceil(z);
        state.counters.jacobians += balance.jacobians as u64;
        state.counters.rejected += u64::from(result.is_err());
        let outcome = match result {
            Ok(()) => {
                state.y.copy_from_slice(&y);
                memory.write(&mut state.memory, self, h.is_finite().then_some(h), &u, &g, balance.seat_held, &scales.limit);
                if h.is_finite() {
                    state.t += h;
                }
                state.counters.steps += 1;
                Ok(balance)
            }
            Err(correction) => Err(ModelError::NoEquilibrium {
                message: format!(
                    "the quasi-dynamic balance of seat, skew, pocket, spin and cage did not converge in {} Newton iterations (largest correction {correction:.3e} times its limit)",
                    balance.iterations
                ),
            }),
        };
        (self.y, self.unknowns, self.base) = (y, u, base_u);
        outcome
    }

    /// Seat the rollers for the step into `y` (from `state`, the quasi-static seat `x` at
    /// `cage_angle`), with their rates at the step's start; write the rollers' unknowns to
    /// start from into `u` (out of the plane those of `state`, in it the seat) and return the
    /// globals' step and unknowns (the cage's of `state`, with a kinematic cage the epicyclic
    /// speed, the cage on the axis and the rollers in their pockets' middle; the cone's seat).
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
    ) -> (CageStep, [f64; GLOBALS]) {
        let z = self.dynamic.g.z;
        let inv_h = if h.is_finite() { 1.0 / h } else { 0.0 };
        y.copy_from_slice(&state.y);
        self.seat(x, cage_angle, y);
        let c = &self.dynamic.c;
        let free = c.cage_dynamic;
        for k in 0..3 {
            // a prescribed cone translation is at its input, at rest over the step
            if c.prescribed[k] {
                y[CONE + 3 + k] = 0.0;
            }
        }
        let cage3 = if free {
            [state.y[CAGE + 5], state.y[CAGE], state.y[CAGE + 1]]
        } else {
            [c.cage_ratio * inputs.relative_speed() + inputs.cup_speed, 0.0, 0.0]
        };
        let cone = |k: usize| state.y[CONE + k];
        let start = [cage3[0], cage3[1], cage3[2], cone(0), cone(1), cone(2)];
        let g = [cage3[0], cage3[1], cage3[2], y[CONE], y[CONE + 1], y[CONE + 2]];
        self.cage_start = start;
        let steady = !h.is_finite();
        let mut cage = CageStep {
            start,
            velocity: if free { [state.y[CAGE + 3], state.y[CAGE + 4]] } else { [0.0; 2] },
            cone_velocity: [state.y[CONE + 3], state.y[CONE + 4], state.y[CONE + 5]],
            inv_h,
            free,
            held: [!free, !free || steady, !free || steady, false, false, false],
            seat_held: false,
            prescribed: c.prescribed,
        };
        cage.hold_seats(steady);
        u.clear();
        for j in 0..z {
            let o = c.layout.roller(j);
            let mut start = self.unknowns(&state.y, j);
            if !free {
                start[0] = 0.0;
            }
            let (pocket_rate, skew_rate, tilt_rate) = self.attitude_rates(&state.y, j);
            self.rates[j] = RollerStep {
                start,
                pocket_rate: if free { pocket_rate } else { 0.0 },
                skew_rate,
                x_rate: state.y[o + 3],
                dr_rate: state.y[o + 4],
                tilt_rate,
                inv_h,
            };
            let mut first = start;
            first[SEAT..].copy_from_slice(&self.seats[j]);
            u.push(first);
        }
        (cage, g)
    }

    /// Place the unknowns `u` and `g` in `y`, evaluate the contacts there (the dynamic
    /// model's evaluation, which the outputs read) and write each roller's residual; return
    /// the globals'.
    fn residuals(&mut self, inputs: &Inputs, cage: &CageStep, u: &[[f64; UNKNOWNS]], g: &[f64; GLOBALS], y: &mut [f64]) -> Col {
        self.place_all(cage, u, g, y);
        self.dynamic.rhs(inputs, y, &mut self.dy);
        let omega_dot = cage.acceleration(g)[0];
        for (j, uj) in u.iter().enumerate() {
            let o = self.dynamic.c.layout.roller(j);
            self.residual[j] = cage.mask(self.roller_residual(j, &self.dy[o..o + PER_ROLLER], uj, omega_dot));
        }
        cage.residual(g, &self.dy)
    }

    /// The global equations' rows (cage: its speed and centre; cone: its free translations)
    /// that roller record `rec` less `base` changes, per unit of the perturbation `by`.
    fn global_rows(&self, rec: &RollerRecord, base: &RollerRecord, cage: &CageStep, by: f64) -> Col {
        let c = &self.dynamic.c;
        let mut col = Col::zeros();
        if cage.free {
            col[0] = -(rec.m_cage - base.m_cage) / c.j_cage;
            col[1] = -(rec.f_cage[1] - base.f_cage[1]) / c.m_cage;
            col[2] = -(rec.f_cage[2] - base.f_cage[2]) / c.m_cage;
        }
        for k in 0..3 {
            if !cage.held[CONE_AT + k] {
                col[CONE_AT + k] = -(rec.f_cone[k] - base.f_cone[k]) / c.m_cone;
            }
        }
        col / by
    }

    /// Each roller's 6 x 6 block and its columns of the global equations by forward
    /// differences of its own contacts (the frame of cone and cage unchanged), about the state
    /// `y` the last `residuals` evaluated.
    fn blocks(&mut self, inputs: &Inputs, cage: &CageStep, u: &[[f64; UNKNOWNS]], g: &[f64; GLOBALS], sc: &Scales, y: &mut [f64]) {
        let frame = contacts::frame(&self.dynamic.g, &self.dynamic.c, inputs, y);
        self.records.copy_from_slice(self.dynamic.records());
        let omega_dot = cage.acceleration(g)[0];
        for (j, uj) in u.iter().enumerate() {
            let o = self.dynamic.c.layout.roller(j);
            let saved: [f64; PER_ROLLER] = std::array::from_fn(|i| y[o + i]);
            for k in 0..UNKNOWNS {
                if (k == 0 && !cage.free) || (k >= SEAT && cage.seat_held) {
                    continue;
                }
                let mut v = *uj;
                v[k] += sc.perturb[k];
                self.place(j, &v, g[0], y);
                let rec = self.evaluate_one(inputs, &frame, y, j);
                let r = cage.mask(self.roller_residual(j, &self.dy_roller, &v, omega_dot));
                self.block[j].set_column(k, &((r - self.residual[j]) / sc.perturb[k]));
                let rows = self.global_rows(&rec, &self.records[j], cage, sc.perturb[k]);
                self.cage_rows[j].set_column(k, &rows);
            }
            y[o..o + PER_ROLLER].copy_from_slice(&saved);
            if !cage.free {
                // the place in the pocket held: its row and column the identity
                self.block[j].row_mut(0).fill(0.0);
                self.block[j].column_mut(0).fill(0.0);
                self.block[j][(0, 0)] = 1.0;
                self.cage_rows[j].column_mut(0).fill(0.0);
            }
            if cage.seat_held {
                for k in SEAT..UNKNOWNS {
                    self.block[j].column_mut(k).fill(0.0);
                    self.block[j][(k, k)] = 1.0;
                    self.cage_rows[j].column_mut(k).fill(0.0);
                }
            }
        }
    }

    /// The rollers' residuals' derivatives with respect to the free globals (into
    /// `to_cage`), by forward differences of the whole right-hand side; returns the global
    /// equations' own derivatives (held globals: their columns zero, their diagonal one) and
    /// the right-hand sides spent.
    #[allow(clippy::too_many_arguments)]
    fn cage_coupling(
        &mut self,
        inputs: &Inputs,
        cage: &CageStep,
        u: &[[f64; UNKNOWNS]],
        g: &[f64; GLOBALS],
        sc: &Scales,
        cage_residual: &Col,
        y: &[f64],
    ) -> (Block, u64) {
        let mut d_cage = Block::identity();
        let mut spent = 0;
        let mut y1 = std::mem::take(&mut self.y_cage);
        let mut dy1 = std::mem::take(&mut self.dy_cage);
        for k in 0..GLOBALS {
            if cage.held[k] {
                for b in self.to_cage.iter_mut() {
                    b.column_mut(k).fill(0.0);
                }
                continue;
            }
            let mut g1 = *g;
            g1[k] += sc.perturb_cage[k];
            y1.copy_from_slice(y);
            self.place_all(cage, u, &g1, &mut y1);
            self.dynamic.rhs(inputs, &y1, &mut dy1);
            spent += 1;
            let omega_dot = cage.acceleration(&g1)[0];
            for (j, uj) in u.iter().enumerate() {
                let o = self.dynamic.c.layout.roller(j);
                let r = cage.mask(self.roller_residual(j, &dy1[o..o + PER_ROLLER], uj, omega_dot));
                self.to_cage[j].set_column(k, &((r - self.residual[j]) / sc.perturb_cage[k]));
            }
            d_cage.set_column(k, &((cage.residual(&g1, &dy1) - cage_residual) / sc.perturb_cage[k]));
        }
        self.y_cage = y1;
        self.dy_cage = dy1;
        (d_cage, spent)
    }

    /// The Newton correction of the rollers' unknowns and the globals (into `correction` and
    /// `cage_correction`) with the Jacobian held, the globals eliminated by their Schur
    /// complement D - sum C_j A_j^-1 B_j; returns the largest correction relative to its
    /// limit, `None` where a matrix is singular.
    fn newton_correction(&mut self, cage_residual: &Col, cage: &CageStep, sc: &Scales) -> Option<f64> {
        let (mut schur, mut rhs) = (self.d_cage, -cage_residual);
        for j in 0..self.residual.len() {
            let inv = regularised_inverse(&self.block[j])?;
            self.solved[j] = (inv * self.residual[j], inv * self.to_cage[j]);
            let (ar, ab) = &self.solved[j];
            schur -= self.cage_rows[j] * ab;
            rhs += self.cage_rows[j] * ar;
        }
        for k in 0..GLOBALS {
            if cage.held[k] {
                schur.row_mut(k).fill(0.0);
                schur[(k, k)] = 1.0;
                rhs[k] = 0.0;
            }
        }
        let mut dg = if cage.held.iter().all(|&h| h) {
            Col::zeros()
        } else {
            regularised_inverse(&schur)? * rhs
        };
        let mut largest: f64 = 0.0;
        for k in 0..GLOBALS {
            dg[k] = dg[k].clamp(-sc.max_step_cage[k], sc.max_step_cage[k]);
            largest = largest.max((dg[k] / sc.limit_cage[k]).abs());
        }
        self.cage_correction = dg;
        for j in 0..self.residual.len() {
            let (ar, ab) = &self.solved[j];
            let mut du = -(ar + ab * dg);
            for k in 0..UNKNOWNS {
                du[k] = du[k].clamp(-sc.max_step[k], sc.max_step[k]);
                largest = largest.max((du[k] / sc.limit[k]).abs());
            }
            self.correction[j] = du;
        }
        Some(largest)
    }

    /// Broyden's update of the held Jacobian from the last evaluation to this one (unknowns
    /// `u`, `g`, the residuals just evaluated): each roller's block A_j takes the change of
    /// its residual that its own step and the globals' (through B_j) leave unexplained, the
    /// globals' D the change of their residual that the rollers' steps (through C_j) and
    /// their own leave; each along its step in the scaled unknowns (the convergence limits:
    /// the least change of the block in that norm, Broyden's good update). The chord
    /// iteration converges superlinearly with it at no evaluation of its own.
    fn secant_update(&mut self, u: &[[f64; UNKNOWNS]], g: &[f64; GLOBALS], cage_residual: &Col, cage: &CageStep, sc: &Scales) {
        let Some((g0, rc0)) = self.evaluated_cage else {
            self.secant_base(u, g, cage_residual);
            return;
        };
        let s_cage = Col::from_fn(|k, _| if cage.held[k] { 0.0 } else { g[k] - g0[k] });
        let mut unexplained_cage = cage_residual - rc0 - self.d_cage * s_cage;
        for (j, uj) in u.iter().enumerate() {
            let (u0, r0) = &self.evaluated[j];
            let s = Col::from_fn(|k, _| uj[k] - u0[k]);
            unexplained_cage -= self.cage_rows[j] * s;
            let w = Col::from_fn(|k, _| s[k] / (sc.limit[k] * sc.limit[k]));
            let ws = w.dot(&s);
            if ws > 0.0 && ws.is_finite() {
                let y = self.residual[j] - r0 - self.to_cage[j] * s_cage;
                let update = (y - self.block[j] * s) * w.transpose() / ws;
                if update.iter().all(|v| v.is_finite()) {
                    self.block[j] += update;
                }
            }
        }
        let w = Col::from_fn(|k, _| s_cage[k] / (sc.limit_cage[k] * sc.limit_cage[k]));
        let ws = w.dot(&s_cage);
        if ws > 0.0 && ws.is_finite() {
            let update = unexplained_cage * w.transpose() / ws;
            if update.iter().all(|v| v.is_finite()) {
                self.d_cage += update;
            }
        }
        self.secant_base(u, g, cage_residual);
    }

    /// Keep the unknowns and residuals just evaluated for the next secant update.
    fn secant_base(&mut self, u: &[[f64; UNKNOWNS]], g: &[f64; GLOBALS], cage_residual: &Col) {
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

    /// Take back a step that went too far: halve its share `lambda` and put `u`, `g` at that
    /// share of the last full Newton step from its start `base_u`, `base`. False (nothing
    /// done) where there is no step to take back or its share is already the least.
    fn take_back(
        &self,
        u: &mut [[f64; UNKNOWNS]],
        g: &mut [f64; GLOBALS],
        base_u: &[[f64; UNKNOWNS]],
        base: &Option<[f64; GLOBALS]>,
        lambda: &mut f64,
    ) -> bool {
        let Some(g0) = base.filter(|_| *lambda > MIN_DAMPING) else {
            return false;
        };
        *lambda *= 0.5;
        for (uj, (u0j, dj)) in u.iter_mut().zip(base_u.iter().zip(&self.step_taken)) {
            for k in 0..UNKNOWNS {
                uj[k] = u0j[k] + *lambda * dj[k];
            }
        }
        for k in 0..GLOBALS {
            g[k] = g0[k] + *lambda * self.cage_step_taken[k];
        }
        true
    }

    /// Apply the share `lambda` of the last Newton correction to `u` and `g`.
    fn apply_correction(&self, u: &mut [[f64; UNKNOWNS]], g: &mut [f64; GLOBALS], lambda: f64) {
        for k in 0..GLOBALS {
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
    pub fn hold(&mut self, state: &mut DynamicState, x: &[f64], cage_angle: f64) {
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

/// Put `state` back to `to`, keeping the work counted since (`DynamicState::counters`).
fn restore_keeping_counters(state: &mut DynamicState, to: &DynamicState) {
    let counters = state.counters;
    state.copy_from(to);
    state.counters = counters;
}

/// The inverse of a roller's block; where it is singular (a roller that touches nothing has
/// no skew or pocket stiffness), with its diagonal raised by 1e-9 of its largest entry (the
/// Jacobian is regularised, never the residual, so a converged balance is exact).
fn regularised_inverse(m: &Block) -> Option<Block> {
    if let Some(inv) = m.try_inverse().filter(|i| i.iter().all(|v| v.is_finite())) {
        return Some(inv);
    }
    let scale = m.amax().max(1e-300);
    (m + Block::identity() * (1e-9 * scale))
        .try_inverse()
        .filter(|i| i.iter().all(|v| v.is_finite()))
}
