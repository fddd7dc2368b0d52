//! Automatic choice between the explicit and the linearly implicit integrator (`integrator`
//! = 3), one communication interval at a time, by their cost per simulated second.
//!
//! Neither method is the cheaper one everywhere (`docs/performance.md`):
//! - Rosenbrock-W (`rosenbrock.rs`) damps the rollers' 40 kHz contact vibration instead of
//!   resolving it and follows the slow motion with millisecond steps: 100x cheaper than
//!   Dormand–Prince in steady running ([W25] case, 0.5 s: 0.47 s against 48 s).
//! - Where inputs jump at every communication point (a co-simulation master's held loads), the
//!   jumps ring the cone on its contacts (2.9 kHz, decaying at about 200 1/s: a physical mode,
//!   visible at the communication points). Both methods must resolve it; Dormand–Prince, of
//!   order 5 and at its stability step anyway, does it cheaper than the order-3 Rosenbrock-W
//!   (case 6 at tolerance 1e-6: 13k against 45k right-hand sides).
//!
//! This is the stiffness switching of LSODA (Petzold 1983), decided on measured cost instead of
//! a stiffness estimate alone: after each interval the active method's right-hand sides per
//! simulated second (Jacobians included) are compared with the other's. The explicit
//! method's cost is bounded below by its stability: with the spectral radius rho of the
//! Jacobian its step is at most about 2.5 / rho (measured: Dormand–Prince's mean step on the
//! settled [W25] state is 0.99x the stability limit of its fastest eigenvalues, |h lambda| =
//! 2.5), 6 right-hand sides each; the ratio of its measured cost to that bound, kept from the
//! last interval it ran, carries its accuracy limit (the run-up from rest, where its steps
//! are ten times shorter). The implicit method's cost is only known by running it, so after
//! switching away from it, it is tried again after 1, 2, 4, ... 64 intervals while its trials
//! lose (LSODA's retry).
//!
//! The switch's memory is part of the FMU state, so a restored state continues bit for bit.

use super::integrator::StepControl;
use serde::{Deserialize, Serialize};

/// |h rho| at Dormand–Prince's step on the contact modes (see the module comment).
pub const EXPLICIT_STABILITY: f64 = 2.5;
/// Right-hand sides per Dormand–Prince step (7 stages, the first reused).
pub const EXPLICIT_RHS_PER_STEP: f64 = 6.0;
/// The other method must be cheaper by this factor to switch (hysteresis: the costs are
/// measured over one interval each).
pub const MARGIN: f64 = 1.25;
/// Longest wait, in intervals, before the implicit method is tried again.
pub const MAX_WAIT: u32 = 64;

/// The switch's memory.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MethodSwitch {
    /// Rosenbrock-W runs (else Dormand–Prince).
    pub implicit: bool,
    /// The idle method's step-size controller.
    pub parked: StepControl,
    /// Intervals the implicit method has run since it was last chosen.
    pub implicit_run: u32,
    /// Intervals left before the implicit method is tried again.
    pub wait: u32,
    /// Trials of the implicit method lost in a row.
    pub lost: u32,
    /// The explicit method's measured cost over its cost bound from stability (1 until
    /// measured; at least 1).
    pub explicit_factor: f64,
    /// Spectral radius of the last Jacobian (1/s) and the Jacobian count it was taken at.
    pub rho: f64,
    pub rho_jacobians: u64,
}

impl Default for MethodSwitch {
    fn default() -> MethodSwitch {
        MethodSwitch {
            implicit: true,
            parked: StepControl::default(),
            implicit_run: 0,
            wait: 0,
            lost: 0,
            explicit_factor: 1.0,
            rho: f64::NAN,
            rho_jacobians: u64::MAX,
        }
    }
}

impl MethodSwitch {
    /// The explicit method's lowest cost (right-hand sides per simulated second) from the
    /// spectral radius; NaN while unknown.
    pub fn explicit_bound(&self) -> f64 {
        EXPLICIT_RHS_PER_STEP * self.rho / EXPLICIT_STABILITY
    }

