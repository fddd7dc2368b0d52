//! The FMU's icon `model.png` (FMI 2.0, archive root): an axial cross-section of the packaged
//! bearing, drawn to scale from its own data, as importers show it for the block.
//!
//! What is drawn, in the axial plane (x along the bearing axis, r radial), the half above the
//! axis and its mirror below, around a dash-dot axis line:
//! - the cup (outer ring) from the outside diameter down to its raceway, a line at the cup
//!   angle through the roller's cup contact ([`Geometry::cup`]); it spans from the roller's
//!   large end to the cup's back face;
//! - the cone (inner ring) from the bore up to its raceway at the cone angle through the
//!   cone contact ([`Geometry::cone`]), with the large-end rib whose face passes through the
//!   flange contact ([`Geometry::flange`]) normal to the flange contact normal, and a small
//!   lip at the small end;
//! - the roller, a trapezoid along its axis ([`Geometry::axis`], [`Geometry::perp`]) of the
//!   effective length with the end diameters of the half-cone angle, touching both raceways.
//!
//! Envelope (bore, outside diameter, width) from the [`Bearing`]; the roller sits axially in
//! the width with the spare room shared 3:2 between the large (rib) and the small end. A
//! cylindrical bearing (no flange in its data) gets straight raceways and a rib-less inner
//! ring; its outer ring has the two guiding ribs of an NU design, which carries no axial
//! load as the model assumes. Rings are steel grey and hatched (cup and cone in opposite
//! directions, each the same way above and below the axis, as in a drawing), the roller is a
//! darker solid. Lengths that would cross (a raceway through the bore or the outside
//! diameter, a rib above the roller) are clamped to a minimum wall, so any bearing the
//! validation lets through, and more, still gives a picture. Rasterising and PNG encoding:
//! `tiny-skia`; the same bearing gives the same bytes.

use tiny_skia::{Color, FillRule, LineCap, Mask, Paint, Path, PathBuilder, Pixmap, Rect, Stroke, StrokeDash, Transform};
use trb::bearing::{Bearing, Kind};
use trb::geometry::{Geometry, RollerProfile, Vec2};

/// Width and height of the icon (px).
pub const SIZE: u32 = 256;
/// Free border around the drawing (px).
const MARGIN: f64 = 8.0;
/// How far the axis line reaches past the bearing faces (px).
const AXIS_OVERHANG: f64 = 10.0;
/// Share of the axial room beside the roller that goes to the large (rib) end.
const LARGE_END_SHARE: f64 = 0.6;
/// Thinnest ring wall kept between a raceway and the bore or outside diameter, as a fraction
/// of the radial section height (outside diameter - bore) / 2.
const MIN_WALL: f64 = 0.04;

/// Steel grey of the rings.
pub const RING_RGB: [u8; 3] = [0xb4, 0xba, 0xc1];
/// Darker tone of the roller.
pub const ROLLER_RGB: [u8; 3] = [0x4d, 0x54, 0x5c];
const HATCH_RGB: [u8; 3] = [0x78, 0x7f, 0x87];
const OUTLINE_RGB: [u8; 3] = [0x23, 0x27, 0x2b];
const AXIS_RGB: [u8; 3] = [0x1d, 0x3f, 0x75];

/// The PNG icon (SIZE x SIZE, transparent background) of `bearing`.
pub fn model_png(bearing: &Bearing) -> Vec<u8> {
    let section = Section::new(bearing);
    render(&section).encode_png().expect("PNG encoding into memory does not fail")
}

/// The upper half of the axial section (metres): outlines of the parts and the envelope.
struct Section {
    cup: Vec<Vec2>,
    cone: Vec<Vec2>,
    roller: Vec<Vec2>,
    x_left: f64,
    x_right: f64,
    outer_radius: f64,
}

/// A raceway generatrix: a point on it and its slope dr/dx.
#[derive(Clone, Copy)]
struct Line {
    point: Vec2,
    slope: f64,
}

impl Line {
    /// The line through `point` normal to the contact normal `normal`.
    fn normal_to(point: Vec2, normal: Vec2) -> Line {
        Line {
            point,
            slope: finite_or(-normal[0] / normal[1], 0.0),
        }
    }

    fn r(&self, x: f64) -> f64 {
        self.point[1] + (x - self.point[0]) * self.slope
    }
}

