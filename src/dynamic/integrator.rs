//! Adaptive explicit Runge-Kutta integration for the dynamic model: Dormand & Prince 5(4)
//! (Hairer, Norsett & Wanner, Solving ODEs I, table 5.2), first-same-as-last, local
//! extrapolation, PI step-size control (Gustafsson), error measured as the RMS of the
//! embedded error over per-component scales `atol_i + rtol_i |y_i|`. Communication points
//! are hit exactly: the last step of an interval is shortened to land on it.
//!
//! No allocation per step: all stage vectors live in the workspace.

/// Butcher tableau of DOPRI5.
const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
// error coefficients: 5th order weights minus 4th order weights
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;

/// Counters of the work done.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Counters {
    pub steps: u64,
    pub rejected: u64,
    /// Right-hand-side evaluations, including those of Jacobians.
    pub rhs: u64,
    /// Jacobians and matrix factorisations of the implicit integrator.
    pub jacobians: u64,
    pub factorizations: u64,
}

/// The step-size controller's memory between calls: the proposed next step and the error
/// of the last accepted step (the I part of the PI controller). It belongs to the caller's
/// state, with the solution, so that a restored state resumes bit for bit.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StepControl {
    /// Next proposed step (s); 0 or non-finite: not known yet.
    pub h: f64,
    /// Scaled error of the last accepted step, floored at 1e-4 (Hairer's start value).
    pub err_prev: f64,
}

impl StepControl {
    /// No step proposed yet, the controller's start value.
    pub const fn start(h: f64) -> StepControl {
        StepControl { h, err_prev: 1e-4 }
    }
}

impl Default for StepControl {
    fn default() -> StepControl {
        StepControl::start(0.0)
    }
}

/// RMS over the components of the error `e` scaled by `atol_i + rtol_i max(|y_i|, |y_new_i|)`.
pub fn error_norm(e: &[f64], y: &[f64], y_new: &[f64], atol: &[f64], rtol: &[f64]) -> f64 {
    let mut sum = 0.0;
    for i in 0..e.len() {
        let sc = atol[i] + rtol[i] * y[i].abs().max(y_new[i].abs());
        let r = e[i] / sc;
        sum += r * r;
    }
    (sum / e.len() as f64).sqrt()
}

/// Why integration stopped early.
#[derive(Debug, Clone, PartialEq)]
pub enum Failure {
    /// The step size fell below the floor at time `t`.
    StepTooSmall { t: f64, h: f64 },
    /// The right-hand side produced NaN/inf at time `t` even at the smallest step.
    NotFinite { t: f64 },
    /// More than the step budget for one interval.
    TooManySteps { t: f64, steps: u64 },
    /// Fixed-step method: the local error estimate exceeded the tolerance by the factor
    /// `estimate` (unstable or far too long a step `h`).
    FixedStepTooLong { t: f64, h: f64, estimate: f64 },
    /// More right-hand sides than the budget for one interval (the doStep's work budget, or the
    /// automatic integrator's limit on Rosenbrock-W); `t` and the state are those of the last
    /// accepted step, `h` the step the method was trying.
    OverBudget { t: f64, h: f64 },
}

impl Failure {
    /// After a rejected step: the proposed step `h` fell below the floor at `t`; the cause is
    /// a non-finite stage when the step's values were not `finite`.
    pub fn below_floor(finite: bool, t: f64, h: f64) -> Failure {
        if finite {
            Failure::StepTooSmall { t, h }
        } else {
            Failure::NotFinite { t }
        }
    }
}

/// Workspace and settings of the integrator.
#[derive(Debug, Clone)]
pub struct Dopri5 {
    k: [Vec<f64>; 7],
    y_stage: Vec<f64>,
    y_new: Vec<f64>,
    /// Per-component absolute and relative tolerances.
    pub atol: Vec<f64>,
    pub rtol: Vec<f64>,
    pub max_step: f64,
    /// Steps allowed per call of `integrate`.
    pub step_budget: u64,
    /// Right-hand sides one call may evaluate before it stops with `Failure::OverBudget`.
    pub rhs_budget: u64,
}

