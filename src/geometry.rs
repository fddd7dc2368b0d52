//! Bearing geometry derived once from the bearing description (MODEL.md section 2): the
//! roller's axial-plane section, slice stations and contact points on the cone, cup and
//! flange, contact normals and equivalent radii, and roller mass properties.
//!
//! Frame: x along the bearing axis, r radial, in the axial plane of a roller; origin on the
//! bearing axis in the plane of the roller centres. The roller apex lies on the +x side, so
//! raceway radii shrink with x, the large roller end and the cone's large rib are on the -x
//! side, and a positive axial force on the cone (towards +x) loads the bearing.
//! In-plane rotations (roller tilt) are positive from +x towards +r, which is a rotation
//! about the tangential direction e_t = e_x cross e_r of the bearing.
//!
//! Contact normals `n` are the directions of the force a ring exerts on the roller:
//! cone n_i = (sin a_i, cos a_i), cup n_o = (-sin a_o, -cos a_o), flange
//! n_f = (sin a_f, -cos a_f) with a_f measured from the radial plane (Harris).

use crate::bearing::{Bearing, ContactLaw};
use crate::contact;

/// Floor of the rib/end-sphere relative curvature in the circumferential direction, as a
/// fraction of the sphere's curvature.
pub const MIN_RELATIVE_CURVATURE: f64 = 0.01;

/// What the geometry takes besides the bearing description: the roller's slice count and
/// its crown drop at the ends (m), the element's parameters `slices` and `crown_drop`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerProfile {
    pub slices: usize,
    pub crown_drop: f64,
}

impl RollerProfile {
    /// The bearing file's slice count and crown drop (the parameters' start values).
    pub fn of_bearing(b: &Bearing) -> RollerProfile {
        RollerProfile {
            slices: b.slices,
            crown_drop: b.crown_drop,
        }
    }
}

/// A point or vector in the axial plane: `[x, r]`.
pub type Vec2 = [f64; 2];

/// 2-D cross product a x b (out-of-plane component, positive from x to r).
#[inline]
pub fn cross(a: Vec2, b: Vec2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The sliced contact line of a roller on one raceway.
#[derive(Debug, Clone)]
pub struct ContactLine {
    /// Nominal contact point of each slice (axial plane).
    pub point: Vec<Vec2>,
    /// Direction of the force of the ring on the roller (same for all slices).
    pub normal: Vec2,
    /// Moment arm about the roller centre: (p - c) x n, per slice.
    pub lever: Vec<f64>,
    /// Equivalent radius of roller and raceway in the plane normal to the generatrix.
    pub r_bar: Vec<f64>,
    /// Distance of the raceway contact point from the bearing axis.
    pub raceway_radius: Vec<f64>,
    /// Principal radius of the raceway normal to the generatrix (signed: + convex, - concave).
    pub raceway_curvature_radius: Vec<f64>,
    /// Line-contact law of each slice (stiffness constants).
    pub law: contact::LineLaw,
}

/// The spherical roller end on the conical rib.
#[derive(Debug, Clone)]
pub struct FlangeContact {
    pub point: Vec2,
    pub normal: Vec2,
    pub lever: f64,
    /// Distance of the contact point from the bearing axis.
    pub rib_radius: f64,
    /// Signed distance of the contact point from the roller axis along m (negative: cone side).
    pub offset: f64,
    pub hertz: contact::PointContact,
}

/// Everything fixed about the geometry for one parameter set.
#[derive(Debug, Clone)]
pub struct Geometry {
    pub z: usize,
    pub slices: usize,
    pub cone_angle: f64,
    pub cup_angle: f64,
    pub half_angle: f64,
    pub axis_angle: f64,
    /// Roller centre in the axial plane.
    pub center: Vec2,
    /// Unit roller axis, from the large towards the small end.
    pub axis: Vec2,
    /// Unit in-plane normal to the roller axis, pointing away from the bearing axis.
    pub perp: Vec2,
    pub length: f64,
    pub mean_radius: f64,
    /// Slice stations along the roller axis from the centre (midpoints).
    pub slice_s: Vec<f64>,
    /// Slice length along the axis.
    pub slice_len: f64,
    /// Roller radius at each slice station.
    pub slice_radius: Vec<f64>,
    /// Profile drop (crown) at each slice station.
    pub crown: Vec<f64>,
    pub cone: ContactLine,
    pub cup: ContactLine,
    pub flange: Option<FlangeContact>,
    /// Effective modulus E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2) of roller and rings.
    pub e_prime: f64,
    pub roller_mass: f64,
    /// Roller moment of inertia about its own axis.
    pub inertia_axial: f64,
    /// Roller moment of inertia about a transverse axis through its centre of mass.
    pub inertia_transverse: f64,
    /// Centre of mass along the roller axis from the roller centre.
    pub cm_offset: f64,
    /// The roller has axial stiffness (tapered bearing); otherwise axial DOFs are fixed.
    pub axial: bool,
}

/// Where the lines of a tapered bearing meet the bearing axis, measured along it from the
/// roller centre's plane (m): a kinematically consistent bearing has one apex for all, so
/// that every point of a roller rolls on both raceways without sliding.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Apexes {
    /// The cone raceway's, the cup raceway's and the roller axis's meeting points.
    pub cone: f64,
    pub cup: f64,
    pub roller_axis: f64,
    /// How far the roller's own apex (where its generatrices meet on its axis) lies from the
    /// roller axis's meeting point.
    pub roller: f64,
}

