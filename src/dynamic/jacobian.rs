//! Block-structured Jacobian of the dynamic model and the linear systems of implicit steps.
//!
//! Rollers do not touch one another: roller j's equations depend on its own 11 states and on
//! the global states (the cone's translations and the cage's, 12; the housing's and the local
//! defects' turns where the model has them, `Layout`), and the global equations on every
//! roller.
//! The Jacobian is therefore block-arrowhead:
//!
//! ```text
//!     | D_1           R_1 |        D_j: 11 x 11 (roller j on itself)
//! J = |     ...       ... |        R_j: 11 x g (roller j on the g globals)
//!     |         D_Z   R_Z |        L_j: g x 11 (the globals on roller j)
//!     | L_1 ... L_Z   G   |        G:   g x g (g = 12 without a housing or defects)
//! ```
//!
//! Finite differences need only 11 + g right-hand sides (+ 1 at the base point): perturbing
//! component i of every roller at once gives column i of every D_j, and of every L_j from each
//! roller's share of the global equations (`Shares`, kept apart by the right-hand side); each
//! global state is perturbed on its own. A kinematic cage (at the mean roller azimuth) couples
//! the rollers weakly; that coupling lands lumped in the D_j (fine for W-methods, which keep
//! their order with any matrix).
//!
//! The matrix of an implicit stage, alpha I - J, is factored by blocks: LU of each
//! A_j = alpha I - D_j, V_j = A_j^-1 R_j, the Schur complement S = alpha I - G - sum L_j V_j
//! (g x g) and its LU; a solve costs two block substitutions per roller and one g x g solve.

/// States per roller and global states.
pub const M: usize = super::PER_ROLLER;
/// The base global states (cone and cage): g without a housing or turning defects.
pub const NG: usize = super::ROLLERS;

/// The Jacobian blocks (row-major).
#[derive(Debug, Clone, PartialEq)]
pub struct BlockJacobian {
    pub z: usize,
    /// Global states: the base twelve and the element's further ones (`Constants::globals`).
    pub ng: usize,
    /// z blocks of M x M.
    pub d: Vec<f64>,
    /// z blocks of M x ng.
    pub r: Vec<f64>,
    /// z blocks of ng x M.
    pub l: Vec<f64>,
    /// ng x ng.
    pub g: Vec<f64>,
}

/// What the finite differences need from the model: the right-hand side and, for the state
/// it was last evaluated at, each roller's share of the global equations (ng values per roller).
pub trait BlockSystem {
    /// The derivative at time `t` (the inputs may ramp over the interval) and state `y`.
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]);
    fn shares(&self, out: &mut [f64]);
    /// Whether the right-hand side changes in time so that its time derivative drives stiff
    /// modes (inputs the contacts see directly, ramped over the interval): the Rosenbrock
    /// stages then take df/dt.
    fn stiffly_time_dependent(&self) -> bool {
        false
    }
    /// Whether the system is near standstill, where the regularised friction's Jacobian
    /// changes fastest (the Rosenbrock stages then keep a Jacobian for fewer steps while the
    /// inputs ramp).
    fn near_standstill(&self) -> bool {
        false
    }
}

impl BlockJacobian {
    pub fn zeros(z: usize, ng: usize) -> BlockJacobian {
        BlockJacobian {
            z,
            ng,
            d: vec![0.0; z * M * M],
            r: vec![0.0; z * M * ng],
            l: vec![0.0; z * ng * M],
            g: vec![0.0; ng * ng],
        }
    }

    /// Number of values in [`BlockJacobian::write`].
    pub fn len(z: usize, ng: usize) -> usize {
        z * (M * M + 2 * M * ng) + ng * ng
    }

    /// Renumber the roller blocks as if every roller had moved on by `k` places: roller j takes
    /// the blocks of roller j + k (mod z). In a state periodic in the roller pitch, roller j
    /// stands after k pitches of orbit where roller j + k stood.
    pub fn shift_rollers(&mut self, k: usize) {
        let k = k % self.z;
        let ng = self.ng;
        self.d.rotate_left(k * M * M);
        self.r.rotate_left(k * M * ng);
        self.l.rotate_left(k * ng * M);
    }

    /// Write the blocks to `out`, [`BlockJacobian::len`] values (for the serialised
    /// integrator state).
    pub fn write(&self, out: &mut [f64]) {
        let (z, ng) = (self.z, self.ng);
        let (a, rest) = out.split_at_mut(z * M * M);
        let (b, rest) = rest.split_at_mut(z * M * ng);
        let (c, d) = rest.split_at_mut(z * ng * M);
        a.copy_from_slice(&self.d);
        b.copy_from_slice(&self.r);
        c.copy_from_slice(&self.l);
        d[..ng * ng].copy_from_slice(&self.g);
    }

