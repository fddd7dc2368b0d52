//! A local defect on the cup raceway (a spall or a dent): where it is, its size, its edges, and
//! how far a roller drops into it (parameters `defect.*`).
//!
//! The defect is a pit in the raceway: `length` along the rolling direction (an arc of the
//! raceway at its mid radius), `width` across it (along the generatrix, centred on the
//! raceway's middle), `depth` below the surface, centred at the azimuth `angle` (measured like
//! `roller[j].azimuth`: from +y towards +z). A roller that stands over it loses contact
//! interference by the drop d of its surface into the pit:
//!
//! - sharp edges (`defect.edge` = 0; Sawalhi & Randall, Mech. Syst. Signal Process. 22 (2008)
//!   1924, for a ball; the same geometry for a roller's circle): a rigid circle of radius R
//!   over a pit of length L cannot reach below the chord its two edges cut, so with its
//!   contact point at a distance e from the nearer edge, d = min(H, R − √(R² − e²)). The drop
//!   grows from the entry edge, is largest in the middle (R − √(R² − (L/2)²) unless the pit is
//!   shallower), and falls at the exit edge with the slope e / √(R² − e²): the roller strikes
//!   the far edge.
//! - rounded edges (`defect.edge` = 1): a worn dent, d = d_max sin(π (x + L/2) / L) over the
//!   pit, with the same largest drop d_max = min(H, R − √(R² − (L/2)²)); smooth in and out.
//!
//! A roller slice is over the defect when its contact point is: the slice is the model's
//! resolution across the raceway. The drop's slope along the azimuth tilts the raceway normal
//! as a lobe's does (`dynamic/contacts.rs`), so the contact force stays the gradient of its
//! energy and the energy books close. A defect longer than the roller's diameter is not a
//! local defect (the roller would fall to its bottom) and is refused.

use crate::geometry::Vec2;
use std::f64::consts::PI;

/// The defect's edge shape (`defect.edge`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Edge {
    /// Sharp edges: the roller's circle limits its drop (Sawalhi & Randall 2008).
    #[default]
    Sharp = 0,
    /// Rounded edges: a half-sine dent.
    Rounded = 1,
}

/// Where a defect sits (`defect.ring`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum DefectRing {
    /// No defect (the default).
    #[default]
    None = 0,
    /// On the cup raceway.
    Cup = 1,
}

/// The defect parameters as the user sets them.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DefectParameters {
    pub ring: DefectRing,
    pub angle: f64,
    pub length: f64,
    pub width: f64,
    pub depth: f64,
    pub edge: Edge,
}

/// A cup defect in the units the contact laws take: half-angles and the drop's limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CupDefect {
    /// Azimuth of the defect's centre (rad).
    pub angle: f64,
    /// Half its length (m) and half its width (m).
    pub half_length: f64,
    pub half_width: f64,
    /// Its depth (m).
    pub depth: f64,
    /// The roller radius whose circle limits the drop (m).
    pub roller_radius: f64,
    pub edge: Edge,
    /// The largest drop (m): min(depth, R − √(R² − (L/2)²)).
    pub max_drop: f64,
    /// The raceway's middle (x, r) in the axial plane and its generatrix direction: where a
    /// contact point lies across the raceway ([`CupDefect::station`]).
    mid: Vec2,
    dir: Vec2,
}

impl CupDefect {
    /// The defect of `p` on the cup raceway whose slice contact points (x, r) are `points`
    /// (from one end of the contact line to the other), under rollers of (mean) radius
    /// `roller_radius`; None without a defect.
    pub fn new(p: &DefectParameters, roller_radius: f64, points: &[Vec2]) -> Option<CupDefect> {
        if p.ring != DefectRing::Cup {
            return None;
        }
        let half_length = 0.5 * p.length;
        let sag = roller_radius - (roller_radius * roller_radius - half_length * half_length).max(0.0).sqrt();
        let (a, e) = (points[0], points[points.len() - 1]);
        let (dx, dr) = (e[0] - a[0], e[1] - a[1]);
        let len = (dx * dx + dr * dr).sqrt().max(f64::MIN_POSITIVE);
        Some(CupDefect {
            angle: p.angle,
            half_length,
            half_width: 0.5 * p.width,
            depth: p.depth,
            roller_radius,
            edge: p.edge,
            max_drop: p.depth.min(sag),
            mid: [0.5 * (a[0] + e[0]), 0.5 * (a[1] + e[1])],
            dir: [dx / len, dr / len],
        })
    }

