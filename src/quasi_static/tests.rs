use super::*;
use crate::bearing::Bearing;
use crate::model::{Inputs, Outputs, Parameters};

fn setup(name: &str) -> (Bearing, Parameters, Inputs) {
    let b = Bearing::preset(name).unwrap();
    let p = Parameters::from_bearing(&b);
    let i = Inputs::from_bearing(&b);
    (b, p, i)
}

fn solve(b: &Bearing, p: &Parameters, i: &Inputs) -> (Outputs, SolveReport, QuasiStatic, Vec<f64>) {
    let mut qs = QuasiStatic::new(b, p).unwrap();
    let mut out = Outputs::new(b.roller_count);
    let mut warm = Vec::new();
    let r = qs.solve(i, p.cage_angle0, &mut warm, &mut out).unwrap_or_else(|e| panic!("{e}"));
    (out, r, qs, warm)
}

#[test]
fn explore_default() {
    for name in ["TRB130x230", "32018X", "32008", "CRB-TRILOBE"] {
        let (b, p, i) = setup(name);
        let (o, r, _, x) = solve(&b, &p, &i);
        println!("{name}: iters {} res {:.2e} cone.x {:.3e} y {:.3e} Qi {:.1} Qo {:.1} Qf {:.1} loaded {} T {:.4} (race {:.4} fl {:.4}) P {:.1} tilt {:.3e} Fx {:.1} My {:.2}",
            r.iterations, r.residual, o.cone_x, o.cone_y, o.qi_max, o.qo_max, o.qf_max, o.loaded_rollers, o.friction_torque,
            o.friction_torque_raceway, o.friction_torque_flange, o.power_loss, o.tilt_max, o.reaction_fx, o.reaction_my);
        println!("   qo: {:?}", o.qo.iter().map(|v| (v*10.0).round()/10.0).collect::<Vec<_>>());
        let _ = x;
    }
}

#[test]
fn explore_guess() {
    let (b, p, i) = setup("32008");
    let qs = QuasiStatic::new(&b, &p).unwrap();
    let mut x = vec![0.0; qs.n_unknowns()];
    let (fc, _, _) = qs.inertial_loads(i.speed);
    qs.initial_guess(&mut x, &i, fc, 1.0);
    println!("x {:?}", &x[..6]);
    println!("geom flange {:?} mass {} law {:?}", qs.geometry.flange, qs.geometry.roller_mass, qs.geometry.cone.law);
}

#[test]
fn explore_crb() {
    let (b, p, i) = setup("CRB-TRILOBE");
    let mut qs = QuasiStatic::new(&b, &p).unwrap();
    let mut x = vec![0.0; qs.n_unknowns()];
    qs.prepare(&i, 0.0);
    let (fc, mfc, mreq) = qs.inertial_loads(i.speed);
    println!("fc {fc} mfc {mfc} mreq {mreq}");
    qs.initial_guess(&mut x, &i, fc, 1.0);
    for it in 0..8 {
        let (mr, me, fr, ring) = qs.evaluate(&x, &i, fc, mfc, mreq);
        println!("it {it} max_r {mr:.3e} merit {me:.3e} fref {fr:.1} ring {:?}", ring.as_slice());
        println!("   roller0 r {:?} qi {} qo {} x {:?}", qs.evals[0].r.as_slice(), qs.evals[0].qi, qs.evals[0].qo, &x[3..6]);
        if !qs.newton_step(&ring) { println!("step failed"); break; }
        for k in 0..x.len() { x[k] += qs.step[k]; }
    }
}
