//! A local defect (a spall or a dent) on the cup raceway, on the cone raceway or on one
//! roller: where it is, its size, its edges, and how far a surface drops into it (parameters
//! `defect.*`).
//!
//! The defect is a pit: `length` along the rolling direction (an arc of the raceway at its mid
//! radius, or of the roller at its mean radius), `width` across it (along the generatrix,
//! centred on the raceway's or the roller's middle), `depth` below the surface, centred at
//! `angle`: on the cup at that azimuth (measured like `roller[j].azimuth`: from +y towards +z);
//! on the cone at that angle of the cone's own material frame, which coincides with the
//! azimuth at t = 0 and turns with the cone; on roller `defect.roller` at that angle of its
//! circumference, measured about its axis from its outward normal (towards the cup) at t = 0,
//! turning with its spin. A contact over it loses interference by the drop d of the one
//! surface into the other's pit:
//!
//! - sharp edges (`defect.edge` = 0; Sawalhi & Randall, Mech. Syst. Signal Process. 22 (2008)
//!   1924, for a ball): the surface bridging a pit of length L cannot reach below the chord
//!   its two edges cut. In the rolling direction the roller of radius R and the raceway of
//!   signed principal radius r (+ convex cone, − concave cup) curve apart by the relative
//!   curvature 1/R_e = 1/R + 1/r, so with the contact point at a distance e from the nearer
//!   edge, d = min(H, R_e − √(R_e² − e²)) (for a ball over a flat race R_e is the ball's
//!   radius, Sawalhi & Randall's case). The drop grows from the entry edge, is largest in the
//!   middle (R_e − √(R_e² − (L/2)²) unless the pit is shallower), and falls at the exit edge
//!   with the slope e / √(R_e² − e²): the roller strikes the far edge.
//! - rounded edges (`defect.edge` = 1): a worn dent, d = d_max sin(π (x + L/2) / L) over the
//!   pit, with the same largest drop d_max = min(H, R_e − √(R_e² − (L/2)²)); smooth in and out.
//!
//! A roller slice is over the defect when its contact point is: the slice is the model's
//! resolution across the raceway. The drop's slope along the rolling direction tilts the
//! contact normal as a lobe's does (`dynamic/contacts.rs`), so the contact force stays the
//! gradient of its energy and the energy books close. A defect longer than the roller's
//! diameter is not a local defect (the roller would fall to its bottom) and is refused.

use crate::geometry::{ContactLine, Vec2};
use std::f64::consts::PI;

/// The defect's edge shape (`defect.edge`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Edge {
    /// Sharp edges: the surfaces' relative curvature limits the drop (Sawalhi & Randall 2008).
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
    /// On the cone raceway, turning with the cone.
    Cone = 2,
    /// On one roller's surface (`defect.roller`), turning with its spin.
    Roller = 3,
}

impl DefectRing {
    /// The location of `defect.ring`'s value, None outside 0..=3.
    pub fn from_index(i: i32) -> Option<DefectRing> {
        [DefectRing::None, DefectRing::Cup, DefectRing::Cone, DefectRing::Roller]
            .get(usize::try_from(i).ok()?)
            .copied()
    }
}

/// The defect parameters as the user sets them.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DefectParameters {
    pub ring: DefectRing,
    /// The defective roller (1 ..= Z) for a roller defect.
    #[serde(default = "first_roller")]
    pub roller: u32,
    pub angle: f64,
    pub length: f64,
    pub width: f64,
    pub depth: f64,
    pub edge: Edge,
}

fn first_roller() -> u32 {
    1
}

impl Default for DefectParameters {
    fn default() -> DefectParameters {
        DefectParameters {
            ring: DefectRing::None,
            roller: 1,
            angle: 0.0,
            length: 0.0,
            width: 0.0,
            depth: 0.0,
            edge: Edge::Sharp,
        }
    }
}

/// The pit's profile along the rolling direction: half its length, its depth, the radius
/// whose circle bridges it, its edges and its largest drop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pit {
    pub half_length: f64,
    pub depth: f64,
    /// The radius of relative curvature R_e of the two surfaces in the rolling direction (m).
    pub edge_radius: f64,
    pub edge: Edge,
    /// The largest drop (m): min(depth, R_e − √(R_e² − (L/2)²)).
    pub max_drop: f64,
}

