//! Contact forces of the dynamic model in full 3-D kinematics and the resulting
//! accelerations (the right-hand side) [W25 section 2, MODEL.md sections 3-5].
//!
//! Raceway slice k of a roller is the disc of radius R_k (+ diameter deviation / 2 - crown)
//! perpendicular to the roller axis a at axial station s_k. Its deepest point towards a
//! raceway is the rim point in the direction of the raceway's inward normal projected on
//! the disc plane; the interference is that point's distance into the raceway, measured in
//! its own axial plane (exact for a straight generatrix). Cup: surface of revolution about
//! the bearing axis, radius enlarged by half the clearance and the lobe profile. Cone: the
//! same about the cone's displaced and misaligned axis. Flange: distance of the roller-end
//! sphere centre from the conical rib, minus the sphere radius. Force along the raceway
//! normal from the slice law plus viscous damping; traction against the sliding velocity
//! (tangential relative velocity of the two surfaces at the contact point), with the
//! entrainment speed taken relative to the orbiting contact point.
//!
//! Cage pocket [W25]: per slice, gap between the roller and each pocket wall (planes
//! parallel to the pocket's axial plane, `cage.pocketClearance` apart in total):
//! hydrodynamic force 2.44 (l/s) eta0 u R / gap and drag 4.58 (l/s) eta0 u sqrt(R / gap)
//! above the critical gap (the composite roughness); below it the hydrodynamic force at the
//! critical gap plus a linear Hertz stiffness and restitution damping (Herbert-McWhannell
//! kappa = 1 - 0.026 |v|^(1/3)), with boundary friction. Cage land: short journal bearing
//! (Ocvirk, `journal_film`) on the cup with the cage's spin, whirl and squeeze: film force,
//! drag and pressure-flow moment; below the critical gap the film there plus Hertz, damping
//! and boundary friction.

use super::Layout;
use super::{RollerRecord, Totals, CAGE, CONE, PER_ROLLER};
use crate::bearing::Bearing;
use crate::contact::{LineLaw, PointContact};
use crate::defect::LocalDefects;
use crate::fastmath as fm;
use crate::geometry::Geometry;
use crate::journal_film::ShortJournal;
use crate::model::{Inputs, LoadCausality, Lubrication, Parameters, Preload};
use crate::tribology as tr;
use nalgebra::Vector3;
use std::f64::consts::{PI, TAU};

type V3 = Vector3<f64>;

/// Speed below which dry and asperity friction are regularised (m/s).
const V_EPS: f64 = tr::DRY_REGULARISATION_SPEED;

/// Fixed-point steps for the deepest rim point against a lobed raceway. Each gains a factor
/// ~10 (CRB-TRILOBE, 0.3 C0 at 40 000 rpm: energy books close to 1.7 %, 0.2 %, 0.05 % of the
/// dissipated power after 1, 2, 3 steps; without them 6 %).
const SLOPED_CONTACT_ITERATIONS: usize = 3;

use tr::traction::LN_MIN_FILM;
use tr::MIN_BOUNDARY_ENTRAINMENT;

/// Constants of the contact model.
#[derive(Debug, Clone)]
pub(crate) struct Constants {
    pub cage_ratio: f64,
    pub spin_ratio: f64,
    m_r: f64,
    i_a: f64,
    i_t: f64,
    /// Centre of mass offset along the axis from the geometric centre.
    cm: f64,
    /// Slice stations relative to the centre of mass, radii, radius reduction of the crown.
    s_cm: Vec<f64>,
    radius: Vec<f64>,
    shrink: Vec<f64>,
    slice_len: f64,
    inv_slice_len: f64,
    cone: LineConst,
    cup: LineConst,
    flange: Option<FlangeConst>,
    cos_o: f64,
    half_clearance: f64,
    pub(crate) lobes: u32,
    waveform: f64,
    /// The local defects (`crate::defect`) on the cup, on the cone and on rollers.
    defects: LocalDefects,
    /// Where the states sit.
    pub(crate) layout: Layout,
    /// The cup's support where the cup moves (`crate::housing`).
    housing: Option<crate::housing::HousingParameters>,
    dd_half: Vec<f64>,
    damping: f64,
    /// 2 zeta sqrt(m / s): the slice damping coefficient is this times sqrt(dq/d delta).
    damping_factor: f64,
    e_prime: f64,
    /// ln(eta0) + 9.67 (Roelands, `fastmath::ln`) for the flange film traction.
    ln_eta0_967: f64,
    /// ln(1.5 sigma): at or above it the raceway film is full (lambda >= 1.5).
    ln_full_film: f64,
    /// ln of the Eyring stress tau_0.
    ln_eyring: f64,
    eta0: f64,
    /// Roelands viscosity of the oil against pressure (z = 0.4: `traction` = 1).
    viscosity: tr::ViscosityTable,
    /// Full-film traction law and, for law 0, the lubricated contact laws' data.
    traction: tr::TractionLaw,
    lubricant: tr::Lubricant,
    /// The lubricant supply: starved films and rolling couple (`tribology::supply`).
    supply: tr::SupplyLaw,
    /// ln(beta eta0 / k): the inlet's thermal loading is exp(this + 2 ln u_e).
    ln_inlet_heating: f64,
    /// EHL rolling resistance at the raceway slices (lubricated, alpha > 0).
    rolling_resistance: bool,
    alpha: f64,
    sigma: f64,
    mu: f64,
    flange_mu0: f64,
    /// Coulomb coefficient of the rib contact (`flange.mu`); `None`: the rib's own law.
    rib_coulomb: Option<f64>,
    dry: bool,
    gyroscopic: bool,
    centrifugal: bool,
    // cage
    pub(crate) cage_dynamic: bool,
    pub(crate) m_cage: f64,
    pub(crate) j_cage: f64,
    pub(crate) pocket_half: f64,
    k_pocket: f64,
    crit_gap: f64,
    mu_pocket: f64,
    reduced_mass: f64,
    /// The cage's guiding land as a short journal bearing.
    pub(crate) land: ShortJournal,
    k_land: f64,
    pub(crate) m_cone: f64,
    pub(crate) pitch_radius: f64,
    axial: bool,
    /// Cone translations (x, y, z) the inputs prescribe: x in displacement preload, all three
    /// in displacement causality (the cone follows them; a bearing without axial stiffness
    /// holds x at 0).
    pub prescribed: [bool; 3],
    pub displacement_causality: bool,
    /// Evaluate the raceway traction two slices at a time (`slice_traction_pair`): x86-64,
    /// lubricated, thermal Eyring law. Tests switch it off for the scalar reference.
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    pub(crate) paired_traction: bool,
    /// Evaluate the slices of a raceway without lobes two at a time (`race_slices_lanes`,
    /// x86-64). Tests switch it off (with `paired_traction`) for the scalar reference.
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    pub(crate) lane_slices: bool,
    /// Take them four at a time (AVX2, where the CPU has it; the same bits as two at a time).
    /// Tests switch it off to compare.
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    pub(crate) four_lanes: bool,
    /// The rollers' thread pool (`threads` > 1; `None`: the caller's thread alone). Each
    /// instance has its own, so parallel instances in a co-simulation master do not share it.
    pub(crate) pool: Option<std::sync::Arc<rayon::ThreadPool>>,
}

/// Whether this CPU takes the four-lane raceway slices (`race_slices_lanes`).
fn four_lanes_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        crate::simd_math::x4::available()
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// One raceway line: a point of its generatrix, its normal (force on the roller), the slice
/// law, equivalent radii and the logarithmic film constants.
#[derive(Debug, Clone)]
struct LineConst {
    reference: [f64; 2],
    normal: [f64; 2],
    law: LineLaw,
    ln_film: Vec<f64>,
    /// Mean Hertz pressure squared per unit load per length: p_mean = sqrt(w k_pmean).
    k_pmean: Vec<f64>,
    /// ln of the EHL rolling couple's constant: couple = 2 F_R R = exp(ln_roll + 0.648 ln u_e
    /// + 0.246 ln w) (`tribology::rolling_couple_log_constant`; -inf without rolling resistance).
    ln_roll: Vec<f64>,
    /// Square of the rolling couple's regularising angular speed per slice (0.1 mm/s / R_eq).
    roll_eps2: Vec<f64>,
}

impl LineConst {
    fn new(line: &crate::geometry::ContactLine, p: &Parameters, e_prime: f64, slice_len: f64) -> LineConst {
        LineConst {
            reference: line.point[0],
            normal: line.normal,
            law: line.law.clone(),
            k_pmean: line.r_bar.iter().map(|r| PI * e_prime / (32.0 * r)).collect(),
            ln_film: line
                .r_bar
                .iter()
                .map(|r| tr::film_line_log_constant(p.eta0, p.alpha.max(1e-12), e_prime, *r))
                .collect(),
            ln_roll: line
                .r_bar
                .iter()
                .map(|r| tr::rolling_couple_log_constant(p.eta0, p.alpha, e_prime, *r, slice_len))
                .collect(),
            roll_eps2: line.r_bar.iter().map(|r| (V_EPS / r).powi(2)).collect(),
        }
    }
}

#[derive(Debug, Clone)]
struct FlangeConst {
    reference: [f64; 2],
    normal: [f64; 2],
    sphere_radius: f64,
    /// Least distance of the sphere centre from the rib axis (radial coordinate) used for
    /// the rib's circumferential curvature; below it the signed in-plane coordinate is used.
    axis_floor: f64,
    /// Sphere centre station along the axis relative to the centre of mass.
    s_sphere: f64,
    hertz: PointContact,
}

