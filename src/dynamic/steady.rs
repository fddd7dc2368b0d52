//! Steady running in the cage's frame: the dynamic model's own equilibrium as its start.
//!
//! The quasi-static solution seats the rollers with the contact forces alone: no skew, the
//! epicyclic speeds of pure rolling, no traction or drag. Started there, the dynamic model
//! rings for about 0.1 s (the [W25] case: skew 0 → 6.8e-5 rad at ~500 Hz, decaying at 85 1/s;
//! the friction torque 13.5 → 36.5 N m), a start-up transient of the initial state, not of the
//! bearing. [W25] integrates through it and reports the running state after it (0.43–0.46 s).
//!
//! Here every body is instead put where it runs steadily with the rings' speeds and loads,
//! seen from the cage: each roller holds its place in its pocket (its orbit rate equals the
//! cage's), and every acceleration and attitude rate vanishes, with the roller forces the
//! full dynamic model computes (traction, drag, gyroscopic moments). Unknowns: all states but
//! the cage angle (held: the frame's gauge); equations: the right-hand side f(y) = 0, except
//! that each roller's azimuth rate equals the cage's instead of vanishing, and the cage angle
//! stays. With a pure axial load on an aligned bearing this is the exact steady state, which
//! a start from it keeps. With radial loads or misalignment the running state is periodic in
//! the orbit; the frozen-azimuth solution of these equations was tried as a start there and
//! shortened nothing (combined load: 498 Rosenbrock-W steps in 20 ms against 291 from the
//! seat), so those cases start at the seat (`Dynamic::runs_steadily`).
//!
//! Solved by Newton's method with the block Jacobian of the implicit integrator
//! (`jacobian.rs`, finite differences, rows of the two changed equations replaced) and a
//! damped step (natural monotonicity test, Deuflhard 2004: the next Newton correction,
//! computed with the same factors, must shrink).

use super::jacobian::{BlockJacobian, BlockLu, BlockSystem, M};
use super::CAGE;

/// Newton iterations at most.
const MAX_ITERATIONS: u32 = 30;
/// Converged when no state moves by more than this fraction of its reference scale (the
/// integrators' tolerance scales: 10 µm for positions, their angles and speeds).
const CONVERGED: f64 = 1e-6;

/// Why the steady state was not found.
#[derive(Debug, Clone, PartialEq)]
pub enum NoSteadyState {
    /// The damped Newton step stalled (the largest scaled correction when it did).
    Stalled { iterations: u32, correction: f64 },
    /// The Jacobian was singular or the state left the model's range.
    Singular { iterations: u32 },
}

/// Work space of the solve.
pub struct SteadySolver {
    z: usize,
    ng: usize,
    jac: BlockJacobian,
    lu: BlockLu,
    r: Vec<f64>,
    delta: Vec<f64>,
    trial: Vec<f64>,
    work: Vec<f64>,
    shares: Vec<f64>,
}

impl SteadySolver {
    /// For `z` rollers and `ng` global states.
    pub fn new(z: usize, ng: usize) -> SteadySolver {
        let n = ng + M * z;
        SteadySolver {
            z,
            ng,
            jac: BlockJacobian::zeros(z, ng),
            lu: BlockLu::new(z, ng),
            r: vec![0.0; n],
            delta: vec![0.0; n],
            trial: vec![0.0; n],
            work: vec![0.0; 3 * n],
            shares: vec![0.0; 2 * z * ng],
        }
    }

    /// Move `y` to the steady running state. `scale`: the reference magnitude of each state,
    /// which the convergence test measures the corrections in; `perturbation`: the floors of
    /// the finite differences' perturbations; `active`: the global states that move (the
    /// others, prescribed, stay). Returns the Newton iterations taken and the number of
    /// right-hand sides evaluated.
    pub fn solve(
        &mut self,
        sys: &mut impl BlockSystem,
        y: &mut [f64],
        scale: &[f64],
        perturbation: &[f64],
        active: &[bool],
    ) -> Result<(u32, u64), NoSteadyState> {
        let cage_angle = y[CAGE + 2];
        let mut rhs = 0u64;
        for it in 0..MAX_ITERATIONS {
            rhs += self
                .jac
                .compute(sys, 0.0, y, perturbation, active, &mut self.work, &mut self.shares);
            self.steady_rows(active);
            if !self.lu.factor(&self.jac, 0.0) {
                return Err(NoSteadyState::Singular { iterations: it });
            }
            residual(sys, y, active, cage_angle, self.z, &mut self.delta);
            rhs += 1;
            // (0 I - J) delta = R is Newton's J delta = -R
            self.lu.solve(&mut self.delta);
            let size = scaled_max(&self.delta, scale);
            if !size.is_finite() {
                return Err(NoSteadyState::Singular { iterations: it });
            }
            if size <= CONVERGED {
                apply(y, &self.delta, 1.0);
                return Ok((it + 1, rhs));
            }
            let mut lambda = 1.0;
            loop {
                self.trial.copy_from_slice(y);
                apply(&mut self.trial, &self.delta, lambda);
                residual(sys, &self.trial, active, cage_angle, self.z, &mut self.r);
                rhs += 1;
                self.lu.solve(&mut self.r);
                let next = scaled_max(&self.r, scale);
                if next.is_finite() && next <= (1.0 - 0.25 * lambda) * size {
                    y.copy_from_slice(&self.trial);
                    break;
                }
                // down to 1/1024: at 1/64 the [W25] case at 39 kN stalled in its third
                // iteration at tolerance 1e-6 (tests/steady_start.rs)
                lambda *= 0.5;
                if lambda < 1.0 / 1024.0 {
                    return Err(NoSteadyState::Stalled {
                        iterations: it + 1,
                        correction: size,
                    });
                }
            }
        }
        Err(NoSteadyState::Stalled {
            iterations: MAX_ITERATIONS,
            correction: f64::NAN,
        })
    }

