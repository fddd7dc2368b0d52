//! Displacement causality (parameter `causality` = 1): the cone's translations relative to
//! the cup are inputs, the five reactions outputs, at both fidelities. Round trips against
//! force causality, zero load off contact, refusal beyond the model's range.

use trb::bearing::Bearing;
use trb::model::Outputs;
use trb::simulation::Simulation;
use trb::variables as var;

fn element(preset: &str, displacement: bool, fidelity: i32) -> Simulation {
    let mut s = Simulation::new(Bearing::preset(preset).unwrap());
    s.set_integer(var::CAUSALITY, displacement as i32).unwrap();
    s.set_integer(var::FIDELITY, fidelity).unwrap();
    s
}

fn solve(s: &mut Simulation, set: &[(u32, f64)]) -> Outputs {
    for &(vr, v) in set {
        s.set_real(vr, v).unwrap();
    }
    s.initialize(0.0).unwrap();
    s.outputs().unwrap().clone()
}

#[test]
fn displacements_of_a_force_solution_give_its_forces_back() {
    for (preset, fx, fy, fz, xi) in [
        ("TRB130x230", 30e3, 20e3, -5e3, 3e-4),
        ("TRB130x230", 30e3, 0.0, 0.0, 0.0),
        ("32008", 10e3, 3e3, 1e3, -2e-4),
        ("32018X", 13e3, 35e3, 0.0, 0.0),
        ("CRB-TRILOBE", 0.0, 8e3, 2e3, 0.0),
    ] {
        let mut f = element(preset, false, 0);
        let of = solve(&mut f, &[(var::FX, fx), (var::FY, fy), (var::FZ, fz), (var::XI, xi)]);
        let mut d = element(preset, true, 0);
        let od = solve(
            &mut d,
            &[
                (var::DISPLACEMENT_X, of.cone_x),
                (var::DISPLACEMENT_Y, of.cone_y),
                (var::DISPLACEMENT_Z, of.cone_z),
                (var::XI, xi),
            ],
        );
        let scale = fx.abs().max(fy.hypot(fz));
        let worst = [od.reaction_fx - of.reaction_fx, od.reaction_fy - fy, od.reaction_fz - fz]
            .iter()
            .fold(0.0_f64, |m, d| m.max(d.abs()))
            / scale;
        eprintln!("{preset}: round trip, largest force difference {worst:.2e} of the load");
        for (name, a, b) in [
            ("Fx", od.reaction_fx, of.reaction_fx),
            ("Fy", od.reaction_fy, fy),
            ("Fz", od.reaction_fz, fz),
        ] {
            assert!((a - b).abs() <= 1e-5 * scale, "{preset}: reaction {name} {a} vs {b}");
        }
        let m_scale = scale * Bearing::preset(preset).unwrap().pitch_diameter;
        assert!(
            (od.reaction_my - of.reaction_my).abs() <= 1e-5 * m_scale,
            "{preset}: My {} vs {}",
            od.reaction_my,
            of.reaction_my
        );
        assert!(
            (od.reaction_mz - of.reaction_mz).abs() <= 1e-5 * m_scale,
            "{preset}: Mz {} vs {}",
            od.reaction_mz,
            of.reaction_mz
        );
        assert_eq!(
            [od.cone_x, od.cone_y, od.cone_z],
            [
                if of.reaction_fx == 0.0 && preset == "CRB-TRILOBE" {
                    0.0
                } else {
                    of.cone_x
                },
                of.cone_y,
                of.cone_z
            ]
        );
        // the roller loads and the torque are those of the same state
        assert!(
            (od.qi_max / of.qi_max - 1.0).abs() < 1e-4,
            "{preset}: Qi.max {} vs {}",
            od.qi_max,
            of.qi_max
        );
        assert!(
            (od.friction_torque / of.friction_torque - 1.0).abs() < 1e-3,
            "{preset}: torque {} vs {}",
            od.friction_torque,
            of.friction_torque
        );
    }
}

