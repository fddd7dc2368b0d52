//! Hours of duty in one element: a repeating duty cycle at fidelity 0 and a long run under
//! combined load at fidelity 1 and at fidelity 2, with the books a long run must keep
//! (`trb soak`).
//!
//! - Memory: the process's resident set (`/proc/self/statm`) after the first simulated minute
//!   (or, for a shorter run, its first sixth) and at the end.
//! - Energy: at fidelities 1 and 2 the shaft's work ∫ T ω dt against the contacts'
//!   dissipation ∫ P dt, the change of the bodies' kinetic energy and the work of the loads on
//!   the cone's translation (trapezoid over the communication points, [`under_load`]); the
//!   contacts' elastic energy is bounded and left out (fidelity 2 stores none: its seat is in
//!   balance). At fidelity 0 the element stores no energy and reports the power
//!   loss as the torque times the relative speed: the books close by construction and are not
//!   counted as a check.
//! - Repeatability: the fidelity-0 duty cycle repeats every [`CYCLE`] seconds, and every sampled
//!   point of a later cycle is compared with the same point of the first where the load is
//!   axisymmetric. Under a radial load the outputs also depend on where the rollers stand
//!   (the varying compliance of the load zone), and the cage, which advances with time, stands
//!   elsewhere when the inputs return: a film ratio then differs by up to 1e-3 between cycles.
//! - Health: every step succeeds and every output is finite.
//!
//! Used by the `soak` command and by `tests/soak.rs` (a one-minute fidelity-0 run and a
//! one-second fidelity-2 run in CI).

use std::time::Instant;
use trb::bearing::Bearing;
use trb::model::Outputs;
use trb::simulation::Simulation;
use trb::variables as var;

/// Period of the fidelity-0 duty cycle (s).
pub const CYCLE: f64 = 20.0;
/// Communication step of both runs (s).
pub const STEP: f64 = 1e-3;
const RPM: f64 = std::f64::consts::PI / 30.0;

/// What a soak run measured.
#[derive(Debug, Clone, Default)]
pub struct Soak {
    pub fidelity: i32,
    pub simulated: f64,
    pub wall: f64,
    pub steps: usize,
    /// Resident memory (bytes) after the first minute (or sixth) and at the end.
    pub rss_early: u64,
    pub rss_end: u64,
    /// Fidelities 1 and 2: shaft work, dissipation, kinetic energy change, work of the loads
    /// (J).
    pub shaft_work: f64,
    pub dissipated: f64,
    pub kinetic_change: f64,
    pub load_work: f64,
    /// Fidelity 0: largest relative difference of a later cycle's sampled outputs from the
    /// first cycle's, and how many points were compared.
    pub repeat_error: f64,
    pub repeat_points: usize,
    /// Fidelities 1 and 2: mean friction torque over the second and the last simulated second
    /// (N m; the second's stays 0 in a run shorter than 2 s).
    pub torque_first: f64,
    pub torque_last: f64,
    /// The first failure: the time and the message.
    pub failure: Option<(f64, String)>,
}

impl Soak {
    /// Growth of the resident memory after the first minute (bytes).
    pub fn memory_growth(&self) -> i64 {
        self.rss_end as i64 - self.rss_early as i64
    }

    /// |shaft work − dissipation − kinetic energy change − load work| over the dissipation.
    pub fn energy_residual(&self) -> f64 {
        (self.shaft_work - self.dissipated - self.kinetic_change + self.load_work).abs() / self.dissipated
    }
}

/// The resident set of this process (bytes; 0 where `/proc` is not there).
pub fn resident_memory() -> u64 {
    std::fs::read_to_string("/proc/self/statm")
        .ok()
        .and_then(|s| s.split_whitespace().nth(1).and_then(|v| v.parse::<u64>().ok()))
        .map_or(0, |pages| pages * 4096)
}

/// Linear interpolation in a table of (time, value) points, held outside.
fn table(points: &[(f64, f64)], t: f64) -> f64 {
    if t <= points[0].0 {
        return points[0].1;
    }
    for w in points.windows(2) {
        let ((t0, v0), (t1, v1)) = (w[0], w[1]);
        if t <= t1 {
            return if t1 > t0 { v0 + (v1 - v0) * (t - t0) / (t1 - t0) } else { v1 };
        }
    }
    points[points.len() - 1].1
}