impl Apexes {
    /// The largest distance between any two of the four (m).
    pub fn mismatch(&self) -> f64 {
        let xs = [self.cone, self.cup, self.roller_axis];
        let spread = xs.iter().fold(f64::NEG_INFINITY, |m, x| m.max(*x)) - xs.iter().fold(f64::INFINITY, |m, x| m.min(*x));
        spread.max(self.roller)
    }
}

impl Geometry {
    /// The apexes of a tapered bearing (`Apexes`); `None` for a cylindrical one.
    pub fn apexes(&self) -> Option<Apexes> {
        let (ai, ao, ar) = (self.cone_angle, self.cup_angle, self.axis_angle);
        if !(ai > 0.0 && ao > 0.0 && ar > 0.0 && self.half_angle > 0.0) {
            return None;
        }
        let meets = |p: Vec2, angle: f64| p[0] + p[1] / libm::tan(angle);
        let c = self.center;
        let roller_axis = meets(c, ar);
        // the roller's own apex, mean radius / tan(half-cone angle) along its axis
        let d = self.mean_radius / libm::tan(self.half_angle);
        let own = [c[0] + d * self.axis[0], c[1] + d * self.axis[1]];
        Some(Apexes {
            cone: meets(self.cone.point[0], ai),
            cup: meets(self.cup.point[0], ao),
            roller_axis,
            roller: libm::hypot(own[0] - roller_axis, own[1]),
        })
    }

    /// The rib's closed form of the roller's equilibrium skew (rad) with Coulomb friction
    /// `mu_f` at the rib and an end sphere of radius `end_radius` (docs/dynamic.md, "The roller
    /// skew mode"): phi = mu_f L_f e / (d (n_a e + d)), with d = R_s - l/2 the sphere centre
    /// from the middle of the roller, e = rho_p - R_s the sphere centre from the point where
    /// the rib normal meets the bearing axis (rho_p the rib's circumferential radius of
    /// curvature), n_a the cosine of the normal's angle to the roller axis and
    /// L_f = l/2 - R_s (1 - n_a) the contact's lever along the roller axis. `None` without a
    /// rib, or where the sphere reaches the axis point (e <= 0: a conformal rib).
    pub fn rib_skew(&self, end_radius: f64, mu_f: f64) -> Option<f64> {
        let f = self.flange.as_ref()?;
        let n_a = f.normal[0] * self.axis[0] + f.normal[1] * self.axis[1];
        let rho_p = f.rib_radius / -f.normal[1];
        let (e, d) = (rho_p - end_radius, end_radius - 0.5 * self.length);
        let lever = 0.5 * self.length - end_radius * (1.0 - n_a);
        (e > 0.0 && d > 0.0).then(|| mu_f * lever * e / (d * (n_a * e + d)))
    }