impl Pit {
    fn new(p: &DefectParameters, edge_radius: f64) -> Pit {
        let half_length = 0.5 * p.length;
        let sag = edge_radius - (edge_radius * edge_radius - half_length * half_length).max(0.0).sqrt();
        Pit {
            half_length,
            depth: p.depth,
            edge_radius,
            edge: p.edge,
            max_drop: p.depth.min(sag),
        }
    }

    /// The drop (m) at `x` (m) from the pit's centre along the rolling direction, and its
    /// derivative in x. Zero outside the pit.
    #[inline]
    pub fn drop(&self, x: f64) -> (f64, f64) {
        if x.abs() >= self.half_length {
            return (0.0, 0.0);
        }
        match self.edge {
            Edge::Sharp => {
                // distance from the nearer edge; the bridging circle's sag there
                let e = self.half_length - x.abs();
                let r = self.edge_radius;
                let root = (r * r - e * e).max(0.0).sqrt();
                let sag = r - root;
                if sag >= self.depth {
                    (self.depth, 0.0)
                } else {
                    // d(sag)/dx = e / root * de/dx, de/dx = -sign(x)
                    let slope = if root > 0.0 { e / root } else { 0.0 };
                    (sag, -x.signum() * slope)
                }
            }
            Edge::Rounded => {
                let phase = PI * (x + self.half_length) / (2.0 * self.half_length);
                let (s, c) = libm::sincos(phase);
                (self.max_drop * s, self.max_drop * c * PI / (2.0 * self.half_length))
            }
        }
    }
}

/// The angle `a` − `b` wrapped to (−π, π].
#[inline]
fn wrapped(a: f64, b: f64) -> f64 {
    (a - b + PI).rem_euclid(2.0 * PI) - PI
}

/// The relative-curvature radius R_e of a roller of radius `roller_radius` on the raceway
/// `line` (its principal radius in the rolling direction at the middle slice).
fn edge_radius(roller_radius: f64, line: &ContactLine) -> f64 {
    let r = line.raceway_curvature_radius[line.raceway_curvature_radius.len() / 2];
    1.0 / (1.0 / roller_radius + 1.0 / r)
}

/// A raceway defect (cup or cone) in the units the contact laws take.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RacewayDefect {
    /// Angle of the defect's centre in the ring's frame (rad).
    pub angle: f64,
    /// Half its width (m).
    pub half_width: f64,
    pub pit: Pit,
    /// How far from a roller's azimuth along the rolling direction its slices' contacts reach
    /// (m): its radius.
    roller_radius: f64,
    /// The raceway's middle (x, r) in the axial plane and its generatrix direction: where a
    /// contact point lies across the raceway ([`RacewayDefect::station`]).
    mid: Vec2,
    dir: Vec2,
}

