//! `trb stress [--quick] [--fidelity 0,1] [--out docs/robustness.md]`: the numerical stress
//! matrix of issue 6 (see `stress/matrix.rs` for the cases and the checks), written into the
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
    /// Fidelities to run, comma separated (fidelity 1 cases report "not available" until the
    /// dynamic model exists).
    #[arg(long, value_delimiter = ',', default_value = "0")]
    pub fidelity: Vec<i32>,
    /// Document to update.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/robustness.md"))]
    pub out: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Only cases whose id contains this text (the document is not written).
    #[arg(long)]
    pub filter: Option<String>,
}

pub fn run(args: StressArgs) -> Result<(), CliError> {
    for f in &args.fidelity {
        if !(0..=1).contains(f) {
            return Err(CliError::invalid(format!("--fidelity: {f} is not a fidelity (0 or 1)")));
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
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1));
    let scratch = std::env::temp_dir().join(format!("trb-stress-{}", std::process::id()));
    println!("running {} cases on {threads} threads ...", cases.len());
    let run = matrix::Run::execute(cases, threads, &scratch);
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
    if args.filter.is_none() {
        let mut command = "cargo run --release -- stress".to_string();
        if args.quick {
            command.push_str(" --quick");
        }
        if args.fidelity != [0] {
            let f: Vec<String> = args.fidelity.iter().map(|f| f.to_string()).collect();
            command.push_str(&format!(" --fidelity {}", f.join(",")));
        }
        let generated = matrix::report(&run, &command);
        write_section(&args.out, &generated)?;
        println!("wrote {}", args.out.display());
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(CliError::failed(format!("{} stress cases FAILED", failures.len())))
    }
}

/// Replace the generated section of `path` (between the markers) with `generated`.
fn write_section(path: &std::path::Path, generated: &str) -> Result<(), CliError> {
    let old = std::fs::read_to_string(path).unwrap_or_default();
    let section = format!("{BEGIN}\n{generated}\n{END}");
    let text = match (old.find(BEGIN), old.find(END)) {
        (Some(b), Some(e)) if e > b => format!("{}{section}{}", &old[..b], &old[e + END.len()..]),
        _ if old.is_empty() => format!("# Robustness\n\n{section}\n"),
        _ => format!("{}\n{section}\n", old.trim_end()),
    };
    std::fs::write(path, text).map_err(|e| CliError::failed(format!("cannot write {}: {e}", path.display())))
}
