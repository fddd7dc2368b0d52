//! The study's integration method [W25]: Gill's fourth-order Runge-Kutta method for the
//! starting values and Hamming's modified predictor-corrector (Milne's predictor, Hamming's
//! corrector with the predictor and final modifiers, Hamming 1959) at a fixed step.
//!
//! Step: h = the communication interval divided into equal steps no longer than `maxStep`.
//! The three starting steps are Gill's (4 right-hand sides each); then per step
//!
//! ```text
//!   p_{n+1} = y_{n-3} + 4h/3 (2 f_n - f_{n-1} + 2 f_{n-2})          (Milne predictor)
//!   m_{n+1} = p_{n+1} - 112/121 (p_n - c_n)                          (modifier)
//!   c_{n+1} = (9 y_n - y_{n-2})/8 + 3h/8 (f(m_{n+1}) + 2 f_n - f_{n-1})  (Hamming corrector)
//!   y_{n+1} = c_{n+1} + 9/121 (p_{n+1} - c_{n+1})                    (final modifier)
//! ```
//!
//! with f_{n+1} = f(y_{n+1}): two right-hand sides per step, no step size control. The
//! method still watches its local error: Milne's estimate of the corrector's truncation
//! error, 9/121 (p_{n+1} - c_{n+1}), in the RMS norm of the adaptive methods (per-component
//! scales atol_i + rtol_i |y_i| from `tolerance`). A fixed step that is unstable or far too
//! long grows that estimate without bound long before the state overflows, so an estimate
//! above [`UNSTABLE`] times the tolerance ends the step with [`Failure::FixedStepTooLong`]
//! instead of returning a finite but meaningless state. The method restarts (Gill again)
//! when the step size or the inputs change. Its history (three past
//! states, two past derivatives, p_n - c_n) is part of the caller's state (`memory`), the
//! current derivative is `fsal`, so a restored state continues bit for bit.

use super::integrator::{Counters, Failure};

/// Milne's error estimate, in units of the tolerance, above which the fixed step is refused.
pub const UNSTABLE: f64 = 1e3;

/// Workspace of the fixed-step method.
#[derive(Debug, Clone)]
pub struct MilneHamming {
    n: usize,
    pub max_step: f64,
    atol: Vec<f64>,
    rtol: Vec<f64>,
    k: [Vec<f64>; 3],
    ys: Vec<f64>,
    p: Vec<f64>,
    /// Right-hand sides one call may evaluate before it stops with `Failure::OverBudget`.
    pub rhs_budget: u64,
}

/// Memory layout: [h, history count, p - c, y_{n-1}, y_{n-2}, y_{n-3}, f_{n-1}, f_{n-2}].
const HEAD: usize = 2;
const PC: usize = 0;
const Y1: usize = 1;
const Y2: usize = 2;
const Y3: usize = 3;
const F1: usize = 4;
const F2: usize = 5;
const BLOCKS: usize = 6;

const SQ: f64 = std::f64::consts::FRAC_1_SQRT_2;

impl MilneHamming {
    /// `atol`, `rtol`: the per-component error scales of the adaptive methods (length n).
    pub fn new(n: usize, max_step: f64, atol: Vec<f64>, rtol: Vec<f64>) -> MilneHamming {
        assert!(atol.len() == n && rtol.len() == n);
        MilneHamming {
            n,
            max_step,
            atol,
            rtol,
            k: std::array::from_fn(|_| vec![0.0; n]),
            ys: vec![0.0; n],
            p: vec![0.0; n],
            rhs_budget: u64::MAX,
        }
    }

