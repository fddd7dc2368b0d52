//! The force of the bearing on a rigid housing (`housing.Fy`, `housing.Fz`): the rollers'
//! contact forces on the cup (and the cage land's), what a force sensor under the cup reads.
//! - Fidelity 0: it carries the applied radial load, as the cone's equilibrium says, but for the
//!   rollers' centrifugal forces (which cancel for equal rollers).
//! - Fidelity 1 under radial load: its mean carries the load, and it rings at the rollers' pass
//!   frequency through the load zone, Z times the cage's speed relative to the cup (the
//!   varying compliance of a healthy bearing), computed here from the cage speed the model
//!   outputs. Measured 2026-11-28 (TRB130x230, 3500 rpm, Fa 20 kN, Fy 40 kN, 0.1 s in 0.1 ms
//!   steps): mean 40 000.4 N, ripple ±12.7 N, peak at 437.6 Hz against 437.8 Hz of roller
//!   passes.

mod common;

use trb::simulation::Simulation;
use trb::variables as var;

const RPM: f64 = std::f64::consts::PI / 30.0;

fn element(fidelity: i32, fy: f64) -> Simulation {
    element_at(fidelity, 30e3, fy)
}

fn element_at(fidelity: i32, fx: f64, fy: f64) -> Simulation {
    let reals = [(var::SPEED, 3500.0 * RPM), (var::FX, fx), (var::FY, fy)];
    common::element("TRB130x230", &[(var::FIDELITY, fidelity)], &reals)
}

#[test]
fn the_housing_carries_the_radial_load_at_fidelity_0() {
    for fy in [5e3, 20e3, 60e3] {
        let mut s = element(0, fy);
        let o = s.outputs().unwrap();
        eprintln!("Fy {fy} N: housing.Fy {} N, housing.Fz {} N", o.housing_fy, o.housing_fz);
        assert!((o.housing_fy / fy - 1.0).abs() < 0.01, "{} against {fy}", o.housing_fy);
        assert!(o.housing_fz.abs() < 0.01 * fy);
    }
    // no radial load: the rollers' forces on the cup cancel
    let mut s = element(0, 0.0);
    let o = s.outputs().unwrap();
    assert!(o.housing_fy.abs() < 1e-6 * o.reaction_fx && o.housing_fz.abs() < 1e-6 * o.reaction_fx);
}

#[test]
fn the_housing_force_rings_at_the_roller_pass_frequency_at_fidelity_1() {
    let fy = 40e3;
    let mut s = element_at(1, 20e3, fy);
    let dt = 1e-4;
    let n = 1000;
    let (mut force, mut cage) = (Vec::with_capacity(n), 0.0);
    for k in 0..n {
        s.do_step(k as f64 * dt, dt).unwrap();
        let o = s.outputs().unwrap();
        force.push(o.housing_fy);
        cage += o.cage_speed / n as f64;
    }
    let mean = force.iter().sum::<f64>() / n as f64;
    let z = 17.0;
    let pass = z * cage / std::f64::consts::TAU;
    // the spectrum of the fluctuation around the mean, 100 Hz to 2 kHz, its peak refined
    let (peak, _) = common::peak(&force, dt, 100.0, 2000.0);
    let ripple = force.iter().fold(0.0_f64, |m, v| m.max((v - mean).abs()));
    eprintln!("housing.Fy mean {mean:.1} N (Fy {fy} N), ripple ±{ripple:.1} N; peak at {peak:.1} Hz, roller passes {pass:.1} Hz");
    assert!((mean / fy - 1.0).abs() < 0.01, "mean {mean}");
    assert!(ripple > 1e-4 * fy, "the load zone's rollers make the force ripple: {ripple}");
    assert!((peak / pass - 1.0).abs() < 0.01, "peak {peak} Hz against {pass} Hz");
}

/// The natural frequencies (Hz) of the cone (mass `m_c`, free radially) on the bearing's
/// radial stiffness `k_b` against the cup and housing (mass `m_h`) on its support `k_h`: the
/// two-mass chain's eigenvalues, ω² from det(K − ω² M) = 0.
fn chain_modes(m_c: f64, m_h: f64, k_b: f64, k_h: f64) -> (f64, f64) {
    // m_c m_h w^4 - (k_b m_h + (k_b + k_h) m_c) w^2 + k_b k_h = 0
    let (a, b, c) = (m_c * m_h, -(k_b * m_h + (k_b + k_h) * m_c), k_b * k_h);
    let root = (b * b - 4.0 * a * c).sqrt();
    let w2 = ((-b - root) / (2.0 * a), (-b + root) / (2.0 * a));
    let hz = |w2: f64| w2.sqrt() / std::f64::consts::TAU;
    (hz(w2.0), hz(w2.1))
}