    /// The right-hand sides the implicit method may spend on an interval of `dt` seconds:
    /// what the explicit method would cost, with the margin (unlimited while that is unknown).
    /// A trial that runs over is abandoned at once instead of finishing a costly interval.
    pub fn implicit_budget(&self, dt: f64) -> u64 {
        let budget = MARGIN * self.explicit_factor * self.explicit_bound() * dt;
        if budget.is_finite() {
            budget as u64
        } else {
            u64::MAX
        }
    }

    /// After an interval of the active method that cost `rate` right-hand sides per simulated
    /// second: whether to switch for the next one.
    pub fn after_interval(&mut self, rate: f64) -> bool {
        let bound = self.explicit_bound();
        if self.implicit {
            self.implicit_run += 1;
            // unknown bound (NaN): stay
            if rate > MARGIN * self.explicit_factor * bound {
                self.give_up_implicit();
                return true;
            }
            false
        } else {
            if bound.is_finite() && bound > 0.0 && rate.is_finite() {
                self.explicit_factor = (rate / bound).max(1.0);
            }
            self.wait = self.wait.saturating_sub(1);
            self.wait == 0
        }
    }

    /// The implicit method costs more than the explicit one: wait before trying it again,
    /// twice as long as last time if this was a trial (its first interval since chosen).
    pub fn give_up_implicit(&mut self) {
        let trial = self.implicit_run <= 1;
        self.lost = if trial { self.lost + 1 } else { 0 };
        self.wait = (1u32 << self.lost.min(6)).min(MAX_WAIT);
    }

    /// Switch to the other method; `step` is the active controller, swapped with the parked.
    pub fn switch(&mut self, step: &mut StepControl) {
        std::mem::swap(step, &mut self.parked);
        self.implicit = !self.implicit;
        self.implicit_run = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with_rho(rho: f64) -> MethodSwitch {
        MethodSwitch {
            rho,
            rho_jacobians: 0,
            ..MethodSwitch::default()
        }
    }

    #[test]
    fn keeps_the_implicit_method_while_it_is_cheaper() {
        // [W25] steady running: ~4e3 RHS/s against the bound 6 x 2.5e5 / 2.5 = 6e5
        let mut s = with_rho(2.5e5);
        for _ in 0..100 {
            assert!(!s.after_interval(4e3));
        }
        assert!(s.implicit);
    }

    #[test]
    fn leaves_a_costly_implicit_method_and_retries_it_ever_later() {
        let mut s = with_rho(2.5e5);
        let mut step = StepControl::start(1e-3);
        // a long implicit run that became costly: switch, retry after 1 interval
        assert!(!s.after_interval(1e5));
        assert!(s.after_interval(2.3e6));
        s.switch(&mut step);
        assert!(!s.implicit && s.wait == 1 && s.lost == 0);
        // each lost trial doubles the wait, up to MAX_WAIT
        let mut waits = Vec::new();
        for _ in 0..9 {
            let mut explicit_intervals = 0;
            while !s.after_interval(6.5e5) {
                explicit_intervals += 1;
            }
            waits.push(explicit_intervals + 1);
            s.switch(&mut step);
            assert!(s.implicit);
            assert!(s.after_interval(2.3e6), "the trial loses");
            s.switch(&mut step);
        }
        assert_eq!(waits, [1, 2, 4, 8, 16, 32, 64, 64, 64]);
        // the controllers went back and forth with the method: the implicit one is parked
        assert!(!s.implicit);
        assert_eq!(s.parked.h, 1e-3);
    }

    #[test]
    fn the_explicit_methods_measured_cost_corrects_its_bound() {
        // run-up from rest: explicit steps 10x below the stability bound
        let mut s = with_rho(2.5e5);
        let mut step = StepControl::default();
        assert!(s.after_interval(2e6));
        s.switch(&mut step);
        // the first interval counts as a lost trial: the next is due after two
        assert!(!s.after_interval(6e6));
        assert!(s.after_interval(6e6), "trial due");
        assert!((s.explicit_factor - 10.0).abs() < 1e-9, "{}", s.explicit_factor);
        s.switch(&mut step);
        // the implicit method at 2.6e6 is now the cheaper one and stays
        for _ in 0..10 {
            assert!(!s.after_interval(2.6e6));
        }
    }
}