    /// Integrate from `t` to `t_end` with `f(t, y, dy)`; `fsal` = f(t, y) or empty (restart),
    /// `memory` the history (any other length restarts).
    #[allow(clippy::too_many_arguments)]
    pub fn integrate<F: FnMut(f64, &[f64], &mut [f64])>(
        &mut self,
        mut f: F,
        t: &mut f64,
        y: &mut [f64],
        t_end: f64,
        counters: &mut Counters,
        fsal: &mut Vec<f64>,
        memory: &mut Vec<f64>,
    ) -> Result<(), Failure> {
        let n = self.n;
        let span = t_end - *t;
        if span <= 1e-15 * t_end.abs().max(1e-3) {
            *t = t_end;
            return Ok(());
        }
        let steps = (span / self.max_step * (1.0 - 1e-12)).ceil().max(1.0);
        let h = span / steps;
        let len = HEAD + BLOCKS * n;
        if fsal.len() != n || memory.len() != len || (memory[0] - h).abs() > 1e-9 * h {
            // (re)start: Gill steps first
            memory.clear();
            memory.resize(len, 0.0);
            memory[0] = h;
            fsal.clear();
            fsal.resize(n, 0.0);
            f(*t, y, fsal);
            counters.rhs += 1;
        }
        let t0 = *t;
        let rhs_at_start = counters.rhs;
        for step in 0..steps as u64 {
            let have = memory[1] as usize;
            // a Gill step takes 4 right-hand sides, a Milne-Hamming step 2
            if counters.rhs - rhs_at_start + 4 > self.rhs_budget {
                return Err(Failure::OverBudget { t: *t, h });
            }
            let ts = t0 + step as f64 * h;
            let estimate = if have < 3 {
                self.gill(&mut f, ts, y, h, fsal, memory, counters);
                0.0
            } else {
                self.milne_hamming(&mut f, ts, y, h, fsal, memory, counters)
            };
            counters.steps += 1;
            *t = if step + 1 == steps as u64 {
                t_end
            } else {
                t0 + (step + 1) as f64 * h
            };
            if !(y.iter().all(|v| v.is_finite()) && fsal.iter().all(|v| v.is_finite())) {
                memory.clear();
                return Err(Failure::NotFinite { t: *t });
            }
            if estimate > UNSTABLE {
                memory.clear();
                return Err(Failure::FixedStepTooLong { t: *t, h, estimate });
            }
        }
        Ok(())
    }

    /// Shift the history: y_{n-3} <- y_{n-2} <- y_{n-1} <- y, f_{n-2} <- f_{n-1} <- f.
    fn push(n: usize, memory: &mut [f64], y: &[f64], f: &[f64]) {
        let at = |b: usize| HEAD + b * n;
        memory.copy_within(at(Y2)..at(Y2) + n, at(Y3));
        memory.copy_within(at(Y1)..at(Y1) + n, at(Y2));
        memory[at(Y1)..at(Y1) + n].copy_from_slice(y);
        memory.copy_within(at(F1)..at(F1) + n, at(F2));
        memory[at(F1)..at(F1) + n].copy_from_slice(f);
    }

    fn gill<F: FnMut(f64, &[f64], &mut [f64])>(
        &mut self,
        f: &mut F,
        t: f64,
        y: &mut [f64],
        h: f64,
        fsal: &mut [f64],
        memory: &mut [f64],
        counters: &mut Counters,
    ) {
        Self::push(self.n, memory, y, fsal);
        let k1 = &*fsal;
        let [k2, k3, k4] = &mut self.k;
        let ys = &mut self.ys;
        for i in 0..self.n {
            ys[i] = y[i] + 0.5 * h * k1[i];
        }
        f(t + 0.5 * h, ys, k2);
        for i in 0..self.n {
            ys[i] = y[i] + h * ((SQ - 0.5) * k1[i] + (1.0 - SQ) * k2[i]);
        }
        f(t + 0.5 * h, ys, k3);
        for i in 0..self.n {
            ys[i] = y[i] + h * (-SQ * k2[i] + (1.0 + SQ) * k3[i]);
        }
        f(t + h, ys, k4);
        for i in 0..self.n {
            y[i] += h / 6.0 * (k1[i] + 2.0 * (1.0 - SQ) * k2[i] + 2.0 * (1.0 + SQ) * k3[i] + k4[i]);
        }
        f(t + h, y, fsal);
        counters.rhs += 4;
        memory[1] += 1.0;
    }