impl Constants {
    pub fn new(b: &Bearing, p: &Parameters, g: &Geometry) -> Constants {
        let (ri, ro) = g.pitch_contact_radii();
        // pure rolling (epicyclic) reference speeds: start values and tolerance scales
        let cage_ratio = ri / (ri + ro);
        let spin_ratio = -cage_ratio * ro / g.mean_radius;
        let defects = LocalDefects::new(p.defects(), b.roller_mean_radius(), &g.cup, &g.cone);
        let cm = g.cm_offset;
        let cos_h = libm::cos(g.half_angle);
        let flange = g.flange.as_ref().map(|f| FlangeConst {
            reference: f.point,
            normal: f.normal,
            sphere_radius: b.roller_end_radius,
            axis_floor: {
                // sphere centre to rib axis (along the normal) at the floored relative
                // curvature k = MIN_RELATIVE_CURVATURE / R_s: rho_p - R_s = k R_s rho_p
                let k = crate::geometry::MIN_RELATIVE_CURVATURE;
                -f.normal[1] * k * b.roller_end_radius / (1.0 - k)
            },
            s_sphere: -0.5 * g.length + b.roller_end_radius - cm,
            hertz: f.hertz,
        });
        // cage pocket: linear Hertz stiffness per slice (pi l / 2s) / ((1-nu_r^2)/E_r + (1-nu_p^2)/E_p)
        let (er, nur) = (b.roller_material.e, b.roller_material.nu);
        let (ec, nuc) = (b.cage_material.e, b.cage_material.nu);
        let k_pocket = (PI * g.length / (2.0 * g.slices as f64)) / ((1.0 - nur * nur) / er + (1.0 - nuc * nuc) / ec);
        let k_land = (PI * b.land_width / 2.0) / ((1.0 - nuc * nuc) / ec + (1.0 - b.ring_material.nu.powi(2)) / b.ring_material.e);
        let m_cage = b.cage_mass;
        let pitch_radius = g.center[1];
        Constants {
            cage_ratio,
            spin_ratio,
            m_r: g.roller_mass,
            i_a: g.inertia_axial,
            i_t: g.inertia_transverse,
            cm,
            s_cm: g.slice_s.iter().map(|s| s - cm).collect(),
            radius: g.slice_radius.clone(),
            shrink: g.crown.iter().map(|c| c / cos_h).collect(),
            slice_len: g.slice_len,
            inv_slice_len: 1.0 / g.slice_len,
            cone: LineConst::new(&g.cone, p, g.e_prime, g.slice_len),
            cup: LineConst::new(&g.cup, p, g.e_prime, g.slice_len),
            flange,
            cos_o: libm::cos(g.cup_angle),
            half_clearance: 0.5 * p.clearance,
            lobes: p.outer_lobes,
            waveform: p.outer_waveform,
            layout: Layout::new(p.housing.is_flexible(), &defects, g.z),
            defects,
            housing: p.housing.is_flexible().then_some(p.housing),
            dd_half: p.roller_dd.iter().map(|d| 0.5 * d).collect(),
            damping: p.contact_damping,
            damping_factor: 2.0 * p.contact_damping * (g.roller_mass / g.slices as f64).sqrt(),
            ln_eta0_967: fm::ln(p.eta0) + 9.67,
            ln_full_film: if p.roughness > 0.0 {
                libm::log(1.5 * p.roughness)
            } else {
                f64::NEG_INFINITY
            },
            ln_eyring: libm::log(tr::EYRING_STRESS),
            e_prime: g.e_prime,
            eta0: p.eta0,
            viscosity: tr::ViscosityTable::new(p.eta0),
            traction: p.traction,
            lubricant: p.lubricant(g.e_prime),
            supply: p.supply_law(b),
            ln_inlet_heating: libm::log(p.oil_beta * p.eta0 / p.oil_conductivity),
            rolling_resistance: p.lubrication != Lubrication::Dry && p.alpha > 0.0,
            alpha: p.alpha,
            sigma: p.roughness,
            mu: p.mu,
            flange_mu0: p.flange_mu0,
            rib_coulomb: p.rib_coulomb(),
            dry: p.lubrication == Lubrication::Dry,
            gyroscopic: p.gyroscopic,
            centrifugal: p.centrifugal,
            cage_dynamic: p.cage_dynamic,
            m_cage,
            j_cage: m_cage * pitch_radius * pitch_radius,
            pocket_half: 0.5 * p.pocket_clearance,
            k_pocket,
            crit_gap: p.roughness.max(1e-7),
            mu_pocket: p.flange_mu0,
            reduced_mass: g.roller_mass * m_cage / (g.roller_mass + m_cage),
            land: ShortJournal {
                eta0: p.eta0,
                radius: b.land_radius,
                width: b.land_width,
                clearance: b.guide_clearance.max(1e-6),
            },
            k_land,
            m_cone: p.cone_mass,
            pitch_radius,
            axial: g.axial,
            prescribed: [
                !g.axial || p.preload == Preload::Displacement || p.causality == LoadCausality::Displacement,
                p.causality == LoadCausality::Displacement,
                p.causality == LoadCausality::Displacement,
            ],
            displacement_causality: p.causality == LoadCausality::Displacement,
            lane_slices: cfg!(target_arch = "x86_64"),
            four_lanes: four_lanes_available(),
            pool: (p.threads > 1)
                .then(|| rayon::ThreadPoolBuilder::new().num_threads(p.threads as usize).build().ok())
                .flatten()
                .map(std::sync::Arc::new),
            paired_traction: cfg!(target_arch = "x86_64")
                && p.lubrication != Lubrication::Dry
                && p.traction == tr::TractionLaw::ThermalEyring,
        }
    }
}

/// The cone translations the inputs prescribe (`Constants::prescribed`), `None` where the
/// cone's state is integrated.
pub(crate) fn prescribed_cone(c: &Constants, inputs: &Inputs) -> [Option<f64>; 3] {
    let x = if !c.axial {
        0.0
    } else if c.displacement_causality {
        inputs.displacement[0]
    } else {
        inputs.axial_displacement
    };
    let values = [x, inputs.displacement[1], inputs.displacement[2]];
    std::array::from_fn(|k| c.prescribed[k].then_some(values[k]))
}

/// Roller `rec`'s share of the global rows of the right-hand side (cone, cage and housing
/// accelerations, the defective roller's spin), in the order of the state vector's global
/// states (`Layout`).
pub(crate) fn global_shares(c: &Constants, j: usize, rec: &RollerRecord, out: &mut [f64]) {
    out.iter_mut().for_each(|v| *v = 0.0);
    for k in 0..3 {
        out[CONE + 3 + k] = if c.prescribed[k] { 0.0 } else { rec.f_cone[k] / c.m_cone };
    }
    if c.cage_dynamic {
        out[CAGE + 3] = rec.f_cage[1] / c.m_cage;
        out[CAGE + 4] = rec.f_cage[2] / c.m_cage;
        out[CAGE + 5] = rec.m_cage / c.j_cage;
    }
    if let (Some(h), Some(housing)) = (c.layout.housing, &c.housing) {
        out[h + 2] = rec.f_cup[1] / housing.mass;
        out[h + 3] = rec.f_cup[2] / housing.mass;
    }
    if let Some(k) = c.layout.spin_of(j) {
        out[k] = rec.defect_spin;
    }
}

/// Cage angle (roller 1's pocket) for the state `y`.
pub(crate) fn cage_angle(g: &Geometry, c: &Constants, y: &[f64]) -> f64 {
    if c.cage_dynamic {
        return y[CAGE + 2];
    }
    // kinematic cage: circular mean of the rollers' azimuths less their pocket offsets
    let (mut sx, mut sy) = (0.0, 0.0);
    for j in 0..g.z {
        let psi = y[c.layout.roller(j) + 2] - TAU * j as f64 / g.z as f64;
        sx += libm::cos(psi);
        sy += libm::sin(psi);
    }
    libm::atan2(sy, sx)
}

/// Cage angular speed for the state `y`.
pub(crate) fn cage_speed(g: &Geometry, c: &Constants, y: &[f64]) -> f64 {
    if c.cage_dynamic {
        return y[CAGE + 5];
    }
    (0..g.z).map(|j| y[c.layout.roller(j) + 5]).sum::<f64>() / g.z as f64
}

/// The cup's translation and velocity on its support in state `y` (zero where the housing
/// is rigid).
pub(crate) fn cup_motion(c: &Constants, y: &[f64]) -> (V3, V3) {
    match c.layout.housing {
        Some(h) => (V3::new(0.0, y[h], y[h + 1]), V3::new(0.0, y[h + 2], y[h + 3])),
        None => (V3::zeros(), V3::zeros()),
    }
}

/// Position, velocity and attitude of roller `j` in state `y`: azimuth frame e_r, e_t (x the
/// bearing axis), orbit radius r, centre of mass position and velocity, the roller's axis a
/// (tilted in the axial plane to u, skewed about m_in), its angular velocity w, and
/// sin/cos of the skew.
struct RollerPose {
    e_r: V3,
    e_t: V3,
    r: f64,
    pos: V3,
    vel: V3,
    u: V3,
    m_in: V3,
    a: V3,
    w: V3,
    sf: f64,
    cf: f64,
}

#[inline(always)]
fn roller_pose(g: &Geometry, c: &Constants, y: &[f64], j: usize) -> RollerPose {
    let o = c.layout.roller(j);
    let (x, dr, psi) = (y[o], y[o + 1], y[o + 2]);
    let (xd, drd, psid) = (y[o + 3], y[o + 4], y[o + 5]);
    let (tilt, skew) = (y[o + 6], y[o + 7]);
    let (sp, cp) = libm::sincos(psi);
    let e_r = V3::new(0.0, cp, sp);
    let e_t = V3::new(0.0, -sp, cp);
    let r = c.pitch_radius + dr;
    let (sb, cb) = libm::sincos(g.axis_angle - tilt);
    let u = V3::x() * cb - e_r * sb;
    let (sf, cf) = libm::sincos(skew);
    RollerPose {
        e_r,
        e_t,
        r,
        pos: V3::x() * x + e_r * r,
        vel: V3::x() * xd + e_r * drd + e_t * (r * psid),
        u,
        m_in: V3::x() * sb + e_r * cb,
        a: u * cf - e_t * sf,
        w: V3::x() * y[o + 8] + e_r * y[o + 9] + e_t * y[o + 10],
        sf,
        cf,
    }
}

/// Kinetic energy of the moving bodies in state `y` (J): rollers (translation, and rotation
/// about their axis and transverse to it), cage (translation and spin), cone translation, the
/// housing's translation where it moves. The cone's spin is driven by the shaft and not
/// counted.
pub(crate) fn kinetic_energy(g: &Geometry, c: &Constants, y: &[f64]) -> f64 {
    let mut e = 0.0;
    for j in 0..g.z {
        let RollerPose { vel, a, w, .. } = roller_pose(g, c, y, j);
        let wa = w.dot(&a);
        e += 0.5 * (c.m_r * vel.norm_squared() + c.i_a * wa * wa + c.i_t * (w.norm_squared() - wa * wa));
    }
    if c.cage_dynamic {
        e += 0.5 * (c.m_cage * (y[CAGE + 3].powi(2) + y[CAGE + 4].powi(2)) + c.j_cage * y[CAGE + 5].powi(2));
    }
    if let Some(housing) = &c.housing {
        e += 0.5 * housing.mass * cup_motion(c, y).1.norm_squared();
    }
    e + 0.5 * c.m_cone * (y[CONE + 3].powi(2) + y[CONE + 4].powi(2) + y[CONE + 5].powi(2))
}