impl Dopri5 {
    pub fn new(n: usize, atol: Vec<f64>, rtol: Vec<f64>, max_step: f64) -> Dopri5 {
        assert!(atol.len() == n && rtol.len() == n);
        Dopri5 {
            k: std::array::from_fn(|_| vec![0.0; n]),
            y_stage: vec![0.0; n],
            y_new: vec![0.0; n],
            atol,
            rtol,
            max_step,
            step_budget: 50_000_000,
            rhs_budget: u64::MAX,
        }
    }

    /// Integrate `y` from `t` to `t_end` with the controller state `step` (its trial step is
    /// updated in place to the next proposed step). `f(t, y, dydt)` evaluates the right-hand side. `fsal` holds the
    /// derivative at (t, y) from the last accepted step (first same as last); empty means
    /// unknown. It belongs to the caller's state, so a restored state resumes bit for bit.
    #[allow(clippy::too_many_arguments)]
    pub fn integrate<F: FnMut(f64, &[f64], &mut [f64])>(
        &mut self,
        f: F,
        t: &mut f64,
        y: &mut [f64],
        t_end: f64,
        step: &mut StepControl,
        counters: &mut Counters,
        fsal: &mut Vec<f64>,
    ) -> Result<(), Failure> {
        let n = y.len();
        let rhs_at_start = counters.rhs;
        if fsal.len() == n {
            self.k[0].copy_from_slice(fsal);
        } else {
            let mut f = f;
            f(*t, y, &mut self.k[0]);
            counters.rhs += 1;
            let r = self.run(f, t, y, t_end, step, counters, rhs_at_start);
            fsal.clear();
            fsal.extend_from_slice(&self.k[0]);
            return r;
        }
        let r = self.run(f, t, y, t_end, step, counters, rhs_at_start);
        fsal.copy_from_slice(&self.k[0]);
        r
    }