/// Radial limits of the ring material: bore, outside radius and the thinnest wall.
struct Envelope {
    inner: f64,
    outer: f64,
    wall: f64,
}

impl Section {
    fn new(b: &Bearing) -> Section {
        let g = Geometry::new(b, &RollerProfile::of_bearing(b));
        let roller = roller_outline(&g);
        let (x_left, x_right) = axial_span(b, &roller);
        let inner = 0.5 * b.bore;
        let outer = 0.5 * b.outside_diameter;
        let env = Envelope {
            inner,
            outer,
            wall: MIN_WALL * (outer - inner).abs(),
        };
        let cone_line = Line::normal_to(contact_point(&g.cone.point, &g, -1.0), g.cone.normal);
        let cup_line = Line::normal_to(contact_point(&g.cup.point, &g, 1.0), g.cup.normal);
        let (cup, cone) = if b.kind == Kind::Cylindrical || g.flange.is_none() {
            let cup = ribbed_cup(&env, &roller, cup_line, (x_left, x_right));
            (cup, plain_cone(&env, cone_line, (x_left, x_right)))
        } else {
            let cup = tapered_cup(&env, &roller, cup_line, x_right);
            (cup, ribbed_cone(&env, &g, &roller, cone_line, (x_left, x_right)))
        };
        Section {
            cup,
            cone,
            roller: roller.to_vec(),
            x_left,
            x_right,
            outer_radius: outer,
        }
    }
}

fn finite_or(v: f64, fallback: f64) -> f64 {
    if v.is_finite() {
        v
    } else {
        fallback
    }
}

/// `v` limited to [lo, hi] without panicking (hi wins if they cross; NaN gives lo).
fn limit(v: f64, lo: f64, hi: f64) -> f64 {
    v.max(lo).min(hi)
}

fn along(p: Vec2, d: Vec2, t: f64) -> Vec2 {
    [p[0] + t * d[0], p[1] + t * d[1]]
}

/// A contact point of the raceway (the first slice's), or the roller surface at its centre.
fn contact_point(points: &[Vec2], g: &Geometry, side: f64) -> Vec2 {
    points
        .first()
        .copied()
        .unwrap_or_else(|| along(g.center, g.perp, side * g.mean_radius))
}

/// Roller corners: large end cone side, large end cup side, small end cup side, small end
/// cone side.
fn roller_outline(g: &Geometry) -> [Vec2; 4] {
    let half = 0.5 * g.length;
    let taper = half * g.half_angle.tan();
    let large = g.mean_radius + taper;
    let small = (g.mean_radius - taper).max(0.0);
    let large_end = along(g.center, g.axis, -half);
    let small_end = along(g.center, g.axis, half);
    [
        along(large_end, g.perp, -large),
        along(large_end, g.perp, large),
        along(small_end, g.perp, small),
        along(small_end, g.perp, -small),
    ]
}

/// Axial extent of the envelope: the width around the roller, the spare room shared
/// between the large and the small end.
fn axial_span(b: &Bearing, roller: &[Vec2; 4]) -> (f64, f64) {
    let lo = roller.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
    let hi = roller.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max);
    let room = (b.width - (hi - lo)).max(0.0);
    let share = if b.kind == Kind::Tapered { LARGE_END_SHARE } else { 0.5 };
    let left = lo - share * room;
    (left, left + (hi - lo) + room)
}

/// Cup of a tapered bearing: outside diameter over its raceway, from the roller's large end
/// to the back face at `x_right`.
fn tapered_cup(env: &Envelope, roller: &[Vec2; 4], race: Line, x_right: f64) -> Vec<Vec2> {
    let front = roller[1][0].min(x_right);
    let r = |x: f64| limit(race.r(x), env.inner + env.wall, env.outer - env.wall);
    vec![[front, env.outer], [x_right, env.outer], [x_right, r(x_right)], [front, r(front)]]
}

/// Outer ring of a cylindrical bearing: straight raceway between two guiding ribs.
fn ribbed_cup(env: &Envelope, roller: &[Vec2; 4], race: Line, span: (f64, f64)) -> Vec<Vec2> {
    let (x0, x1) = span;
    let r_race = limit(race.r(0.5 * (x0 + x1)), env.inner + env.wall, env.outer - env.wall);
    let depth = 0.3 * (roller[1][1] - roller[0][1]).abs();
    let r_rib = limit(r_race - depth, env.inner + env.wall, r_race);
    let (e0, e1) = (limit(roller[1][0], x0, x1), limit(roller[2][0], x0, x1));
    vec![
        [x0, env.outer],
        [x1, env.outer],
        [x1, r_rib],
        [e1, r_rib],
        [e1, r_race],
        [e0, r_race],
        [e0, r_rib],
        [x0, r_rib],
    ]
}

