//! Outputs of the dynamic model (fidelity 1) that follow its state: the ring torques of
//! [L22] and the rollers' sliding friction are the moments and forces of the contacts now,
//! not the quasi-static start values, and the moments about the bearing axis balance.

use trb::variables as var;

mod common;

#[test]
fn ring_torques_and_sliding_friction_follow_the_dynamic_state() {
    let mut s = common::dynamic_element(2, 1e-4, 10e3);
    let start = s.outputs().unwrap().clone();
    let h = 5e-4;
    let mut t = 0.0;
    let (mut cone, mut cup, mut n) = (0.0, 0.0, 0.0);
    let mut last = start.clone();
    for k in 0..40 {
        s.do_step(t, h).unwrap();
        t += h;
        last = s.outputs().unwrap().clone();
        if k >= 8 {
            cone += last.friction_torque_cone;
            cup += last.friction_torque_cup;
            n += 1.0;
        }
    }
    let (cone, cup) = (cone / n, cup / n);
    // the dynamic model writes them (the quasi-static start values were kept before)
    assert!((last.friction_torque_cup - start.friction_torque_cup).abs() > 1e-3 * cup.abs());
    assert!((last.sliding_friction_max - start.sliding_friction_max).abs() > 1e-3 * last.sliding_friction_max);
    let z = s.n_rollers();
    let per_roller_max = (0..z)
        .map(|j| s.get_real(var::ROLLER_SLIDING_FRICTION + j as u32).unwrap())
        .fold(0.0, f64::max);
    assert_eq!(per_roller_max, last.sliding_friction_max);
    assert!(last.sliding_friction.iter().all(|&f| f > 0.0));
    // the cone's torque is what drives it; the cup is dragged along in the sense of rotation
    assert_eq!(last.friction_torque_cone, last.friction_torque);
    assert!(cup > 0.0 && cone > 0.0);
    // moments about the bearing axis on rollers and cage at steady running: what the cone puts
    // in, the cup takes out, but for the cage land's drag on the cage (a few per cent)
    assert!(
        cone - cup >= -0.01 * cone && cone - cup <= 0.1 * cone,
        "mean cone torque {cone} N m, cup torque {cup} N m"
    );
}
