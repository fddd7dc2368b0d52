//! Real time at default settings: the cases a system simulation runs the dynamic model in,
//! each over the long-run span (0.5 s by default) in the FMU's default 1 ms communication
//! steps, with the default integrator at the preset's tolerance, once. Wall time per simulated
//! second, integrator steps, right-hand sides and rejected steps, counted as the FMU counts
//! them (`integrator.steps`, `integrator.rhs`, `integrator.rejected`).
//!
//! The cases are the benchmark scenarios of the same names (their inputs, not their 10 ms
//! windows): the [W25] axial case, its deflected case, the combined load of a drivetrain, and
//! the two ends of [W25]'s speed and axial-load series with deflection. Each runs at the
//! scenario's fidelity (the dynamic model), then at fidelity 2 (quasi-dynamic) and 0
//! (quasi-static) with the same inputs, so that the table shows what each fidelity costs for
//! the same scene. Cases that have no work-precision window (a small bearing, whose dynamic
//! model is too slow for the sweeps) come from `benches/real_time/`.
//!
//! The same runs give the agreement of fidelities 2 and 0 with fidelity 1 on what a user reads
//! at the communication step: skew, tilt, torque, cage speed and the largest contact loads,
//! over the run's second half or its last cage revolution, whichever is longer.

use super::precision::{self, Reading, Trace};
use super::{at_fidelity, default_method, long_run_scenario, ScenarioResult};
use crate::cli::report::table;
use crate::cli::scenario::Scenario;
use crate::cli::CliError;
use std::fmt::Write as _;
use std::path::Path;

/// Benchmark scenarios run for real time, in the table's order.
const CASES: [&str; 6] = [
    "w25_axial_3500rpm",
    "deflected_xi0.004",
    "combined_fy10kN",
    "combined_load_zone",
    "series_500rpm_xi0.004",
    "series_12kN_xi0.004",
];

pub(super) struct Row {
    name: String,
    fidelity: i32,
    description: String,
    seconds: f64,
    outcome: Result<Trace, String>,
}

/// Run every real-time case present in `results`, then those of the folder `extra` (whose
/// names contain `filter`), over `seconds` simulated.
pub(super) fn measure(results: &[ScenarioResult], extra: &Path, filter: Option<&str>, seconds: f64) -> Result<Vec<Row>, CliError> {
    let mut cases: Vec<(String, Scenario)> = CASES
        .iter()
        .filter_map(|case| results.iter().find(|r| r.name == *case))
        .map(|r| (r.name.clone(), r.scenario.clone()))
        .collect();
    cases.extend(super::load_scenarios(extra, filter, false)?);
    let mut rows = Vec::new();
    for (case, scenario) in cases {
        let default = default_method(&scenario);
        for fidelity in [1, 2, 0] {
            let run = at_fidelity(&long_run_scenario(&scenario, seconds), fidelity);
            println!("real time: {seconds} s of {case} at default settings, fidelity {fidelity} ...");
            let outcome = precision::run(&run, &default);
            if let Ok(t) = &outcome {
                println!("  {:.2} s wall", t.wall);
            }
            rows.push(Row {
                name: case.clone(),
                fidelity,
                description: scenario.description.clone(),
                seconds,
                outcome,
            });
        }
    }
    Ok(rows)
}

/// The goal of a fidelity's wall time per simulated second: real time for the dynamic model,
/// a tenth of it for the quasi-dynamic one (a drivetrain model at a 1 ms step spends the rest on
/// itself), real time for the quasi-static one.
fn goal(fidelity: i32) -> f64 {
    if fidelity == 2 {
        0.1
    } else {
        1.0
    }
}

/// The table of the real-time runs.
pub(super) fn write(d: &mut String, rows: &[Row]) {
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(d, "### Real time at default settings\n");
    let _ = writeln!(
        d,
        "Each case over {} s simulated in 1 ms communication steps, the default integrator at the preset's \
         tolerance, from the start the scenario gives (the steady running state where there is one, else the \
         run-in at the initial inputs); one run each, wall time from building the element to the last output. \
         Goal: at most real time (wall time per simulated second ≤ 1). Each case at fidelity 1 (the scenario's \
         dynamic model), 2 (quasi-dynamic: right-hand sides are roller-contact evaluations over the roller count, \
         steps its Newton solves) and 0 (quasi-static: no integrator).\n",
        rows[0].seconds
    );
    let body: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            let mut row = vec![
                if r.fidelity == 1 {
                    format!("`{}`: {}", r.name, r.description)
                } else {
                    format!("`{}`", r.name)
                },
                r.fidelity.to_string(),
            ];
            match &r.outcome {
                Ok(t) => {
                    let per_second = t.wall / r.seconds;
                    row.extend([
                        format!("{per_second:.2}"),
                        format!("{:.0}", t.steps as f64 / r.seconds),
                        format!("{:.0}", t.rhs as f64 / r.seconds),
                        format!("{:.0}", t.rejected as f64 / r.seconds),
                        if t.rhs > 0 {
                            format!("{:.0} µs", t.wall / t.rhs as f64 * 1e6)
                        } else {
                            "–".into()
                        },
                        if per_second <= goal(r.fidelity) { "met" } else { "not met" }.into(),
                    ]);
                }
                Err(e) => row.extend([format!("failed: {e}"), "".into(), "".into(), "".into(), "".into(), "".into()]),
            }
            row
        })
        .collect();
    *d += &table(
        &[
            "case",
            "fidelity",
            "wall s per simulated s",
            "steps per s",
            "right-hand sides per s",
            "rejected per s",
            "wall per right-hand side",
            "goal (≤ 1; fidelity 2 ≤ 0.1)",
        ],
        &body,
    );
    d.push('\n');
}