/// With the cup on its support: move the bearing in state `y` onto the support's static
/// deflection under the inputs, u0 = F_b / k with F_b the bearing's force on the cup in `y`
/// (cup centred): the cup, the cone's free radial translations, the cage and every roller are
/// translated by u0, so that the bearing's inner state is unchanged and the support carries
/// its load. A roller keeps its axis: translated, its azimuth frame turns by d psi, and its
/// skew and its angular velocity's frame components are taken back by that turn.
pub(crate) fn seat_on_support(g: &Geometry, c: &Constants, inputs: &Inputs, y: &mut [f64]) {
    let (Some(h), Some(housing)) = (c.layout.housing, &c.housing) else {
        return;
    };
    let mut records = vec![RollerRecord::default(); g.z];
    let tot = evaluate(g, c, inputs, y, None, &mut records, None);
    let u0 = V3::new(0.0, tot.f_cup[1], tot.f_cup[2]) / housing.stiffness;
    y[h] += u0[1];
    y[h + 1] += u0[2];
    for k in 1..3 {
        if !c.prescribed[k] {
            y[CONE + k] += u0[k];
        }
    }
    if c.cage_dynamic {
        y[CAGE] += u0[1];
        y[CAGE + 1] += u0[2];
    }
    for j in 0..g.z {
        let o = c.layout.roller(j);
        let pose = roller_pose(g, c, y, j);
        let moved = pose.pos + u0;
        let turn = libm::atan2(moved.dot(&pose.e_t), moved.dot(&pose.e_r));
        y[o + 1] = (moved[1] * moved[1] + moved[2] * moved[2]).sqrt() - c.pitch_radius;
        y[o + 2] += turn;
        // the axis stays: the frame's turn about x takes sin(beta) of it from the skew
        y[o + 7] -= turn * -pose.u.dot(&pose.e_r);
        let (st, ct) = libm::sincos(turn);
        let (wr, wt) = (y[o + 9], y[o + 10]);
        y[o + 9] = wr * ct + wt * st;
        y[o + 10] = -wr * st + wt * ct;
    }
}

/// The housing's books in state `y`: the support's spring energy ½ k |u|² (J) and the power
/// its damper dissipates, c |u'|² (W); zero for a rigid housing.
pub(crate) fn housing_books(c: &Constants, y: &[f64]) -> (f64, f64) {
    match &c.housing {
        Some(h) => {
            let (u, v) = cup_motion(c, y);
            (0.5 * h.stiffness * u.norm_squared(), h.damping * v.norm_squared())
        }
        None => (0.0, 0.0),
    }
}

/// Traction coefficient of a raceway slice and its EHL rolling couple: the force on the roller
/// is -coef v_t (dissipating coef |v_t|^2), the couple's magnitude 2 F_R R_eq, for normal load
/// `q`, sliding speed `vs` = |v_t| and entrainment speed `u_e`. Boundary / mixed / full-film
/// law [W25] with the full-film law of `traction`, or dry Coulomb (no rolling couple).
///
/// The Hamrock film h = exp(ln_c + 0.692 ln u_e - 0.166 ln w) stays in logarithms: ln u_e and
/// ln w serve the film, the inlet heating factor (its thermal loading is beta eta0 u_e^2 / k)
/// and the rolling couple (exp(ln_roll + 0.648 ln u_e + 0.246 ln w)), ln v_s the Eyring argument
/// eta |v_s| / (h tau_0) and the heating factor's slide-to-roll ratio.
#[inline(always)]
fn slice_traction(c: &Constants, line: &LineConst, st: Starved, k: usize, q: f64, vs: f64, u_e: f64) -> (f64, f64) {
    if q <= 0.0 {
        return (0.0, 0.0);
    }
    if c.dry {
        return (c.mu * q / (vs * vs + V_EPS * V_EPS).sqrt(), 0.0);
    }
    if u_e < 1e-6 {
        // no rolling, no film: the boundary law at the floored entrainment speed
        let coef = if vs > 0.0 {
            st.mixed.boundary_mu(vs / MIN_BOUNDARY_ENTRAINMENT) * q / vs
        } else {
            0.0
        };
        return (coef, 0.0);
    }
    let w = q * c.inv_slice_len;
    let (ln_ue, ln_w) = (fm::ln(u_e), fm::ln(w));
    let ln_h_iso = line.ln_film[k] + st.ln_film + 0.692 * ln_ue - 0.166 * ln_w;
    let (coef, heating) = match c.traction {
        tr::TractionLaw::NewtonianEyring => (
            if vs > 0.0 {
                newtonian_traction_coef(c, line, k, q, w, ln_h_iso, vs, u_e)
            } else {
                0.0
            },
            1.0,
        ),
        tr::TractionLaw::ThermalEyring => {
            // mean Hertz pressure w / (2 b); inlet shear heating of the film (Gupta et al. 1992)
            let p_mean = (w * line.k_pmean[k]).sqrt();
            let ln_vs = if vs > 0.0 { fm::ln(vs) } else { f64::NEG_INFINITY };
            let heating = tr::film::thermal_reduction_ln(c.ln_inlet_heating + 2.0 * ln_ue, 4.0 / PI * p_mean / c.e_prime, ln_vs - ln_ue);
            let coef = if vs > 0.0 {
                let (h, ln_h) = (heating * fm::exp(ln_h_iso), ln_h_iso + fm::ln(heating));
                let mu = c
                    .lubricant
                    .raceway_mu_film(w, p_mean, h, ln_h, u_e, vs, ln_vs, vs / u_e.max(MIN_BOUNDARY_ENTRAINMENT), st.mixed);
                mu * q / vs
            } else {
                0.0
            };
            (coef, heating)
        }
    };
    let couple = if c.rolling_resistance {
        heating * fm::exp(line.ln_roll[k] + st.ln_roll + 0.648 * ln_ue + 0.246 * ln_w)
    } else {
        0.0
    };
    (coef, couple)
}

/// [`slice_traction`]'s coefficient with the isothermal Newtonian Eyring law (`traction` = 1);
/// `ln_h` the isothermal film's logarithm, `vs` > 0.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn newtonian_traction_coef(c: &Constants, line: &LineConst, k: usize, q: f64, w: f64, ln_h: f64, vs: f64, u_e: f64) -> f64 {
    // sliding speed with the slide-to-roll ratio floored at 1e-9
    let v_s = vs.max(1e-9 * u_e);
    if c.sigma <= 0.0 || ln_h >= c.ln_full_film {
        let (tau, den) = full_film_stress(c, line, k, w, ln_h, v_s);
        return tau * q / (den * v_s);
    }
    let lambda = fm::exp(ln_h) / c.sigma;
    let mu = if lambda >= 1.5 {
        let (tau, den) = full_film_stress(c, line, k, w, ln_h, v_s);
        tau / den
    } else {
        let s = v_s / u_e.max(MIN_BOUNDARY_ENTRAINMENT);
        if lambda < 0.01 {
            tr::boundary_mu(s)
        } else {
            let (tau, den) = full_film_stress(c, line, k, w, ln_h, v_s);
            tr::traction_mu(lambda, s, tau / den)
        }
    };
    mu * q / v_s
}

/// Full-film traction of a raceway slice as a fraction `(t, d)`, mu = t / d: Eyring shear
/// stress tau_e = tau_0 asinh(eta v_s / (h tau_0)) at the Roelands viscosity of the mean Hertz
/// pressure p (film floored at 1e-9 m), smoothly capped by tau_L = 0.08 p:
/// mu = tau_e tau_L / ((tau_e^4 + tau_L^4)^(1/4) p) = 0.08 tau_e / (tau_e^4 + tau_L^4)^(1/4).
/// `w` load per length, `ln_h` ln of the film thickness, `v_s` sliding speed.
#[inline(always)]
fn full_film_stress(c: &Constants, line: &LineConst, k: usize, w: f64, ln_h: f64, v_s: f64) -> (f64, f64) {
    let p_mean = (w * line.k_pmean[k]).sqrt(); // w / (2 b), b the Hertz half-width
    let x = fm::exp(c.viscosity.ln_eta(p_mean) - ln_h.max(LN_MIN_FILM) - c.ln_eyring) * v_s;
    let asinh = if x < 0.1 {
        let x2 = x * x;
        x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (3.0 / 40.0 + x2 * (-15.0 / 336.0 + x2 * (105.0 / 3456.0)))))
    } else {
        fm::ln(x + (x * x + 1.0).sqrt())
    };
    let tau_e = tr::EYRING_STRESS * asinh;
    let tau_l = tr::LIMITING_SHEAR * p_mean;
    let (e2, l2) = (tau_e * tau_e, tau_l * tau_l);
    (tr::LIMITING_SHEAR * tau_e, (e2 * e2 + l2 * l2).sqrt().sqrt())
}

/// Traction coefficient of the rib contact (force on the roller -coef v_t) for normal load
/// `q`, sliding speed `vs` and entrainment speed `u_e` (`tribology::rib`).
fn rib_traction_coef(c: &Constants, fl: &FlangeConst, starved: Starved, q: f64, vs: f64, u_e: f64) -> f64 {
    let h_iso = tr::film_point(c.eta0, c.alpha, c.e_prime, u_e, fl.hertz.ry, fl.hertz.rx, q) * starved.rib;
    let (ea, eb, ph) = fl.hertz.ellipse(q);
    match c.traction {
        tr::TractionLaw::NewtonianEyring => {
            let ratio = if c.sigma > 0.0 { h_iso / c.sigma } else { f64::INFINITY };
            let asperity = q * tr::flange_boundary_mu(c.flange_mu0, ratio) / (vs * vs + V_EPS * V_EPS).sqrt();
            let viscous = tr::flange_viscous_traction_with(c.eta0, c.ln_eta0_967, vs, h_iso, ea, eb, ph) / vs;
            asperity + viscous
        }
        tr::TractionLaw::ThermalEyring => {
            let slide_roll = vs / u_e.max(MIN_BOUNDARY_ENTRAINMENT);
            #[cfg(target_arch = "x86_64")]
            if c.paired_traction {
                let film = if c.four_lanes {
                    tr::pair::rib_film_traction_four
                } else {
                    tr::pair::rib_film_traction
                };
                return c
                    .lubricant
                    .rib_force(q, vs, u_e, slide_roll, h_iso, ea, eb, ph, starved.mixed, film)
                    / vs;
            }
            c.lubricant
                .rib_force(q, vs, u_e, slide_roll, h_iso, ea, eb, ph, starved.mixed, tr::rib_film_traction)
                / vs
        }
    }
}

