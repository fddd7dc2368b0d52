//! The running state of a bearing whose state is periodic, not steady, seen from the cage:
//! radial load, misalignment, a lobed cup or rollers of different diameters.
//!
//! The quasi-static seat with epicyclic speeds is in force equilibrium, but not in its power
//! balance: the rollers roll purely, so the cone's raceways carry almost none of the traction
//! that drives them in running (a 30206 at 3000 rpm under Fx 3 kN, Fy 2 kN: a friction torque
//! of 0.142 N m at the seat, 0.53 N m when running, while the contacts already dissipate
//! 167 W). Started there, the first output sample breaks the relation every later one obeys,
//! friction torque = power loss / (speed − cupSpeed), and a transient rings for about a
//! millisecond while the rollers' spin, skew and the cage take up their traction.
//!
//! `run_in` runs the bearing at its initial inputs, in chunks of [`CHUNK`], until the
//! shaft's input power and the contacts' dissipation agree within [`BALANCE`]: then the
//! kinetic energy of rollers and cage no longer changes on the time scale of a chunk, which is
//! what running means. It stops after [`MAX_RUN_IN`] in any case. Then it turns the rolling set
//! back to where it started (roller 1 at `cage.angle0`). Identical rollers run on until the
//! cage has turned a whole number of pitches and are renumbered: the running state being
//! periodic in the pitch, that is exact but for the small remainder of the turn that the cage
//! speed's change over the last stretch leaves, turned back as a rigid rotation of rollers
//! and cage about the bearing axis. (Turned back by a rotation alone, up to half a pitch, the
//! rollers sit where their neighbours' loads were, and the state rings: the 30206 below took
//! 4357 right-hand sides over its first millisecond against 967.) Rollers that differ are
//! turned back by the whole turn. Last, the cone is moved to where the rollers' forces
//! balance the loads on it (Newton on its free translations), so that the first sample's
//! reactions balance the inputs, as every later one does up to the vibration of running.
//!
//! What the run-in does not wait for: the slow ringing of the rollers' skew, which settles
//! over about 0.1 s on the [W25] bearing (`docs/dynamic.md`) and hardly moves the power
//! balance.

use super::{Dynamic, DynamicState, CAGE, CONE, PER_ROLLER};
use crate::model::{Inputs, ModelError, Outputs};
use std::f64::consts::TAU;

/// Simulated time per chunk of the run-in (s): the roller spin takes up its traction within
/// about 40 µs (the 30206 above), so a chunk sees that change within it.
pub const CHUNK: f64 = 1e-4;

/// Relative mismatch of input power and dissipation at which the bearing runs: 1 %, the
/// size of the mismatch that the roller passes alone make in running under radial load (the
/// 30206 above: up to 0.4 % between communication points).
pub const BALANCE: f64 = 1e-2;

/// Longest run-in (s): the default bearing under Fy 25 kN takes about 4 ms to come within
/// [`BALANCE`] from the seat (its rollers weigh 0.1 kg; the 30206's 3.6 g rollers 0.1 ms).
pub const MAX_RUN_IN: f64 = 10e-3;

/// Most right-hand sides the run-in spends (it stops there, balanced or not): the work of a
/// hard millisecond, about 1.5 s on a 17-roller bearing. Running in costs what running does:
/// 1 000 to 2 000 right-hand sides per millisecond of the presets under moderate loads, so the
/// cap only stops it under heavy loads near the model's range.
pub const RUN_IN_WORK: u64 = 20_000;

/// Longest run on to the next whole pitch (s): beyond it (a slow cage) the rest of the turn
/// is turned back as a rotation.
pub const MAX_TO_PITCH: f64 = 3e-3;

/// Newton iterations of the cone's balance after the rolling set is turned back.
pub const BALANCE_ITERATIONS: usize = 4;

/// What the run-in did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunIn {
    /// Simulated time run in (s).
    pub time: f64,
    /// The input power and the dissipation agreed within [`BALANCE`].
    pub balanced: bool,
}

/// |T w − P| / max(|T w|, P): how far the shaft's input power and the contacts' dissipation
/// are apart.
pub fn power_mismatch(out: &Outputs, inputs: &Inputs) -> f64 {
    let input = out.friction_torque * inputs.relative_speed();
    let scale = input.abs().max(out.power_loss.abs());
    if scale > 0.0 {
        (input - out.power_loss).abs() / scale
    } else {
        0.0
    }
}

impl Dynamic {
    /// Run the bearing in from `state` at the held `inputs` (see the module's doc), then turn
    /// the rolling set back to where it started; the time, the integrator's memory and its
    /// counters are those of a fresh start. On failure `state` is unchanged.
    pub fn run_in(&mut self, state: &mut DynamicState, inputs: &Inputs) -> Result<RunIn, ModelError> {
        // with the bearing's default integrator settings, a fresh integrator, whatever the
        // element's own (which it gets back, untouched, after)
        let own = self
            .run_in_settings
            .as_ref()
            .map(|(settings, speed)| super::integrator(&self.g, &self.c, settings, *speed))
            .map(|ig| std::mem::replace(&mut self.ig, ig));
        let result = self.run_in_with_integrator(state, inputs);
        if let Some(own) = own {
            self.ig = own;
        }
        result
    }