    /// Read the blocks written by [`BlockJacobian::write`].
    pub fn read(&mut self, v: &[f64]) {
        let (z, ng) = (self.z, self.ng);
        let (a, rest) = v.split_at(z * M * M);
        let (b, rest) = rest.split_at(z * M * ng);
        let (c, d) = rest.split_at(z * ng * M);
        self.d.copy_from_slice(a);
        self.r.copy_from_slice(b);
        self.l.copy_from_slice(c);
        self.g.copy_from_slice(&d[..ng * ng]);
    }

    /// Finite-difference Jacobian at (`t`, `y`) with `f0` = f(t, y) (recomputed here, with the shares),
    /// perturbation of component i: sqrt(eps) max(|y_i|, scale_i). `work` holds 3 n values,
    /// `shares` 2 z ng. `global_active[k]` = false skips global columns that nothing reads.
    /// Returns the number of right-hand sides evaluated.
    #[allow(clippy::too_many_arguments)]
    pub fn compute(
        &mut self,
        sys: &mut impl BlockSystem,
        t: f64,
        y: &[f64],
        scale: &[f64],
        global_active: &[bool],
        work: &mut [f64],
        shares: &mut [f64],
    ) -> u64 {
        let n = y.len();
        let (z, ng) = (self.z, self.ng);
        let (f0, rest) = work.split_at_mut(n);
        let (yp, rest) = rest.split_at_mut(n);
        let fp = &mut rest[..n];
        let (s0, sp) = shares.split_at_mut(z * ng);
        let sp = &mut sp[..z * ng];
        let mut count = 0;
        sys.rhs(t, y, f0);
        sys.shares(s0);
        count += 1;
        let eps = f64::EPSILON.sqrt();
        let step = |i: usize| eps * y[i].abs().max(scale[i]);
        // roller columns: component i of every roller at once
        for i in 0..M {
            yp.copy_from_slice(y);
            for j in 0..z {
                let k = ng + M * j + i;
                yp[k] = y[k] + step(k);
            }
            sys.rhs(t, yp, fp);
            sys.shares(sp);
            count += 1;
            for j in 0..z {
                let k = ng + M * j + i;
                let inv = 1.0 / (yp[k] - y[k]);
                let o = ng + M * j;
                for row in 0..M {
                    self.d[j * M * M + row * M + i] = (fp[o + row] - f0[o + row]) * inv;
                }
                for row in 0..ng {
                    self.l[j * ng * M + row * M + i] = (sp[j * ng + row] - s0[j * ng + row]) * inv;
                }
            }
        }
        // global columns
        for gc in 0..ng {
            if !global_active[gc] {
                for row in 0..ng {
                    self.g[row * ng + gc] = 0.0;
                }
                for j in 0..z {
                    for row in 0..M {
                        self.r[j * M * ng + row * ng + gc] = 0.0;
                    }
                }
                continue;
            }
            yp.copy_from_slice(y);
            yp[gc] = y[gc] + step(gc);
            let inv = 1.0 / (yp[gc] - y[gc]);
            sys.rhs(t, yp, fp);
            count += 1;
            for row in 0..ng {
                self.g[row * ng + gc] = (fp[row] - f0[row]) * inv;
            }
            for j in 0..z {
                let o = ng + M * j;
                for row in 0..M {
                    self.r[j * M * ng + row * ng + gc] = (fp[o + row] - f0[o + row]) * inv;
                }
            }
        }
        count
    }

    /// y = J x (tests; power iteration for the spectral radius).
    pub fn apply(&self, x: &[f64], y: &mut [f64]) {
        let (z, ng) = (self.z, self.ng);
        let (xg, xr) = x.split_at(ng);
        let (yg, yr) = y.split_at_mut(ng);
        for row in 0..ng {
            yg[row] = (0..ng).map(|c| self.g[row * ng + c] * xg[c]).sum();
        }
        for j in 0..z {
            let xj = &xr[M * j..M * j + M];
            for row in 0..M {
                let mut s = 0.0;
                for c in 0..M {
                    s += self.d[j * M * M + row * M + c] * xj[c];
                }
                for c in 0..ng {
                    s += self.r[j * M * ng + row * ng + c] * xg[c];
                }
                yr[M * j + row] = s;
            }
            for row in 0..ng {
                let mut s = 0.0;
                for c in 0..M {
                    s += self.l[j * ng * M + row * M + c] * xj[c];
                }
                yg[row] += s;
            }
        }
    }
}

