//! The operating cases of the three quasi-static studies [D19], [L22], [Y22] as functions of
//! the product: each case is one quasi-static solve of a preset with the study's parameters
//! and inputs (the same model the FMU runs). `trb study` turns them into tables and plots
//! (docs/results-studies.md); tests/studies.rs checks the studies' stated trends on them.

use super::QuasiStatic;
use crate::bearing::Bearing;
use crate::model::{Inputs, Lubrication, ModelError, Outputs, Parameters, Preload};
use std::f64::consts::PI;

/// rpm to rad/s.
pub fn rpm(n: f64) -> f64 {
    n * PI / 30.0
}

/// Solve one case: preset `name`, parameters and inputs changed by `edit`, roller 1 at `cage_angle`.
pub fn solve_case(name: &str, cage_angle: f64, edit: impl FnOnce(&mut Parameters, &mut Inputs)) -> Result<Outputs, ModelError> {
    let b = Bearing::preset(name).map_err(|e| ModelError::InvalidParameter {
        name: "bearing".into(),
        message: e.to_string(),
    })?;
    let mut p = Parameters::from_bearing(&b);
    let mut i = Inputs::from_bearing(&b);
    edit(&mut p, &mut i);
    p.validate(&b)?;
    i.validate(&b, &p)?;
    let mut qs = QuasiStatic::new(&b, &p)?;
    let mut out = Outputs::new(b.roller_count);
    let mut warm = Vec::new();
    qs.solve(&i, cage_angle, &mut warm, &mut out)?;
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// [D19] 32018X, dry, skew model
// ---------------------------------------------------------------------------------------------

/// The [D19] axial preloads: force 12,970 N or displacement 0.01 mm.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum D19Preload {
    Force,
    Displacement,
}

impl D19Preload {
    pub fn label(self) -> &'static str {
        match self {
            D19Preload::Force => "force preload 12,970 N",
            D19Preload::Displacement => "displacement preload 0.01 mm",
        }
    }
}

/// Friction coefficients of the [D19] sweep.
pub const D19_MU: [f64; 15] = [0.005, 0.01, 0.02, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.55, 0.6];
/// Pocket clearances of the [D19] sweep (m).
pub const D19_POCKET: [f64; 16] = [
    0.3e-3, 0.4e-3, 0.5e-3, 0.6e-3, 0.7e-3, 0.8e-3, 0.9e-3, 1.0e-3, 1.1e-3, 1.2e-3, 1.3e-3, 1.4e-3, 1.5e-3, 1.6e-3, 1.7e-3, 1.8e-3,
];

/// One [D19] case: 32018X dry, skew model, radial 35 kN, 60 rpm, friction `mu`, pocket clearance `pocket`.
pub fn d19(preload: D19Preload, mu: f64, pocket: f64) -> Result<Outputs, ModelError> {
    solve_case("32018X", 0.0, |p, i| {
        p.skew_model = true;
        p.lubrication = Lubrication::Dry;
        p.mu = mu;
        p.pocket_clearance = pocket;
        i.speed = rpm(60.0);
        i.fy = 35_000.0;
        i.fz = 0.0;
        match preload {
            D19Preload::Force => {
                p.preload = Preload::Force;
                i.fx = 12_970.0;
            }
            D19Preload::Displacement => {
                p.preload = Preload::Displacement;
                i.axial_displacement = 0.01e-3;
            }
        }
    })
}

// ---------------------------------------------------------------------------------------------
// [L22] 32008, roller diameter deviations
// ---------------------------------------------------------------------------------------------

/// Roller diameter deviations of ../shared/data/roller_deviations_32008.csv (um), series 1..6:
/// Sd = 0.5, 0.5, 1.0, 1.0, 1.5, 1.5 um; odd series in random order, even series sorted in
/// descending order around the cage.
pub const L22_SERIES_UM: [[f64; 23]; 6] = [
    [
        0.28, 0.52, -0.56, 0.63, 0.33, -0.03, -0.10, -0.11, -0.15, 0.01, 0.03, 0.41, 0.76, 0.23, -0.10, 0.31, 0.09, -0.51, 0.47, 0.15,
        0.07, 0.26, 0.13,
    ],
    [
        0.76, 0.63, 0.52, 0.47, 0.41, 0.33, 0.31, 0.28, 0.26, 0.23, 0.15, 0.13, 0.09, 0.07, 0.03, 0.01, -0.03, -0.10, -0.10, -0.11, -0.15,
        -0.51, -0.56,
    ],
    [
        0.55, 1.04, -1.12, 1.26, 0.66, -0.07, -0.20, -0.22, -0.30, 0.02, 0.05, 0.83, 1.53, 0.47, -0.21, 0.63, 0.18, -1.03, 0.95, 0.31,
        0.14, 0.52, 0.26,
    ],
    [
        1.53, 1.26, 1.04, 0.95, 0.83, 0.66, 0.63, 0.55, 0.52, 0.47, 0.31, 0.26, 0.18, 0.14, 0.05, 0.02, -0.07, -0.20, -0.21, -0.22, -0.30,
        -1.03, -1.12,
    ],
    [
        0.83, 1.56, -1.68, 1.89, 0.99, -0.10, -0.29, -0.33, -0.45, 0.03, 0.08, 1.24, 2.29, 0.70, -0.31, 0.94, 0.27, -1.54, 1.42, 0.46,
        0.20, 0.77, 0.39,
    ],
    [
        2.29, 1.89, 1.56, 1.42, 1.24, 0.99, 0.94, 0.83, 0.77, 0.70, 0.46, 0.39, 0.27, 0.20, 0.08, 0.03, -0.10, -0.29, -0.31, -0.33, -0.45,
        -1.54, -1.68,
    ],
];