/// Means (of the mean angles, torque and cage speed) and maxima (of the largest angles and
/// loads) of `readings` over their last `span` points.
fn settled(readings: &[Reading], span: usize) -> Reading {
    let window = &readings[readings.len().saturating_sub(span)..];
    let n = window.len().max(1) as f64;
    let mean = |f: fn(&Reading) -> f64| window.iter().map(f).sum::<f64>() / n;
    let max = |f: fn(&Reading) -> f64| window.iter().map(f).fold(0.0, f64::max);
    Reading {
        skew_abs_mean: mean(|r| r.skew_abs_mean),
        skew_max: max(|r| r.skew_max),
        tilt_abs_mean: mean(|r| r.tilt_abs_mean),
        tilt_max: max(|r| r.tilt_max),
        torque: mean(|r| r.torque),
        cage_speed: mean(|r| r.cage_speed),
        qi_max: max(|r| r.qi_max),
        qo_max: max(|r| r.qo_max),
    }
}

/// The quantities of the agreement table: name, value, whether fidelity 0 computes it, and
/// fidelity 2's bound against fidelity 1 (relative; with an absolute floor in rad for the
/// mean skew, 0.001°).
#[allow(clippy::type_complexity)]
const AGREEMENT: [(&str, fn(&Reading) -> f64, bool, f64, f64); 8] = [
    ("ϕavg (°)", |r| r.skew_abs_mean.to_degrees(), false, 0.10, 1e-3),
    ("ϕmax (°)", |r| r.skew_max.to_degrees(), false, 0.25, 0.0),
    ("θavg (°)", |r| r.tilt_abs_mean.to_degrees(), true, 0.05, 0.0),
    ("θmax (°)", |r| r.tilt_max.to_degrees(), true, 0.05, 0.0),
    ("T (N m)", |r| r.torque, true, 0.02, 0.0),
    ("cage (rad/s)", |r| r.cage_speed, true, 0.005, 0.0),
    ("Qi (N)", |r| r.qi_max, true, 0.02, 0.0),
    ("Qo (N)", |r| r.qo_max, true, 0.02, 0.0),
];

/// The table of fidelities 2 and 0 against fidelity 1 over the real-time runs.
pub(super) fn write_agreement(d: &mut String, rows: &[Row]) {
    let mut body = Vec::new();
    for dynamic in rows.iter().filter(|r| r.fidelity == 1) {
        let Ok(reference) = &dynamic.outcome else {
            continue;
        };
        let other = |fidelity: i32| {
            rows.iter()
                .find(|r| r.name == dynamic.name && r.fidelity == fidelity)
                .and_then(|r| r.outcome.as_ref().ok())
        };
        let points = reference.readings.len();
        let step = dynamic.seconds / (points.max(2) - 1) as f64;
        let half = settled(&reference.readings, points / 2);
        let revolution = (std::f64::consts::TAU / half.cage_speed.abs().max(1e-9) / step).ceil() as usize;
        let span = (points / 2).max(revolution).min(points);
        let at = |t: Option<&Trace>| t.map(|t| settled(&t.readings, span));
        let (f1, f2, f0) = (settled(&reference.readings, span), at(other(2)), at(other(0)));
        let mut row = vec![format!("`{}`", dynamic.name), format!("{:.3}", span as f64 * step)];
        let mut missed = Vec::new();
        for (name, get, with_f0, bound, floor) in AGREEMENT {
            let v = get(&f1);
            row.push(significant(v));
            let ratio = |r: Option<Reading>| r.map_or("–".to_string(), |r| format!("{:.3}", get(&r) / v));
            if with_f0 {
                row.push(ratio(f0));
            }
            row.push(ratio(f2));
            let within = f2.is_some_and(|r| (get(&r) - v).abs() <= (bound * v.abs()).max(floor));
            if !within {
                missed.push(name.split(' ').next().unwrap_or(name));
            }
        }
        row.push(if missed.is_empty() {
            "yes".into()
        } else {
            format!("no: {}", missed.join(", "))
        });
        body.push(row);
    }
    if body.is_empty() {
        return;
    }
    let _ = writeln!(d, "### Fidelities 2 and 0 against fidelity 1\n");
    let _ = writeln!(
        d,
        "The runs of the table above, over their second half or their last cage revolution, whichever is \
         longer (the span column, s): the fidelity-1 value and the ratios fidelity 0 / 1 and 2 / 1. ϕ skew, θ \
         tilt (mean of |·| over rollers and samples, and the largest), T friction torque, cage speed, Qi and Qo \
         the largest cone and cup loads. Fidelity 1 runs at its default tolerance (docs/validation.md checks that \
         tolerance against one a hundred times tighter on the [W25] cases). Fidelity 0 has no skew in lubricated contact. Bounds of fidelity 2: mean \
         skew 10 % (or 0.001°), largest skew 25 %, tilt 5 %, torque 2 %, cage speed 0.5 %, loads 2 %. \
         docs/validation-notes.md explains where mean |skew| differs: fidelity 1's skew vibration about the \
         balance that fidelity 2 gives.\n"
    );
    let mut header = vec!["case".to_string(), "span".to_string()];
    for (name, _, with_f0, _, _) in AGREEMENT {
        header.push(name.to_string());
        if with_f0 {
            header.push("0/1".into());
        }
        header.push("2/1".into());
    }
    header.push("fidelity 2 within the bounds".into());
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    *d += &table(&header, &body);
    d.push('\n');
}

/// `v` with four significant digits.
fn significant(v: f64) -> String {
    let digits = if v == 0.0 || !v.is_finite() {
        0
    } else {
        (3 - v.abs().log10().floor() as i32).max(0) as usize
    };
    format!("{v:.digits$}")
}
