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
//! (Ocvirk) on the cup, radial and tangential film force and drag torque; Hertz below the
//! critical gap.

use super::{RollerRecord, Totals, CAGE, CONE, PER_ROLLER, ROLLERS};
use crate::bearing::Bearing;
use crate::contact::{LineLaw, PointContact};
use crate::geometry::Geometry;
use crate::model::{Inputs, Lubrication, Parameters, Preload};
use crate::tribology as tr;
use nalgebra::Vector3;
use std::f64::consts::{PI, TAU};

type V3 = Vector3<f64>;

/// Speed below which dry and asperity friction are regularised (m/s).
const V_EPS: f64 = tr::DRY_REGULARISATION_SPEED;

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
    cone: LineConst,
    cup: LineConst,
    flange: Option<FlangeConst>,
    cos_o: f64,
    half_clearance: f64,
    lobes: u32,
    waveform: f64,
    dd_half: Vec<f64>,
    damping: f64,
    e_prime: f64,
    eta0: f64,
    /// Roelands viscosity of the oil against pressure.
    viscosity: tr::ViscosityTable,
    alpha: f64,
    sigma: f64,
    mu: f64,
    flange_mu0: f64,
    dry: bool,
    gyroscopic: bool,
    centrifugal: bool,
    // cage
    cage_dynamic: bool,
    m_cage: f64,
    j_cage: f64,
    pocket_half: f64,
    k_pocket: f64,
    crit_gap: f64,
    mu_pocket: f64,
    reduced_mass: f64,
    land_radius: f64,
    land_width: f64,
    land_clearance: f64,
    k_land: f64,
    m_cone: f64,
    pitch_radius: f64,
    axial: bool,
    displacement_preload: bool,
}

/// One raceway line: a point of its generatrix, its normal (force on the roller), the slice
/// law, equivalent radii and the logarithmic film constants.
#[derive(Debug, Clone)]
struct LineConst {
    reference: [f64; 2],
    normal: [f64; 2],
    law: LineLaw,
    r_bar: Vec<f64>,
    ln_film: Vec<f64>,
}

impl LineConst {
    fn new(line: &crate::geometry::ContactLine, p: &Parameters, e_prime: f64) -> LineConst {
        LineConst {
            reference: line.point[0],
            normal: line.normal,
            law: line.law.clone(),
            r_bar: line.r_bar.clone(),
            ln_film: line
                .r_bar
                .iter()
                .map(|r| tr::film_line_log_constant(p.eta0, p.alpha.max(1e-12), e_prime, *r))
                .collect(),
        }
    }
}

#[derive(Debug, Clone)]
struct FlangeConst {
    reference: [f64; 2],
    normal: [f64; 2],
    sphere_radius: f64,
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
        let cm = g.cm_offset;
        let cos_h = g.half_angle.cos();
        let flange = g.flange.as_ref().map(|f| FlangeConst {
            reference: f.point,
            normal: f.normal,
            sphere_radius: b.roller_end_radius,
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
            cone: LineConst::new(&g.cone, p, g.e_prime),
            cup: LineConst::new(&g.cup, p, g.e_prime),
            flange,
            cos_o: g.cup_angle.cos(),
            half_clearance: 0.5 * p.clearance,
            lobes: p.outer_lobes,
            waveform: p.outer_waveform,
            dd_half: p.roller_dd.iter().map(|d| 0.5 * d).collect(),
            damping: p.contact_damping,
            e_prime: g.e_prime,
            eta0: p.eta0,
            viscosity: tr::ViscosityTable::new(p.eta0),
            alpha: p.alpha,
            sigma: p.roughness,
            mu: p.mu,
            flange_mu0: p.flange_mu0,
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
            land_radius: b.land_radius,
            land_width: b.land_width,
            land_clearance: b.guide_clearance.max(1e-6),
            k_land,
            m_cone: p.cone_mass,
            pitch_radius,
            axial: g.axial,
            displacement_preload: p.preload == Preload::Displacement,
        }
    }
}

