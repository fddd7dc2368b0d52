//! The bearing's tangent stiffness about a quasi-static solution: d(reaction_i)/d(q_j) with
//! q = (x, y, z, xi, zeta) the cone's translations and tilts relative to the cup, every roller
//! re-equilibrated (the rollers' unknowns condensed out of the Newton Jacobian by its Schur
//! complement: the static condensation of the load-distribution methods of Harris & Kotzalas,
//! "Rolling Bearing Analysis" 5th ed., vol. 2 ch. 1, and of Lim & Singh's bearing stiffness
//! matrix, J. Sound Vib. 139(2), 1990, here with the model's own sliced contacts).
//!
//! Per roller j, with its local cone coordinates l = (dx, dr, gamma) = T_j q (gamma = zeta
//! cos psi - xi sin psi, the cone's tilt in the roller's axial plane):
//! - the roller residual r(u, l) (force and moment balance of the roller, unknowns
//!   u = (a, rho, theta L_s)) with A = dr/du, B = dr/dl;
//! - the roller's generalised force on the cone F = (f_x, f_r, m) with D = dF/dl and
//!   dF/du = B^T (the contacts are conservative: every term is k g h^T of a slice's stiffness
//!   k and its interference's gradients g, h);
//! - at equilibrium r = 0, so du/dl = -A^-1 B and dF/dl|_(r = 0) = D - B^T A^-1 B.
//!
//! The reactions R = -sum_j T_j^T F_j (the load the bearing carries, as the outputs define
//! them), so K = dR/dq = -sum_j T_j^T (D_j - B_j^T A_j^-1 B_j) T_j. The centrifugal force and
//! gyroscopic moment do not depend on the displacements and drop out.

use super::{QuasiStatic, RollerEval};
use nalgebra::{Matrix3, SMatrix, Vector3};

/// 3 x 5 map from the cone's global coordinates (x, y, z, xi, zeta) to a roller's local ones.
fn local_map(cos_psi: f64, sin_psi: f64) -> SMatrix<f64, 3, 5> {
    let mut t = SMatrix::<f64, 3, 5>::zeros();
    t[(0, 0)] = 1.0;
    t[(1, 1)] = cos_psi;
    t[(1, 2)] = sin_psi;
    t[(2, 3)] = -sin_psi;
    t[(2, 4)] = cos_psi;
    t
}

impl QuasiStatic {
    /// Tangent stiffness (row-major 5 x 5, reactions by (x, y, z, xi, zeta)) at the solution
    /// `x` whose roller evaluations are in `self.evals` (in-plane model).
    pub(super) fn tangent_stiffness(&self, x: &[f64]) -> [f64; 25] {
        let g = &self.geometry;
        let mut k5 = SMatrix::<f64, 5, 5>::zeros();
        let reg = Matrix3::identity() * self.regularisation;
        for j in 0..g.z {
            let e = &self.evals[j];
            let st = &self.setup[j];
            let (bl, dl) = self.gamma_blocks(x, j, e);
            let mut a = e.a - reg;
            let mut bl = bl;
            if !g.axial {
                a[(0, 0)] = -1.0;
                bl.set_row(0, &nalgebra::RowVector3::zeros());
            }
            let Some(a_inv) = a.try_inverse() else { continue };
            let condensed = dl - bl.transpose() * a_inv * bl;
            let t = local_map(st.cos_psi, st.sin_psi);
            k5 -= t.transpose() * condensed * t;
        }
        if !g.axial {
            // no axial stiffness: the axial reaction is held at zero
            k5.set_row(0, &SMatrix::<f64, 1, 5>::zeros());
        }
        let mut out = [0.0; 25];
        for i in 0..5 {
            for c in 0..5 {
                out[5 * i + c] = k5[(i, c)];
            }
        }
        out
    }

    /// chi_k = cross(P_k, n) of the cone's slices as alpha + beta lever_k (both are affine in
    /// the slice station along the roller axis), from the end slices.
    pub(super) fn chi_fit(chi: &[f64], lever: &[f64]) -> (f64, f64) {
        let n = chi.len();
        let span = if n >= 2 { lever[n - 1] - lever[0] } else { 0.0 };
        if span == 0.0 {
            let mean = chi.iter().sum::<f64>() / n as f64;
            return (mean, 0.0);
        }
        let beta = (chi[n - 1] - chi[0]) / span;
        (chi[0] - beta * lever[0], beta)
    }

