//! The roller's skew against the rib's closed form (docs/dynamic.md, "The roller skew mode").
//!
//! The rib's normal force passes through the end-sphere centre P and, the rib being a surface
//! of revolution, through the point A where the contact normal meets the bearing axis. A skew
//! phi carries P sideways by d phi (d = |OP|, O the middle of the contact lines, where the
//! raceways' reactions act) and turns the force line about A (e = |PA| = rho_p - R_s, rho_p
//! the rib's circumferential radius of curvature). The restoring stiffness is
//! K = Q_f d (n_a + d / e): the towed trailer Q_f d n_a (n_a = cos beta, beta the angle of the
//! contact normal to the roller axis) and the pendulum Q_f d^2 / e. The rib's Coulomb friction
//! mu_f Q_f, along the rolling direction at the contact, drives with the lever L_f of the
//! contact from O along the roller axis, L_f = l/2 - R_s (1 - cos beta). So
//! phi = mu_f L_f e / (d (n_a e + d)), independent of the load.
//!
//! The bearings are 32008 ([L22]; apex-consistent to 0.6 % in its roller half-angle) with its
//! end radius given as R_s / rho_p through `rollers.end_radius_ratio` in a bearing file the
//! test writes, the raceways lubricated as the preset says and the rib in Coulomb friction
//! (`flange.mu`). d, e, L_f and beta come from the file's numbers and the geometry's formulas
//! written out here, not from the model's geometry code.

use std::f64::consts::PI;
use trb::bearing::Bearing;
use trb::simulation::Simulation;
use trb::variables as var;

const RPM: f64 = PI / 30.0;

/// The closed form's lengths for a bearing file (mm and degrees as the file gives them).
#[derive(Debug, Clone, Copy)]
struct Rib {
    /// Sphere centre from the middle of the roller, along its axis (m).
    d: f64,
    /// Sphere centre to the rib normal's point on the bearing axis (m).
    e: f64,
    /// Lever of the rib friction about the middle of the roller (m).
    lever: f64,
    /// cos of the contact normal's angle to the roller axis.
    n_a: f64,
}

impl Rib {
    fn of(file: &serde_json::Value) -> Rib {
        let num = |v: &serde_json::Value| v.as_f64().expect("a number");
        let mm = 1e-3;
        let r = &file["rollers"];
        let l = num(&r["length_mm"]) * mm;
        let dm = num(&file["pitch_diameter_mm"]) * mm;
        let (ai, ao) = (num(&file["cone_angle_deg"]).to_radians(), num(&file["cup_angle_deg"]).to_radians());
        // roller axis angle to the bearing axis: the mean of cone and cup angles
        let axis = 0.5 * (ai + ao);
        // flange contact angle to the radial plane from [L22]'s angle of the rib face to the
        // roller axis: the normal leans (pi/2 - face) off the roller axis
        let face = num(&file["flange"]["face_to_roller_axis_rad"]);
        let af = PI / 2.0 - axis + (PI / 2.0 - face);
        let beta = af - (PI / 2.0 - axis);
        // the contact's distance from the bearing axis for end radius R_s (sphere centre on the
        // roller axis, R_s from the large end at the pitch station minus l/2):
        // r_f = dm/2 + (l/2) sin(axis) + R_s (cos af - sin axis), rho_p = r_f / cos af
        let r_f = |rs: f64| 0.5 * dm + 0.5 * l * axis.sin() + rs * (af.cos() - axis.sin());
        let k = num(&r["end_radius_ratio"]);
        // R_s = k rho_p(R_s): linear in R_s
        let c = k / af.cos();
        let rs = c * r_f(0.0) / (1.0 - c * (af.cos() - axis.sin()));
        let rho_p = r_f(rs) / af.cos();
        assert!((rs / rho_p - k).abs() < 1e-12);
        Rib {
            d: rs - 0.5 * l,
            e: rho_p - rs,
            lever: 0.5 * l - rs * (1.0 - beta.cos()),
            n_a: beta.cos(),
        }
    }