    /// The largest Hertz pressure (Pa) over the raceway slices whose loads `slice_loads` holds,
    /// per roller the cone's slices then the cup's (the layout of both models' slice loads).
    pub fn max_raceway_pressure(&self, slice_loads: &[f64]) -> f64 {
        // the pressure goes with the root of q / R: the largest of those first, one root after
        let ns = self.slices;
        let mut worst = [0.0_f64; 2];
        for roller in slice_loads.chunks_exact(2 * ns) {
            let (cone, cup) = roller.split_at(ns);
            for (w, (line, loads)) in worst.iter_mut().zip([(&self.cone, cone), (&self.cup, cup)]) {
                for (q, r) in loads.iter().zip(&line.r_bar) {
                    *w = w.max(q / r);
                }
            }
        }
        let p = |q_over_r: f64| contact::line_contact_pressure(q_over_r / self.slice_len, self.e_prime, 1.0);
        p(worst[0]).max(p(worst[1]))
    }

    pub fn new(b: &Bearing, p: &RollerProfile) -> Geometry {
        let s = p.slices;
        let ai = b.cone_angle;
        let ao = b.cup_angle;
        let ah = b.roller_half_angle;
        let ar = b.roller_axis_angle();
        let center = [0.0, 0.5 * b.pitch_diameter];
        let axis = [libm::cos(ar), -libm::sin(ar)];
        let perp = [libm::sin(ar), libm::cos(ar)];
        let l = b.roller_length;
        let rm = b.roller_mean_radius();
        let slice_len = l / s as f64;
        let slice_s: Vec<f64> = (0..s).map(|k| -0.5 * l + (k as f64 + 0.5) * slice_len).collect();
        let slice_radius: Vec<f64> = slice_s.iter().map(|&x| rm - x * libm::tan(ah)).collect();
        let crown: Vec<f64> = slice_s.iter().map(|&x| p.crown_drop * (2.0 * x / l).powi(2)).collect();
        let e_prime = contact::effective_modulus(b.roller_material.e, b.roller_material.nu, b.ring_material.e, b.ring_material.nu);

        let surface = |sign: f64| -> Vec<Vec2> {
            slice_s
                .iter()
                .zip(&slice_radius)
                .map(|(&x, &r)| {
                    [
                        center[0] + x * axis[0] + sign * r * perp[0],
                        center[1] + x * axis[1] + sign * r * perp[1],
                    ]
                })
                .collect()
        };
        let make_line = |points: Vec<Vec2>, normal: Vec2, race_angle: f64, convex: bool| -> ContactLine {
            let lever = points
                .iter()
                .map(|pt| cross([pt[0] - center[0], pt[1] - center[1]], normal))
                .collect();
            let raceway_radius: Vec<f64> = points.iter().map(|pt| pt[1]).collect();
            let raceway_curvature_radius: Vec<f64> = raceway_radius
                .iter()
                .map(|&r| {
                    if libm::cos(race_angle) > 0.0 {
                        (if convex { 1.0 } else { -1.0 }) * r / libm::cos(race_angle)
                    } else {
                        f64::INFINITY
                    }
                })
                .collect();
            let r_bar: Vec<f64> = slice_radius
                .iter()
                .zip(&raceway_curvature_radius)
                .map(|(&rr, &rc)| 1.0 / (libm::cos(ah) / rr + 1.0 / rc))
                .collect();
            let law = match b.contact_law {
                ContactLaw::Johnson => contact::LineLaw::johnson(e_prime, slice_len, &r_bar),
                ContactLaw::JohnsonW25 => contact::LineLaw::johnson_w25(e_prime, slice_len, &r_bar),
                ContactLaw::Palmgren => contact::LineLaw::palmgren(l, s),
            };
            ContactLine {
                point: points,
                normal,
                lever,
                r_bar,
                raceway_radius,
                raceway_curvature_radius,
                law,
            }
        };
        let cone = make_line(surface(-1.0), [libm::sin(ai), libm::cos(ai)], ai, true);
        let cup = make_line(surface(1.0), [-libm::sin(ao), -libm::cos(ao)], ao, false);

        let flange = b.flange_angle.map(|af| {
            let rs = b.roller_end_radius;
            let n = [libm::sin(af), -libm::cos(af)];
            let sphere_center = [center[0] + (-0.5 * l + rs) * axis[0], center[1] + (-0.5 * l + rs) * axis[1]];
            let point = [sphere_center[0] - rs * n[0], sphere_center[1] - rs * n[1]];
            let rel = [point[0] - center[0], point[1] - center[1]];
            let offset = rel[0] * perp[0] + rel[1] * perp[1];
            let rib_radius = point[1];
            // Principal radii at the contact: meridian direction of the rib is straight, its
            // circumferential direction is concave towards the roller (centre on the axis).
            // A rib whose circumferential radius nearly matches the sphere (32018X: R_s / rho_p =
            // 1.0003) would make the contact conformal; the relative curvature is floored at
            // 1 % of the sphere's (ellipse radius ratio <= 100, the Hamrock-Brewe range).
            let r_meridian = rs;
            let kappa = (1.0 / rs - libm::cos(af) / rib_radius).max(MIN_RELATIVE_CURVATURE / rs);
            let r_circ = 1.0 / kappa;
            let e_f = contact::effective_modulus(b.roller_material.e, b.roller_material.nu, b.ring_material.e, b.ring_material.nu);
            FlangeContact {
                point,
                normal: n,
                lever: cross(rel, n),
                rib_radius,
                offset,
                hertz: contact::PointContact::new(r_meridian, r_circ, e_f),
            }
        });

        let (roller_mass, inertia_axial, inertia_transverse, cm_offset) =
            frustum_mass_properties(rm, libm::tan(ah), l, b.roller_material.density);

        Geometry {
            z: b.roller_count,
            slices: s,
            cone_angle: ai,
            cup_angle: ao,
            half_angle: ah,
            axis_angle: ar,
            center,
            axis,
            perp,
            length: l,
            mean_radius: rm,
            slice_s,
            slice_len,
            slice_radius,
            crown,
            cone,
            cup,
            flange,
            e_prime,
            roller_mass,
            inertia_axial,
            inertia_transverse,
            cm_offset,
            axial: b.has_axial_stiffness(),
        }
    }