/// The fidelity-0 duty cycle at time `t` within its period: speed (rad/s), axial and radial
/// load (N) of a default bearing: a run-up, load steps and ramps, a slow-down, all within the
/// bearing's rating.
pub fn duty(t: f64) -> (f64, f64, f64) {
    // the table's times are sixtieths of the cycle
    let t = t.rem_euclid(CYCLE) * 60.0 / CYCLE;
    let speed = table(
        &[
            (0.0, 1000.0),
            (10.0, 3500.0),
            (30.0, 3500.0),
            (40.0, 2000.0),
            (55.0, 2000.0),
            (60.0, 1000.0),
        ],
        t,
    );
    let axial = table(
        &[
            (0.0, 20e3),
            (15.0, 20e3),
            (15.003, 50e3),
            (25.0, 50e3),
            (35.0, 20e3),
            (45.0, 20e3),
            (45.003, 30e3),
            (60.0, 20e3),
        ],
        t,
    );
    let radial = table(
        &[
            (0.0, 0.0),
            (5.0, 0.0),
            (5.003, 20e3),
            (20.0, 20e3),
            (30.0, 60e3),
            (50.0, 60e3),
            (50.003, 0.0),
        ],
        t,
    );
    (speed * RPM, axial, radial)
}

/// The outputs compared between cycles.
fn signature(o: &Outputs) -> [f64; 8] {
    [
        o.friction_torque,
        o.power_loss,
        o.cone_x,
        o.cone_y,
        o.reaction_fx,
        o.film_ratio_raceway,
        o.film_ratio_flange,
        o.life_l10,
    ]
}

fn rel(a: f64, b: f64) -> f64 {
    let scale = a.abs().max(b.abs());
    if scale == 0.0 {
        0.0
    } else {
        (a - b).abs() / scale
    }
}

/// The moment of the run after which memory must not grow: one minute, or a sixth of a
/// shorter run.
fn early(seconds: f64) -> f64 {
    (seconds / 6.0).min(60.0)
}

/// `seconds` of the fidelity-0 duty cycle on the default bearing in 1 ms steps.
pub fn fidelity_0(seconds: f64) -> Soak {
    let b = Bearing::default_preset();
    let mut s = Simulation::new(b);
    let mut r = Soak::default();
    let n = (seconds / STEP).round() as usize;
    let samples_per_cycle = (CYCLE / STEP).round() as usize;
    // a sample every 0.1 s within the first cycle
    let every = (0.1 / STEP).round() as usize;
    let mut first: Vec<Option<[f64; 8]>> = vec![None; samples_per_cycle / every + 1];
    let set = |s: &mut Simulation, t: f64| {
        let (speed, axial, radial) = duty(t);
        s.set_real(var::SPEED, speed)
            .and(s.set_real(var::FX, axial))
            .and(s.set_real(var::FY, radial))
    };
    let start = Instant::now();
    let outcome = (|| -> Result<(), (f64, String)> {
        set(&mut s, 0.0).map_err(|e| (0.0, format!("{e:?}")))?;
        s.initialize(0.0).map_err(|e| (0.0, e.to_string()))?;
        let early_step = (early(seconds) / STEP).round() as usize;
        for k in 0..n {
            let t = k as f64 * STEP;
            s.do_step(t, STEP).map_err(|e| (t, e.to_string()))?;
            let t1 = (k + 1) as f64 * STEP;
            set(&mut s, t1).map_err(|e| (t1, format!("{e:?}")))?;
            let o = s.outputs().map_err(|e| (t1, e.to_string()))?;
            if !o.all_finite() {
                return Err((t1, "an output is not finite".into()));
            }
            let phase = (k + 1) % samples_per_cycle;
            // with a radial load the outputs depend on where the rollers stand, and the cage
            // advances with time: only axisymmetric points repeat
            if phase % every == 0 && duty(t1).2 == 0.0 {
                let sig = signature(o);
                if k < samples_per_cycle {
                    first[phase / every] = Some(sig);
                } else if let Some(Some(f)) = first.get(phase / every) {
                    for (a, b) in sig.iter().zip(f) {
                        r.repeat_error = r.repeat_error.max(rel(*a, *b));
                    }
                    r.repeat_points += 1;
                }
            }
            if k + 1 == early_step {
                r.rss_early = resident_memory();
            }
            r.steps += 1;
        }
        Ok(())
    })();
    r.failure = outcome.err();
    r.wall = start.elapsed().as_secs_f64();
    r.simulated = r.steps as f64 * STEP;
    r.rss_end = resident_memory();
    r
}