#[test]
fn a_cone_lifted_off_every_roller_carries_no_load() {
    // pulled out axially: no roller touches the cone; at standstill nothing loads the rings
    let mut d = element("TRB130x230", true, 0);
    let o = solve(&mut d, &[(var::DISPLACEMENT_X, -20e-6), (var::SPEED, 0.0)]);
    assert_eq!(o.qi_max, 0.0);
    assert!(
        o.reaction_fx.abs() < 1e-6 && o.reaction_fy.abs() < 1e-6,
        "{} {}",
        o.reaction_fx,
        o.reaction_fy
    );
    assert!(o.stiffness.iter().all(|k| k.abs() < 1e-3), "{:?}", o.stiffness);
    assert_eq!(o.loaded_rollers, 0);
}

#[test]
fn a_displacement_beyond_the_model_range_is_refused_with_its_reason() {
    let mut d = element("TRB130x230", true, 0);
    d.set_real(var::DISPLACEMENT_Y, 5e-3).unwrap();
    let e = d.initialize(0.0).unwrap_err().to_string();
    assert!(e.contains("displacement.y") && e.contains("range"), "{e}");
}

#[test]
fn at_fidelity_1_the_cone_follows_the_prescribed_displacements() {
    // the displacements of a quasi-static force solution, prescribed to the dynamic model:
    // the reactions settle at the forces (the rollers' dynamics add little at steady running)
    let (fx, fy) = (30e3, 20e3);
    let mut f = element("TRB130x230", false, 0);
    let of = solve(&mut f, &[(var::FX, fx), (var::FY, fy)]);
    let mut d = element("TRB130x230", true, 1);
    d.set_integer(var::INTEGRATOR, 2).unwrap();
    d.set_real(var::TOLERANCE, 1e-4).unwrap();
    let mut o = solve(
        &mut d,
        &[
            (var::DISPLACEMENT_X, of.cone_x),
            (var::DISPLACEMENT_Y, of.cone_y),
            (var::DISPLACEMENT_Z, of.cone_z),
        ],
    );
    let (mut t, h) = (0.0, 5e-4);
    for _ in 0..20 {
        d.do_step(t, h).unwrap();
        t += h;
        o = d.outputs().unwrap().clone();
        assert_eq!([o.cone_x, o.cone_y, o.cone_z], [of.cone_x, of.cone_y, of.cone_z]);
    }
    assert!((o.reaction_fx / fx - 1.0).abs() < 0.02, "Fx {}", o.reaction_fx);
    assert!((o.reaction_fy / fy - 1.0).abs() < 0.02, "Fy {}", o.reaction_fy);
    assert!(o.reaction_fz.abs() < 0.02 * fy, "Fz {}", o.reaction_fz);
    // a radial step of 5 um: the cone jumps there and the radial reaction grows
    d.set_real(var::DISPLACEMENT_Y, of.cone_y + 5e-6).unwrap();
    for _ in 0..10 {
        d.do_step(t, h).unwrap();
        t += h;
    }
    let o2 = d.outputs().unwrap().clone();
    assert_eq!(o2.cone_y, of.cone_y + 5e-6);
    assert!(o2.reaction_fy > 1.2 * o.reaction_fy, "{} vs {}", o2.reaction_fy, o.reaction_fy);
}

/// Central finite differences of the reactions in displacement causality about `q0`
/// (x, y, z, xi, zeta), steps `h` (m, rad), of elements that `configure` sets up beyond that.
fn fd_stiffness(preset: &str, q0: [f64; 5], h: [f64; 5], configure: impl Fn(&mut Simulation)) -> [f64; 25] {
    let inputs = [var::DISPLACEMENT_X, var::DISPLACEMENT_Y, var::DISPLACEMENT_Z, var::XI, var::ZETA];
    let mut k = [0.0; 25];
    for c in 0..5 {
        let mut r = [[0.0; 5]; 2];
        for (side, sign) in [1.0, -1.0].iter().enumerate() {
            let set: Vec<(u32, f64)> = (0..5)
                .map(|i| (inputs[i], q0[i] + if i == c { sign * h[c] } else { 0.0 }))
                .collect();
            let mut d = element(preset, true, 0);
            configure(&mut d);
            let o = solve(&mut d, &set);
            r[side] = [o.reaction_fx, o.reaction_fy, o.reaction_fz, o.reaction_my, o.reaction_mz];
        }
        for i in 0..5 {
            k[5 * i + c] = (r[0][i] - r[1][i]) / (2.0 * h[c]);
        }
    }
    k
}