/// A raceway as one slice loop sees it: the roller's kinematics in the raceway's frame, the
/// velocity field of the raceway and of the orbiting contact point in that frame.
struct Race<'a> {
    line: &'a LineConst,
    /// Roller centre of mass, velocity, angular velocity and axis in this frame.
    pos: V3,
    vel: V3,
    w: V3,
    a: V3,
    /// Raceway velocity at p: v0 + omega x p (the cup: zero).
    ring_v0: V3,
    ring_omega: V3,
    /// Velocity of the contact point orbiting with the roller: pt_v0 + pt_omega x p.
    pt_v0: V3,
    pt_omega: V3,
    /// Largest value of the extra gap term (clearance, lobes) for the cheap gap test.
    gap_max: f64,
    /// What the supply's starvation does to the films and the rolling couple.
    starved: Starved,
}

/// The lubricant supply's starvation at the current speed, as the contact laws take it: ln of
/// the raceway film's and the rolling couple's factors, and the rib film's factor
/// (`tribology::supply`; 0, 0, 1 when flooded, which changes no bit); and the mixed law at
/// that speed (`tribology::mixed`).
#[derive(Debug, Clone, Copy)]
pub(super) struct Starved {
    pub ln_film: f64,
    pub ln_roll: f64,
    pub rib: f64,
    pub mixed: tr::Mixed,
}

impl Starved {
    fn of(s: tr::Starvation) -> Starved {
        if s == tr::Starvation::FLOODED {
            return Starved {
                ln_film: 0.0,
                ln_roll: 0.0,
                rib: 1.0,
                mixed: tr::Mixed::FilmRatio,
            };
        }
        Starved {
            ln_film: libm::log(s.raceway),
            ln_roll: libm::log(s.rolling),
            rib: s.rib,
            mixed: s.mixed,
        }
    }
}

/// Sums of one roller's slice loop against one raceway (force on the roller, its moment about
/// the roller's centre of mass, normal load, sliding friction force, dissipated power).
#[derive(Default)]
struct LineSum {
    f: V3,
    m: V3,
    q: f64,
    /// Net tangential (sliding traction) force of the slices on the roller.
    traction: V3,
    power: f64,
    extrapolated: bool,
}

/// The extra interference of the cup at contact point `q` (global frame) and its derivative
/// along the azimuth: the clearance, the lobes ([Y22]) and, where `defect` says the roller is
/// near it, the drop into the cup's local defects, turned with the cup by `turn` since t = 0
/// (`crate::defect`; the drop is normal to the raceway, the lobes radial).
#[inline]
fn cup_gap(c: &Constants, q: &V3, defect: bool, turn: f64) -> (f64, f64) {
    let psi = libm::atan2(q[2], q[1]);
    let (mut gap, mut gap_psi) = if c.lobes > 0 {
        let nl = c.lobes as f64;
        let (sl, cl) = libm::sincos(nl * psi);
        let lobe = 0.5 * c.waveform * (1.0 - cl);
        let lobe_psi = 0.5 * c.waveform * nl * sl;
        (-(c.half_clearance + lobe) * c.cos_o, -lobe_psi * c.cos_o)
    } else {
        (-c.half_clearance * c.cos_o, 0.0)
    };
    if defect {
        let rho = (q[1] * q[1] + q[2] * q[2]).sqrt();
        let (drop, drop_psi) = LocalDefects::raceway_drop(&c.defects.cup, psi - turn, q[0], rho);
        gap -= drop;
        gap_psi -= drop_psi;
    }
    (gap, gap_psi)
}

/// Whether a roller whose centre is at `pos` (in a ring's frame, the ring turned by `turn`
/// since t = 0) can touch one of the ring's defects `on`: the cheap test before the contact
/// closure (no angle computed for a ring without defects).
#[inline]
fn near(on: &[crate::defect::RacewayDefect], pos: &V3, turn: f64) -> bool {
    !on.is_empty() && LocalDefects::near(on, libm::atan2(pos[2], pos[1]) - turn, (pos[1] * pos[1] + pos[2] * pos[2]).sqrt())
}

/// The extra interference of the cone at contact point `q` (the cone's frame) from its local
/// defects, turned by `turn` since t = 0, and its derivative along the azimuth.
#[inline]
fn cone_gap(c: &Constants, q: &V3, turn: f64) -> (f64, f64) {
    let rho = (q[1] * q[1] + q[2] * q[2]).sqrt();
    let (drop, drop_psi) = LocalDefects::raceway_drop(&c.defects.cone, libm::atan2(q[2], q[1]) - turn, q[0], rho);
    (-drop, -drop_psi)
}

/// A roller that carries defects (`crate::defect::RollerDefect`): its index, its outward
/// normal (global frame), its spin angle since t = 0 and its centre of mass's offset along the
/// axis from its middle.
struct RollerBody<'a> {
    defects: &'a LocalDefects,
    j: usize,
    normal: V3,
    spin: f64,
    cm: f64,
}

/// The defective roller as one raceway's contacts see it, in that raceway's frame: against
/// the cup (`on_cup`) or the cone.
struct RollerPit<'a> {
    defects: &'a LocalDefects,
    j: usize,
    on_cup: bool,
    pos: V3,
    a: V3,
    /// The roller's body frame about its axis before its spin: the outward normal and a x it.
    u1: V3,
    u2: V3,
    spin: f64,
    cm: f64,
}

impl<'a> RollerBody<'a> {
    /// As the contacts of `race` (the cup: `on_cup`) see it, with the outward normal `normal`
    /// in the race's frame.
    fn in_frame(&self, race: &Race, normal: V3, on_cup: bool) -> RollerPit<'a> {
        RollerPit {
            defects: self.defects,
            j: self.j,
            on_cup,
            pos: race.pos,
            a: race.a,
            u1: normal,
            u2: race.a.cross(&normal),
            spin: self.spin,
            cm: self.cm,
        }
    }
}

impl RollerPit<'_> {
    /// The extra interference at contact point `q` (the race's frame) from the roller's
    /// defect, and its derivative along the azimuth of the point about the bearing axis: the
    /// defect's drop at the body angle and axial station of the roller's surface point there,
    /// its slope along the roller's circumference carried over to the azimuthal direction.
    #[inline]
    fn gap(&self, q: &V3) -> (f64, f64) {
        let lever = q - self.pos;
        let along = lever.dot(&self.a);
        let d = lever - self.a * along;
        let chi = libm::atan2(d.dot(&self.u2), d.dot(&self.u1)) - self.spin;
        let (drop, slope) = self.defects.roller_drop(self.j, self.on_cup, chi, along + self.cm);
        if drop == 0.0 && slope == 0.0 {
            return (0.0, 0.0);
        }
        let rho = (q[1] * q[1] + q[2] * q[2]).sqrt();
        let dn = d.norm();
        if rho == 0.0 || dn == 0.0 {
            return (-drop, 0.0);
        }
        // the roller's rolling direction at the point (increasing body angle), a x d / |d|,
        // against the point's azimuthal direction
        let e_t = V3::new(0.0, -q[2] / rho, q[1] / rho);
        let rolling = self.a.cross(&d).dot(&e_t) / dn;
        (-drop, -rho * slope * rolling)
    }
}

