//! Quasi-static bearing model, fidelity 0 (MODEL.md section 6), after Harris / Andreason
//! with the sliced contacts of [W25, D19, L22, Y22].
//!
//! Unknowns: cone translation (axial, two radial; the two tilts are imposed by the shaft
//! deflection inputs and their reaction moments reported) and, per roller, its axial and
//! radial displacement and tilt in its axial plane. Per roller: force and moment balance of
//! the sliced cone and cup contacts, the flange (Hertz point contact), the centrifugal force
//! (applied at the roller's centre of mass) and the gyroscopic moment of spin and orbit.
//! Cone: equilibrium with the external forces (force preload) or prescribed axial
//! displacement (displacement preload). Displacements are small against the geometry, so
//! the interference of each contact is linear in the unknowns (exact Jacobian).
//!
//! Solver: Newton-Raphson on all 3 + 3Z unknowns at once, the block-arrowhead Jacobian
//! solved by a Schur complement on the 3 cone unknowns (O(Z) per iteration), step clamping,
//! and a damping factor halved while the residual grows [Y22]. Warm-started from the
//! previous step; a cold start uses the rigid-ring estimate and falls back to load stepping.
//! Rollers that touch nothing keep their position (the Jacobian is regularised, never the
//! residual, so converged solutions are exact).

mod friction;
mod load_table;
#[cfg(target_arch = "x86_64")]
mod simd;
mod skew;
mod stiffness;
pub mod studies;

use crate::bearing::Bearing;
use crate::contact::{self, LineLaw};
use crate::geometry::Geometry;
use crate::model::{load_within_range, Inputs, LoadCausality, Lubrication, ModelError, Outputs, Parameters, Preload, SolveReport};
use nalgebra::{Matrix2x3, Matrix3, Matrix3x2, Vector2, Vector3};
use std::f64::consts::TAU;

pub use friction::{FrictionModel, SliceWeights};
pub use stiffness::Linearisation;

/// Inputs kept with a warm start (for the temporal predictor).
const WARM_INPUTS: usize = 11;

/// The inputs of a solve as the warm start keeps them.
fn warm_inputs(i: &Inputs) -> [f64; WARM_INPUTS] {
    let [dx, dy, dz] = i.displacement;
    [
        i.speed,
        i.xi,
        i.zeta,
        i.fx,
        i.fy,
        i.fz,
        i.axial_displacement,
        dx,
        dy,
        dz,
        i.cup_speed,
    ]
}

/// Hold the prescribed cone translations in a Newton step on the cone's Schur complement:
/// their rows and columns become the identity with a zero right-hand side.
fn hold_prescribed(schur: &mut Matrix3<f64>, rhs: &mut Vector3<f64>, prescribed: &[Option<f64>; 3]) {
    for (c, v) in prescribed.iter().enumerate() {
        if v.is_some() {
            let mut unit = Vector3::zeros();
            unit[c] = 1.0;
            schur.set_row(c, &unit.transpose());
            schur.set_column(c, &unit);
            rhs[c] = 0.0;
        }
    }
}

/// Bins per roller pitch of the azimuth table predictor (`QuasiStatic::table_predict`).
const TABLE_BINS: usize = 64;

/// `v` rounded to an integer (|v| < 2^51; no libm call on baseline x86-64, which lacks the
/// SSE4.1 rounding instruction).
#[inline(always)]
fn round_int(v: f64) -> f64 {
    const ROUNDER: f64 = 6_755_399_441_055_744.0;
    (v + ROUNDER) - ROUNDER
}

/// `a` wrapped into [0, period) (up to rounding at the ends).
#[inline(always)]
fn wrap_to(a: f64, period: f64) -> f64 {
    let w = a - period * round_int(a / period);
    if w < 0.0 {
        w + period
    } else {
        w
    }
}

/// Cubic interpolation at `t` in a periodic table of `nb` bins over `period` (4 values per bin:
/// position, then three values; NaN position: empty) on the two nearest filled nodes on each
/// side of `t` within two pitches (TABLE_BINS bins each way) or half the period.
fn table_interpolate(nodes: &[f64], nb: usize, period: f64, t: f64, out: &mut [f64; 3]) -> bool {
    let b = ((t / period * nb as f64) as usize).min(nb - 1);
    let reach = (2 * TABLE_BINS).min(nb / 2);
    let offset = |bin: usize| {
        let d = nodes[4 * bin] - t;
        d - period * round_int(d / period)
    };
    // two nodes at or below t, nearest first, then two above
    let (mut below, mut nbelow) = ([(0.0, 0usize); 2], 0);
    let (mut above, mut nabove) = ([(0.0, 0usize); 2], 0);
    // bins b - k and b + k modulo nb (k <= reach <= nb / 2 and b < nb: one wrap at most)
    let wrap = |i: usize| if i >= nb { i - nb } else { i };
    for k in 0..=reach {
        let bin = wrap(b + nb - k);
        if nbelow < 2 && !nodes[4 * bin].is_nan() {
            let d = offset(bin);
            if d <= 0.0 && (nbelow == 0 || d < below[0].0) {
                below[nbelow] = (d, bin);
                nbelow += 1;
            }
        }
        let bin = wrap(b + k);
        if nabove < 2 && !nodes[4 * bin].is_nan() {
            let d = offset(bin);
            if d > 0.0 && (nabove == 0 || d > above[0].0) {
                above[nabove] = (d, bin);
                nabove += 1;
            }
        }
        if nbelow == 2 && nabove == 2 {
            break;
        }
    }
    if nbelow < 2 || nabove < 2 {
        return false;
    }
    // Lagrange weights at offset 0 of the nodes at offsets d
    let node = [below[1], below[0], above[0], above[1]];
    let d = [node[0].0, node[1].0, node[2].0, node[3].0];
    *out = [0.0; 3];
    for i in 0..4 {
        let (mut num, mut den) = (1.0, 1.0);
        for m in 0..4 {
            if m != i {
                num *= -d[m];
                den *= d[i] - d[m];
            }
        }
        let l = num / den;
        let v = &nodes[4 * node[i].1 + 1..4 * node[i].1 + 4];
        for c in 0..3 {
            out[c] += l * v[c];
        }
    }
    out.iter().all(|v| v.is_finite())
}

/// The roller unknowns of `src` (roller 1 at some cage angle) interpolated at the rollers'
/// azimuths after a cage advance `shift` (rad) into `dst` (periodic in azimuth over the `z`
/// rollers); the cone unknowns are not touched. Per roller, the quintic through the six
/// nearest samples where they are smooth (a full load zone: the error of the cubic
/// Catmull-Rom spline, only third order, kept the warm start of TRB130x230 and 32008 in a
/// smooth time table one Newton iteration short), else that cubic spline (the edge of a
/// load zone, a lobe: the quintic would ring). Smooth: in each unknown, the two fourth
/// differences of the six samples at most 0.3 times the larger second difference of the
/// middle four (or 0.09 times the middle first difference: a straight run); a sampled
/// sinusoid of 17 to 26 rollers per period has a ratio of (2 pi / Z)^2 < 0.14, a kink of 1
/// and more.
fn spatial_interpolate(z: usize, shift: f64, src: &[f64], dst: &mut [f64]) {
    let u = shift * z as f64 / TAU;
    let whole = u.floor();
    let f = u - whole;
    // Catmull-Rom weights at fraction f between samples k and k+1 (samples k-1 .. k+2).
    let w = [
        0.5 * (-f + 2.0 * f * f - f * f * f),
        0.5 * (2.0 - 5.0 * f * f + 3.0 * f * f * f),
        0.5 * (f + 4.0 * f * f - 3.0 * f * f * f),
        0.5 * (-f * f + f * f * f),
    ];
    // Lagrange weights of the quintic at f on the samples k-2 .. k+3
    let mut w6 = [0.0; 6];
    for (i, wi) in w6.iter_mut().enumerate() {
        let mut l = 1.0;
        for m in 0..6 {
            if m != i {
                l *= (f - (m as f64 - 2.0)) / (i as f64 - m as f64);
            }
        }
        *wi = l;
    }
    let base = whole.rem_euclid(z as f64) as usize;
    let sample = |j: usize, m: usize, c: usize| src[3 + 3 * ((j + base + 2 * z + m - 2) % z) + c];
    for j in 0..z {
        let smooth = z >= 8
            && (0..3).all(|c| {
                let s: [f64; 6] = std::array::from_fn(|m| sample(j, m, c));
                let d4 = (s[0] - 4.0 * s[1] + 6.0 * s[2] - 4.0 * s[3] + s[4])
                    .abs()
                    .max((s[1] - 4.0 * s[2] + 6.0 * s[3] - 4.0 * s[4] + s[5]).abs());
                let d2 = (s[1] - 2.0 * s[2] + s[3]).abs().max((s[2] - 2.0 * s[3] + s[4]).abs());
                d4 <= 0.3 * d2.max(0.3 * (s[3] - s[2]).abs())
            });
        for c in 0..3 {
            let v = if smooth {
                (0..6).map(|m| w6[m] * sample(j, m, c)).sum()
            } else {
                (0..4).map(|m| w[m] * sample(j, m + 1, c)).sum()
            };
            dst[3 + 3 * j + c] = v;
        }
    }
}

/// The film ratio output without a loaded raceway contact (a finite stand-in for infinity).
pub const FILM_RATIO_CAP: f64 = 1e9;

/// Maximum Newton iterations of one solve.
const MAX_ITERATIONS: u32 = 100;

/// Evaluation of one roller at a trial point: residual, Jacobian blocks, loads.
#[derive(Debug, Clone, Copy, Default)]
struct RollerEval {
    /// Scaled residual (F_x, F_r, M / L_s) of the roller.
    r: Vector3<f64>,
    /// d r / d (a, rho, theta L_s).
    a: Matrix3<f64>,
    /// d r / d (cone dx, cone dr).
    b: Matrix3x2<f64>,
    /// d f_cone / d (cone dx, cone dr).
    d: nalgebra::Matrix2<f64>,
    /// Force of the roller on the cone in the axial plane (x, r).
    f_cone: Vector2<f64>,
    /// In-plane moment about the bearing origin of the forces on the cone.
    m_cone: f64,
    qi: f64,
    qo: f64,
    qf: f64,
    /// Tilt moments about the roller centre from cone, cup, flange.
    nit: f64,
    not: f64,
    nft: f64,
    /// Slice sums of the cone and cup lines, for the friction model.
    cone: LineSums,
    cup: LineSums,
    /// Smallest separation from any contact (m; <= 0 when touching something).
    gap: f64,
    extrapolated: bool,
}

/// Sums over the slices of one contact line (the normal is common to all slices).
#[derive(Debug, Clone, Copy, Default)]
struct LineSums {
    q: f64,
    q_lever: f64,
    q_chi: f64,
    k: f64,
    k_lever: f64,
    k_lever2: f64,
    /// Number of loaded slices.
    loaded: u32,
    /// Largest interference over the slices (negative: the line is separated by that gap).
    max_delta: f64,
    extrapolated: bool,
}

