//! `trb simulate SCENARIO.json --out results.csv`: run a scenario with the model code of the
//! FMU (no FMI in between) and write one CSV row per communication point.
//!
//! The stepping order is documented in `cli/scenario.rs` (and scenarios/README.md); every
//! value is printed with Rust's `{:?}` for f64 (shortest text that parses back to the same
//! bits), integers as integers, so a replay through the FMU can be compared exactly.

use super::scenario::{Scenario, Signal, Value};
use super::CliError;
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::fmt::Write as _;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use trb::model::{ModelError, Severity};
use trb::simulation::{AccessError, Simulation};
use trb::variables::VarType;

/// Runs longer than this many steps get a progress bar (on a terminal, unless --quiet).
pub const PROGRESS_THRESHOLD: usize = 2000;

#[derive(Debug, Clone, Args)]
pub struct SimulateArgs {
    /// Scenario file (JSON; see scenarios/README.md).
    #[arg(value_name = "SCENARIO.json")]
    pub scenario: PathBuf,
    /// CSV file to write (`-` for standard output).
    #[arg(long, short, value_name = "results.csv")]
    pub out: PathBuf,
    /// No progress bar and no summary line.
    #[arg(long, short)]
    pub quiet: bool,
}

/// What a completed run did.
#[derive(Debug, Clone)]
pub struct RunSummary {
    pub rows: usize,
    pub columns: usize,
    pub wall: Duration,
}

pub fn run(args: SimulateArgs) -> Result<(), CliError> {
    let scenario = Scenario::load(&args.scenario)?;
    let to_stdout = args.out.as_os_str() == "-";
    let summary = if to_stdout {
        let stdout = std::io::stdout();
        run_to(&scenario, std::io::BufWriter::new(stdout.lock()), args.quiet, "standard output")?
    } else {
        run_to_file(&scenario, &args.out, args.quiet)?
    };
    if !args.quiet {
        let line = summary_line(&scenario, &summary, &args.out);
        if to_stdout {
            eprintln!("{line}");
        } else {
            println!("{line}");
        }
    }
    Ok(())
}

/// How a run's wall time compares with the time it simulated, saying which way: "3.2 × faster
/// than real time" or "2.5 × slower than real time".
pub fn real_time(simulated: f64, wall: f64) -> String {
    let (ratio, way) = if wall <= simulated {
        (simulated / wall, "faster")
    } else {
        (wall / simulated, "slower")
    };
    let digits = if ratio >= 10.0 { 0 } else { 1 };
    format!("{ratio:.digits$} × {way} than real time")
}

pub fn summary_line(scenario: &Scenario, summary: &RunSummary, out: &Path) -> String {
    let simulated = scenario.stop_time - scenario.start_time;
    let wall = summary.wall.as_secs_f64();
    let speed = if wall > 0.0 {
        format!(", {}", real_time(simulated, wall))
    } else {
        String::new()
    };
    format!(
        "{}: {} rows x {} columns, bearing {}, t = {:?} .. {:?} s in {} steps, {:.2} s wall time{speed}",
        out.display(),
        summary.rows,
        summary.columns,
        scenario.bearing.bearing.name,
        scenario.start_time,
        scenario.stop_time,
        scenario.n_steps,
        wall,
    )
}

/// Run `scenario` and write its CSV to `path` (parent directories are created).
pub fn run_to_file(scenario: &Scenario, path: &Path, quiet: bool) -> Result<RunSummary, CliError> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| CliError::failed(format!("cannot create directory {}: {e}", dir.display())))?;
    }
    // Initialize first, so a scenario the model rejects does not clobber an existing file.
    let started = Instant::now();
    let sim = prepare(scenario)?;
    let file = std::fs::File::create(path).map_err(|e| CliError::failed(format!("cannot create {}: {e}", path.display())))?;
    run_prepared(
        scenario,
        sim,
        std::io::BufWriter::new(file),
        quiet,
        &path.display().to_string(),
        started,
    )
}

