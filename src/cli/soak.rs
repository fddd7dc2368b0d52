//! `trb soak [--fidelity0 3600] [--fidelity1 60] [--fidelity2 60] [--out docs/soak.md]`:
//! hours of duty, one element per fidelity (`soak/duty.rs`), judged by what a long run must
//! keep. Writes the generated part of each fidelity that ran into the document (the parts of
//! the fidelities skipped stay as they are) and exits with code 1 when a criterion fails:
//! - no failed step and no output that is not finite;
//! - resident memory grows by less than [`MEMORY_GROWTH`] after the first minute;
//! - fidelities 1 and 2: the energy books close within [`ENERGY_RESIDUAL`] of the
//!   dissipation;
//! - fidelity 0: every later cycle of the duty cycle gives the first cycle's outputs within
//!   [`REPEAT`] (relative).

use super::report;
use super::CliError;
use clap::Args;
use std::path::PathBuf;

pub mod duty;

pub const BEGIN: &str = "<!-- soak:begin -->";
pub const END: &str = "<!-- soak:end -->";
/// Largest growth of the resident memory after the first minute (bytes).
pub const MEMORY_GROWTH: i64 = 1 << 20;
/// Largest energy residual over the dissipation (fidelities 1 and 2).
pub const ENERGY_RESIDUAL: f64 = 0.01;
/// Largest relative difference between cycles (fidelity 0).
pub const REPEAT: f64 = 1e-9;

#[derive(Debug, Clone, Args)]
pub struct SoakArgs {
    /// Simulated seconds of the fidelity-0 duty cycle (0: skip).
    #[arg(long, default_value_t = 3600.0)]
    pub fidelity0: f64,
    /// Simulated seconds at fidelity 1 under combined load (0: skip).
    #[arg(long, default_value_t = 60.0)]
    pub fidelity1: f64,
    /// Simulated seconds at fidelity 2 under the same combined load (0: skip).
    #[arg(long, default_value_t = 60.0)]
    pub fidelity2: f64,
    /// Document to update.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/soak.md"))]
    pub out: PathBuf,
}

/// The criteria a run fails, as sentences (empty: it passed).
pub fn failures(r: &duty::Soak) -> Vec<String> {
    let mut f = Vec::new();
    if let Some((t, m)) = &r.failure {
        f.push(format!("failed at t = {t} s: {m}"));
    }
    if r.memory_growth() >= MEMORY_GROWTH {
        f.push(format!(
            "resident memory grew by {} kB after the first minute",
            r.memory_growth() / 1024
        ));
    }
    if r.fidelity != 0 && r.failure.is_none() && !(r.energy_residual() < ENERGY_RESIDUAL) {
        f.push(format!("energy books open by {:.2e} of the dissipation", r.energy_residual()));
    }
    if r.fidelity == 0 && r.repeat_error > REPEAT {
        f.push(format!("a later cycle differs from the first by {:.2e}", r.repeat_error));
    }
    f
}

fn row(r: &duty::Soak) -> Vec<String> {
    let books = if r.fidelity != 0 {
        format!(
            "shaft {:.1} J, dissipated {:.1} J, kinetic {:+.2e} J, loads {:+.2e} J: residual {:.1e}",
            r.shaft_work,
            r.dissipated,
            r.kinetic_change,
            r.load_work,
            r.energy_residual()
        )
    } else {
        "closed by construction (no stored energy; loss = torque × speed)".to_string()
    };
    let repeat = if r.fidelity == 0 && r.repeat_points == 0 {
        "one cycle: nothing to compare".to_string()
    } else if r.fidelity == 0 {
        format!(
            "{:.1e} over {} axisymmetric points of later cycles",
            r.repeat_error, r.repeat_points
        )
    } else if r.simulated >= 2.0 {
        format!(
            "mean torque {:.4} N m in the 2nd second, {:.4} N m in the last",
            r.torque_first, r.torque_last
        )
    } else {
        format!("mean torque {:.4} N m in the last second", r.torque_last)
    };
    let failed = failures(r);
    vec![
        r.fidelity.to_string(),
        format!("{:.0} s", r.simulated),
        format!("{:.1} s ({:.3} s per simulated s)", r.wall, r.wall / r.simulated.max(1e-12)),
        format!("{:.1} MB, {:+} kB", r.rss_end as f64 / 1e6, r.memory_growth() / 1024),
        books,
        repeat,
        if failed.is_empty() {
            "passed".into()
        } else {
            format!("**FAILED**: {}", failed.join("; "))
        },
    ]
}

pub fn run(args: SoakArgs) -> Result<(), CliError> {
    for (name, v) in [
        ("--fidelity0", args.fidelity0),
        ("--fidelity1", args.fidelity1),
        ("--fidelity2", args.fidelity2),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(CliError::invalid(format!("{name}: {v} is not a number of seconds")));
        }
    }
    let mut runs = Vec::new();
    if args.fidelity0 > 0.0 {
        eprintln!("fidelity 0: {} s of the duty cycle ...", args.fidelity0);
        runs.push(duty::fidelity_0(args.fidelity0));
    }
    if args.fidelity1 > 0.0 {
        eprintln!("fidelity 1: {} s under combined load ...", args.fidelity1);
        runs.push(duty::fidelity_1(args.fidelity1));
    }
    if args.fidelity2 > 0.0 {
        eprintln!("fidelity 2: {} s under combined load ...", args.fidelity2);
        runs.push(duty::fidelity_2(args.fidelity2));
    }
    let (date, machine, commit) = (report::date(), report::machine(), report::commit());
    let parts: Vec<(i32, String)> = runs
        .iter()
        .map(|r| {
            let part = format!(
                "Fidelity {f}: generated by `trb soak --fidelity{f} {}` on {date}, {machine} (commit {commit}).\n\n{}",
                [args.fidelity0, args.fidelity1, args.fidelity2][r.fidelity as usize],
                report::table(
                    &[
                        "fidelity",
                        "simulated",
                        "wall time",
                        "resident memory at the end, growth after the first minute",
                        "energy books",
                        "repeatability",
                        "result"
                    ],
                    &[row(r)]
                ),
                f = r.fidelity,
            );
            println!("{part}");
            (r.fidelity, part)
        })
        .collect();
    report::replace_section_parts(&args.out, (BEGIN, END, "Soak: hours of duty"), "soak", "", &parts, 0..=2)?;
    let failed: Vec<String> = runs.iter().flat_map(failures).collect();
    if failed.is_empty() {
        Ok(())
    } else {
        Err(CliError::failed(format!("soak: {}", failed.join("; "))))
    }
}
