//! Minimal SVG charts for the study and benchmark figures, written by hand (no fonts or C
//! libraries needed): x-y line charts (linear or logarithmic axes) with markers and a legend,
//! and polar charts of per-roller loads.

use std::fmt::Write as _;

const COLORS: [&str; 8] = [
    "#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf",
];
const W: f64 = 640.0;
const H: f64 = 400.0;
const LEFT: f64 = 72.0;
const RIGHT: f64 = 170.0;
const TOP: f64 = 40.0;
const BOTTOM: f64 = 56.0;

/// One named curve.
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    /// A dot at every point (off for dense curves: signals and spectra).
    pub markers: bool,
}

impl Series {
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            markers: true,
        }
    }

    /// A curve drawn as a line only, without a dot at each point.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            markers: false,
            ..Series::new(name, points)
        }
    }
}

/// A labelled vertical line at `x` (a characteristic frequency on a spectrum).
pub struct Mark {
    pub x: f64,
    pub label: String,
}

impl Mark {
    pub fn new(x: f64, label: impl Into<String>) -> Mark {
        Mark { x, label: label.into() }
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

/// A "nice" tick step for the range (1, 2, 5 x 10^k) giving about `n` ticks.
fn nice_step(span: f64, n: f64) -> f64 {
    let raw = (span / n).max(1e-300);
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let m = if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    };
    m * mag
}

fn fmt_tick(v: f64, step: f64) -> String {
    // ticks are multiples of the step: a residue of rounding is zero
    if v.abs() < 1e-9 * step.abs() {
        return "0".into();
    }
    if v.abs() >= 1e5 || v.abs() < 1e-3 {
        return format!("{v:.1e}");
    }
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

fn header(out: &mut String, title: &str) {
    let _ = write!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" font-family="sans-serif" font-size="12">
<rect width="{W}" height="{H}" fill="white"/>
<text x="{}" y="22" text-anchor="middle" font-size="14" font-weight="bold">{}</text>
"#,
        (LEFT + W - RIGHT) / 2.0,
        esc(title)
    );
}

fn legend(out: &mut String, names: &[&str]) {
    for (k, name) in names.iter().enumerate() {
        let y = TOP + 14.0 + 18.0 * k as f64;
        let x = W - RIGHT + 14.0;
        let c = COLORS[k % COLORS.len()];
        let _ = writeln!(
            out,
            r#"<line x1="{x}" y1="{y}" x2="{}" y2="{y}" stroke="{c}" stroke-width="2"/><circle cx="{}" cy="{y}" r="3" fill="{c}"/><text x="{}" y="{}">{}</text>"#,
            x + 22.0,
            x + 11.0,
            x + 28.0,
            y + 4.0,
            esc(name)
        );
    }
}

/// Ticks of an axis over [v0, v1] (transformed coordinates): 1, 2, 5 per decade on a log axis
/// (values, with the decade below as the formatting step), a nice step otherwise.
fn axis_ticks(v0: f64, v1: f64, log: bool, step: f64) -> Vec<(f64, f64)> {
    let mut ticks = Vec::new();
    if log {
        // 1, 2, 5 per decade over up to 3 decades; beyond, the powers of ten only (every
        // second one beyond 8 decades) so that the labels do not overlap
        let span = v1 - v0;
        let multipliers: &[f64] = if span > 3.0 { &[1.0] } else { &[1.0, 2.0, 5.0] };
        let stride = if span > 8.0 { 2 } else { 1 };
        for k in (v0.floor() as i32)..=(v1.ceil() as i32) {
            if k.rem_euclid(stride) != 0 {
                continue;
            }
            for &m in multipliers {
                let v = m * 10f64.powi(k);
                if v.log10() >= v0 - 1e-9 && v.log10() <= v1 + 1e-9 {
                    ticks.push((v, v / 10.0));
                }
            }
        }
    } else {
        let mut v = (v0 / step).ceil() * step;
        while v <= v1 + 1e-9 * step.abs() {
            ticks.push((v, step));
            v += step;
        }
    }
    ticks
}

/// An x-y chart; `log_x` plots x on a logarithmic axis (x > 0).
pub fn line_chart(title: &str, x_label: &str, y_label: &str, series: &[Series], log_x: bool) -> String {
    chart(title, x_label, y_label, series, log_x, false)
}

/// An x-y chart with either axis linear or logarithmic (values > 0 on a log axis).
pub fn chart(title: &str, x_label: &str, y_label: &str, series: &[Series], log_x: bool, log_y: bool) -> String {
    marked_chart(title, x_label, y_label, series, &[], log_x, log_y)
}

/// An x-y chart with labelled vertical lines at `marks` (those outside the curves' x range
/// are left out); either axis linear or logarithmic.
pub fn marked_chart(title: &str, x_label: &str, y_label: &str, series: &[Series], marks: &[Mark], log_x: bool, log_y: bool) -> String {
    let tx = |x: f64| if log_x { x.max(1e-300).log10() } else { x };
    let ty = |y: f64| if log_y { y.max(1e-300).log10() } else { y };
    let pts = series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for p in pts {
        x0 = x0.min(tx(p.0));
        x1 = x1.max(tx(p.0));
        y0 = y0.min(ty(p.1));
        y1 = y1.max(ty(p.1));
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if log_x {
        (x0, x1) = (x0.floor(), x1.ceil());
    }
    if log_y {
        (y0, y1) = (y0.floor(), y1.ceil());
    } else {
        y0 = y0.min(0.0);
    }
    if y1 <= y0 {
        y1 = y0 + 1.0;
    }
    if x1 <= x0 {
        x1 = x0 + 1.0;
    }
    let ystep = nice_step(y1 - y0, 5.0);
    if !log_y {
        y0 = (y0 / ystep).floor() * ystep;
        y1 = (y1 / ystep).ceil() * ystep;
    }
    let (pw, ph) = (W - LEFT - RIGHT, H - TOP - BOTTOM);
    let px = |x: f64| LEFT + (tx(x) - x0) / (x1 - x0) * pw;
    let py = |y: f64| TOP + ph - (ty(y) - y0) / (y1 - y0) * ph;
    let mut out = String::new();
    header(&mut out, title);
    // grid and ticks
    let yticks = if log_y {
        axis_ticks(y0, y1, true, ystep)
    } else {
        let mut v = Vec::new();
        let mut y = y0;
        while y <= y1 + 0.5 * ystep {
            v.push((y, ystep));
            y += ystep;
        }
        v
    };
    for (y, step) in yticks {
        let yy = py(y);
        let _ = writeln!(
            out,
            r##"<line x1="{LEFT}" y1="{yy:.1}" x2="{:.1}" y2="{yy:.1}" stroke="#ddd"/><text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"##,
            LEFT + pw,
            LEFT - 6.0,
            yy + 4.0,
            fmt_tick(y, step)
        );
    }
    let ticks = axis_ticks(x0, x1, log_x, nice_step(x1 - x0, 6.0));
    for (x, step) in ticks {
        let xx = px(x);
        let _ = writeln!(
            out,
            r##"<line x1="{xx:.1}" y1="{TOP}" x2="{xx:.1}" y2="{:.1}" stroke="#eee"/><text x="{xx:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            TOP + ph,
            TOP + ph + 16.0,
            fmt_tick(x, step)
        );
    }
    let _ = writeln!(
        out,
        r#"<rect x="{LEFT}" y="{TOP}" width="{pw}" height="{ph}" fill="none" stroke="black"/>
<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>
<text x="16" y="{:.1}" text-anchor="middle" transform="rotate(-90 16 {:.1})">{}</text>"#,
        LEFT + pw / 2.0,
        H - 14.0,
        esc(x_label),
        TOP + ph / 2.0,
        TOP + ph / 2.0,
        esc(y_label)
    );
    for (k, s) in series.iter().enumerate() {
        let c = COLORS[k % COLORS.len()];
        let path: Vec<String> = s
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|p| format!("{:.1},{:.1}", px(p.0), py(p.1)))
            .collect();
        if path.is_empty() {
            continue;
        }
        let width = if s.markers { 2.0 } else { 1.2 };
        let _ = writeln!(
            out,
            r#"<polyline points="{}" fill="none" stroke="{c}" stroke-width="{width}"/>"#,
            path.join(" ")
        );
        if s.markers {
            for p in &path {
                let (a, b) = p.split_once(',').unwrap();
                let _ = writeln!(out, r#"<circle cx="{a}" cy="{b}" r="2.5" fill="{c}"/>"#);
            }
        }
    }
    for m in marks.iter().filter(|m| m.x.is_finite() && (!log_x || m.x > 0.0)) {
        let t = tx(m.x);
        if t < x0 || t > x1 {
            continue;
        }
        let xx = px(m.x);
        // the label runs up along the line from the bottom of the plot
        let _ = writeln!(
            out,
            r##"<line x1="{xx:.1}" y1="{TOP}" x2="{xx:.1}" y2="{:.1}" stroke="#555" stroke-width="0.8" stroke-dasharray="4 3"/><text x="{:.1}" y="{:.1}" font-size="10" fill="#333" transform="rotate(-90 {:.1} {:.1})">{}</text>"##,
            TOP + ph,
            xx - 2.0,
            TOP + ph - 4.0,
            xx - 2.0,
            TOP + ph - 4.0,
            esc(&m.label)
        );
    }
    let names: Vec<&str> = series.iter().map(|s| s.name.as_str()).collect();
    legend(&mut out, &names);
    out.push_str("</svg>\n");
    out
}

/// Polar chart of per-roller values: each series is (azimuth rad, value >= 0) with azimuth 0
/// at the top (the direction of Fy) and increasing clockwise; bars from the centre.
/// Charts of this module one above the other in one SVG document (each keeps its own
/// coordinates inside a nested `<svg>` placed at its offset).
pub fn stack(charts: &[String]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{}" viewBox="0 0 {W} {}">"#,
        H * charts.len() as f64,
        H * charts.len() as f64
    );
    for (k, chart) in charts.iter().enumerate() {
        // the chart's own root element, re-opened at its place (xmlns only on the outer one)
        let inner = chart.replacen(
            "<svg xmlns=\"http://www.w3.org/2000/svg\"",
            &format!(r#"<svg y="{}""#, H * k as f64),
            1,
        );
        out.push_str(inner.trim_end());
        out.push('\n');
    }
    out.push_str("</svg>\n");
    out
}

pub fn polar_chart(title: &str, unit: &str, series: &[Series]) -> String {
    let vmax = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .fold(0.0_f64, f64::max)
        .max(1e-12);
    let step = nice_step(vmax, 4.0);
    let rmax_v = (vmax / step).ceil() * step;
    let (cx, cy, r) = (
        LEFT + (W - LEFT - RIGHT) / 2.0,
        TOP + (H - TOP - BOTTOM) / 2.0 + 10.0,
        (H - TOP - BOTTOM) / 2.0,
    );
    let mut out = String::new();
    header(&mut out, title);
    let mut v = step;
    while v <= rmax_v + 1e-9 * step {
        let rr = v / rmax_v * r;
        let _ = writeln!(
            out,
            r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="{rr:.1}" fill="none" stroke="#ddd"/><text x="{:.1}" y="{:.1}" font-size="10" fill="#666">{} {}</text>"##,
            cx + 3.0,
            cy - rr - 2.0,
            fmt_tick(v, step),
            esc(unit)
        );
        v += step;
    }
    for deg in (0..360).step_by(30) {
        let a = (deg as f64).to_radians();
        let (x, y) = (cx + r * a.sin(), cy - r * a.cos());
        let _ = writeln!(
            out,
            r##"<line x1="{cx:.1}" y1="{cy:.1}" x2="{x:.1}" y2="{y:.1}" stroke="#eee"/><text x="{:.1}" y="{:.1}" text-anchor="middle" font-size="10">{deg}°</text>"##,
            cx + (r + 12.0) * a.sin(),
            cy - (r + 12.0) * a.cos() + 4.0
        );
    }
    for (k, s) in series.iter().enumerate() {
        let c = COLORS[k % COLORS.len()];
        let mut poly = Vec::new();
        for &(a, val) in &s.points {
            let rr = val.max(0.0) / rmax_v * r;
            let (x, y) = (cx + rr * a.sin(), cy - rr * a.cos());
            let _ = writeln!(
                out,
                r#"<line x1="{cx:.1}" y1="{cy:.1}" x2="{x:.1}" y2="{y:.1}" stroke="{c}" stroke-width="{}" opacity="0.8"/><circle cx="{x:.1}" cy="{y:.1}" r="3" fill="{c}"/>"#,
                3.0 - k as f64
            );
            poly.push(format!("{x:.1},{y:.1}"));
        }
        if !poly.is_empty() {
            let _ = writeln!(
                out,
                r#"<polygon points="{}" fill="{c}" fill-opacity="0.08" stroke="{c}" stroke-dasharray="3 3"/>"#,
                poly.join(" ")
            );
        }
    }
    let names: Vec<&str> = series.iter().map(|s| s.name.as_str()).collect();
    legend(&mut out, &names);
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn charts_are_well_formed_svg() {
        let s = vec![Series::new("a & b", vec![(0.01, 1.0), (0.1, 2.0), (1.0, 0.5)])];
        for svg in [
            line_chart("t", "x", "y", &s, true),
            line_chart("t", "x", "y", &s, false),
            chart("t", "x", "y", &s, true, true),
            marked_chart(
                "t",
                "x",
                "y",
                &s,
                &[Mark::new(0.5, "BPFO"), Mark::new(-1.0, "outside")],
                true,
                false,
            ),
            polar_chart("p", "N", &s),
        ] {
            assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
            assert!(svg.contains("a &amp; b"));
            assert!(!svg.contains("NaN") && !svg.contains("inf"));
        }
        let marked = marked_chart(
            "t",
            "x",
            "y",
            &s,
            &[Mark::new(0.5, "BPFO"), Mark::new(2.0, "outside")],
            false,
            false,
        );
        assert!(marked.contains(">BPFO</text>") && !marked.contains("outside"));
        let dense = line_chart("t", "x", "y", &[Series::line("signal", vec![(0.0, 1.0), (1.0, 2.0)])], false);
        // the legend's dot only
        assert_eq!(dense.matches("<circle").count(), 1, "{dense}");
        assert_eq!(nice_step(10.0, 5.0), 2.0);
    }
}