/// Per-slice constants of one contact line, as flat arrays for the slice loop, padded to a
/// multiple of four slices for the lane kernel (`simd.rs`; a padding slice never touches:
/// lever and chi 0, crown +inf).
#[derive(Debug, Clone)]
struct SliceTable {
    /// Number of slices (the arrays may be up to three longer).
    n: usize,
    /// Use the two-lane kernel (`simd.rs`). Not for the quasi-static start of the dynamic
    /// model: that start keeps the scalar loop's bits.
    vector: bool,
    /// Run that kernel four slices at a time (the CPU has AVX2; the same bits as two).
    four_lanes: bool,
    /// ln(8 R) per slice of the Johnson law (empty for Palmgren), and an interference below
    /// which no slice of the line is beyond the law's validity (ln(8R/delta) - 1 >= 3).
    ln_8r: Vec<f64>,
    johnson_limit: f64,
    lever: Vec<f64>,
    /// lever / L_s
    lever_s: Vec<f64>,
    /// cross(P, n) about the bearing origin (cone only; zeros for the cup).
    chi: Vec<f64>,
    crown: Vec<f64>,
}

impl SliceTable {
    fn new(line: &crate::geometry::ContactLine, crown: &[f64], ls: f64, chi: Option<&[f64]>, vector: bool) -> SliceTable {
        let n = line.lever.len();
        let padded = n.div_ceil(4) * 4;
        let pad = |mut v: Vec<f64>, fill: f64| {
            v.resize(padded, fill);
            v
        };
        SliceTable {
            n,
            vector,
            #[cfg(target_arch = "x86_64")]
            four_lanes: vector && simd::four_lanes_available(),
            #[cfg(not(target_arch = "x86_64"))]
            four_lanes: false,
            ln_8r: match &line.law {
                LineLaw::Johnson { ln_8r, .. } => pad(ln_8r[..n].to_vec(), 0.0),
                LineLaw::Palmgren { .. } => Vec::new(),
            },
            johnson_limit: match &line.law {
                LineLaw::Johnson { ln_8r, .. } => {
                    0.999
                        * ln_8r[..n]
                            .iter()
                            .fold(f64::INFINITY, |m, l| m.min(libm::exp(l - (contact::JOHNSON_LOG_FLOOR + 1.0))))
                }
                LineLaw::Palmgren { .. } => f64::INFINITY,
            },
            lever: pad(line.lever.clone(), 0.0),
            lever_s: pad(line.lever.iter().map(|l| l / ls).collect(), 0.0),
            chi: pad(chi.map(|c| c[..n].to_vec()).unwrap_or_else(|| vec![0.0; n]), 0.0),
            crown: pad(crown[..n].to_vec(), f64::INFINITY),
        }
    }
}

/// Per-solve constants of one roller.
#[derive(Debug, Clone, Copy, Default)]
struct RollerSetup {
    cos_psi: f64,
    sin_psi: f64,
    /// Cone tilt in this roller's axial plane (rotation from x towards r).
    gamma: f64,
    gap_cone: f64,
    gap_cup: f64,
    /// The roller stands on a local defect with its cup (cone) slices: they take the crown
    /// plus the defect's drop of `cup_defect_tables[j]` (`cone_defect_tables[j]`).
    on_cup_defect: bool,
    on_cone_defect: bool,
}

/// The level-0 model of one bearing with one parameter set.
#[derive(Debug, Clone)]
pub struct QuasiStatic {
    pub geometry: Geometry,
    params: Parameters,
    /// Tilt scale L_s = l/2: the solver's third roller unknown is theta * L_s (metres).
    ls: f64,
    /// cross(P, n) about the bearing origin per cone slice, and for the flange.
    cone_chi: Vec<f64>,
    /// cone_chi as alpha + beta lever (`stiffness.rs`).
    cone_chi_fit: (f64, f64),
    flange_chi: f64,
    /// Kinematic cage speed relative to the cup per unit speed of the cone relative to the
    /// cup (epicyclic, with the slip rate).
    cage_ratio: f64,
    /// Roller spin relative to the cage per unit speed of the cone relative to the cup
    /// (about the roller axis).
    spin_ratio: f64,
    cone_table: SliceTable,
    cup_table: SliceTable,
    /// The local defects (`crate::defect`) on the cup, the cone and rollers, and per roller the
    /// cup's and the cone's slice tables with the defects' drops added to the crown (filled
    /// for the rollers on one, `prepare`); the turns since t = 0 of the cone, of the rollers'
    /// spin and of the cup (rad; `set_defect_turns`).
    defects: crate::defect::LocalDefects,
    cup_defect_tables: Vec<SliceTable>,
    cone_defect_tables: Vec<SliceTable>,
    defect_turns: [f64; 3],
    /// This solve is axisymmetric: one roller is evaluated and replicated.
    axisymmetric: bool,
    /// The cone translations (x, y, z) this solve prescribes (`prepare`): all three in
    /// displacement causality, the axial one in displacement preload or, at 0, for a bearing
    /// without axial stiffness; `None`: solved for from the force balance.
    prescribed: [Option<f64>; 3],
    setup: Vec<RollerSetup>,
    evals: Vec<RollerEval>,
    trial: Vec<f64>,
    step: Vec<f64>,
    friction: FrictionModel,
    /// Largest Newton step of one roller or cone component (m).
    max_step: f64,
    /// Jacobian regularisation of roller blocks (N/m).
    regularisation: f64,
    /// The roller skew model [D19] (`skewModel` = true).
    skew: Option<skew::SkewSetup>,
    /// Slice loads per roller (cone slices, then cup slices) of the last evaluation, for the
    /// friction model (at convergence: of the solution).
    slice_load_buffer: Vec<f64>,
    /// ISO 281 / ISO/TS 16281 ratings of the bearing with one lamina per slice.
    rating: crate::bearing::rating::BearingRating,
    /// Scratch for the unknowns of a solve and for one roller's slice loads (allocated once).
    x: Vec<f64>,
    local_scratch: Vec<f64>,
    /// The solve under way is the seat of the quasi-dynamic model (`solve_seat`): its
    /// outputs stop at the loads and the pressure the range check reads.
    seat_only: bool,
}

impl QuasiStatic {
    pub fn new(bearing: &Bearing, params: &Parameters) -> Result<QuasiStatic, ModelError> {
        let geometry = Geometry::new(bearing, &params.roller_profile());
        let z = geometry.z;
        let ls = 0.5 * geometry.length;
        let cone_chi: Vec<f64> = geometry
            .cone
            .point
            .iter()
            .map(|p| crate::geometry::cross(*p, geometry.cone.normal))
            .collect();
        let flange_chi = geometry
            .flange
            .as_ref()
            .map(|f| crate::geometry::cross(f.point, f.normal))
            .unwrap_or(0.0);
        let cone_chi_fit = QuasiStatic::chi_fit(&cone_chi, &geometry.cone.lever);
        let (ri, ro) = geometry.pitch_contact_radii();
        let cage_ratio = (1.0 - params.cage_slip_rate) * ri / (ri + ro);
        // Outer-raceway control: pure rolling on the cup at mid-roller.
        let spin_ratio = -cage_ratio * ro / geometry.mean_radius;
        // Reference stiffness: whole roller at 1 um on one raceway.
        let k_ref = {
            let line = &geometry.cone;
            let mid = geometry.slices / 2;
            line.law.load(mid, 1e-6).1 * geometry.slices as f64
        };
        let friction = FrictionModel::new(bearing, params, &geometry, cage_ratio, spin_ratio);
        let vector = params.fidelity == crate::model::Fidelity::QuasiStatic;
        let cone_table = SliceTable::new(&geometry.cone, &geometry.crown, ls, Some(&cone_chi), vector);
        let cup_table = SliceTable::new(&geometry.cup, &geometry.crown, ls, None, vector);
        let defects = crate::defect::LocalDefects::new(params.defects(), bearing.roller_mean_radius(), &geometry.cup, &geometry.cone);
        let tables = |table: &SliceTable, on: bool| if on { vec![table.clone(); z] } else { Vec::new() };
        let on_rollers = !defects.rollers.is_empty();
        let cup_defect_tables = tables(&cup_table, !defects.cup.is_empty() || on_rollers);
        let cone_defect_tables = tables(&cone_table, !defects.cone.is_empty() || on_rollers);
        let skew = params
            .skew_model
            .then(|| skew::SkewSetup::new(bearing, &geometry, params.pocket_clearance, cage_ratio, spin_ratio, k_ref));
        Ok(QuasiStatic {
            rating: crate::bearing::rating::BearingRating::new(bearing, params.slices),
            skew,
            slice_load_buffer: vec![0.0; 2 * geometry.slices * z],
            x: Vec::new(),
            local_scratch: Vec::with_capacity(2 * geometry.slices),
            seat_only: false,
            axisymmetric: false,
            prescribed: [None; 3],
            cone_table,
            cup_table,
            defects,
            cup_defect_tables,
            cone_defect_tables,
            defect_turns: [0.0; 3],
            max_step: 1e-3 * 2.0 * geometry.mean_radius,
            regularisation: 1e-9 * k_ref,
            geometry,
            params: params.clone(),
            ls,
            cone_chi_fit,
            cone_chi,
            flange_chi,
            cage_ratio,
            spin_ratio,
            setup: vec![RollerSetup::default(); z],
            evals: vec![RollerEval::default(); z],
            trial: vec![0.0; 3 + 3 * z],
            step: vec![0.0; 3 + 3 * z],
            friction,
        })
    }

    /// Cage angular speed (epicyclic kinematics with slip): the cup's speed plus the cage's
    /// share of the cone's speed relative to the cup, omega_c = omega_o + (1 - S_c) r_i /
    /// (r_i + r_o) (omega_i - omega_o); with slip 0 the mean (omega_i r_i + omega_o r_o) /
    /// (r_i + r_o) of the two rings' pitch-contact surface speeds over r_i + r_o.
    pub fn cage_speed(&self, inputs: &Inputs) -> f64 {
        self.cage_ratio * inputs.relative_speed() + inputs.cup_speed
    }

    /// Roller spin about its own axis relative to the cage, per unit speed of the cone
    /// relative to the cup.
    pub fn spin_ratio(&self) -> f64 {
        self.spin_ratio
    }

    /// Number of unknowns.
    pub fn n_unknowns(&self) -> usize {
        3 + 3 * self.geometry.z
    }

    fn prepare(&mut self, inputs: &Inputs, cage_angle: f64) {
        let g = &self.geometry;
        let p = &self.params;
        let z = g.z;
        self.prescribed = match (p.causality, g.axial, p.preload) {
            (LoadCausality::Displacement, axial, _) => {
                let [dx, dy, dz] = inputs.displacement;
                [Some(if axial { dx } else { 0.0 }), Some(dy), Some(dz)]
            }
            (LoadCausality::Force, false, _) => [Some(0.0), None, None],
            (LoadCausality::Force, true, Preload::Displacement) => [Some(inputs.axial_displacement), None, None],
            (LoadCausality::Force, true, Preload::Force) => [None; 3],
        };
        let radial = match p.causality {
            LoadCausality::Force => inputs.fy != 0.0 || inputs.fz != 0.0,
            LoadCausality::Displacement => inputs.displacement[1] != 0.0 || inputs.displacement[2] != 0.0,
        };
        // Aligned shaft, no radial load, equal rollers and a round cup: every roller sees the
        // same equilibrium, exactly, whatever the cage angle.
        self.axisymmetric = !radial
            && inputs.xi == 0.0
            && inputs.zeta == 0.0
            && (p.outer_lobes == 0 || p.outer_waveform == 0.0)
            && p.roller_dd.iter().all(|d| *d == p.roller_dd[0])
            && !p.has_defect();
        let cos_h = libm::cos(g.half_angle);
        let cos_o = libm::cos(g.cup_angle);
        for j in 0..z {
            let psi = cage_angle + TAU * j as f64 / z as f64;
            let (s, c) = libm::sincos(psi);
            let lobe = if p.outer_lobes > 0 {
                0.5 * p.outer_waveform * (1.0 - libm::cos(p.outer_lobes as f64 * psi))
            } else {
                0.0
            };
            let dd = 0.5 * p.roller_dd[j] * cos_h;
            self.setup[j] = RollerSetup {
                cos_psi: c,
                sin_psi: s,
                gamma: inputs.zeta * c - inputs.xi * s,
                gap_cone: dd,
                gap_cup: dd - (0.5 * p.clearance + lobe) * cos_o,
                on_cup_defect: false,
                on_cone_defect: false,
            };
        }
        if !self.defects.is_empty() {
            for j in 0..z {
                let (on_cup, on_cone) = self.place_defect(j, cage_angle + TAU * j as f64 / z as f64);
                (self.setup[j].on_cup_defect, self.setup[j].on_cone_defect) = (on_cup, on_cone);
            }
        }
    }