    /// The generatrix station (m, from the raceway's middle) of a point at axial position `x`
    /// and distance `rho` from the bearing axis.
    #[inline]
    pub fn station(&self, x: f64, rho: f64) -> f64 {
        (x - self.mid[0]) * self.dir[0] + (rho - self.mid[1]) * self.dir[1]
    }

    /// The drop (m) of a contact point at azimuth `psi`, radius `rho` from the bearing axis
    /// and generatrix station `s` (from the raceway's middle), and the drop's derivative along
    /// the azimuth (m/rad). Zero outside the defect.
    #[inline]
    pub fn drop(&self, psi: f64, rho: f64, s: f64) -> (f64, f64) {
        if s.abs() > self.half_width {
            return (0.0, 0.0);
        }
        // arc from the defect's centre along the rolling direction
        let dpsi = (psi - self.angle + PI).rem_euclid(2.0 * PI) - PI;
        let x = dpsi * rho;
        if x.abs() >= self.half_length {
            return (0.0, 0.0);
        }
        match self.edge {
            Edge::Sharp => {
                // distance from the nearer edge; the circle's sag there
                let e = self.half_length - x.abs();
                let r = self.roller_radius;
                let root = (r * r - e * e).max(0.0).sqrt();
                let sag = r - root;
                if sag >= self.depth {
                    (self.depth, 0.0)
                } else {
                    // d(sag)/dx = e / root * de/dx, de/dx = -sign(x); dx/dpsi = rho
                    let slope = if root > 0.0 { e / root } else { 0.0 };
                    (sag, -x.signum() * slope * rho)
                }
            }
            Edge::Rounded => {
                let phase = PI * (x + self.half_length) / (2.0 * self.half_length);
                let (s, c) = libm::sincos(phase);
                (self.max_drop * s, self.max_drop * c * PI / (2.0 * self.half_length) * rho)
            }
        }
    }

    /// Whether a roller whose centre is at azimuth `psi`, `rho` from the axis, can touch the
    /// defect: its slices' contacts lie within its radius of its azimuth along the rolling
    /// direction. The cheap test before the contact closure.
    #[inline]
    pub fn near(&self, psi: f64, rho: f64) -> bool {
        let dpsi = (psi - self.angle + PI).rem_euclid(2.0 * PI) - PI;
        (dpsi * rho).abs() < self.half_length + self.roller_radius
    }
}