impl RacewayDefect {
    /// The defect of `p` if it sits on `ring` (cup or cone), whose raceway is `line`, under
    /// rollers of (mean) radius `roller_radius`; None otherwise.
    pub fn new(p: &DefectParameters, ring: DefectRing, roller_radius: f64, line: &ContactLine) -> Option<RacewayDefect> {
        if p.ring != ring || !matches!(ring, DefectRing::Cup | DefectRing::Cone) {
            return None;
        }
        let points = &line.point;
        let (a, e) = (points[0], points[points.len() - 1]);
        let (dx, dr) = (e[0] - a[0], e[1] - a[1]);
        let len = (dx * dx + dr * dr).sqrt().max(f64::MIN_POSITIVE);
        Some(RacewayDefect {
            angle: p.angle,
            half_width: 0.5 * p.width,
            pit: Pit::new(p, edge_radius(roller_radius, line)),
            roller_radius,
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

    /// The drop (m) of a contact point at angle `psi` of the ring's frame, radius `rho` from
    /// the bearing axis and generatrix station `s` (from the raceway's middle), and the drop's
    /// derivative along that angle (m/rad). Zero outside the defect.
    #[inline]
    pub fn drop(&self, psi: f64, rho: f64, s: f64) -> (f64, f64) {
        if s.abs() > self.half_width {
            return (0.0, 0.0);
        }
        // arc from the defect's centre along the rolling direction; dx/dpsi = rho
        let (d, slope) = self.pit.drop(wrapped(psi, self.angle) * rho);
        (d, slope * rho)
    }

    /// Whether a roller whose centre is at angle `psi` of the ring's frame, `rho` from the
    /// axis, can touch the defect: its slices' contacts lie within its radius of its azimuth
    /// along the rolling direction. The cheap test before the contact closure.
    #[inline]
    pub fn near(&self, psi: f64, rho: f64) -> bool {
        (wrapped(psi, self.angle) * rho).abs() < self.pit.half_length + self.roller_radius
    }
}

/// A defect on one roller's surface in the units the contact laws take: the pit as the cup and
/// as the cone bridge it (their relative curvatures differ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerDefect {
    /// The defective roller (0-based).
    pub roller: usize,
    /// Angle of the defect's centre on the roller's circumference, from its outward normal at
    /// t = 0 (rad).
    pub angle: f64,
    /// Half its width along the roller's axis (m), centred on the roller's middle.
    pub half_width: f64,
    /// The roller's mean radius (m): arcs on its surface are angles times it.
    pub radius: f64,
    /// The pit against the cup and against the cone.
    pub on_cup: Pit,
    pub on_cone: Pit,
}

impl RollerDefect {
    /// The defect of `p` if it sits on a roller, with rollers of mean radius `roller_radius`
    /// on the raceways `cup` and `cone`.
    pub fn new(p: &DefectParameters, roller_radius: f64, cup: &ContactLine, cone: &ContactLine) -> Option<RollerDefect> {
        if p.ring != DefectRing::Roller {
            return None;
        }
        Some(RollerDefect {
            roller: p.roller.saturating_sub(1) as usize,
            angle: p.angle,
            half_width: 0.5 * p.width,
            radius: roller_radius,
            on_cup: Pit::new(p, edge_radius(roller_radius, cup)),
            on_cone: Pit::new(p, edge_radius(roller_radius, cone)),
        })
    }

    /// The drop (m) of a contact at body angle `chi` of the roller (from the defect's frame
    /// origin, turned with the spin) and axial station `s` from the roller's middle, against
    /// the raceway whose pit is `pit`, and its derivative along the roller's circumference
    /// (per metre of arc).
    #[inline]
    pub fn drop(&self, pit: &Pit, chi: f64, s: f64) -> (f64, f64) {
        if s.abs() > self.half_width {
            return (0.0, 0.0);
        }
        pit.drop(wrapped(chi, self.angle) * self.radius)
    }
}

/// The defects beside the first (`defect.*`) that a bearing may have: `defect[2].*` to
/// `defect[4].*`.
pub const FURTHER_DEFECTS: usize = 3;

/// The FMU names of one defect's parameters.
#[derive(Debug, Clone, Copy)]
pub struct DefectNames {
    pub roller: &'static str,
    pub angle: &'static str,
    pub length: &'static str,
    pub width: &'static str,
    pub depth: &'static str,
}

macro_rules! names {
    ($p:literal) => {
        DefectNames {
            roller: concat!($p, ".roller"),
            angle: concat!($p, ".angle"),
            length: concat!($p, ".length"),
            width: concat!($p, ".width"),
            depth: concat!($p, ".depth"),
        }
    };
}

/// The names of the first defect's parameters and of the further ones', in order.
pub const NAMES: [DefectNames; 1 + FURTHER_DEFECTS] = [names!("defect"), names!("defect[2]"), names!("defect[3]"), names!("defect[4]")];

/// Every local defect of a bearing in the units the contact laws take, by where it sits. Two
/// pits of one surface that overlap drop as deep as the deeper one; a pit on the raceway and
/// one on the roller under the same contact add.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LocalDefects {
    pub cup: Vec<RacewayDefect>,
    pub cone: Vec<RacewayDefect>,
    pub rollers: Vec<RollerDefect>,
}

impl LocalDefects {
    /// The defects `defects` (those with `ring` = none left out) of a bearing whose rollers
    /// of mean radius `roller_radius` run on the raceways `cup` and `cone`.
    pub fn new<'a>(
        defects: impl Iterator<Item = &'a DefectParameters>,
        roller_radius: f64,
        cup: &ContactLine,
        cone: &ContactLine,
    ) -> LocalDefects {
        let mut all = LocalDefects::default();
        for p in defects {
            all.cup.extend(RacewayDefect::new(p, DefectRing::Cup, roller_radius, cup));
            all.cone.extend(RacewayDefect::new(p, DefectRing::Cone, roller_radius, cone));
            all.rollers.extend(RollerDefect::new(p, roller_radius, cup, cone));
        }
        all
    }

