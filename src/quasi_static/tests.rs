//! Physics tests of the quasi-static model: equilibrium, symmetry, convergence under slice
//! refinement, the classical rigid-ring load-zone integrals, preload modes, clearance,
//! diameter deviations, lobed raceways and friction torque.

use super::*;
use crate::bearing::Bearing;
use crate::model::{Inputs, Outputs, Parameters};

fn setup(name: &str) -> (Bearing, Parameters, Inputs) {
    let b = Bearing::preset(name).unwrap();
    let p = Parameters::from_bearing(&b);
    let i = Inputs::from_bearing(&b);
    (b, p, i)
}

struct Solved {
    out: Outputs,
    report: SolveReport,
    qs: QuasiStatic,
    x: Vec<f64>,
}

fn solve_at(b: &Bearing, p: &Parameters, i: &Inputs, cage_angle: f64) -> Solved {
    let mut qs = QuasiStatic::new(b, p).unwrap();
    let mut out = Outputs::new(b.roller_count);
    let mut x = Vec::new();
    let report = qs
        .solve(i, cage_angle, &mut x, &mut out)
        .unwrap_or_else(|e| panic!("{}: {e}", b.name));
    Solved { out, report, qs, x }
}

fn solve(b: &Bearing, p: &Parameters, i: &Inputs) -> Solved {
    solve_at(b, p, i, p.cage_angle0)
}

/// Sum over rollers and slices of the force the rollers exert on the cup, (axial, y, z),
/// for a solution at cage angle 0.
fn cup_force(s: &Solved) -> [f64; 3] {
    let g = &s.qs.geometry;
    let mut cone = vec![0.0; g.slices];
    let mut cup = vec![0.0; g.slices];
    let mut f = [0.0; 3];
    for j in 0..g.z {
        s.qs.slice_loads(&s.x, j, &mut cone, &mut cup);
        let qo: f64 = cup.iter().sum();
        let psi = std::f64::consts::TAU * j as f64 / g.z as f64;
        // force on the cup = -q n_o
        f[0] -= qo * g.cup.normal[0];
        f[1] -= qo * g.cup.normal[1] * psi.cos();
        f[2] -= qo * g.cup.normal[1] * psi.sin();
    }
    f
}

#[test]
fn newton_converges_below_1e9_relative_on_every_preset() {
    for name in ["TRB130x230", "32018X", "32008", "CRB-TRILOBE"] {
        let (b, p, i) = setup(name);
        let s = solve(&b, &p, &i);
        assert!(s.report.residual <= 1e-9, "{name}: residual {}", s.report.residual);
        assert!(s.out.all_finite(), "{name}");
    }
}

#[test]
fn pure_axial_load_is_carried_by_the_cup_and_shared_equally() {
    for name in ["TRB130x230", "32008"] {
        let (b, p, mut i) = setup(name);
        i.fy = 0.0;
        i.fz = 0.0;
        let s = solve(&b, &p, &i);
        let f = cup_force(&s);
        assert!((f[0] - i.fx).abs() <= 1e-9 * i.fx, "{name}: cup axial {} vs Fx {}", f[0], i.fx);
        assert!((s.out.reaction_fx - i.fx).abs() <= 1e-9 * i.fx);
        let q0 = s.out.qo[0];
        for j in 0..b.roller_count {
            for (a, bq) in [(s.out.qo[j], q0), (s.out.qi[j], s.out.qi[0]), (s.out.qf[j], s.out.qf[0])] {
                assert!((a - bq).abs() <= 1e-9 * q0, "{name}: roller {j} differs: {a} vs {bq}");
            }
        }
        // Classical: Qo = Fa / (Z sin a_o) exactly, since the cup carries Fa.
        let qo = i.fx / (b.roller_count as f64 * b.cup_angle.sin());
        assert!((q0 - qo).abs() < 1e-9 * qo);
        // No cone radial displacement, no reaction moments (up to round-off).
        assert!(s.out.cone_y.abs() < 1e-15 && s.out.cone_z.abs() < 1e-15);
        assert!(s.out.reaction_my.abs() < 1e-9 * i.fx * b.pitch_diameter);
        assert_eq!(s.out.loaded_rollers as usize, b.roller_count);
    }
}

