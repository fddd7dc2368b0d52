//! The `trb` command line: argument definitions (clap derive) and dispatch.
//!
//! Every subcommand lives in its own module with an argument struct (`#[derive(clap::Args)]`)
//! and a `run(args) -> Result<(), CliError>` function. To add a subcommand: write
//! `cli/<name>.rs` with its arguments and `run`, add `pub mod <name>;` below, a variant to
//! [`Command`] and its arm in [`run`]. Nothing else needs to change.
//!
//! Exit codes: 0 success, 1 the model or the file system failed while running, 2 the request
//! was invalid (command line, scenario file, bearing file), as clap does for usage errors, 3 an
//! external tool the command needs is missing (`fmu --portable`: the message names each one and
//! how to install it).

use clap::{Parser, Subcommand};
use std::fmt;

pub mod bearing;
pub mod bench;
pub mod demo;
pub mod documentation;
pub mod icon;
pub mod package;
pub mod paths;
pub mod portable;
pub mod report;
pub mod scenario;
pub mod simulate;
pub mod soak;
pub mod stress;
pub mod strip;
pub mod study;
pub mod svg;

/// Tapered roller bearing element: package the FMI 2.0 Co-Simulation FMU, or run a scenario
/// with the same model code without FMI.
#[derive(Debug, Parser)]
#[command(name = "trb", version, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Package the FMU (default: <cargo target dir>/fmu/TaperedRollerBearing.fmu; another bearing's: <cargo target dir>/fmu/TRB_<name>.fmu).
    Fmu(package::FmuArgs),
    /// Run a scenario file (see scenarios/README.md) and write the results as CSV.
    Simulate(simulate::SimulateArgs),
    /// Package the default FMU, run scenarios/demo.json and demo_dynamic.json, print short tables and where the CSVs and the plot go.
    Demo(demo::DemoArgs),
    /// Run the cases of the studies [D19], [L22], [Y22]; write docs/results-studies.md and docs/figures/.
    Study(study::StudyArgs),
    /// Run the numerical stress matrix and update docs/robustness.md.
    Stress(stress::StressArgs),
    /// Benchmark: work-precision of the dynamic model, kernels and targets; update docs/performance.md.
    Bench(bench::BenchArgs),
    /// Bearing files: `show NAME` prints a preset as a bearing file to start from.
    Bearing(bearing::BearingArgs),
    /// Hours of duty: a duty cycle at fidelity 0 and long runs at fidelities 1 and 2; update docs/soak.md.
    Soak(soak::SoakArgs),
}

/// Run the parsed command line.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Fmu(args) => package::run(args),
        Command::Simulate(args) => simulate::run(args),
        Command::Demo(args) => demo::run(args),
        Command::Study(args) => study::run(args),
        Command::Stress(args) => stress::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Bearing(args) => bearing::run(args),
        Command::Soak(args) => soak::run(args),
    }
}

/// A failed command: the message for stderr and the process exit code.
#[derive(Debug, Clone, PartialEq)]
pub struct CliError {
    pub code: i32,
    pub message: String,
}

impl CliError {
    /// The request was invalid (bad scenario, bad bearing file, bad option): exit code 2.
    pub fn invalid(message: impl Into<String>) -> CliError {
        CliError {
            code: 2,
            message: message.into(),
        }
    }

    /// An external program the command needs is not installed: exit code 3.
    pub fn missing_tool(message: impl Into<String>) -> CliError {
        CliError {
            code: 3,
            message: message.into(),
        }
    }

    /// Running failed (model error, I/O error): exit code 1.
    pub fn failed(message: impl Into<String>) -> CliError {
        CliError {
            code: 1,
            message: message.into(),
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for CliError {}