/// LU factors of alpha I - J by blocks.
#[derive(Debug, Clone)]
pub struct BlockLu {
    z: usize,
    ng: usize,
    pub alpha: f64,
    a: Vec<f64>,
    piv_a: Vec<usize>,
    v: Vec<f64>,
    l: Vec<f64>,
    s: Vec<f64>,
    piv_s: Vec<usize>,
}

impl BlockLu {
    pub fn new(z: usize, ng: usize) -> BlockLu {
        BlockLu {
            z,
            ng,
            alpha: f64::NAN,
            a: vec![0.0; z * M * M],
            piv_a: vec![0; z * M],
            v: vec![0.0; z * M * ng],
            l: vec![0.0; z * ng * M],
            s: vec![0.0; ng * ng],
            piv_s: vec![0; ng],
        }
    }

    /// Factor alpha I - J. False if singular.
    pub fn factor(&mut self, jac: &BlockJacobian, alpha: f64) -> bool {
        self.alpha = alpha;
        let (z, ng) = (self.z, self.ng);
        self.l.copy_from_slice(&jac.l);
        // S = alpha I - G - sum L_j V_j
        for row in 0..ng {
            for c in 0..ng {
                self.s[row * ng + c] = if row == c { alpha } else { 0.0 } - jac.g[row * ng + c];
            }
        }
        for j in 0..z {
            let a = &mut self.a[j * M * M..(j + 1) * M * M];
            for row in 0..M {
                for c in 0..M {
                    a[row * M + c] = if row == c { alpha } else { 0.0 } - jac.d[j * M * M + row * M + c];
                }
            }
            let piv = &mut self.piv_a[j * M..(j + 1) * M];
            if !lu_factor(a, M, piv) {
                return false;
            }
            // V_j = A_j^-1 R_j, column by column
            let v = &mut self.v[j * M * ng..(j + 1) * M * ng];
            let mut col = [0.0; M];
            for c in 0..ng {
                for row in 0..M {
                    col[row] = jac.r[j * M * ng + row * ng + c];
                }
                lu_solve(a, M, piv, &mut col);
                for row in 0..M {
                    v[row * ng + c] = col[row];
                }
            }
            let l = &jac.l[j * ng * M..(j + 1) * ng * M];
            for row in 0..ng {
                for c in 0..ng {
                    let mut sum = 0.0;
                    for k in 0..M {
                        sum += l[row * M + k] * v[k * ng + c];
                    }
                    self.s[row * ng + c] -= sum;
                }
            }
        }
        lu_factor(&mut self.s, ng, &mut self.piv_s)
    }

    /// Solve (alpha I - J) x = b in place.
    pub fn solve(&mut self, b: &mut [f64]) {
        let (z, ng) = (self.z, self.ng);
        let (bg, br) = b.split_at_mut(ng);
        // z_j = A_j^-1 b_j; r = b_g + sum L_j z_j
        for j in 0..z {
            let zj = &mut br[M * j..M * j + M];
            lu_solve(&self.a[j * M * M..(j + 1) * M * M], M, &self.piv_a[j * M..(j + 1) * M], zj);
            let l = &self.l[j * ng * M..(j + 1) * ng * M];
            for row in 0..ng {
                let mut s = 0.0;
                for k in 0..M {
                    s += l[row * M + k] * zj[k];
                }
                bg[row] += s;
            }
        }
        lu_solve(&self.s, ng, &self.piv_s, bg);
        // x_j = z_j + V_j x_g
        for j in 0..z {
            let v = &self.v[j * M * ng..(j + 1) * M * ng];
            for row in 0..M {
                let mut s = 0.0;
                for c in 0..ng {
                    s += v[row * ng + c] * bg[c];
                }
                br[M * j + row] += s;
            }
        }
    }
}

