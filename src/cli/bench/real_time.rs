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
//! the same scene.

use super::precision::{self, Trace};
use super::{default_method, long_run_scenario, ScenarioResult};
use crate::cli::report::table;
use std::fmt::Write as _;

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

/// Run every real-time case present in `results` over `seconds` simulated.
pub(super) fn measure(results: &[ScenarioResult], seconds: f64) -> Vec<Row> {
    let mut rows = Vec::new();
    for case in CASES {
        let Some(r) = results.iter().find(|r| r.name == case) else {
            continue;
        };
        let default = default_method(&r.scenario);
        for fidelity in [1, 2, 0] {
            let scenario = at_fidelity(&long_run_scenario(&r.scenario, seconds), fidelity);
            println!("real time: {seconds} s of {case} at default settings, fidelity {fidelity} ...");
            let outcome = precision::run(&scenario, &default);
            if let Ok(t) = &outcome {
                println!("  {:.2} s wall", t.wall);
            }
            rows.push(Row {
                name: case.to_string(),
                fidelity,
                description: r.scenario.description.clone(),
                seconds,
                outcome,
            });
        }
    }
    rows
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

/// `scenario` with the parameter `fidelity` set to `fidelity`.
fn at_fidelity(scenario: &crate::cli::scenario::Scenario, fidelity: i32) -> crate::cli::scenario::Scenario {
    let mut s = scenario.clone();
    let (vr, row) = trb::variables::find("fidelity", s.bearing.bearing.roller_count).expect("fidelity in the model description");
    s.parameters.retain(|(v, _)| v.name != "fidelity");
    let var = crate::cli::scenario::Var {
        vr,
        name: "fidelity".to_string(),
        ty: row.ty,
    };
    s.parameters.push((var, crate::cli::scenario::Value::Integer(fidelity)));
    s
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
