//! Oil film of a short journal bearing: the cage riding on its guiding land (MODEL.md
//! section 3, "Cage / guiding land" [W25]: Ocvirk short bearing).
//!
//! Short-bearing Reynolds equation (Ocvirk & DuBois 1953) for a journal of radius R and
//! width L in a bearing of radial clearance c, eccentricity ratio eps, with the journal both
//! spinning (omega) and moving (radial speed de/dt, whirl speed dphi/dt):
//!
//!   d/dz (h^3 dp/dz) = 12 eta0 (dh/dt + omega/2 dh/dalpha),  h = c (1 - eps cos psi),
//!
//! psi measured from the line of centres (thinnest film at psi = 0). Per unit angle the
//! pressure integrates over the width to
//!
//!   P(psi) = eta0 L^3 / h^3 (e_dot cos psi - e (omega - 2 dphi/dt)/2 sin psi),
//!
//! and the film carries pressure only where P > 0 (Guembel condition; the rest cavitates).
//! With the substitution of Sommerfeld, 1 + eps cos theta = (1 - eps^2)/(1 - eps cos gamma),
//! theta = psi + pi, the positive part is one arc |gamma - gamma0| < beta and the force
//! integrals are elementary, so the film force is closed-form for any spin, whirl and squeeze
//! (the steady case gives Ocvirk's radial eta U L^3 eps^2 / (c^2 (1-eps^2)^2) and tangential
//! pi eta U L^3 eps / (4 c^2 (1-eps^2)^(3/2)), whose resultant is MODEL.md's load; a whirl at
//! half the spin carries no load; squeeze gives damping). The Couette drag over the whole land
//! is Petroff's 2 pi eta0 u R L / (c sqrt(1 - eps^2)) (MODEL.md); the pressure flow adds the
//! moment -e F_t / 2 on the journal. Dissipation -(M omega + F.v) is returned in closed form
//! and is never negative.

use std::f64::consts::PI;

/// A short journal bearing: the cage's guiding land.
#[derive(Debug, Clone, Copy)]
pub struct ShortJournal {
    /// Oil viscosity at ambient pressure (Pa s).
    pub eta0: f64,
    /// Journal radius (m).
    pub radius: f64,
    /// Land width (m).
    pub width: f64,
    /// Radial clearance (m).
    pub clearance: f64,
}

/// Film forces on the journal and the power the film dissipates.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct JournalFilm {
    /// Force along the eccentricity direction (negative: pushes the journal back to centre), N.
    pub radial: f64,
    /// Force perpendicular to it, positive in the positive sense of rotation, N.
    pub tangential: f64,
    /// Moment on the journal about its own axis (Couette drag and pressure flow), N m.
    pub moment: f64,
    /// Power dissipated in the film (>= 0), W.
    pub power: f64,
}