    /// Fill roller `j`'s defect tables for the roller at azimuth `psi`: each slice's crown
    /// plus the drop of the cup's defects at `psi`, of the cone's at `psi` less the cone's
    /// turn, and of the roller's own at the body angle of its cup contact (its outward normal,
    /// 0) and of its cone contact (π), less its spin. Whether its cup and its cone slices stand
    /// on a defect.
    fn place_defect(&mut self, j: usize, psi: f64) -> (bool, bool) {
        use crate::defect::LocalDefects;
        let g = &self.geometry;
        let [cone_turn, spin, cup_turn] = self.defect_turns;
        let defects = &self.defects;
        let fill = |table: &mut SliceTable, drop: &dyn Fn(usize) -> f64| {
            let mut on = false;
            for k in 0..g.slices {
                let d = drop(k);
                table.crown[k] = g.crown[k] + d;
                on |= d > 0.0;
            }
            on
        };
        let mut on_cup = false;
        if !self.cup_defect_tables.is_empty() {
            let (point, rho) = (&g.cup.point, &g.cup.raceway_radius);
            on_cup = fill(&mut self.cup_defect_tables[j], &|k| {
                LocalDefects::raceway_drop(&defects.cup, psi - cup_turn, point[k][0], rho[k]).0
                    + defects.roller_drop(j, true, -spin, g.slice_s[k]).0
            });
        }
        let mut on_cone = false;
        if !self.cone_defect_tables.is_empty() {
            let (point, rho) = (&g.cone.point, &g.cone.raceway_radius);
            on_cone = fill(&mut self.cone_defect_tables[j], &|k| {
                LocalDefects::raceway_drop(&defects.cone, psi - cone_turn, point[k][0], rho[k]).0
                    + defects.roller_drop(j, false, std::f64::consts::PI - spin, g.slice_s[k]).0
            });
        }
        (on_cup, on_cone)
    }

    /// Set the turns (rad) since t = 0 of the cone, of the rollers' spin relative to the cage
    /// and of the cup ([`QuasiStatic::defect_turn_rates`], integrated by the element): the
    /// next solve places the defects there.
    pub fn set_defect_turns(&mut self, turns: [f64; 3]) {
        self.defect_turns = turns;
    }

    /// The rates (rad/s) at which the cone, the rollers' spin relative to the cage and the
    /// cup turn at `inputs`: the cone's speed, the rollers' epicyclic spin, the cup's speed.
    pub fn defect_turn_rates(&self, inputs: &Inputs) -> [f64; 3] {
        [inputs.speed, self.spin_ratio * inputs.relative_speed(), inputs.cup_speed]
    }

    /// The cone's slice table of roller `j`: with the defect's drop where it stands on one.
    #[inline]
    fn cone_table_of(&self, j: usize) -> &SliceTable {
        if self.setup[j].on_cone_defect {
            &self.cone_defect_tables[j]
        } else {
            &self.cone_table
        }
    }

    /// The cup's slice table of roller `j`: with the defect's drop where it stands on it.
    #[inline]
    fn cup_table_of(&self, j: usize) -> &SliceTable {
        if self.setup[j].on_cup_defect {
            &self.cup_defect_tables[j]
        } else {
            &self.cup_table
        }
    }

    /// Centrifugal force (N, radial) and the moment the contacts must supply for the
    /// gyroscopic turning of the spin axis (N m, in-plane): both follow the roller's orbit at
    /// the cage speed (absolute) and its spin relative to the cage (set by the relative
    /// speed of the rings), so a turning cup changes them even at the same relative speed.
    fn inertial_loads(&self, inputs: &Inputs) -> (f64, f64, f64) {
        let g = &self.geometry;
        let wc = self.cage_speed(inputs);
        let w = self.spin_ratio * inputs.relative_speed();
        let fc = if self.params.centrifugal {
            g.roller_mass * wc * wc * (g.center[1] + g.cm_offset * g.axis[1])
        } else {
            0.0
        };
        // Moment of the centrifugal force about the roller centre (applied at the centre of mass).
        let m_fc = g.cm_offset * g.axis[0] * fc;
        let m_req = if self.params.gyroscopic {
            let (sa, ca) = libm::sincos(g.axis_angle);
            // H = I_a (wc cos a + w) e + I_t wc (x - cos a e); d H / dt = wc x_hat cross H.
            // x_hat cross e = -sin a e_t, so the in-plane component is:
            -wc * sa * (g.inertia_axial * (wc * ca + w) - g.inertia_transverse * wc * ca)
        } else {
            0.0
        };
        (fc, m_fc, m_req)
    }

    /// Sums over the slices of one contact line. The interference of slice k is affine in
    /// the unknowns: delta_k = base - theta lever_k + gamma chi_k - crown_k. One specialised
    /// loop per contact law (no per-slice dispatch). The slice loads go to `loads` (0 where
    /// the slice is not in contact).
    #[inline]
    fn line_sums(line: &crate::geometry::ContactLine, t: &SliceTable, base: f64, theta: f64, gamma: f64, loads: &mut [f64]) -> LineSums {
        #[cfg(target_arch = "x86_64")]
        if t.vector {
            let law = match &line.law {
                LineLaw::Johnson { c, .. } => simd::Law::Johnson { c: *c, ln_8r: &t.ln_8r },
                LineLaw::Palmgren { k } => simd::Law::Palmgren { k: *k },
            };
            if let Some(s) = simd::line_sums(t, t.n, law, base, theta, gamma, loads, t.four_lanes) {
                return s;
            }
        }
        match &line.law {
            LineLaw::Johnson { c, ln_8r } => {
                let ln_8r = &ln_8r[..t.n];
                Self::line_sums_with(t, base, theta, gamma, loads, |k, d| contact::johnson(*c, ln_8r[k], d))
            }
            LineLaw::Palmgren { k } => Self::line_sums_with(t, base, theta, gamma, loads, |_, d| contact::palmgren(*k, d)),
        }
    }

    #[inline(always)]
    fn line_sums_with<L: Fn(usize, f64) -> (f64, f64, bool)>(
        t: &SliceTable,
        base: f64,
        theta: f64,
        gamma: f64,
        loads: &mut [f64],
        law: L,
    ) -> LineSums {
        let mut s = LineSums {
            max_delta: f64::NEG_INFINITY,
            ..LineSums::default()
        };
        let n = t.n;
        let (lever, lever_s, chi, crown, loads) = (&t.lever[..n], &t.lever_s[..n], &t.chi[..n], &t.crown[..n], &mut loads[..n]);
        for k in 0..n {
            let delta = base - theta * lever[k] + gamma * chi[k] - crown[k];
            s.max_delta = s.max_delta.max(delta);
            if delta <= 0.0 {
                loads[k] = 0.0;
                continue;
            }
            let (q, dq, ext) = law(k, delta);
            let lv = lever_s[k];
            s.q += q;
            s.q_lever += q * lever[k];
            s.q_chi += q * chi[k];
            s.k += dq;
            s.k_lever += dq * lv;
            s.k_lever2 += dq * lv * lv;
            loads[k] = q;
            s.loaded += 1;
            s.extrapolated |= ext;
        }
        s
    }

    /// Evaluate roller `j` with cone local displacement (dx, dr) and roller unknowns `q`; its
    /// slice loads go to `loads` (cone slices, then cup slices).
    #[allow(clippy::too_many_arguments)]
    fn eval_roller(&self, j: usize, cone: [f64; 2], q: [f64; 3], fc: f64, m_fc: f64, m_req: f64, loads: &mut [f64]) -> RollerEval {
        let g = &self.geometry;
        let st = &self.setup[j];
        let ls = self.ls;
        let theta = q[2] / ls;
        let mut e = RollerEval {
            gap: f64::INFINITY,
            ..RollerEval::default()
        };

        // Cone: delta = (dx - a) n_x + (dr - rho) n_r + gamma chi - theta lever + gap - crown
        let ni = g.cone.normal;
        let base_i = (cone[0] - q[0]) * ni[0] + (cone[1] - q[1]) * ni[1] + st.gap_cone;
        let (cone_loads, cup_loads) = loads.split_at_mut(g.slices);
        let si = Self::line_sums(&g.cone, self.cone_table_of(j), base_i, theta, st.gamma, cone_loads);
        // Cup: delta = -(a n_x + rho n_r) - theta lever + gap - crown
        let no = g.cup.normal;
        let base_o = -(q[0] * no[0] + q[1] * no[1]) + st.gap_cup;
        let so = Self::line_sums(&g.cup, self.cup_table_of(j), base_o, theta, 0.0, cup_loads);

        let add_line = |e: &mut RollerEval, n: [f64; 2], s: &LineSums, on_cone: bool| {
            let nv = Vector3::new(n[0], n[1], 0.0);
            e.r += nv * s.q + Vector3::new(0.0, 0.0, s.q_lever / ls);
            // A -= sum k g g^T, g = (n_x, n_r, lever/L_s)
            let mut a = nv * nv.transpose() * s.k;
            a[(0, 2)] = n[0] * s.k_lever;
            a[(1, 2)] = n[1] * s.k_lever;
            a[(2, 0)] = a[(0, 2)];
            a[(2, 1)] = a[(1, 2)];
            a[(2, 2)] = s.k_lever2;
            e.a -= a;
            e.extrapolated |= s.extrapolated;
            if on_cone {
                // B = sum k g n^T ; D = -sum k n n^T ; f_cone = -sum q n
                let n2 = Vector2::new(n[0], n[1]);
                let gk = Vector3::new(n[0] * s.k, n[1] * s.k, s.k_lever);
                e.b += gk * n2.transpose();
                e.d -= n2 * n2.transpose() * s.k;
                e.f_cone -= n2 * s.q;
                e.m_cone -= s.q_chi;
            }
        };
        add_line(&mut e, ni, &si, true);
        add_line(&mut e, no, &so, false);
        e.qi = si.q;
        e.qo = so.q;
        e.gap = e.gap.min(-si.max_delta).min(-so.max_delta);
        e.cone = si;
        e.cup = so;
        e.nit = si.q_lever;
        e.not = so.q_lever;

        if let Some(f) = &g.flange {
            let n = f.normal;
            let delta = (cone[0] - q[0]) * n[0] + (cone[1] - q[1]) * n[1] + st.gamma * self.flange_chi - theta * f.lever;
            e.gap = -delta;
            let (qf, kf) = f.hertz.load(delta);
            if qf > 0.0 {
                let lv = f.lever / ls;
                let gv = Vector3::new(n[0], n[1], lv);
                e.r += gv * qf;
                e.a -= gv * gv.transpose() * kf;
                let n2 = Vector2::new(n[0], n[1]);
                e.b += gv * n2.transpose() * kf;
                e.d -= n2 * n2.transpose() * kf;
                e.f_cone -= n2 * qf;
                e.m_cone -= qf * self.flange_chi;
                e.qf = qf;
                e.nft = qf * f.lever;
            }
        }
        // Centrifugal force (radial) and gyroscopic moment.
        e.r[1] += fc;
        e.r[2] += (m_fc - m_req) / ls;
        if !g.axial {
            // Cylindrical bearing: no axial stiffness, the axial unknown is held at zero.
            e.r[0] = 0.0;
            e.a.set_row(0, &Vector3::zeros().transpose());
            e.a.set_column(0, &Vector3::zeros());
            e.b.set_row(0, &nalgebra::RowVector2::zeros());
        }
        e
    }