    /// Contact radii from the bearing axis at mid-roller on the cone and cup.
    pub fn pitch_contact_radii(&self) -> (f64, f64) {
        let rm = self.mean_radius;
        let c = self.center;
        let ri = c[1] - rm * self.perp[1];
        let ro = c[1] + rm * self.perp[1];
        (ri, ro)
    }
}

/// Mass, axial and transverse (about the centre of mass) inertia, and centre-of-mass offset
/// along the axis of a truncated cone with radius `r(x) = rm - x tan_h` for x in [-l/2, l/2].
/// Gauss-Legendre with 5 points integrates these polynomials (degree <= 6) exactly.
pub fn frustum_mass_properties(rm: f64, tan_h: f64, l: f64, density: f64) -> (f64, f64, f64, f64) {
    const X: [f64; 5] = [
        -0.906_179_845_938_664,
        -0.538_469_310_105_683,
        0.0,
        0.538_469_310_105_683,
        0.906_179_845_938_664,
    ];
    const W: [f64; 5] = [
        0.236_926_885_056_189,
        0.478_628_670_499_366,
        0.568_888_888_888_889,
        0.478_628_670_499_366,
        0.236_926_885_056_189,
    ];
    let half = 0.5 * l;
    let (mut m, mut mx, mut ia, mut ixx2, mut ir2) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for k in 0..5 {
        let x = half * X[k];
        let w = half * W[k];
        let r = rm - x * tan_h;
        let dm = density * std::f64::consts::PI * r * r * w;
        m += dm;
        mx += dm * x;
        ia += 0.5 * dm * r * r;
        ixx2 += dm * x * x;
        ir2 += 0.25 * dm * r * r;
    }
    let xc = mx / m;
    let it = ir2 + ixx2 - m * xc * xc;
    (m, ia, it, xc)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bearing::Bearing;

    fn geometry(name: &str) -> Geometry {
        let b = Bearing::preset(name).unwrap();
        Geometry::new(&b, &RollerProfile::of_bearing(&b))
    }

    /// R_s / rho_p of a loaded bearing, rho_p = r_f / cos(a_f) from the geometry's rib contact.
    fn end_radius_over_rib(b: &Bearing) -> f64 {
        let g = Geometry::new(b, &RollerProfile::of_bearing(b));
        let f = g.flange.as_ref().expect("a rib");
        b.roller_end_radius / (f.rib_radius / libm::cos(b.flange_angle.unwrap()))
    }

    #[test]
    fn the_end_radius_follows_its_ratio_to_the_rib() {
        // 32008 gives neither: the default ratio
        let b = Bearing::preset("32008").unwrap();
        assert!((end_radius_over_rib(&b) - crate::bearing::DEFAULT_END_RADIUS_RATIO).abs() < 1e-12);
        let text = crate::bearing::PRESETS.iter().find(|(n, _)| *n == "32008").expect("a preset").1;
        let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
        let mut last = 0.0;
        for k in [0.75, 0.85, 0.9, 0.95] {
            v["rollers"]["end_radius_ratio"] = serde_json::json!(k);
            let b = Bearing::from_json(&v.to_string()).unwrap();
            assert!((end_radius_over_rib(&b) - k).abs() < 1e-12, "{k}");
            assert!(b.roller_end_radius > last);
            last = b.roller_end_radius;
            if k == 0.9 {
                let d = Bearing::preset("32008").unwrap();
                assert_eq!(b.roller_end_radius.to_bits(), d.roller_end_radius.to_bits());
            }
        }
    }

    #[test]
    fn cylinder_mass_properties_match_closed_form() {
        let (r, l, rho) = (0.01, 0.03, 7850.0);
        let (m, ia, it, xc) = frustum_mass_properties(r, 0.0, l, rho);
        let m0 = rho * std::f64::consts::PI * r * r * l;
        assert!((m - m0).abs() < 1e-12 * m0);
        assert!((ia - 0.5 * m0 * r * r).abs() < 1e-12 * ia);
        assert!((it - m0 * (3.0 * r * r + l * l) / 12.0).abs() < 1e-12 * it);
        assert!(xc.abs() < 1e-15);
    }

    #[test]
    fn frustum_mass_matches_closed_form() {
        let (r1, r2, l, rho) = (0.012_f64, 0.009_f64, 0.04, 7850.0);
        let rm = 0.5 * (r1 + r2);
        let tan_h = (r1 - r2) / l;
        let (m, ia, _, xc) = frustum_mass_properties(rm, tan_h, l, rho);
        let v = std::f64::consts::PI * l / 3.0 * (r1 * r1 + r1 * r2 + r2 * r2);
        assert!((m - rho * v).abs() < 1e-12 * m);
        let ia0 = std::f64::consts::PI * rho * l / 10.0 * (r1.powi(5) - r2.powi(5)) / (r1 - r2);
        assert!((ia - ia0).abs() < 1e-12 * ia0);
        // centre of mass towards the large end (negative x)
        assert!(xc < 0.0);
    }

    #[test]
    fn contact_normals_are_perpendicular_to_generatrices() {
        let g = geometry("TRB130x230-W25");
        let k = g.slices - 1;
        for line in [&g.cone, &g.cup] {
            let d = [line.point[k][0] - line.point[0][0], line.point[k][1] - line.point[0][1]];
            let dot = d[0] * line.normal[0] + d[1] * line.normal[1];
            assert!(dot.abs() < 1e-12, "generatrix not normal to the contact normal: {dot}");
        }
        // Cone radius shrinks towards the apex at +x.
        assert!(g.cone.raceway_radius[k] < g.cone.raceway_radius[0]);
    }

    #[test]
    fn flange_contact_sits_on_the_end_face_towards_the_cone() {
        let g = geometry("TRB130x230-W25");
        let f = g.flange.as_ref().unwrap();
        // [W25]: 83 deg flange angle, 5 deg cone, 5 deg half angle -> 3 deg off the axis.
        let expect = 0.15395 * 3.0_f64.to_radians().sin();
        assert!((f.offset + expect).abs() < 1e-9, "offset {}", f.offset);
        assert!(f.rib_radius < g.center[1]);
        // flange pushes the roller towards the apex
        assert!(f.normal[0] > 0.9);
    }
}
