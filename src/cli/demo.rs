//! `trb demo`: package the default FMU (as `trb fmu` does), run `scenarios/demo.json`
//! (compiled into the program, quasi-static) to `<target dir>/demo.csv` and print a short
//! table; then run `scenarios/demo_dynamic.json`, the [W25] reference case in the dynamic
//! model, to `<target dir>/demo_dynamic.csv`, print skew, tilt and torque with the wall time,
//! and draw skew and tilt against time in `<target dir>/demo_dynamic.svg`. It says first which
//! files and which plot it writes, and where.

use super::scenario::Scenario;
use super::svg::{self, Series};
use super::{package, paths, simulate, CliError};
use clap::Args;
use std::path::{Path, PathBuf};

/// The demonstration scenario, compiled in so `demo` works from any directory.
pub const DEMO_SCENARIO: &str = include_str!("../../scenarios/demo.json");

/// The dynamic part: the [W25] reference case at fidelity 1 (50 ms).
pub const DEMO_DYNAMIC_SCENARIO: &str = include_str!("../../scenarios/demo_dynamic.json");

/// Rows of the printed table (besides the header).
const TABLE_ROWS: usize = 10;

#[derive(Debug, Clone, Args)]
pub struct DemoArgs {
    /// Where to write the CSV. Default: <cargo target dir>/demo.csv; the dynamic part's CSV
    /// and SVG go next to it (demo_dynamic.csv, demo_dynamic.svg).
    #[arg(long, value_name = "PATH")]
    pub csv: Option<PathBuf>,
    /// Only the quasi-static part.
    #[arg(long)]
    pub skip_dynamic: bool,
}

pub fn run(args: DemoArgs) -> Result<(), CliError> {
    let packaged = package::package(trb::bearing::DEFAULT_PRESET, None, None)?;
    for w in &packaged.warnings {
        eprintln!("warning: {w}");
    }

    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let scenario = Scenario::from_json(DEMO_SCENARIO, &base).map_err(|e| CliError::failed(format!("scenarios/demo.json: {e}")))?;
    let csv = match args.csv {
        Some(p) => p,
        None => paths::target_dir()?.join("demo.csv"),
    };
    let dynamic_csv = csv.with_file_name("demo_dynamic.csv");
    println!("{}", files_line(&csv, &dynamic_csv, args.skip_dynamic));
    println!();
    let summary = simulate::run_to_file(&scenario, &csv, false)?;

    println!("{}", scenario.description);
    println!();
    let text = read_back(&csv)?;
    println!("{}", table(&text, COLUMNS).map_err(CliError::failed)?);
    println!();
    println!("FMU: {}", packaged.summary());
    println!("CSV: {}", simulate::summary_line(&scenario, &summary, &csv));
    if !args.skip_dynamic {
        println!();
        run_dynamic(&base, &dynamic_csv)?;
    }
    Ok(())
}

/// Where the demo writes: the CSVs and, unless the dynamic part is skipped, the plot (the
/// SVG beside the dynamic CSV).
fn files_line(csv: &Path, dynamic_csv: &Path, skip_dynamic: bool) -> String {
    if skip_dynamic {
        return format!("Writes {} (no plot: the dynamic part, which draws it, is skipped)", csv.display());
    }
    format!(
        "Writes {}, {} and one plot: {} (roller skew and tilt against time)",
        csv.display(),
        dynamic_csv.display(),
        dynamic_csv.with_extension("svg").display()
    )
}

fn read_back(csv: &Path) -> Result<String, CliError> {
    std::fs::read_to_string(csv).map_err(|e| CliError::failed(format!("cannot read back {}: {e}", csv.display())))
}

/// The dynamic part: run, print the table and the wall time, draw the SVG.
fn run_dynamic(base: &Path, csv: &Path) -> Result<(), CliError> {
    let scenario =
        Scenario::from_json(DEMO_DYNAMIC_SCENARIO, base).map_err(|e| CliError::failed(format!("scenarios/demo_dynamic.json: {e}")))?;
    let summary = simulate::run_to_file(&scenario, csv, false)?;
    println!("{}", scenario.description);
    println!();
    let text = read_back(csv)?;
    println!("{}", table(&text, DYNAMIC_COLUMNS).map_err(CliError::failed)?);
    println!();
    let simulated = scenario.stop_time - scenario.start_time;
    println!(
        "{:.0} ms simulated in {:.2} s of wall time ({})",
        simulated * 1e3,
        summary.wall.as_secs_f64(),
        simulate::real_time(simulated, summary.wall.as_secs_f64())
    );
    let svg = csv.with_extension("svg");
    std::fs::write(&svg, skew_and_tilt_svg(&text).map_err(CliError::failed)?)
        .map_err(|e| CliError::failed(format!("cannot write {}: {e}", svg.display())))?;
    println!("CSV: {}", simulate::summary_line(&scenario, &summary, csv));
    println!("Plot: {} (roller skew and tilt against time)", svg.display());
    Ok(())
}

