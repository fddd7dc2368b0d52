//! Friction torque and power loss of the quasi-static model (MODEL.md section 7), from the
//! converged contact loads and the epicyclic kinematics with cage slip (outer-raceway
//! control [L22]: pure rolling on the cup at mid-roller, sliding S_c omega_i R_i on the cone).
//!
//! Power is summed over every loaded slice and the flange: rolling resistance times the
//! rolling (entrainment) speed plus traction times the sliding speed. The torque needed to
//! drive the cone is power / speed; computing it from speed ratios keeps it finite and
//! continuous through zero speed. The traction forces also give each roller's skew
//! moments from cone, cup and flange (the tangential force at axial station s about the
//! roller centre: N = -s F_t).
//!
//! EHL (`lubrication` = 0): film, film ratio, boundary/mixed/full-film traction per slice,
//! Zhou-Hoeprich rolling resistance; flange: asperity share mu0 exp(-1.8 Lambda^1.2) plus
//! viscous film traction over the Hertz ellipse. Dry (`lubrication` = 1): one Coulomb
//! coefficient, smoothly regularised, at raceways and flange [D19].

use super::QuasiStatic;
use crate::bearing::Bearing;
use crate::contact::line_contact_half_width;
use crate::geometry::Geometry;
use crate::model::{Inputs, Lubrication, Outputs, Parameters};
use crate::tribology as tr;

/// Kinematics of one contact point per unit cone speed, in the cage frame.
#[derive(Debug, Clone, Copy, Default)]
struct Kinematics {
    /// Sliding speed (roller surface minus ring surface, along the rolling direction).
    slide: f64,
    /// Entrainment speed (mean of the two surface speeds, magnitude).
    entrain: f64,
}

impl Kinematics {
    fn new(roller: f64, ring: f64) -> Kinematics {
        Kinematics {
            slide: roller - ring,
            entrain: 0.5 * (roller + ring).abs(),
        }
    }
}

/// Torque parts (N m) needed to drive the cone.
#[derive(Debug, Clone, Copy, Default)]
pub struct TorqueParts {
    pub raceway: f64,
    pub flange: f64,
}

/// Precomputed per-slice kinematics and oil data.
#[derive(Debug, Clone)]
pub struct FrictionModel {
    cone: Vec<Kinematics>,
    cup: Vec<Kinematics>,
    flange: Kinematics,
    /// Axial station of the flange contact along the roller axis (for its skew moment).
    flange_s: f64,
    eta0: f64,
    alpha: f64,
    sigma: f64,
    mu: f64,
    flange_mu0: f64,
}

impl FrictionModel {
    pub fn new(_b: &Bearing, p: &Parameters, g: &Geometry, cage_ratio: f64, spin_ratio: f64) -> FrictionModel {
        let cone = (0..g.slices)
            .map(|k| {
                let ring = (1.0 - cage_ratio) * g.cone.raceway_radius[k];
                let roller = -spin_ratio * g.slice_radius[k];
                Kinematics::new(roller, ring)
            })
            .collect();
        let cup = (0..g.slices)
            .map(|k| {
                let ring = -cage_ratio * g.cup.raceway_radius[k];
                let roller = spin_ratio * g.slice_radius[k];
                Kinematics::new(roller, ring)
            })
            .collect();
        let (flange, flange_s) = match &g.flange {
            Some(f) => {
                let ring = (1.0 - cage_ratio) * f.rib_radius;
                let roller = spin_ratio * f.offset;
                let rel = [f.point[0] - g.center[0], f.point[1] - g.center[1]];
                (Kinematics::new(roller, ring), rel[0] * g.axis[0] + rel[1] * g.axis[1])
            }
            None => (Kinematics::default(), 0.0),
        };
        FrictionModel {
            cone,
            cup,
            flange,
            flange_s,
            eta0: p.eta0,
            alpha: p.alpha,
            sigma: p.roughness,
            mu: p.mu,
            flange_mu0: p.flange_mu0,
        }
    }

