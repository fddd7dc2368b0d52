//! Helpers shared by the integration tests (`mod common;` in each test file that uses them).

use trb::bearing::Bearing;
use trb::simulation::Simulation;
use trb::variables as var;

/// The [W25] bearing as published (TRB130x230-W25: 3500 rpm, Fa 30 kN) at fidelity 1 with radial load `fy`,
/// integrated by `integrator` with `setting` as its tolerance (0, 2) or fixed step `maxStep`
/// (1), initialized at t = 0.
#[allow(dead_code)] // not every test file that includes `common` uses it
pub fn dynamic_element(integrator: i32, setting: f64, fy: f64) -> Simulation {
    let mut s = Simulation::new(Bearing::preset("TRB130x230-W25").unwrap());
    s.set_integer(var::FIDELITY, 1).unwrap();
    s.set_integer(var::INTEGRATOR, integrator).unwrap();
    if integrator == 1 {
        s.set_real(var::MAX_STEP, setting).unwrap();
    } else {
        s.set_real(var::TOLERANCE, setting).unwrap();
    }
    s.set_real(var::FY, fy).unwrap();
    s.initialize(0.0).unwrap();
    s
}

/// An element of `preset` with the Integer parameters `ints` and then the Real inputs and
/// parameters `reals` set (value reference, value), initialized at t = 0.
#[allow(dead_code)] // not every test file that includes `common` uses it
pub fn element(preset: &str, ints: &[(u32, i32)], reals: &[(u32, f64)]) -> Simulation {
    let mut s = Simulation::new(Bearing::preset(preset).unwrap());
    for &(vr, v) in ints {
        s.set_integer(vr, v).unwrap();
    }
    for &(vr, v) in reals {
        s.set_real(vr, v).unwrap();
    }
    s.initialize(0.0).unwrap();
    s
}

/// Outputs of a quasi-static element of `preset` initialized with the given Real inputs and
/// parameters (value reference, value).
#[allow(dead_code)] // not every test file that includes `common` uses it
pub fn solved(preset: &str, set: &[(u32, f64)]) -> trb::model::Outputs {
    element(preset, &[], set).outputs().unwrap().clone()
}

/// Amplitude of the Hann-windowed Fourier sum of `x` (sampled every `dt`, its mean removed) at
/// frequency `f`.
#[allow(dead_code)] // not every test file that includes `common` uses it
pub fn amplitude(x: &[f64], dt: f64, f: f64) -> f64 {
    let n = x.len();
    let mean = x.iter().sum::<f64>() / n as f64;
    let (mut c, mut s) = (0.0, 0.0);
    for (k, v) in x.iter().enumerate() {
        let w = 0.5 - 0.5 * (std::f64::consts::TAU * k as f64 / (n - 1) as f64).cos();
        let (si, co) = (std::f64::consts::TAU * f * k as f64 * dt).sin_cos();
        c += w * (v - mean) * co;
        s += w * (v - mean) * si;
    }
    c.hypot(s)
}

/// The spectrum's largest peak between `lo` and `hi` (Hz) of `x` (sampled every `dt`),
/// refined by a parabola through the log magnitudes of the three bins around it, and its
/// amplitude.
#[allow(dead_code)] // not every test file that includes `common` uses it
pub fn peak(x: &[f64], dt: f64, lo: f64, hi: f64) -> (f64, f64) {
    let df = 1.0 / (x.len() as f64 * dt);
    let bins: Vec<f64> = (1..=(hi / df) as usize + 1)
        .map(|k| k as f64 * df)
        .filter(|f| *f >= lo - df)
        .collect();
    let a: Vec<f64> = bins.iter().map(|f| amplitude(x, dt, *f)).collect();
    let k = (1..a.len() - 1).max_by(|i, j| a[*i].total_cmp(&a[*j])).unwrap();
    let (l, m, r) = (a[k - 1].ln(), a[k].ln(), a[k + 1].ln());
    (bins[k] + 0.5 * (l - r) / (l - 2.0 * m + r) * df, a[k])
}