#[test]
fn roller_force_triangle_matches_harris() {
    // Harris: with fixed contact directions, Qi/Qo and Qf/Qo follow from the roller's force
    // balance; at low speed (no centrifugal force) Qi = Qo sin(a_o + a_f)/sin(a_i + a_f).
    let (b, mut p, mut i) = setup("TRB130x230");
    i.speed = 0.0;
    p.gyroscopic = false;
    let s = solve(&b, &p, &i);
    let (ai, ao, af) = (b.cone_angle, b.cup_angle, b.flange_angle.unwrap());
    let qo = s.out.qo[0];
    let qi = qo * (ao + af).sin() / (ai + af).sin();
    let qf = qo * (ao - ai).sin() / (ai + af).sin();
    assert!((s.out.qi[0] - qi).abs() < 1e-8 * qo, "{} vs {qi}", s.out.qi[0]);
    assert!((s.out.qf[0] - qf).abs() < 1e-8 * qo, "{} vs {qf}", s.out.qf[0]);
}

#[test]
fn total_roller_load_converges_as_slices_grow() {
    // A tilted cone (misalignment) and a radial load make the interference non-uniform
    // along the rollers, so the slice sums are a quadrature that must converge.
    for name in ["TRB130x230", "32018X"] {
        let (b, mut p, mut i) = setup(name);
        i.xi = 0.02_f64.to_radians();
        i.fy = 0.3 * i.fx.max(10_000.0);
        let mut last: Option<(f64, f64)> = None;
        let mut diffs: Vec<f64> = Vec::new();
        for s in [5, 10, 20, 40, 80, 160] {
            p.slices = s;
            let out = solve(&b, &p, &i).out;
            let v = (out.qo_max, out.reaction_my);
            if let Some((q, m)) = last {
                diffs.push(((v.0 - q) / q).abs().max(((v.1 - m) / m).abs()));
            }
            last = Some(v);
        }
        // Differences shrink (second order of the midpoint rule: about 4x per halving) ...
        for w in diffs.windows(2) {
            assert!(w[1] < 0.5 * w[0], "{name}: no convergence: {diffs:?}");
        }
        // ... and 80 -> 160 slices changes the results by less than 2e-4.
        assert!(*diffs.last().unwrap() < 2e-4, "{name}: {diffs:?}");
    }
}

/// Sjovall's load-zone integrals for load-deflection exponent n and load-zone parameter eps:
/// J_r = 1/(2 pi) int (1 - (1 - cos psi)/(2 eps))^n cos psi dpsi, J_a the same without cos.
fn sjovall(eps: f64, n: f64) -> (f64, f64) {
    let m = 20_000;
    let (mut jr, mut ja) = (0.0, 0.0);
    for k in 0..m {
        let psi = -std::f64::consts::PI + (k as f64 + 0.5) * std::f64::consts::TAU / m as f64;
        let f = 1.0 - (1.0 - psi.cos()) / (2.0 * eps);
        if f > 0.0 {
            let q = f.powf(n);
            jr += q * psi.cos();
            ja += q;
        }
    }
    (jr / m as f64, ja / m as f64)
}

