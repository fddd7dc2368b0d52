//! The quasi-static friction with a shaft speed that changes: a speed held
//! since the last solve reads the friction laws from the per-speed tables, a speed that
//! changes takes the laws themselves (four slices at a time), which a table rebuilt every step
//! would cost many times over. Which one a step takes is decided from the warm start (the last
//! solve's speeds), part of the FMU state, so a restored state replays bit for bit; and both
//! give the same friction to the tables' accuracy.

use trb::bearing::Bearing;
use trb::simulation::Simulation;
use trb::variables as var;

const H: f64 = 1e-3;

fn element(preset: &str, fy: f64) -> Simulation {
    let mut s = Simulation::new(Bearing::preset(preset).unwrap());
    s.set_integer(var::FIDELITY, 0).unwrap();
    s.set_real(var::FY, fy).unwrap();
    s.initialize(0.0).unwrap();
    s
}

/// Step k: the speed follows (1 + 0.2 sin(2 pi t / 0.1 s)) in steps 0-9 and 20-29 of every
/// 40 and is held in between; the friction outputs after it.
fn step(s: &mut Simulation, speed0: f64, k: usize) -> Vec<f64> {
    let t = k as f64 * H;
    let moving = (k % 40) < 10 || (20..30).contains(&(k % 40));
    if moving {
        s.set_real(var::SPEED, speed0 * (1.0 + 0.2 * libm::sin(std::f64::consts::TAU * (t + H) / 0.1)))
            .unwrap();
    }
    s.do_step(t, H).unwrap();
    let o = s.last_outputs();
    let mut v = vec![o.friction_torque, o.friction_torque_cone, o.friction_torque_cup, o.power_loss];
    v.extend(o.nis.iter().chain(&o.nos).chain(&o.nfs).chain(&o.sliding_friction));
    v
}

#[test]
fn friction_replays_bit_for_bit_through_speed_changes() {
    for (preset, fy) in [("TRB130x230", 10e3), ("32008", 5e3)] {
        let mut a = element(preset, fy);
        let speed0 = a.inputs().speed;
        for k in 0..15 {
            step(&mut a, speed0, k);
        }
        let bytes = a.serialize_state();
        let run = |s: &mut Simulation| -> Vec<u64> { (15..45).flat_map(|k| step(s, speed0, k)).map(f64::to_bits).collect() };
        let reference = run(&mut a);
        let mut b = element(preset, fy);
        b.deserialize_state(&bytes).unwrap();
        assert_eq!(run(&mut b), reference, "{preset}: a fresh instance from the state");
        a.deserialize_state(&bytes).unwrap();
        assert_eq!(run(&mut a), reference, "{preset}: the same instance");
    }
}

/// A step whose speed changed (the laws) and the next step at the same speed (the table),
/// under pure axial load (every roller in the same state, whatever the cage's position: the
/// same equilibrium in both steps), give the same friction to the table's accuracy (traction
/// coefficient within about 1e-6, docs/performance.md): the friction torque within 1e-5.
#[test]
fn laws_and_table_agree_at_the_same_speed() {
    for preset in ["TRB130x230", "32008"] {
        let mut s = element(preset, 0.0);
        let speed0 = s.inputs().speed;
        s.do_step(0.0, H).unwrap();
        s.set_real(var::SPEED, 1.1 * speed0).unwrap();
        s.do_step(H, H).unwrap();
        let laws = s.last_outputs().clone();
        s.do_step(2.0 * H, H).unwrap();
        let table = s.last_outputs().clone();
        assert_eq!(laws.cone_x.to_bits(), table.cone_x.to_bits(), "{preset}: the same equilibrium");
        let rel = (table.friction_torque / laws.friction_torque - 1.0).abs();
        eprintln!(
            "{preset}: friction torque {:.9} N m (laws) vs {:.9} N m (table): {rel:.1e}",
            laws.friction_torque, table.friction_torque
        );
        assert!(rel < 1e-5, "{preset}: {rel:.1e}");
        assert!(rel > 0.0, "{preset}: the second step did not read the table");
    }
}

/// Held inputs from the start read the table from the first solve on: under pure axial load
/// (every step the same equilibrium) the friction torque is the same at every step, the
/// initial solve's included (a first solve counts as a held speed).
#[test]
fn a_held_speed_reads_the_table_from_the_first_solve() {
    for preset in ["TRB130x230", "32008"] {
        let mut s = element(preset, 0.0);
        let first = s.last_outputs().friction_torque;
        for k in 0..5 {
            s.do_step(k as f64 * H, H).unwrap();
            assert_eq!(s.last_outputs().friction_torque.to_bits(), first.to_bits(), "{preset}, step {k}");
        }
    }
}