    /// Evaluate every roller at `x`; returns the scaled residual max-norm, the merit
    /// (sum of squares) and the reference force.
    fn evaluate(&mut self, x: &[f64], inputs: &Inputs, fc: f64, m_fc: f64, m_req: f64) -> (f64, f64, f64, Vector3<f64>) {
        let z = self.geometry.z;
        let mut ring = Vector3::new(inputs.fx, inputs.fy, inputs.fz);
        let mut max_r: f64 = 0.0;
        let mut merit = 0.0;
        let mut f_ref: f64 = inputs.fx.abs().max(inputs.fy.abs()).max(inputs.fz.abs()).max(fc.abs()).max(1.0);
        let evaluated = if self.axisymmetric { 1 } else { z };
        let ns = self.geometry.slices;
        let mut loads = std::mem::take(&mut self.slice_load_buffer);
        for j in 0..evaluated {
            let st = self.setup[j];
            let dr = x[1] * st.cos_psi + x[2] * st.sin_psi;
            let q = [x[3 + 3 * j], x[4 + 3 * j], x[5 + 3 * j]];
            let e = self.eval_roller(j, [x[0], dr], q, fc, m_fc, m_req, &mut loads[2 * ns * j..2 * ns * (j + 1)]);
            ring[0] += e.f_cone[0];
            ring[1] += e.f_cone[1] * st.cos_psi;
            ring[2] += e.f_cone[1] * st.sin_psi;
            for c in 0..3 {
                let v = e.r[c];
                // NaN must never pass for convergence: it makes the residual infinite.
                max_r = if v.is_finite() { max_r.max(v.abs()) } else { f64::INFINITY };
                merit += v * v;
            }
            f_ref = f_ref.max(e.qi).max(e.qo);
            self.evals[j] = e;
        }
        self.slice_load_buffer = loads;
        if self.axisymmetric {
            let e = self.evals[0];
            for j in 1..z {
                self.evals[j] = e;
            }
            ring[0] = inputs.fx + z as f64 * e.f_cone[0];
            ring[1] = 0.0;
            ring[2] = 0.0;
            merit *= z as f64;
        }
        self.hold_prescribed_ring(&mut ring);
        for c in 0..3 {
            let v = ring[c];
            max_r = if v.is_finite() { max_r.max(v.abs()) } else { f64::INFINITY };
            merit += v * v;
        }
        if !merit.is_finite() {
            merit = f64::INFINITY;
        }
        (max_r, merit, f_ref, ring)
    }

    /// No residual on the prescribed cone translations (they are not unknowns).
    fn hold_prescribed_ring(&self, ring: &mut Vector3<f64>) {
        for c in 0..3 {
            if self.prescribed[c].is_some() {
                ring[c] = 0.0;
            }
        }
    }

    /// The ring (cone) residual of [`QuasiStatic::evaluate`] from the current roller
    /// evaluations (not axisymmetric).
    fn ring_residual(&self, _x: &[f64], inputs: &Inputs) -> Vector3<f64> {
        let mut ring = Vector3::new(inputs.fx, inputs.fy, inputs.fz);
        for (e, st) in self.evals.iter().zip(&self.setup) {
            ring[0] += e.f_cone[0];
            ring[1] += e.f_cone[1] * st.cos_psi;
            ring[2] += e.f_cone[1] * st.sin_psi;
        }
        self.hold_prescribed_ring(&mut ring);
        ring
    }

    /// The residual max-norm, merit and reference force of [`QuasiStatic::evaluate`] from the
    /// current roller evaluations and ring residual `ring` (not axisymmetric).
    fn norms(&self, ring: &Vector3<f64>, inputs: &Inputs, fc: f64) -> (f64, f64, f64) {
        let mut max_r: f64 = 0.0;
        let mut merit = 0.0;
        let mut f_ref: f64 = inputs.fx.abs().max(inputs.fy.abs()).max(inputs.fz.abs()).max(fc.abs()).max(1.0);
        for e in &self.evals {
            for c in 0..3 {
                let v = e.r[c];
                max_r = if v.is_finite() { max_r.max(v.abs()) } else { f64::INFINITY };
                merit += v * v;
            }
            f_ref = f_ref.max(e.qi).max(e.qo);
        }
        for c in 0..3 {
            let v = ring[c];
            max_r = if v.is_finite() { max_r.max(v.abs()) } else { f64::INFINITY };
            merit += v * v;
        }
        if !merit.is_finite() {
            merit = f64::INFINITY;
        }
        (max_r, merit, f_ref)
    }

    /// Lightly loaded rollers (total contact load below `light`: at the edge of the load zone
    /// or outside it) barely move the cone, but their few touching slices switch on and off
    /// from one Newton step to the next (a tilted roller rolling onto its end), so they can
    /// hold the whole solve for many global iterations. Each such roller with a residual above
    /// `target` takes its own Newton steps here with the cone held, one roller evaluation
    /// each, with the global step's clamps; a step that does not lower its residual is undone.
    /// The caller recomputes the ring residual (the roller's force on the cone changed by at
    /// most `light`). Returns whether any roller moved.
    fn relax_light_rollers(&mut self, x: &mut [f64], fc: f64, m_fc: f64, m_req: f64, target: f64, light: f64) -> bool {
        let needs = |e: &RollerEval| {
            let size = e.r.amax();
            size > target && size.is_finite() && e.qi + e.qo + e.qf <= light
        };
        self.relax_rollers(x, fc, m_fc, m_req, 10, needs)
    }

    /// A warm start's prediction puts each roller where the solutions before had a roller at
    /// its azimuth, the cone where they continue; at the edge of the load zone, where the zone
    /// grows or shrinks with the inputs, that can leave a roller pressed by the cone but not
    /// yet by the cup or the flange (or the reverse): a residual comparable with its own
    /// loads. The global Newton step then overshoots on the contact that opens or closes
    /// (the flange's Hertz law has no stiffness at zero load) and needs several iterations to
    /// come back. Such rollers (residual above 5 % of their largest contact load and above
    /// 1 % of the largest residual `max_r`) take up to ten Newton steps of their own with
    /// the cone held first (as in `relax_light_rollers`), one roller evaluation each. Ten,
    /// not three: where the flange carries little, Newton's step on its Hertz law (q ~ d^1.5)
    /// cuts the overshoot only about fivefold per step until it is near (32018X at 35 kN in a
    /// smooth time table: 6 global iterations on such a step with three, 4 with ten).
    fn relax_unbalanced_rollers(&mut self, x: &mut [f64], fc: f64, m_fc: f64, m_req: f64, max_r: f64) -> bool {
        let floor = 0.01 * max_r;
        let needs = |e: &RollerEval| {
            let size = e.r.amax();
            size > floor && size > 0.05 * e.qi.max(e.qo).max(e.qf) && size.is_finite()
        };
        self.relax_rollers(x, fc, m_fc, m_req, 10, needs)
    }

    /// Newton steps of single rollers with the cone held, up to `local_iterations` each, for
    /// every roller whose evaluation `needs` it (see `relax_light_rollers`).
    fn relax_rollers<N: Fn(&RollerEval) -> bool>(
        &mut self,
        x: &mut [f64],
        fc: f64,
        m_fc: f64,
        m_req: f64,
        local_iterations: usize,
        needs: N,
    ) -> bool {
        if self.axisymmetric {
            return false;
        }
        let z = self.geometry.z;
        let ns = self.geometry.slices;
        let axial = self.geometry.axial;
        let reg = Matrix3::identity() * self.regularisation;
        if !self.evals.iter().any(&needs) {
            return false;
        }
        let mut loads = std::mem::take(&mut self.slice_load_buffer);
        let mut saved = std::mem::take(&mut self.local_scratch);
        let mut moved = false;
        for j in 0..z {
            let roller_loads = &mut loads[2 * ns * j..2 * ns * (j + 1)];
            for _ in 0..local_iterations {
                if !needs(&self.evals[j]) {
                    break;
                }
                let e = self.evals[j];
                let size = e.r.amax();
                let mut a = e.a - reg;
                if !axial {
                    a[(0, 0)] = -1.0;
                }
                let Some(a_inv) = a.try_inverse() else { break };
                let mut dq = -(a_inv * e.r);
                if !axial {
                    dq[0] = 0.0;
                }
                let mut limit = self.max_step;
                if e.gap > 0.0 {
                    limit = limit.min(e.gap + 1e-9);
                }
                let largest = dq.amax();
                if !largest.is_finite() {
                    break;
                }
                if largest > limit {
                    dq *= limit / largest;
                }
                let old = [x[3 + 3 * j], x[4 + 3 * j], x[5 + 3 * j]];
                let q = [old[0] + dq[0], old[1] + dq[1], old[2] + dq[2]];
                let st = self.setup[j];
                let dr = x[1] * st.cos_psi + x[2] * st.sin_psi;
                saved.clear();
                saved.extend_from_slice(roller_loads);
                let trial = self.eval_roller(j, [x[0], dr], q, fc, m_fc, m_req, roller_loads);
                if trial.r.amax() < size {
                    x[3 + 3 * j..6 + 3 * j].copy_from_slice(&q);
                    self.evals[j] = trial;
                    moved = true;
                } else {
                    roller_loads.copy_from_slice(&saved);
                    break;
                }
            }
        }
        self.local_scratch = saved;
        self.slice_load_buffer = loads;
        moved
    }