/// All slices of one roller against one raceway. `gap(p)` is the extra interference term at
/// the contact point (clearance and lobes of the cup; zero for the cone) and its derivative
/// along the azimuth of the point: a lobe's slope tilts the raceway normal, so the force
/// stays the gradient of the contact's energy and the damping sees the lobe's rate.
/// `slice_loads`, when given (outputs, not the right-hand side), receives each slice's
/// normal load (zero where it does not touch).
#[inline(always)]
fn race_slices(c: &Constants, race: &Race, dd: f64, mut slice_loads: Option<&mut [f64]>, gap: impl Fn(&V3) -> (f64, f64)) -> LineSum {
    let line = race.line;
    let (r0, r1) = (line.reference[0], line.reference[1]);
    let (n0, n1) = (line.normal[0], line.normal[1]);
    // Velocity fields about the roller's centre of mass, per slice only a cross product with
    // the lever: sliding v_rel = v_c + w_rel x lever, entrainment (relative to the orbiting
    // contact point) u = u_c + w_e x lever.
    let ring_c = race.ring_v0 + race.ring_omega.cross(&race.pos);
    let pt_c = race.pt_v0 + race.pt_omega.cross(&race.pos);
    let v_c = race.vel - ring_c;
    let w_rel = race.w - race.ring_omega;
    let u_c = (race.vel + ring_c) * 0.5 - pt_c;
    let w_e = (race.w + race.ring_omega) * 0.5 - race.pt_omega;
    let mut sum = LineSum::default();
    if let Some(loads) = slice_loads.as_deref_mut() {
        loads.fill(0.0);
    }
    // a slice's contribution to the sums with its traction (coef, couple)
    let mut add = |s: &Slice, (coef, couple): (f64, f64)| {
        let fk = s.n * s.q - s.v_t * coef;
        sum.f += fk;
        sum.m += s.lever.cross(&fk);
        sum.q += s.q;
        sum.traction -= s.v_t * coef;
        if let Some(loads) = slice_loads.as_deref_mut() {
            loads[s.k] = s.q;
        }
        sum.power += coef * s.vs * s.vs + s.damping_power.max(0.0);
        if couple > 0.0 {
            // EHL rolling resistance: the inlet pressure shifts the normal force upstream; on
            // the roller a couple against its rolling relative to the raceway, 2 F_R R_eq, the
            // raceway the opposite (through the race's moment sum), dissipating 2 F_R u
            // the roller's rotation relative to the raceway, without its spin about the normal
            let w_roll = w_rel - s.n * w_rel.dot(&s.n);
            let norm = (w_roll.norm_squared() + line.roll_eps2[s.k]).sqrt();
            let m_roll = w_roll * (-couple / norm);
            sum.m += m_roll;
            sum.power += -m_roll.dot(&w_roll);
        }
        sum.extrapolated |= s.ext;
    };
    // the thermal Eyring law's slices two at a time (`slice_traction_pair`): `held[0]` waits
    // for its partner while `n_held` is 1
    #[cfg(target_arch = "x86_64")]
    let paired = c.paired_traction;
    let mut held = [Slice::default(); 2];
    #[cfg_attr(not(target_arch = "x86_64"), allow(unused_mut))]
    let mut n_held = 0;
    for k in 0..c.s_cm.len() {
        let rad = c.radius[k] + dd - c.shrink[k];
        let cl = race.pos + race.a * c.s_cm[k];
        let rho_c = (cl[1] * cl[1] + cl[2] * cl[2]).sqrt();
        // Cheap gap test: the interference function is 1-Lipschitz in space and the contact
        // point lies `rad` from the slice centre, so the centre's interference + rad + the
        // largest extra gap bounds it from above.
        let bound = -((cl[0] - r0) * n0 + (rho_c - r1) * n1) + rad + race.gap_max;
        if bound < -1e-12 {
            continue;
        }
        let (ey, ez) = if rho_c > 0.0 {
            let inv = 1.0 / rho_c;
            (cl[1] * inv, cl[2] * inv)
        } else {
            (1.0, 0.0)
        };
        // deepest rim point: towards the raceway (minus its normal) projected on the disc plane
        let g = V3::new(-n0, -ey * n1, -ez * n1);
        let mut d = g - race.a * g.dot(&race.a);
        let dn = d.norm();
        if dn == 0.0 {
            continue;
        }
        d *= 1.0 / dn;
        let mut pl = cl + d * rad;
        let mut rho_p = (pl[1] * pl[1] + pl[2] * pl[2]).sqrt();
        let (mut extra, mut extra_psi) = gap(&pl);
        let unit = |pl: &V3, rho_p: f64| if rho_p > 0.0 { (pl[1] / rho_p, pl[2] / rho_p) } else { (1.0, 0.0) };
        let (mut py, mut pz) = unit(&pl, rho_p);
        // raceway normal -grad(delta) / |grad(delta)|: a lobe's azimuthal slope tilts it
        let normal = |py: f64, pz: f64, rho_p: f64, extra_psi: f64| {
            let n = V3::new(n0, py * n1, pz * n1);
            if extra_psi != 0.0 && rho_p > 0.0 {
                let n = n - V3::new(0.0, -pz, py) * (extra_psi / rho_p);
                n / n.norm()
            } else {
                n
            }
        };
        for _ in 0..SLOPED_CONTACT_ITERATIONS {
            if extra_psi == 0.0 {
                break;
            }
            // the deepest rim point against a sloped surface lies along the tilted normal
            // (fixed-point steps); there the rim's motion does not change the interference,
            // so the contact's energy stays consistent with its force
            let g = -normal(py, pz, rho_p, extra_psi);
            let mut d = g - race.a * g.dot(&race.a);
            let dn = d.norm();
            if dn > 0.0 {
                d *= 1.0 / dn;
                pl = cl + d * rad;
                rho_p = (pl[1] * pl[1] + pl[2] * pl[2]).sqrt();
                (extra, extra_psi) = gap(&pl);
                (py, pz) = unit(&pl, rho_p);
            }
        }
        let delta = -((pl[0] - r0) * n0 + (rho_p - r1) * n1) + extra;
        if delta <= 0.0 {
            continue;
        }
        let (q_el, dq, ext) = line.law.load(k, delta);
        let n = normal(py, pz, rho_p, extra_psi);
        let lever = pl - race.pos;
        let v_rel = v_c + w_rel.cross(&lever);
        let vn = v_rel.dot(&n);
        // damping: c = 2 zeta sqrt(m k_slice / s) per slice (critical for the whole line)
        let c_damp = c.damping_factor * dq.sqrt();
        let q = (q_el - c_damp * vn).max(0.0);
        let damping_power = (q - q_el) * (-vn);
        let v_t = v_rel - n * vn;
        let ue_vec = u_c + w_e.cross(&lever);
        let u_e = (ue_vec - n * ue_vec.dot(&n)).norm();
        // (written in place: the slice waiting for its partner stays where it is)
        held[n_held] = Slice {
            k,
            q,
            n,
            lever,
            v_t,
            vs: v_t.norm(),
            u_e,
            damping_power,
            ext,
        };
        // the lubricated traction of two slices at once; the others, and the last one left
        // over, before the next slice's sums (the sums stay in slice order)
        #[cfg(target_arch = "x86_64")]
        {
            if paired && held[n_held].paired() {
                if n_held == 0 {
                    n_held = 1;
                } else {
                    let [ta, tb] = slice_traction_pair(c, line, race.starved, &held[0], &held[1]);
                    add(&held[0], ta);
                    add(&held[1], tb);
                    n_held = 0;
                }
                continue;
            }
            if n_held == 1 {
                add(&held[0], slice_traction_pair(c, line, race.starved, &held[0], &held[0])[0]);
            }
        }
        let s = &held[n_held];
        add(s, slice_traction(c, line, race.starved, k, s.q, s.vs, s.u_e));
        n_held = 0;
    }
    #[cfg(target_arch = "x86_64")]
    if n_held == 1 {
        add(&held[0], slice_traction_pair(c, line, race.starved, &held[0], &held[0])[0]);
    }
    sum
}

/// A touching slice of [`race_slices`] as its traction and the sums take it: index, normal
/// load, raceway normal, lever from the centre of mass, tangential relative velocity and its
/// norm, entrainment speed, damping power, extrapolated contact law.
#[derive(Clone, Copy, Default)]
struct Slice {
    k: usize,
    q: f64,
    n: V3,
    lever: V3,
    v_t: V3,
    vs: f64,
    u_e: f64,
    damping_power: f64,
    ext: bool,
}

impl Slice {
    /// Whether [`slice_traction_pair`] takes this slice: loaded, sliding and entrained (the
    /// full law of [`slice_traction`], not one of its special cases), finite.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    fn paired(&self) -> bool {
        self.q > 0.0 && self.vs > 0.0 && self.u_e >= 1e-6 && self.q.is_finite() && self.vs.is_finite() && self.u_e.is_finite()
    }
}

/// [`slice_traction`] of two slices at once (`slice_traction_lanes`), a lane outside the
/// two-lane kernels' range by the scalar code: (coef, couple) of `a` and of `b`.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn slice_traction_pair(c: &Constants, line: &LineConst, st: Starved, a: &Slice, b: &Slice) -> [(f64, f64); 2] {
    use crate::simd_math::F2;
    let (q, vs, u_e) = (F2::new(a.q, b.q), F2::new(a.vs, b.vs), F2::new(a.u_e, b.u_e));
    let (coef, couple, ok) = lanes2::slice_traction_lanes(c, line, st, [a.k, b.k], q, vs, u_e);
    let ([ca, cb], [pa, pb], bits) = (coef.lanes(), couple.lanes(), ok.bits());
    [
        if bits & 1 != 0 {
            (ca, pa)
        } else {
            slice_traction(c, line, st, a.k, a.q, a.vs, a.u_e)
        },
        if bits & 2 != 0 {
            (cb, pb)
        } else {
            slice_traction(c, line, st, b.k, b.q, b.vs, b.u_e)
        },
    ]
}

/// The raceway slices in two lanes (SSE2, every x86-64 CPU).
#[cfg(target_arch = "x86_64")]
mod lanes2 {
    use super::*;
    use crate::simd_math::{exp, ln, V3x2 as V, F2 as F, M2 as M};
    use crate::tribology::pair::x2 as pair;
    include!("slice_lanes.rs");
}

/// The raceway slices in four lanes (AVX2), entered through [`race_slices_avx2`].
#[cfg(target_arch = "x86_64")]
mod lanes4 {
    use super::*;
    use crate::simd_math::x4::{exp, ln, V3x4 as V, F4 as F, M4 as M};
    use crate::tribology::pair::x4 as pair;
    include!("slice_lanes.rs");

    /// `race_slices_lanes` in four lanes, compiled for AVX2.
    ///
    /// # Safety
    /// The CPU has AVX2 (`simd_math::x4::available`).
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn race_slices_avx2(c: &Constants, race: &Race, dd: f64, slice_loads: Option<&mut [f64]>, extra: f64) -> LineSum {
        race_slices_lanes(c, race, dd, slice_loads, extra)
    }

    /// `pocket_sums_lanes` in four lanes, compiled for AVX2.
    ///
    /// # Safety
    /// The CPU has AVX2 (`simd_math::x4::available`).
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn pocket_sums_avx2(c: &Constants, p: &PocketLine) -> Option<PocketSums> {
        pocket_sums_lanes(c, p)
    }
}

/// [`race_slices`] for a raceway without lobes, in lanes: four where the CPU has AVX2
/// (`Constants::four_lanes`), else two; the same bits either way (`slice_lanes.rs`).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn race_slices_lanes(c: &Constants, race: &Race, dd: f64, slice_loads: Option<&mut [f64]>, extra: f64) -> LineSum {
    if c.four_lanes {
        // SAFETY: `four_lanes` is set only where the CPU has AVX2 (`Constants::new`).
        unsafe { lanes4::race_slices_avx2(c, race, dd, slice_loads, extra) }
    } else {
        lanes2::race_slices_lanes(c, race, dd, slice_loads, extra)
    }
}

/// [`pocket_sums`] in lanes where no slice is within the critical gap of either wall (the
/// hydrodynamic force and drag alone, as in steady running): four slices at a time where the
/// CPU has AVX2, else two, the same bits either way (`slice_lanes.rs`); `None` where some
/// slice touches a wall (the scalar loop then takes the roller).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn pocket_sums_lanes(c: &Constants, p: &PocketLine) -> Option<PocketSums> {
    if c.four_lanes {
        // SAFETY: `four_lanes` is set only where the CPU has AVX2 (`Constants::new`).
        unsafe { lanes4::pocket_sums_avx2(c, p) }
    } else {
        lanes2::pocket_sums_lanes(c, p)
    }
}

/// The cone's and cage's pose and motion, the same for every roller of one evaluation.
pub(crate) struct Frame {
    /// Cone rotation (columns: the cone's axes), its transpose and the cone's axis.
    rot: nalgebra::Matrix3<f64>,
    rot_t: nalgebra::Matrix3<f64>,
    axis_c: V3,
    origin: V3,
    cone_vel: V3,
    /// In the cone's frame: its own velocity, the bearing axis, the axis term of the orbit.
    cone_vel_l: V3,
    x_l: V3,
    x_cross_o_l: V3,
    cage_psi: f64,
    cage_rate: f64,
    cage_pos: V3,
    cage_vel: V3,
    /// The cup's translation on its support and its velocity, and the bearing axis crossed
    /// with the translation (zero where the housing is rigid).
    cup_pos: V3,
    cup_vel: V3,
    cup_orbit: V3,
    /// The cone's and the cup's turns since t = 0 with their defects (rad; `Layout`).
    cone_turn: f64,
    cup_turn: f64,
    /// The supply's starvation at the current speed.
    starved: Starved,
}

