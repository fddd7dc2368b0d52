//! Quasi-static roller skew equilibrium with the cage pocket limit and the dry friction
//! torque of [D19] (`skewModel` = true). Documented in docs/model.md, "Roller skew and dry
//! friction torque".
//!
//! A fourth unknown per roller, the skew angle phi (rotation of the roller axis about its
//! in-plane normal p, right-handed: the small end moves towards -e_t), balanced by the skew
//! moments about p:
//! - raceway slices: Coulomb traction mu q along the rolling direction with the sign of the
//!   slice's kinematic sliding (moment s * q * mu(v_s)), and the normal loads through the
//!   contact shift: a skewed roller's cross-section at station s sits s phi off its axial
//!   plane, i.e. (s phi)^2 / (2 r_c) further from the bearing axis, which adds
//!   cos(a_o) (s phi)^2 / (2 r_c) to the cup interference and removes cos(a_i) (s phi)^2 / (2 r_c)
//!   from the cone's (moment -sum q d delta / d phi);
//! - flange: Coulomb traction mu Q_f at the rib contact (station s_f; `flange.mu` where set),
//!   and the normal force,
//!   which acts through the end-sphere centre (station s_c = R_s - l/2): skewed, the sphere
//!   centre moves s_c phi sideways, a restoring moment -Q_f s_c sin(a_f + a_r) phi;
//! - cage: the roller touches its pocket at two diagonal corners when |phi| reaches
//!   phi_max = eps_c / (l/2); the force F_c >= 0 at each corner gives -sgn(phi) F_c l.
//!
//! Complementarity (either |phi| < phi_max and F_c = 0, or |phi| = phi_max and F_c >= 0) is
//! built into the unknown: zeta with phi = clamp(zeta, -phi_max, phi_max) and
//! F_c = K_c (|zeta| - phi_max)^+, so both conditions hold identically and Newton sees a
//! piecewise-smooth residual (semismooth Newton). K_c only scales the unknown.
//!
//! Skew also adds friction thrust along the contact lines [D19]: mu q sin(phi) per slice along
//! the raceway's generatrix, at the slice's contact point, opposing the axial sliding of the
//! skewed roller on that raceway. The roller's spin adds nothing along its own axis, so that
//! sliding is minus the ring's surface speed resolved on the skewed axis. For phi > 0 and
//! positive speed the cone's surface speed resolved on that axis points towards the roller's
//! large end, so the roller slides towards its small end on the cone, and towards its large end
//! on the cup. Its speed is |omega_k sin(phi)| (r_k(s) + s sin(a_r)) with omega_k the ring's
//! speed relative to the cage, r_k(s) the radius of the slice's contact point and s its station
//! towards the small end: nearly, not exactly, uniform along the line (3-D kinematics,
//! docs/model.md). The thrust on the roller is then towards its large end from the cone and its
//! small end from the cup (a tilt couple); the cone's reaction points towards +x, along the
//! applied axial load, and the cup's towards -x, which tightens the bearing too (the skewed
//! rollers screw the rings together). The sense goes as sgn(omega_c phi) (omega_c the cone's
//! speed relative to the cage) and phi has the sign of omega_c, so it never flips (the opposite
//! of [D19]'s statement about its Eq. (9b); docs/model.md). Also the pocket friction mu F_c at
//! the two corners (a tilt couple).
//!
//! Solver: Newton on 3 + 4Z unknowns started from the in-plane solution; the per-roller
//! 4x4 blocks and their couplings to the cone are built by central differences of the roller
//! evaluation (an exact derivative of the regularised friction would need the slice sign
//! pattern's derivative, which is zero almost everywhere), the arrowhead system solved by a
//! Schur complement as in the in-plane solver.
//!
//! Torque [D19]: T = H / omega with H the friction power of roller-race microslip (sliding
//! speed across the contact width in the rolling direction: the slice's kinematic sliding plus
//! the Heathcote microslip of a freely rolling line contact, integrated with Simpson's rule over
//! the Hertz pressure) and of the Eq. (7) thrust mu q |sin phi| against the skewed roller's
//! axial sliding v |sin phi| (the power of the force the model applies; the axial sliding in
//! the Coulomb integral at full mu would be 12 times the thrust at the pocket limit and make
//! the raceway torque jump where the rollers reach it), end-rib sliding (Karna: Coulomb
//! force times the sliding speed at the rib contact) and roller-cage sliding (mu F_c at each
//! corner times the roller surface speed there).

use super::QuasiStatic;
use crate::bearing::Bearing;
use crate::contact::line_contact_half_width;
use crate::geometry::{cross, Geometry};
use crate::model::{Inputs, ModelError, Outputs, SolveReport};
use crate::tribology::dry_mu;
use nalgebra::{Matrix2x3, Matrix3, Matrix4, Matrix4x3, SMatrix, Vector2, Vector3, Vector4};

/// Unknowns per roller in the skew model.
const PER: usize = 4;
/// Simpson intervals across the contact width.
const SIMPSON: usize = 32;
const MAX_ITERATIONS: u32 = 200;

/// Per-slice constants of one contact line for the skew model.
#[derive(Debug, Clone)]
struct SkewLine {
    /// Interference change per phi^2 (m/rad^2): +cos(a_o) s^2 / (2 r_c) on the cup, negative on the cone.
    shift: Vec<f64>,
    /// Unit generatrix of the raceway in the axial plane, from the large towards the small
    /// roller end: the line of action of the friction thrust (Coulomb, tangent to the raceway).
    tangent: [f64; 2],
    /// Tilt moment about the roller centre of a unit thrust along `tangent` at the slice's
    /// contact point: cross(P - C, t) (about +R cos a_h on the cone, -R cos a_h on the cup).
    thrust_lever: Vec<f64>,
    /// In-plane moment about the bearing origin of a unit thrust along `tangent` at the
    /// slice's contact point: cross(P, t) (the cone's reaction moment).
    thrust_chi: Vec<f64>,
    /// Kinematic sliding speed (roller - ring) per unit cone speed, signed.
    slide: Vec<f64>,
    /// Rolling speed per unit cone speed (roller surface speed magnitude).
    rolling: Vec<f64>,
    /// Heathcote microslip coefficient (1/R_roller^2 - 1/R_race^2) / 4 in the normal plane (1/m^2).
    microslip: Vec<f64>,
    /// Equivalent radius (Hertz half width).
    r_bar: Vec<f64>,
    /// Ring radius at the slice (lever of the ring torque).
    ring_radius: Vec<f64>,
    /// Sign of the thrust on the roller per unit mu sin(phi) (cone -1, cup +1).
    thrust_sign: f64,
}