/// Inner ring without ribs: bore under a straight raceway over the whole width.
fn plain_cone(env: &Envelope, race: Line, span: (f64, f64)) -> Vec<Vec2> {
    let (x0, x1) = span;
    let r = |x: f64| limit(race.r(x), env.inner + env.wall, env.outer - env.wall);
    vec![[x0, env.inner], [x0, r(x0)], [x1, r(x1)], [x1, env.inner]]
}

/// Cone of a tapered bearing: bore, large rib (its face through the flange contact), the
/// raceway, a small lip past the roller's small end, front face.
fn ribbed_cone(env: &Envelope, g: &Geometry, roller: &[Vec2; 4], race: Line, span: (f64, f64)) -> Vec<Vec2> {
    let (x0, x1) = span;
    let r = |x: f64| limit(race.r(x), env.inner + env.wall, env.outer - env.wall);
    let mut out = vec![[x0, env.inner]];
    out.extend(large_rib(g, roller, race, x0, &r));
    out.extend(small_lip(roller, x1, &r));
    out.push([x1, env.inner]);
    out
}

/// The small lip past the roller's small end: a quarter of the end diameter high, clear of the
/// tilted end face, at most up to the roller axis.
fn small_lip(roller: &[Vec2; 4], x1: f64, r: &dyn Fn(f64) -> f64) -> [Vec2; 3] {
    let d = ((roller[2][0] - roller[3][0]).powi(2) + (roller[2][1] - roller[3][1]).powi(2)).sqrt();
    let lean = (roller[2][0] - roller[3][0]).max(0.0);
    let x = limit(roller[3][0] + 0.25 * lean + 0.08 * d, roller[3][0].min(x1), x1);
    let axis_r = 0.5 * (roller[2][1] + roller[3][1]);
    let top = limit(r(x) + 0.25 * d, r(x), axis_r.max(r(x)));
    [[x, r(x)], [x, top], [x1, top]]
}

/// The large rib's corners from the back face to the raceway: its top halfway between the
/// flange contact and the roller axis, its face along the rib (normal to the flange contact
/// normal).
fn large_rib(g: &Geometry, roller: &[Vec2; 4], race: Line, x0: f64, r: &dyn Fn(f64) -> f64) -> [Vec2; 3] {
    let axis_r = 0.5 * (roller[0][1] + roller[1][1]);
    let (point, normal) = match &g.flange {
        Some(f) => (f.point, f.normal),
        None => (roller[0], [g.axis[0], g.axis[1]]),
    };
    let face = [-normal[1], normal[0]];
    let top = limit(0.5 * (point[1] + axis_r), r(x0), axis_r.max(r(x0)));
    let slope = finite_or(face[0] / face[1], 0.0);
    let x_top = limit(point[0] + (top - point[1]) * slope, x0, roller[0][0].max(x0));
    // Foot of the face on the raceway: x = x_top + (r_race(x) - top) * slope.
    let denom = 1.0 - race.slope * slope;
    let x_foot = finite_or(x_top + (race.r(x_top) - top) * slope / denom, x_top);
    let x_foot = limit(x_foot, x0, roller[0][0].max(x0));
    [[x0, r(x0).max(top)], [x_top, top], [x_foot, r(x_foot)]]
}

/// Pixel mapping: bearing axis on the middle row, the envelope centred and fitted.
struct View {
    scale: f64,
    x_mid: f64,
}

impl View {
    fn fit(s: &Section) -> View {
        let side = SIZE as f64 - 2.0 * MARGIN;
        let width = (s.x_right - s.x_left).abs();
        let by_height = side / (2.0 * s.outer_radius.abs());
        let by_width = (side - 2.0 * AXIS_OVERHANG) / width;
        View {
            scale: finite_or(by_height.min(by_width), 1.0),
            x_mid: finite_or(0.5 * (s.x_left + s.x_right), 0.0),
        }
    }