    fn run_in_with_integrator(&mut self, state: &mut DynamicState, inputs: &Inputs) -> Result<RunIn, ModelError> {
        let t0 = state.t;
        let start_angle = state.y[CAGE + 2];
        let mut out = Outputs::new(self.g.z);
        let mut running = state.clone();
        let mut balanced = false;
        let mut chunks = 0;
        let work = |st: &DynamicState| st.counters.rhs - state.counters.rhs;
        while !balanced && (chunks as f64) * CHUNK < MAX_RUN_IN * (1.0 - 1e-9) && work(&running) < RUN_IN_WORK {
            chunks += 1;
            self.advance(&mut running, inputs, t0 + chunks as f64 * CHUNK)?;
            self.write_outputs(&running, inputs, &mut out);
            balanced = power_mismatch(&out, inputs) <= BALANCE;
        }
        // identical rollers: on to the next whole pitch of the cage, so that renumbering the
        // rollers turns the set back onto its periodic orbit, but for the cage speed's change
        // over that last stretch
        let pitch = TAU / self.g.z as f64;
        let cage_speed = running.y[CAGE + 5];
        let turned = running.y[CAGE + 2] - start_angle;
        if super::identical_rollers(&self.p) && cage_speed != 0.0 {
            let target = turned.signum() * (turned.abs() / pitch).ceil() * pitch;
            let rest = (target - turned) / cage_speed;
            if rest > 0.0 && rest <= MAX_TO_PITCH && work(&running) < RUN_IN_WORK {
                let t = running.t;
                self.advance(&mut running, inputs, t + rest)?;
            }
        }
        let turned = running.y[CAGE + 2] - start_angle;
        self.turn_back(&mut running, turned);
        // a turning defect starts where its parameters put it
        for k in self.c.layout.turns() {
            running.y[k] = 0.0;
        }
        self.balance_cone(&mut running, inputs);
        running.t = t0;
        running.counters = Default::default();
        running.fsal.clear();
        running.fsal_inputs = None;
        running.memory.clear();
        *state = running;
        Ok(RunIn {
            time: chunks as f64 * CHUNK,
            balanced,
        })
    }

    /// Move the cone's free translations (force inputs) to where the forces on it balance:
    /// its acceleration zero, by Newton's method with a finite-difference Jacobian (at most
    /// [`BALANCE_ITERATIONS`] iterations of four right-hand sides). A balance not found
    /// keeps the best state seen.
    fn balance_cone(&mut self, state: &mut DynamicState, inputs: &Inputs) {
        let moving = super::moving_globals(&self.g, &self.p, &self.c.layout);
        let free: Vec<usize> = (0..3).filter(|&k| moving[k]).collect();
        if free.is_empty() {
            return;
        }
        let n = self.n_states();
        let (mut f, mut fp) = (vec![0.0; n], vec![0.0; n]);
        let residual = |dy: &[f64]| -> Vec<f64> { free.iter().map(|&k| dy[CONE + 3 + k]).collect() };
        let norm = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>().sqrt();
        self.rhs(inputs, &state.y, &mut f);
        let mut r = residual(&f);
        for _ in 0..BALANCE_ITERATIONS {
            let m = free.len();
            let mut jac = nalgebra::DMatrix::<f64>::zeros(m, m);
            for (c, &k) in free.iter().enumerate() {
                let step = 1e-9;
                let keep = state.y[CONE + k];
                state.y[CONE + k] = keep + step;
                self.rhs(inputs, &state.y, &mut fp);
                state.y[CONE + k] = keep;
                for (row, v) in residual(&fp).iter().enumerate() {
                    jac[(row, c)] = (v - r[row]) / step;
                }
            }
            let Some(dx) = jac.lu().solve(&nalgebra::DVector::from_column_slice(&r)) else {
                return;
            };
            let before: Vec<f64> = free.iter().map(|&k| state.y[CONE + k]).collect();
            for (c, &k) in free.iter().enumerate() {
                state.y[CONE + k] -= dx[c];
            }
            self.rhs(inputs, &state.y, &mut f);
            let next = residual(&f);
            if !(norm(&next) < norm(&r)) {
                for (c, &k) in free.iter().enumerate() {
                    state.y[CONE + k] = before[c];
                }
                return;
            }
            r = next;
        }
    }

    /// Turn the rolling set (rollers and cage) back about the bearing axis by `angle`: whole
    /// pitches by renumbering identical rollers, the rest as a rotation. Each roller's orbit
    /// angle stays continuous with its nominal place, j pitches after roller 1.
    fn turn_back(&self, state: &mut DynamicState, angle: f64) {
        let z = self.g.z;
        let pitch = TAU / z as f64;
        let whole = if super::identical_rollers(&self.p) {
            (angle / pitch).round() as i64
        } else {
            0
        };
        let shift = whole.rem_euclid(z as i64) as usize;
        let layout = &self.c.layout;
        let rollers = &mut state.y[layout.roller(0)..layout.roller(z)];
        // roller j takes the state of the roller that turned into its place
        rollers.rotate_right(PER_ROLLER * shift);
        for j in 0..z {
            let from = (j + z - shift) % z;
            rollers[PER_ROLLER * j + 2] += (j as f64 - from as f64) * pitch - angle;
        }
        state.y[CAGE + 2] -= angle;
    }
}