/// Everything fixed about the skew model for one parameter set.
#[derive(Debug, Clone)]
pub(super) struct SkewSetup {
    phi_max: f64,
    /// F_c = k_c (|zeta| - phi_max)^+ (N/rad).
    k_c: f64,
    cone: SkewLine,
    cup: SkewLine,
    /// Flange: station of the contact, lever s_c sin(a_f + a_r) of the normal force per unit phi,
    /// sliding speed per unit cone speed (signed), rib radius.
    flange_s: f64,
    flange_restoring: f64,
    /// Largest lever of the normal force: the contact reaches the rim of the end face.
    flange_lever_max: f64,
    flange_slide: f64,
    rib_radius: f64,
    /// Roller length; end radii (pocket contacts).
    length: f64,
    end_radii: (f64, f64),
    /// Roller spin per unit cone speed.
    spin: f64,
    /// Free-rolling pure-rolling lines of the microslip at +-u0 b.
    u0: f64,
}

/// One roller evaluated in the skew model.
#[derive(Debug, Clone, Copy, Default)]
struct SkewEval {
    /// Scaled residual (F_x, F_r, M_tilt / L_s, M_skew / L_s).
    r: Vector4<f64>,
    /// Force of the roller on the cone (x, r) and its in-plane moment about the origin.
    f_cone: Vector2<f64>,
    m_cone: f64,
    qi: f64,
    qo: f64,
    qf: f64,
    qc: f64,
    phi: f64,
    nit: f64,
    not: f64,
    nft: f64,
    nis: f64,
    nos: f64,
    nfs: f64,
    gap: f64,
}

/// Newton blocks of one roller kept for the back substitution: A^-1 (A = dr/dq) and B = dr/dc (global c).
#[derive(Debug, Clone, Copy, Default)]
struct Blocks {
    a_inv: Matrix4<f64>,
    b: Matrix4x3<f64>,
}

impl SkewSetup {
    pub(super) fn new(b: &Bearing, g: &Geometry, pocket_clearance: f64, cage_ratio: f64, spin_ratio: f64, k_ref: f64) -> SkewSetup {
        let l = g.length;
        let ls = 0.5 * l;
        let ah = g.half_angle;
        let line = |which: &crate::geometry::ContactLine, race_angle: f64, sign: f64, ring_speed: f64| {
            let n = g.slices;
            let tangent = [libm::cos(race_angle), -libm::sin(race_angle)];
            let mut out = SkewLine {
                shift: Vec::with_capacity(n),
                tangent,
                thrust_lever: which
                    .point
                    .iter()
                    .map(|p| cross([p[0] - g.center[0], p[1] - g.center[1]], tangent))
                    .collect(),
                thrust_chi: which.point.iter().map(|p| cross(*p, tangent)).collect(),
                slide: Vec::with_capacity(n),
                rolling: Vec::with_capacity(n),
                microslip: Vec::with_capacity(n),
                r_bar: which.r_bar.clone(),
                ring_radius: which.raceway_radius.clone(),
                thrust_sign: sign,
            };
            for k in 0..n {
                let s = g.slice_s[k];
                let r_c = g.center[1] + s * g.axis[1];
                out.shift.push(sign * libm::cos(race_angle) * s * s / (2.0 * r_c));
                // Roller surface speed facing this ring (cage frame): -w R on the cone, w R on the cup.
                let roller = sign * spin_ratio * g.slice_radius[k];
                let ring = ring_speed * which.raceway_radius[k];
                out.slide.push(roller - ring);
                out.rolling.push(roller.abs());
                let rho_r = g.slice_radius[k] / libm::cos(ah);
                let rho_g = which.raceway_curvature_radius[k].abs();
                out.microslip.push(0.25 * (1.0 / (rho_r * rho_r) - 1.0 / (rho_g * rho_g)));
            }
            out
        };
        let cone = line(&g.cone, g.cone_angle, -1.0, 1.0 - cage_ratio);
        let cup = line(&g.cup, g.cup_angle, 1.0, -cage_ratio);
        let rl = g.mean_radius + ls * libm::tan(ah);
        let rs = g.mean_radius - ls * libm::tan(ah);
        let (flange_s, flange_restoring, flange_lever_max, flange_slide, rib_radius) = match &g.flange {
            Some(f) => {
                let rel = [f.point[0] - g.center[0], f.point[1] - g.center[1]];
                let s_f = rel[0] * g.axis[0] + rel[1] * g.axis[1];
                // End-sphere centre: on the roller axis, R_s from the large end.
                let s_c = -0.5 * l + b.roller_end_radius;
                let af = b.flange_angle.unwrap_or(0.0);
                let restoring = s_c * libm::sin(af + g.axis_angle);
                let slide = spin_ratio * f.offset - (1.0 - cage_ratio) * f.rib_radius;
                // The contact point travels sideways over the end face, at most to its rim
                // (large-end radius, no chamfer data) at the contact's distance from the axis.
                let lever_max = (rl * rl - f.offset * f.offset).max(0.0).sqrt();
                (s_f, restoring, lever_max, slide, f.rib_radius)
            }
            None => (0.0, 0.0, 0.0, 0.0, 0.0),
        };
        // Pure-rolling lines of a freely rolling line contact with microslip v ~ u^2 under the
        // semi-elliptical pressure: (2/pi)(u0 sqrt(1 - u0^2) + asin u0) = 1/2.
        let frac = |u: f64| (2.0 / std::f64::consts::PI) * (u * (1.0 - u * u).sqrt() + libm::asin(u));
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        for _ in 0..60 {
            let m = 0.5 * (lo + hi);
            if frac(m) < 0.5 {
                lo = m
            } else {
                hi = m
            }
        }
        SkewSetup {
            phi_max: pocket_clearance / ls,
            k_c: k_ref * ls,
            cone,
            cup,
            flange_s,
            flange_restoring,
            flange_lever_max,
            flange_slide,
            rib_radius,
            length: l,
            end_radii: (rl, rs),
            spin: spin_ratio,
            u0: 0.5 * (lo + hi),
        }
    }

