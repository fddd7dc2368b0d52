//! A minute of duty in CI: the fidelity-0 duty cycle of `trb soak` (`src/cli/soak/duty.rs`)
//! for 60 simulated seconds in 1 ms steps, three cycles of speed, axial and radial load steps
//! and ramps. Every step succeeds with finite outputs, resident memory does not grow after
//! the first ten seconds, and the second and third cycles give the first cycle's outputs
//! where the load is axisymmetric (under radial load they hang on where the rollers stand).
//! And a second of the fidelity-2 run of `trb soak`: its energy books close within 1 %.
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

#[test]
fn a_second_at_fidelity_2_keeps_its_energy_books() {
    // the default bearing at 3500 rpm, Fa 30 kN, Fy 10 kN in 1 ms steps: what drives the cone
    // is dissipated in the contacts or stored in the rollers' and cage's motion
    let r = duty::fidelity_2(1.0);
    let open = r.shaft_work - r.dissipated - r.kinetic_change + r.load_work;
    eprintln!(
        "{} steps in {:.2} s; shaft {:.3} J, dissipated {:.3} J, kinetic {:+.3e} J, loads {:+.3e} J: residual {:.2e} of the dissipation; resident memory growth {} kB",
        r.steps,
        r.wall,
        r.shaft_work,
        r.dissipated,
        r.kinetic_change,
        r.load_work,
        r.energy_residual(),
        r.memory_growth() / 1024
    );
    assert!(r.failure.is_none(), "{:?}", r.failure);
    assert_eq!(r.steps, 1000);
    // about 20 N m at 366.5 rad/s: kilojoules in the second, not a bookkeeping of zeros
    assert!(r.dissipated > 1e3 && r.shaft_work > 1e3, "{} J, {} J", r.dissipated, r.shaft_work);
    assert!(
        open.abs() < 0.01 * r.dissipated,
        "the books open by {open:.3} J of {:.3} J dissipated",
        r.dissipated
    );
    assert!(r.torque_last > 0.0 && r.torque_last.is_finite());
}