/// `seconds` at fidelity 1 under combined load ([`under_load`]).
pub fn fidelity_1(seconds: f64) -> Soak {
    under_load(1, seconds)
}

/// `seconds` at fidelity 2 under combined load ([`under_load`]).
pub fn fidelity_2(seconds: f64) -> Soak {
    under_load(2, seconds)
}

/// `seconds` at `fidelity` (1 or 2) under combined load: the default bearing at 3500 rpm,
/// Fa 30 kN, Fy 10 kN, in 1 ms steps, with its energy books: the shaft's work and the
/// dissipation by the trapezoid rule over the communication points, the change of the
/// kinetic energy from the start to the end, and the loads' work on the cone's travel.
pub fn under_load(fidelity: i32, seconds: f64) -> Soak {
    let b = Bearing::default_preset();
    let mut s = Simulation::new(b);
    let mut r = Soak {
        fidelity,
        ..Soak::default()
    };
    let n = (seconds / STEP).round() as usize;
    let (speed, fx, fy) = (3500.0 * RPM, 30e3, 10e3);
    let start = Instant::now();
    let per_second = (1.0 / STEP).round() as usize;
    let outcome = (|| -> Result<(), (f64, String)> {
        let bad = |t: f64| move |e: trb::simulation::AccessError| (t, format!("{e:?}"));
        s.set_integer(var::FIDELITY, fidelity).map_err(bad(0.0))?;
        s.set_real(var::SPEED, speed).map_err(bad(0.0))?;
        s.set_real(var::FX, fx).map_err(bad(0.0))?;
        s.set_real(var::FY, fy).map_err(bad(0.0))?;
        s.initialize(0.0).map_err(|e| (0.0, e.to_string()))?;
        let books = |s: &mut Simulation, t: f64| -> Result<(f64, f64, f64, f64), (f64, String)> {
            let o = s.outputs().map_err(|e| (t, e.to_string()))?;
            if !o.all_finite() {
                return Err((t, "an output is not finite".into()));
            }
            Ok((o.friction_torque * speed, o.power_loss, o.cone_x, o.cone_y))
        };
        let (mut input, mut loss, x0, y0) = books(&mut s, 0.0)?;
        let ke0 = s.kinetic_energy();
        let early_step = (early(seconds) / STEP).round() as usize;
        let mut torque_sum = 0.0;
        let (mut x, mut y) = (x0, y0);
        for k in 0..n {
            let t = k as f64 * STEP;
            s.do_step(t, STEP).map_err(|e| (t, e.to_string()))?;
            let (a, l, xn, yn) = books(&mut s, t + STEP)?;
            r.shaft_work += 0.5 * (a + input) * STEP;
            r.dissipated += 0.5 * (l + loss) * STEP;
            (input, loss, x, y) = (a, l, xn, yn);
            torque_sum += a / speed;
            if (k + 1) % per_second == 0 {
                let second = (k + 1) / per_second;
                let mean = torque_sum / per_second as f64;
                if second == 2 {
                    r.torque_first = mean;
                }
                r.torque_last = mean;
                torque_sum = 0.0;
            }
            if k + 1 == early_step {
                r.rss_early = resident_memory();
            }
            r.steps += 1;
        }
        r.kinetic_change = s.kinetic_energy() - ke0;
        // the loads push the cone into the bearing along +x and +y
        r.load_work = fx * (x - x0) + fy * (y - y0);
        Ok(())
    })();
    r.failure = outcome.err();
    r.wall = start.elapsed().as_secs_f64();
    r.simulated = r.steps as f64 * STEP;
    r.rss_end = resident_memory();
    r
}