    /// Lever of the flange normal force about the skew axis at skew `phi`: s_c sin(a_f + a_r) phi
    /// while the contact stays on the end face, smoothly capped at the rim (x / (1 + x^4)^(1/4)).
    #[inline]
    fn flange_lever(&self, phi: f64) -> f64 {
        if self.flange_lever_max <= 0.0 {
            return self.flange_restoring * phi;
        }
        let x = self.flange_restoring * phi / self.flange_lever_max;
        self.flange_lever_max * x / (1.0 + x * x * x * x).sqrt().sqrt()
    }

    /// Skew angle and pocket force of the complementarity unknown zeta.
    #[inline]
    fn split(&self, zeta: f64) -> (f64, f64) {
        let phi = zeta.clamp(-self.phi_max, self.phi_max);
        let fc = self.k_c * (zeta.abs() - self.phi_max).max(0.0);
        (phi, fc)
    }
}

impl QuasiStatic {
    /// Evaluate roller `j` of the skew model: cone local (dx, dr), roller (a, rho, theta L_s, zeta L_s).
    fn eval_skew(&self, j: usize, cone: [f64; 2], q: [f64; 4], speed: f64, fc: f64, m_fc: f64, m_req: f64) -> SkewEval {
        let sk = self.skew.as_ref().expect("skew model set up");
        let g = &self.geometry;
        let st = &self.setup[j];
        let ls = self.ls;
        let mu = self.params.mu;
        let mu_rib = self.params.rib_mu();
        let theta = q[2] / ls;
        let (phi, f_c) = sk.split(q[3] / ls);
        let phi2 = phi * phi;
        let sin_phi = libm::sin(phi);
        let mut e = SkewEval {
            gap: f64::INFINITY,
            phi,
            qc: f_c,
            ..SkewEval::default()
        };
        let mut force = Vector2::zeros();
        let mut tilt = 0.0;
        // Rolling-speed friction coefficient (signed like the speed), for the thrust and the pocket.
        let mu_roll = |v: f64| dry_mu(mu, speed * v);

        // Cone and cup lines.
        let ni = g.cone.normal;
        let base_i = (cone[0] - q[0]) * ni[0] + (cone[1] - q[1]) * ni[1] + st.gap_cone;
        let no = g.cup.normal;
        let base_o = -(q[0] * no[0] + q[1] * no[1]) + st.gap_cup;
        for (line, sl, base, chi, crown, is_cone) in [
            (
                &g.cone,
                &sk.cone,
                base_i,
                &self.cone_chi[..],
                &self.cone_table_of(j).crown[..],
                true,
            ),
            (&g.cup, &sk.cup, base_o, &self.cone_chi[..], &self.cup_table_of(j).crown[..], false),
        ] {
            let n = Vector2::new(line.normal[0], line.normal[1]);
            let (mut sum_q, mut sum_lever, mut sum_chi, mut geom, mut fric) = (0.0, 0.0, 0.0, 0.0, 0.0);
            let (mut thrust_tilt, mut thrust_chi) = (0.0, 0.0);
            let mut max_delta = f64::NEG_INFINITY;
            for k in 0..g.slices {
                let gamma_term = if is_cone { st.gamma * chi[k] } else { 0.0 };
                let delta = base - theta * line.lever[k] + gamma_term - crown[k] + sl.shift[k] * phi2;
                max_delta = max_delta.max(delta);
                if delta <= 0.0 {
                    continue;
                }
                let qk = line.law.load(k, delta).0;
                sum_q += qk;
                sum_lever += qk * line.lever[k];
                if is_cone {
                    sum_chi += qk * chi[k];
                }
                // -q d delta / d phi
                geom -= qk * 2.0 * sl.shift[k] * phi;
                // Traction on the roller -q mu(v_s) e_t at station s: moment -s F_t.
                fric += g.slice_s[k] * qk * dry_mu(mu, speed * sl.slide[k]);
                // Thrust along the generatrix at the slice's contact point: its tilt moment
                // about the roller centre and (cone) its moment about the bearing origin.
                thrust_tilt += qk * sl.thrust_lever[k];
                thrust_chi += qk * sl.thrust_chi[k];
            }
            e.gap = e.gap.min(-max_delta);
            // Thrust on the roller along the raceway's generatrix t, per unit load:
            // sign(line) mu sin(phi) (against the roller's axial sliding on that raceway).
            let thrust = sl.thrust_sign * mu_roll(sl.rolling[g.slices / 2]) * sin_phi;
            let t = Vector2::new(sl.tangent[0], sl.tangent[1]);
            force += n * sum_q + t * (thrust * sum_q);
            tilt += sum_lever + thrust * thrust_tilt;
            if is_cone {
                e.qi = sum_q;
                e.nit = sum_lever;
                e.nis = geom + fric;
                e.f_cone -= n * sum_q + t * (thrust * sum_q);
                // Moment about the origin of the thrust reaction, slice by slice.
                e.m_cone -= sum_chi + thrust * thrust_chi;
            } else {
                e.qo = sum_q;
                e.not = sum_lever;
                e.nos = geom + fric;
            }
        }

        // Flange.
        if let Some(f) = &g.flange {
            let n = f.normal;
            let delta = (cone[0] - q[0]) * n[0] + (cone[1] - q[1]) * n[1] + st.gamma * self.flange_chi - theta * f.lever;
            e.gap = e.gap.min(-delta);
            let (qf, _) = f.hertz.load(delta);
            if qf > 0.0 {
                let nv = Vector2::new(n[0], n[1]);
                force += nv * qf;
                tilt += qf * f.lever;
                e.f_cone -= nv * qf;
                e.m_cone -= qf * self.flange_chi;
                e.qf = qf;
                e.nft = qf * f.lever;
                e.nfs = sk.flange_s * qf * dry_mu(mu_rib, speed * sk.flange_slide) - qf * sk.flange_lever(phi);
            }
        }

        // Cage pocket: normal couple against the skew, friction couple in the axial plane.
        let sz = if q[3] < 0.0 { -1.0 } else { 1.0 };
        let m_cage = -sz * f_c * sk.length;
        let mu_c = mu_roll(sk.spin.abs() * sk.end_radii.0);
        tilt += sz * mu_c * sk.length * f_c;

        e.r[0] = force[0];
        e.r[1] = force[1] + fc;
        e.r[2] = (tilt + m_fc - m_req) / ls;
        e.r[3] = (e.nis + e.nos + e.nfs + m_cage) / ls;
        if !g.axial {
            e.r[0] = 0.0;
        }
        e
    }

