//! The dependencies the model description declares (`ModelStructure`, from the table's
//! `depends_on` and `initial_depends_on`) hold for the element itself: perturb every input
//! (after a step, at both fidelities and both preload modes) and every parameter and input
//! (in initialization mode), and every output that changes must declare what changed it.
//! A declared empty list (integrator counters, roller azimuths) is thereby a tested claim
//! that a master can cut an algebraic loop there.

use trb::bearing::Bearing;
use trb::simulation::Simulation;
use trb::variables::{self as var, Causality, VarType, Variable};

/// (name, value as f64 bits or integer) of every output.
fn outputs(sim: &mut Simulation) -> Vec<(String, &'static Variable, u64)> {
    var::expanded(sim.n_rollers())
        .into_iter()
        .filter(|(_, _, row)| row.causality == Causality::Output)
        .map(|(vr, name, row)| {
            let v = match row.ty {
                VarType::Real => sim.get_real(vr).expect("output").to_bits(),
                VarType::Integer => sim.get_integer(vr).expect("output") as u64,
                VarType::Boolean => sim.get_boolean(vr).expect("output") as u64,
            };
            (name, row, v)
        })
        .collect()
}

/// Set `vr` (a parameter or input) to a different valid value; false if the row has none.
fn perturb(sim: &mut Simulation, vr: u32, row: &Variable) -> bool {
    match row.ty {
        VarType::Real => {
            let v = sim.get_real(vr).expect("readable");
            let mut w = if v == 0.0 { 1e-6 } else { v * 1.02 };
            if let Some(max) = row.max {
                if w > max {
                    w = v * 0.98;
                }
            }
            if let Some(min) = row.min {
                if w < min {
                    return false;
                }
            }
            sim.set_real(vr, w).is_ok()
        }
        VarType::Integer => {
            let v = sim.get_integer(vr).expect("readable");
            let (lo, hi) = (row.min.unwrap_or(0.0) as i32, row.max.unwrap_or(i32::MAX as f64) as i32);
            let w = if v < hi { v + 1 } else { v - 1 };
            w >= lo && sim.set_integer(vr, w).is_ok()
        }
        VarType::Boolean => {
            let v = sim.get_boolean(vr).expect("readable");
            sim.set_boolean(vr, !v).is_ok()
        }
    }
}

fn declared(list: Option<&[&str]>, known: &str) -> bool {
    list.is_none_or(|names| names.contains(&known))
}

/// A loaded element: radial and axial load, misalignment.
fn loaded(fidelity: i32, preload: i32) -> Simulation {
    let mut sim = Simulation::new(Bearing::default_preset());
    sim.set_integer(var::FIDELITY, fidelity).unwrap();
    sim.set_integer(var::PRELOAD, preload).unwrap();
    if preload == 1 {
        sim.set_real(var::AXIAL_DISPLACEMENT, 2e-5).unwrap();
    }
    sim.set_real(var::FY, 20_000.0).unwrap();
    sim.set_real(var::XI, 3e-5).unwrap();
    sim
}

#[test]
fn outputs_change_only_with_the_inputs_they_declare() {
    for (fidelity, preload) in [(0, 0), (0, 1), (1, 0)] {
        let mut base = loaded(fidelity, preload);
        base.initialize(0.0).expect("initialize");
        base.do_step(0.0, 1e-4).expect("step");
        let before = outputs(&mut base);
        let mut changed_any = 0;
        for (vr, name, row) in var::expanded(base.n_rollers()) {
            if row.causality != Causality::Input {
                continue;
            }
            let mut sim = base.clone();
            assert!(perturb(&mut sim, vr, row), "cannot perturb {name}");
            let after = outputs(&mut sim);
            for ((out, orow, a), (_, _, b)) in before.iter().zip(&after) {
                if a != b {
                    changed_any += 1;
                    assert!(
                        declared(orow.depends_on, &name),
                        "fidelity {fidelity}, preload {preload}: {out} changed with input {name}, which it does not declare"
                    );
                }
            }
        }
        // the probe is not vacuous: the physical outputs do follow the inputs
        assert!(changed_any > 100, "fidelity {fidelity}: only {changed_any} output changes");
    }
}

#[test]
fn initial_outputs_change_only_with_the_knowns_they_declare() {
    let mut base = loaded(0, 0);
    let before = outputs(&mut base);
    let mut probed = 0;
    for (vr, name, row) in var::expanded(base.n_rollers()) {
        if row.causality == Causality::Output {
            continue;
        }
        let mut sim = base.clone();
        if !perturb(&mut sim, vr, row) {
            continue;
        }
        // a perturbation the model refuses (outside its range) says nothing
        if sim.outputs().is_err() {
            continue;
        }
        probed += 1;
        let after = outputs(&mut sim);
        for ((out, orow, a), (_, _, b)) in before.iter().zip(&after) {
            if a != b {
                assert!(
                    declared(orow.initial_depends_on, &name),
                    "initialization: {out} changed with {name}, which it does not declare"
                );
            }
        }
    }
    let knowns = var::TABLE.iter().filter(|r| r.causality != Causality::Output).count();
    assert!(probed + 5 >= knowns, "only {probed} of {knowns} knowns probed");
}