    #[allow(clippy::too_many_arguments)]
    fn run<F: FnMut(f64, &[f64], &mut [f64])>(
        &mut self,
        mut f: F,
        t: &mut f64,
        y: &mut [f64],
        t_end: f64,
        step: &mut StepControl,
        counters: &mut Counters,
        rhs_at_start: u64,
    ) -> Result<(), Failure> {
        let n = y.len();
        let StepControl { h, err_prev } = step;
        let mut steps_here = 0u64;
        let h_floor = |t: f64| 1e-15 * t.abs().max(1e-3);
        if !(*h > 0.0 && h.is_finite()) {
            *h = self.max_step.min(1e-6);
        }
        while *t < t_end {
            let remaining = t_end - *t;
            if remaining <= h_floor(t_end) {
                *t = t_end;
                break;
            }
            let mut hs = h.min(self.max_step);
            let last = hs >= remaining * (1.0 - 1e-12);
            if last {
                hs = remaining;
            }
            if steps_here >= self.step_budget {
                return Err(Failure::TooManySteps { t: *t, steps: steps_here });
            }
            if counters.rhs - rhs_at_start + 6 > self.rhs_budget {
                return Err(Failure::OverBudget { t: *t, h: hs });
            }
            // stages
            let [k1, k2, k3, k4, k5, k6, k7] = &mut self.k;
            let ys = &mut self.y_stage;
            for i in 0..n {
                ys[i] = y[i] + hs * A21 * k1[i];
            }
            f(*t + C2 * hs, ys, k2);
            for i in 0..n {
                ys[i] = y[i] + hs * (A31 * k1[i] + A32 * k2[i]);
            }
            f(*t + C3 * hs, ys, k3);
            for i in 0..n {
                ys[i] = y[i] + hs * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i]);
            }
            f(*t + C4 * hs, ys, k4);
            for i in 0..n {
                ys[i] = y[i] + hs * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i]);
            }
            f(*t + C5 * hs, ys, k5);
            for i in 0..n {
                ys[i] = y[i] + hs * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i]);
            }
            let t_new = if last { t_end } else { *t + hs };
            f(t_new, ys, k6);
            let yn = &mut self.y_new;
            for i in 0..n {
                yn[i] = y[i] + hs * (A71 * k1[i] + A73 * k3[i] + A74 * k4[i] + A75 * k5[i] + A76 * k6[i]);
            }
            f(t_new, yn, k7);
            counters.rhs += 6;
            // error estimate
            let mut sum = 0.0;
            let mut finite = true;
            for i in 0..n {
                let e = hs * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
                let sc = self.atol[i] + self.rtol[i] * y[i].abs().max(yn[i].abs());
                let r = e / sc;
                sum += r * r;
                finite &= yn[i].is_finite() && k7[i].is_finite();
            }
            let err = if finite { (sum / n as f64).sqrt() } else { f64::INFINITY };
            if err <= 1.0 {
                // accept
                y.copy_from_slice(yn);
                std::mem::swap(k1, k7);
                *t = t_new;
                counters.steps += 1;
                steps_here += 1;
                // PI controller (Hairer's constants for DOPRI5)
                let fac = if err == 0.0 {
                    5.0
                } else {
                    0.9 * libm::pow(err, -0.7 / 5.0) * libm::pow(*err_prev, 0.4 / 5.0)
                };
                let fac = fac.clamp(0.2, 5.0);
                *err_prev = err.max(1e-4);
                if !last {
                    *h = hs * fac;
                } else {
                    // keep the step that fitted best; a shortened last step says little
                    *h = h.max(hs * fac).min(self.max_step);
                }
            } else {
                counters.rejected += 1;
                let fac = if finite {
                    (0.9 * libm::pow(err, -1.0 / 5.0)).clamp(0.1, 0.9)
                } else {
                    0.1
                };
                *h = hs * fac;
                if *h < h_floor(*t) {
                    return Err(Failure::below_floor(finite, *t, *h));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(tol: f64) -> (f64, Counters) {
        // harmonic oscillator y'' = -w^2 y over several periods
        let w = 7.0;
        let mut ig = Dopri5::new(2, vec![tol; 2], vec![tol; 2], 1.0);
        let mut y = [1.0, 0.0];
        let (mut t, mut h) = (0.0, StepControl::start(1e-3));
        let mut c = Counters::default();
        let mut fsal = Vec::new();
        for k in 1..=10 {
            let t_end = k as f64 * 0.3;
            ig.integrate(
                |_, y: &[f64], d: &mut [f64]| {
                    d[0] = y[1];
                    d[1] = -w * w * y[0];
                },
                &mut t,
                &mut y,
                t_end,
                &mut h,
                &mut c,
                &mut fsal,
            )
            .unwrap();
            assert_eq!(t, t_end, "communication point must be hit exactly");
        }
        ((y[0] - (w * 3.0_f64).cos()).abs(), c)
    }

    #[test]
    fn error_follows_tolerance_with_fifth_order_work() {
        let (e1, c1) = run(1e-6);
        let (e2, c2) = run(1e-9);
        assert!(e1 < 1e-4 && e2 < 1e-7, "{e1} {e2}");
        assert!(e2 < e1 / 50.0);
        // 1000x tighter tolerance costs about 1000^(1/5) = 4x the steps
        let ratio = c2.steps as f64 / c1.steps as f64;
        assert!(ratio > 2.0 && ratio < 8.0, "step ratio {ratio}");
    }

    #[test]
    fn non_finite_right_hand_side_is_reported() {
        let mut ig = Dopri5::new(1, vec![1e-6], vec![1e-6], 1.0);
        let mut y = [1.0];
        let (mut t, mut h) = (0.0, StepControl::start(0.1));
        let mut c = Counters::default();
        let r = ig.integrate(
            |_, _, d: &mut [f64]| d[0] = f64::NAN,
            &mut t,
            &mut y,
            1.0,
            &mut h,
            &mut c,
            &mut Vec::new(),
        );
        assert!(
            matches!(r, Err(Failure::NotFinite { .. }) | Err(Failure::StepTooSmall { .. })),
            "{r:?}"
        );
        assert!(y[0].is_finite());
    }
}