    /// Raceway slice traction: returns (tangential force on the roller, torque contribution
    /// per unit sign of speed) for one slice.
    #[inline]
    fn slice(&self, g: &Geometry, line_r_bar: f64, kin: Kinematics, q: f64, speed: f64, lubrication: Lubrication) -> (f64, f64) {
        let v_s = speed * kin.slide;
        match lubrication {
            Lubrication::Dry => {
                let mu = tr::dry_mu(self.mu, v_s);
                // power = |mu q v_s|; torque per unit sign of speed = power / |speed|
                (-mu * q, mu.abs() * q * kin.slide.abs())
            }
            Lubrication::Ehl => {
                let l = g.slice_len;
                let w = q / l;
                let u_e = speed.abs() * kin.entrain;
                let h = tr::film_line(self.eta0, self.alpha, g.e_prime, u_e, line_r_bar, w);
                let lambda = if self.sigma > 0.0 { h / self.sigma } else { f64::INFINITY };
                let slide_roll = if kin.entrain > 0.0 { kin.slide.abs() / kin.entrain } else { 0.0 };
                let (b, _) = line_contact_half_width(w, line_r_bar, g.e_prime);
                let p_mean = if b > 0.0 { w / (2.0 * b) } else { 0.0 };
                let mu_fl = tr::full_film_mu(self.eta0, v_s, h, p_mean).abs();
                let mu = tr::traction_mu(lambda, slide_roll, mu_fl);
                let f_roll = tr::rolling_resistance(self.eta0, self.alpha, g.e_prime, u_e, line_r_bar, q, l);
                let dir = if v_s > 0.0 {
                    1.0
                } else if v_s < 0.0 {
                    -1.0
                } else {
                    0.0
                };
                (-mu * q * dir, mu * q * kin.slide.abs() + f_roll * kin.entrain)
            }
        }
    }

    /// Friction torque parts at the solution `x` of `qs`; fills the skew moments of `out`.
    #[allow(clippy::too_many_arguments)]
    pub fn evaluate(
        &self,
        qs: &QuasiStatic,
        x: &[f64],
        inputs: &Inputs,
        lubrication: Lubrication,
        out: &mut Outputs,
        cone: &mut [f64],
        cup: &mut [f64],
    ) -> TorqueParts {
        let g = &qs.geometry;
        let speed = inputs.speed;
        let sign = if speed < 0.0 { -1.0 } else { 1.0 };
        let mut parts = TorqueParts::default();
        for j in 0..g.z {
            qs.slice_loads(x, j, cone, cup);
            let (mut nis, mut nos) = (0.0, 0.0);
            for k in 0..g.slices {
                if cone[k] > 0.0 {
                    let (ft, t) = self.slice(g, g.cone.r_bar[k], self.cone[k], cone[k], speed, lubrication);
                    parts.raceway += t;
                    nis -= g.slice_s[k] * ft;
                }
                if cup[k] > 0.0 {
                    let (ft, t) = self.slice(g, g.cup.r_bar[k], self.cup[k], cup[k], speed, lubrication);
                    parts.raceway += t;
                    nos -= g.slice_s[k] * ft;
                }
            }
            let mut nfs = 0.0;
            let qf = qs.flange_load(j);
            if let (Some(f), true) = (&g.flange, qf > 0.0) {
                let kin = self.flange;
                let v_s = speed * kin.slide;
                let (ft, t) = match lubrication {
                    Lubrication::Dry => {
                        let mu = tr::dry_mu(self.mu, v_s);
                        (-mu * qf, mu.abs() * qf * kin.slide.abs())
                    }
                    Lubrication::Ehl => {
                        let u_e = speed.abs() * kin.entrain;
                        let (a, b, p_h) = f.hertz.ellipse(qf);
                        let h = tr::film_point(self.eta0, self.alpha, g.e_prime, u_e, f.hertz.ry, f.hertz.rx, qf);
                        let film_ratio = if self.sigma > 0.0 { h / self.sigma } else { f64::INFINITY };
                        let f_total = qf * tr::flange_boundary_mu(self.flange_mu0, film_ratio)
                            + tr::flange_viscous_traction(self.eta0, v_s, h, a, b, p_h);
                        let dir = if v_s > 0.0 {
                            1.0
                        } else if v_s < 0.0 {
                            -1.0
                        } else {
                            0.0
                        };
                        (-f_total * dir, f_total * kin.slide.abs())
                    }
                };
                parts.flange += t;
                nfs = -self.flange_s * ft;
            }
            out.nis[j] = nis;
            out.nos[j] = nos;
            out.nfs[j] = nfs;
        }
        parts.raceway *= sign;
        parts.flange *= sign;
        parts
    }
}
