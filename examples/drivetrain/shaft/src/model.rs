//! Quasi-static rigid shaft on two bearings, one Newton step per communication step.
//!
//! Physics. The shaft is rigid with five degrees of freedom q = (u, v, w, θY, θZ) at X = 0
//! (X the shaft axis; rotation about X is the drive's and not a DOF). A point of the axis at
//! X = s moves by (u, v + s θZ, w − s θY) and tilts by (θY, θZ).
//!
//! Bearing i sits at X = s_i; its own frame is the shaft frame (bearing A) or its mirror
//! image in the Y-Z plane (bearing B, the O arrangement: each bearing's x points into its
//! own loading direction). A reflection X → −X flips the polar vectors' x component and the
//! axial vectors' y and z components, so with σ = +1 (A) or −1 (B) the bearing's inputs are
//!
//!   d_i = T_i q + (δ/2, 0, 0, 0, 0),   T_i q = (σ u, v + s θZ, w − s θY, σ θY, σ θZ),
//!
//! δ the pair's axial preload interference. The bearing's reactions R_i (the load it carries,
//! work-conjugate to d_i: its stiffness K_i = ∂R_i/∂d_i is symmetric) act on the shaft as
//! the generalised force −T_iᵀ R_i (virtual work). The gear mesh force F = (Fa, Fr, Ft) r(t)
//! (1 + m sin 2πft) at the mesh point P = (g, ρ, 0) gives Q_F = (Fx, Fy, Fz, −g Fz, g Fy − ρ Fx).
//!
//! Equilibrium: Q_F − Σ T_iᵀ R_i(d_i) = 0. Every step the shaft takes one Newton step from
//! the state the bearing inputs belong to (q rebuilt from the bearings' echoed cone
//! displacements, so that the update is a true Newton step whatever the master's order):
//! q⁺ = q + ω K⁻¹ (Q_F(t + h) − Σ T_iᵀ R_i), K = Σ T_iᵀ K_i T_i, ω ≤ `relaxation` so that no
//! bearing input moves by more than `max_step` in one step (a trust region).

/// A 5-vector.
pub type V5 = [f64; 5];
/// A 5×5 matrix, row-major.
pub type M5 = [[f64; 5]; 5];

/// The shaft's parameters.
#[derive(Clone, Copy, Debug)]
pub struct Shaft {
    /// Axial positions of bearing A and B (m).
    pub pos: [f64; 2],
    /// Total axial preload interference δ (m), the thermal part included (`fmi.rs`).
    pub preload: f64,
    /// Axial position g and pitch radius ρ of the mesh point (m).
    pub mesh_pos: f64,
    pub mesh_radius: f64,
    /// Mean mesh force: axial, radial (+Y), tangential (+Z) (N).
    pub mesh_force: [f64; 3],
    /// Relative modulation amplitude and its frequency (Hz).
    pub modulation: f64,
    pub frequency: f64,
    /// Ramp time of the mesh force (s; 0 = none).
    pub ramp: f64,
    /// Fraction of the Newton step taken.
    pub relaxation: f64,
    /// Largest change per step of a bearing's translation (m) and tilt (rad): a trust region
    /// that keeps a step from a poor linearisation (an unloaded bearing's near-zero
    /// stiffness, e.g. when a master starts with zero inputs) inside the bearings' range.
    pub max_step: [f64; 2],
}

/// Mirror sign σ of bearing `i` (0 = A, 1 = B).
pub fn sigma(i: usize) -> f64 {
    if i == 0 {
        1.0
    } else {
        -1.0
    }
}

impl Shaft {
    /// T_i: bearing i's (x, y, z, ξ, ζ) from the shaft's q.
    pub fn t(&self, i: usize) -> M5 {
        let (s, sg) = (self.pos[i], sigma(i));
        [
            [sg, 0.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0, s],
            [0.0, 0.0, 1.0, -s, 0.0],
            [0.0, 0.0, 0.0, sg, 0.0],
            [0.0, 0.0, 0.0, 0.0, sg],
        ]
    }

    /// The inputs of bearing i for the shaft displacement q.
    pub fn bearing_input(&self, i: usize, q: &V5) -> V5 {
        let mut d = mat_vec(&self.t(i), q);
        d[0] += 0.5 * self.preload;
        d
    }

    /// The shaft's q from the bearings' translations (x, y, z) in their own frames: u the
    /// mean of the two axial ones, v, θZ from the y's and w, θY from the z's.
    pub fn q_from_cones(&self, cone: &[[f64; 3]; 2]) -> V5 {
        let [a, b] = self.pos;
        let u = 0.5 * (sigma(0) * (cone[0][0] - 0.5 * self.preload) + sigma(1) * (cone[1][0] - 0.5 * self.preload));
        let theta_z = (cone[1][1] - cone[0][1]) / (b - a);
        let v = cone[0][1] - a * theta_z;
        let theta_y = -(cone[1][2] - cone[0][2]) / (b - a);
        let w = cone[0][2] + a * theta_y;
        [u, v, w, theta_y, theta_z]
    }