    /// Newton step for the current evaluations and ring residual.
    fn newton_step(&mut self, ring: &Vector3<f64>) -> bool {
        if self.axisymmetric {
            return self.newton_step_axisymmetric(ring);
        }
        let z = self.geometry.z;
        let reg = Matrix3::identity() * self.regularisation;
        let mut schur = Matrix3::<f64>::zeros();
        let mut rhs = -ring;
        // Accumulate D and Schur terms. Global cone unknowns c = (dx, dy, dz); local (dx, dr) = T c.
        for j in 0..z {
            let st = self.setup[j];
            let t = Matrix2x3::new(1.0, 0.0, 0.0, 0.0, st.cos_psi, st.sin_psi);
            let e = self.evals[j];
            let mut a = e.a - reg;
            if !self.geometry.axial {
                a[(0, 0)] = -1.0;
            }
            let a_inv = match a.try_inverse() {
                Some(m) => m,
                None => return false,
            };
            let b = e.b * t; // 3x3: d r_j / d c
            let c = t.transpose() * e.b.transpose(); // d ring / d q_j  (J_cr = J_rc^T)
            let d = t.transpose() * e.d * t;
            schur += d - c * a_inv * b;
            rhs += c * a_inv * e.r;
            // store A^{-1} and B for back substitution in place of the blocks
            self.evals[j].a = a_inv;
            self.evals[j].b = e.b;
        }
        // A cone that touches no roller has no stiffness: regularise like the rollers.
        schur -= Matrix3::identity() * (self.regularisation * z as f64);
        hold_prescribed(&mut schur, &mut rhs, &self.prescribed);
        let dc = match schur.try_inverse() {
            Some(s) => s * rhs,
            None => return false,
        };
        self.step[0] = dc[0];
        self.step[1] = dc[1];
        self.step[2] = dc[2];
        for j in 0..z {
            let st = self.setup[j];
            let t = Matrix2x3::new(1.0, 0.0, 0.0, 0.0, st.cos_psi, st.sin_psi);
            let e = &self.evals[j];
            let dq = e.a * (-e.r - e.b * (t * dc));
            for c in 0..3 {
                self.step[3 + 3 * j + c] = dq[c];
            }
            if !self.geometry.axial {
                self.step[3 + 3 * j] = 0.0;
            }
        }
        // Clamp per block (cone, each roller): no component moves more than max_step in one
        // iteration, and a roller touching nothing no more than its smallest gap (plus a
        // nanometre), so it closes the gap instead of plunging into a contact. Per block, so
        // one free roller's long regularised step does not shrink everybody's Newton step.
        for (b, block) in self.step.chunks_mut(3).enumerate() {
            let largest = block.iter().fold(0.0_f64, |m, s| m.max(s.abs()));
            if !largest.is_finite() {
                return false;
            }
            let mut limit = self.max_step;
            if b > 0 {
                let gap = self.evals[b - 1].gap;
                if gap > 0.0 {
                    limit = limit.min(gap + 1e-9);
                }
            }
            if largest > limit {
                let f = limit / largest;
                block.iter_mut().for_each(|s| *s *= f);
            }
        }
        true
    }

    /// Newton step when all rollers are equal: the cone moves only axially, every roller
    /// takes roller 1's step. The axial Schur complement is Z times one roller's.
    fn newton_step_axisymmetric(&mut self, ring: &Vector3<f64>) -> bool {
        let z = self.geometry.z as f64;
        let fixed_axial = self.prescribed[0].is_some();
        let e = self.evals[0];
        let mut a = e.a - Matrix3::identity() * self.regularisation;
        if !self.geometry.axial {
            a[(0, 0)] = -1.0;
        }
        let Some(a_inv) = a.try_inverse() else { return false };
        let b = e.b.column(0).into_owned(); // d r / d(cone dx)
        let dx = if fixed_axial {
            0.0
        } else {
            let s = z * (e.d[(0, 0)] - (b.transpose() * a_inv * b)[(0, 0)]) - self.regularisation * z;
            let rhs = -ring[0] + z * (b.transpose() * a_inv * e.r)[(0, 0)];
            rhs / s
        };
        let mut dq = a_inv * (-e.r - b * dx);
        if !self.geometry.axial {
            dq[0] = 0.0;
        }
        let mut limit = self.max_step;
        if e.gap > 0.0 {
            limit = limit.min(e.gap + 1e-9);
        }
        let largest = dq.amax();
        if !(largest.is_finite() && dx.is_finite()) {
            return false;
        }
        if largest > limit {
            dq *= limit / largest;
        }
        self.step[0] = dx.clamp(-self.max_step, self.max_step);
        self.step[1] = 0.0;
        self.step[2] = 0.0;
        for j in 0..self.geometry.z {
            for c in 0..3 {
                self.step[3 + 3 * j + c] = dq[c];
            }
        }
        true
    }

    /// Rollers off the cone raceway rest on the cup and the flange under their centrifugal
    /// force alone. Where such a roller has lost either seat, place it analytically: loads
    /// from the force triangle Qo n_o + Qf n_f + Fc e_r = 0, interferences from the inverse
    /// contact laws, position from the two linear interference equations (tilt kept).
    /// Returns whether any roller moved. Its Jacobian is then regular and Newton converges
    /// quadratically instead of crawling along a zero-stiffness direction.
    fn seat_free_rollers(&self, x: &mut [f64], fc: f64) -> bool {
        let g = &self.geometry;
        let mid = g.slices / 2;
        let no = g.cup.normal;
        let mut moved = false;
        for j in 0..g.z {
            let e = &self.evals[j];
            let seated = e.qo > 0.0 && (e.qf > 0.0 || g.flange.is_none());
            if e.qi > 0.0 || seated || (fc <= 0.0 && e.gap >= 0.0) {
                continue;
            }
            let st = &self.setup[j];
            let theta = x[5 + 3 * j] / self.ls;
            let s = g.slices as f64;
            // delta_o(mid) = -(a n_ox + rho n_or) - theta lever + gap_cup - crown
            let cup_rest = -theta * g.cup.lever[mid] + st.gap_cup - self.cup_table_of(j).crown[mid];
            match &g.flange {
                Some(f) => {
                    let nf = f.normal;
                    let m = nalgebra::Matrix2::new(no[0], nf[0], no[1], nf[1]);
                    let loads = m.try_inverse().map(|mi| mi * Vector2::new(0.0, -fc.max(0.0)));
                    let (qo, qf) = match loads {
                        Some(l) => (l[0].max(0.0), l[1].max(0.0)),
                        None => continue,
                    };
                    let d_o = g.cup.law.deflection(mid, qo / s);
                    let d_f = if qf > 0.0 {
                        libm::pow(qf / f.hertz.stiffness, 2.0 / 3.0)
                    } else {
                        0.0
                    };
                    // delta_f = (dx - a) n_fx + (dr - rho) n_fr + gamma chi_f - theta lever_f
                    let dr = x[1] * st.cos_psi + x[2] * st.sin_psi;
                    let flange_rest = x[0] * nf[0] + dr * nf[1] + st.gamma * self.flange_chi - theta * f.lever;
                    // [-n_ox -n_or; -n_fx -n_fr] (a, rho) = (d_o - cup_rest, d_f - flange_rest)
                    let a = nalgebra::Matrix2::new(-no[0], -no[1], -nf[0], -nf[1]);
                    if let Some(ai) = a.try_inverse() {
                        let v = ai * Vector2::new(d_o - cup_rest, d_f - flange_rest);
                        x[3 + 3 * j] = v[0];
                        x[4 + 3 * j] = v[1];
                        moved = true;
                    }
                }
                None => {
                    // Cylindrical: radial seat on the cup only (axial held at zero).
                    let d_o = g.cup.law.deflection(mid, fc.max(0.0) / s);
                    x[4 + 3 * j] = (cup_rest - d_o) / no[1];
                    moved = true;
                }
            }
        }
        moved
    }

    /// Rigid-ring start values: every roller carries the axial load share (or the
    /// displacement preload is met), placed to meet cone, cup and flange.
    fn initial_guess(&self, x: &mut [f64], inputs: &Inputs, fc: f64, load_scale: f64) {
        let g = &self.geometry;
        let z = g.z;
        x.iter_mut().for_each(|v| *v = 0.0);
        let ni = g.cone.normal;
        let no = g.cup.normal;
        let mid = g.slices / 2;
        let s = g.slices as f64;
        let place = |fa: f64| -> Option<[f64; 3]> {
            // Roller loads from 2-D force balance with cup load Qo = fa / (Z sin a_o).
            let f = g.flange.as_ref()?;
            let qo = fa / (z as f64 * (-no[0]).max(1e-6));
            // Qi ni + Qf nf + Qo no + fc e_r = 0
            let nf = f.normal;
            let m = nalgebra::Matrix2::new(ni[0], nf[0], ni[1], nf[1]);
            let rhs = Vector2::new(-qo * no[0], -qo * no[1] - fc);
            let sol = m.try_inverse()? * rhs;
            let (qi, qf) = (sol[0].max(0.0), sol[1].max(0.0));
            let di = g.cone.law.deflection(mid, qi / s);
            // the cup sits (c/2 + mean lobe depth) cos a_o further out: the roller must travel
            // that far before it deflects the cup
            let mean_lobe = if self.params.outer_lobes > 0 {
                0.5 * self.params.outer_waveform
            } else {
                0.0
            };
            let cup_gap = (0.5 * self.params.clearance + mean_lobe) * libm::cos(g.cup_angle);
            let dol = g.cup.law.deflection(mid, qo / s) + cup_gap;
            let dfl = if qf > 0.0 {
                libm::pow(qf / f.hertz.stiffness, 2.0 / 3.0)
            } else {
                0.0
            };
            // dol = -(a no_x + rho no_r) (+ the gap); di = (dx - a) ni_x - rho ni_r; dfl = (dx - a) nf_x - rho nf_r
            let mm = Matrix3::new(-no[0], -no[1], 0.0, -ni[0], -ni[1], ni[0], -nf[0], -nf[1], nf[0]);
            let v = mm.try_inverse()? * Vector3::new(dol, di, dfl);
            Some([v[0], v[1], v[2]])
        };
        if g.axial {
            let fr = (inputs.fy * inputs.fy + inputs.fz * inputs.fz).sqrt();
            let tan_o = libm::tan(g.cup_angle);
            let sol = match self.prescribed[0] {
                None => {
                    let fa = (inputs.fx.max(0.0) + 0.0 * fr).max(1.2 * fr * tan_o).max(1.0) * load_scale;
                    place(fa)
                }
                Some(target) => {
                    // Bisect the axial load giving the prescribed axial displacement.
                    if target <= 0.0 {
                        None
                    } else {
                        let (mut lo, mut hi) = (1e-3_f64, 1e8_f64);
                        for _ in 0..80 {
                            let m = (lo * hi).sqrt();
                            match place(m) {
                                Some(v) if v[2] > target => hi = m,
                                _ => lo = m,
                            }
                        }
                        place((lo * hi).sqrt())
                    }
                }
            };
            if let Some([a, rho, dx]) = sol {
                x[0] = self.prescribed[0].unwrap_or(dx);
                for j in 0..z {
                    x[3 + 3 * j] = a;
                    x[4 + 3 * j] = rho;
                }
            } else if let Some(dx) = self.prescribed[0] {
                x[0] = dx;
            }
        } else {
            // Cylindrical: rollers sit on the cup under their centrifugal force.
            let dol = g.cup.law.deflection(mid, fc.max(0.0) / s);
            for j in 0..z {
                x[4 + 3 * j] = dol;
            }
        }
    }

    /// Solve the equilibrium for `inputs` with roller 1 at `cage_angle`. `warm` holds the
    /// unknowns of the previous solve (replaced by the solution); `out` receives everything.
    /// With `skewModel` the roller skew equilibrium is solved too (see `skew.rs`).
    pub fn solve(&mut self, inputs: &Inputs, cage_angle: f64, warm: &mut Vec<f64>, out: &mut Outputs) -> Result<SolveReport, ModelError> {
        // In displacement causality the force inputs are not loads on the cone.
        let displaced;
        let inputs = if self.params.causality == LoadCausality::Displacement {
            displaced = Inputs {
                fx: 0.0,
                fy: 0.0,
                fz: 0.0,
                axial_displacement: 0.0,
                ..*inputs
            };
            &displaced
        } else {
            inputs
        };
        if self.skew.is_some() {
            self.solve_skew(inputs, cage_angle, warm, out)
        } else {
            self.solve_in_plane(inputs, cage_angle, warm, out)
        }
    }

