//! `trb demo`: package the default FMU (as `trb fmu` does), run `scenarios/demo.json`
//! (compiled into the program) to `<target dir>/demo.csv`, and print a short table.

use super::scenario::Scenario;
use super::{package, paths, simulate, CliError};
use clap::Args;
use std::path::{Path, PathBuf};

/// The demonstration scenario, compiled in so `demo` works from any directory.
pub const DEMO_SCENARIO: &str = include_str!("../../scenarios/demo.json");

/// Rows of the printed table (besides the header).
const TABLE_ROWS: usize = 10;

#[derive(Debug, Clone, Args)]
pub struct DemoArgs {
    /// Where to write the CSV. Default: <cargo target dir>/demo.csv.
    #[arg(long, value_name = "PATH")]
    pub csv: Option<PathBuf>,
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
    let summary = simulate::run_to_file(&scenario, &csv, false)?;

    println!("{}", scenario.description);
    println!();
    let text = std::fs::read_to_string(&csv).map_err(|e| CliError::failed(format!("cannot read back {}: {e}", csv.display())))?;
    println!("{}", table(&text).map_err(CliError::failed)?);
    println!();
    println!("FMU: {}", packaged.summary());
    println!("CSV: {}", simulate::summary_line(&scenario, &summary, &csv));
    Ok(())
}

/// (header, CSV column, scale, decimals)
const COLUMNS: &[(&str, &str, f64, usize)] = &[
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
pub fn table(text: &str) -> Result<String, String> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().ok_or("empty CSV")?.split(',').collect();
    let index: Vec<usize> = COLUMNS
        .iter()
        .map(|(_, name, _, _)| header.iter().position(|h| h == name).ok_or(format!("CSV has no column `{name}`")))
        .collect::<Result<_, _>>()?;
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    if rows.is_empty() {
        return Err("CSV has no rows".into());
    }
    let last = rows.len() - 1;
    let mut picked: Vec<usize> = (0..=TABLE_ROWS).map(|i| (i * last + TABLE_ROWS / 2) / TABLE_ROWS).collect();
    picked.dedup();

    let mut cells: Vec<Vec<String>> = vec![COLUMNS.iter().map(|c| c.0.to_string()).collect()];
    for &r in &picked {
        let row = &rows[r];
        let mut out = Vec::new();
        for ((_, name, scale, decimals), &i) in COLUMNS.iter().zip(&index) {
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
    let widths: Vec<usize> = (0..COLUMNS.len())
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
    fn the_table_has_about_ten_aligned_rows() {
        let mut csv = String::from("time,speed,xi,zeta,Fx,Fy,Fz,axialDisplacement,cone.x,Qo.max,loadedRollers,frictionTorque,powerLoss\n");
        for k in 0..=200 {
            let t = k as f64 * 0.001;
            csv.push_str(&format!(
                "{t:?},366.5,0.0,0.0,30000.0,{:?},0.0,0.0,2.2e-5,6818.3,17,5.3,1960.7\n",
                t * 1e5
            ));
        }
        let text = table(&csv).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 12);
        assert!(lines[0].starts_with("t [s]"));
        assert!(lines[1].trim_start().starts_with("0.000"));
        assert!(lines[11].trim_start().starts_with("0.200"));
        assert!(lines[11].contains("20.00"));
        let width = lines[1].len();
        assert!(lines[1..].iter().all(|l| l.len() == width), "rows not aligned:\n{text}");
        assert!(table("time,speed\n0.0,1.0\n").is_err());
    }
}