/// LU with partial pivoting of the n x n row-major `a` in place. False if singular.
fn lu_factor(a: &mut [f64], n: usize, piv: &mut [usize]) -> bool {
    for k in 0..n {
        let mut p = k;
        let mut best = a[k * n + k].abs();
        for i in k + 1..n {
            let v = a[i * n + k].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        piv[k] = p;
        if best == 0.0 || !best.is_finite() {
            return false;
        }
        if p != k {
            for c in 0..n {
                a.swap(k * n + c, p * n + c);
            }
        }
        let inv = 1.0 / a[k * n + k];
        for i in k + 1..n {
            let f = a[i * n + k] * inv;
            a[i * n + k] = f;
            if f != 0.0 {
                for c in k + 1..n {
                    a[i * n + c] -= f * a[k * n + c];
                }
            }
        }
    }
    true
}

/// Solve with the factors of [`lu_factor`], in place.
fn lu_solve(a: &[f64], n: usize, piv: &[usize], b: &mut [f64]) {
    // whole rows were swapped in the factorisation (multipliers too): all swaps first
    for k in 0..n {
        let p = piv[k];
        if p != k {
            b.swap(k, p);
        }
    }
    for k in 0..n {
        let bk = b[k];
        if bk != 0.0 {
            for i in k + 1..n {
                b[i] -= a[i * n + k] * bk;
            }
        }
    }
    for k in (0..n).rev() {
        let mut s = b[k];
        for c in k + 1..n {
            s -= a[k * n + c] * b[c];
        }
        b[k] = s / a[k * n + k];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Renumbering by k places gives roller j the blocks roller j + k had, leaves the global
    /// block alone, and k places forward then z - k forward is the identity.
    #[test]
    fn shifting_the_rollers_renumbers_their_blocks() {
        let z = 5;
        let mut jac = BlockJacobian::zeros(z, NG);
        // every entry tells its roller and position: 1000 (roller + 1) + index in the block
        for j in 0..z {
            let tag = |i: usize| 1000.0 * (j + 1) as f64 + i as f64;
            jac.d[j * M * M..(j + 1) * M * M]
                .iter_mut()
                .enumerate()
                .for_each(|(i, v)| *v = tag(i));
            jac.r[j * M * NG..(j + 1) * M * NG]
                .iter_mut()
                .enumerate()
                .for_each(|(i, v)| *v = -tag(i));
            jac.l[j * NG * M..(j + 1) * NG * M]
                .iter_mut()
                .enumerate()
                .for_each(|(i, v)| *v = 0.5 * tag(i));
        }
        jac.g.iter_mut().enumerate().for_each(|(i, v)| *v = i as f64);
        let before = jac.clone();
        let k = 2;
        jac.shift_rollers(k);
        for j in 0..z {
            let from = (j + k) % z;
            assert_eq!(jac.d[j * M * M..(j + 1) * M * M], before.d[from * M * M..(from + 1) * M * M]);
            assert_eq!(jac.r[j * M * NG..(j + 1) * M * NG], before.r[from * M * NG..(from + 1) * M * NG]);
            assert_eq!(jac.l[j * NG * M..(j + 1) * NG * M], before.l[from * NG * M..(from + 1) * NG * M]);
        }
        assert_eq!(jac.g, before.g);
        jac.shift_rollers(z - k);
        assert_eq!(jac, before);
        jac.shift_rollers(z);
        assert_eq!(jac, before);
    }

    /// A random block-arrowhead system: the block solve agrees with a dense solve.
    #[test]
    fn block_solve_matches_dense() {
        let z = 5;
        let n = NG + M * z;
        let mut seed = 12345_u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        let mut jac = BlockJacobian::zeros(z, NG);
        for v in jac
            .d
            .iter_mut()
            .chain(jac.r.iter_mut())
            .chain(jac.l.iter_mut())
            .chain(jac.g.iter_mut())
        {
            *v = rnd();
        }
        // rows of very different scales (stiffness over mass against identities) force pivoting
        for j in 0..z {
            for row in (1..M).step_by(2) {
                for c in 0..M {
                    jac.d[j * M * M + row * M + c] *= 1e6;
                }
            }
        }
        let alpha = 3.0;
        let mut lu = BlockLu::new(z, NG);
        assert!(lu.factor(&jac, alpha));
        let x: Vec<f64> = (0..n).map(|_| rnd()).collect();
        // b = (alpha I - J) x
        let mut jx = vec![0.0; n];
        jac.apply(&x, &mut jx);
        let mut b: Vec<f64> = (0..n).map(|i| alpha * x[i] - jx[i]).collect();
        lu.solve(&mut b);
        for i in 0..n {
            assert!((b[i] - x[i]).abs() < 1e-9, "{i}: {} vs {}", b[i], x[i]);
        }
        // serialisation round trip
        let mut v = vec![f64::NAN; BlockJacobian::len(z, NG)];
        jac.write(&mut v);
        assert!(v.iter().all(|x| x.is_finite()), "every value written");
        let mut back = BlockJacobian::zeros(z, NG);
        back.read(&v);
        assert_eq!(back, jac);
    }
}