    /// The equilibrium skew (rad) at rib friction coefficient `mu_f`.
    fn skew(&self, mu_f: f64) -> f64 {
        mu_f * self.lever * self.e / (self.d * (self.n_a * self.e + self.d))
    }
}

/// 32008's bearing file with `rollers.end_radius_ratio` = `k`, written to a temporary file and
/// read back as a user's file is; with the file's JSON.
fn bearing(k: f64) -> (Bearing, serde_json::Value) {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/32008.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["rollers"]["end_radius_ratio"] = serde_json::json!(k);
    let path = std::env::temp_dir().join(format!("trb-skew-32008-{k}-{}.json", std::process::id()));
    std::fs::write(&path, v.to_string()).unwrap();
    let b = Bearing::from_name_or_file(path.to_str().unwrap()).unwrap();
    let _ = std::fs::remove_file(&path);
    (b, v)
}

/// 1500 rpm, axial load `fa`, the rib at Coulomb `mu_f`. Fidelity 1 starts from the
/// quasi-static seat with the rollers unskewed (`startSteady` off), so that its skew is what
/// its rollers' dynamics settle to, not its steady solver's answer.
fn element(b: Bearing, fidelity: i32, fa: f64, mu_f: f64) -> Simulation {
    let mut s = Simulation::new(b);
    s.set_integer(var::FIDELITY, fidelity).unwrap();
    s.set_real(var::SPEED, 1500.0 * RPM).unwrap();
    s.set_real(var::FX, fa).unwrap();
    s.set_real(var::FLANGE_MU, mu_f).unwrap();
    if fidelity == 1 {
        s.set_boolean(var::START_STEADY, false).unwrap();
    }
    s.initialize(0.0).unwrap();
    s
}

/// Mean signed skew over the rollers.
fn mean_skew(s: &mut Simulation) -> f64 {
    let o = s.outputs().unwrap();
    o.skew.iter().sum::<f64>() / o.skew.len() as f64
}

/// Fidelity 2: 1 ms steps until the mean skew changes by less than 0.1 % in a step (at most
/// 20 steps).
fn quasi_dynamic(k: f64, fa: f64, mu_f: f64) -> f64 {
    let mut s = element(bearing(k).0, 2, fa, mu_f);
    let h = 1e-3;
    let mut last = f64::NAN;
    for n in 0..20 {
        s.do_step(n as f64 * h, h).unwrap();
        let phi = mean_skew(&mut s);
        if (phi - last).abs() < 1e-3 * phi.abs() {
            return phi;
        }
        last = phi;
    }
    panic!("fidelity 2, R_s/rho_p {k}, mu_f {mu_f}: the skew has not settled in 20 ms ({last} rad)");
}

/// Fidelity 1 from the unskewed seat: 10 ms to settle (the skew reaches its level in about
/// 5 ms, the skew mode being damped by the raceways' traction), then the mean over 10 ms
/// sampled every 0.5 ms; with the largest deviation of a sample from that mean.
fn dynamic(k: f64, mu_f: f64) -> (f64, f64) {
    let mut s = element(bearing(k).0, 1, 4000.0, mu_f);
    let h = 5e-4;
    let mut t = 0.0;
    for _ in 0..20 {
        s.do_step(t, h).unwrap();
        t += h;
    }
    let mut samples = Vec::new();
    for _ in 0..20 {
        s.do_step(t, h).unwrap();
        t += h;
        samples.push(mean_skew(&mut s));
    }
    let mean = samples.iter().sum::<f64>() / samples.len() as f64;
    let spread = samples.iter().fold(0.0_f64, |m, v| m.max((v - mean).abs()));
    (mean, spread)
}

const RATIOS: [f64; 3] = [0.75, 0.85, 0.95];
const MUS: [f64; 3] = [0.05, 0.10, 0.15];