/// The largest difference between a stiffness matrix and finite differences, entry by entry
/// relative to the largest entry of the entry's block (forces/moments by translations/tilts)
/// of the differences; a block that is zero (a cylindrical bearing's tilt blocks) is measured
/// against the translational block's scale times the pitch radius to the power of its moment
/// and tilt count. Returns the difference and the entry (row, column, from 1).
fn stiffness_difference(analytic: &[f64; 25], fd: &[f64; 25], pitch_radius: f64) -> (f64, usize, usize) {
    let block_max = |rows: std::ops::Range<usize>, cols: std::ops::Range<usize>, m: &[f64; 25]| {
        rows.flat_map(|i| cols.clone().map(move |c| m[5 * i + c].abs())).fold(0.0, f64::max)
    };
    let k_tt = block_max(0..3, 0..3, fd);
    let mut worst = (0.0, 1, 1);
    for i in 0..5 {
        for c in 0..5 {
            let power = (i >= 3) as i32 + (c >= 3) as i32;
            let floor = 1e-3 * k_tt * pitch_radius.powi(power);
            let scale = block_max(if i < 3 { 0..3 } else { 3..5 }, if c < 3 { 0..3 } else { 3..5 }, fd).max(floor);
            let d = (analytic[5 * i + c] - fd[5 * i + c]).abs() / scale.max(1e-300);
            if d > worst.0 {
                worst = (d, i + 1, c + 1);
            }
        }
    }
    worst
}

/// The analytic and the finite-difference matrices agree to `tol` ([`stiffness_difference`]).
fn assert_stiffness_close(what: &str, analytic: &[f64; 25], fd: &[f64; 25], tol: f64, pitch_radius: f64) {
    let (worst, i, c) = stiffness_difference(analytic, fd, pitch_radius);
    assert!(
        worst <= tol,
        "{what}: stiffness[{i},{c}] analytic {:.6e} vs finite differences {:.6e}: {worst:.2e} of its block's scale",
        analytic[5 * (i - 1) + c - 1],
        fd[5 * (i - 1) + c - 1]
    );
    eprintln!("{what}: largest difference {worst:.2e} of its block's scale");
}

#[test]
fn the_stiffness_matrix_is_the_derivative_of_the_reactions() {
    for (preset, fx, fy, fz, xi, zeta) in [
        ("TRB130x230", 30e3, 20e3, -5e3, 3e-4, 1e-4),
        ("32008", 10e3, 3e3, 1e3, -2e-4, 0.0),
        ("32018X", 13e3, 35e3, 0.0, 0.0, 0.0),
        ("CRB-TRILOBE", 0.0, 8e3, 2e3, 0.0, 0.0),
    ] {
        let mut f = element(preset, false, 0);
        let of = solve(
            &mut f,
            &[(var::FX, fx), (var::FY, fy), (var::FZ, fz), (var::XI, xi), (var::ZETA, zeta)],
        );
        let q0 = [of.cone_x, of.cone_y, of.cone_z, xi, zeta];
        let fd = fd_stiffness(preset, q0, [2e-9, 2e-9, 2e-9, 2e-7, 2e-7], |_| {});
        let radius = 0.5 * Bearing::preset(preset).unwrap().pitch_diameter;
        assert_stiffness_close(&format!("{preset} (force causality solution)"), &of.stiffness, &fd, 1e-3, radius);
        let mut d = element(preset, true, 0);
        let od = solve(
            &mut d,
            &[
                (var::DISPLACEMENT_X, q0[0]),
                (var::DISPLACEMENT_Y, q0[1]),
                (var::DISPLACEMENT_Z, q0[2]),
                (var::XI, xi),
                (var::ZETA, zeta),
            ],
        );
        assert_stiffness_close(&format!("{preset} (displacement causality)"), &od.stiffness, &fd, 1e-3, radius);
    }
}