    /// Evaluate every roller; returns (max residual, merit, reference force, ring residual).
    fn evaluate_skew(
        &self,
        x: &[f64],
        evals: &mut [SkewEval],
        inputs: &Inputs,
        fc: f64,
        m_fc: f64,
        m_req: f64,
    ) -> (f64, f64, f64, Vector3<f64>) {
        let z = self.geometry.z;
        let mut ring = Vector3::new(inputs.fx, inputs.fy, inputs.fz);
        let (mut max_r, mut merit) = (0.0_f64, 0.0);
        let mut f_ref: f64 = inputs.fx.abs().max(inputs.fy.abs()).max(inputs.fz.abs()).max(fc.abs()).max(1.0);
        for j in 0..z {
            let st = self.setup[j];
            let dr = x[1] * st.cos_psi + x[2] * st.sin_psi;
            let b = 3 + PER * j;
            let e = self.eval_skew(
                j,
                [x[0], dr],
                [x[b], x[b + 1], x[b + 2], x[b + 3]],
                inputs.relative_speed(),
                fc,
                m_fc,
                m_req,
            );
            ring[0] += e.f_cone[0];
            ring[1] += e.f_cone[1] * st.cos_psi;
            ring[2] += e.f_cone[1] * st.sin_psi;
            for v in e.r.iter() {
                max_r = if v.is_finite() { max_r.max(v.abs()) } else { f64::INFINITY };
                merit += v * v;
            }
            f_ref = f_ref.max(e.qi).max(e.qo);
            evals[j] = e;
        }
        self.hold_prescribed_ring(&mut ring);
        for v in ring.iter() {
            max_r = if v.is_finite() { max_r.max(v.abs()) } else { f64::INFINITY };
            merit += v * v;
        }
        if !merit.is_finite() {
            merit = f64::INFINITY;
        }
        (max_r, merit, f_ref, ring)
    }