/// Cage angle (roller 1's pocket) for the state `y`.
pub(crate) fn cage_angle(g: &Geometry, p: &Parameters, y: &[f64]) -> f64 {
    if p.cage_dynamic {
        return y[CAGE + 2];
    }
    // kinematic cage: circular mean of the rollers' azimuths less their pocket offsets
    let (mut sx, mut sy) = (0.0, 0.0);
    for j in 0..g.z {
        let psi = y[ROLLERS + PER_ROLLER * j + 2] - TAU * j as f64 / g.z as f64;
        sx += psi.cos();
        sy += psi.sin();
    }
    sy.atan2(sx)
}

/// Cage angular speed for the state `y`.
pub(crate) fn cage_speed(g: &Geometry, p: &Parameters, y: &[f64]) -> f64 {
    if p.cage_dynamic {
        return y[CAGE + 5];
    }
    (0..g.z).map(|j| y[ROLLERS + PER_ROLLER * j + 5]).sum::<f64>() / g.z as f64
}

/// The radial unit vector of the point `q` about the x axis (and its distance).
#[inline]
fn radial(q: &V3) -> (V3, f64) {
    let rho = (q[1] * q[1] + q[2] * q[2]).sqrt();
    if rho > 0.0 {
        (V3::new(0.0, q[1] / rho, q[2] / rho), rho)
    } else {
        (V3::new(0.0, 1.0, 0.0), 0.0)
    }
}

/// Traction on a surface sliding at `v_t` (tangential, roller relative to ring) under normal
/// load `q`, entrainment speed `u_e`: returns the force on the roller and the dissipated power.
#[inline]
fn raceway_traction(c: &Constants, q: f64, v_t: &V3, u_e: f64, r_bar: f64, ln_film: f64) -> (V3, f64) {
    let vs = v_t.norm();
    if q <= 0.0 || vs == 0.0 {
        return (V3::zeros(), 0.0);
    }
    let coef = if c.dry {
        c.mu * q / (vs * vs + V_EPS * V_EPS).sqrt()
    } else if u_e < 1e-6 {
        // no rolling: boundary friction, regularised
        0.1 * q / (vs * vs + V_EPS * V_EPS).sqrt()
    } else {
        let s = (vs / u_e).max(1e-9);
        let w = q / c.slice_len;
        let h = tr::film_line_fast(ln_film, u_e, w);
        let lambda = if c.sigma > 0.0 { h / c.sigma } else { f64::INFINITY };
        // boundary / mixed / full film [W25]; each law only where it is used
        let full_film = || {
            let p_mean = (w * PI * c.e_prime / (32.0 * r_bar)).sqrt(); // w / (2 b), b the Hertz half-width
            tr::full_film_mu_at_viscosity(c.viscosity.eta(p_mean), s * u_e, h, p_mean).abs()
        };
        let mu = if lambda >= 1.5 {
            full_film()
        } else if lambda < 0.01 {
            tr::boundary_mu(s)
        } else {
            tr::traction_mu(lambda, s, full_film())
        };
        mu * q / (s * u_e)
    };
    (-v_t * coef, coef * vs * vs)
}