/// The roller-end sphere on the conical rib (Hertz point contact, damping, rib traction) of a
/// roller at `pos` with velocity `vel`, angular velocity `w`, axis `a`, orbit rate `psid`:
/// force and moment about the roller's centre of mass on the roller, normal load, friction
/// force and dissipated power (all zero without a flange or contact).
#[allow(clippy::too_many_arguments)]
fn flange_contact(c: &Constants, f: &Frame, inputs: &Inputs, pos: V3, vel: V3, w: V3, a: V3, psid: f64) -> (V3, V3, f64, f64, f64) {
    let (mut f_fl, mut m_fl, mut q_fl, mut sliding_fl, mut p_flange) = (V3::zeros(), V3::zeros(), 0.0, 0.0, 0.0);
    if let Some(fl) = &c.flange {
        let s_centre = pos + a * fl.s_sphere;
        let sl = f.rot_t * (s_centre - f.origin);
        // The rib is a surface of revolution: the sphere centre's distance from its
        // meridian in the centre's own half-plane, with rho its distance from the axis.
        // That holds while the centre lies well off the axis on the roller's side. An end
        // radius near (or above) the rib's circumferential radius rho_p = r_f / cos a_f
        // puts the centre on or beyond the axis (32018X: R_s / rho_p = 1.0003, centre
        // 18 um past it): rho = |r| would reflect it, adding 2 |r| cos a_f of spurious
        // interference (9 um, 10 kN), and the term t^2 / (2 r) of a tangential offset t
        // would be singular. There the radial coordinate is taken signed, in the roller's
        // half-plane, and the centre's distance from the axis used for the circumferential
        // curvature is floored at `axis_floor`, the geometry's floor on the relative
        // curvature (the same rib as the quasi-static model's and the Hertz law's).
        let pl = f.rot_t * (pos - f.origin);
        let pr = (pl[1] * pl[1] + pl[2] * pl[2]).sqrt();
        let (cr, ct) = if pr > 0.0 { (pl[1] / pr, pl[2] / pr) } else { (1.0, 0.0) };
        let r_signed = sl[1] * cr + sl[2] * ct;
        let (rho, er) = if r_signed >= fl.axis_floor {
            let rho = (sl[1] * sl[1] + sl[2] * sl[2]).sqrt();
            (rho, V3::new(0.0, sl[1] / rho, sl[2] / rho))
        } else {
            let t = sl[2] * cr - sl[1] * ct;
            let hyp = (fl.axis_floor * fl.axis_floor + t * t).sqrt();
            let (ur, ut) = (fl.axis_floor / hyp, t / hyp);
            (r_signed + hyp - fl.axis_floor, V3::new(0.0, ur * cr - ut * ct, ur * ct + ut * cr))
        };
        let dist = (sl[0] - fl.reference[0]) * fl.normal[0] + (rho - fl.reference[1]) * fl.normal[1];
        // `reference` is the nominal contact point on the rib, the nominal sphere centre
        // lies a sphere radius from it along the normal: interference = R_s - distance.
        let delta = fl.sphere_radius - dist;
        if delta > 0.0 {
            let (q_el, dq) = fl.hertz.load(delta);
            let n = f.rot * (V3::x() * fl.normal[0] + er * fl.normal[1]);
            let pk = s_centre - n * fl.sphere_radius;
            let lever = pk - pos;
            let v_roller = vel + w.cross(&lever);
            let v_ring = f.cone_vel + (f.axis_c * inputs.speed).cross(&(pk - f.origin));
            let v_rel = v_roller - v_ring;
            let vn = v_rel.dot(&n);
            let c_damp = 2.0 * c.damping * (c.m_r * dq).sqrt();
            let q = (q_el - c_damp * vn).max(0.0);
            let damping_power = ((q - q_el) * (-vn)).max(0.0);
            let v_t = v_rel - n * vn;
            let vs = v_t.norm();
            let (f_t, p_t) = if vs > 0.0 {
                // Coulomb friction: `flange.mu` whatever the raceways' law, or dry contacts' `mu`
                let coef = if let Some(mu_f) = c.rib_coulomb.or(c.dry.then_some(c.mu)) {
                    mu_f * q / (vs * vs + V_EPS * V_EPS).sqrt()
                } else {
                    let v_point = V3::x().cross(&pk) * psid;
                    let ue_vec = (v_roller - v_point + v_ring - v_point) * 0.5;
                    let u_e = (ue_vec - n * ue_vec.dot(&n)).norm();
                    rib_traction_coef(c, fl, f.starved, q, vs, u_e)
                };
                (-v_t * coef, coef * vs * vs)
            } else {
                (V3::zeros(), 0.0)
            };
            let fk = n * q + f_t;
            sliding_fl = f_t.norm();
            f_fl = fk;
            m_fl = lever.cross(&fk);
            q_fl = q;
            p_flange = p_t + damping_power;
        }
    }
    (f_fl, m_fl, q_fl, sliding_fl, p_flange)
}

/// Cage pocket of roller `j` (at `pos`, velocity `vel`, angular velocity `w`, axis `a`):
/// walls at ±pocket_half from the pocket's axial plane, per slice and wall. The gap and the
/// velocity relative to the cage are affine in the station s and the wall side, so the sums
/// over slices reduce to eight scalar sums per roller and a few cross products (the same
/// forces as slice by slice). Returns the force and moment (about the centre of mass) on the
/// roller, the summed normal load and the dissipated power.
#[allow(clippy::too_many_arguments)]
fn cage_pocket(g: &Geometry, c: &Constants, f: &Frame, j: usize, pos: V3, vel: V3, w: V3, a: V3) -> (V3, V3, f64, f64) {
    let psi_p = f.cage_psi + TAU * j as f64 / g.z as f64;
    let (spp, cpp) = libm::sincos(psi_p);
    let e_tp = V3::new(0.0, -spp, cpp);
    let pocket_origin = f.cage_pos + V3::new(0.0, cpp, spp) * c.pitch_radius;
    let w_cage_rel = w - V3::x() * f.cage_rate;
    let spin_rel = w_cage_rel.dot(&a).abs();
    let tau0 = (pos - pocket_origin).dot(&e_tp);
    let tau1 = a.dot(&e_tp);
    // velocity of the roller surface relative to the cage at station s, side sigma:
    // v0 + s v1 + sigma rad rim; tangential part (normal e_tp removed) A + s B + sigma rad C
    let v0 = vel - (f.cage_vel + V3::x().cross(&(pos - f.cage_pos)) * f.cage_rate);
    let v1 = w_cage_rel.cross(&a);
    let rim = w_cage_rel.cross(&e_tp);
    let (v0e, v1e) = (v0.dot(&e_tp), v1.dot(&e_tp));
    let va = v0 - e_tp * v0e;
    let vb = v1 - e_tp * v1e;
    let vc = rim - e_tp * rim.dot(&e_tp);
    let (aa, bb, cc) = (va.dot(&va), vb.dot(&vb), vc.dot(&vc));
    let (ab, ac, bc) = (va.dot(&vb), va.dot(&vc), vb.dot(&vc));
    let l = c.slice_len;
    let line = PocketLine {
        tau0,
        tau1,
        aa,
        bb,
        cc,
        ab,
        ac,
        bc,
        v0e,
        v1e,
        k_hyd: 2.44 * l * c.eta0 * spin_rel,
        k_drag: 4.58 * l * c.eta0 * spin_rel,
    };
    #[cfg(target_arch = "x86_64")]
    let sums = if c.lane_slices {
        pocket_sums_lanes(c, &line).unwrap_or_else(|| pocket_sums(c, &line))
    } else {
        pocket_sums(c, &line)
    };
    #[cfg(not(target_arch = "x86_64"))]
    let sums = pocket_sums(c, &line);
    let f_pk = -(e_tp * sums.q + va * sums.c + vb * sums.cs + vc * sums.crad);
    let m_pk = -(a.cross(&e_tp) * sums.qs
        + a.cross(&va) * sums.cs
        + a.cross(&vb) * sums.css
        + a.cross(&vc) * sums.csrad
        + e_tp.cross(&va) * sums.crad
        + e_tp.cross(&vb) * sums.csrad
        + e_tp.cross(&vc) * sums.crr);
    (f_pk, m_pk, sums.q_pocket, sums.power)
}

/// One roller's pocket in the terms its slice sums need (`cage_pocket`): the offset of the
/// roller axis from the pocket's mid-plane at station s, tau0 + tau1 s; the tangential
/// surface velocity relative to the cage, A + s B + sigma rad C, by its dot products; the
/// closing speed v0e + v1e s (times the wall's side); the hydrodynamic force and drag
/// factors.
#[derive(Clone, Copy)]
struct PocketLine {
    tau0: f64,
    tau1: f64,
    aa: f64,
    bb: f64,
    cc: f64,
    ab: f64,
    ac: f64,
    bc: f64,
    v0e: f64,
    v1e: f64,
    k_hyd: f64,
    k_drag: f64,
}

/// The slice sums of one roller's pocket (`cage_pocket`): sigma q, sigma q s, c, c s, c s^2,
/// sigma rad c, sigma c s rad, c rad^2 (sigma the wall's side, c the drag over the sliding
/// speed), the summed normal load and the dissipated power.
#[derive(Default)]
struct PocketSums {
    q: f64,
    qs: f64,
    c: f64,
    cs: f64,
    css: f64,
    crad: f64,
    csrad: f64,
    crr: f64,
    q_pocket: f64,
    power: f64,
}