/// Header and rows of a simulate CSV (RFC 4180: names such as `stiffness[1,2]` are quoted).
fn records(text: &str) -> Result<(Vec<String>, Vec<Vec<String>>), String> {
    let mut reader = csv::ReaderBuilder::new().has_headers(true).from_reader(text.as_bytes());
    let header = reader
        .headers()
        .map_err(|e| format!("CSV header: {e}"))?
        .iter()
        .map(str::to_string)
        .collect();
    let rows = reader
        .records()
        .map(|r| r.map(|r| r.iter().map(str::to_string).collect()).map_err(|e| format!("CSV: {e}")))
        .collect::<Result<_, _>>()?;
    Ok((header, rows))
}

/// Columns of `text` (a simulate CSV) by name, scaled.
fn columns(text: &str, wanted: &[(&str, f64)]) -> Result<Vec<Vec<f64>>, String> {
    let (header, rows) = records(text)?;
    let index: Vec<usize> = wanted
        .iter()
        .map(|(name, _)| header.iter().position(|h| h == name).ok_or(format!("CSV has no column `{name}`")))
        .collect::<Result<_, _>>()?;
    let mut out = vec![Vec::new(); wanted.len()];
    for (r, cells) in rows.iter().enumerate() {
        for (k, (&i, (name, scale))) in index.iter().zip(wanted).enumerate() {
            let raw = cells.get(i).ok_or(format!("row {r} has no column `{name}`"))?;
            let v: f64 = raw
                .parse()
                .map_err(|_| format!("row {r}, column `{name}`: `{raw}` is not a number"))?;
            out[k].push(v * scale);
        }
    }
    Ok(out)
}

/// Two charts one above the other: roller skew (max and mean over the rollers) and roller
/// tilt against time, in degrees.
pub fn skew_and_tilt_svg(text: &str) -> Result<String, String> {
    let deg = 180.0 / std::f64::consts::PI;
    let c = columns(
        text,
        &[
            ("time", 1e3),
            ("skew.max", deg),
            ("skew.mean", deg),
            ("tilt.max", deg),
            ("tilt.mean", deg),
        ],
    )?;
    let series = |k: usize, name: &str| Series::new(name, c[0].iter().copied().zip(c[k].iter().copied()).collect());
    let skew = svg::chart(
        "Roller skew, [W25] reference case (dynamic model)",
        "time [ms]",
        "skew [deg]",
        &[series(1, "max over rollers"), series(2, "mean over rollers")],
        false,
        false,
    );
    let tilt = svg::chart(
        "Roller tilt",
        "time [ms]",
        "tilt [deg]",
        &[series(3, "max over rollers"), series(4, "mean over rollers")],
        false,
        false,
    );
    Ok(svg::stack(&[skew, tilt]))
}

/// (header, CSV column, scale, decimals)
type Column = (&'static str, &'static str, f64, usize);

/// The dynamic part's table.
const DYNAMIC_COLUMNS: &[Column] = &[
    ("t [ms]", "time", 1e3, 1),
    ("skew.max [deg]", "skew.max", 180.0 / std::f64::consts::PI, 5),
    ("skew.mean [deg]", "skew.mean", 180.0 / std::f64::consts::PI, 5),
    ("tilt.max [mdeg]", "tilt.max", 180e3 / std::f64::consts::PI, 3),
    ("torque [N m]", "frictionTorque", 1.0, 3),
    ("cage [rpm]", "cage.speed", 30.0 / std::f64::consts::PI, 1),
    ("steps", "integrator.steps", 1.0, 0),
];

const COLUMNS: &[Column] = &[
    ("t [s]", "time", 1.0, 3),
    ("speed [rpm]", "speed", 30.0 / std::f64::consts::PI, 0),
    ("Fx [kN]", "Fx", 1e-3, 2),
    ("Fy [kN]", "Fy", 1e-3, 2),
    ("xi [deg]", "xi", 180.0 / std::f64::consts::PI, 4),
    ("cone.x [um]", "cone.x", 1e6, 3),
    ("Qo.max [N]", "Qo.max", 1.0, 0),
    ("loaded", "loadedRollers", 1.0, 0),
    ("torque [N m]", "frictionTorque", 1.0, 4),
    ("powerLoss [W]", "powerLoss", 1.0, 1),
];