    /// [`QuasiStatic::solve`] as the seat of the quasi-dynamic model: the same equilibrium
    /// and warm start, with the outputs only as far as the loads, the cone's place and the
    /// largest pressure (the range check's); the friction torque, the lives and the
    /// stiffness, which the quasi-dynamic model takes from its own contacts or does not
    /// need per step, are not computed.
    pub fn solve_seat(
        &mut self,
        inputs: &Inputs,
        cage_angle: f64,
        warm: &mut Vec<f64>,
        out: &mut Outputs,
    ) -> Result<SolveReport, ModelError> {
        self.seat_only = true;
        let result = self.solve(inputs, cage_angle, warm, out);
        self.seat_only = false;
        result
    }

    /// The in-plane equilibrium (3 unknowns per roller, no skew).
    fn solve_in_plane(
        &mut self,
        inputs: &Inputs,
        cage_angle: f64,
        warm: &mut Vec<f64>,
        out: &mut Outputs,
    ) -> Result<SolveReport, ModelError> {
        self.prepare(inputs, cage_angle);
        let n = self.n_unknowns();
        let (fc, m_fc, m_req) = self.inertial_loads(inputs);
        let tol = (self.params.tolerance * 1e-3).clamp(1e-13, 1e-9);

        // The warm start: the unknowns, the cage angle and the inputs they were solved at (a
        // block of n + 1 + WARM_INPUTS; n + 1 from an older caller: no inputs), the same block
        // of the solve before, and the azimuth table of converged solutions (`table_record`).
        // It stays in place; the unknowns are solved in a scratch vector.
        let block = n + 1 + WARM_INPUTS;
        let full = 2 * block + self.table_len();
        let cold = !(warm.len() == n + 1 || warm.len() == block || warm.len() == full);
        let now = warm_inputs(inputs);
        let mut x = std::mem::take(&mut self.x);
        x.clear();
        if cold {
            x.resize(n, 0.0);
        } else {
            x.extend_from_slice(&warm[..n]);
            // the table first: with constant inputs it interpolates converged solutions at
            // nearby azimuths (fourth order); the temporal extrapolation is linear
            let predicted = warm.len() == full
                && (self.table_predict(&warm[2 * block..], &mut x, cage_angle, &now)
                    || self.extrapolate(&mut x, &warm[..2 * block], cage_angle, &now));
            if !predicted {
                self.predict(&mut x, cage_angle - warm[n]);
                if warm.len() == full {
                    self.predict_trend(&mut x, &warm[..2 * block], cage_angle, &now);
                }
            }
        }
        let prescribed = self.prescribed;
        let result = if cold {
            self.initial_guess(&mut x, inputs, fc, 1.0);
            self.newton(&mut x, inputs, fc, m_fc, m_req, tol, prescribed, false)
        } else {
            self.newton(&mut x, inputs, fc, m_fc, m_req, tol, prescribed, true)
        };
        let report = match result {
            Ok(r) => r,
            Err(first) => {
                // Load stepping from a fresh start: 10 %, 20 %, ... of the loads.
                let mut ok = None;
                let mut xs = x.clone();
                self.initial_guess(&mut xs, inputs, fc, 0.1);
                let mut stepped = *inputs;
                let mut total_iters = 0;
                for stage in 1..=10 {
                    let f = stage as f64 / 10.0;
                    stepped.fx = inputs.fx * f;
                    stepped.fy = inputs.fy * f;
                    stepped.fz = inputs.fz * f;
                    stepped.axial_displacement = inputs.axial_displacement * f;
                    stepped.displacement = inputs.displacement.map(|v| v * f);
                    self.prescribed = prescribed.map(|v| v.map(|v| v * f));
                    match self.newton(&mut xs, &stepped, fc, m_fc, m_req, tol, self.prescribed, false) {
                        Ok(r) => {
                            total_iters += r.iterations;
                            if stage == 10 {
                                ok = Some(SolveReport {
                                    iterations: total_iters,
                                    ..r
                                });
                            }
                        }
                        Err(_) => break,
                    }
                }
                match ok {
                    Some(r) => {
                        x = xs;
                        r
                    }
                    None => {
                        // the warm start stays as it was: a failed solve changes no state
                        self.x = x;
                        return Err(first);
                    }
                }
            }
        };
        // the speeds of the last solve, from its block of the warm start (part of the FMU
        // state, so a restored state decides as the original did); a first solve counts as
        // held, so that constant inputs read the table from the start
        let speed_held = warm.len() < block || (warm[n + 1] == now[0] && warm[n + 1 + 10] == now[10]);
        self.write_outputs(&x, inputs, report, speed_held, out);
        if let Err(e) = load_within_range(out, &report) {
            self.x = x;
            return Err(e);
        }
        if warm.len() == full {
            // this solve's block becomes the previous one
            warm.copy_within(0..block, block);
        } else {
            // from a shorter (or no) warm start: its block, if any, is the previous one (inputs
            // unknown if it had none), the table empty (allocates on the first solves only)
            let mut w = vec![f64::NAN; full];
            if !cold {
                let m = warm.len().min(block);
                w[block..block + m].copy_from_slice(&warm[..m]);
            }
            *warm = w;
        }
        warm[..n].copy_from_slice(&x);
        warm[n] = cage_angle;
        warm[n + 1..block].copy_from_slice(&now);
        self.table_record(&mut warm[2 * block..], &x, cage_angle, &now, report.residual <= 0.1 * tol);
        self.x = x;
        Ok(report)
    }

    /// Length of the azimuth table in the warm start.
    fn table_len(&self) -> usize {
        1 + WARM_INPUTS + 4 * TABLE_BINS * self.geometry.z + 4 * TABLE_BINS
    }

    /// Whether the table predictor applies: identical rollers (then a roller's solution is a
    /// function of its azimuth alone) and a solve that is not axisymmetric.
    fn table_applies(&self) -> bool {
        let dd = &self.params.roller_dd;
        !self.axisymmetric && dd.iter().all(|d| *d == dd[0])
    }

    /// Record the solution `x` (roller 1 at `cage_angle`) in the azimuth table: with constant
    /// inputs the equilibrium is periodic, each roller's unknowns a function of its azimuth
    /// and the cone's of the cage phase (the cage angle modulo the pitch). The table keeps, in
    /// TABLE_BINS bins per pitch, the latest solution seen there with its exact azimuth; it is
    /// emptied when the inputs change. Only a solution converged well below the tolerance
    /// (`converged_below`: residual at most a tenth of it) replaces a recorded one: a solve
    /// that stops at the prediction (no Newton step) is only as accurate as the table's
    /// nodes, and recording it would let the nodes drift up to the tolerance, where half the
    /// predictions fail it (32018X at constant load: 1.1 Newton iterations per step, 0.4 with
    /// this rule and the table tried first). Layout: 1 (version), the inputs, per roller bin
    /// (psi, a, rho, theta L_s), per cone bin (phase, x, y, z).
    fn table_record(&self, table: &mut [f64], x: &[f64], cage_angle: f64, now: &[f64; WARM_INPUTS], converged_below: bool) {
        if !self.table_applies() {
            return;
        }
        let z = self.geometry.z;
        let pitch = TAU / z as f64;
        let (head, rest) = table.split_at_mut(1 + WARM_INPUTS);
        if head[0] != 1.0 || head[1..] != now[..] {
            head[0] = 1.0;
            head[1..].copy_from_slice(now);
            rest.fill(f64::NAN);
        }
        let nb = TABLE_BINS * z;
        let (rollers, cone) = rest.split_at_mut(4 * nb);
        for j in 0..z {
            let psi = wrap_to(cage_angle + pitch * j as f64, TAU);
            let b = ((psi / TAU * nb as f64) as usize).min(nb - 1);
            if converged_below || rollers[4 * b].is_nan() {
                rollers[4 * b..4 * b + 4].copy_from_slice(&[psi, x[3 + 3 * j], x[4 + 3 * j], x[5 + 3 * j]]);
            }
        }
        let phase = wrap_to(cage_angle, pitch);
        let b = ((phase / pitch * TABLE_BINS as f64) as usize).min(TABLE_BINS - 1);
        if converged_below || cone[4 * b].is_nan() {
            cone[4 * b..4 * b + 4].copy_from_slice(&[phase, x[0], x[1], x[2]]);
        }
    }

    /// Table predictor: with the inputs of the table unchanged, every roller's unknowns and the
    /// cone's are interpolated (cubic, on the four nearest recorded azimuths, two on each
    /// side within two pitches) from the solutions recorded at nearby azimuths in earlier
    /// steps. Far finer than the spatial predictor's one sample per pitch once the table has
    /// filled (rollers that advance a non-integral number of pitches per step sample new
    /// azimuths every step). False (x untouched) where any node is missing.
    fn table_predict(&mut self, table: &[f64], x: &mut [f64], cage_angle: f64, now: &[f64; WARM_INPUTS]) -> bool {
        if !self.table_applies() || table.len() != self.table_len() || table[0] != 1.0 || table[1..1 + WARM_INPUTS] != now[..] {
            return false;
        }
        let z = self.geometry.z;
        let pitch = TAU / z as f64;
        let nb = TABLE_BINS * z;
        let (rollers, cone) = table[1 + WARM_INPUTS..].split_at(4 * nb);
        let mut pred = [0.0; 3];
        if !table_interpolate(cone, TABLE_BINS, pitch, wrap_to(cage_angle, pitch), &mut pred) {
            return false;
        }
        // all or nothing: into the scratch first
        let mut trial = std::mem::take(&mut self.trial);
        trial[..3].copy_from_slice(&pred);
        let mut ok = true;
        for j in 0..z {
            let psi = wrap_to(cage_angle + pitch * j as f64, TAU);
            if !table_interpolate(rollers, nb, TAU, psi, &mut pred) {
                ok = false;
                break;
            }
            trial[3 + 3 * j..6 + 3 * j].copy_from_slice(&pred);
        }
        if ok {
            x[..3 + 3 * z].copy_from_slice(&trial[..3 + 3 * z]);
        }
        self.trial = trial;
        ok
    }

    /// Temporal predictor: when the cage moved little since the last solve and the one before
    /// (at most a tenth of the roller pitch each time) and the inputs changed along the same
    /// line (constant, or a ramp: a smooth time table), every unknown continues along its
    /// own path: x + r (x - x_prev), r the ratio of this cage advance to the last one. `blocks`:
    /// the last two solves' blocks (see `solve_in_plane`); `x` holds the last solution and
    /// receives the prediction. Far more accurate than the spatial predictor where the rollers
    /// move little per step (slow shafts, small steps) and with rollers of different diameters.
    fn extrapolate(&self, x: &mut [f64], blocks: &[f64], cage_angle: f64, now: &[f64; WARM_INPUTS]) -> bool {
        if self.axisymmetric {
            return false;
        }
        let n = x.len();
        let block = n + 1 + WARM_INPUTS;
        let pitch = TAU / self.geometry.z as f64;
        let wrap = |a: f64| a - TAU * round_int(a / TAU);
        let d = wrap(cage_angle - blocks[n]);
        let d1 = wrap(blocks[n] - blocks[block + n]);
        if !(d1.abs() > 0.0 && d1.abs() <= 0.1 * pitch && d.abs() <= 0.1 * pitch) {
            return false;
        }
        let ratio = d / d1;
        let (u, u1) = (&blocks[n + 1..block], &blocks[block + n + 1..2 * block]);
        for i in 0..WARM_INPUTS {
            let step = now[i] - u[i];
            let last = u[i] - u1[i];
            if !((step - ratio * last).abs() <= 0.1 * step.abs() + 1e-12 * now[i].abs().max(1.0)) {
                return false;
            }
        }
        let prev = &blocks[block..block + n];
        for i in 0..n {
            x[i] += ratio * (x[i] - prev[i]);
        }
        true
    }