    /// Newton step of the skew model (central-difference blocks, Schur complement on the cone).
    #[allow(clippy::too_many_arguments)]
    fn skew_step(
        &self,
        x: &[f64],
        evals: &[SkewEval],
        ring: &Vector3<f64>,
        inputs: &Inputs,
        fc: f64,
        m_fc: f64,
        m_req: f64,
        step: &mut [f64],
        freeze: bool,
    ) -> bool {
        let g = &self.geometry;
        let z = g.z;
        let h = 1e-10;
        let sk = self.skew.as_ref().expect("skew model");
        let mut blocks = vec![Blocks::default(); z];
        let mut schur = Matrix3::<f64>::zeros();
        let mut rhs = -ring;
        for j in 0..z {
            let st = self.setup[j];
            let t = Matrix2x3::new(1.0, 0.0, 0.0, 0.0, st.cos_psi, st.sin_psi);
            let b0 = 3 + PER * j;
            let q0 = [x[b0], x[b0 + 1], x[b0 + 2], x[b0 + 3]];
            let c0 = [x[0], x[1] * st.cos_psi + x[2] * st.sin_psi];
            // Jacobian of (r, f_cone) w.r.t. (q, c_local): 6 x 6 by central differences.
            let mut jac = SMatrix::<f64, 6, 6>::zeros();
            for col in 0..6 {
                let (mut qp, mut qm, mut cp, mut cm) = (q0, q0, c0, c0);
                let (ep, em, width) = if col == 3 {
                    // One-sided, on the current branch of the complementarity kink.
                    let zeta = q0[3] / self.ls;
                    let out_dir = if zeta < 0.0 { -1.0 } else { 1.0 };
                    let dir = if zeta.abs() >= sk.phi_max { out_dir } else { -out_dir };
                    qp[3] += dir * h;
                    (
                        self.eval_skew(j, cp, qp, inputs.relative_speed(), fc, m_fc, m_req),
                        evals[j],
                        dir * h,
                    )
                } else {
                    if col < 4 {
                        qp[col] += h;
                        qm[col] -= h;
                    } else {
                        cp[col - 4] += h;
                        cm[col - 4] -= h;
                    }
                    (
                        self.eval_skew(j, cp, qp, inputs.relative_speed(), fc, m_fc, m_req),
                        self.eval_skew(j, cm, qm, inputs.relative_speed(), fc, m_fc, m_req),
                        2.0 * h,
                    )
                };
                for row in 0..4 {
                    jac[(row, col)] = (ep.r[row] - em.r[row]) / width;
                }
                for row in 0..2 {
                    jac[(4 + row, col)] = (ep.f_cone[row] - em.f_cone[row]) / width;
                }
            }
            let mut a: Matrix4<f64> = jac.fixed_view::<4, 4>(0, 0).into_owned();
            a -= Matrix4::identity() * self.regularisation;
            if freeze {
                // zeta is solved per roller beforehand (`settle_skew`): held here.
                a.set_row(3, &Vector4::zeros().transpose());
                a[(3, 3)] = -1.0;
            }
            if !g.axial {
                a.set_row(0, &Vector4::zeros().transpose());
                a.set_column(0, &Vector4::zeros());
                a[(0, 0)] = -1.0;
            }
            let Some(a_inv) = a.try_inverse() else { return false };
            let mut b_loc = jac.fixed_view::<4, 2>(0, 4).into_owned();
            if freeze {
                b_loc.set_row(3, &nalgebra::RowVector2::zeros());
            }
            let mut c_loc = jac.fixed_view::<2, 4>(4, 0).into_owned();
            if !g.axial {
                b_loc.set_row(0, &nalgebra::RowVector2::zeros());
                c_loc.set_column(0, &Vector2::zeros());
            }
            let d_loc = jac.fixed_view::<2, 2>(4, 4).into_owned();
            let b = b_loc * t; // 4x3
            let c = t.transpose() * c_loc; // 3x4
            let d = t.transpose() * d_loc * t;
            let mut r = evals[j].r;
            if freeze {
                r[3] = 0.0;
            }
            schur += d - c * a_inv * b;
            rhs += c * a_inv * r;
            blocks[j] = Blocks { a_inv, b };
        }
        schur -= Matrix3::identity() * (self.regularisation * z as f64);
        super::hold_prescribed(&mut schur, &mut rhs, &self.prescribed);
        let Some(s_inv) = schur.try_inverse() else { return false };
        let dc = s_inv * rhs;
        step[..3].copy_from_slice(dc.as_slice());
        for j in 0..z {
            let bl = &blocks[j];
            let mut r = evals[j].r;
            if freeze {
                r[3] = 0.0;
            }
            let dq = bl.a_inv * (-r - bl.b * dc);
            let b0 = 3 + PER * j;
            for c in 0..PER {
                step[b0 + c] = dq[c];
            }
            if !g.axial {
                step[b0] = 0.0;
            }
            // Clamp the in-plane part like the in-plane solver, the skew part to 0.1 rad.
            let largest = dq.fixed_rows::<3>(0).amax();
            if !(largest.is_finite() && dq[3].is_finite()) {
                return false;
            }
            let mut limit = self.max_step;
            if evals[j].gap > 0.0 {
                limit = limit.min(evals[j].gap + 1e-9);
            }
            if largest > limit {
                for c in 0..3 {
                    step[b0 + c] *= limit / largest;
                }
            }
            if freeze {
                step[b0 + 3] = 0.0;
            } else {
                let zlim = 0.1 * sk.phi_max.max(1e-3) * self.ls;
                step[b0 + 3] = step[b0 + 3].clamp(-zlim, zlim);
            }
        }
        let largest = dc.amax();
        if !largest.is_finite() {
            return false;
        }
        if largest > self.max_step {
            for s in step[..3].iter_mut() {
                *s *= self.max_step / largest;
            }
        }
        true
    }

    /// Solve each roller's skew moment balance for zeta with everything else held
    /// (nonlinear block Gauss-Seidel step): bracketing, then Illinois regula falsi. The
    /// balance is monotone in zeta (restoring flange lever, pocket force).
    fn settle_skew(&self, x: &mut [f64], inputs: &Inputs, fc: f64, m_fc: f64, m_req: f64) {
        let sk = self.skew.as_ref().expect("skew model");
        let ls = self.ls;
        for j in 0..self.geometry.z {
            let st = self.setup[j];
            let b0 = 3 + PER * j;
            let c = [x[0], x[1] * st.cos_psi + x[2] * st.sin_psi];
            let f = |zeta: f64| {
                let e = self.eval_skew(
                    j,
                    c,
                    [x[b0], x[b0 + 1], x[b0 + 2], zeta * ls],
                    inputs.relative_speed(),
                    fc,
                    m_fc,
                    m_req,
                );
                e.r[3]
            };
            let z0 = x[b0 + 3] / ls;
            let f0 = f(z0);
            if f0 == 0.0 || !f0.is_finite() {
                continue;
            }
            // The residual falls with zeta: bracket towards the sign of f0.
            let dir = f0.signum();
            let mut width = 0.25 * sk.phi_max.max(1e-4);
            let (mut a, mut fa) = (z0, f0);
            let (mut b, mut fb) = (z0 + dir * width, f(z0 + dir * width));
            let mut tries = 0;
            while fb.signum() == fa.signum() && tries < 60 {
                a = b;
                fa = fb;
                width *= 2.0;
                b = a + dir * width;
                fb = f(b);
                tries += 1;
            }
            if fb.signum() == fa.signum() {
                continue;
            }
            let mut side = 0;
            let mut m = b;
            for _ in 0..100 {
                m = (a * fb - b * fa) / (fb - fa);
                let fm = f(m);
                if fm == 0.0 || (b - a).abs() < 1e-15 {
                    break;
                }
                if fm.signum() == fb.signum() {
                    b = m;
                    fb = fm;
                    if side == -1 {
                        fa *= 0.5;
                    }
                    side = -1;
                } else {
                    a = m;
                    fa = fm;
                    if side == 1 {
                        fb *= 0.5;
                    }
                    side = 1;
                }
            }
            x[b0 + 3] = m * ls;
        }
    }