#[test]
fn at_fidelity_1_the_stiffness_is_the_quasi_static_linearisation_about_the_current_state() {
    for causality in [false, true] {
        let (fx, fy, xi) = (30e3, 15e3, 2e-4);
        let mut f = element("TRB130x230", false, 0);
        let of = solve(&mut f, &[(var::FX, fx), (var::FY, fy), (var::XI, xi)]);
        let mut d = element("TRB130x230", causality, 1);
        d.set_integer(var::INTEGRATOR, 2).unwrap();
        d.set_real(var::TOLERANCE, 1e-4).unwrap();
        let set = if causality {
            vec![
                (var::DISPLACEMENT_X, of.cone_x),
                (var::DISPLACEMENT_Y, of.cone_y),
                (var::DISPLACEMENT_Z, of.cone_z),
                (var::XI, xi),
            ]
        } else {
            vec![(var::FX, fx), (var::FY, fy), (var::XI, xi)]
        };
        solve(&mut d, &set);
        let mut t = 0.0;
        for _ in 0..10 {
            d.do_step(t, 5e-4).unwrap();
            t += 5e-4;
        }
        let o = d.outputs().unwrap().clone();
        // finite differences of the quasi-static reactions about the dynamic cone position,
        // with roller 1 where the dynamic cage has carried it
        let cage = d.get_real(var::ROLLER_AZIMUTH).unwrap();
        let q0 = [o.cone_x, o.cone_y, o.cone_z, xi, 0.0];
        let fd = fd_stiffness("TRB130x230", q0, [2e-9, 2e-9, 2e-9, 2e-7, 2e-7], |d| {
            d.set_real(var::CAGE_ANGLE0, cage).unwrap()
        });
        let radius = 0.5 * Bearing::preset("TRB130x230").unwrap().pitch_diameter;
        assert_stiffness_close(
            &format!("fidelity 1, displacement causality {causality}"),
            &o.stiffness,
            &fd,
            1e-3,
            radius,
        );
    }
}

#[test]
fn the_skew_model_stiffness_is_the_derivative_of_its_own_reactions() {
    // [D19]'s dry 32018X with the skew model: the stiffness output (the element's central
    // differences, 2 nm and 0.2 µrad, warm-started from the solve at the cone position) against
    // this test's central differences of cold-started solves with twice the steps, in both
    // causalities; and it is not the in-plane stiffness at the same cone position (skew
    // changes the load distribution by more than the tolerance)
    let set = [
        (var::FX, 12_970.0),
        (var::FY, 35e3),
        (var::MU, 0.1),
        (var::CAGE_POCKET_CLEARANCE, 0.9e-3),
    ];
    let configure = |d: &mut Simulation, skew: bool| {
        d.set_boolean(var::SKEW_MODEL, skew).unwrap();
        d.set_integer(var::LUBRICATION, 1).unwrap();
        d.set_real(var::MU, 0.1).unwrap();
        d.set_real(var::CAGE_POCKET_CLEARANCE, 0.9e-3).unwrap();
    };
    let mut f = element("32018X", false, 0);
    configure(&mut f, true);
    let of = solve(&mut f, &set);
    let q0 = [of.cone_x, of.cone_y, of.cone_z, 0.0, 0.0];
    let fd = fd_stiffness("32018X", q0, [4e-9, 4e-9, 4e-9, 4e-7, 4e-7], |d| configure(d, true));
    let radius = 0.5 * Bearing::preset("32018X").unwrap().pitch_diameter;
    assert!(of.stiffness[0] > 0.0);
    assert_stiffness_close("32018X skew model, force causality", &of.stiffness, &fd, 1e-3, radius);
    let displacements = [
        (var::DISPLACEMENT_X, of.cone_x),
        (var::DISPLACEMENT_Y, of.cone_y),
        (var::DISPLACEMENT_Z, of.cone_z),
    ];
    let mut d = element("32018X", true, 0);
    configure(&mut d, true);
    let od = solve(&mut d, &displacements);
    assert_stiffness_close("32018X skew model, displacement causality", &od.stiffness, &fd, 1e-3, radius);
    let mut in_plane = element("32018X", true, 0);
    configure(&mut in_plane, false);
    let oi = solve(&mut in_plane, &displacements);
    let (moved, i, c) = stiffness_difference(&oi.stiffness, &fd, radius);
    eprintln!("32018X: the in-plane stiffness differs from the skew model's by {moved:.2e} (stiffness[{i},{c}])");
    assert!(moved > 1e-3, "skew moves the stiffness by only {moved:.2e} of its block's scale");
}