    pub fn is_empty(&self) -> bool {
        self.cup.is_empty() && self.cone.is_empty() && self.rollers.is_empty()
    }

    /// The drop (m) of a contact point of a raceway with the defects `on` (the cup's or the
    /// cone's) at angle `psi` of the ring's frame, axial position `x` and radius `rho`, and its
    /// derivative along that angle (m/rad): the deepest of the pits it lies in.
    #[inline]
    pub fn raceway_drop(on: &[RacewayDefect], psi: f64, x: f64, rho: f64) -> (f64, f64) {
        deepest(on.iter().map(|d| d.drop(psi, rho, d.station(x, rho))))
    }

    /// Whether a roller at angle `psi` of the ring's frame, `rho` from the axis, can touch one
    /// of the defects `on`.
    #[inline]
    pub fn near(on: &[RacewayDefect], psi: f64, rho: f64) -> bool {
        on.iter().any(|d| d.near(psi, rho))
    }

    /// The defects of roller `j` (0-based).
    pub fn of_roller(&self, j: usize) -> impl Iterator<Item = &RollerDefect> {
        self.rollers.iter().filter(move |d| d.roller == j)
    }

    /// The drop (m) of roller `j`'s surface at body angle `chi` and axial station `s`
    /// against the cup (`on_cup`) or the cone, and its derivative per metre of arc: the
    /// deepest of its pits there.
    #[inline]
    pub fn roller_drop(&self, j: usize, on_cup: bool, chi: f64, s: f64) -> (f64, f64) {
        deepest(
            self.of_roller(j)
                .map(|d| d.drop(if on_cup { &d.on_cup } else { &d.on_cone }, chi, s)),
        )
    }

    /// The rollers (0-based, ascending, each once) that carry a defect.
    pub fn defective_rollers(&self) -> Vec<usize> {
        let mut js: Vec<usize> = self.rollers.iter().map(|d| d.roller).collect();
        js.sort_unstable();
        js.dedup();
        js
    }
}

/// The deepest of `drops` (drop, its derivative); (0, 0) for none.
#[inline]
fn deepest(drops: impl Iterator<Item = (f64, f64)>) -> (f64, f64) {
    drops.fold((0.0, 0.0), |deepest, drop| if drop.0 > deepest.0 { drop } else { deepest })
}