    /// Whether the spatial predictor applies: identical rollers, not axisymmetric.
    fn spatial_applies(&self) -> bool {
        let dd = &self.params.roller_dd;
        !self.axisymmetric && dd.iter().all(|d| *d == dd[0])
    }

    /// Predictor for a cage advance `shift` (rad) since the warm start: the load zone stays
    /// in place while the rollers move through it, so each roller starts from the previous
    /// solution interpolated (periodic in azimuth, `spatial_interpolate`) at its new position. Only for
    /// identical rollers; a roller with its own diameter deviation keeps its own state.
    fn predict(&mut self, x: &mut [f64], shift: f64) {
        if shift == 0.0 || !shift.is_finite() || !self.spatial_applies() {
            return;
        }
        let mut prev = std::mem::take(&mut self.trial);
        prev[..x.len()].copy_from_slice(x);
        spatial_interpolate(self.geometry.z, shift, &prev, x);
        self.trial = prev;
    }

    /// Space-time predictor, after the spatial one (`x`: the last solution interpolated at the
    /// rollers' new azimuths) where the temporal one does not apply (the cage moved more
    /// than a tenth of a pitch, or the inputs left a straight line): in a smooth time table
    /// the equilibrium changes with the inputs as well as with the azimuth, and the spatial
    /// predictor ignores the first. The solve before the last, interpolated at the same new
    /// azimuths, gives the change of the solution over the last step as a field of the
    /// azimuth (and the cone's), which continues over this step: x + (x - x_before), both
    /// interpolated at the new azimuths. Only when that step is this one's repetition: the
    /// same cage advance (modulo a turn: the same speed and step size), some input changed
    /// over the last step, and every input's linear continuation is no further from the
    /// new input than the last value is (a ramp, or the sine of a time table away from its
    /// turning points; not a jump after a constant, nor the stop of a ramp). `blocks`: the
    /// last two solves' blocks (see `solve_in_plane`). Returns whether it applied.
    fn predict_trend(&mut self, x: &mut [f64], blocks: &[f64], cage_angle: f64, now: &[f64; WARM_INPUTS]) -> bool {
        if !self.spatial_applies() {
            return false;
        }
        let n = x.len();
        let block = n + 1 + WARM_INPUTS;
        let (last, before) = (&blocks[..block], &blocks[block..2 * block]);
        let wrap = |a: f64| a - TAU * round_int(a / TAU);
        let d = cage_angle - last[n];
        let d1 = last[n] - before[n];
        let pitch = TAU / self.geometry.z as f64;
        if !(wrap(d - d1).abs() <= 1e-9 * pitch) {
            return false;
        }
        let (u, u1) = (&last[n + 1..block], &before[n + 1..block]);
        let mut changed = false;
        for i in 0..WARM_INPUTS {
            let step = now[i] - u[i];
            let prior = u[i] - u1[i];
            if !((step - prior).abs() <= step.abs() + 1e-12 * now[i].abs().max(1.0)) {
                return false;
            }
            changed |= prior != 0.0;
        }
        if !changed || !before[..n].iter().all(|v| v.is_finite()) {
            return false;
        }
        // the solve before the last at the new azimuths, in the step buffer (free until the
        // first Newton step)
        let mut older = std::mem::take(&mut self.step);
        older[..3].copy_from_slice(&before[..3]);
        spatial_interpolate(self.geometry.z, cage_angle - before[n], &before[..n], &mut older[..n]);
        for i in 0..n {
            x[i] += x[i] - older[i];
        }
        self.step = older;
        true
    }

    /// Damped Newton from `x` (`predicted`: a warm start's prediction, whose unbalanced
    /// rollers are first relaxed onto the cone, see `relax_unbalanced_rollers`).
    #[allow(clippy::too_many_arguments)]
    fn newton(
        &mut self,
        x: &mut [f64],
        inputs: &Inputs,
        fc: f64,
        m_fc: f64,
        m_req: f64,
        tol: f64,
        prescribed: [Option<f64>; 3],
        predicted: bool,
    ) -> Result<SolveReport, ModelError> {
        for (c, v) in prescribed.iter().enumerate() {
            if let Some(v) = v {
                x[c] = *v;
            }
        }
        if !self.geometry.axial {
            for j in 0..self.geometry.z {
                x[3 + 3 * j] = 0.0;
            }
        }
        if self.axisymmetric {
            // Start from a symmetric point: cone centred, every roller as roller 1.
            x[1] = 0.0;
            x[2] = 0.0;
            let (first, rest) = x[3..].split_at_mut(3);
            for block in rest.chunks_mut(3) {
                block.copy_from_slice(first);
            }
        }
        let (mut max_r, mut merit, mut f_ref, mut ring) = self.evaluate(x, inputs, fc, m_fc, m_req);
        if self.seat_free_rollers(x, fc) {
            (max_r, merit, f_ref, ring) = self.evaluate(x, inputs, fc, m_fc, m_req);
        }
        if predicted && max_r > tol * f_ref && self.relax_unbalanced_rollers(x, fc, m_fc, m_req, max_r) {
            ring = self.ring_residual(x, inputs);
            (max_r, merit, f_ref) = self.norms(&ring, inputs, fc);
        }
        let mut iterations = 0;
        let mut history = [0.0_f64; 4];
        let mut extrapolated = self.evals.iter().any(|e| e.extrapolated);
        let limit = self.runaway_limit();
        loop {
            if max_r > tol * f_ref && self.relax_light_rollers(x, fc, m_fc, m_req, 0.1 * tol * f_ref, 1e-3 * f_ref) {
                ring = self.ring_residual(x, inputs);
                (max_r, merit, f_ref) = self.norms(&ring, inputs, fc);
                extrapolated = self.evals.iter().any(|e| e.extrapolated);
            }
            if max_r <= tol * f_ref {
                return Ok(SolveReport {
                    iterations,
                    residual: max_r / f_ref,
                    contact_law_extrapolated: extrapolated,
                    ..SolveReport::default()
                });
            }
            if iterations >= MAX_ITERATIONS {
                break;
            }
            iterations += 1;
            if !self.newton_step(&ring) {
                break;
            }
            // Damped update [Y22], non-monotone: contact problems often pass through a larger
            // residual on the way (rollers entering and leaving the load zone, a ring crossing
            // a clearance and landing on its rollers), so a full step is taken while its merit
            // stays below 100x the worst of the last few iterates, and a halved step is taken
            // as long as it does not increase the merit (across a gap the merit is flat).
            history[iterations as usize % history.len()] = merit;
            let allowed = 100.0 * history.iter().fold(0.0_f64, |m, h| m.max(*h));
            let mut alpha = 1.0;
            let mut accepted = false;
            let mut trial = std::mem::take(&mut self.trial);
            for _ in 0..12 {
                for i in 0..x.len() {
                    trial[i] = x[i] + alpha * self.step[i];
                }
                let (mut mr, mut me, mut fr, mut rg) = self.evaluate(&trial, inputs, fc, m_fc, m_req);
                // A full step the merit rejects: where it presses the cone into a roller the
                // step left in place (a roller the cone did not touch, so the linear model did
                // not move it), that roller alone takes its own steps at the trial point first
                // (`relax_unbalanced_rollers`) instead of the whole step being cut down.
                if alpha == 1.0 && !(me <= merit || me < allowed) && self.relax_unbalanced_rollers(&mut trial, fc, m_fc, m_req, mr) {
                    rg = self.ring_residual(&trial, inputs);
                    (mr, me, fr) = self.norms(&rg, inputs, fc);
                }
                if me <= merit || (me < allowed && alpha == 1.0) || alpha < 1e-3 {
                    x.copy_from_slice(&trial);
                    max_r = mr;
                    merit = me;
                    f_ref = fr;
                    ring = rg;
                    accepted = true;
                    break;
                }
                alpha *= 0.5;
            }
            self.trial = trial;
            if !accepted {
                break;
            }
            if self.seat_free_rollers(x, fc) {
                (max_r, merit, f_ref, ring) = self.evaluate(x, inputs, fc, m_fc, m_req);
            }
            extrapolated = self.evals.iter().any(|e| e.extrapolated);
            let stalled = self
                .step
                .iter()
                .zip(x.iter())
                .all(|(s, v)| (alpha * s).abs() <= 1e-15 * v.abs().max(1e-12));
            if x.iter().any(|v| !v.is_finite() || v.abs() > limit) {
                break;
            }
            if stalled && max_r <= 1e3 * tol * f_ref {
                return Ok(SolveReport {
                    iterations,
                    residual: max_r / f_ref,
                    contact_law_extrapolated: extrapolated,
                    ..SolveReport::default()
                });
            }
        }
        Err(self.explain_failure(x, inputs, max_r / f_ref, iterations))
    }

    /// Largest displacement the solver accepts before it declares a runaway: 5 % of the roller
    /// diameter, plus the axial travel a positive clearance needs to seat a tapered cone.
    fn runaway_limit(&self) -> f64 {
        let g = &self.geometry;
        let seat = if g.axial && self.params.clearance > 0.0 {
            0.5 * self.params.clearance / libm::tan(g.cup_angle)
        } else {
            0.0
        };
        0.05 * 2.0 * g.mean_radius + seat
    }

    /// The axial force below which the rollers' centrifugal force, resting on cup and flange,
    /// pushes the cone out (force triangle Qo n_o + Qf n_f + Fc e_r = 0; the flange pushes the
    /// cone back by Qf sin a_f per roller).
    fn seating_force(&self, inputs: &Inputs) -> f64 {
        let g = &self.geometry;
        let (fc, _, _) = self.inertial_loads(inputs);
        match (&g.flange, g.axial) {
            (Some(f), true) if fc > 0.0 => {
                let (no, nf) = (g.cup.normal, f.normal);
                let m = nalgebra::Matrix2::new(no[0], nf[0], no[1], nf[1]);
                m.try_inverse()
                    .map(|mi| (mi * Vector2::new(0.0, -fc))[1].max(0.0) * nf[0] * g.z as f64)
                    .unwrap_or(0.0)
            }
            _ => 0.0,
        }
    }