fn access(name: &str, e: AccessError) -> CliError {
    match e {
        AccessError::Model(m) => model_error(m, None),
        other => CliError::invalid(format!("{name}: {other}")),
    }
}

/// Invalid parameters or inputs are the scenario's fault (exit 2) when found at
/// initialization; anything failing while stepping is a run failure (exit 1).
fn model_error(e: ModelError, at: Option<String>) -> CliError {
    match at {
        Some(at) => CliError::failed(format!("{at}: {e}")),
        None => match e.severity() {
            Severity::Error => CliError::invalid(format!("the model rejected the scenario: {e}")),
            Severity::Discard => CliError::failed(format!("initialization failed: {e}")),
        },
    }
}

/// Run `scenario`, writing the CSV to `w` (`what` names it in messages). On a model error
/// the rows written so far are flushed and kept.
pub fn run_to<W: Write>(scenario: &Scenario, w: W, quiet: bool, what: &str) -> Result<RunSummary, CliError> {
    let started = Instant::now();
    let sim = prepare(scenario)?;
    run_prepared(scenario, sim, w, quiet, what, started)
}

/// Step 1 of the stepping semantics: a new element with the scenario's parameters and
/// inputs u(t_0), initialized at t_0.
pub fn prepare(scenario: &Scenario) -> Result<Simulation, CliError> {
    let mut sim = Simulation::new(scenario.bearing.bearing.clone());

    // 1. Parameters, inputs at t_0, initialization.
    for (var, value) in &scenario.parameters {
        let field = format!("parameters.{}", var.name);
        match value {
            Value::Real(x) => sim.set_real(var.vr, *x),
            Value::Integer(i) => sim.set_integer(var.vr, *i),
            Value::Boolean(b) => sim.set_boolean(var.vr, *b),
        }
        .map_err(|e| access(&field, e))?;
    }
    let t0 = scenario.time(0);
    let u: Vec<f64> = scenario.inputs.iter().map(|(_, s)| s.at(t0)).collect();
    set_inputs(&mut sim, scenario, &u)?;
    sim.initialize(t0).map_err(|e| model_error(e, None))?;
    Ok(sim)
}

/// Step 2: row 0, then the N steps, writing one row per communication point.
fn run_prepared<W: Write>(
    scenario: &Scenario,
    mut sim: Simulation,
    mut w: W,
    quiet: bool,
    what: &str,
    started: Instant,
) -> Result<RunSummary, CliError> {
    let io = |e: std::io::Error| CliError::failed(format!("cannot write {what}: {e}"));
    let t0 = scenario.time(0);
    let mut u: Vec<f64> = scenario.inputs.iter().map(|(_, s)| s.at(t0)).collect();
    writeln!(w, "{}", scenario.header()).map_err(io)?;
    let mut line = String::new();
    let mut rows = 0usize;
    let result = (|| -> Result<(), CliError> {
        sim.outputs().map_err(|e| model_error(e, Some(format!("at t = {t0:?}"))))?;
        let mut warned = 0;
        print_warnings(&sim, &mut warned);
        write_row(&mut line, &mut sim, scenario, t0, &u)?;
        w.write_all(line.as_bytes()).map_err(io)?;
        rows += 1;

        let progress = progress_bar(scenario.n_steps, quiet);
        // 2. Steps.
        for k in 0..scenario.n_steps {
            let t_next = step(&mut sim, scenario, &mut u, k)?;
            sim.outputs()
                .map_err(|e| model_error(e, Some(format!("at t = {t_next:?}: solving for the inputs u({t_next:?}) failed"))))?;
            print_warnings(&sim, &mut warned);
            write_row(&mut line, &mut sim, scenario, t_next, &u)?;
            w.write_all(line.as_bytes()).map_err(io)?;
            rows += 1;
            if let Some(p) = &progress {
                p.inc(1);
            }
        }
        if let Some(p) = progress {
            p.finish_and_clear();
        }
        Ok(())
    })();
    // Keep what was written, also after a failure.
    let flushed = w.flush().map_err(io);
    result?;
    flushed?;
    Ok(RunSummary {
        rows,
        columns: 1 + scenario.inputs.len() + scenario.outputs.len(),
        wall: started.elapsed(),
    })
}