/// The cup on a housing of 10 kg on the default support (1e9 N/m, 2000 N s/m), TRB130x230 at
/// 3500 rpm, Fx 20 kN, Fy 40 kN:
/// - it starts where the support carries the load: the first sample's acceleration is a
///   small part of Fy / m;
/// - running, its acceleration rings at the rollers' pass frequency through the load zone
///   (the kinematic Z f_s r_i / (r_i + r_o), within 1 %);
/// - after Fy steps to 30 kN the cone and the housing ring at the lower natural frequency of
///   the two-mass chain, cone on the bearing's radial stiffness (`stiffness[2,2]` of the
///   quasi-static model) and housing on its support. The rollers' mass, which the chain
///   leaves out, moves with the rings in that mode: the frequency lies between the chain's
///   without them and with all of them lumped into the cone (2 % margins).
#[test]
fn the_cup_on_its_housing_rings_at_the_roller_passes_and_at_its_natural_frequency() {
    use trb::bearing::Bearing;
    use trb::model::Parameters;
    let b = Bearing::preset("TRB130x230").unwrap();
    let g = trb::geometry::Geometry::new(&b, &trb::geometry::RollerProfile::of_bearing(&b));
    let mid = g.slices / 2;
    let (ri, ro) = (g.cone.raceway_radius[mid], g.cup.raceway_radius[mid]);
    let pass = 17.0 * 3500.0 / 60.0 * ri / (ri + ro);
    let reals = [
        (var::SPEED, 3500.0 * RPM),
        (var::FX, 20e3),
        (var::FY, 40e3),
        (var::HOUSING_MASS, 10.0),
    ];
    let mut s = common::element("TRB130x230", &[(var::FIDELITY, 1)], &reals);
    let first = s.outputs().unwrap().cup_ay;
    let dt = 5e-5;
    let n = 2000;
    let mut running = Vec::with_capacity(n);
    for k in 0..n {
        s.do_step(k as f64 * dt, dt).unwrap();
        running.push(s.outputs().unwrap().cup_ay);
    }
    let (f_pass, _) = common::peak(&running, dt, 0.8 * pass, 1.2 * pass);
    // the load step, then 40 ms at 50 kHz
    s.set_real(var::FY, 30e3).unwrap();
    let (t0, dt_ring) = (n as f64 * dt, 2e-5);
    let mut ringing = Vec::with_capacity(2000);
    for k in 0..2000 {
        s.do_step(t0 + k as f64 * dt_ring, dt_ring).unwrap();
        ringing.push(s.outputs().unwrap().cup_ay);
    }
    let (f_ring, _) = common::peak(&ringing, dt_ring, 200.0, 10e3);
    let k_b = common::solved("TRB130x230", &[(var::SPEED, 3500.0 * RPM), (var::FX, 20e3), (var::FY, 30e3)]).stiffness[6].abs();
    let m_c = Parameters::from_bearing(&b).cone_mass;
    let m_rollers = 17.0 * g.roller_mass;
    let (light, _) = chain_modes(m_c, 10.0, k_b, 1e9);
    let (heavy, _) = chain_modes(m_c + m_rollers, 10.0, k_b, 1e9);
    eprintln!(
        "first cup.ay {first:.3e} m/s2 (Fy / m = 4e3); running: peak {f_pass:.1} Hz against roller passes {pass:.1} Hz; after the step: peak {f_ring:.0} Hz, the chain's lower mode {heavy:.0} Hz with the rollers lumped into the cone, {light:.0} Hz without (cone {m_c:.2} kg, rollers {m_rollers:.2} kg, bearing {k_b:.3e} N/m)"
    );
    assert!(first.abs() < 0.01 * 4e3, "{first}");
    assert!((f_pass / pass - 1.0).abs() < 0.01, "{f_pass} Hz against {pass} Hz");
    assert!(
        f_ring > 0.98 * heavy && f_ring < 1.02 * light,
        "{f_ring} Hz against {heavy} to {light} Hz"
    );
}