#[test]
fn combined_load_matches_the_rigid_ring_load_zone_integrals() {
    // [D19] case: 32018X, Fr = 35 kN, Fa = 12.97 kN. Rigid rings: the cup load of the roller
    // at psi is Q(psi) = Q_max (1 - (1 - cos psi)/(2 eps))^n with n = 10/9 (Palmgren line
    // contact); eps from Fr tan(a)/Fa = J_r/J_a; Fa = Z Q_max J_a sin(a).
    let (b, mut p, mut i) = setup("32018X");
    i.speed = 0.0;
    p.gyroscopic = false;
    let s = solve(&b, &p, &i);
    let (fr, fa, z, a) = (i.fy, i.fx, b.roller_count as f64, b.cup_angle);
    let n = 10.0 / 9.0;
    let target = fr * a.tan() / fa;
    let (mut lo, mut hi) = (0.01, 5.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let (jr, ja) = sjovall(mid, n);
        // J_r/J_a falls from 1 (tiny load zone) as eps grows
        if jr / ja > target {
            lo = mid
        } else {
            hi = mid
        }
    }
    let eps = 0.5 * (lo + hi);
    let (_, ja) = sjovall(eps, n);
    let q_max = fa / (z * ja * a.sin());
    let err = (s.out.qo_max - q_max).abs() / q_max;
    // A finite roller count (26) and the flange's Hertz exponent 3/2 in series with the
    // raceways make the discrete bearing differ slightly from the continuous integral.
    println!(
        "Sjovall: Qo.max {:.1} N, integral {:.1} N, eps {eps:.4}, error {:.3} %",
        s.out.qo_max,
        q_max,
        100.0 * err
    );
    assert!(
        err < 0.01,
        "Qo.max {:.1} vs Sjovall {:.1} (eps {eps:.3}): {:.2} %",
        s.out.qo_max,
        q_max,
        100.0 * err
    );
    // The load zone spans the same angle: rollers within psi_l = acos(1 - 2 eps) are loaded.
    let psi_l = (1.0 - 2.0 * eps).clamp(-1.0, 1.0).acos();
    for j in 0..b.roller_count {
        let psi = std::f64::consts::TAU * j as f64 / z;
        let psi = if psi > std::f64::consts::PI {
            std::f64::consts::TAU - psi
        } else {
            psi
        };
        if psi < psi_l - 0.1 {
            assert!(s.out.qo[j] > 0.0, "roller {j} at {psi:.2} rad inside the load zone is unloaded");
        }
        if psi > psi_l + 0.1 {
            assert!(
                s.out.qo[j] < 0.02 * q_max,
                "roller {j} at {psi:.2} rad outside the load zone carries {}",
                s.out.qo[j]
            );
        }
    }
}

#[test]
fn radial_load_distribution_is_mirror_symmetric_about_the_load_line() {
    let (b, p, i) = setup("32018X");
    let s = solve(&b, &p, &i);
    let z = b.roller_count;
    for j in 1..z {
        let (a, c) = (s.out.qo[j], s.out.qo[z - j]);
        assert!((a - c).abs() <= 1e-7 * s.out.qo_max, "roller {j}: {a} vs {c}");
        assert!((s.out.tilt[j] - s.out.tilt[z - j]).abs() <= 1e-7 * s.out.tilt_max.max(1e-12));
    }
    assert!(s.out.cone_z.abs() < 1e-9 * s.out.cone_y.abs());
}

#[test]
fn displacement_and_force_preload_agree() {
    let (b, p, i) = setup("TRB130x230");
    let mut i = i;
    i.fy = 5_000.0;
    i.xi = 0.003_f64.to_radians();
    let force = solve(&b, &p, &i);
    let mut pd = p.clone();
    pd.preload = Preload::Displacement;
    let mut id = i;
    id.axial_displacement = force.out.cone_x;
    let disp = solve(&b, &pd, &id);
    assert!(
        (disp.out.reaction_fx - i.fx).abs() < 1e-6 * i.fx,
        "{} vs {}",
        disp.out.reaction_fx,
        i.fx
    );
    assert!((disp.out.qo_max - force.out.qo_max).abs() < 1e-6 * force.out.qo_max);
    assert!((disp.out.reaction_my - force.out.reaction_my).abs() < 1e-6 * force.out.reaction_my.abs());
    // More axial displacement, more axial force.
    id.axial_displacement *= 1.1;
    assert!(solve(&b, &pd, &id).out.reaction_fx > 1.1 * i.fx);
}

#[test]
fn clearance_shifts_the_cone_but_not_the_loads_under_axial_force() {
    let (b, p, i) = setup("32008");
    let base = solve(&b, &p, &i);
    let mut pc = p.clone();
    pc.clearance = 20e-6;
    let with = solve(&b, &pc, &i);
    // The cup is 10 um further out radially: the cone travels (c/2)/tan(a_o) further.
    let expect = 0.5 * pc.clearance / b.cup_angle.tan();
    assert!(((with.out.cone_x - base.out.cone_x) - expect).abs() < 1e-9 * expect.max(base.out.cone_x));
    assert!((with.out.qo_max - base.out.qo_max).abs() < 1e-9 * base.out.qo_max);
}

