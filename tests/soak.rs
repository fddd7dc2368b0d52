//! A minute of duty in CI: the fidelity-0 duty cycle of `trb soak` (`src/cli/soak/duty.rs`)
//! for 60 simulated seconds in 1 ms steps, three cycles of speed, axial and radial load steps
//! and ramps. Every step succeeds with finite outputs, resident memory does not grow after
//! the first ten seconds, and the second and third cycles give the first cycle's outputs
//! where the load is axisymmetric (under radial load they hang on where the rollers stand).
#![cfg(target_os = "linux")]

#[allow(dead_code)]
#[path = "../src/cli/soak/duty.rs"]
mod duty;

#[test]
fn a_minute_of_duty_cycles_keeps_memory_and_repeats() {
    let r = duty::fidelity_0(60.0);
    eprintln!(
        "{} steps in {:.2} s; resident memory {} kB, growth {} kB; cycles differ by {:.2e} over {} points",
        r.steps,
        r.wall,
        r.rss_end / 1024,
        r.memory_growth() / 1024,
        r.repeat_error,
        r.repeat_points
    );
    assert!(r.failure.is_none(), "{:?}", r.failure);
    assert_eq!(r.steps, 60_000);
    assert!(
        r.rss_early > 0 && r.memory_growth() < 1 << 20,
        "memory grew by {} bytes",
        r.memory_growth()
    );
    assert!(
        r.repeat_points >= 80,
        "two later cycles, every 0.1 s where the load is axisymmetric: {}",
        r.repeat_points
    );
    assert!(r.repeat_error <= 1e-9, "a later cycle differs by {}", r.repeat_error);
}