    /// Solve the skew model: the in-plane equilibrium first (cold start), then Newton on all
    /// 3 + 4Z unknowns. `warm` holds the previous skew solution and its cage angle.
    pub(super) fn solve_skew(
        &mut self,
        inputs: &Inputs,
        cage_angle: f64,
        warm: &mut Vec<f64>,
        out: &mut Outputs,
    ) -> Result<SolveReport, ModelError> {
        let z = self.geometry.z;
        let n = 3 + PER * z;
        let mut x = if warm.len() == n + 1 {
            self.prepare(inputs, cage_angle);
            warm[..n].to_vec()
        } else {
            // In-plane solution as the start (skew 0).
            let mut plane = Vec::new();
            self.solve_in_plane(inputs, cage_angle, &mut plane, out)?;
            let mut x = vec![0.0; n];
            x[..3].copy_from_slice(&plane[..3]);
            for j in 0..z {
                for c in 0..3 {
                    x[3 + PER * j + c] = plane[3 + 3 * j + c];
                }
            }
            x
        };
        for (c, v) in self.prescribed.iter().enumerate() {
            if let Some(v) = v {
                x[c] = *v;
            }
        }
        let (fc, m_fc, m_req) = self.inertial_loads(inputs);
        let tol = (self.params.tolerance * 1e-3).clamp(1e-13, 1e-9);
        let mut evals = vec![SkewEval::default(); z];
        let mut step = vec![0.0; n];
        let mut trial = vec![0.0; n];
        let (mut max_r, mut merit, mut f_ref, mut ring) = self.evaluate_skew(&x, &mut evals, inputs, fc, m_fc, m_req);
        let mut iterations = 0;
        let mut history = [0.0_f64; 4];
        let mut full_failed = false;
        let converged = loop {
            if max_r <= tol * f_ref {
                break true;
            }
            if iterations >= MAX_ITERATIONS {
                // Within 1e3 x the tolerance, as the in-plane solver accepts a stall.
                break max_r <= 1e3 * tol * f_ref;
            }
            // Far from the solution (or after a full step failed): settle the skew per roller,
            // then a Newton step of the in-plane unknowns (zeta held); close to it, full Newton
            // for quadratic convergence.
            let freeze = max_r > 1e-8 * f_ref || full_failed;
            if freeze {
                self.settle_skew(&mut x, inputs, fc, m_fc, m_req);
                (max_r, merit, f_ref, ring) = self.evaluate_skew(&x, &mut evals, inputs, fc, m_fc, m_req);
                if max_r <= tol * f_ref {
                    break true;
                }
            }
            if !self.skew_step(&x, &evals, &ring, inputs, fc, m_fc, m_req, &mut step, freeze) {
                break false;
            }
            iterations += 1;
            history[iterations as usize % history.len()] = merit;
            let allowed = 10.0 * history.iter().fold(0.0_f64, |m, h| m.max(*h));
            let mut alpha = 1.0;
            let mut accepted = false;
            let mut trial_evals = evals.clone();
            for _ in 0..12 {
                for i in 0..n {
                    trial[i] = x[i] + alpha * step[i];
                }
                let (mr, me, fr, rg) = self.evaluate_skew(&trial, &mut trial_evals, inputs, fc, m_fc, m_req);
                if me < merit || (me < allowed && alpha == 1.0) || alpha < 1e-3 {
                    x.copy_from_slice(&trial);
                    evals.copy_from_slice(&trial_evals);
                    (max_r, merit, f_ref, ring) = (mr, me, fr, rg);
                    accepted = true;
                    break;
                }
                alpha *= 0.5;
            }
            if !accepted {
                break false;
            }
            full_failed = !freeze && alpha < 1e-3;
            // As the in-plane solver: a stalled line search within 1e3 x the tolerance is
            // converged (finite-difference blocks, kinks of the contact and pocket laws).
            if alpha < 1e-3 && freeze && max_r <= 1e3 * tol * f_ref {
                break true;
            }
        };
        if !converged {
            // the warm start stays as it was: a failed solve changes no state
            return Err(ModelError::NoEquilibrium {
                message: format!(
                    "skew model: Newton solver stopped after {iterations} iterations with relative residual {:.3e} (mu = {}, pocket clearance = {} m)",
                    max_r / f_ref,
                    self.params.mu,
                    self.params.pocket_clearance
                ),
            });
        }
        let report = SolveReport {
            iterations,
            residual: max_r / f_ref,
            contact_law_extrapolated: false,
            ..SolveReport::default()
        };
        self.write_skew_outputs(&x, &evals, inputs, report, out);
        crate::model::load_within_range(out, &report)?;
        x.push(cage_angle);
        *warm = x;
        Ok(report)
    }

