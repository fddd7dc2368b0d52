//! `trb stress [--quick] [--fidelity 0,1,2] [--out docs/robustness.md]`: the numerical stress
//! matrix (see `stress/matrix.rs` for the cases and the checks), written into the
//! generated section of `docs/robustness.md`. Exit code 1 when any case FAILED.
//!
//! The hand-written parts of the document stay as they are: only the text between the
//! markers `<!-- stress:begin -->` and `<!-- stress:end -->` is replaced (a new file gets
//! the markers).

use super::CliError;
use clap::Args;
use std::path::PathBuf;
use std::time::Instant;

pub mod matrix;

pub const BEGIN: &str = "<!-- stress:begin -->";
pub const END: &str = "<!-- stress:end -->";

#[derive(Debug, Clone, Args)]
pub struct StressArgs {
    /// The quick subset: the same cases with shorter time-dependent runs (as `cargo test` runs them).
    #[arg(long)]
    pub quick: bool,
    /// Fidelities to run, comma separated (the cases of a fidelity this build lacks report
    /// "not available").
    #[arg(long, value_delimiter = ',', default_value = "0")]
    pub fidelity: Vec<i32>,
    /// Document to update.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/robustness.md"))]
    pub out: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Extra parameter for every case, `name=value` (repeatable; for experiments: the
    /// document is not written). Integer parameters take an integer, Booleans true/false.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// Print every case (id, outcome, wall time) to stderr as it ends.
    #[arg(long, short)]
    pub verbose: bool,
    /// Only cases whose id contains this text (the document is not written).
    #[arg(long)]
    pub filter: Option<String>,
}

pub fn run(args: StressArgs) -> Result<(), CliError> {
    for f in &args.fidelity {
        if !(0..=2).contains(f) {
            return Err(CliError::invalid(format!("--fidelity: {f} is not a fidelity (0, 1 or 2)")));
        }
    }
    let started = Instant::now();
    let mut cases = Vec::new();
    for f in &args.fidelity {
        cases.extend(matrix::cases(*f, args.quick));
    }
    if let Some(filter) = &args.filter {
        cases.retain(|c| c.id.contains(filter.as_str()));
    }
    for set in &args.set {
        let (name, value) = set
            .split_once('=')
            .ok_or_else(|| CliError::invalid(format!("--set {set}: expected NAME=VALUE")))?;
        let name: &'static str = trb::variables::TABLE
            .iter()
            .find(|v| v.name == name)
            .map(|v| v.name)
            .ok_or_else(|| CliError::invalid(format!("--set {set}: no parameter {name}")))?;
        let value = if let Ok(i) = value.parse::<i32>() {
            matrix::Value::Integer(i)
        } else if let Ok(b) = value.parse::<bool>() {
            matrix::Value::Boolean(b)
        } else {
            matrix::Value::Real(value.parse().map_err(|_| CliError::invalid(format!("--set {set}: not a value")))?)
        };
        for c in &mut cases {
            c.params.retain(|(n, _)| *n != name);
            c.params.push((name, value));
        }
    }
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1));
    let scratch = std::env::temp_dir().join(format!("trb-stress-{}", std::process::id()));
    println!("running {} cases on {threads} threads ...", cases.len());
    let total = cases.len() + cases.iter().filter(|c| c.fmu).count();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let verbose = args.verbose;
    let run = matrix::Run::execute_with(cases, threads, &scratch, |c, r, fmu| {
        let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        if verbose {
            eprintln!(
                "[{k}/{total} {:.0} s] {}{}: {} after {} steps, {:.1} s",
                started.elapsed().as_secs_f64(),
                c.id,
                if fmu { " (FMU)" } else { "" },
                r.outcome.label(),
                r.steps,
                r.seconds
            );
        }
    });
    let _ = std::fs::remove_dir_all(&scratch);

    let failures = run.failures();
    println!(
        "{} cases: {} passed, {} refused with a clear message, {} not available, {} FAILED; FMU subset {} cases ({:.1} s)",
        run.cases.len(),
        run.count("passed"),
        run.count("refused"),
        run.count("not available"),
        run.count("FAILED"),
        run.fmu.len(),
        started.elapsed().as_secs_f64()
    );
    for f in &failures {
        println!("FAILED {f}");
    }
    let mut slow: Vec<(f64, &str)> = run.sim.iter().zip(&run.cases).map(|(r, c)| (r.seconds, c.id.as_str())).collect();
    slow.sort_by(|a, b| b.0.total_cmp(&a.0));
    let shown: Vec<String> = slow.iter().take(5).map(|(s, id)| format!("{id} {s:.1} s")).collect();
    println!("slowest: {}", shown.join(", "));
    if args.filter.is_none() && args.set.is_empty() {
        let mut command = "cargo run --release -- stress".to_string();
        if args.quick {
            command.push_str(" --quick");
        }
        if args.fidelity != [0] {
            let f: Vec<String> = args.fidelity.iter().map(|f| f.to_string()).collect();
            command.push_str(&format!(" --fidelity {}", f.join(",")));
        }
        let (header, parts) = matrix::report(&run, &command);
        write_section(&args.out, &header, &parts)?;
        println!("wrote {}", args.out.display());
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(CliError::failed(format!("{} stress cases FAILED", failures.len())))
    }
}

/// Replace the generated section of `path` (between the markers) with `header` and, per
/// fidelity, the new part if it ran, else the part the document already has (so
/// `--fidelity 2` keeps the fidelity-0 and fidelity-1 results, and so on).
fn write_section(path: &std::path::Path, header: &str, parts: &[(i32, String)]) -> Result<(), CliError> {
    super::report::replace_section_parts(path, (BEGIN, END, "Robustness"), "stress", header, parts, 0..=2)
}