#[test]
fn a_larger_roller_carries_more_load() {
    let (b, mut p, i) = setup("32008");
    p.roller_dd[4] = 2e-6;
    let s = solve(&b, &p, &i);
    let others = s
        .out
        .qo
        .iter()
        .enumerate()
        .filter(|(j, _)| *j != 4)
        .map(|(_, q)| *q)
        .fold(0.0, f64::max);
    assert!(s.out.qo[4] > 1.2 * others, "{} vs {others}", s.out.qo[4]);
    // The cup still carries Fx.
    assert!((cup_force(&s)[0] - i.fx).abs() < 1e-8 * i.fx);
}

#[test]
fn misalignment_needs_a_moment_in_its_own_direction() {
    let (b, p, mut i) = setup("TRB130x230");
    for (xi, zeta) in [(0.004_f64, 0.0_f64), (0.0, 0.004), (-0.004, 0.0)] {
        i.xi = xi.to_radians();
        i.zeta = zeta.to_radians();
        let s = solve(&b, &p, &i);
        let work = s.out.reaction_my * i.xi + s.out.reaction_mz * i.zeta;
        assert!(
            work > 0.0,
            "moment does not resist the tilt: My {} Mz {}",
            s.out.reaction_my,
            s.out.reaction_mz
        );
        // the misalignment tilts the rollers and spreads the loads
        assert!(s.out.qo_max > s.out.qo.iter().cloned().fold(f64::INFINITY, f64::min));
    }
}

#[test]
fn cylindrical_bearing_balances_centrifugal_force_and_has_three_preload_zones() {
    let (b, p, mut i) = setup("CRB-TRILOBE");
    // Radial equilibrium of a loaded roller with zero contact angles: Qo = Qi + Fc.
    let s = solve(&b, &p, &i);
    let g = &s.qs.geometry;
    let wc = s.qs.cage_speed(&i);
    let fc = g.roller_mass * wc * wc * g.center[1];
    for j in 0..b.roller_count {
        if s.out.qi[j] > 0.0 {
            assert!((s.out.qo[j] - s.out.qi[j] - fc).abs() < 1e-6 * s.out.qo[j]);
        }
    }
    // Without radial load, the loads repeat with the three lobes (24 rollers: period 8).
    i.fy = 0.0;
    let s = solve(&b, &p, &i);
    for j in 0..b.roller_count {
        let k = (j + 8) % b.roller_count;
        assert!(
            (s.out.qo[j] - s.out.qo[k]).abs() < 1e-6 * s.out.qo_max,
            "{j}: {} vs {}",
            s.out.qo[j],
            s.out.qo[k]
        );
    }
    assert!(s.out.qi[0] > 0.0, "roller on a lobe's low point must be preloaded");
    // Double pressed (half a pitch away): fewer rollers touch the cone than single pressed.
    let single = solve_at(&b, &p, &i, 0.0).out.loaded_rollers;
    let double = solve_at(&b, &p, &i, std::f64::consts::PI / b.roller_count as f64)
        .out
        .loaded_rollers;
    assert!(single % 3 == 0 && double % 3 == 0, "{single} {double}");
    assert!(single != double, "single {single}, double {double}");
}

#[test]
fn more_speed_fewer_loaded_rollers_in_the_lobed_bearing() {
    let (b, p, mut i) = setup("CRB-TRILOBE");
    i.speed = 1000.0;
    let slow = solve(&b, &p, &i).out.loaded_rollers;
    i.speed = 6000.0;
    let fast = solve(&b, &p, &i).out.loaded_rollers;
    assert!(fast <= slow && slow > 0, "slow {slow}, fast {fast}");
}

#[test]
fn warm_start_reproduces_the_solution_in_at_most_one_iteration() {
    let (b, p, mut i) = setup("32018X");
    i.xi = 0.002_f64.to_radians();
    let mut s = solve(&b, &p, &i);
    let mut out2 = Outputs::new(b.roller_count);
    let r = s.qs.solve(&i, 0.0, &mut s.x, &mut out2).unwrap();
    assert!(r.iterations <= 1, "{} iterations from the converged point", r.iterations);
    assert!((out2.qo_max - s.out.qo_max).abs() < 1e-9 * s.out.qo_max);
}