/// [`PocketSums`] slice by slice and wall by wall: above the critical gap the hydrodynamic
/// force and drag, below it the wall contact (Hertz, restitution damping, boundary friction).
fn pocket_sums(c: &Constants, p: &PocketLine) -> PocketSums {
    let mut p_cage = 0.0;
    let (mut s_q, mut s_c, mut s_cs, mut s_crad, mut s_qs, mut s_css, mut s_csrad, mut s_crr, mut q_pocket) =
        (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let ns = c.s_cm.len();
    for k in 0..ns {
        let sk = c.s_cm[k];
        let rad = c.radius[k];
        let tau = p.tau0 + p.tau1 * sk;
        let alpha = p.aa + sk * (2.0 * p.ab + sk * p.bb) + rad * rad * p.cc;
        let beta = 2.0 * rad * (p.ac + sk * p.bc);
        let closing0 = p.v0e + p.v1e * sk;
        for side in [1.0_f64, -1.0] {
            // gap to the wall on side `side` (front wall at +e_tp)
            let gap = c.pocket_half - side * tau;
            let (qn, drag) = if gap >= c.crit_gap {
                let inv = 1.0 / gap;
                (p.k_hyd * rad * rad * inv, p.k_drag * rad * (rad * inv).sqrt())
            } else {
                let closing = side * closing0;
                let qh = p.k_hyd * rad * rad / c.crit_gap;
                let kappa = (1.0 - 0.026 * libm::cbrt(closing.abs())).clamp(0.05, 1.0);
                let lk = libm::log(kappa);
                let c_ph = 2.0 * (c.reduced_mass * c.k_pocket).sqrt() * (-lk) / (lk * lk + PI * PI).sqrt();
                let q_el = qh + (c.crit_gap - gap) * c.k_pocket;
                let q = (q_el + c_ph * closing).max(0.0);
                // restitution damping dissipates (q - q_el) * closing
                p_cage += ((q - q_el) * closing).max(0.0);
                (q, c.mu_pocket * q)
            };
            let vs2 = (alpha + side * beta).max(0.0);
            let ct = if vs2 > 0.0 { drag / (vs2 + V_EPS * V_EPS).sqrt() } else { 0.0 };
            s_q += side * qn;
            s_qs += side * qn * sk;
            q_pocket += qn;
            s_c += ct;
            s_cs += ct * sk;
            s_css += ct * sk * sk;
            s_crad += side * rad * ct;
            s_csrad += side * sk * rad * ct;
            s_crr += ct * rad * rad;
            p_cage += ct * vs2;
        }
    }
    PocketSums {
        q: s_q,
        qs: s_qs,
        c: s_c,
        cs: s_cs,
        css: s_css,
        crad: s_crad,
        csrad: s_csrad,
        crr: s_crr,
        q_pocket,
        power: p_cage,
    }
}

/// Roller `j`'s contacts (cup, cone, flange, cage pocket) at state `y`: its record (loads,
/// moments, its shares of the cone's, cage's and cup's equations and of the dissipated
/// power) and, when given, its 11 derivatives in `dy` and its slice loads (cone, then cup) in
/// `slice_loads`. It reads only `y`, so rollers may be evaluated in any order or at once.
#[allow(clippy::too_many_arguments)]
pub(crate) fn evaluate_roller(
    g: &Geometry,
    c: &Constants,
    inputs: &Inputs,
    f: &Frame,
    y: &[f64],
    j: usize,
    dy: Option<&mut [f64]>,
    slice_loads: Option<&mut [f64]>,
) -> RollerRecord {
    let ns = c.s_cm.len();
    let o = c.layout.roller(j);
    let RollerPose {
        e_r,
        e_t,
        r,
        pos,
        vel,
        u,
        m_in,
        a,
        w,
        sf,
        cf,
    } = roller_pose(g, c, y, j);
    let (xd, drd, psid) = (y[o + 3], y[o + 4], y[o + 5]);
    let da_dtilt = m_in * cf;
    let da_dskew = -u * sf - e_t * cf;
    let dd = c.dd_half[j];
    // defects on this roller: its body frame (the outward normal, turned with its spin)
    let on_roller = c.layout.spin_of(j).map(|k| RollerBody {
        defects: &c.defects,
        j,
        normal: m_in,
        spin: y[k],
        cm: c.cm,
    });

    // cup: on its support (fixed where the housing is rigid); it turns at `cupSpeed` about
    // its axis
    let moving_cup = c.housing.is_some();
    let cup = Race {
        line: &c.cup,
        pos: if moving_cup { pos - f.cup_pos } else { pos },
        vel,
        w,
        a,
        ring_v0: f.cup_vel,
        ring_omega: V3::x() * inputs.cup_speed,
        pt_v0: if moving_cup { f.cup_orbit * psid } else { V3::zeros() },
        pt_omega: V3::x() * psid,
        gap_max: -c.half_clearance * c.cos_o,
        starved: f.starved,
    };
    let (cone_loads, cup_loads) = match slice_loads {
        Some(roller) => {
            let (cone, cup) = roller.split_at_mut(ns);
            (Some(cone), Some(cup))
        }
        None => (None, None),
    };
    let near_defect = near(&c.defects.cup, &cup.pos, f.cup_turn);
    let cup_sum = if let Some(body) = &on_roller {
        let body = body.in_frame(&cup, body.normal, true);
        race_slices(c, &cup, dd, cup_loads, |q: &V3| {
            let (gap, gap_psi) = cup_gap(c, q, near_defect, f.cup_turn);
            let (drop, drop_psi) = body.gap(q);
            (gap + drop, gap_psi + drop_psi)
        })
    } else if c.lobes > 0 || near_defect {
        race_slices(c, &cup, dd, cup_loads, |q: &V3| cup_gap(c, q, near_defect, f.cup_turn))
    } else {
        let gap = -c.half_clearance * c.cos_o;
        #[cfg(target_arch = "x86_64")]
        if c.lane_slices {
            race_slices_lanes(c, &cup, dd, cup_loads, gap)
        } else {
            race_slices(c, &cup, dd, cup_loads, |_: &V3| (gap, 0.0))
        }
        #[cfg(not(target_arch = "x86_64"))]
        race_slices(c, &cup, dd, cup_loads, |_: &V3| (gap, 0.0))
    };
    // cone: in its own (displaced, misaligned, spinning) frame, rotated back once
    let cone = Race {
        line: &c.cone,
        pos: f.rot_t * (pos - f.origin),
        vel: f.rot_t * vel,
        w: f.rot_t * w,
        a: f.rot_t * a,
        ring_v0: f.cone_vel_l,
        ring_omega: V3::x() * inputs.speed,
        pt_v0: f.x_cross_o_l * psid,
        pt_omega: f.x_l * psid,
        gap_max: 0.0,
        starved: f.starved,
    };
    // a cone defect in the cone's material frame, turned by `f.cone_turn` since t = 0
    let near_cone_defect = near(&c.defects.cone, &cone.pos, f.cone_turn);
    let cone_sum = if near_cone_defect || on_roller.is_some() {
        let body = on_roller.as_ref().map(|b| b.in_frame(&cone, f.rot_t * b.normal, false));
        race_slices(c, &cone, dd, cone_loads, |q: &V3| {
            let (mut gap, mut gap_psi) = if near_cone_defect {
                cone_gap(c, q, f.cone_turn)
            } else {
                (0.0, 0.0)
            };
            if let Some(body) = &body {
                let (drop, drop_psi) = body.gap(q);
                gap += drop;
                gap_psi += drop_psi;
            }
            (gap, gap_psi)
        })
    } else {
        #[cfg(target_arch = "x86_64")]
        if c.lane_slices {
            race_slices_lanes(c, &cone, dd, cone_loads, 0.0)
        } else {
            race_slices(c, &cone, dd, cone_loads, |_: &V3| (0.0, 0.0))
        }
        #[cfg(not(target_arch = "x86_64"))]
        race_slices(c, &cone, dd, cone_loads, |_: &V3| (0.0, 0.0))
    };
    let (f_cone_r, m_cone_r) = (f.rot * cone_sum.f, f.rot * cone_sum.m);
    let p_raceway = cup_sum.power + cone_sum.power;
    let extrapolated = cup_sum.extrapolated | cone_sum.extrapolated;

    let (f_fl, m_fl, q_fl, sliding_fl, p_flange) = flange_contact(c, f, inputs, pos, vel, w, a, psid);
    let (f_pk, m_pk, q_pocket, p_cage) = cage_pocket(g, c, f, j, pos, vel, w, a);

    // totals of the roller
    let force = cup_sum.f + f_cone_r + f_fl + f_pk;
    let m = cup_sum.m + m_cone_r + m_fl + m_pk;
    // moments about the geometric centre (the centre of mass is cm along a from it)
    let to_centre = a * c.cm;
    let mut rec = RollerRecord {
        qi: cone_sum.q,
        qo: cup_sum.q,
        qf: q_fl,
        qc: q_pocket,
        m_cone: m_cone_r + to_centre.cross(&f_cone_r),
        m_cup: cup_sum.m + to_centre.cross(&cup_sum.f),
        m_flange: m_fl + to_centre.cross(&f_fl),
        tilt_axis: e_t * cf + u * sf,
        skew_axis: m_in,
        f_cone: -(f_cone_r + f_fl),
        f_cage: -f_pk,
        m_cage: -((pos - f.cage_pos).cross(&f_pk) + m_pk)[0],
        f_cup: -cup_sum.f,
        sliding: cone_sum.traction.norm() + cup_sum.traction.norm() + sliding_fl,
        // on the cone: its moment about the origin (the rollers' moment about their centre
        // of mass is -(m_cone_r + m_fl)) and about its own axis; on the cup (fixed): the
        // opposite of the cup contact's moment on the roller about the bearing axis
        m_cone_origin: -(m_cone_r + m_fl) + pos.cross(&(-(f_cone_r + f_fl))),
        t_cone_raceway: (-m_cone_r - (pos - f.origin).cross(&f_cone_r)).dot(&f.axis_c),
        t_cone_flange: (-m_fl - (pos - f.origin).cross(&f_fl)).dot(&f.axis_c),
        t_cup: -(cup_sum.m + pos.cross(&cup_sum.f))[0],
        p_raceway,
        p_flange,
        p_cage,
        extrapolated,
        defect_spin: 0.0,
    };

    if let Some(dy) = dy {
        // translation in cylindrical coordinates
        let (fx, fr, ft) = (force[0], force.dot(&e_r), force.dot(&e_t));
        dy[0] = xd;
        dy[1] = drd;
        dy[2] = psid;
        dy[3] = if c.axial { fx / c.m_r } else { 0.0 };
        let centripetal = if c.centrifugal { r * psid * psid } else { 0.0 };
        dy[4] = fr / c.m_r + centripetal;
        dy[5] = (ft / c.m_r - 2.0 * drd * psid) / r;
        // attitude rates from the angular velocity relative to the azimuth frame
        let w_rel = w - V3::x() * psid;
        let a_dot = w_rel.cross(&a);
        dy[6] = a_dot.dot(&da_dtilt) / (cf * cf);
        dy[7] = a_dot.dot(&da_dskew);
        if on_roller.is_some() {
            // the spin relative to the body frame (outward normal, a x it), whose rotation
            // about the axis is cos(beta) cos(skew) psi' - sin(skew) tilt'
            rec.defect_spin = w.dot(&a) - (u[0] * cf * psid - sf * dy[6]);
        }
        // Euler: w' = (M.a/I_a) a + [M - (M.a) a - (I_a - I_t)(w.a)(w x a)] / I_t
        let ma = m.dot(&a);
        let gyro = if c.gyroscopic {
            w.cross(&a) * ((c.i_a - c.i_t) * w.dot(&a))
        } else {
            V3::zeros()
        };
        let wdot = a * (ma / c.i_a) + (m - a * ma - gyro) / c.i_t;
        // in the rotating azimuth frame: d/dt(w_r) = w'.e_r + psi' w_t, d/dt(w_t) = w'.e_t - psi' w_r
        dy[8] = wdot[0];
        dy[9] = wdot.dot(&e_r) + psid * y[o + 10];
        dy[10] = wdot.dot(&e_t) - psid * y[o + 9];
    }
    rec
}

/// Every roller's contacts into `records` (and `dy`, `slice_loads` when given): on the
/// caller's thread, or spread over the element's thread pool (`threads` > 1) for a
/// right-hand side with its slice loads. Each roller writes only its own record, derivatives
/// and slice loads.
#[allow(clippy::too_many_arguments)]
fn rollers(
    g: &Geometry,
    c: &Constants,
    inputs: &Inputs,
    frame: &Frame,
    y: &[f64],
    dy: Option<&mut [f64]>,
    records: &mut [RollerRecord],
    mut slice_loads: Option<&mut [f64]>,
) {
    let ns = c.s_cm.len();
    match (&c.pool, dy, slice_loads.as_deref_mut()) {
        (Some(pool), Some(dy), Some(loads)) => {
            use rayon::prelude::*;
            let per_roller = &mut dy[c.layout.roller(0)..c.layout.roller(g.z)];
            pool.install(|| {
                records
                    .par_iter_mut()
                    .zip(per_roller.par_chunks_mut(PER_ROLLER))
                    .zip(loads.par_chunks_mut(2 * ns))
                    .enumerate()
                    .for_each(|(j, ((rec, d), l))| *rec = evaluate_roller(g, c, inputs, frame, y, j, Some(d), Some(l)));
            });
        }
        (_, mut dy, _) => {
            for (j, rec) in records.iter_mut().enumerate().take(g.z) {
                let o = c.layout.roller(j);
                let d = dy.as_deref_mut().map(|d| &mut d[o..o + PER_ROLLER]);
                let loads = slice_loads.as_deref_mut().map(|l| &mut l[2 * ns * j..2 * ns * (j + 1)]);
                *rec = evaluate_roller(g, c, inputs, frame, y, j, d, loads);
            }
        }
    }
}

/// The cone's and cage's pose and motion at state `y` with `inputs`: what every roller of one
/// evaluation shares.
pub(crate) fn frame(g: &Geometry, c: &Constants, inputs: &Inputs, y: &[f64]) -> Frame {
    // cone pose: rotation R (columns: the cone's axes), origin, velocity, spin about R x
    let rot = super::cone_rotation(inputs.xi, inputs.zeta);
    let rot_t = rot.transpose();
    let axis_c: V3 = rot.column(0).into_owned();
    let held = prescribed_cone(c, inputs);
    let origin = V3::from_fn(|k, _| held[k].unwrap_or(y[CONE + k]));
    // a prescribed translation's velocity is its input's rate, held in the state over the
    // interval (`Dynamic::advance_ramped`; zero for held inputs)
    let cone_vel = V3::from_fn(|k, _| y[CONE + 3 + k]);
    // in the cone's frame: its own velocity, the bearing axis, the axis term of the orbit
    let cone_vel_l = rot_t * cone_vel;
    let x_l = rot_t * V3::x();
    let x_cross_o_l = rot_t * V3::x().cross(&origin);
    // cage pose
    let (cage_psi, cage_rate, cage_pos, cage_vel) = if c.cage_dynamic {
        (
            y[CAGE + 2],
            y[CAGE + 5],
            V3::new(0.0, y[CAGE], y[CAGE + 1]),
            V3::new(0.0, y[CAGE + 3], y[CAGE + 4]),
        )
    } else {
        (cage_angle(g, c, y), cage_speed(g, c, y), V3::zeros(), V3::zeros())
    };
    let (cup_pos, cup_vel) = cup_motion(c, y);
    Frame {
        rot,
        rot_t,
        axis_c,
        origin,
        cone_vel,
        cone_vel_l,
        x_l,
        x_cross_o_l,
        cage_psi,
        cage_rate,
        cage_pos,
        cage_vel,
        cup_pos,
        cup_vel,
        cup_orbit: V3::x().cross(&cup_pos),
        cone_turn: c.layout.cone_turn.map_or(0.0, |k| y[k]),
        cup_turn: c.layout.cup_turn.map_or(0.0, |k| y[k]),
        starved: Starved::of(c.supply.starvation(inputs.relative_speed())),
    }
}

/// The cage on its guiding land: the short-bearing film with spin, whirl and squeeze,
/// evaluated at the critical gap at most; Hertz, damping and boundary friction below it. Adds
/// the land's force and moment about the axis on the cage, and the power it dissipates, to
/// `tot`.
pub(crate) fn cage_land(c: &Constants, f: &Frame, inputs: &Inputs, tot: &mut Totals) {
    let land = &c.land;
    // the cage relative to the cup, which carries the land (a rigid housing's cup is at
    // +0, which the differences leave exact)
    let (e, v) = (f.cage_pos - f.cup_pos, f.cage_vel - f.cup_vel);
    let ecc = e.norm();
    let e_hat = if ecc > 0.0 { e / ecc } else { V3::new(0.0, 1.0, 0.0) };
    let e_perp = V3::x().cross(&e_hat);
    let v_r = v.dot(&e_hat);
    let gap = land.clearance - ecc;
    // The land turns with the cup: the film seen from the cup, where the cage spins at
    // its speed relative to the cup and its centre whirls at the tangential speed less
    // the cup's rotation (Reynolds' wedge term takes the sum of the surface speeds,
    // (omega_cage + omega_cup) / 2 - whirl; the Couette drag their difference); forces,
    // moment and dissipation are the same in either frame.
    let land_rate = f.cage_rate - inputs.cup_speed;
    let film = land.film(
        ecc.min(land.clearance - c.crit_gap),
        land_rate,
        v_r,
        v.dot(&e_perp) - inputs.cup_speed * ecc,
    );
    tot.f_cage += e_hat * film.radial + e_perp * film.tangential;
    tot.m_cage += film.moment;
    tot.p_cage += film.power;
    if gap < c.crit_gap {
        let c_land = 2.0 * (c.m_cage * c.k_land).sqrt() * 0.1;
        let q_el = (c.crit_gap - gap) * c.k_land;
        let q = (q_el + c_land * v_r).max(0.0);
        tot.f_cage -= e_hat * q;
        // damping (q - q_el) v_r and boundary friction against the cage's surface speed
        tot.p_cage += ((q - q_el) * v_r).max(0.0);
        tot.m_cage -= c.mu_pocket * q * land.radius * land_rate.signum();
        tot.p_cage += c.mu_pocket * q * (land_rate * land.radius).abs();
    }
}

/// Evaluate all contacts at state `y`; write the derivatives into `dy` when given; fill the
/// per-roller `records`; return the totals.
#[allow(clippy::too_many_arguments)]
pub(crate) fn evaluate(
    g: &Geometry,
    c: &Constants,
    inputs: &Inputs,
    y: &[f64],
    mut dy: Option<&mut [f64]>,
    records: &mut [RollerRecord],
    slice_loads: Option<&mut [f64]>,
) -> Totals {
    let mut tot = Totals::default();
    let frame = frame(g, c, inputs, y);
    let (cup_pos, cup_vel) = (frame.cup_pos, frame.cup_vel);
    rollers(g, c, inputs, &frame, y, dy.as_deref_mut(), records, slice_loads);
    // the rollers' shares, added in roller order (the same bits for any thread count)
    for rec in records.iter() {
        tot.f_cone += rec.f_cone;
        tot.m_cone += rec.m_cone_origin;
        tot.t_cone_raceway += rec.t_cone_raceway;
        tot.t_cone_flange += rec.t_cone_flange;
        tot.t_cup += rec.t_cup;
        tot.f_cup += rec.f_cup;
        tot.f_cage += rec.f_cage;
        tot.m_cage += rec.m_cage;
        tot.p_raceway += rec.p_raceway;
        tot.p_flange += rec.p_flange;
        tot.p_cage += rec.p_cage;
        tot.extrapolated |= rec.extrapolated;
    }

    // cage land (dynamic cage on the cup land)
    let f_cage_rollers = tot.f_cage;
    if c.cage_dynamic {
        cage_land(c, &frame, inputs, &mut tot);
        // the land's force on the cage comes from the cup
        tot.f_cup -= tot.f_cage - f_cage_rollers;
    }
    // the cup on its support: m u'' = F_b - k u - c u'
    if let Some(h) = &c.housing {
        tot.cup_acceleration = (tot.f_cup - cup_pos * h.stiffness - cup_vel * h.damping) / h.mass;
    }
    if let Some(dy) = dy {
        // cone
        for k in 0..3 {
            dy[CONE + k] = y[CONE + 3 + k];
        }
        let f_ext = V3::new(inputs.fx, inputs.fy, inputs.fz);
        let acc = (f_ext + tot.f_cone) / c.m_cone;
        for k in 0..3 {
            if c.prescribed[k] {
                dy[CONE + k] = 0.0;
                dy[CONE + 3 + k] = 0.0;
            } else {
                dy[CONE + 3 + k] = acc[k];
            }
        }
        if let Some(h) = c.layout.housing {
            dy[h] = cup_vel[1];
            dy[h + 1] = cup_vel[2];
            dy[h + 2] = tot.cup_acceleration[1];
            dy[h + 3] = tot.cup_acceleration[2];
        }
        if let Some(k) = c.layout.cup_turn {
            dy[k] = inputs.cup_speed;
        }
        if let Some(k) = c.layout.cone_turn {
            dy[k] = inputs.speed;
        }
        for &(j, k) in &c.layout.roller_spins {
            dy[k] = records[j].defect_spin;
        }
        // cage
        if c.cage_dynamic {
            dy[CAGE] = y[CAGE + 3];
            dy[CAGE + 1] = y[CAGE + 4];
            dy[CAGE + 2] = y[CAGE + 5];
            dy[CAGE + 3] = tot.f_cage[1] / c.m_cage;
            dy[CAGE + 4] = tot.f_cage[2] / c.m_cage;
            dy[CAGE + 5] = tot.m_cage / c.j_cage;
        } else {
            for k in 0..6 {
                dy[CAGE + k] = 0.0;
            }
        }
    }
    tot
}