/// One slice against one raceway. `to_ring` maps a global point into the raceway's frame
/// (identity for the cup), `from_ring` back. Returns (force on roller, contact point,
/// elastic+damping normal load, dissipated power, extrapolated).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn raceway_slice(
    c: &Constants,
    line: &LineConst,
    k: usize,
    gap: impl Fn(&V3) -> f64,
    centre_local: &V3,
    axis_local: &V3,
    radius: f64,
    frame: &RingFrame,
    roller_point_velocity: impl Fn(&V3) -> V3,
    orbit_rate: f64,
) -> Option<(V3, V3, f64, f64, bool)> {
    let (law, reference, normal) = (&line.law, line.reference, line.normal);
    // slice centre and axis in the ring frame
    let (cl, al) = (*centre_local, *axis_local);
    let (er_c, _) = radial(&cl);
    // into the ring: minus its normal
    let g = -(V3::x() * normal[0] + er_c * normal[1]);
    let mut d = g - al * g.dot(&al);
    let dn = d.norm();
    if dn == 0.0 {
        return None;
    }
    d /= dn;
    let pl = cl + d * radius;
    let (er_p, rho_p) = radial(&pl);
    let delta = -((pl[0] - reference[0]) * normal[0] + (rho_p - reference[1]) * normal[1]) + gap(&pl);
    if delta <= 0.0 {
        return None;
    }
    let (q_el, dq, ext) = law.load(k, delta);
    let r_bar = line.r_bar[k];
    let n_local = V3::x() * normal[0] + er_p * normal[1];
    let n = frame.rotate_to_global(&n_local);
    let p = frame.to_global(&pl);
    let v_roller = roller_point_velocity(&p);
    let v_ring = frame.velocity(&p);
    let v_rel = v_roller - v_ring;
    let vn = v_rel.dot(&n);
    // damping: c = 2 zeta sqrt(m k_slice / s) per slice (critical for the whole line)
    let c_damp = 2.0 * c.damping * (c.m_r * dq / c.radius.len() as f64).sqrt();
    let q = (q_el - c_damp * vn).max(0.0);
    let damping_power = (q - q_el) * (-vn);
    let v_t = v_rel - n * vn;
    // entrainment relative to the contact point, which orbits with the roller
    let v_point = V3::x().cross(&p) * orbit_rate;
    let u1 = v_roller - v_point;
    let u2 = v_ring - v_point;
    let ue_vec = (u1 + u2) * 0.5;
    let u_e = (ue_vec - n * ue_vec.dot(&n)).norm();
    let (f_t, p_t) = raceway_traction(c, q, &v_t, u_e, r_bar, line.ln_film[k]);
    Some((n * q + f_t, p, q, p_t + damping_power.max(0.0), ext))
}

/// A ring's pose: rotation (columns: the ring's axes in global coordinates), origin,
/// translational velocity and angular velocity.
pub(crate) struct RingFrame {
    rot: nalgebra::Matrix3<f64>,
    rot_t: nalgebra::Matrix3<f64>,
    origin: V3,
    velocity: V3,
    omega: V3,
    /// The fixed cup: every transform is the identity.
    fixed: bool,
}

impl RingFrame {
    #[inline(always)]
    fn to_local(&self, q: &V3) -> V3 {
        if self.fixed {
            *q
        } else {
            self.rot_t * (q - self.origin)
        }
    }
    #[inline(always)]
    fn to_global(&self, q: &V3) -> V3 {
        if self.fixed {
            *q
        } else {
            self.rot * q + self.origin
        }
    }
    #[inline(always)]
    fn rotate_to_local(&self, v: &V3) -> V3 {
        if self.fixed {
            *v
        } else {
            self.rot_t * v
        }
    }
    #[inline(always)]
    fn rotate_to_global(&self, v: &V3) -> V3 {
        if self.fixed {
            *v
        } else {
            self.rot * v
        }
    }
    #[inline(always)]
    fn velocity(&self, q: &V3) -> V3 {
        if self.fixed {
            V3::zeros()
        } else {
            self.velocity + self.omega.cross(&(q - self.origin))
        }
    }
}