#[test]
fn friction_power_equals_torque_times_speed_and_flips_with_speed() {
    for name in ["TRB130x230", "32018X"] {
        let (b, p, mut i) = setup(name);
        let fwd = solve(&b, &p, &i).out;
        assert!(fwd.friction_torque > 0.0, "{name}: {}", fwd.friction_torque);
        assert!((fwd.power_loss - fwd.friction_torque * i.speed).abs() <= 1e-12 * fwd.power_loss.abs());
        assert!(
            (fwd.friction_torque - fwd.friction_torque_raceway - fwd.friction_torque_flange - fwd.friction_torque_cage).abs()
                < 1e-12 * fwd.friction_torque
        );
        i.speed = -i.speed;
        let rev = solve(&b, &p, &i).out;
        assert!((rev.friction_torque + fwd.friction_torque).abs() < 1e-9 * fwd.friction_torque);
        assert!(rev.power_loss > 0.0);
    }
}

#[test]
fn standstill_torque_is_finite_and_continuous() {
    let (b, p, mut i) = setup("TRB130x230");
    i.speed = 0.0;
    let zero = solve(&b, &p, &i).out;
    assert!(zero.friction_torque.is_finite() && zero.friction_torque > 0.0);
    assert_eq!(zero.power_loss, 0.0);
    i.speed = 1e-6;
    let creep = solve(&b, &p, &i).out;
    assert!((creep.friction_torque - zero.friction_torque).abs() < 1e-3 * zero.friction_torque);
}

#[test]
fn ehl_torque_grows_with_viscosity_and_dry_torque_with_mu() {
    let (b, mut p, i) = setup("TRB130x230");
    let t1 = solve(&b, &p, &i).out.friction_torque;
    p.eta0 *= 4.0;
    let t2 = solve(&b, &p, &i).out.friction_torque;
    assert!(t2 > t1, "{t2} <= {t1}");
    let (b, mut p, i) = setup("32018X");
    p.mu = 0.05;
    let d1 = solve(&b, &p, &i).out.friction_torque;
    p.mu = 0.2;
    let d2 = solve(&b, &p, &i).out.friction_torque;
    assert!((d2 / d1 - 4.0).abs() < 1e-6, "dry torque not proportional to mu: {d1} {d2}");
}

#[test]
fn centrifugal_and_gyroscopic_effects_act_as_expected() {
    let (b, mut p, i) = setup("TRB130x230");
    let full = solve(&b, &p, &i).out;
    p.centrifugal = false;
    let no_cf = solve(&b, &p, &i).out;
    // Centrifugal force loads the cup more than the cone.
    assert!(full.qo[0] - full.qi[0] > no_cf.qo[0] - no_cf.qi[0]);
    p.centrifugal = true;
    p.gyroscopic = false;
    let no_gyro = solve(&b, &p, &i).out;
    assert!((no_gyro.tilt[0] - full.tilt[0]).abs() > 1e-3 * full.tilt[0].abs());
}

#[test]
fn single_bearing_without_axial_force_under_radial_load_is_reported() {
    let (b, p, mut i) = setup("TRB130x230");
    i.fx = 0.0;
    i.fy = 10_000.0;
    let mut qs = QuasiStatic::new(&b, &p).unwrap();
    let mut out = Outputs::new(b.roller_count);
    let mut x = Vec::new();
    let e = qs.solve(&i, 0.0, &mut x, &mut out).expect_err("no equilibrium");
    let msg = e.to_string();
    assert!(msg.contains("axial force"), "{msg}");
    assert!(out.all_finite());
}

#[test]
fn equilibrium_is_independent_of_cage_angle_for_axisymmetric_load() {
    let (b, p, i) = setup("TRB130x230");
    let a = solve_at(&b, &p, &i, 0.0).out;
    let c = solve_at(&b, &p, &i, 0.37).out;
    assert!((a.qo_max - c.qo_max).abs() < 1e-9 * a.qo_max);
    assert!((a.friction_torque - c.friction_torque).abs() < 1e-9 * a.friction_torque);
}