    /// Pixel of the axial-plane point `p`, above (`sign` = 1) or below (-1) the axis.
    fn px(&self, p: Vec2, sign: f64) -> (f32, f32) {
        let c = 0.5 * SIZE as f64;
        let x = c + self.scale * (p[0] - self.x_mid);
        let y = c - sign * self.scale * p[1];
        let far = 4.0 * SIZE as f64;
        (limit(x, -far, far) as f32, limit(y, -far, far) as f32)
    }
}

fn polygon(points: &[Vec2], view: &View, sign: f64) -> Option<Path> {
    let mut pb = PathBuilder::new();
    for (k, &p) in points.iter().enumerate() {
        let (x, y) = view.px(p, sign);
        if k == 0 {
            pb.move_to(x, y);
        } else {
            pb.line_to(x, y);
        }
    }
    pb.close();
    pb.finish()
}

fn paint(rgb: [u8; 3]) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(rgb[0], rgb[1], rgb[2], 255));
    p.anti_alias = true;
    p
}

fn render(s: &Section) -> Pixmap {
    let mut pm = Pixmap::new(SIZE, SIZE).expect("a non-empty pixmap");
    let view = View::fit(s);
    for sign in [1.0, -1.0] {
        if let Some(path) = polygon(&s.cup, &view, sign) {
            draw_ring(&mut pm, &path, 1.0);
        }
        if let Some(path) = polygon(&s.cone, &view, sign) {
            draw_ring(&mut pm, &path, -1.0);
        }
        if let Some(path) = polygon(&s.roller, &view, sign) {
            draw_solid(&mut pm, &path, ROLLER_RGB);
        }
    }
    draw_axis(&mut pm, s, &view);
    pm
}

fn outline_stroke() -> Stroke {
    Stroke {
        width: 1.0,
        ..Stroke::default()
    }
}

fn draw_solid(pm: &mut Pixmap, path: &Path, rgb: [u8; 3]) {
    pm.fill_path(path, &paint(rgb), FillRule::Winding, Transform::identity(), None);
    pm.stroke_path(path, &paint(OUTLINE_RGB), &outline_stroke(), Transform::identity(), None);
}

/// A ring's section: grey, hatched at 45 degrees rising (`dir` = 1) or falling (-1), outlined.
fn draw_ring(pm: &mut Pixmap, path: &Path, dir: f32) {
    pm.fill_path(path, &paint(RING_RGB), FillRule::Winding, Transform::identity(), None);
    if let (Some(mut mask), Some(lines)) = (Mask::new(SIZE, SIZE), hatch_lines(path.bounds(), dir)) {
        mask.fill_path(path, FillRule::Winding, true, Transform::identity());
        pm.stroke_path(&lines, &paint(HATCH_RGB), &outline_stroke(), Transform::identity(), Some(&mask));
    }
    pm.stroke_path(path, &paint(OUTLINE_RGB), &outline_stroke(), Transform::identity(), None);
}

/// Parallel 45-degree lines over `bounds`, on a fixed grid of 5 px spacing: x + y = c
/// (rising, `dir` = 1) or x - y = c (falling).
fn hatch_lines(bounds: Rect, dir: f32) -> Option<Path> {
    const GAP: f32 = 5.0;
    let (top, bottom) = (bounds.top() - 1.0, bounds.bottom() + 1.0);
    let (lo, hi) = if dir > 0.0 {
        (bounds.left() + top, bounds.right() + bottom)
    } else {
        (bounds.left() - bottom, bounds.right() - top)
    };
    let mut pb = PathBuilder::new();
    let mut c = (lo / GAP).floor() * GAP;
    while c <= hi {
        pb.move_to(c - dir * top, top);
        pb.line_to(c - dir * bottom, bottom);
        c += GAP;
    }
    pb.finish()
}

