//! Work-precision runs of the dynamic model: one scenario run with one integrator setting,
//! its outputs at every communication point, and its error against a reference run.
//!
//! The error of one output is the root-mean-square difference over the communication points
//! divided by the root-mean-square of the reference signal (or by a floor for outputs that
//! are nearly zero in a case, such as the tilting moments under pure axial load). A run's
//! error is the largest over [`OUTPUTS`]; its torque/skew error the largest over friction
//! torque, mean skew and roller 1's skew (the targets name those two).

use crate::cli::scenario::{Scenario, Value, Var};
use crate::cli::simulate::{prepare, step};
use std::time::Instant;
use trb::variables as var;

/// The outputs compared, with the scale floor of their relative error (SI units).
pub const OUTPUTS: [(&str, f64); 11] = [
    ("roller[1].skew", 1e-7),
    ("skew.mean", 1e-7),
    ("roller[1].tilt", 1e-8),
    ("tilt.max", 1e-8),
    ("cage.speed", 1e-3),
    ("frictionTorque", 1e-3),
    ("reaction.Fx", 1.0),
    ("reaction.My", 1.0),
    ("reaction.Mz", 1.0),
    ("cone.x", 1e-9),
    ("Qo.max", 1.0),
];

/// Indices into [`OUTPUTS`] of the torque/skew error.
const TORQUE_SKEW: [usize; 3] = [0, 1, 5];

/// The integrator families, in report order: (integrator parameter value, name, short name).
pub const FAMILIES: [(i32, &str, &str); 4] = [
    (0, "Dormand–Prince 5(4), adaptive", "Dormand–Prince"),
    (2, "Rosenbrock-W ROS34PW2, adaptive, block Jacobian", "Rosenbrock-W"),
    (
        3,
        "automatic: Dormand–Prince or Rosenbrock-W per communication step (default)",
        "automatic",
    ),
    (1, "Gill RK + Milne–Hamming, fixed step (the [W25] method)", "Gill/Milne–Hamming"),
];

/// One integrator setting: `integrator` with `tolerance` (0, 2, 3) or the fixed step `maxStep` (1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Method {
    pub integrator: i32,
    pub setting: f64,
}

impl Method {
    pub fn family(&self) -> &'static str {
        FAMILIES.iter().find(|f| f.0 == self.integrator).map_or("?", |f| f.1)
    }

    pub fn short_family(&self) -> &'static str {
        FAMILIES.iter().find(|f| f.0 == self.integrator).map_or("?", |f| f.2)
    }

    /// "tol 1e-6" or "h 2.0e-6 s".
    pub fn label(&self) -> String {
        if self.integrator == 1 {
            format!("h {:.1e} s", self.setting)
        } else {
            format!("tol {:.0e}", self.setting)
        }
    }

    /// The scenario with this method's parameters added (replacing the scenario's own).
    fn apply(&self, scenario: &Scenario) -> Scenario {
        let mut s = scenario.clone();
        let n = s.bearing.bearing.roller_count;
        let param = |name: &str| {
            let (vr, row) = var::find(name, n).expect("parameter in the model description");
            Var {
                vr,
                name: name.to_string(),
                ty: row.ty,
            }
        };
        let setting = if self.integrator == 1 { "maxStep" } else { "tolerance" };
        s.parameters
            .retain(|(v, _)| v.name != "integrator" && v.name != setting && v.name != "workBudget");
        s.parameters.push((param("integrator"), Value::Integer(self.integrator)));
        s.parameters.push((param(setting), Value::Real(self.setting)));
        // A benchmark measures what a method costs, however much: the largest work budget, so
        // that no tight reference or slow method stops at the FMU's cap for a master's step
        s.parameters.push((param("workBudget"), Value::Real(WORK_BUDGET)));
        s
    }
}

/// The work budget of every benchmark run (right-hand sides per simulated second): the
/// largest `workBudget` allows.
const WORK_BUDGET: f64 = 1e12;

/// The settings swept per family (`quick`: one each).
pub fn sweep(quick: bool) -> Vec<Method> {
    let m = |integrator, setting| Method { integrator, setting };
    if quick {
        return vec![m(0, 1e-6), m(2, 1e-4), m(3, 1e-6), m(1, 2e-6)];
    }
    let mut all = Vec::new();
    all.extend([1e-4, 1e-5, 1e-6, 1e-7, 1e-8].map(|t| m(0, t)));
    all.extend([1e-2, 1e-3, 1e-4, 1e-5, 1e-6].map(|t| m(2, t)));
    all.extend([1e-4, 1e-5, 1e-6, 1e-7].map(|t| m(3, t)));
    all.extend([0.5e-6, 1e-6, 2e-6, 3e-6].map(|h| m(1, h)));
    all
}

/// The reference: Dormand–Prince at a tolerance far below the sweep.
pub fn reference(quick: bool) -> Method {
    Method {
        integrator: 0,
        setting: if quick { 1e-8 } else { 1e-10 },
    }
}

/// The check of the reference, a different method, in order of preference: Gill/Milne–Hamming
/// at a fine fixed step (where it is stable), else Rosenbrock at a tight tolerance.
pub fn checks(quick: bool) -> Vec<Method> {
    if quick {
        vec![Method {
            integrator: 2,
            setting: 1e-7,
        }]
    } else {
        vec![
            Method {
                integrator: 1,
                setting: 0.5e-6,
            },
            Method {
                integrator: 2,
                setting: 1e-9,
            },
        ]
    }
}