/// Check the defect parameters against the raceway: `raceway_length` (m) the cup's contact
/// length along the generatrix, `circumference` (m) the raceway's at its mid radius, `roller_
/// diameter` (m) the rollers' mean diameter. The first bad value: its parameter's name and
/// what is wrong.
pub fn validate(p: &DefectParameters, raceway_length: f64, circumference: f64, roller_diameter: f64) -> Result<(), (&'static str, String)> {
    if p.ring == DefectRing::None {
        return Ok(());
    }
    let finite = |name: &'static str, v: f64| {
        if v.is_finite() {
            Ok(())
        } else {
            Err((name, format!("must be finite, got {v}")))
        }
    };
    finite("defect.angle", p.angle)?;
    finite("defect.length", p.length)?;
    finite("defect.width", p.width)?;
    finite("defect.depth", p.depth)?;
    if !(p.length > 0.0) {
        return Err(("defect.length", format!("must be positive, got {} m", p.length)));
    }
    if p.length >= roller_diameter || p.length >= circumference {
        return Err((
            "defect.length",
            format!(
                "{} m: a roller of {:.4} m diameter would fall to the bottom of a defect this long; a local defect is shorter than the roller's diameter",
                p.length, roller_diameter
            ),
        ));
    }
    if !(p.width > 0.0) {
        return Err(("defect.width", format!("must be positive, got {} m", p.width)));
    }
    if p.width > raceway_length {
        return Err((
            "defect.width",
            format!(
                "{} m reaches outside the raceway: the cup's contact length is {:.4} m",
                p.width, raceway_length
            ),
        ));
    }
    if !(p.depth > 0.0) {
        return Err(("defect.depth", format!("must be positive, got {} m", p.depth)));
    }
    if p.depth > 0.5 * roller_diameter {
        return Err((
            "defect.depth",
            format!(
                "{} m is deeper than a roller of {:.4} m diameter can reach (its radius)",
                p.depth, roller_diameter
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cup contact line 20 mm long at 0.1 m from the axis.
    const LINE: [Vec2; 2] = [[0.0, 0.1], [0.02, 0.1]];

    fn defect(edge: Edge, depth: f64) -> CupDefect {
        let p = DefectParameters {
            ring: DefectRing::Cup,
            angle: 0.3,
            length: 2e-3,
            width: 5e-3,
            depth,
            edge,
        };
        CupDefect::new(&p, 10e-3, &LINE).unwrap()
    }

    /// The drop is zero outside the pit and at its edges, largest in its middle at the
    /// circle's sag R − √(R² − (L/2)²) (a shallower pit: its depth), and its azimuthal
    /// derivative is the drop's slope (central differences).
    #[test]
    fn the_drop_follows_the_rollers_circle_and_its_slope_is_the_derivative() {
        let rho = 0.1;
        let sag = 10e-3 - (1e-4_f64 - 1e-6).sqrt();
        for edge in [Edge::Sharp, Edge::Rounded] {
            let d = defect(edge, 1e-3);
            assert!((d.drop(0.3, rho, 0.0).0 - sag).abs() < 1e-15, "{edge:?}");
            assert_eq!(d.drop(0.3 + 0.011, rho, 0.0), (0.0, 0.0));
            assert_eq!(d.drop(0.3, rho, 3e-3), (0.0, 0.0));
            assert!(d.drop(0.3 + 0.0099999, rho, 0.0).0 < 1e-9);
            for psi in [0.291, 0.295, 0.2999, 0.3001, 0.304, 0.309] {
                let h = 1e-7;
                let numeric = (d.drop(psi + h, rho, 0.0).0 - d.drop(psi - h, rho, 0.0).0) / (2.0 * h);
                let analytic = d.drop(psi, rho, 0.0).1;
                assert!(
                    (numeric - analytic).abs() < 1e-5 * analytic.abs().max(1e-6),
                    "{edge:?} at {psi}: {numeric} vs {analytic}"
                );
            }
        }
        // a shallow pit: the roller reaches its bottom, which is flat
        let shallow = defect(Edge::Sharp, 10e-6);
        assert_eq!(shallow.drop(0.3, rho, 0.0), (10e-6, 0.0));
        // across the wrap of the azimuth
        let p = DefectParameters {
            ring: DefectRing::Cup,
            angle: -3.14,
            length: 2e-3,
            width: 5e-3,
            depth: 1e-3,
            edge: Edge::Sharp,
        };
        let wrap = CupDefect::new(&p, 10e-3, &LINE).unwrap();
        assert!(wrap.drop(3.14, rho, 0.0).0 > 0.0);
    }

    /// Defects outside the raceway, longer than a roller or deeper than it reaches are refused
    /// by name; no defect is never refused.
    #[test]
    fn bad_defects_are_refused_by_name() {
        let good = DefectParameters {
            ring: DefectRing::Cup,
            angle: 0.0,
            length: 2e-3,
            width: 5e-3,
            depth: 50e-6,
            edge: Edge::Sharp,
        };
        let check = |p: DefectParameters| validate(&p, 30e-3, 0.6, 20e-3);
        assert!(check(good).is_ok());
        for (bad, name) in [
            (DefectParameters { width: 40e-3, ..good }, "defect.width"),
            (DefectParameters { length: 25e-3, ..good }, "defect.length"),
            (DefectParameters { length: 0.0, ..good }, "defect.length"),
            (DefectParameters { depth: 15e-3, ..good }, "defect.depth"),
            (DefectParameters { depth: -1.0, ..good }, "defect.depth"),
            (DefectParameters { angle: f64::NAN, ..good }, "defect.angle"),
        ] {
            let (named, why) = check(bad).unwrap_err();
            assert_eq!(named, name, "{why}");
        }
        assert!(check(DefectParameters {
            ring: DefectRing::None,
            width: 1.0,
            ..good
        })
        .is_ok());
    }
}