    fn milne_hamming<F: FnMut(f64, &[f64], &mut [f64])>(
        &mut self,
        f: &mut F,
        t: f64,
        y: &mut [f64],
        h: f64,
        fsal: &mut [f64],
        memory: &mut [f64],
        counters: &mut Counters,
    ) -> f64 {
        let n = self.n;
        let at = |b: usize| HEAD + b * n;
        let p = &mut self.p;
        let m = &mut self.ys;
        {
            let (fn0, pc) = (&*fsal, &memory[at(PC)..at(PC) + n]);
            let (y3, f1, f2) = (
                &memory[at(Y3)..at(Y3) + n],
                &memory[at(F1)..at(F1) + n],
                &memory[at(F2)..at(F2) + n],
            );
            for i in 0..n {
                p[i] = y3[i] + 4.0 * h / 3.0 * (2.0 * fn0[i] - f1[i] + 2.0 * f2[i]);
                m[i] = p[i] - 112.0 / 121.0 * pc[i];
            }
        }
        let [fm, c, _] = &mut self.k;
        f(t + h, m, fm);
        // corrector and final modifier; the history moves by one
        {
            let (fn0, y2, f1) = (&*fsal, &memory[at(Y2)..at(Y2) + n], &memory[at(F1)..at(F1) + n]);
            for i in 0..n {
                c[i] = (9.0 * y[i] - y2[i]) / 8.0 + 3.0 * h / 8.0 * (fm[i] + 2.0 * fn0[i] - f1[i]);
            }
        }
        Self::push(self.n, memory, y, fsal);
        let mut sum = 0.0;
        for i in 0..n {
            let y_old = y[i];
            memory[at(PC) + i] = p[i] - c[i];
            y[i] = c[i] + 9.0 / 121.0 * (p[i] - c[i]);
            let scale = self.atol[i] + self.rtol[i] * y_old.abs().max(y[i].abs());
            let e = 9.0 / 121.0 * (p[i] - c[i]) / scale;
            sum += e * e;
        }
        f(t + h, y, fsal);
        counters.rhs += 2;
        // the RMS norm; NaN (a diverged corrector) counts as unstable
        let norm = (sum / n as f64).sqrt();
        if norm.is_nan() {
            f64::INFINITY
        } else {
            norm
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(h: f64) -> (f64, Counters) {
        // harmonic oscillator y'' = -w^2 y, communication interval 0.1
        let w = 3.0;
        let mut ig = MilneHamming::new(2, h, vec![1e-6; 2], vec![1e-6; 2]);
        let mut y = [1.0, 0.0];
        let mut t = 0.0;
        let mut c = Counters::default();
        let (mut fsal, mut mem) = (Vec::new(), Vec::new());
        for k in 1..=20 {
            ig.integrate(
                |_t: f64, y: &[f64], d: &mut [f64]| {
                    d[0] = y[1];
                    d[1] = -w * w * y[0];
                },
                &mut t,
                &mut y,
                k as f64 * 0.1,
                &mut c,
                &mut fsal,
                &mut mem,
            )
            .unwrap();
        }
        ((y[0] - (w * 2.0_f64).cos()).abs(), c)
    }

    #[test]
    fn fourth_order_convergence_and_two_evaluations_per_step() {
        let (e1, c1) = run(0.01);
        let (e2, c2) = run(0.005);
        let order = (e1 / e2).log2();
        assert!((3.5..5.5).contains(&order), "order {order}: {e1} {e2}");
        // 3 Gill steps (4 rhs each) once, then 2 per step, + the first derivative
        assert_eq!(c1.steps, 200);
        assert_eq!(c1.rhs, 1 + 3 * 4 + 197 * 2);
        assert_eq!(c2.steps, 400);
    }

    /// y' = -lambda y with h lambda = 1: beyond the stability interval of Milne-Hamming (about
    /// 0.69); the solution decays, the method's oscillates and grows. The error estimate must
    /// stop it with a message long before overflow, while a stable step passes.
    #[test]
    fn an_unstable_fixed_step_is_refused_before_the_state_overflows() {
        let lambda = 1e4;
        let run = |h: f64| {
            let mut ig = MilneHamming::new(1, h, vec![1e-9], vec![1e-6]);
            let (mut t, mut y) = (0.0, [1.0]);
            let (mut fsal, mut mem) = (Vec::new(), Vec::new());
            let mut c = Counters::default();
            ig.integrate(
                |_t: f64, y: &[f64], d: &mut [f64]| d[0] = -lambda * y[0],
                &mut t,
                &mut y,
                0.05,
                &mut c,
                &mut fsal,
                &mut mem,
            )
            .map(|_| y[0])
        };
        let stable = run(1e-6).expect("h lambda = 0.01 is stable and accurate");
        assert!((stable - (-lambda * 0.05_f64).exp()).abs() < 1e-9);
        match run(1e-4) {
            Err(Failure::FixedStepTooLong { t, h, estimate }) => {
                assert!(estimate > UNSTABLE && h == 1e-4 && t < 0.05, "{t} {h} {estimate}");
            }
            other => panic!("expected FixedStepTooLong, got {other:?}"),
        }
    }
}