#[test]
fn in_force_causality_the_stiffness_predicts_the_compliance() {
    // forces and tilts in, displacements and moments out: d(cone.x/y/z)/d(Fx, Fy, Fz) = K_uu^-1,
    // d(cone)/d(xi, zeta) = -K_uu^-1 K_ut, d(My, Mz)/d(xi, zeta) = K_tt - K_tu K_uu^-1 K_ut
    use nalgebra::{Matrix3, SMatrix};
    for (preset, fx, fy, fz, xi) in [("TRB130x230", 30e3, 20e3, -5e3, 3e-4), ("32008", 10e3, 3e3, 1e3, -2e-4)] {
        let base = [fx, fy, fz, xi, 0.0];
        let vrs = [var::FX, var::FY, var::FZ, var::XI, var::ZETA];
        let run = |v: [f64; 5]| {
            let mut f = element(preset, false, 0);
            let set: Vec<(u32, f64)> = vrs.iter().zip(v).map(|(r, x)| (*r, x)).collect();
            let o = solve(&mut f, &set);
            ([o.cone_x, o.cone_y, o.cone_z, o.reaction_my, o.reaction_mz], o.stiffness)
        };
        let (_, k) = run(base);
        let k = SMatrix::<f64, 5, 5>::from_row_slice(&k);
        let h = [fx * 1e-5, fx * 1e-5, fx * 1e-5, 2e-7, 2e-7];
        let mut d = SMatrix::<f64, 5, 5>::zeros(); // d(out)/d(in)
        for c in 0..5 {
            let (mut p, mut m) = (base, base);
            p[c] += h[c];
            m[c] -= h[c];
            let (op, om) = (run(p).0, run(m).0);
            for i in 0..5 {
                d[(i, c)] = (op[i] - om[i]) / (2.0 * h[c]);
            }
        }
        let kuu: Matrix3<f64> = k.fixed_view::<3, 3>(0, 0).into_owned();
        let kut = k.fixed_view::<3, 2>(0, 3).into_owned();
        let ktu = k.fixed_view::<2, 3>(3, 0).into_owned();
        let ktt = k.fixed_view::<2, 2>(3, 3).into_owned();
        let kuu_inv = kuu.try_inverse().unwrap();
        let want_c = kuu_inv;
        let want_ut = -kuu_inv * kut;
        let want_tt = ktt - ktu * kuu_inv * kut;
        let got_c = d.fixed_view::<3, 3>(0, 0).into_owned();
        let got_ut = d.fixed_view::<3, 2>(0, 3).into_owned();
        let got_tt = d.fixed_view::<2, 2>(3, 3).into_owned();
        assert!(
            (got_c - want_c).amax() < 1e-3 * want_c.amax(),
            "{preset}: compliance {got_c} vs {want_c}"
        );
        assert!(
            (got_ut - want_ut).amax() < 1e-3 * want_ut.amax(),
            "{preset}: d(cone)/d(tilt) {got_ut} vs {want_ut}"
        );
        assert!(
            (got_tt - want_tt).amax() < 1e-3 * want_tt.amax(),
            "{preset}: d(M)/d(tilt) {got_tt} vs {want_tt}"
        );
        eprintln!(
            "{preset} force causality: compliance {:.2e}, d(cone)/d(tilt) {:.2e}, d(M)/d(tilt) {:.2e}",
            (got_c - want_c).amax() / want_c.amax(),
            (got_ut - want_ut).amax() / want_ut.amax(),
            (got_tt - want_tt).amax() / want_tt.amax()
        );
    }
}

#[test]
fn the_linearised_stiffness_is_computed_when_read_and_restores_bit_for_bit() {
    let mut d = element("TRB130x230", false, 1);
    d.set_integer(var::INTEGRATOR, 2).unwrap();
    d.set_real(var::TOLERANCE, 1e-4).unwrap();
    d.set_real(var::FY, 15e3).unwrap();
    d.initialize(0.0).unwrap();
    let h = 5e-4;
    for k in 0..4 {
        d.do_step(k as f64 * h, h).unwrap();
    }
    let saved = d.serialize_state();
    let mut first = Vec::new();
    for k in 4..8 {
        d.do_step(k as f64 * h, h).unwrap();
        first.push(d.get_real(var::STIFFNESS_2_2).unwrap());
    }
    assert!(first.iter().all(|k| *k > 1e9), "{first:?}");
    d.deserialize_state(&saved).unwrap();
    for (i, k) in (4..8).enumerate() {
        d.do_step(k as f64 * h, h).unwrap();
        assert_eq!(d.get_real(var::STIFFNESS_2_2).unwrap().to_bits(), first[i].to_bits(), "step {k}");
    }
}