/// The bearing axis: dash-dot on the middle row, past both faces.
fn draw_axis(pm: &mut Pixmap, s: &Section, view: &View) {
    let (x0, y) = view.px([s.x_left, 0.0], 1.0);
    let (x1, _) = view.px([s.x_right, 0.0], 1.0);
    let over = AXIS_OVERHANG as f32;
    let mut pb = PathBuilder::new();
    pb.move_to(x0.min(x1) - over, y);
    pb.line_to(x0.max(x1) + over, y);
    let stroke = Stroke {
        width: 1.5,
        line_cap: LineCap::Butt,
        dash: StrokeDash::new(vec![9.0, 2.5, 1.5, 2.5], 0.0),
        ..Stroke::default()
    };
    if let Some(path) = pb.finish() {
        pm.stroke_path(&path, &paint(AXIS_RGB), &stroke, Transform::identity(), None);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tiny_skia::PremultipliedColorU8;

    fn preset_png(name: &str) -> Vec<u8> {
        model_png(&Bearing::preset(name).unwrap())
    }

    fn decode(png: &[u8]) -> Pixmap {
        Pixmap::decode_png(png).expect("a PNG tiny-skia reads back")
    }

    fn is(p: PremultipliedColorU8, rgb: [u8; 3]) -> bool {
        p.alpha() == 255 && [p.red(), p.green(), p.blue()] == rgb
    }

    fn ink(pm: &Pixmap, x: u32, y: u32) -> bool {
        pm.pixel(x, y).is_some_and(|p| p.alpha() >= 128)
    }

    /// Pixels of colour `rgb` in rows `rows`.
    fn count(pm: &Pixmap, rows: std::ops::Range<u32>, rgb: [u8; 3]) -> usize {
        rows.flat_map(|y| (0..SIZE).map(move |x| (x, y)))
            .filter(|&(x, y)| is(pm.pixel(x, y).unwrap(), rgb))
            .count()
    }

    /// Roller pixels of column `x` in the upper half: how many and their mean row.
    fn roller_column(pm: &Pixmap, x: u32) -> (usize, f64) {
        let rows: Vec<u32> = (0..SIZE / 2).filter(|&y| is(pm.pixel(x, y).unwrap(), ROLLER_RGB)).collect();
        let mean = rows.iter().sum::<u32>() as f64 / rows.len().max(1) as f64;
        (rows.len(), mean)
    }

    /// First and last column holding roller pixels in the upper half, shrunk by `inset`.
    fn roller_columns(pm: &Pixmap, inset: u32) -> (u32, u32) {
        let cols: Vec<u32> = (0..SIZE).filter(|&x| roller_column(pm, x).0 > 0).collect();
        (cols[0] + inset, cols[cols.len() - 1] - inset)
    }

    #[test]
    fn icon_is_a_png_of_the_intended_size() {
        let png = preset_png("TRB130x230");
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        assert_eq!(&png[12..16], b"IHDR");
        assert_eq!(u32::from_be_bytes(png[16..20].try_into().unwrap()), SIZE);
        assert_eq!(u32::from_be_bytes(png[20..24].try_into().unwrap()), SIZE);
        let pm = decode(&png);
        assert_eq!((pm.width(), pm.height()), (SIZE, SIZE));
        // Transparent background in the corners.
        assert_eq!(pm.pixel(0, 0).unwrap().alpha(), 0);
    }

    #[test]
    fn icon_is_deterministic_and_differs_between_presets() {
        let pngs: Vec<Vec<u8>> = trb::bearing::PRESETS.iter().map(|(n, _)| preset_png(n)).collect();
        for (k, (name, _)) in trb::bearing::PRESETS.iter().enumerate() {
            assert_eq!(preset_png(name), pngs[k], "{name}: a second drawing differs");
            for other in &pngs[k + 1..] {
                assert_ne!(&pngs[k], other, "{name}: same icon as another preset");
            }
        }
    }

    #[test]
    fn icon_draws_rings_and_roller_in_the_upper_half() {
        for (name, _) in trb::bearing::PRESETS {
            let pm = decode(&preset_png(name));
            let ring = count(&pm, 0..SIZE / 2, RING_RGB);
            let roller = count(&pm, 0..SIZE / 2, ROLLER_RGB);
            assert!(ring > 250, "{name}: {ring} ring pixels in the upper half");
            assert!(roller > 200, "{name}: {roller} roller pixels in the upper half");
            // Nothing but the axis line in the bore near the axis.
            assert_eq!(count(&pm, SIZE / 2 - 20..SIZE / 2 - 2, RING_RGB), 0, "{name}");
        }
    }

    #[test]
    fn icon_is_symmetric_about_the_axis_row() {
        for (name, _) in trb::bearing::PRESETS {
            let pm = decode(&preset_png(name));
            let mismatched = (0..SIZE / 2)
                .flat_map(|y| (0..SIZE).map(move |x| (x, y)))
                .filter(|&(x, y)| {
                    let m = SIZE - 1 - y;
                    let mirrored = (m - 1..=(m + 1).min(SIZE - 1)).any(|yy| ink(&pm, x, yy));
                    ink(&pm, x, y) != mirrored && ink(&pm, x, y)
                })
                .count();
            assert_eq!(mismatched, 0, "{name}: upper-half pixels without a mirror image");
            let (up, down) = (count(&pm, 0..SIZE / 2, ROLLER_RGB), count(&pm, SIZE / 2..SIZE, ROLLER_RGB));
            assert!(up.abs_diff(down) * 50 <= up, "{name}: roller {up} px above, {down} below");
        }
    }

    #[test]
    fn icon_tapered_roller_is_tilted_towards_the_axis() {
        for name in ["TRB130x230", "32018X", "32008"] {
            let pm = decode(&preset_png(name));
            let (left, right) = roller_columns(&pm, 3);
            let (large, row_large) = roller_column(&pm, left);
            let (small, row_small) = roller_column(&pm, right);
            // Apex towards +x and the axis: the roller descends (larger row) to the right and
            // is thinner there.
            assert!(row_small > row_large + 2.0, "{name}: rows {row_large} -> {row_small}");
            assert!(small <= large, "{name}: end heights {large} -> {small}");
        }
    }

    #[test]
    fn icon_crb_roller_is_a_cylinder_between_straight_raceways() {
        let pm = decode(&preset_png("CRB-TRILOBE"));
        let (left, right) = roller_columns(&pm, 2);
        let (h0, row0) = roller_column(&pm, left);
        let (h1, row1) = roller_column(&pm, right);
        assert!(h0.abs_diff(h1) <= 1 && (row0 - row1).abs() <= 0.5, "{h0} {row0} / {h1} {row1}");
        assert!(count(&pm, 0..SIZE / 2, RING_RGB) > 250);
    }

    /// A bearing file of extreme proportions the validation accepts, and absurd values set
    /// on the struct directly: always a PNG of the intended size.
    #[test]
    fn icon_survives_extreme_proportions() {
        let mut file: serde_json::Value = serde_json::from_str(trb::bearing::PRESETS.iter().find(|p| p.0 == "32008").unwrap().1).unwrap();
        file["envelope"] = serde_json::json!({"bore_mm": 1.0, "outside_diameter_mm": 2000.0, "width_mm": 900.0});
        let wide = Bearing::from_json(&file.to_string()).unwrap();
        let mut cases = vec![wide];
        let base = Bearing::preset("TRB130x230").unwrap();
        type Edit = fn(&mut Bearing);
        let edits: [Edit; 6] = [
            |b| b.width = 1e-9,
            |b| b.width = f64::NAN,
            |b| b.bore = 10.0 * b.outside_diameter,
            |b| b.cone_angle = 1.5,
            |b| b.roller_length = 1e6,
            |b| b.outside_diameter = f64::INFINITY,
        ];
        for edit in edits {
            let mut b = base.clone();
            edit(&mut b);
            cases.push(b);
        }
        for b in &cases {
            let pm = decode(&model_png(b));
            assert_eq!((pm.width(), pm.height()), (SIZE, SIZE));
        }
    }

    #[test]
    #[ignore = "writes /tmp/icons/<preset>.png and an enlarged zoom-<preset>.png to look at"]
    fn icon_write_presets_for_viewing() {
        std::fs::create_dir_all("/tmp/icons").unwrap();
        for (name, _) in trb::bearing::PRESETS {
            let b = Bearing::preset(name).unwrap();
            let t = std::time::Instant::now();
            let runs = 50;
            for _ in 1..runs {
                std::hint::black_box(model_png(&b));
            }
            let png = model_png(&b);
            eprintln!("{name}: {} bytes, {:?} per drawing", png.len(), t.elapsed() / runs);
            std::fs::write(format!("/tmp/icons/{name}.png"), &png).unwrap();
            zoom(&png).save_png(format!("/tmp/icons/zoom-{name}.png")).unwrap();
        }
    }

    /// The upper half, four times enlarged on white (for looking at, not shipped).
    fn zoom(png: &[u8]) -> Pixmap {
        let icon = decode(png);
        let mut big = Pixmap::new(4 * SIZE, 2 * SIZE + 40).unwrap();
        big.fill(Color::WHITE);
        let paint = tiny_skia::PixmapPaint {
            quality: tiny_skia::FilterQuality::Nearest,
            ..Default::default()
        };
        big.draw_pixmap(0, 0, icon.as_ref(), &paint, Transform::from_scale(4.0, 4.0), None);
        big
    }
}
