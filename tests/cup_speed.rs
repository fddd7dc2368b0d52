//! Either ring may rotate: the input `cupSpeed` turns the cup.
//!
//! Seen from the cup, a bearing whose rings both turn is one with a standing cup and the cone
//! at the relative speed omega_i - omega_o: the rolling and sliding speeds, traction and
//! dissipation follow that relative speed alone. Only the inertial loads see the absolute
//! speeds: the rollers' centrifugal force follows the cage (orbit) speed omega_c =
//! omega_o + c (omega_i - omega_o), the gyroscopic moment the orbit and the spin. The tests
//! check exactly that: identical friction with the inertial loads switched off, differences
//! bounded by the change of the centrifugal force with them on.
//!
//! Case: the default bearing (TRB130x230, [W25]: 3500 rpm, Fx = 30 kN) with Fy = 10 kN.

use std::f64::consts::PI;
use trb::bearing::Bearing;
use trb::model::Parameters;
use trb::quasi_static::QuasiStatic;
use trb::simulation::Simulation;
use trb::variables as var;

/// 3500 rpm (rad/s).
const W: f64 = 3500.0 * PI / 30.0;
const FY: f64 = 10e3;

/// Outputs of one solve or run.
#[derive(Debug, Clone, Copy)]
struct Out {
    torque: f64,
    power: f64,
    cage: f64,
    cone: f64,
    cup: f64,
    qi_max: f64,
    qo_max: f64,
}

fn read(s: &mut Simulation) -> Out {
    let mut g = |v| s.get_real(v).unwrap();
    Out {
        torque: g(var::FRICTION_TORQUE),
        power: g(var::POWER_LOSS),
        cage: g(var::CAGE_SPEED),
        cone: g(var::FRICTION_TORQUE_CONE),
        cup: g(var::FRICTION_TORQUE_CUP),
        qi_max: g(var::QI_MAX),
        qo_max: g(var::QO_MAX),
    }
}

/// The element at `fidelity` with cone speed `cone` and cup speed `cup` (rad/s), initialized.
fn element(fidelity: i32, cone: f64, cup: f64, configure: impl Fn(&mut Simulation)) -> Simulation {
    let mut s = Simulation::new(Bearing::default_preset());
    s.set_integer(var::FIDELITY, fidelity).unwrap();
    s.set_real(var::FY, FY).unwrap();
    s.set_real(var::SPEED, cone).unwrap();
    s.set_real(var::CUP_SPEED, cup).unwrap();
    configure(&mut s);
    s.initialize(0.0).unwrap();
    s
}

/// Quasi-static outputs at (cone, cup), with `configure` applied to the parameters.
fn qs(cone: f64, cup: f64, configure: impl Fn(&mut Simulation)) -> Out {
    read(&mut element(0, cone, cup, configure))
}

fn no_inertia(s: &mut Simulation) {
    s.set_boolean(var::CENTRIFUGAL, false).unwrap();
    s.set_boolean(var::GYROSCOPIC, false).unwrap();
}