/// What one run of a scenario produced.
#[derive(Debug, Clone)]
pub struct Trace {
    pub wall: f64,
    pub steps: i32,
    pub rhs: i32,
    pub rejected: i32,
    /// Per communication point, the values of [`OUTPUTS`].
    pub values: Vec<[f64; OUTPUTS.len()]>,
    /// Per communication point, what a user reads of the rollers.
    pub readings: Vec<Reading>,
}

/// What a user at the communication step reads of the rollers at one point: mean and
/// largest |skew| and |tilt| over the rollers (rad), friction torque (N m), cage speed
/// (rad/s), largest cone and cup loads of any roller (N).
#[derive(Debug, Clone, Copy, Default)]
pub struct Reading {
    pub skew_abs_mean: f64,
    pub skew_max: f64,
    pub tilt_abs_mean: f64,
    pub tilt_max: f64,
    pub torque: f64,
    pub cage_speed: f64,
    pub qi_max: f64,
    pub qo_max: f64,
}

impl Reading {
    fn of(o: &trb::model::Outputs) -> Reading {
        let z = o.skew.len().max(1) as f64;
        Reading {
            skew_abs_mean: o.skew.iter().map(|v| v.abs()).sum::<f64>() / z,
            skew_max: o.skew_max,
            tilt_abs_mean: o.tilt.iter().map(|v| v.abs()).sum::<f64>() / z,
            tilt_max: o.tilt_max,
            torque: o.friction_torque,
            cage_speed: o.cage_speed,
            qi_max: o.qi_max,
            qo_max: o.qo_max,
        }
    }
}

/// Run `scenario` with `method` under the stepping semantics of `trb simulate` (set the
/// inputs of t_{k+1} after the step to t_{k+1}, read the outputs). The wall time covers
/// everything from building the element to the last output. A model error ends the run
/// with the time and the model's message.
pub fn run(scenario: &Scenario, method: &Method) -> Result<Trace, String> {
    let s = method.apply(scenario);
    let n = s.bearing.bearing.roller_count;
    let vrs: Vec<u32> = OUTPUTS
        .iter()
        .map(|(name, _)| var::find(name, n).expect("output in the model description").0)
        .collect();
    let started = Instant::now();
    let mut sim = prepare(&s).map_err(|e| e.message)?;
    let mut values = Vec::with_capacity(s.n_steps + 1);
    let mut readings = Vec::with_capacity(s.n_steps + 1);
    let mut u: Vec<f64> = s.inputs.iter().map(|(_, sig)| sig.at(s.time(0))).collect();
    let mut read = |sim: &mut trb::simulation::Simulation, t: f64| -> Result<(), String> {
        readings.push(Reading::of(sim.outputs().map_err(|e| format!("t = {t:.6} s: {e}"))?));
        let mut row = [0.0; OUTPUTS.len()];
        for (r, vr) in row.iter_mut().zip(&vrs) {
            *r = sim.last_real(*vr).map_err(|e| format!("{e:?}"))?;
        }
        values.push(row);
        Ok(())
    };
    read(&mut sim, s.time(0))?;
    for k in 0..s.n_steps {
        let t_next = step(&mut sim, &s, &mut u, k).map_err(|e| e.message)?;
        read(&mut sim, t_next)?;
    }
    let wall = started.elapsed().as_secs_f64();
    let int = |vr| sim.last_integer(vr).unwrap_or(-1);
    Ok(Trace {
        wall,
        steps: int(var::INTEGRATOR_STEPS),
        rhs: int(var::INTEGRATOR_RHS),
        rejected: int(var::INTEGRATOR_REJECTED),
        values,
        readings,
    })
}

/// Relative RMS error of every output of `run` against `reference`.
pub fn errors(run: &Trace, reference: &Trace) -> [f64; OUTPUTS.len()] {
    let mut e = [0.0; OUTPUTS.len()];
    let n = run.values.len().min(reference.values.len()).max(1) as f64;
    for (k, (_, floor)) in OUTPUTS.iter().enumerate() {
        let (mut diff, mut scale) = (0.0, 0.0);
        for (a, r) in run.values.iter().zip(&reference.values) {
            diff += (a[k] - r[k]).powi(2);
            scale += r[k] * r[k];
        }
        e[k] = (diff / n).sqrt() / (scale / n).sqrt().max(*floor);
    }
    e
}

/// The largest error over all outputs.
pub fn max_error(e: &[f64; OUTPUTS.len()]) -> f64 {
    e.iter().fold(0.0, |m, v| m.max(*v))
}

/// The largest error over friction torque and skew.
pub fn torque_skew_error(e: &[f64; OUTPUTS.len()]) -> f64 {
    TORQUE_SKEW.iter().fold(0.0, |m, k| m.max(e[*k]))
}

/// Median of a non-empty list.
pub fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    if n % 2 == 1 {
        s[n / 2]
    } else {
        0.5 * (s[n / 2 - 1] + s[n / 2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trace(values: Vec<[f64; OUTPUTS.len()]>) -> Trace {
        Trace {
            wall: 0.0,
            steps: 0,
            rhs: 0,
            rejected: 0,
            values,
            readings: Vec::new(),
        }
    }

    #[test]
    fn relative_rms_error_with_floor() {
        let mut r = [0.0; OUTPUTS.len()];
        r[5] = 2.0; // frictionTorque 2 N m
        let mut a = r;
        a[5] = 2.002;
        a[7] = 0.1; // reaction.My: reference 0, floor 1 N m
        let e = errors(&trace(vec![a, a]), &trace(vec![r, r]));
        assert!((e[5] - 1e-3).abs() < 1e-12);
        assert!((e[7] - 0.1).abs() < 1e-12);
        assert_eq!(max_error(&e), e[7]);
        assert_eq!(torque_skew_error(&e), e[5]);
    }

    #[test]
    fn median_of_odd_and_even_lists() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
    }
}