    /// B = dr/d(dx, dr, gamma) (3 x 3) and D = dF/d(dx, dr, gamma) (3 x 3) of roller `j` at
    /// `x`: the (dx, dr) columns from its evaluation, the gamma column from the slice
    /// stiffnesses of its cone line and flange contact (gamma moves slice k by chi_k).
    fn gamma_blocks(&self, x: &[f64], j: usize, e: &RollerEval) -> (Matrix3<f64>, Matrix3<f64>) {
        let g = &self.geometry;
        let st = &self.setup[j];
        let ls = self.ls;
        let theta = x[5 + 3 * j] / ls;
        let (a_roller, rho) = (x[3 + 3 * j], x[4 + 3 * j]);
        let dr = x[1] * st.cos_psi + x[2] * st.sin_psi;
        let ni = g.cone.normal;
        debug_assert!(self.cone_chi.len() == g.slices);
        // sums over the cone's slices: k chi, k chi lever / L_s, k chi^2, from the solve's own
        // slice sums (chi_k = alpha + beta lever_k: both are affine in the slice station)
        let (alpha, beta) = self.cone_chi_fit;
        let s = &e.cone;
        let bl = beta * ls;
        let k_chi = alpha * s.k + bl * s.k_lever;
        let k_chi_lever = alpha * s.k_lever + bl * s.k_lever2;
        let k_chi2 = alpha * alpha * s.k + 2.0 * alpha * bl * s.k_lever + bl * bl * s.k_lever2;
        // r = sum q g with g = (n_x, n_r, lever / L_s): dr/dgamma = sum k g chi
        let mut b_gamma = Vector3::new(ni[0] * k_chi, ni[1] * k_chi, k_chi_lever);
        // F = -sum q (n_x, n_r, chi): dF/dgamma = -sum k (n_x, n_r, chi) chi
        let mut d_gamma = Vector3::new(-ni[0] * k_chi, -ni[1] * k_chi, -k_chi2);
        if let Some(f) = &g.flange {
            let n = f.normal;
            let chi = self.flange_chi;
            let delta = (x[0] - a_roller) * n[0] + (dr - rho) * n[1] + st.gamma * chi - theta * f.lever;
            let (qf, kf) = f.hertz.load(delta);
            if qf > 0.0 {
                b_gamma += Vector3::new(n[0], n[1], f.lever / ls) * (kf * chi);
                d_gamma -= Vector3::new(n[0], n[1], chi) * (kf * chi);
            }
        }
        let mut b = Matrix3::zeros();
        b.fixed_view_mut::<3, 2>(0, 0).copy_from(&e.b);
        b.set_column(2, &b_gamma);
        let mut d = Matrix3::zeros();
        d.fixed_view_mut::<2, 2>(0, 0).copy_from(&e.d);
        d.set_column(2, &d_gamma);
        d.set_row(2, &d_gamma.transpose());
        (b, d)
    }
}

/// Steps of the skew model's central differences: translations 2 nm, tilts 0.2 µrad. They
/// are about 1e-4 of the elastic approach of a loaded roller (10–50 µm) and of the tilts
/// that load a roller's edge (1–5 mrad), so the truncation error (of relative order h^2 over
/// those scales, 1e-8) stays far below the 1e-3 the stiffness is checked to, and the change
/// of the reactions (K h, 1–100 N) stays far above the solver's residual (1e-9 of the load).
const SKEW_STEP_TRANSLATION: f64 = 2e-9;
const SKEW_STEP_TILT: f64 = 2e-7;