/// Print each warning whose condition holds now and that `warned` (a set of causes) does not
/// hold yet, as the FMU logs it: once per run.
fn print_warnings(sim: &Simulation, warned: &mut u32) {
    let new = sim.warnings() & !*warned;
    *warned |= new;
    for w in trb::warnings::Warning::ALL.into_iter().filter(|w| new & w.bit() != 0) {
        eprintln!("warning: {}", sim.warning_message(w));
    }
}

pub fn set_inputs(sim: &mut Simulation, scenario: &Scenario, u: &[f64]) -> Result<(), CliError> {
    for ((var, _), value) in scenario.inputs.iter().zip(u) {
        sim.set_real(var.vr, *value)
            .map_err(|e| access(&format!("inputs.{}", var.name), e))?;
    }
    Ok(())
}

/// Communication step k of `scenario` (stepping semantics 2, `scenario.rs`), the inputs `u`
/// those at t_k: their rates where the scenario ramps them, the step, and the inputs set to
/// u(t_{k+1}), which `u` becomes. Returns t_{k+1}.
pub fn step(sim: &mut Simulation, scenario: &Scenario, u: &mut [f64], k: usize) -> Result<f64, CliError> {
    let (t, t_next) = (scenario.time(k), scenario.time(k + 1));
    if scenario.interpolate_inputs {
        set_input_rates(sim, scenario, u, t, t_next)?;
    }
    sim.do_step(t, t_next - t).map_err(|e| {
        let inputs = if scenario.interpolate_inputs {
            "inputs ramped"
        } else {
            "inputs held"
        };
        model_error(
            e,
            Some(format!("at t = {t:?}: the step to t = {t_next:?} ({inputs} from u({t:?})) failed")),
        )
    })?;
    for (ui, (_, signal)) in u.iter_mut().zip(&scenario.inputs) {
        *ui = signal.at(t_next);
    }
    set_inputs(sim, scenario, u)?;
    Ok(t_next)
}

/// Set each table input's rate over the step from `t` (inputs `u`) to `t_next`: the secant of
/// its table, so the ramp ends on the table's value at `t_next`.
fn set_input_rates(sim: &mut Simulation, scenario: &Scenario, u: &[f64], t: f64, t_next: f64) -> Result<(), CliError> {
    for ((var, signal), value) in scenario.inputs.iter().zip(u) {
        if let Signal::Table { .. } = signal {
            let rate = (signal.at(t_next) - value) / (t_next - t);
            sim.set_real_derivative(var.vr, rate)
                .map_err(|e| access(&format!("inputs.{}", var.name), e))?;
        }
    }
    Ok(())
}

/// Format one CSV row (with its newline) into `line`.
fn write_row(line: &mut String, sim: &mut Simulation, scenario: &Scenario, t: f64, u: &[f64]) -> Result<(), CliError> {
    line.clear();
    let _ = write!(line, "{t:?}");
    for value in u {
        let _ = write!(line, ",{value:?}");
    }
    for var in &scenario.outputs {
        match var.ty {
            VarType::Real => {
                let v = sim.get_real(var.vr).map_err(|e| access(&var.name, e))?;
                let _ = write!(line, ",{v:?}");
            }
            VarType::Integer => {
                let v = sim.get_integer(var.vr).map_err(|e| access(&var.name, e))?;
                let _ = write!(line, ",{v}");
            }
            VarType::Boolean => {
                let v = sim.get_boolean(var.vr).map_err(|e| access(&var.name, e))?;
                let _ = write!(line, ",{}", v as i32);
            }
        }
    }
    line.push('\n');
    Ok(())
}

fn progress_bar(n_steps: usize, quiet: bool) -> Option<ProgressBar> {
    if quiet || n_steps <= PROGRESS_THRESHOLD || !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::with_draw_target(Some(n_steps as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{spinner} [{elapsed_precise}] {wide_bar} {pos}/{len} steps (eta {eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    Some(bar)
}