    /// The mesh force (Fx, Fy, Fz) at time t.
    pub fn mesh_force(&self, t: f64) -> [f64; 3] {
        let ramp = if self.ramp > 0.0 { (t / self.ramp).clamp(0.0, 1.0) } else { 1.0 };
        let f = ramp * (1.0 + self.modulation * (2.0 * std::f64::consts::PI * self.frequency * t).sin());
        self.mesh_force.map(|c| c * f)
    }

    /// Generalised force Q_F of the mesh force at time t.
    pub fn applied(&self, t: f64) -> V5 {
        let [fx, fy, fz] = self.mesh_force(t);
        let (g, rho) = (self.mesh_pos, self.mesh_radius);
        [fx, fy, fz, -g * fz, g * fy - rho * fx]
    }

    /// Q_F − Σ T_iᵀ R_i: the equilibrium residual.
    pub fn residual(&self, t: f64, reactions: &[V5; 2]) -> V5 {
        let mut r = self.applied(t);
        for (i, reaction) in reactions.iter().enumerate() {
            let g = mat_t_vec(&self.t(i), reaction);
            for k in 0..5 {
                r[k] -= g[k];
            }
        }
        r
    }

    /// |residual| / |applied|, moments divided by the bearing span; without an applied load
    /// relative to the larger bearing reaction (the preload), absolute if there is none.
    pub fn relative(&self, residual: &V5, applied: &V5, reactions: &[V5; 2]) -> f64 {
        let span = (self.pos[1] - self.pos[0]).abs().max(f64::MIN_POSITIVE);
        let norm = |v: &V5| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + (v[3] / span).powi(2) + (v[4] / span).powi(2)).sqrt();
        let mut scale = norm(applied);
        if scale == 0.0 {
            scale = norm(&reactions[0]).max(norm(&reactions[1]));
        }
        if scale == 0.0 {
            scale = 1.0;
        }
        norm(residual) / scale
    }

    /// K = Σ T_iᵀ K_i T_i.
    pub fn stiffness(&self, k: &[M5; 2]) -> M5 {
        let mut out = [[0.0; 5]; 5];
        for (i, ki) in k.iter().enumerate() {
            let t = self.t(i);
            let kt = mat_mul(ki, &t);
            for r in 0..5 {
                for c in 0..5 {
                    out[r][c] += (0..5).map(|m| t[m][r] * kt[m][c]).sum::<f64>();
                }
            }
        }
        out
    }

    /// One Newton step from q towards the equilibrium with the load at time t_target. None
    /// when the assembled stiffness is singular or not finite (e.g. both bearings unloaded).
    pub fn newton(&self, q: &V5, t_target: f64, reactions: &[V5; 2], k: &[M5; 2]) -> Option<V5> {
        let r = self.residual(t_target, reactions);
        let dq = solve(self.stiffness(k), r)?;
        let mut factor = self.relaxation;
        for i in 0..2 {
            let dd = mat_vec(&self.t(i), &dq);
            let translation = dd[..3].iter().fold(0.0_f64, |a, x| a.max(x.abs()));
            let tilt = dd[3..].iter().fold(0.0_f64, |a, x| a.max(x.abs()));
            factor = factor.min(self.max_step[0] / translation).min(self.max_step[1] / tilt);
        }
        let mut out = *q;
        for m in 0..5 {
            out[m] += factor * dq[m];
        }
        Some(out)
    }
}

pub fn mat_vec(a: &M5, x: &V5) -> V5 {
    std::array::from_fn(|r| (0..5).map(|c| a[r][c] * x[c]).sum())
}

pub fn mat_t_vec(a: &M5, x: &V5) -> V5 {
    std::array::from_fn(|c| (0..5).map(|r| a[r][c] * x[r]).sum())
}

pub fn mat_mul(a: &M5, b: &M5) -> M5 {
    std::array::from_fn(|r| std::array::from_fn(|c| (0..5).map(|m| a[r][m] * b[m][c]).sum()))
}