/// One [L22] case: 32008, pure axial `fx`, `speed_rpm`, cage slip rate `slip`, deviation series
/// `series` (1..6, 0 = ideal rollers).
pub fn l22(series: usize, fx: f64, slip: f64, speed_rpm: f64) -> Result<Outputs, ModelError> {
    solve_case("32008", 0.0, |p, i| {
        p.preload = Preload::Force;
        p.cage_slip_rate = slip;
        if series > 0 {
            for (j, d) in L22_SERIES_UM[series - 1].iter().enumerate() {
                p.roller_dd[j] = d * 1e-6;
            }
        }
        i.fx = fx;
        i.fy = 0.0;
        i.fz = 0.0;
        i.speed = rpm(speed_rpm);
    })
}

/// Population variance of the loads.
pub fn variance(v: &[f64]) -> f64 {
    let n = v.len().max(1) as f64;
    let mean = v.iter().sum::<f64>() / n;
    v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n
}

// ---------------------------------------------------------------------------------------------
// [Y22] CRB-TRILOBE
// ---------------------------------------------------------------------------------------------

/// The two roller positions of [Y22]: roller 1 on a lobe low point, or half a pitch away.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Y22State {
    Single,
    Double,
}

impl Y22State {
    pub fn cage_angle(self) -> f64 {
        match self {
            Y22State::Single => 0.0,
            // 24 rollers: half a pitch.
            Y22State::Double => PI / 24.0,
        }
    }
    pub fn label(self) -> &'static str {
        match self {
            Y22State::Single => "single-pressed",
            Y22State::Double => "double-pressed",
        }
    }
}

/// One [Y22] case: CRB-TRILOBE in `state`, mounted `clearance` (m), waveform `ee` (m),
/// radial load `fy` (N) at `speed_rpm`.
pub fn y22(state: Y22State, clearance: f64, ee: f64, fy: f64, speed_rpm: f64) -> Result<Outputs, ModelError> {
    solve_case("CRB-TRILOBE", state.cage_angle(), |p, i| {
        p.clearance = clearance;
        p.outer_waveform = ee;
        p.outer_lobes = 3;
        i.fy = fy;
        i.fx = 0.0;
        i.fz = 0.0;
        i.speed = rpm(speed_rpm);
    })
}

/// The preset's defaults for [Y22]: clearance -10 um, waveform 20 um, Fy 100 N, 40,000 rpm.
pub const Y22_CLEARANCE: f64 = -10e-6;
pub const Y22_WAVEFORM: f64 = 20e-6;
pub const Y22_FY: f64 = 100.0;
pub const Y22_RPM: f64 = 40_000.0;

/// Number of lobe zones (120 deg sectors centred on the lobe low points at 0, 120, 240 deg)
/// holding at least one roller that touches both raceways, for roller 1 at `cage_angle`.
pub fn loaded_lobe_zones(out: &Outputs, cage_angle: f64) -> usize {
    let z = out.qi.len();
    let mut zones = [false; 3];
    for j in 0..z {
        if out.qi[j] > 0.0 && out.qo[j] > 0.0 {
            let psi = (cage_angle + 2.0 * PI * j as f64 / z as f64).rem_euclid(2.0 * PI);
            let k = (((psi + PI / 3.0) / (2.0 * PI / 3.0)).floor() as usize) % 3;
            zones[k] = true;
        }
    }
    zones.iter().filter(|z| **z).count()
}

/// Preload exists: all three lobe zones carry rollers, not only the loaded side.
pub fn y22_preloaded(out: &Outputs, state: Y22State) -> bool {
    loaded_lobe_zones(out, state.cage_angle()) == 3
}