/// Check the defect parameters against the bearing: `raceway_length` (m) the rollers' contact
/// length along the generatrix, `circumference` (m) the raceway's at its mid radius, `roller_
/// diameter` (m) the rollers' mean diameter, `rollers` their number. The first bad value: its
/// parameter's name and what is wrong.
pub fn validate(
    p: &DefectParameters,
    names: &DefectNames,
    raceway_length: f64,
    circumference: f64,
    roller_diameter: f64,
    rollers: usize,
) -> Result<(), (&'static str, String)> {
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
    if p.ring == DefectRing::Roller && !(1..=rollers).contains(&(p.roller as usize)) {
        return Err((
            names.roller,
            format!("must name one of the {rollers} rollers (1 to {rollers}), got {}", p.roller),
        ));
    }
    finite(names.angle, p.angle)?;
    finite(names.length, p.length)?;
    finite(names.width, p.width)?;
    finite(names.depth, p.depth)?;
    if !(p.length > 0.0) {
        return Err((names.length, format!("must be positive, got {} m", p.length)));
    }
    if p.length >= roller_diameter || p.length >= circumference {
        return Err((
            names.length,
            format!(
                "{} m: a roller of {:.4} m diameter would fall to the bottom of a defect this long; a local defect is shorter than the roller's diameter",
                p.length, roller_diameter
            ),
        ));
    }
    if !(p.width > 0.0) {
        return Err((names.width, format!("must be positive, got {} m", p.width)));
    }
    if p.width > raceway_length {
        return Err((
            names.width,
            format!(
                "{} m reaches outside the raceway: the rollers' contact length is {:.4} m",
                p.width, raceway_length
            ),
        ));
    }
    if !(p.depth > 0.0) {
        return Err((names.depth, format!("must be positive, got {} m", p.depth)));
    }
    if p.depth > 0.5 * roller_diameter {
        return Err((
            names.depth,
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

    /// A cup contact line 20 mm long at 0.1 m from the axis (concave, radius 0.1 m).
    fn line() -> ContactLine {
        let b = crate::bearing::Bearing::preset("TRB130x230").unwrap();
        let mut line = crate::geometry::Geometry::new(&b, &crate::geometry::RollerProfile::of_bearing(&b)).cup;
        line.point = vec![[0.0, 0.1], [0.02, 0.1]];
        line.raceway_curvature_radius = vec![-0.1; 2];
        line
    }

    fn defect(edge: Edge, depth: f64) -> RacewayDefect {
        let p = DefectParameters {
            ring: DefectRing::Cup,
            roller: 1,
            angle: 0.3,
            length: 2e-3,
            width: 5e-3,
            depth,
            edge,
        };
        RacewayDefect::new(&p, DefectRing::Cup, 10e-3, &line()).unwrap()
    }

    /// The drop is zero outside the pit and at its edges, largest in its middle at the
    /// bridging circle's sag R_e − √(R_e² − (L/2)²) (a shallower pit: its depth), and its azimuthal
    /// derivative is the drop's slope (central differences).
    #[test]
    fn the_drop_follows_the_rollers_circle_and_its_slope_is_the_derivative() {
        let rho = 0.1;
        // the roller (10 mm) in the concave cup (0.1 m): R_e = 1 / (1/R - 1/r)
        let re: f64 = 1.0 / (1.0 / 10e-3 - 1.0 / 0.1);
        let sag = re - (re * re - 1e-6).sqrt();
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
            roller: 1,
            angle: -3.14,
            length: 2e-3,
            width: 5e-3,
            depth: 1e-3,
            edge: Edge::Sharp,
        };
        let wrap = RacewayDefect::new(&p, DefectRing::Cup, 10e-3, &line()).unwrap();
        assert!(wrap.drop(3.14, rho, 0.0).0 > 0.0);
    }

    /// Defects outside the raceway, longer than a roller or deeper than it reaches are refused
    /// by name; no defect is never refused.
    #[test]
    fn bad_defects_are_refused_by_name() {
        let good = DefectParameters {
            ring: DefectRing::Cup,
            roller: 1,
            angle: 0.0,
            length: 2e-3,
            width: 5e-3,
            depth: 50e-6,
            edge: Edge::Sharp,
        };
        let check = |p: DefectParameters| validate(&p, &NAMES[0], 30e-3, 0.6, 20e-3, 17);
        assert!(check(good).is_ok());
        for (bad, name) in [
            (DefectParameters { width: 40e-3, ..good }, "defect.width"),
            (DefectParameters { length: 25e-3, ..good }, "defect.length"),
            (DefectParameters { length: 0.0, ..good }, "defect.length"),
            (DefectParameters { depth: 15e-3, ..good }, "defect.depth"),
            (DefectParameters { depth: -1.0, ..good }, "defect.depth"),
            (DefectParameters { angle: f64::NAN, ..good }, "defect.angle"),
            (
                DefectParameters {
                    ring: DefectRing::Roller,
                    roller: 18,
                    ..good
                },
                "defect.roller",
            ),
            (
                DefectParameters {
                    ring: DefectRing::Roller,
                    roller: 0,
                    ..good
                },
                "defect.roller",
            ),
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