/// Solve K x = r: symmetric diagonal scaling (N/m and N·m/rad differ by orders of magnitude)
/// then Gaussian elimination with partial pivoting.
pub fn solve(k: M5, r: V5) -> Option<V5> {
    let d: V5 = std::array::from_fn(|i| {
        let kii = k[i][i].abs();
        if kii > 0.0 && kii.is_finite() {
            1.0 / kii.sqrt()
        } else {
            1.0
        }
    });
    let mut a: M5 = std::array::from_fn(|i| std::array::from_fn(|j| d[i] * k[i][j] * d[j]));
    let mut b: V5 = std::array::from_fn(|i| d[i] * r[i]);
    if a.iter().flatten().chain(b.iter()).any(|x| !x.is_finite()) {
        return None;
    }
    for col in 0..5 {
        let p = (col..5).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[p][col].abs() < 1e-12 {
            return None;
        }
        a.swap(col, p);
        b.swap(col, p);
        for row in col + 1..5 {
            let f = a[row][col] / a[col][col];
            for c in col..5 {
                a[row][c] -= f * a[col][c];
            }
            b[row] -= f * b[col];
        }
    }
    let mut y = [0.0; 5];
    for row in (0..5).rev() {
        let s: f64 = (row + 1..5).map(|c| a[row][c] * y[c]).sum();
        y[row] = (b[row] - s) / a[row][row];
    }
    Some(std::array::from_fn(|i| d[i] * y[i]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shaft() -> Shaft {
        Shaft {
            pos: [-0.15, 0.15],
            preload: 40e-6,
            mesh_pos: 0.05,
            mesh_radius: 0.2,
            mesh_force: [5e3, 2e4, 4e4],
            modulation: 0.0,
            frequency: 1.0,
            ramp: 0.0,
            relaxation: 1.0,
            max_step: [1e-3, 1e-2],
        }
    }

    /// Two linear "bearings" R_i = K_i (d_i − d0): one Newton step lands on the equilibrium,
    /// and q is recovered from the cone translations.
    #[test]
    fn linear_bearings_converge_in_one_step() {
        let s = shaft();
        let mut k = [[[0.0; 5]; 5]; 2];
        for (i, ki) in k.iter_mut().enumerate() {
            let diag = [1.2e9, 8e9, 8e9, 7e6, 7e6];
            for m in 0..5 {
                ki[m][m] = diag[m] * (1.0 + 0.1 * i as f64);
            }
            ki[1][4] = -1.9e8;
            ki[4][1] = -1.9e8;
            ki[2][3] = 1.9e8;
            ki[3][2] = 1.9e8;
        }
        let reaction = |q: &V5| -> [V5; 2] { std::array::from_fn(|i| mat_vec(&k[i], &mat_vec(&s.t(i), q))) };
        let q0 = [0.0; 5];
        let q1 = s.newton(&q0, 0.0, &reaction(&q0), &k).unwrap();
        let r = s.residual(0.0, &reaction(&q1));
        assert!(s.relative(&r, &s.applied(0.0), &reaction(&q1)) < 1e-12, "{r:?}");
        let cones: [[f64; 3]; 2] = std::array::from_fn(|i| {
            let d = s.bearing_input(i, &q1);
            [d[0], d[1], d[2]]
        });
        let back = s.q_from_cones(&cones);
        for m in 0..5 {
            assert!((back[m] - q1[m]).abs() <= 1e-12 * q1[m].abs().max(1e-9), "{back:?} {q1:?}");
        }
    }

    /// The mirror: B's axial and tilt inputs have the opposite sign of A's for the same shaft
    /// motion, its translations y, z the same sign.
    #[test]
    fn mirror_signs() {
        let s = shaft();
        let q = [1e-6, 2e-6, 3e-6, 1e-4, 2e-4];
        let a = mat_vec(&s.t(0), &q);
        let b = mat_vec(&s.t(1), &q);
        assert_eq!(a[0], -b[0]);
        assert_eq!(a[3], -b[3]);
        assert_eq!(a[4], -b[4]);
        assert_eq!(a[1], 2e-6 - 0.15 * 2e-4);
        assert_eq!(b[1], 2e-6 + 0.15 * 2e-4);
    }

    /// A step larger than the trust region is scaled down as a whole (same direction).
    #[test]
    fn trust_region_limits_the_step() {
        let mut s = shaft();
        s.max_step = [1e-6, 1e-2];
        let mut k = [[[0.0; 5]; 5]; 2];
        for ki in k.iter_mut() {
            for m in 0..5 {
                ki[m][m] = 1e6;
            }
        }
        let q = s.newton(&[0.0; 5], 0.0, &[[0.0; 5]; 2], &k).unwrap();
        let largest = (0..2)
            .flat_map(|i| mat_vec(&s.t(i), &q)[..3].to_vec())
            .fold(0.0_f64, |a, x| a.max(x.abs()));
        assert!((largest - 1e-6).abs() < 1e-18, "{largest}");
    }

    #[test]
    fn singular_stiffness_is_none() {
        let s = shaft();
        assert!(s.newton(&[0.0; 5], 0.0, &[[0.0; 5]; 2], &[[[0.0; 5]; 5]; 2]).is_none());
    }
}
