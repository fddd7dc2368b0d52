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
    // the spectrum of the fluctuation around the mean, 100 Hz to 2 kHz, its peak refined by a
    // parabola through the log magnitudes of the three bins around it
    let amplitude = |f: f64| common::amplitude(&force, dt, f);
    let df = 1.0 / (n as f64 * dt);
    let bins: Vec<f64> = (1..=(2000.0 / df) as usize)
        .map(|k| k as f64 * df)
        .filter(|f| *f >= 100.0)
        .collect();
    let spectrum: Vec<f64> = bins.iter().map(|f| amplitude(*f)).collect();
    let k = (1..spectrum.len() - 1)
        .max_by(|a, b| spectrum[*a].total_cmp(&spectrum[*b]))
        .unwrap();
    let (a, b, c) = (spectrum[k - 1].ln(), spectrum[k].ln(), spectrum[k + 1].ln());
    let peak = bins[k] + 0.5 * (a - c) / (a - 2.0 * b + c) * df;
    let ripple = force.iter().fold(0.0_f64, |m, v| m.max((v - mean).abs()));
    eprintln!("housing.Fy mean {mean:.1} N (Fy {fy} N), ripple ±{ripple:.1} N; peak at {peak:.1} Hz, roller passes {pass:.1} Hz");
    assert!((mean / fy - 1.0).abs() < 0.01, "mean {mean}");
    assert!(ripple > 1e-4 * fy, "the load zone's rollers make the force ripple: {ripple}");
    assert!((peak / pass - 1.0).abs() < 0.01, "peak {peak} Hz against {pass} Hz");
}