    fn write_skew_outputs(&mut self, x: &[f64], evals: &[SkewEval], inputs: &Inputs, report: SolveReport, out: &mut Outputs) {
        let mut slice_loads = std::mem::take(&mut self.slice_load_buffer);
        let g = &self.geometry;
        let sk = self.skew.as_ref().expect("skew model");
        let z = g.z;
        let ns = g.slices;
        // The rolling and sliding speeds follow the cone's speed relative to the cup.
        let speed = inputs.relative_speed();
        let mu = self.params.mu;
        let mu_rib = self.params.rib_mu();
        let (mut my, mut mz, mut fx, mut fy, mut fz) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let (mut h_race, mut h_flange, mut h_cage) = (0.0, 0.0, 0.0);
        let (mut m_cone, mut m_cup) = (0.0, 0.0);
        let e_prime = g.e_prime;
        for j in 0..z {
            let e = &evals[j];
            let st = &self.setup[j];
            my += st.sin_psi * e.m_cone;
            mz -= st.cos_psi * e.m_cone;
            fx -= e.f_cone[0];
            fy -= e.f_cone[1] * st.cos_psi;
            fz -= e.f_cone[1] * st.sin_psi;
            let b0 = 3 + PER * j;
            out.qi[j] = e.qi;
            out.qo[j] = e.qo;
            out.qf[j] = e.qf;
            out.qc[j] = e.qc;
            out.tilt[j] = x[b0 + 2] / self.ls;
            out.skew[j] = e.phi;
            out.nit[j] = e.nit;
            out.not[j] = e.not;
            out.nft[j] = e.nft;
            out.nis[j] = e.nis;
            out.nos[j] = e.nos;
            out.nfs[j] = e.nfs;
            // Slice loads at the solution, for the microslip power and the ring torques.
            let (cone_loads, cup_loads) = slice_loads[2 * ns * j..2 * ns * (j + 1)].split_at_mut(ns);
            self.skew_slice_loads(x, j, cone_loads, cup_loads);
            let mut sliding = 0.0;
            for (sl, loads, is_cone) in [(&sk.cone, &*cone_loads, true), (&sk.cup, &*cup_loads, false)] {
                let mut traction = 0.0;
                for k in 0..g.slices {
                    let q = loads[k];
                    if q <= 0.0 {
                        continue;
                    }
                    let v_k = speed * sl.slide[k];
                    let v_roll = speed.abs() * sl.rolling[k];
                    let (b, _) = line_contact_half_width(q / g.slice_len, sl.r_bar[k], e_prime);
                    // Microslip along the direction of motion of the ring (cone +e_t, cup -e_t).
                    let micro = -sl.thrust_sign * speed * sl.rolling[k] * sl.microslip[k] * b * b;
                    // the thrust of Eq. (7), mu q |sin phi| along the raceway, against the skewed
                    // roller's axial sliding v_roll |sin phi|: its power, consistent with the
                    // force the model applies (the rolling-direction microslip carries the rest)
                    let v_axial = v_roll * libm::sin(e.phi).abs();
                    h_race += q * (microslip_power(mu, v_k, micro, sk.u0) + dry_mu(mu, v_axial).abs() * libm::sin(e.phi).abs() * v_axial);
                    traction += q * dry_mu(mu, v_k);
                    let ring_force = q * dry_mu(mu, v_k);
                    if is_cone {
                        m_cone -= ring_force * sl.ring_radius[k];
                    } else {
                        m_cup += ring_force * sl.ring_radius[k];
                    }
                }
                sliding += traction.abs();
            }
            if e.qf > 0.0 {
                let v_f = speed * sk.flange_slide;
                let f = dry_mu(mu_rib, v_f) * e.qf;
                h_flange += f * v_f;
                m_cone -= f * sk.rib_radius;
                sliding += f.abs();
            }
            if e.qc > 0.0 {
                let w = speed * sk.spin;
                let (rl, rs) = sk.end_radii;
                // mu F_c at each corner, sliding at the roller surface speed there.
                h_cage += e.qc * (dry_mu(mu, w * rl) * w * rl + dry_mu(mu, w * rs) * w * rs);
                sliding += e.qc * (dry_mu(mu, w * rl).abs() + dry_mu(mu, w * rs).abs());
            }
            out.sliding_friction[j] = sliding;
        }
        out.cone_x = x[0];
        out.cone_y = x[1];
        out.cone_z = x[2];
        out.reaction_fx = if g.axial { fx } else { 0.0 };
        out.reaction_my = my;
        out.reaction_mz = mz;
        out.cage_speed = self.cage_speed(inputs);
        out.solver_iterations = report.iterations as i32;
        out.solver_residual = report.residual;
        // T = H / omega, with the sign of speed (zero at standstill: dry friction fades there).
        let to_torque = |h: f64| if speed != 0.0 { h / speed } else { 0.0 };
        out.friction_torque_raceway = to_torque(h_race);
        out.friction_torque_flange = to_torque(h_flange);
        out.friction_torque_cage = to_torque(h_cage);
        out.friction_torque = out.friction_torque_raceway + out.friction_torque_flange + out.friction_torque_cage;
        out.friction_torque_cone = m_cone;
        out.friction_torque_cup = m_cup;
        out.power_loss = out.friction_torque * speed;
        self.slice_load_buffer = slice_loads;
        self.write_reactions_and_lives(fy, fz, z, inputs, out);
        out.summarize();
    }

    /// Slice loads of roller `j` at the skew solution `x`.
    fn skew_slice_loads(&self, x: &[f64], j: usize, cone: &mut [f64], cup: &mut [f64]) {
        let g = &self.geometry;
        let sk = self.skew.as_ref().expect("skew model");
        let st = &self.setup[j];
        let b0 = 3 + PER * j;
        let theta = x[b0 + 2] / self.ls;
        let (phi, _) = sk.split(x[b0 + 3] / self.ls);
        let dr = x[1] * st.cos_psi + x[2] * st.sin_psi;
        let (a, rho) = (x[b0], x[b0 + 1]);
        let ni = g.cone.normal;
        let no = g.cup.normal;
        let base_i = (x[0] - a) * ni[0] + (dr - rho) * ni[1] + st.gap_cone;
        let base_o = -(a * no[0] + rho * no[1]) + st.gap_cup;
        let (cone_crown, cup_crown) = (&self.cone_table_of(j).crown, &self.cup_table_of(j).crown);
        for k in 0..g.slices {
            let di = base_i + st.gamma * self.cone_chi[k] - theta * g.cone.lever[k] - cone_crown[k] + sk.cone.shift[k] * phi * phi;
            cone[k] = g.cone.law.load(k, di).0;
            let d_o = base_o - theta * g.cup.lever[k] - cup_crown[k] + sk.cup.shift[k] * phi * phi;
            cup[k] = g.cup.law.load(k, d_o).0;
        }
    }
}