/// Evaluate all contacts at state `y`; write the derivatives into `dy` when given; fill the
/// per-roller `records`; return the totals.
pub(crate) fn evaluate(
    g: &Geometry,
    _p: &Parameters,
    c: &Constants,
    inputs: &Inputs,
    y: &[f64],
    mut dy: Option<&mut [f64]>,
    records: &mut [RollerRecord],
) -> Totals {
    let z = g.z;
    let mut tot = Totals::default();
    // cone pose
    let rot = super::cone_rotation(inputs.xi, inputs.zeta);
    let axis_c = rot.column(0).into_owned();
    let cone_x = if c.displacement_preload {
        inputs.axial_displacement
    } else {
        y[CONE]
    };
    let cone = RingFrame {
        rot,
        rot_t: rot.transpose(),
        fixed: false,
        origin: V3::new(if c.axial { cone_x } else { 0.0 }, y[CONE + 1], y[CONE + 2]),
        velocity: V3::new(
            if c.displacement_preload || !c.axial { 0.0 } else { y[CONE + 3] },
            y[CONE + 4],
            y[CONE + 5],
        ),
        omega: axis_c * inputs.speed,
    };
    let id = nalgebra::Matrix3::identity();
    let cup = RingFrame {
        rot: id,
        rot_t: id,
        origin: V3::zeros(),
        velocity: V3::zeros(),
        omega: V3::zeros(),
        fixed: true,
    };
    // cage pose
    let (cage_psi, cage_rate, cage_pos, cage_vel) = if c.cage_dynamic {
        (
            y[CAGE + 2],
            y[CAGE + 5],
            V3::new(0.0, y[CAGE], y[CAGE + 1]),
            V3::new(0.0, y[CAGE + 3], y[CAGE + 4]),
        )
    } else {
        (cage_angle(g, _p, y), cage_speed(g, _p, y), V3::zeros(), V3::zeros())
    };
    let cage_point_velocity = |q: &V3| cage_vel + V3::x().cross(&(q - cage_pos)) * cage_rate;

    for j in 0..z {
        let o = ROLLERS + PER_ROLLER * j;
        let (x, dr, psi) = (y[o], y[o + 1], y[o + 2]);
        let (xd, drd, psid) = (y[o + 3], y[o + 4], y[o + 5]);
        let (tilt, skew) = (y[o + 6], y[o + 7]);
        let (sp, cp) = psi.sin_cos();
        let e_r = V3::new(0.0, cp, sp);
        let e_t = V3::new(0.0, -sp, cp);
        let r = c.pitch_radius + dr;
        let pos = V3::x() * x + e_r * r;
        let vel = V3::x() * xd + e_r * drd + e_t * (r * psid);
        let beta = g.axis_angle - tilt;
        let (sb, cb) = beta.sin_cos();
        let u = V3::x() * cb - e_r * sb;
        let m_in = V3::x() * sb + e_r * cb;
        let (sf, cf) = skew.sin_cos();
        let a = u * cf - e_t * sf;
        let da_dtilt = m_in * cf;
        let da_dskew = -u * sf - e_t * cf;
        let w = V3::x() * y[o + 8] + e_r * y[o + 9] + e_t * y[o + 10];
        let roller_point_velocity = |q: &V3| vel + w.cross(&(q - pos));
        let centre = pos - a * c.cm;
        let mut f = V3::zeros();
        let mut m = V3::zeros();
        let mut rec = RollerRecord {
            tilt_axis: e_t * cf + u * sf,
            skew_axis: m_in,
            ..RollerRecord::default()
        };
        let dd = c.dd_half[j];
        let cup_gap = |q: &V3| {
            let mut lobe = 0.0;
            if c.lobes > 0 {
                let psi_q = q[2].atan2(q[1]);
                lobe = 0.5 * c.waveform * (1.0 - (c.lobes as f64 * psi_q).cos());
            }
            -(c.half_clearance + lobe) * c.cos_o
        };
        let no_gap = |_: &V3| 0.0;
        // the roller in the cone's frame (slice centres are affine in the station)
        let (pos_c, a_c) = (cone.to_local(&pos), cone.rotate_to_local(&a));
        for k in 0..c.s_cm.len() {
            let ck = pos + a * c.s_cm[k];
            let ck_c = pos_c + a_c * c.s_cm[k];
            let rad = c.radius[k] + dd - c.shrink[k];
            if let Some((fk, pk, q, pw, ext)) = raceway_slice(c, &c.cup, k, cup_gap, &ck, &a, rad, &cup, roller_point_velocity, psid) {
                f += fk;
                m += (pk - pos).cross(&fk);
                rec.qo += q;
                rec.m_cup += (pk - centre).cross(&fk);
                tot.p_raceway += pw;
                tot.extrapolated |= ext;
            }
            if let Some((fk, pk, q, pw, ext)) = raceway_slice(c, &c.cone, k, no_gap, &ck_c, &a_c, rad, &cone, roller_point_velocity, psid) {
                f += fk;
                m += (pk - pos).cross(&fk);
                rec.qi += q;
                rec.m_cone += (pk - centre).cross(&fk);
                tot.p_raceway += pw;
                tot.extrapolated |= ext;
                tot.f_cone -= fk;
                tot.m_cone += pk.cross(&(-fk));
                tot.t_cone_raceway += (pk - cone.origin).cross(&(-fk)).dot(&axis_c);
            }
        }
        // flange: roller-end sphere on the conical rib
        if let Some(fl) = &c.flange {
            let s_centre = pos + a * fl.s_sphere;
            let sl = cone.to_local(&s_centre);
            let (er, rho) = radial(&sl);
            let dist = (sl[0] - fl.reference[0]) * fl.normal[0] + (rho - fl.reference[1]) * fl.normal[1];
            // `reference` is the nominal contact point on the rib, the nominal sphere centre
            // lies a sphere radius from it along the normal: interference = R_s - distance.
            let delta = fl.sphere_radius - dist;
            if delta > 0.0 {
                let (q_el, dq) = fl.hertz.load(delta);
                let n = cone.rotate_to_global(&(V3::x() * fl.normal[0] + er * fl.normal[1]));
                let pk = s_centre - n * fl.sphere_radius;
                let v_rel = roller_point_velocity(&pk) - cone.velocity(&pk);
                let vn = v_rel.dot(&n);
                let c_damp = 2.0 * c.damping * (c.m_r * dq).sqrt();
                let q = (q_el - c_damp * vn).max(0.0);
                let damping_power = ((q - q_el) * (-vn)).max(0.0);
                let v_t = v_rel - n * vn;
                let vs = v_t.norm();
                let (f_t, p_t) = if vs > 0.0 {
                    let coef = if c.dry {
                        c.mu * q / (vs * vs + V_EPS * V_EPS).sqrt()
                    } else {
                        let v_point = V3::x().cross(&pk) * psid;
                        let ue_vec = (roller_point_velocity(&pk) - v_point + cone.velocity(&pk) - v_point) * 0.5;
                        let u_e = (ue_vec - n * ue_vec.dot(&n)).norm();
                        let h = tr::film_point(c.eta0, c.alpha, c.e_prime, u_e, fl.hertz.ry, fl.hertz.rx, q);
                        let ratio = if c.sigma > 0.0 { h / c.sigma } else { f64::INFINITY };
                        let (ea, eb, ph) = fl.hertz.ellipse(q);
                        let asperity = q * tr::flange_boundary_mu(c.flange_mu0, ratio) / (vs * vs + V_EPS * V_EPS).sqrt();
                        let viscous = tr::flange_viscous_traction(c.eta0, vs, h, ea, eb, ph) / vs;
                        asperity + viscous
                    };
                    (-v_t * coef, coef * vs * vs)
                } else {
                    (V3::zeros(), 0.0)
                };
                let fk = n * q + f_t;
                f += fk;
                m += (pk - pos).cross(&fk);
                rec.qf += q;
                rec.m_flange += (pk - centre).cross(&fk);
                tot.p_flange += p_t + damping_power;
                tot.f_cone -= fk;
                tot.m_cone += pk.cross(&(-fk));
                tot.t_cone_flange += (pk - cone.origin).cross(&(-fk)).dot(&axis_c);
            }
        }
        // cage pocket: walls at +-pocket_half from the pocket's axial plane
        let psi_p = cage_psi + TAU * j as f64 / z as f64;
        let (spp, cpp) = psi_p.sin_cos();
        let e_tp = V3::new(0.0, -spp, cpp);
        let pocket_origin = cage_pos + V3::new(0.0, cpp, spp) * c.pitch_radius;
        let w_cage_rel = w - V3::x() * cage_rate;
        let w_rel_spin = w_cage_rel.dot(&a);
        // position across the pocket and velocity relative to the cage are affine in the
        // station s along the axis: value at the centre of mass + s * rate
        let tau0 = (pos - pocket_origin).dot(&e_tp);
        let tau1 = a.dot(&e_tp);
        let v0 = roller_point_velocity(&pos) - cage_point_velocity(&pos);
        let v1 = w_cage_rel.cross(&a);
        let rim_dir = w_cage_rel.cross(&e_tp);
        for k in 0..c.s_cm.len() {
            let sk = c.s_cm[k];
            let ck = pos + a * sk;
            let rad = c.radius[k];
            let tau = tau0 + tau1 * sk;
            let u_sum = w_rel_spin.abs() * rad;
            // relative velocity at the slice centre and the rim's offset towards the walls
            let v_centre = v0 + v1 * sk;
            let v_rim = rim_dir * rad;
            for side in [1.0_f64, -1.0] {
                // gap to the wall on side `side` (front wall at +e_tp)
                let gap = c.pocket_half - side * tau;
                let pk = ck + e_tp * (side * rad);
                let v_rel = v_centre + v_rim * side;
                let closing = side * v_rel.dot(&e_tp);
                let l = c.slice_len;
                let (qn, drag) = if gap >= c.crit_gap {
                    let qh = 2.44 * l * c.eta0 * u_sum * rad / gap;
                    (qh, 4.58 * l * c.eta0 * u_sum * (rad / gap).sqrt())
                } else {
                    let qh = 2.44 * l * c.eta0 * u_sum * rad / c.crit_gap;
                    let kappa = (1.0 - 0.026 * closing.abs().cbrt()).clamp(0.05, 1.0);
                    let lk = kappa.ln();
                    let c_ph = 2.0 * (c.reduced_mass * c.k_pocket).sqrt() * (-lk) / (lk * lk + PI * PI).sqrt();
                    let q_el = qh + (c.crit_gap - gap) * c.k_pocket;
                    let q = (q_el + c_ph * closing).max(0.0);
                    // restitution damping dissipates (q - q_el) * closing
                    tot.p_cage += ((q - q_el) * closing).max(0.0);
                    (q, c.mu_pocket * q)
                };
                if qn <= 0.0 && drag <= 0.0 {
                    continue;
                }
                let n = -e_tp * side; // force of the wall on the roller
                let v_t = v_rel - e_tp * v_rel.dot(&e_tp);
                let vs = v_t.norm();
                let f_t = if vs > 0.0 {
                    -v_t * (drag / (vs * vs + V_EPS * V_EPS).sqrt())
                } else {
                    V3::zeros()
                };
                let fk = n * qn + f_t;
                f += fk;
                m += (pk - pos).cross(&fk);
                rec.qc += qn;
                tot.f_cage -= fk;
                tot.m_cage -= (pk - cage_pos).cross(&fk)[0];
                tot.p_cage += -f_t.dot(&v_t);
            }
        }
        records[j] = rec;

        if let Some(dy) = dy.as_deref_mut() {
            // translation in cylindrical coordinates
            let (fx, fr, ft) = (f[0], f.dot(&e_r), f.dot(&e_t));
            dy[o] = xd;
            dy[o + 1] = drd;
            dy[o + 2] = psid;
            dy[o + 3] = if c.axial { fx / c.m_r } else { 0.0 };
            let centripetal = if c.centrifugal { r * psid * psid } else { 0.0 };
            dy[o + 4] = fr / c.m_r + centripetal;
            dy[o + 5] = (ft / c.m_r - 2.0 * drd * psid) / r;
            // attitude rates from the angular velocity relative to the azimuth frame
            let w_rel = w - V3::x() * psid;
            let a_dot = w_rel.cross(&a);
            dy[o + 6] = a_dot.dot(&da_dtilt) / (cf * cf);
            dy[o + 7] = a_dot.dot(&da_dskew);
            // Euler: w' = (M.a/I_a) a + [M - (M.a) a - (I_a - I_t)(w.a)(w x a)] / I_t
            let ma = m.dot(&a);
            let gyro = if c.gyroscopic {
                w.cross(&a) * ((c.i_a - c.i_t) * w.dot(&a))
            } else {
                V3::zeros()
            };
            let wdot = a * (ma / c.i_a) + (m - a * ma - gyro) / c.i_t;
            // in the rotating azimuth frame: d/dt(w_r) = w'.e_r + psi' w_t, d/dt(w_t) = w'.e_t - psi' w_r
            dy[o + 8] = wdot[0];
            dy[o + 9] = wdot.dot(&e_r) + psid * y[o + 10];
            dy[o + 10] = wdot.dot(&e_t) - psid * y[o + 9];
        }
    }
    // cage land (dynamic cage on the cup land)
    if c.cage_dynamic {
        let e = V3::new(0.0, y[CAGE], y[CAGE + 1]);
        let ecc = e.norm();
        let eps = (ecc / c.land_clearance).min(0.999_999);
        let u = (cage_rate * c.land_radius).abs();
        let (b3, c2) = (c.land_width.powi(3), c.land_clearance * c.land_clearance);
        let e_hat = if ecc > 0.0 { e / ecc } else { V3::new(0.0, 1.0, 0.0) };
        let e_perp = V3::x().cross(&e_hat) * cage_rate.signum();
        let gap = c.land_clearance - ecc;
        let one = 1.0 - eps * eps;
        let mut force = V3::zeros();
        if gap >= c.crit_gap {
            let w_r = c.eta0 * u * b3 * eps * eps / (c2 * one * one);
            let w_t = PI * c.eta0 * u * b3 * eps / (4.0 * c2 * one.powf(1.5));
            force -= e_hat * w_r + e_perp * w_t;
        } else {
            let v_rad = V3::new(0.0, y[CAGE + 3], y[CAGE + 4]).dot(&e_hat);
            let c_land = 2.0 * (c.m_cage * c.k_land).sqrt() * 0.1;
            let q = ((c.crit_gap - gap) * c.k_land + c_land * v_rad).max(0.0);
            force -= e_hat * q;
            // boundary friction against the cage's surface speed on the land
            tot.m_cage -= c.mu_pocket * q * c.land_radius * cage_rate.signum();
            tot.p_cage += c.mu_pocket * q * u;
        }
        let drag = 2.0 * PI * c.eta0 * u * c.land_radius * c.land_width / (c.land_clearance * one.sqrt());
        tot.m_cage -= drag * c.land_radius * cage_rate.signum();
        tot.p_cage += drag * u;
        tot.f_cage += force;
    }
    if let Some(dy) = dy {
        // cone
        for k in 0..3 {
            dy[CONE + k] = y[CONE + 3 + k];
        }
        let f_ext = V3::new(inputs.fx, inputs.fy, inputs.fz);
        let acc = (f_ext + tot.f_cone) / c.m_cone;
        dy[CONE + 3] = if c.displacement_preload || !c.axial { 0.0 } else { acc[0] };
        if c.displacement_preload || !c.axial {
            dy[CONE] = 0.0;
        }
        dy[CONE + 4] = acc[1];
        dy[CONE + 5] = acc[2];
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