/// Both dynamic fidelities over R_s / rho_p = 0.75, 0.85, 0.95 and mu_f = 0.05, 0.10, 0.15 at
/// 1500 rpm, Fa 4 kN (the whole grid: fidelity 2 settles in a few steps, fidelity 1 runs
/// 20 ms in about half a second a point).
///
/// Measured (2026-12-03): fidelity 2 at 0.94-1.11 of the closed form, fidelity 1 at
/// 0.98-1.11. What the closed form leaves out:
/// - the raceways' own traction drive: with the rib frictionless (`flange.mu` = 0) the
///   rollers still skew by 0.0006-0.0035 deg at 4 kN (0.007-0.03 deg at 8 kN), which is most
///   of the excess at mu_f = 0.05;
/// - the skewed roller's axial sliding on the raceways, whose traction pushes it against the
///   rib (Q_f 37 N unskewed, 79-110 N at mu_f = 0.1) and, with the skew's tilt couple, bends
///   the growth below linear: the model's rise from mu_f = 0.05 to 0.15 is 0.86-0.90 of the
///   closed form's.
/// The bound, 25 %, holds those with margin; the skew's rise with mu_f, which the raceway
/// drive does not share, is held to the same bound.
#[test]
fn the_skew_meets_the_ribs_closed_form_at_both_dynamic_fidelities() {
    for k in RATIOS {
        let rib = Rib::of(&bearing(k).1);
        let mut quasi = Vec::new();
        for mu_f in MUS {
            let closed = rib.skew(mu_f);
            let q = quasi_dynamic(k, 4000.0, mu_f);
            let (d, spread) = dynamic(k, mu_f);
            println!(
                "R_s/rho_p {k}, mu_f {mu_f}: closed form {:.5} deg, fidelity 2 {:.5} deg ({:.3}), fidelity 1 {:.5} deg ({:.3})",
                closed.to_degrees(),
                q.to_degrees(),
                q / closed,
                d.to_degrees(),
                d / closed
            );
            assert!(
                (q / closed - 1.0).abs() < 0.25,
                "fidelity 2, R_s/rho_p {k}, mu_f {mu_f}: {q} rad against {closed} rad"
            );
            assert!(
                (d / closed - 1.0).abs() < 0.25,
                "fidelity 1, R_s/rho_p {k}, mu_f {mu_f}: {d} rad against {closed} rad"
            );
            // settled: the window's samples stay within 1 % of its mean
            assert!(
                spread < 0.01 * d.abs(),
                "fidelity 1, R_s/rho_p {k}, mu_f {mu_f}: not settled, {spread} rad about {d} rad"
            );
            quasi.push(q);
        }
        let rise = (quasi[2] - quasi[0]) / (rib.skew(MUS[2]) - rib.skew(MUS[0]));
        assert!(
            (rise - 1.0).abs() < 0.25,
            "R_s/rho_p {k}: the skew rises {rise} of the closed form's with mu_f"
        );
    }
}

/// The rib's share of the equilibrium skew is set by its geometry and friction, not by the
/// load: at fidelity 2, Fa 2 and 8 kN (the rib load 30-160 N), the skew at mu_f = 0.1 less the
/// skew with a frictionless rib (the raceways' own traction drive, which the closed form leaves
/// out and which grows with the load: up to 0.03 deg at 8 kN, more than the closed form's
/// 0.018 deg at R_s/rho_p = 0.95) is the closed form's within 25 % (measured 2026-12-03: 0.99-1.00 of
/// it at 2 kN, 0.79-0.85 at 8 kN, where the rib load has grown and the skew is no longer a sum).
#[test]
fn the_ribs_share_of_the_skew_does_not_follow_the_load() {
    for k in RATIOS {
        let rib = Rib::of(&bearing(k).1);
        for fa in [2000.0, 8000.0] {
            let share = quasi_dynamic(k, fa, 0.1) - quasi_dynamic(k, fa, 0.0);
            let ratio = share / rib.skew(0.1);
            println!("R_s/rho_p {k}, Fa {fa} N: the rib's share at fidelity 2 at {ratio:.3} of the closed form");
            assert!((ratio - 1.0).abs() < 0.25, "R_s/rho_p {k}, Fa {fa} N: {ratio}");
        }
    }
}

