//! The dynamic model's rollers on a thread pool (`threads`): the same bits
//! as on one thread, for the default integrator and for Rosenbrock-W (whose Jacobian
//! evaluates the right-hand side with perturbed states), under combined load and
//! misalignment and on the lobed cylindrical preset; a state saved with a pool replays.

use trb::bearing::Bearing;
use trb::simulation::Simulation;
use trb::variables::{self as var, Causality, VarType};

/// The bits of every Real output.
fn real_outputs(s: &mut Simulation, rollers: usize) -> Vec<u64> {
    var::expanded(rollers)
        .into_iter()
        .filter(|(_, _, v)| v.ty == VarType::Real && v.causality == Causality::Output)
        .map(|(vr, _, _)| s.get_real(vr).unwrap().to_bits())
        .collect()
}

/// Every Real output after `steps` steps of 0.5 ms at fidelity 1 with `threads` threads.
fn run(preset: &str, integrator: i32, threads: i32, steps: usize) -> Vec<u64> {
    let mut s = Simulation::new(Bearing::preset(preset).unwrap());
    s.set_integer(var::FIDELITY, 1).unwrap();
    s.set_integer(var::INTEGRATOR, integrator).unwrap();
    s.set_integer(var::THREADS, threads).unwrap();
    s.set_real(var::FY, 8e3).unwrap();
    s.set_real(var::XI, 3e-4).unwrap();
    let mut t = 0.0;
    for _ in 0..steps {
        s.do_step(t, 5e-4).unwrap();
        t += 5e-4;
    }
    let z = Bearing::preset(preset).unwrap().roller_count;
    real_outputs(&mut s, z)
}

#[test]
fn two_and_three_threads_give_the_bits_of_one() {
    for (preset, integrator) in [("TRB130x230", 0), ("TRB130x230", 2), ("CRB-TRILOBE", 0)] {
        let one = run(preset, integrator, 1, 6);
        for threads in [2, 3] {
            let many = run(preset, integrator, threads, 6);
            assert_eq!(one.len(), many.len());
            let differing = one.iter().zip(&many).filter(|(a, b)| a != b).count();
            assert_eq!(
                differing, 0,
                "{preset}, integrator {integrator}, {threads} threads: {differing} outputs differ"
            );
        }
    }
}

#[test]
fn a_state_saved_with_two_threads_replays_in_a_fresh_instance() {
    // the thread count is a parameter and travels with the state; the pool is rebuilt
    let mut a = Simulation::new(Bearing::preset("TRB130x230").unwrap());
    a.set_integer(var::FIDELITY, 1).unwrap();
    a.set_integer(var::THREADS, 2).unwrap();
    a.set_real(var::FY, 8e3).unwrap();
    a.do_step(0.0, 5e-4).unwrap();
    let saved = a.serialize_state();
    a.do_step(5e-4, 5e-4).unwrap();
    let z = Bearing::preset("TRB130x230").unwrap().roller_count;
    let want = real_outputs(&mut a, z);
    let mut b = Simulation::new(Bearing::preset("TRB130x230").unwrap());
    b.deserialize_state(&saved).unwrap();
    assert_eq!(b.get_integer(var::THREADS).unwrap(), 2);
    b.do_step(5e-4, 5e-4).unwrap();
    assert_eq!(want, real_outputs(&mut b, z));
}

#[test]
fn a_thread_count_out_of_range_is_refused_by_name() {
    let mut s = Simulation::new(Bearing::default_preset());
    for bad in [0, 65, -3] {
        let e = s.set_integer(var::THREADS, bad).unwrap_err().to_string();
        assert!(e.contains("threads") || e.contains(&var::THREADS.to_string()), "{e}");
    }
}