    /// Why no equilibrium was found, in the user's terms (always with a reason after "; ").
    fn explain_failure(&self, x: &[f64], inputs: &Inputs, residual: f64, iterations: u32) -> ModelError {
        let fr = (inputs.fy * inputs.fy + inputs.fz * inputs.fz).sqrt();
        let g = &self.geometry;
        let limit = self.runaway_limit();
        let runaway = x.iter().any(|v| !v.is_finite() || v.abs() > limit);
        let mut message = format!(
            "Newton solver stopped after {iterations} iterations with relative residual {residual:.3e} (Fx = {:.6} N, Fr = {:.6} N, speed = {:.6} rad/s)",
            inputs.fx, fr, inputs.speed
        );
        let force_preload = g.axial && self.prescribed[0].is_none();
        let seat = self.seating_force(inputs);
        let tan_o = libm::tan(g.cup_angle);
        if force_preload && inputs.fx <= seat * 1.05 && fr <= inputs.fx.max(0.0) / tan_o {
            message.push_str(&format!(
                "; the bearing is not seated: at this speed the rollers' centrifugal force pushes the cone out through the flange with about {seat:.1} N, and Fx = {:.1} N does not hold it; a tapered roller bearing running at speed needs a minimum axial load",
                inputs.fx
            ));
        } else if force_preload && inputs.fx < fr * tan_o + seat {
            message.push_str(&format!(
                "; a single tapered roller bearing needs an axial force of the order of Fr tan(cup angle) = {:.1} N (plus about {seat:.1} N against the rollers' centrifugal force at this speed) to carry a radial load, and Fx = {:.1} N does not seat it",
                fr * tan_o,
                inputs.fx
            ));
        } else if g.axial && self.prescribed[0].is_some_and(|dx| dx <= 0.0) && (fr > 0.0 || self.prescribed[1].is_some()) {
            message.push_str("; with an axial displacement <= 0 the cone is not seated");
        } else if runaway {
            message.push_str(&format!(
                "; displacements exceeded {limit:.3e} m (5 % of the roller diameter, plus the seating travel of the clearance) without an equilibrium"
            ));
            return ModelError::OutOfRange { message };
        } else {
            message.push_str(&format!(
                "; the solver stalled {} equilibrium: the contact state keeps switching between iterations, as at extreme shaft deflections, deep or many lobes, or very few slices; more slices or smaller input steps per communication step may help",
                if residual < 1e-2 { "close to" } else { "away from" }
            ));
        }
        ModelError::NoEquilibrium { message }
    }

    /// The outputs at the solution `x`; `speed_held`: the shaft speeds are those of the last
    /// solve (the friction tables serve them).
    fn write_outputs(&mut self, x: &[f64], inputs: &Inputs, report: SolveReport, speed_held: bool, out: &mut Outputs) {
        let z = self.geometry.z;
        let (mut my, mut mz, mut fx, mut fy, mut fz) = (0.0, 0.0, 0.0, 0.0, 0.0);
        // the cup contact's load acts along the cup raceway's normal, outwards at cos(a_o)
        let cup_radial = libm::cos(self.geometry.cup_angle);
        let (mut housing_fy, mut housing_fz) = (0.0, 0.0);
        for j in 0..z {
            let e = &self.evals[j];
            let st = &self.setup[j];
            // Reaction: moment the shaft applies = -(moment of roller forces on the cone).
            my += st.sin_psi * e.m_cone;
            mz -= st.cos_psi * e.m_cone;
            fx -= e.f_cone[0];
            fy -= e.f_cone[1] * st.cos_psi;
            fz -= e.f_cone[1] * st.sin_psi;
            housing_fy += e.qo * cup_radial * st.cos_psi;
            housing_fz += e.qo * cup_radial * st.sin_psi;
            out.qi[j] = e.qi;
            out.qo[j] = e.qo;
            out.qf[j] = e.qf;
            out.qc[j] = 0.0;
            out.tilt[j] = x[5 + 3 * j] / self.ls;
            out.skew[j] = 0.0;
            out.nit[j] = e.nit;
            out.not[j] = e.not;
            out.nft[j] = e.nft;
        }
        out.cone_x = x[0];
        out.cone_y = x[1];
        out.cone_z = x[2];
        out.reaction_fx = if self.geometry.axial { fx } else { 0.0 };
        out.reaction_my = my;
        out.reaction_mz = mz;
        out.cage_speed = self.cage_speed(inputs);
        out.solver_iterations = report.iterations as i32;
        out.solver_residual = report.residual;
        // Friction torque, power loss and the skew moments of the traction forces.
        // The slice loads of the last evaluation, which was at the solution `x`; for the start
        // of the dynamic model recomputed by `slice_loads` at `x` (the interference summed in its
        // order, which fixes the start's outputs to the bit).
        let evaluated = if self.axisymmetric { 1 } else { self.geometry.z };
        if !self.cone_table.vector {
            let ns = self.geometry.slices;
            let mut loads = std::mem::take(&mut self.slice_load_buffer);
            for j in 0..evaluated {
                let (cone, cup) = loads[2 * ns * j..2 * ns * (j + 1)].split_at_mut(ns);
                self.slice_loads(x, j, cone, cup);
            }
            self.slice_load_buffer = loads;
        }
        if self.seat_only {
            let loads = &self.slice_load_buffer[..2 * self.geometry.slices * evaluated];
            out.pressure_max = self.geometry.max_raceway_pressure(loads);
            out.safety_s0 = self.rating.static_safety((fy * fy + fz * fz).sqrt(), out.reaction_fx);
            return;
        }
        let torque = self.friction.evaluate(
            &self.geometry,
            &self.evals,
            evaluated,
            inputs,
            self.params.lubrication,
            &self.slice_load_buffer,
            speed_held,
            out,
        );
        out.friction_torque_raceway = torque.raceway;
        out.friction_torque_flange = torque.flange;
        out.friction_torque_cage = 0.0;
        out.friction_torque = torque.raceway + torque.flange;
        out.friction_torque_cone = torque.cone;
        out.friction_torque_cup = torque.cup;
        // Dissipated power: the friction torque between the rings times their relative speed
        // (frame-independent; zero when the rings turn together).
        out.power_loss = out.friction_torque * inputs.relative_speed();
        self.write_reactions_and_lives(fy, fz, evaluated, inputs, out);
        (out.housing_fy, out.housing_fz) = (housing_fy, housing_fz);
        out.stiffness = self.tangent_stiffness(x);
        out.summarize();
    }

    /// The radial reactions (the opposite of the rollers' radial force on the cone: the load
    /// the bearing carries, as `reaction.Fx`), the load rating and the fatigue lives from the
    /// carried loads and the slice loads of the first `rollers` rollers in
    /// `slice_load_buffer` (all of them, or one standing for all when the load is axisymmetric).
    fn write_reactions_and_lives(&self, fy: f64, fz: f64, rollers: usize, inputs: &Inputs, out: &mut Outputs) {
        out.reaction_fy = fy;
        out.reaction_fz = fz;
        out.rating_c = self.rating.c_r;
        let fr = (fy * fy + fz * fz).sqrt();
        out.life_l10 = self.rating.life_l10(fr, out.reaction_fx, inputs.speed, inputs.cup_speed);
        let loads = &self.slice_load_buffer[..2 * self.geometry.slices * rollers];
        out.life_l10r = self.rating.life_l10r(loads, inputs.speed, inputs.cup_speed);
        out.rating_c0 = self.rating.c_0r;
        out.safety_s0 = self.rating.static_safety(fr, out.reaction_fx);
        out.pressure_max = self.geometry.max_raceway_pressure(loads);
        out.film_ratio_raceway = self.film_ratio_output(loads, inputs);
    }

    /// [`QuasiStatic::min_film_ratio`] as the output reports it: finite (at most
    /// [`FILM_RATIO_CAP`], which stands for no loaded contact), 0 for dry contacts.
    pub fn film_ratio_output(&self, slice_loads: &[f64], inputs: &Inputs) -> f64 {
        self.reported_film_ratio(|| self.min_film_ratio(slice_loads, inputs))
    }

    /// The rib's film ratio as the output `filmRatio.flange` reports it, at the most heavily
    /// loaded rib contact of `flange_loads` (one per roller): the film thins with load.
    /// Finite (at most [`FILM_RATIO_CAP`], which stands for no loaded rib), 0 for dry
    /// contacts.
    pub fn flange_film_ratio_output(&self, flange_loads: &[f64], inputs: &Inputs) -> f64 {
        self.reported_film_ratio(|| {
            let qf = flange_loads.iter().cloned().fold(0.0, f64::max);
            self.friction.flange_film_ratio(&self.geometry, qf, inputs.relative_speed())
        })
    }

    /// A film ratio as the outputs report it: 0 for dry contacts (without computing it), else
    /// finite, at most [`FILM_RATIO_CAP`] (no loaded contact), 0 where it is undefined.
    fn reported_film_ratio(&self, ratio: impl FnOnce() -> f64) -> f64 {
        if self.params.lubrication != Lubrication::Ehl {
            return 0.0;
        }
        let r = ratio();
        if r.is_nan() {
            0.0
        } else {
            r.min(FILM_RATIO_CAP)
        }
    }

    /// The smallest film ratio Λ = h / σ of the raceway contacts, taken at the most heavily
    /// loaded slice of the cone and of the cup in `slice_loads` (per roller the cone's slices
    /// then the cup's): the film thins with load, so that is where the asperities meet first.
    /// Infinite without lubrication by oil (dry Coulomb) or without load.
    pub fn min_film_ratio(&self, slice_loads: &[f64], inputs: &Inputs) -> f64 {
        if self.params.lubrication != Lubrication::Ehl {
            return f64::INFINITY;
        }
        let g = &self.geometry;
        let ns = g.slices;
        let (mut cone, mut cup) = ((0, 0.0), (0, 0.0));
        for roller in slice_loads.chunks_exact(2 * ns) {
            for k in 0..ns {
                if roller[k] > cone.1 {
                    cone = (k, roller[k]);
                }
                if roller[ns + k] > cup.1 {
                    cup = (k, roller[ns + k]);
                }
            }
        }
        let f = &self.friction;
        let speed = inputs.relative_speed();
        f.film_ratio(&g.cone, &f.cone_weights, cone.0, cone.1, speed)
            .min(f.film_ratio(&g.cup, &f.cup_weights, cup.0, cup.1, speed))
    }

    /// Slice loads of roller `j` at the solution `x` (cone, cup), for the friction model and tests.
    pub fn slice_loads(&self, x: &[f64], j: usize, cone: &mut [f64], cup: &mut [f64]) {
        let g = &self.geometry;
        let st = &self.setup[j];
        let theta = x[5 + 3 * j] / self.ls;
        let dr = x[1] * st.cos_psi + x[2] * st.sin_psi;
        let (a, rho) = (x[3 + 3 * j], x[4 + 3 * j]);
        let ni = g.cone.normal;
        let no = g.cup.normal;
        let base_i = (x[0] - a) * ni[0] + (dr - rho) * ni[1] + st.gap_cone;
        let base_o = -(a * no[0] + rho * no[1]) + st.gap_cup;
        let (cone_crown, cup_crown) = (&self.cone_table_of(j).crown, &self.cup_table_of(j).crown);
        for k in 0..g.slices {
            let di = base_i + st.gamma * self.cone_chi[k] - theta * g.cone.lever[k] - cone_crown[k];
            cone[k] = g.cone.law.load(k, di).0;
            let d_o = base_o - theta * g.cup.lever[k] - cup_crown[k];
            cup[k] = g.cup.law.load(k, d_o).0;
        }
    }

    /// The bearing's load ratings.
    pub fn rating(&self) -> &crate::bearing::rating::BearingRating {
        &self.rating
    }

    /// The oil's dynamic viscosity at ambient pressure this model was built with (Pa s).
    pub fn oil_viscosity(&self) -> f64 {
        self.params.eta0
    }

    pub fn lubrication(&self) -> Lubrication {
        self.params.lubrication
    }
}

#[cfg(test)]
mod tests;