/// The product's own closed form (`Geometry::rib_skew`, which the docs' tables use) is the
/// one written out here from the bearing file.
#[test]
fn the_geometrys_closed_form_is_the_files() {
    for k in RATIOS {
        let (b, file) = bearing(k);
        let g = trb::geometry::Geometry::new(&b, &trb::geometry::RollerProfile::of_bearing(&b));
        let own = g.rib_skew(b.roller_end_radius, 0.1).expect("a rib");
        let here = Rib::of(&file).skew(0.1);
        assert!((own / here - 1.0).abs() < 1e-9, "R_s/rho_p {k}: {own} against {here}");
    }
}

/// `flange.mu` is the rib's Coulomb coefficient at fidelity 0 too: the rib's friction torque
/// is proportional to it (the quasi-static rib load does not depend on friction), and it is
/// refused outside [-1, 2].
#[test]
fn flange_mu_is_the_ribs_coulomb_coefficient_at_fidelity_0() {
    let torque = |mu_f: f64| {
        let mut s = element(bearing(0.9).0, 0, 4000.0, mu_f);
        s.do_step(0.0, 1e-3).unwrap();
        s.outputs().unwrap().friction_torque_flange
    };
    let (a, b) = (torque(0.05), torque(0.1));
    assert!(a > 0.0 && (b / a - 2.0).abs() < 1e-9, "{a} {b}");
    for bad in [2.5, -1.5] {
        let mut s = Simulation::new(bearing(0.9).0);
        s.set_real(var::FLANGE_MU, bad).unwrap();
        match s.initialize(0.0) {
            Err(trb::model::ModelError::InvalidParameter { name, .. }) => assert_eq!(name, "flange.mu"),
            other => panic!("flange.mu = {bad}: {other:?}"),
        }
    }
}

/// Fidelity 0's skew model (`skewModel`, after [D19], whose moment balance has no pendulum
/// term) holds the rib's towed-trailer term Q_f d n_a alone: with the raceways frictionless
/// (`mu` = 0, its raceways are Coulomb's) and the rib at mu_f = 0.1 its skew is
/// mu_f L_f / (d n_a), which is (n_a e + d) / (n_a e) times the closed form: 3.8 times at
/// R_s/rho_p = 0.75, 19 times at 0.95 (measured 2026-12-03: its own form to 0.1 %).
#[test]
fn fidelity_0_holds_the_trailer_term_alone() {
    for k in RATIOS {
        let rib = Rib::of(&bearing(k).1);
        let mut s = Simulation::new(bearing(k).0);
        s.set_boolean(var::SKEW_MODEL, true).unwrap();
        s.set_real(var::SPEED, 1500.0 * RPM).unwrap();
        s.set_real(var::FX, 4000.0).unwrap();
        s.set_real(var::MU, 0.0).unwrap();
        s.set_real(var::FLANGE_MU, 0.1).unwrap();
        s.initialize(0.0).unwrap();
        s.do_step(0.0, 1e-3).unwrap();
        let phi = mean_skew(&mut s);
        let trailer = 0.1 * rib.lever / (rib.d * rib.n_a);
        println!(
            "R_s/rho_p {k}: fidelity 0 {:.4} deg, its trailer-only form {:.4} deg, the closed form {:.4} deg",
            phi.to_degrees(),
            trailer.to_degrees(),
            rib.skew(0.1).to_degrees()
        );
        assert!((phi / trailer - 1.0).abs() < 0.01, "R_s/rho_p {k}: {phi} against {trailer}");
        let over = (rib.n_a * rib.e + rib.d) / (rib.n_a * rib.e);
        assert!((phi / rib.skew(0.1) / over - 1.0).abs() < 0.01);
    }
}