impl ShortJournal {
    /// Film at eccentricity `e` (< clearance) for journal spin `omega` (rad/s, signed) and
    /// journal-centre velocity with components `v_r` along the eccentricity and `v_t`
    /// perpendicular to it in the positive sense (m/s).
    pub fn film(&self, e: f64, omega: f64, v_r: f64, v_t: f64) -> JournalFilm {
        let c = self.clearance;
        let eps = (e / c).clamp(0.0, 1.0 - 1e-9);
        let one = 1.0 - eps * eps;
        let s = one.sqrt();
        let u = (omega * self.radius).abs();
        // Couette drag of the whole land (Petroff, MODEL.md)
        let drag = 2.0 * PI * self.eta0 * u * self.radius * self.width / (c * s);
        let couette = -drag * self.radius * omega.signum();
        // pressure: P = (eta0 L^3 / c^2) (eps_dot cos psi - a sin psi) / (1 - eps cos psi)^3
        let a = 0.5 * (eps * omega - 2.0 * v_t / c); // eps (omega - 2 dphi/dt) / 2
        let eps_dot = v_r / c;
        let r = (a * a * one + eps_dot * eps_dot).sqrt();
        if r == 0.0 {
            return JournalFilm {
                moment: couette,
                power: drag * u,
                ..Default::default()
            };
        }
        // positive-pressure arc |gamma - gamma0| < beta: cos(beta) = -eps_dot eps / r
        let beta = libm::acos((-eps_dot * eps / r).clamp(-1.0, 1.0));
        let (sb, cb) = libm::sincos(beta);
        let j0 = 2.0 * (sb - beta * cb);
        let j1 = beta - sb * cb;
        let k = self.eta0 * self.radius * self.width.powi(3) / (c * c);
        let k5 = k / (one * one * s);
        let radial = -k5 * (eps_dot * j1 + eps * r * j0);
        let tangential = k5 * one * a * j1;
        // dissipation of the pressure flow: k c r^2 (beta (1 + 2 cos^2 beta) - 3 sin beta cos beta)
        let pressure_power = k5 * c * r * r * (beta * (1.0 + 2.0 * cb * cb) - 3.0 * sb * cb);
        JournalFilm {
            radial,
            tangential,
            moment: couette - 0.5 * e.min(eps * c) * tangential,
            power: drag * u + pressure_power.max(0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The CRB-TRILOBE cage land: 47 mm, 4 mm wide, 0.3 mm clearance, eta0 5.5 mPa s.
    const LAND: ShortJournal = ShortJournal {
        eta0: 0.0055,
        radius: 0.047,
        width: 0.004,
        clearance: 3e-4,
    };

    /// Film force by brute-force quadrature of the pressure P(psi) (Guembel: P > 0 only).
    fn quadrature(j: &ShortJournal, e: f64, omega: f64, v_r: f64, v_t: f64) -> (f64, f64, f64) {
        let n = 2_000_000;
        let c = j.clearance;
        let (mut fr, mut ft, mut p_dh) = (0.0, 0.0, 0.0);
        let dpsi = 2.0 * PI / n as f64;
        for i in 0..n {
            let psi = (i as f64 + 0.5) * dpsi;
            let (sp, cp) = psi.sin_cos();
            let h = c - e * cp;
            // d/dt h at a fixed bearing angle and omega/2 dh/dalpha
            let squeeze = -v_r * cp - v_t * sp + 0.5 * omega * e * sp;
            let p = (-j.eta0 * j.width.powi(3) / h.powi(3) * squeeze).max(0.0);
            // journal outward normal n = e_hat cos psi + e_perp sin psi; force -P n R dpsi
            fr -= p * cp * j.radius * dpsi;
            ft -= p * sp * j.radius * dpsi;
            p_dh += p * squeeze * j.radius * dpsi;
        }
        (fr, ft, -p_dh)
    }

    #[test]
    fn steady_film_is_ocvirk_and_its_resultant_is_models_load() {
        let omega = 1873.0;
        let u = omega * LAND.radius;
        for eps in [0.1, 0.5, 0.9, 0.99] {
            let f = LAND.film(eps * LAND.clearance, omega, 0.0, 0.0);
            let (c2, b3, one) = (LAND.clearance.powi(2), LAND.width.powi(3), 1.0 - eps * eps);
            let w_r = LAND.eta0 * u * b3 * eps * eps / (c2 * one * one);
            let w_t = PI * LAND.eta0 * u * b3 * eps / (4.0 * c2 * one.powf(1.5));
            assert!((f.radial + w_r).abs() < 1e-10 * w_r, "eps {eps}: radial {} vs {}", f.radial, -w_r);
            assert!(
                (f.tangential - w_t).abs() < 1e-10 * w_t,
                "eps {eps}: tangential {} vs {w_t}",
                f.tangential
            );
            // MODEL.md: load = eta0 U b^3 eps sqrt(16 eps^2 + pi^2 (1 - eps^2)) / (4 c^2 (1 - eps^2)^2)
            let load = LAND.eta0 * u * b3 * eps * (16.0 * eps * eps + PI * PI * one).sqrt() / (4.0 * c2 * one * one);
            assert!((f.radial.hypot(f.tangential) - load).abs() < 1e-10 * load);
            // the tangential force leads in the sense of rotation: reversed spin, reversed force
            let r = LAND.film(eps * LAND.clearance, -omega, 0.0, 0.0);
            assert_eq!((r.radial, r.tangential), (f.radial, -f.tangential));
        }
    }

    #[test]
    fn closed_form_matches_quadrature_for_spin_whirl_and_squeeze() {
        let c = LAND.clearance;
        for &(eps, omega, v_r, v_t) in &[
            (0.3, 1873.0, 0.0, 0.0),
            (0.3, 1873.0, 0.05, 0.0),
            (0.6, 1873.0, -0.05, 0.1),
            (0.8, -900.0, 0.02, -0.3),
            (0.5, 0.0, 0.1, 0.0),
            (0.5, 0.0, -0.1, 0.0),
            (0.7, 0.0, 0.0, 0.2),
            (0.4, 1873.0, 0.0, 0.5 * 1873.0 * 0.4 * 3e-4),
        ] {
            let f = LAND.film(eps * c, omega, v_r, v_t);
            let (fr, ft, power) = quadrature(&LAND, eps * c, omega, v_r, v_t);
            let scale = fr.hypot(ft).max(1e-12);
            assert!(
                (f.radial - fr).abs() < 1e-5 * scale,
                "{eps} {omega} {v_r} {v_t}: radial {} vs {fr}",
                f.radial
            );
            assert!(
                (f.tangential - ft).abs() < 1e-5 * scale,
                "{eps} {omega} {v_r} {v_t}: tangential {} vs {ft}",
                f.tangential
            );
            let drag = 2.0 * PI * LAND.eta0 * (omega * LAND.radius).abs() * LAND.radius * LAND.width / (c * (1.0 - eps * eps).sqrt());
            let u = (omega * LAND.radius).abs();
            assert!(
                (f.power - drag * u - power).abs() < 1e-5 * power.max(1e-9),
                "{eps} {omega} {v_r} {v_t}: power {} vs {}",
                f.power - drag * u,
                power
            );
        }
    }

    #[test]
    fn film_dissipates_what_its_forces_and_moment_take() {
        // -(M omega + F.v) = power, for random spin, whirl and squeeze
        let c = LAND.clearance;
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..1000 {
            let eps = 0.999 * next();
            let omega = 4000.0 * (next() - 0.5);
            let (v_r, v_t) = (2.0 * (next() - 0.5), 2.0 * (next() - 0.5));
            let f = LAND.film(eps * c, omega, v_r, v_t);
            let taken = -(f.moment * omega + f.radial * v_r + f.tangential * v_t);
            assert!(f.power >= 0.0);
            assert!(
                (taken - f.power).abs() <= 1e-9 * f.power.max(1e-6),
                "{eps} {omega} {v_r} {v_t}: {taken} vs {}",
                f.power
            );
        }
    }

    #[test]
    fn half_speed_whirl_carries_no_load_and_squeeze_damps() {
        let (c, omega, e) = (LAND.clearance, 1873.0, 0.5 * LAND.clearance);
        let whirl = LAND.film(e, omega, 0.0, 0.5 * omega * e);
        assert!(whirl.radial.abs() < 1e-9 && whirl.tangential.abs() < 1e-9, "{whirl:?}");
        // squeeze resists the radial motion both ways and grows towards the wall
        let mut last = 0.0;
        for eps in [0.0, 0.3, 0.6, 0.9] {
            let inward = LAND.film(eps * c, 0.0, 0.01, 0.0);
            let outward = LAND.film(eps * c, 0.0, -0.01, 0.0);
            assert!(inward.radial < 0.0 && outward.radial > 0.0);
            assert!(-inward.radial > last);
            last = -inward.radial;
        }
    }
}