/// The quasi-static model in displacement causality, solved from a cold start at a given cone
/// position: the stiffness of a state the solver of the outputs did not produce in
/// displacement causality (the dynamic model's current state, the skew model's solution).
/// A cold start makes the result a function of its inputs alone, so a restored FMU state
/// gives the same bits.
///
/// - In-plane (the dynamic model): the analytic condensation above, with the rollers
///   re-equilibrated quasi-statically at the dynamic cone position.
/// - With the skew model: central differences of the skew model's own five reactions, ten
///   skew solves warm-started from the solve at the cone position. The analytic condensation
///   of the in-plane contacts misses what skew does to the load distribution (1.6e-3 of the
///   matrix on [D19]'s dry 32018X), and the skew solve has no condensed Jacobian of its own.
#[derive(Debug, Clone)]
pub struct Linearisation {
    qs: QuasiStatic,
    out: crate::model::Outputs,
    warm: Vec<f64>,
    /// The skew solve at the cone position, every difference's warm start.
    centre: Vec<f64>,
}

impl Linearisation {
    /// The in-plane linearisation (the skew model off whatever `params` say).
    pub fn new(bearing: &crate::bearing::Bearing, params: &crate::model::Parameters) -> Result<Linearisation, crate::model::ModelError> {
        Self::with_skew(bearing, params, false)
    }

    /// The skew model's stiffness by differences of its reactions.
    pub fn of_skew_model(
        bearing: &crate::bearing::Bearing,
        params: &crate::model::Parameters,
    ) -> Result<Linearisation, crate::model::ModelError> {
        Self::with_skew(bearing, params, true)
    }

    fn with_skew(
        bearing: &crate::bearing::Bearing,
        params: &crate::model::Parameters,
        skew: bool,
    ) -> Result<Linearisation, crate::model::ModelError> {
        let mut p = params.clone();
        p.causality = crate::model::LoadCausality::Displacement;
        p.fidelity = crate::model::Fidelity::QuasiStatic;
        p.skew_model = skew;
        Ok(Linearisation {
            qs: QuasiStatic::new(bearing, &p)?,
            out: crate::model::Outputs::new(bearing.roller_count),
            warm: Vec::new(),
            centre: Vec::new(),
        })
    }

    /// The tangent stiffness with the cone at `cone` (x, y, z), the tilts, speed and the rest
    /// of `inputs`, roller 1 at `cage_angle`.
    pub fn stiffness(
        &mut self,
        inputs: &crate::model::Inputs,
        cone: [f64; 3],
        cage_angle: f64,
    ) -> Result<[f64; 25], crate::model::ModelError> {
        let at = crate::model::Inputs {
            displacement: cone,
            ..*inputs
        };
        self.warm.clear();
        self.qs.solve(&at, cage_angle, &mut self.warm, &mut self.out)?;
        if self.qs.skew.is_none() {
            return Ok(self.out.stiffness);
        }
        self.centre.clone_from(&self.warm);
        let mut k = [0.0; 25];
        for c in 0..5 {
            let h = if c < 3 { SKEW_STEP_TRANSLATION } else { SKEW_STEP_TILT };
            let mut sides = [[0.0; 5]; 2];
            for (side, sign) in [1.0, -1.0].into_iter().enumerate() {
                let mut moved = at;
                match c {
                    0..=2 => moved.displacement[c] += sign * h,
                    3 => moved.xi += sign * h,
                    _ => moved.zeta += sign * h,
                }
                self.warm.clone_from(&self.centre);
                self.qs.solve(&moved, cage_angle, &mut self.warm, &mut self.out)?;
                let o = &self.out;
                sides[side] = [o.reaction_fx, o.reaction_fy, o.reaction_fz, o.reaction_my, o.reaction_mz];
            }
            for i in 0..5 {
                k[5 * i + c] = (sides[0][i] - sides[1][i]) / (2.0 * h);
            }
        }
        Ok(k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bearing::Bearing;
    use crate::model::Parameters;

    #[test]
    fn the_cone_slices_chi_is_affine_in_their_lever() {
        for name in ["TRB130x230", "32018X", "32008", "CRB-TRILOBE"] {
            let b = Bearing::preset(name).unwrap();
            let qs = QuasiStatic::new(&b, &Parameters::from_bearing(&b)).unwrap();
            let (alpha, beta) = qs.cone_chi_fit;
            let scale = qs.cone_chi.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
            for (k, chi) in qs.cone_chi.iter().enumerate() {
                let fit = alpha + beta * qs.geometry.cone.lever[k];
                assert!((fit - chi).abs() <= 1e-12 * scale, "{name} slice {k}: {fit} vs {chi}");
            }
        }
    }
}