#[test]
#[ignore]
fn debug_iterations() {
    let (b, p, mut i) = setup(&std::env::var("PRESET").unwrap_or("32018X".into()));
    if let Ok(v) = std::env::var("XI_DEG") {
        i.xi = v.parse::<f64>().unwrap().to_radians();
    }
    let mut qs = QuasiStatic::new(&b, &p).unwrap();
    let mut x = vec![0.0; qs.n_unknowns()];
    qs.prepare(&i, 0.0);
    let (fc, mfc, mreq) = qs.inertial_loads(&i);
    qs.initial_guess(&mut x, &i, fc, 1.0);
    for it in 0..60 {
        let (mr, me, fr, ring) = qs.evaluate(&x, &i, fc, mfc, mreq);
        let (mut worst, mut wj, mut wc) = (0.0, 0, 0);
        for j in 0..b.roller_count {
            for c in 0..3 {
                if qs.evals[j].r[c].abs() > worst {
                    worst = qs.evals[j].r[c].abs();
                    wj = j;
                    wc = c;
                }
            }
        }
        println!(
            "it {it}: max_r {mr:.3e} merit {me:.3e} ring {:.2e} worst roller {wj} comp {wc} = {worst:.3e} qi {:.3e} qo {:.3e} qf {:.3e}",
            ring.amax(),
            qs.evals[wj].qi,
            qs.evals[wj].qo,
            qs.evals[wj].qf
        );
        if mr <= 1e-9 * fr {
            break;
        }
        qs.newton_step(&ring);
        for k in 0..x.len() {
            x[k] += qs.step[k];
        }
    }
}

#[test]
#[ignore]
fn debug_warm_step() {
    let (b, p, i) = setup(&std::env::var("PRESET").unwrap_or("32018X".into()));
    let mut qs = QuasiStatic::new(&b, &p).unwrap();
    let mut out = Outputs::new(b.roller_count);
    let mut x = Vec::new();
    qs.solve(&i, 0.0, &mut x, &mut out).unwrap();
    let angle = qs.cage_speed(&i) * 1e-3;
    qs.prepare(&i, angle);
    let (fc, mfc, mreq) = qs.inertial_loads(&i);
    for it in 0..10 {
        let (mr, me, fr, ring) = qs.evaluate(&x, &i, fc, mfc, mreq);
        let (mut worst, mut wj, mut wc) = (0.0, 0, 0);
        for j in 0..b.roller_count {
            for c in 0..3 {
                if qs.evals[j].r[c].abs() > worst {
                    worst = qs.evals[j].r[c].abs();
                    wj = j;
                    wc = c;
                }
            }
        }
        println!("it {it}: max_r {mr:.3e} (tol {:.1e}) merit {me:.3e} ring {:.2e} worst roller {wj} comp {wc} = {worst:.3e} qi {:.3e} qo {:.3e} qf {:.3e} gap {:.2e}", 1e-9*fr, ring.amax(), qs.evals[wj].qi, qs.evals[wj].qo, qs.evals[wj].qf, qs.evals[wj].gap);
        if mr <= 1e-9 * fr {
            break;
        }
        if qs.seat_free_rollers(&mut x, fc) {
            println!("   seated");
            continue;
        }
        qs.newton_step(&ring);
        for k in 0..x.len() {
            x[k] += qs.step[k];
        }
    }
}