/// Friction power per unit load of one slice (W/N) in the rolling direction [D19, Eq. (10)]:
/// Coulomb mu under the semi-elliptical Hertz pressure across the contact width, sliding speed
/// v(u) = v_k + micro (u^2 - u0^2) (kinematic sliding plus the free-rolling microslip);
/// Simpson's rule over u = y/b in [-1, 1].
pub(super) fn microslip_power(mu: f64, v_k: f64, micro: f64, u0: f64) -> f64 {
    let n = SIMPSON;
    let du = 2.0 / n as f64;
    let mut sum = 0.0;
    for i in 0..=n {
        let u: f64 = -1.0 + i as f64 * du;
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let v = v_k + micro * (u * u - u0 * u0);
        let speed = v.abs();
        let p = (2.0 / std::f64::consts::PI) * (1.0 - u * u).max(0.0).sqrt();
        sum += w * p * dry_mu(mu, speed) * speed;
    }
    sum * du / 3.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Lubrication, Parameters, Preload};
    use crate::quasi_static::studies::rpm;

    /// The [D19] case (32018X, dry, Fr = 35 kN, pocket 0.9 mm) at `mu` and `speed_rpm`, force
    /// preload 12,970 N or displacement preload 0.01 mm: the model, its inputs, the solution
    /// vector and the outputs.
    fn d19_solved(mu: f64, force: bool, speed_rpm: f64) -> (QuasiStatic, Inputs, Vec<f64>, Outputs) {
        let b = Bearing::preset("32018X").unwrap();
        let mut p = Parameters::from_bearing(&b);
        let mut i = Inputs::from_bearing(&b);
        p.skew_model = true;
        p.lubrication = Lubrication::Dry;
        p.mu = mu;
        p.pocket_clearance = 0.9e-3;
        i.speed = rpm(speed_rpm);
        i.fy = 35_000.0;
        i.fz = 0.0;
        if force {
            p.preload = Preload::Force;
            i.fx = 12_970.0;
        } else {
            p.preload = Preload::Displacement;
            i.axial_displacement = 0.01e-3;
        }
        let mut qs = QuasiStatic::new(&b, &p).unwrap();
        let mut out = Outputs::new(b.roller_count);
        let mut x = Vec::new();
        qs.solve(&i, 0.0, &mut x, &mut out).unwrap();
        (qs, i, x, out)
    }

    /// The load the shaft applies to the cone (Fx, Fy, Fz, My, Mz), rebuilt independently of
    /// the solver's roller evaluation: per roller and slice the cone contact force -q n_i at
    /// the slice's contact point, plus the friction thrust mu q |sin phi| along the cone's
    /// generatrix (Coulomb: tangent to the raceway) in the sense of the roller's axial sliding
    /// on the cone, taken from 3-D rigid-body kinematics (roller centre fixed in the cage
    /// frame, cone turning at omega_c about x, roller spinning about its skewed axis a', which
    /// adds nothing along a'); plus the rib contact force -Q_f n_f.
    fn cone_load_rebuilt(qs: &QuasiStatic, i: &Inputs, x: &[f64], out: &Outputs) -> [f64; 5] {
        let g = &qs.geometry;
        let mu = qs.params.mu;
        let omega_c = i.speed - qs.cage_speed(i);
        let gen = [g.cone_angle.cos(), -g.cone_angle.sin()];
        let n = g.cone.normal;
        let (mut cone, mut cup) = (vec![0.0; g.slices], vec![0.0; g.slices]);
        let mut load = [0.0; 5];
        for j in 0..g.z {
            qs.skew_slice_loads(x, j, &mut cone, &mut cup);
            let phi = out.skew[j];
            // Skewed roller axis in (x, r, t): the small end moves towards -t for phi > 0.
            let a = [g.axis[0] * phi.cos(), g.axis[1] * phi.cos(), -phi.sin()];
            let (mut fx, mut fr, mut m) = (0.0, 0.0, 0.0);
            for k in 0..g.slices {
                let q = cone[k];
                let p = g.cone.point[k];
                let t = g.slice_s[k] * a[2];
                // Cone surface velocity omega_c e_x x (x, r, t) = omega_c (0, -t, r).
                let v_cone = [0.0, -omega_c * t, omega_c * p[1]];
                let slide = -(v_cone[0] * a[0] + v_cone[1] * a[1] + v_cone[2] * a[2]);
                // Friction on the cone along the roller's sliding on it.
                let thrust = slide.signum() * mu * q * phi.sin().abs();
                let f = [-q * n[0] + thrust * gen[0], -q * n[1] + thrust * gen[1]];
                fx += f[0];
                fr += f[1];
                m += cross(p, f);
            }
            if let Some(fl) = &g.flange {
                let f = [-out.qf[j] * fl.normal[0], -out.qf[j] * fl.normal[1]];
                fx += f[0];
                fr += f[1];
                m += cross(fl.point, f);
            }
            let psi = std::f64::consts::TAU * j as f64 / g.z as f64;
            load[0] -= fx;
            load[1] -= fr * psi.cos();
            load[2] -= fr * psi.sin();
            load[3] += psi.sin() * m;
            load[4] -= psi.cos() * m;
        }
        load
    }

    #[test]
    fn cone_equilibrium_rebuilt_from_slices_with_the_kinematic_thrust() {
        // mu = 0.3: skew below the pocket limit; mu = 0.5: at the limit, pocket contact. Both
        // senses of rotation (the skew reverses, the thrust on the cone does not).
        for (mu, force, rpm_) in [(0.3, true, 60.0), (0.5, true, 60.0), (0.5, true, -60.0), (0.5, false, 60.0)] {
            let (qs, i, x, out) = d19_solved(mu, force, rpm_);
            let rebuilt = cone_load_rebuilt(&qs, &i, &x, &out);
            let fx = if force { i.fx } else { out.reaction_fx };
            let expected = [fx, i.fy, i.fz, out.reaction_my, out.reaction_mz];
            let tol = [0.05, 0.05, 0.05, 0.05 * 0.06, 0.05 * 0.06];
            for c in 0..5 {
                assert!(
                    (rebuilt[c] - expected[c]).abs() <= tol[c],
                    "mu {mu}, force {force}, {rpm_} rpm, component {c}: rebuilt {} solver {}",
                    rebuilt[c],
                    expected[c]
                );
            }
            // The skew follows the sense of rotation (the rib drags the large end along).
            assert!(out.skew.iter().all(|s| *s * rpm_ > 0.0), "{:?}", out.skew);
        }
    }
}
