//! Inputs ramped over the communication step (FMI 2.0 input interpolation of order 1:
//! `Simulation::set_real_derivative`, `fmi2SetRealInputDerivatives`). A ramp is the input a
//! master means when its signal is continuous: the solution then no longer depends on the
//! communication step, and the implicit integrator is spared the ring every held jump
//! excites.

mod common;

use std::f64::consts::TAU;
use trb::bearing::Bearing;
use trb::simulation::{AccessError, Simulation};
use trb::variables as var;

/// Friction torque, mean skew and cone.x every 1 ms of the settled [W25] case while Fx
/// follows `fx(t)`, communicated every `h`: held at each point, or ramped along the secant to
/// the next. With the right-hand sides spent.
fn load_history(integrator: i32, tol: f64, h: f64, ramped: bool, fx: impl Fn(f64) -> f64) -> (Vec<[f64; 3]>, i32) {
    let mut s = common::dynamic_element(integrator, tol, 0.0);
    let per_ms = (1e-3 / h).round() as usize;
    let mut out = Vec::new();
    for k in 0..10 * per_ms {
        let (t, t_next) = (k as f64 * h, (k + 1) as f64 * h);
        s.set_real(var::FX, fx(t)).unwrap();
        if ramped {
            s.set_real_derivative(var::FX, (fx(t_next) - fx(t)) / h).unwrap();
        }
        s.do_step(t, h).unwrap();
        if (k + 1) % per_ms == 0 {
            let o = s.last_outputs();
            out.push([o.friction_torque, o.skew_mean, o.cone_x]);
        }
    }
    (out, s.last_outputs().integrator_rhs)
}

/// Largest difference of each output between two histories, relative to its largest value.
fn worst(a: &[[f64; 3]], b: &[[f64; 3]]) -> [f64; 3] {
    std::array::from_fn(|k| {
        let scale = b.iter().fold(0.0_f64, |m, v| m.max(v[k].abs()));
        a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x[k] - y[k]).abs())) / scale
    })
}

/// The axial load rises linearly by 10 % in 10 ms. Ramped, the communication step no longer
/// matters: 1 ms steps give what 0.25 ms steps give, to the integration tolerance. Held, the
/// 1 ms staircase is another input, and its solution is off by much more.
#[test]
fn a_ramped_load_gives_the_same_solution_at_any_communication_step() {
    let fx = |t: f64| 30e3 * (1.0 + 10.0 * t);
    let (fine, _) = load_history(2, 1e-7, 0.25e-3, true, fx);
    let (ramped, _) = load_history(2, 1e-7, 1e-3, true, fx);
    let (held, _) = load_history(2, 1e-7, 1e-3, false, fx);
    let (d_ramped, d_held) = (worst(&ramped, &fine), worst(&held, &fine));
    eprintln!("against 0.25 ms ramped steps: 1 ms ramped {d_ramped:?}, 1 ms held {d_held:?}");
    for k in 0..3 {
        assert!(d_ramped[k] < 1e-6, "output {k}: ramped 1 ms steps differ by {:.1e}", d_ramped[k]);
        assert!(
            d_ramped[k] < 1e-3 * d_held[k],
            "output {k}: ramped {:.1e}, held {:.1e}",
            d_ramped[k],
            d_held[k]
        );
    }
}

/// The co-simulation case of `tests/integrators.rs` (Fx ± 1 % at 50 Hz, 1 ms steps,
/// tolerance 1e-6) with the master's input derivatives. Held, each jump rings the cone on its
/// contacts (2.9 kHz, ±1.3e-7 m), which Rosenbrock-W resolves dearer than Dormand–Prince.
/// Ramped, only the kinks of the secants excite it, some 60 times less; Rosenbrock-W needs a
/// quarter of its right-hand sides and fewer than Dormand–Prince (measured: 4.8k against
/// 20.6k held, Dormand–Prince 5.9k), the automatic integrator keeps it, and the solution is
/// the explicit method's.
#[test]
fn ramped_inputs_spare_rosenbrock_w_the_ring_of_held_jumps() {
    let fx = |t: f64| 30e3 * (1.0 + 0.01 * (TAU * 50.0 * t).sin());
    let (held, held_rhs) = load_history(2, 1e-6, 1e-3, false, fx);
    let (implicit, implicit_rhs) = load_history(2, 1e-6, 1e-3, true, fx);
    let (automatic, automatic_rhs) = load_history(3, 1e-6, 1e-3, true, fx);
    let (explicit, explicit_rhs) = load_history(0, 1e-6, 1e-3, true, fx);
    eprintln!(
        "10 ms, right-hand sides: Rosenbrock-W held {held_rhs}, ramped {implicit_rhs}; automatic ramped {automatic_rhs}; Dormand-Prince ramped {explicit_rhs}"
    );
    assert!(3 * implicit_rhs < held_rhs, "ramped {implicit_rhs} against held {held_rhs}");
    assert!(
        implicit_rhs < explicit_rhs,
        "Rosenbrock-W {implicit_rhs} against Dormand-Prince {explicit_rhs}"
    );
    assert!(
        (automatic_rhs as f64) <= 1.1 * implicit_rhs as f64,
        "automatic {automatic_rhs} against Rosenbrock-W {implicit_rhs}"
    );
    for (name, d) in [
        ("Rosenbrock-W", worst(&implicit, &explicit)),
        ("automatic", worst(&automatic, &explicit)),
    ] {
        assert!(d.iter().all(|&e| e < 1e-4), "{name} against Dormand-Prince: {d:?}");
    }
    // ramped and held are different inputs: their solutions differ visibly
    assert!(worst(&held, &implicit).iter().any(|&e| e > 1e-4));
}