/// An aligned table of about ten evenly spaced rows of the CSV `text`.
pub fn table(text: &str, columns: &[Column]) -> Result<String, String> {
    let (header, rows) = records(text)?;
    let index: Vec<usize> = columns
        .iter()
        .map(|(_, name, _, _)| header.iter().position(|h| h == name).ok_or(format!("CSV has no column `{name}`")))
        .collect::<Result<_, _>>()?;
    if rows.is_empty() {
        return Err("CSV has no rows".into());
    }
    let last = rows.len() - 1;
    let mut picked: Vec<usize> = (0..=TABLE_ROWS).map(|i| (i * last + TABLE_ROWS / 2) / TABLE_ROWS).collect();
    picked.dedup();

    let mut cells: Vec<Vec<String>> = vec![columns.iter().map(|c| c.0.to_string()).collect()];
    for &r in &picked {
        let row = &rows[r];
        let mut out = Vec::new();
        for ((_, name, scale, decimals), &i) in columns.iter().zip(&index) {
            let raw = row.get(i).ok_or(format!("row {r} has no column `{name}`"))?;
            let v: f64 = raw
                .parse()
                .map_err(|_| format!("row {r}, column `{name}`: `{raw}` is not a number"))?;
            let v = v * scale;
            // No "-0.000".
            let s = format!("{v:.decimals$}");
            out.push(if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
                s.trim_start_matches('-').to_string()
            } else {
                s
            });
        }
        cells.push(out);
    }
    let widths: Vec<usize> = (0..columns.len())
        .map(|c| cells.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    let mut s = String::new();
    for (n, row) in cells.iter().enumerate() {
        let line: Vec<String> = row.iter().zip(&widths).map(|(cell, w)| format!("{cell:>w$}")).collect();
        s.push_str(line.join("  ").trim_end());
        if n + 1 < cells.len() {
            s.push('\n');
        }
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_demo_scenario_is_valid() {
        let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
        let s = Scenario::from_json(DEMO_SCENARIO, &base).unwrap();
        assert_eq!(s.bearing.bearing.name, "TRB130x230");
        assert_eq!(s.stop_time, 0.2);
        assert_eq!(s.n_steps, 200);
    }

    #[test]
    fn the_dynamic_demo_is_the_w25_reference_case_at_fidelity_1_for_50_ms() {
        let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
        let s = Scenario::from_json(DEMO_DYNAMIC_SCENARIO, &base).unwrap();
        assert_eq!(s.bearing.bearing.name, "TRB130x230");
        assert!(s.stop_time - s.start_time >= 0.05);
        assert!(s.description.contains("fidelity 1"));
    }

    #[test]
    fn the_skew_and_tilt_svg_has_two_charts_of_the_csv() {
        let mut csv = String::from("time,skew.max,skew.mean,tilt.max,tilt.mean\n");
        for k in 0..=10 {
            let t = k as f64 * 0.005;
            csv.push_str(&format!("{t:?},{:?},{:?},1e-5,5e-6\n", 1e-4 * t, 5e-5 * t));
        }
        let svg = skew_and_tilt_svg(&csv).unwrap();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains("Roller skew") && svg.contains("Roller tilt"));
        assert_eq!(svg.matches("<polyline").count(), 4, "four curves");
        assert!(skew_and_tilt_svg("time,skew.max\n0,1\n").is_err());
    }

    #[test]
    fn the_files_line_names_the_plot_and_where_it_goes() {
        let (csv, dynamic) = (Path::new("/t/demo.csv"), Path::new("/t/demo_dynamic.csv"));
        let line = files_line(csv, dynamic, false);
        assert!(line.contains("/t/demo.csv") && line.contains("/t/demo_dynamic.csv"), "{line}");
        assert!(
            line.contains("one plot: /t/demo_dynamic.svg (roller skew and tilt against time)"),
            "{line}"
        );
        assert!(files_line(csv, dynamic, true).contains("no plot"));
    }

    #[test]
    fn the_table_has_about_ten_aligned_rows() {
        let mut csv = String::from("time,speed,xi,zeta,Fx,Fy,Fz,axialDisplacement,cone.x,Qo.max,loadedRollers,frictionTorque,powerLoss\n");
        for k in 0..=200 {
            let t = k as f64 * 0.001;
            csv.push_str(&format!(
                "{t:?},366.5,0.0,0.0,30000.0,{:?},0.0,0.0,2.2e-5,6818.3,17,5.3,1960.7\n",
                t * 1e5
            ));
        }
        let text = table(&csv, COLUMNS).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 12);
        assert!(lines[0].starts_with("t [s]"));
        assert!(lines[1].trim_start().starts_with("0.000"));
        assert!(lines[11].trim_start().starts_with("0.200"));
        assert!(lines[11].contains("20.00"));
        let width = lines[1].len();
        assert!(lines[1..].iter().all(|l| l.len() == width), "rows not aligned:\n{text}");
        assert!(table("time,speed\n0.0,1.0\n", COLUMNS).is_err());
    }
}