/// (cage ratio with the slip rate, cage ratio of pure rolling, roller mass times the orbit
/// radius of its centre of mass) of the default bearing.
fn kinematics() -> (f64, f64, f64) {
    let b = Bearing::default_preset();
    let p = Parameters::from_bearing(&b);
    let g = QuasiStatic::new(&b, &p).unwrap().geometry;
    let (ri, ro) = g.pitch_contact_radii();
    let pure = ri / (ri + ro);
    (
        (1.0 - p.cage_slip_rate) * pure,
        pure,
        g.roller_mass * (g.center[1] + g.cm_offset * g.axis[1]),
    )
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn rotating_cup_with_standing_cone_mirrors_the_rotating_cone() {
    let (c, _, m_r) = kinematics();
    let cone = qs(W, 0.0, |_| {});
    // the cup turning backwards: the cone turns at +W relative to it, as in the cone case
    let cup = qs(0.0, -W, |_| {});
    // epicyclic cage speed with the slip on the relative part: omega_o + c (0 - omega_o),
    // with no slip omega_o r_o / (r_i + r_o)
    let expected = -W + c * W;
    assert!(rel(cup.cage, expected) < 1e-12, "cage {} vs {expected}", cup.cage);
    assert!(rel(cone.cage, c * W) < 1e-12);
    assert!(cup.torque > 0.0 && cup.power > 0.0 && cup.cone > 0.0 && cup.cup > 0.0, "{cup:?}");
    // power = torque between the rings x relative speed
    assert!(rel(cup.power, cup.torque * W) < 1e-12);
    // Inertial loads off: the contact kinematics are those of the cone case exactly.
    let cone_0 = qs(W, 0.0, no_inertia);
    let cup_0 = qs(0.0, -W, no_inertia);
    assert_eq!(cup_0.torque, cone_0.torque);
    assert_eq!(cup_0.power, cone_0.power);
    assert_eq!((cup_0.cone, cup_0.cup), (cone_0.cone, cone_0.cup));
    // Inertial loads on: the cage orbits at |-W + c W| instead of c W, the centrifugal force
    // grows by dFc = m r (omega_c,cup^2 - omega_c,cone^2) and shifts at most that much load
    // between the contacts of a roller; friction about proportional to load, the loss moves
    // by less than dFc over the roller load. It does move (the inertial loads are there).
    let d_fc = m_r * (expected * expected - (c * W) * (c * W));
    let bound = d_fc / cone.qo_max;
    let d_p = rel(cup.power, cone.power);
    println!(
        "dFc = {d_fc:.1} N, bound {bound:.4}; power {:.1} vs {:.1} W: {d_p:.4}",
        cup.power, cone.power
    );
    assert!(d_p < bound && d_p > 1e-6, "{d_p} vs {bound}");
    assert!(rel(cup.torque, cone.torque) < bound);
    assert!(cup.qi_max < cone.qi_max, "more centrifugal force unloads the cone");
    // The cup turning forwards: the cone turns backwards relative to it; the torque changes
    // sign with the relative speed, the loss stays positive, the same.
    let fwd = qs(0.0, W, |_| {});
    assert_eq!(fwd.torque, -cup.torque);
    assert_eq!(fwd.power, cup.power);
    assert_eq!(fwd.cage, -cup.cage);
}

#[test]
fn rings_turning_together_do_not_roll_and_lose_nothing() {
    for lubrication in [0, 1] {
        let lub = |s: &mut Simulation| s.set_integer(var::LUBRICATION, lubrication).unwrap();
        let together = qs(W, W, lub);
        let cone = qs(W, 0.0, lub);
        // no relative rolling, no sliding: no dissipation at all; the cage turns with the rings
        assert_eq!(together.power, 0.0, "lubrication {lubrication}");
        assert!(rel(together.cage, W) < 1e-12);
        assert!(cone.power > 1e3);
        // the centrifugal force of the rollers orbiting at W is still there: it unloads the
        // cone more than at the cone speed alone (orbit c W)
        assert!(together.qi_max < cone.qi_max - 500.0, "{together:?} {cone:?}");
        // The torque between the rings is the one at zero relative speed, as at standstill:
        // dry friction regularised to zero; the EHL boundary law finite, the limit of creep.
        if lubrication == 1 {
            assert_eq!((together.torque, together.cone, together.cup), (0.0, 0.0, 0.0));
        } else {
            let creep = qs(W + 1e-6, W, lub);
            assert!(together.torque > 0.0);
            assert!(
                (creep.torque - together.torque).abs() < 1e-3 * together.torque,
                "{creep:?} {together:?}"
            );
        }
        // without the inertial loads the rings turning together are the bearing at rest
        let together_0 = qs(W, W, |s| {
            lub(s);
            no_inertia(s)
        });
        let rest_0 = qs(0.0, 0.0, |s| {
            lub(s);
            no_inertia(s)
        });
        assert_eq!(together_0.torque, rest_0.torque);
        assert_eq!((together_0.cone, together_0.cup), (rest_0.cone, rest_0.cup));
        assert_eq!(together_0.power, 0.0);
    }
}

#[test]
fn turning_the_whole_bearing_slowly_changes_only_the_inertial_loads() {
    // Galilean check: cone W, cup 0 against cone W + Omega, cup Omega at a low Omega.
    let (c, _, m_r) = kinematics();
    let omega = 10.0;
    let base = qs(W, 0.0, |_| {});
    let moved = qs(W + omega, omega, |_| {});
    assert!(rel(moved.cage, base.cage + omega) < 1e-12);
    // the orbit goes from c W to c W + Omega: dFc = m r ((c W + Omega)^2 - (c W)^2)
    let d_fc = m_r * ((c * W + omega).powi(2) - (c * W).powi(2));
    let bound = d_fc / base.qo_max;
    let (d_t, d_p) = (rel(moved.torque, base.torque), rel(moved.power, base.power));
    println!("dFc = {d_fc:.1} N, bound {bound:.4}: torque {d_t:.2e}, power {d_p:.2e}");
    assert!(d_t < bound && d_p < bound, "{d_t} {d_p} vs {bound}");
    // without the inertial loads only the rounding of (W + Omega) - Omega remains
    let base_0 = qs(W, 0.0, no_inertia);
    let moved_0 = qs(W + omega, omega, no_inertia);
    assert!(rel(moved_0.torque, base_0.torque) < 1e-9);
    assert!(rel(moved_0.power, base_0.power) < 1e-9);
}

#[test]
fn skew_model_follows_the_relative_speed() {
    // the dry skew model of [D19] on its own case (32018X, Fr = 35 kN, 60 rpm) with the cup
    // turning: the same friction as the cone case without inertial loads
    let skew = |cone: f64, cup: f64| {
        let mut s = Simulation::new(Bearing::preset("32018X").unwrap());
        s.set_boolean(var::SKEW_MODEL, true).unwrap();
        s.set_integer(var::LUBRICATION, 1).unwrap();
        no_inertia(&mut s);
        s.set_real(var::SPEED, cone).unwrap();
        s.set_real(var::CUP_SPEED, cup).unwrap();
        s.initialize(0.0).unwrap();
        read(&mut s)
    };
    let w = 60.0 * PI / 30.0;
    let cone = skew(w, 0.0);
    let cup = skew(0.0, -w);
    assert!(cone.power > 0.0);
    assert_eq!(cup.torque, cone.torque);
    assert_eq!(cup.power, cone.power);
    assert_eq!(cup.cage, cone.cage - w);
}

#[test]
fn lobed_turning_cup_is_refused_by_name() {
    let mut s = Simulation::new(Bearing::default_preset());
    s.set_integer(var::OUTER_LOBES, 3).unwrap();
    s.set_real(var::OUTER_WAVEFORM, 2e-6).unwrap();
    s.set_real(var::CUP_SPEED, 10.0).unwrap();
    let e = s.initialize(0.0).unwrap_err().to_string();
    assert!(e.contains("cupSpeed"), "{e}");
    let mut s = Simulation::new(Bearing::default_preset());
    assert!(s.set_real(var::CUP_SPEED, f64::NAN).is_err() || s.initialize(0.0).is_err());
}

/// Dynamic run of `ms` communication steps of 1 ms; the outputs after each.
fn run(cone: f64, cup: f64, ms: usize, configure: impl Fn(&mut Simulation)) -> Vec<Out> {
    let mut s = element(1, cone, cup, configure);
    (0..ms)
        .map(|k| {
            s.do_step(k as f64 * 1e-3, 1e-3).unwrap();
            read(&mut s)
        })
        .collect()
}

#[test]
fn dynamic_cage_follows_a_turning_cup_at_the_epicyclic_speed() {
    let (_, pure, _) = kinematics();
    let cone = run(W, 0.0, 5, |_| {});
    let cup = run(0.0, -W, 5, |_| {});
    for (a, b) in cone.iter().zip(&cup) {
        // dissipation is never negative; the cup case's close to the cone case's (the
        // centrifugal force differs, as in the quasi-static model: about 1 %)
        assert!(b.power > 0.0 && a.power > 0.0);
        assert!(rel(b.power, a.power) < 0.03, "{} vs {}", b.power, a.power);
    }
    let (a, b) = (cone.last().unwrap(), cup.last().unwrap());
    // the cage relative to the cup orbits at the pure-rolling share of the relative speed
    // (the rollers' traction sets it; a little less under the cage's drag)
    let relative = b.cage - (-W);
    println!(
        "cage relative to the cup {relative:.4} (cone case {:.4}), pure rolling {:.4}",
        a.cage,
        pure * W
    );
    assert!(rel(relative, pure * W) < 0.02);
    assert!(rel(relative, a.cage) < 0.01);
    assert!(b.torque > 0.0);
}

#[test]
fn dynamic_rings_turning_together_stay_at_rest_relative_to_each_other() {
    // zero relative speed: the regularised friction is stiff, the linearly implicit
    // Rosenbrock-W integrator steps over it. The cage (dynamic, on its land) turns with the
    // rings: its land film, taken in the cup's frame, shears nothing (taken in the fixed
    // frame it would drag the cage at 36 m/s: 445 W and a lagging cage, which this fails on)
    let rosenbrock = |s: &mut Simulation| s.set_integer(var::INTEGRATOR, 2).unwrap();
    let together = run(W, W, 3, rosenbrock);
    let cone = run(W, 0.0, 3, rosenbrock);
    for (t, c) in together.iter().zip(&cone) {
        println!(
            "together: P {:.3e} W, T {:.3e} N m, cage {:.6}; cone: P {:.3e} W, T {:.3e} N m",
            t.power, t.torque, t.cage, c.power, c.torque
        );
        assert!(rel(t.cage, W) < 1e-3);
        assert!(t.power >= 0.0 && t.power < 1e-4 * c.power);
        assert!(t.torque.abs() < 0.1 * c.torque);
    }
}