    /// Replace the rows of the finite-difference Jacobian of f by those of the steady
    /// equations: each roller's azimuth rate minus the cage's, the cage angle itself, and
    /// the identity for the prescribed global states.
    fn steady_rows(&mut self, active: &[bool]) {
        let ng = self.ng;
        let jac = &mut self.jac;
        for j in 0..self.z {
            jac.r[j * M * ng + 2 * ng + CAGE + 5] -= 1.0;
        }
        for k in 0..ng {
            if k == CAGE + 2 || !active[k] {
                for c in 0..ng {
                    jac.g[k * ng + c] = if c == k { 1.0 } else { 0.0 };
                }
                for j in 0..self.z {
                    jac.l[j * ng * M + k * M..j * ng * M + (k + 1) * M].fill(0.0);
                }
            }
        }
    }
}

/// The steady equations at `y`: f(y), with each roller's azimuth rate taken relative to the
/// cage's, the cage angle's departure from `cage_angle`, and zero for prescribed states.
fn residual(sys: &mut impl BlockSystem, y: &[f64], active: &[bool], cage_angle: f64, z: usize, out: &mut [f64]) {
    let ng = active.len();
    sys.rhs(0.0, y, out);
    for (k, a) in active.iter().enumerate() {
        if !a {
            out[k] = 0.0;
        }
    }
    out[CAGE + 2] = y[CAGE + 2] - cage_angle;
    for j in 0..z {
        out[ng + M * j + 2] -= y[CAGE + 5];
    }
}

fn apply(y: &mut [f64], delta: &[f64], lambda: f64) {
    for (v, d) in y.iter_mut().zip(delta) {
        *v += lambda * d;
    }
}

fn scaled_max(v: &[f64], scale: &[f64]) -> f64 {
    let mut m: f64 = 0.0;
    for (d, s) in v.iter().zip(scale) {
        let r = (d / s).abs();
        if !r.is_finite() {
            return f64::INFINITY;
        }
        m = m.max(r);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::super::jacobian::NG;
    use super::*;

    /// Rollers held by springs and dampers, with one spin component driven by 1 - w^2 - brake:
    /// steady at w = 1 without the brake; with a brake above 1, f never vanishes.
    struct Braked {
        z: usize,
        brake: f64,
    }

    impl BlockSystem for Braked {
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy.fill(0.0);
            dy[CAGE + 2] = y[CAGE + 5];
            for j in 0..self.z {
                let o = NG + M * j;
                dy[o + 2] = y[o + 5];
                // a stiff spring on the roller's azimuth relative to the cage (the pocket) and
                // on every other state, and the brake on the spin
                dy[o + 5] = -1e4 * (y[o + 2] - y[CAGE + 2]) - (y[o + 5] - y[CAGE + 5]);
                for k in [0, 1, 3, 4, 6, 7, 9, 10] {
                    dy[o + k] = -y[o + k];
                }
                dy[o + 8] = 1.0 - y[o + 8] * y[o + 8] - self.brake;
            }
            dy[CAGE + 5] = -y[CAGE + 5] + 1.0;
        }
        fn shares(&self, out: &mut [f64]) {
            out.fill(0.0);
        }
    }

    fn solve(brake: f64) -> (Vec<f64>, Result<(u32, u64), NoSteadyState>) {
        let z = 3;
        let n = NG + M * z;
        let mut y = vec![0.1; n];
        y[CAGE + 2] = 0.0;
        let mut active = [false; NG];
        active[CAGE + 2] = true;
        active[CAGE + 5] = true;
        let scale = vec![1.0; n];
        let r = SteadySolver::new(z, NG).solve(&mut Braked { z, brake }, &mut y, &scale, &scale, &active);
        (y, r)
    }

    #[test]
    fn finds_the_steady_state_of_a_system_that_has_one() {
        let (y, r) = solve(0.0);
        let (iterations, _) = r.unwrap();
        assert!(iterations <= 12, "{iterations}");
        // the cage runs at 1, every roller in its pocket at the cage's speed, its spin at 1
        assert!((y[CAGE + 5] - 1.0).abs() < 1e-9 && y[CAGE + 2] == 0.0);
        for j in 0..3 {
            let o = NG + M * j;
            let yj = &y[o..o + M];
            assert!(
                (yj[5] - 1.0).abs() < 1e-9 && yj[2].abs() < 1e-9 && (yj[8] - 1.0).abs() < 1e-9,
                "{yj:?}"
            );
        }
    }

    #[test]
    fn says_so_when_there_is_none() {
        let (_, r) = solve(2.0);
        assert!(r.is_err(), "{r:?}");
    }
}