#[test]
fn deflection_sweep_to_the_model_limit_converges() {
    // Shaft deflection up to 0.3 deg with and without radial load, cold and warm.
    let (b, p, mut i) = setup("TRB130x230");
    for fy in [0.0, 10_000.0] {
        i.fy = fy;
        let mut qs = QuasiStatic::new(&b, &p).unwrap();
        let mut out = Outputs::new(b.roller_count);
        let mut warm = Vec::new();
        for xi_deg in [0.0, 0.001, 0.004, 0.006, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3] {
            i.xi = f64::to_radians(xi_deg);
            let r = qs
                .solve(&i, 0.1, &mut warm, &mut out)
                .unwrap_or_else(|e| panic!("warm, Fy {fy}, xi {xi_deg} deg: {e}"));
            assert!(r.residual <= 1e-9);
            let mut cold = Vec::new();
            let mut out2 = Outputs::new(b.roller_count);
            qs.solve(&i, 0.1, &mut cold, &mut out2)
                .unwrap_or_else(|e| panic!("cold, Fy {fy}, xi {xi_deg} deg: {e}"));
            assert!(
                (out2.qo_max - out.qo_max).abs() < 1e-6 * out.qo_max,
                "cold and warm starts disagree"
            );
        }
    }
}

#[test]
fn displacement_preload_sweeps_converge_from_cold_starts() {
    // [W25]: axial displacement preload 10 um with Fr = 1.5 .. 45 kN at xi = 0 and 0.003 deg.
    let (b, mut p, mut i) = setup("TRB130x230");
    p.preload = Preload::Displacement;
    i.axial_displacement = 10e-6;
    i.fx = 0.0;
    for xi_deg in [0.0, 0.003] {
        i.xi = f64::to_radians(xi_deg);
        let mut last_fx = 0.0;
        for fr in [1_500.0, 5_000.0, 15_000.0, 30_000.0, 45_000.0] {
            i.fy = fr;
            let s = solve(&b, &p, &i);
            assert!(s.report.residual <= 1e-9);
            // more radial load on a fixed axial position: a larger axial reaction
            assert!(
                s.out.reaction_fx > last_fx,
                "xi {xi_deg}, Fr {fr}: {} <= {last_fx}",
                s.out.reaction_fx
            );
            last_fx = s.out.reaction_fx;
        }
    }
}

#[test]
#[ignore]
fn debug_skew() {
    let (b, mut p, mut i) = setup("32018X");
    p.skew_model = true;
    p.mu = std::env::var("MU").map(|v| v.parse().unwrap()).unwrap_or(0.1);
    if let Ok(v) = std::env::var("EPS") {
        p.pocket_clearance = v.parse().unwrap();
    }
    if std::env::var("DISP").is_ok() {
        p.preload = Preload::Displacement;
        i.axial_displacement = 10e-6;
    }
    let s = solve(&b, &p, &i);
    let o = &s.out;
    println!("iters {} res {:.2e}", s.report.iterations, s.report.residual);
    for j in 0..b.roller_count {
        println!(
            "{j:2} qi {:9.1} qo {:9.1} qf {:8.1} qc {:8.2} skew {:9.5} tilt {:9.2e} nis {:8.4} nos {:8.4} nfs {:8.4}",
            o.qi[j], o.qo[j], o.qf[j], o.qc[j], o.skew[j], o.tilt[j], o.nis[j], o.nos[j], o.nfs[j]
        );
    }
    println!(
        "T {:.4} race {:.4} flange {:.4} cage {:.4} cone {:.4} cup {:.4} Fx {:.1} loaded {}",
        o.friction_torque,
        o.friction_torque_raceway,
        o.friction_torque_flange,
        o.friction_torque_cage,
        o.friction_torque_cone,
        o.friction_torque_cup,
        o.reaction_fx,
        o.loaded_rollers
    );
}

#[test]
fn a_ring_crossing_a_positive_clearance_lands_in_a_few_iterations() {
    // Regression: with positive clearance the cone first travels across the gap with no
    // contact (flat residual), then lands on the roller at the lobe's low point.
    let (b, mut p, i) = setup("CRB-TRILOBE");
    for c in [4e-6, 5e-6, 10e-6, 20e-6] {
        p.clearance = c;
        let s = solve_at(&b, &p, &i, 0.0);
        assert!(s.report.iterations <= 20, "clearance {c}: {} iterations", s.report.iterations);
        // the ring sits about half the clearance off centre, on its loaded roller(s)
        assert!(
            s.out.cone_y > 0.5 * c && s.out.cone_y < 0.5 * c + 5e-6,
            "clearance {c}: cone.y {}",
            s.out.cone_y
        );
        assert!(s.out.loaded_rollers >= 1);
    }
}