/// At fidelity 0 the cage turns with the ring speeds, which it follows linearly: over a speed
/// ramp it turns by the mean of its speeds at the two ends. The inputs reach their ramped
/// values at the step's end, and the rates apply to that step only.
#[test]
fn a_quasi_static_cage_turns_by_the_mean_speed_of_a_ramp() {
    let mut s = Simulation::new(Bearing::preset("TRB130x230-W25").unwrap());
    s.set_real(var::SPEED, 100.0).unwrap();
    s.initialize(0.0).unwrap();
    let azimuth = |s: &mut Simulation| s.get_real(var::ROLLER_AZIMUTH).unwrap();
    let cage = |s: &mut Simulation| s.get_real(var::CAGE_SPEED).unwrap();
    let (a0, w0) = (azimuth(&mut s), cage(&mut s));
    let h = 1e-3;
    s.set_real_derivative(var::SPEED, 5e4).unwrap(); // 100 -> 150 rad/s
    s.do_step(0.0, h).unwrap();
    assert_eq!(s.get_real(var::SPEED).unwrap(), 150.0);
    let (a1, w1) = (azimuth(&mut s), cage(&mut s));
    assert!((w1 / w0 - 1.5).abs() < 1e-12, "cage speed {w0} -> {w1}");
    let turned = (a1 - a0).rem_euclid(TAU);
    assert!((turned - 0.5 * (w0 + w1) * h).abs() < 1e-12 * turned, "turned {turned}");
    // the next step holds the speed
    s.do_step(h, h).unwrap();
    assert_eq!(s.get_real(var::SPEED).unwrap(), 150.0);
    let turned = (azimuth(&mut s) - a1).rem_euclid(TAU);
    assert!((turned - w1 * h).abs() < 1e-12 * turned);
}

/// Pending rates are part of the state: a state saved with them set replays the ramped step
/// bit for bit, also in another element.
#[test]
fn input_rates_are_part_of_the_state() {
    let mut s = common::dynamic_element(3, 1e-6, 0.0);
    s.do_step(0.0, 1e-3).unwrap();
    s.set_real_derivative(var::FX, 3e5).unwrap();
    s.set_real_derivative(var::SPEED, 100.0).unwrap();
    let saved = s.serialize_state();
    s.do_step(1e-3, 1e-3).unwrap();
    let first = s.last_outputs().clone();
    assert_eq!(s.get_real(var::FX).unwrap(), 30e3 + 300.0);
    let mut other = common::dynamic_element(3, 1e-6, 0.0);
    for element in [&mut s, &mut other] {
        element.deserialize_state(&saved).unwrap();
        assert_eq!(element.input_rates().fx, 3e5);
        element.do_step(1e-3, 1e-3).unwrap();
        assert_eq!(element.last_outputs().friction_torque.to_bits(), first.friction_torque.to_bits());
        assert_eq!(element.last_outputs().skew_mean.to_bits(), first.skew_mean.to_bits());
        assert_eq!(element.last_outputs().integrator_rhs, first.integrator_rhs);
    }
}

/// Derivatives only of Real inputs, finite; a ramp that leaves the model's range is refused
/// before the step, naming the input, and the element is unchanged.
#[test]
fn bad_input_rates_are_refused_with_a_reason() {
    let mut s = Simulation::new(Bearing::preset("TRB130x230-W25").unwrap());
    s.initialize(0.0).unwrap();
    for (vr, rate) in [
        (var::TOLERANCE, 1.0),
        (var::FRICTION_TORQUE, 1.0),
        (var::FX, f64::NAN),
        (var::FY, f64::INFINITY),
    ] {
        match s.set_real_derivative(vr, rate) {
            Err(AccessError::BadValue { message, .. }) => eprintln!("{message}"),
            other => panic!("value reference {vr}, rate {rate}: {other:?}"),
        }
    }
    assert!(matches!(s.set_real_derivative(999_999, 1.0), Err(AccessError::UnknownReference(_))));
    let before = s.serialize_state();
    s.set_real_derivative(var::OIL_TEMPERATURE, -1e9).unwrap();
    let e = s.do_step(0.0, 1e-3).expect_err("the oil temperature ramps far below its range");
    assert!(e.to_string().contains("oilTemperature"), "{e}");
    s.set_real_derivative(var::OIL_TEMPERATURE, 0.0).unwrap();
    s.do_step(0.0, 1e-3).unwrap();
    let mut fresh = Simulation::new(Bearing::preset("TRB130x230-W25").unwrap());
    fresh.deserialize_state(&before).unwrap();
    fresh.do_step(0.0, 1e-3).unwrap();
    assert_eq!(
        fresh.last_outputs().friction_torque.to_bits(),
        s.last_outputs().friction_torque.to_bits()
    );
}
