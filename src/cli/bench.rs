//! `trb bench [--quick] [--repeats N] [--filter TEXT]`: the performance report.
//!
//! 1. Work-precision of the dynamic model: every scenario in `benches/scenarios/` is run with
//!    a sweep of settings of the three integrators (`precision::sweep`), each repeated for
//!    a median wall time, and compared with a reference run at a far tighter tolerance
//!    (`precision::reference`), itself checked against a second, different method
//!    (`precision::checks`). Writes one SVG work-precision diagram per scenario.
//! 2. The speedup at equal error of each adaptive method over the study's fixed-step method.
//! 3. The targets table: right-hand side, quasi-static doStep, FMI bookkeeping per doStep,
//!    and the [W25] 3500 rpm case over 0.5 s simulated with the cheapest setting of each
//!    method that meets torque and skew errors of 1e-3 on the benchmark window.
//!
//! The report replaces the section between `<!-- bench:begin -->` and `<!-- bench:end -->`
//! of `docs/performance.md`; the hand-written rest stays.

use super::report::{self, table};
use super::scenario::Scenario;
use super::svg::{self, Series};
use super::CliError;
use clap::Args;
use precision::{Method, Trace, FAMILIES, OUTPUTS};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

mod kernels;
pub mod precision;
mod real_time;

pub const BEGIN: &str = "<!-- bench:begin -->";
pub const END: &str = "<!-- bench:end -->";

/// Runs longer than this (s) are not repeated: their relative noise is small.
const LONG_RUN: f64 = 10.0;

/// The error level of the targets (torque and skew).
const TARGET_ERROR: f64 = 1e-3;

#[derive(Debug, Clone, Args)]
pub struct BenchArgs {
    /// A smoke run: one setting per method, one repeat, loose reference, no 0.5 s runs.
    #[arg(long)]
    pub quick: bool,
    /// Repeats of every timed run (the report gives the median).
    #[arg(long, default_value_t = 3)]
    pub repeats: usize,
    /// Only scenarios whose file name contains this text.
    #[arg(long)]
    pub filter: Option<String>,
    /// Skip the 0.5 s runs of the [W25] case (minutes with the explicit methods) and of the
    /// real-time cases.
    #[arg(long)]
    pub skip_long: bool,
    /// Simulated seconds of the long [W25] runs of the targets table and of the real-time runs.
    #[arg(long, default_value_t = 0.5)]
    pub long_seconds: f64,
    /// Folder of the benchmark scenarios.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/scenarios"))]
    pub scenarios: PathBuf,
    /// Folder of the real-time cases that have no work-precision window.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/real_time"))]
    pub real_time: PathBuf,
    /// Document to update (its generated section); figures go to `figures/` next to it.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/performance.md"))]
    pub out: PathBuf,
}

/// One scenario's runs.
struct ScenarioResult {
    name: String,
    scenario: Scenario,
    reference: Trace,
    reference_method: Method,
    /// The check run and its largest difference from the reference over the outputs.
    check: Option<(Method, f64)>,
    check_failures: Vec<(Method, String)>,
    runs: Vec<RunResult>,
    /// The window at fidelities 2 and 0 (`OTHER_FIDELITIES`), default settings.
    fidelities: Vec<(i32, Result<Measured, String>)>,
}

struct RunResult {
    method: Method,
    outcome: Result<Measured, String>,
}

struct Measured {
    wall: f64,
    trace: Trace,
    errors: [f64; OUTPUTS.len()],
}

impl ScenarioResult {
    /// The cheapest run of `integrator` whose torque/skew error is at most `level`.
    fn cheapest(&self, integrator: i32, level: f64) -> Option<(&Method, &Measured)> {
        self.runs
            .iter()
            .filter(|r| r.method.integrator == integrator)
            .filter_map(|r| r.outcome.as_ref().ok().map(|m| (&r.method, m)))
            .filter(|(_, m)| precision::torque_skew_error(&m.errors) <= level)
            .min_by(|a, b| a.1.wall.total_cmp(&b.1.wall))
    }

    /// Smallest error the reference resolves: the check's difference (0 without a check).
    fn resolution(&self) -> f64 {
        self.check.map_or(0.0, |c| c.1)
    }
}

pub fn run(args: BenchArgs) -> Result<(), CliError> {
    if args.repeats == 0 {
        return Err(CliError::invalid("--repeats must be at least 1"));
    }
    if !(args.long_seconds > 0.0 && args.long_seconds.is_finite()) {
        return Err(CliError::invalid("--long-seconds must be positive"));
    }
    let started = Instant::now();
    let repeats = if args.quick { 1 } else { args.repeats };
    let scenarios = load_scenarios(&args.scenarios, args.filter.as_deref(), args.quick)?;
    if scenarios.is_empty() {
        return Err(CliError::invalid(format!("no benchmark scenario in {}", args.scenarios.display())));
    }
    let mut results = Vec::new();
    for (name, scenario) in scenarios {
        results.push(bench_scenario(name, scenario, repeats, args.quick)?);
    }
    println!("timing kernels ...");
    let kernels = Kernels::measure(args.quick).map_err(CliError::failed)?;
    let slices = slice_study(&results, args.quick)?;
    let (long, real_time) = if args.quick || args.skip_long {
        (Vec::new(), Vec::new())
    } else {
        (
            long_runs(&results, args.long_seconds)?,
            real_time::measure(&results, &args.real_time, args.filter.as_deref(), args.long_seconds)?,
        )
    };
    let figures = args
        .out
        .parent()
        .map(|p| p.join("figures"))
        .unwrap_or_else(|| PathBuf::from("figures"));
    std::fs::create_dir_all(&figures).map_err(|e| CliError::failed(format!("cannot create {}: {e}", figures.display())))?;
    let runs = Runs {
        slices: &slices,
        long: &long,
        real_time: &real_time,
    };
    let text = document(&args, &results, &kernels, &runs, &figures, started.elapsed().as_secs_f64())?;
    report::replace_section(&args.out, BEGIN, END, "Performance", &text)?;
    println!("wrote {} ({:.0} s)", args.out.display(), started.elapsed().as_secs_f64());
    Ok(())
}

/// The scenario files of the folder whose names contain `filter` (sorted by name; none is
/// no error); `quick` shortens each to 10 steps.
fn load_scenarios(dir: &Path, filter: Option<&str>, quick: bool) -> Result<Vec<(String, Scenario)>, CliError> {
    let entries = std::fs::read_dir(dir).map_err(|e| CliError::invalid(format!("cannot read {}: {e}", dir.display())))?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    let mut out = Vec::new();
    for path in files {
        let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        if filter.is_some_and(|f| !name.contains(f)) {
            continue;
        }
        let mut scenario = Scenario::load(&path)?;
        if quick {
            scenario.n_steps = scenario.n_steps.min(10);
            scenario.stop_time = scenario.start_time + scenario.n_steps as f64 * scenario.step;
        }
        out.push((name, scenario));
    }
    Ok(out)
}

/// Reference, check and the sweep of one scenario.
fn bench_scenario(name: String, scenario: Scenario, repeats: usize, quick: bool) -> Result<ScenarioResult, CliError> {
    let reference_method = precision::reference(quick);
    println!("{name}: reference {} {} ...", reference_method.family(), reference_method.label());
    let reference =
        precision::run(&scenario, &reference_method).map_err(|e| CliError::failed(format!("{name}: the reference run failed: {e}")))?;
    let mut check = None;
    let mut check_failures = Vec::new();
    for m in precision::checks(quick) {
        match precision::run(&scenario, &m) {
            Ok(t) => {
                let d = precision::max_error(&precision::errors(&t, &reference));
                println!("  check {} {}: largest difference {d:.2e}", m.family(), m.label());
                check = Some((m, d));
                break;
            }
            Err(e) => {
                println!("  check {} {} failed: {e}", m.family(), m.label());
                check_failures.push((m, e));
            }
        }
    }
    let mut runs = Vec::new();
    for method in precision::sweep(quick) {
        let outcome = timed(&scenario, &method, repeats, &reference);
        match &outcome {
            Ok(m) => println!(
                "  {} {}: {:.3} s, {} steps, error {:.2e}, torque/skew {:.2e}",
                method.family(),
                method.label(),
                m.wall,
                m.trace.steps,
                precision::max_error(&m.errors),
                precision::torque_skew_error(&m.errors)
            ),
            Err(e) => println!("  {} {}: failed: {e}", method.family(), method.label()),
        }
        runs.push(RunResult { method, outcome });
    }
    // the other fidelities at default settings, at the window's communication step
    let fidelities = OTHER_FIDELITIES
        .iter()
        .map(|&(fidelity, what)| {
            let outcome = timed(&at_fidelity(&scenario, fidelity), &default_method(&scenario), repeats, &reference);
            match &outcome {
                Ok(m) => println!("  {what}: {:.3} s, error {:.2e}", m.wall, precision::max_error(&m.errors)),
                Err(e) => println!("  {what}: failed: {e}"),
            }
            (fidelity, outcome)
        })
        .collect();
    Ok(ScenarioResult {
        name,
        scenario,
        reference,
        reference_method,
        check,
        check_failures,
        runs,
        fidelities,
    })
}

/// `scenario` run with `method` `repeats` times (once where a run is long): the median wall
/// time, the last trace and its errors against `reference`.
fn timed(scenario: &Scenario, method: &Method, repeats: usize, reference: &Trace) -> Result<Measured, String> {
    let mut walls = Vec::new();
    let mut trace = None;
    for _ in 0..repeats {
        let t = precision::run(scenario, method)?;
        walls.push(t.wall);
        let long = t.wall > LONG_RUN;
        trace = Some(t);
        if long {
            break;
        }
    }
    let trace = trace.ok_or_else(|| "no run".to_string())?;
    Ok(Measured {
        wall: precision::median(&walls),
        errors: precision::errors(&trace, reference),
        trace,
    })
}

/// The fidelities run beside the dynamic model's sweep in every work-precision window, with
/// their names in the report.
const OTHER_FIDELITIES: [(i32, &str); 2] = [(2, "quasi-dynamic (fidelity 2)"), (0, "quasi-static (fidelity 0)")];

/// Medians of the kernels of the targets table (seconds).
struct Kernels {
    rhs_axial: f64,
    rhs_combined: f64,
    quasi_static_step: f64,
    bookkeeping: kernels::Bookkeeping,
}

impl Kernels {
    fn measure(quick: bool) -> Result<Kernels, String> {
        Ok(Kernels {
            bookkeeping: kernels::fmi_do_step_seconds(quick)?,
            rhs_axial: kernels::rhs_seconds(20, 0.0, quick)?,
            rhs_combined: kernels::rhs_seconds(20, 25_000.0, quick)?,
            quasi_static_step: kernels::quasi_static_step_seconds(quick)?,
        })
    }
}

/// The fidelity knob `slices` on the [W25] window: cost and output change against 20 slices.
struct SliceRow {
    slices: usize,
    rhs: f64,
    outcome: Result<(Trace, [f64; OUTPUTS.len()]), String>,
}

/// Slices per contact line: RHS cost and the change of every output against 20 slices
/// (Dormand–Prince at 1e-7, so that integration error is far below the differences).
fn slice_study(results: &[ScenarioResult], quick: bool) -> Result<Vec<SliceRow>, CliError> {
    let Some(w25) = results.iter().find(|r| r.name.starts_with("w25_axial")) else {
        return Ok(Vec::new());
    };
    let method = Method {
        integrator: 0,
        setting: 1e-7,
    };
    let with_slices = |n: usize| -> Result<Trace, String> {
        let mut s = w25.scenario.clone();
        let (vr, row) = trb::variables::find("slices", s.bearing.bearing.roller_count).expect("slices parameter");
        s.parameters.retain(|(v, _)| v.name != "slices");
        s.parameters.push((
            super::scenario::Var {
                vr,
                name: "slices".into(),
                ty: row.ty,
            },
            super::scenario::Value::Integer(n as i32),
        ));
        precision::run(&s, &method)
    };
    let base = with_slices(20).map_err(|e| CliError::failed(format!("slices study, 20 slices: {e}")))?;
    let mut rows = Vec::new();
    for n in [5, 10, 20, 40] {
        println!("slices {n} ...");
        let rhs = kernels::rhs_seconds(n, 0.0, quick).map_err(CliError::failed)?;
        let outcome = if n == 20 { Ok(base.clone()) } else { with_slices(n) }.map(|t| {
            let e = precision::errors(&t, &base);
            (t, e)
        });
        rows.push(SliceRow { slices: n, rhs, outcome });
    }
    Ok(rows)
}

/// Communication step of the long runs (s): `stepSize` of the DefaultExperiment.
const LONG_RUN_STEP: f64 = 1e-3;

/// A long run of the [W25] case with a method chosen on the benchmark window.
struct LongRun {
    why: &'static str,
    method: Method,
    window_error: f64,
    seconds: f64,
    outcome: Result<Trace, String>,
}

/// The [W25] axial case over `seconds` simulated with the cheapest setting meeting the
/// target error of the explicit method and of the fastest method (once each).
fn long_runs(results: &[ScenarioResult], seconds: f64) -> Result<Vec<LongRun>, CliError> {
    let Some(w25) = results.iter().find(|r| r.name.starts_with("w25_axial")) else {
        return Ok(Vec::new());
    };
    let mut picks: Vec<(&'static str, Method, f64)> = Vec::new();
    if let Some((m, meas)) = w25.cheapest(0, TARGET_ERROR) {
        picks.push(("explicit (Dormand–Prince)", *m, precision::torque_skew_error(&meas.errors)));
    }
    let fastest = FAMILIES
        .iter()
        .filter_map(|f| w25.cheapest(f.0, TARGET_ERROR))
        .min_by(|a, b| a.1.wall.total_cmp(&b.1.wall));
    if let Some((m, meas)) = fastest {
        if picks.iter().all(|p| p.1 != *m) {
            picks.push(("fastest method", *m, precision::torque_skew_error(&meas.errors)));
        } else {
            picks[0].0 = "explicit, also the fastest method";
        }
        // The window holds only the start of the run: the next tighter setting of the fastest
        // adaptive method too, which may be the one that holds the error over the whole run.
        let tighter = w25
            .runs
            .iter()
            .filter(|r| m.integrator != 1 && r.method.integrator == m.integrator)
            .filter(|r| (r.method.setting * 10.0 / m.setting - 1.0).abs() < 1e-9)
            .find_map(|r| r.outcome.as_ref().ok().map(|meas| (r.method, meas)));
        if let Some((method, meas)) = tighter {
            picks.push(("fastest method, 10× tighter", method, precision::torque_skew_error(&meas.errors)));
        }
    }
    if let Some((m, meas)) = w25.cheapest(1, TARGET_ERROR) {
        picks.push((
            "the [W25] method (Gill + Milne–Hamming)",
            *m,
            precision::torque_skew_error(&meas.errors),
        ));
    }
    // Real time at default settings: the default integrator at the preset's tolerance,
    // whatever the window says is cheapest
    let default = default_method(&w25.scenario);
    if picks.iter().all(|p| p.1 != default) {
        let window_error = w25
            .runs
            .iter()
            .find(|r| r.method == default)
            .and_then(|r| r.outcome.as_ref().ok())
            .map_or(f64::NAN, |meas| precision::torque_skew_error(&meas.errors));
        picks.push(("default settings", default, window_error));
    }
    // At the communication step of the FMU's default experiment (a system simulation's step,
    // not the benchmark window's 0.1 ms, which would cap the implicit method's steps)
    let scenario = long_run_scenario(&w25.scenario, seconds);
    let mut out = Vec::new();
    for (why, method, window_error) in picks {
        println!(
            "long run: {seconds} s of {} with {} {} ...",
            w25.name,
            method.family(),
            method.label()
        );
        let outcome = precision::run(&scenario, &method);
        if let Ok(t) = &outcome {
            println!("  {:.1} s wall", t.wall);
        }
        out.push(LongRun {
            why,
            method,
            window_error,
            seconds,
            outcome,
        });
    }
    Ok(out)
}

/// The default settings of the scenario's bearing: the automatic integrator at its tolerance.
fn default_method(scenario: &Scenario) -> Method {
    Method {
        integrator: trb::model::AUTOMATIC_INTEGRATOR as i32,
        setting: trb::simulation::Simulation::new(scenario.bearing.bearing.clone())
            .params()
            .tolerance,
    }
}

/// `scenario` (its inputs) over `seconds` simulated in the long runs' communication step.
fn long_run_scenario(scenario: &Scenario, seconds: f64) -> Scenario {
    let mut s = scenario.clone();
    s.step = LONG_RUN_STEP;
    s.n_steps = ((seconds - s.start_time) / s.step).round().max(1.0) as usize;
    s.stop_time = s.start_time + seconds;
    s
}

/// `scenario` with the parameter `fidelity` set to `fidelity`.
pub(super) fn at_fidelity(scenario: &Scenario, fidelity: i32) -> Scenario {
    let mut s = scenario.clone();
    s.set_parameter("fidelity", fidelity.into())
        .expect("fidelity 0, 1 and 2 are in the parameter's range");
    s
}

fn sci(v: f64) -> String {
    format!("{v:.1e}")
}

fn micro(s: f64) -> String {
    format!("{:.2} µs", s * 1e6)
}

/// The generated section.
/// The runs of the report beside the work-precision sweeps.
struct Runs<'a> {
    slices: &'a [SliceRow],
    long: &'a [LongRun],
    real_time: &'a [real_time::Row],
}

fn document(
    args: &BenchArgs,
    results: &[ScenarioResult],
    k: &Kernels,
    runs: &Runs,
    figures: &Path,
    elapsed: f64,
) -> Result<String, CliError> {
    let mut d = String::new();
    let mut command = String::from("cargo run --release -- bench");
    if args.quick {
        command.push_str(" --quick");
    }
    if let Some(f) = &args.filter {
        let _ = write!(command, " --filter {f}");
    }
    let _ = writeln!(d, "Generated by `{command}`; do not edit by hand.\n");
    let _ = writeln!(
        d,
        "Machine: {}. Compiler: {}. Commit: {}. Date: {}. Median of {} repeats per timed run (runs over {LONG_RUN} s once); \
         one core; the whole benchmark took {:.0} s.\n",
        report::machine(),
        report::compiler(),
        report::commit(),
        report::date(),
        if args.quick { 1 } else { args.repeats },
        elapsed
    );
    targets(&mut d, results, k, runs.long);
    real_time::write(&mut d, runs.real_time);
    real_time::write_agreement(&mut d, runs.real_time);
    speedups(&mut d, results);
    slice_table(&mut d, runs.slices);
    let _ = writeln!(d, "### Work-precision diagrams\n");
    let _ = writeln!(
        d,
        "Error of an output: RMS over the communication points of the difference from the \
         reference, divided by the RMS of the reference signal (or by a floor where that is \
         nearly zero: skew 1e-7 rad, tilt 1e-8 rad, cage speed 1e-3 rad/s, torque 1e-3 N m, \
         force 1 N, moment 1 N m, cone displacement 1 nm). The run's error is the largest \
         over {} outputs: {}. Torque/skew error: the largest over friction torque, mean \
         skew and roller 1's skew. Wall time: the whole run, building the element and the \
         quasi-static start included. Errors below the reference's resolution (its \
         difference from the check run) are drawn at that resolution. The quasi-dynamic \
         (fidelity 2) and quasi-static (fidelity 0) models at default settings are single points, \
         run at the window's communication step: their error is what the model leaves out (the \
         contact and skew vibrations; at fidelity 0 all dynamics and the lubricated skew), not \
         an integration error.\n",
        OUTPUTS.len(),
        OUTPUTS.iter().map(|o| format!("`{}`", o.0)).collect::<Vec<_>>().join(", ")
    );
    for r in results {
        scenario_section(&mut d, r, figures)?;
    }
    Ok(d)
}

fn targets(d: &mut String, results: &[ScenarioResult], k: &Kernels, long: &[LongRun]) {
    let _ = writeln!(d, "### Targets (17 rollers, 20 slices, one core)\n");
    let status = |v: f64, goal: f64| if v <= goal { "met" } else { "not met" };
    let mut rows = vec![
        vec![
            "quasi-static doStep ([W25] case, warm start)".into(),
            "≤ 20 µs".into(),
            micro(k.quasi_static_step),
            status(k.quasi_static_step, 20e-6).into(),
        ],
        vec![
            "one right-hand side, [W25] case (Fa 30 kN, 3500 rpm)".into(),
            "≤ 6 µs".into(),
            micro(k.rhs_axial),
            status(k.rhs_axial, 6e-6).into(),
        ],
        vec![
            "one right-hand side, combined load (Fa 30 kN, Fr 25 kN)".into(),
            "≤ 6 µs".into(),
            micro(k.rhs_combined),
            status(k.rhs_combined, 6e-6).into(),
        ],
    ];
    let b = &k.bookkeeping;
    rows.push(vec![
        format!(
            "FMU bookkeeping per doStep: fmi2DoStep (median {}) − Simulation::do_step (median {}), difference of the fastest samples ± the resolution (half the interquartile range of paired differences)",
            micro(b.through_fmi),
            micro(b.direct)
        ),
        "≤ 0.2 µs".into(),
        if b.added < 0.0 {
            format!("{} (measured {}: noise) ± {}", micro(0.0), micro(b.added), micro(b.spread))
        } else {
            format!("{} ± {}", micro(b.added), micro(b.spread))
        },
        if b.added <= 0.2e-6 {
            if b.spread > 0.2e-6 { "met, within the resolution" } else { "met" }
        } else {
            "not met"
        }
        .into(),
    ]);
    // The whole run's error, against the long run of the smallest error on the window (the
    // fixed-step method at a step that resolves the contact modes, where it ran): the window
    // holds the start-up transient only.
    let reference = long
        .iter()
        .filter_map(|l| l.outcome.as_ref().ok().map(|t| (l.window_error, t)))
        .min_by(|a, b| a.0.total_cmp(&b.0));
    for l in long {
        let goal = if l.why.starts_with("explicit") { 1.5 } else { 0.5 } * l.seconds / 0.5;
        let (value, met) = match &l.outcome {
            Ok(t) => {
                let whole = match reference {
                    Some((_, r)) if !std::ptr::eq(r, t) => format!(
                        "; torque/skew error {} over the whole run",
                        sci(precision::torque_skew_error(&precision::errors(t, r)))
                    ),
                    _ => String::new(),
                };
                (
                    format!(
                        "{} s wall ({} steps, {} RHS{whole})",
                        if t.wall < 10.0 {
                            format!("{:.2}", t.wall)
                        } else {
                            format!("{:.1}", t.wall)
                        },
                        t.steps,
                        t.rhs
                    ),
                    status(t.wall, goal).to_string(),
                )
            }
            Err(e) => (format!("failed: {e}"), "not met".into()),
        };
        let goal_text = if l.why.starts_with("the [W25]") {
            "(comparison)".to_string()
        } else {
            format!("≤ {goal:.1} s")
        };
        rows.push(vec![
            format!(
                "[W25] 3500 rpm, {} s simulated in {} ms communication steps, {}: {} {} (torque/skew error {} on the window)",
                l.seconds,
                LONG_RUN_STEP * 1e3,
                l.why,
                l.method.family(),
                l.method.label(),
                sci(l.window_error)
            ),
            goal_text,
            value,
            met,
        ]);
    }
    if long.is_empty() {
        rows.push(vec![
            "[W25] 3500 rpm, 0.5 s simulated".into(),
            "≤ 1.5 s explicit, ≤ 0.5 s fastest".into(),
            "not run (--quick or --skip-long)".into(),
            "–".into(),
        ]);
    }
    if let Some(w25) = results.iter().find(|r| r.name.starts_with("w25_axial")) {
        let window = w25.scenario.stop_time - w25.scenario.start_time;
        for f in FAMILIES {
            if let Some((m, meas)) = w25.cheapest(f.0, TARGET_ERROR) {
                rows.push(vec![
                    format!(
                        "[W25] window {window} s, cheapest {} with torque/skew error ≤ 1e-3: {}",
                        f.1,
                        m.label()
                    ),
                    "–".into(),
                    format!("{:.3} s wall, {:.0} s per simulated s", meas.wall, meas.wall / window),
                    "–".into(),
                ]);
            }
        }
    }
    d.push_str(&table(&["target", "goal", "measured (median)", "status"], &rows));
    d.push('\n');
}

fn slice_table(d: &mut String, rows: &[SliceRow]) {
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(d, "### Fidelity knob: slices per contact line ([W25] window)\n");
    let _ = writeln!(
        d,
        "Cost of one right-hand side and of the window (Dormand–Prince, tol 1e-7) against the \
         number of slices, and how far the outputs move from the 20-slice run (relative RMS as \
         above). Fewer slices is a fidelity choice, not an integration error: it changes the \
         contact-line load distribution and so the tilting and skewing moments.\n"
    );
    let mut table_rows = Vec::new();
    for r in rows {
        let mut row = vec![r.slices.to_string(), micro(r.rhs)];
        match &r.outcome {
            Ok((t, e)) => {
                row.push(format!("{:.3} s ({} RHS)", t.wall, t.rhs));
                for k in [5, 0, 3, 4, 10] {
                    row.push(sci(e[k]));
                }
            }
            Err(e) => {
                row.push(format!("failed: {e}"));
                row.extend(std::iter::repeat_n(String::new(), 5));
            }
        }
        table_rows.push(row);
    }
    d.push_str(&table(
        &[
            "slices",
            "one RHS",
            "window wall",
            "frictionTorque",
            "roller[1].skew",
            "tilt.max",
            "cage.speed",
            "Qo.max",
        ],
        &table_rows,
    ));
    d.push('\n');
}

fn speedups(d: &mut String, results: &[ScenarioResult]) {
    let _ = writeln!(d, "### Speedup over the study's method at equal error\n");
    let _ = writeln!(
        d,
        "For each error level: the cheapest run of each method whose torque/skew error is at \
         most that level (median wall time), and the ratio of the Gill/Milne–Hamming wall time \
         to the method's. \"none\" means no run of the sweep reached the level (for the \
         fixed-step method: every step large enough to be cheap is unstable).\n"
    );
    let mut rows = Vec::new();
    for r in results {
        for level in [1e-3, 1e-5] {
            let gmh = r.cheapest(1, level).map(|x| x.1.wall);
            let mut row = vec![r.name.clone(), sci(level)];
            for f in FAMILIES {
                row.push(match r.cheapest(f.0, level) {
                    Some((m, meas)) => format!("{:.3} s ({})", meas.wall, m.label()),
                    None => "none".into(),
                });
            }
            for f in [0, 2, 3] {
                row.push(match (r.cheapest(f, level), gmh) {
                    (Some((_, meas)), Some(g)) => format!("{:.1}×", g / meas.wall),
                    _ => "–".into(),
                });
            }
            rows.push(row);
        }
    }
    d.push_str(&table(
        &[
            "scenario",
            "error level",
            "Dormand–Prince",
            "Rosenbrock-W",
            "automatic",
            "Gill/Milne–Hamming",
            "speedup DP",
            "speedup ROS",
            "speedup auto",
        ],
        &rows,
    ));
    d.push('\n');
}

fn scenario_section(d: &mut String, r: &ScenarioResult, figures: &Path) -> Result<(), CliError> {
    let window = r.scenario.stop_time - r.scenario.start_time;
    let _ = writeln!(d, "#### {}\n", r.name);
    let _ = writeln!(
        d,
        "{} Window {window} s, communication step {} s ({} points). Reference: {} {} ({:.2} s, {} steps, {} RHS).",
        r.scenario.description,
        r.scenario.step,
        r.scenario.n_steps + 1,
        r.reference_method.family(),
        r.reference_method.label(),
        r.reference.wall,
        r.reference.steps,
        r.reference.rhs
    );
    for (m, e) in &r.check_failures {
        let _ = write!(d, " Check with {} {} failed: {e}.", m.family(), m.label());
    }
    match r.check {
        Some((m, diff)) => {
            let _ = writeln!(
                d,
                " Check: {} {} differs from the reference by at most {} (relative RMS, largest over the outputs).\n",
                m.family(),
                m.label(),
                sci(diff)
            );
        }
        None => {
            let _ = writeln!(d, " No check run succeeded: the reference is unconfirmed.\n");
        }
    }
    let floor = r.resolution();
    let mut series = Vec::new();
    for f in FAMILIES {
        let points: Vec<(f64, f64)> = r
            .runs
            .iter()
            .filter(|x| x.method.integrator == f.0)
            .filter_map(|x| x.outcome.as_ref().ok())
            .map(|m| (precision::max_error(&m.errors).max(floor).max(1e-16), m.wall))
            .collect();
        if !points.is_empty() {
            series.push(Series::new(f.2, points));
        }
    }
    for (fidelity, outcome) in &r.fidelities {
        if let Ok(m) = outcome {
            let point = (precision::max_error(&m.errors).max(floor).max(1e-16), m.wall);
            series.push(Series::new(&format!("fidelity {fidelity}"), vec![point]));
        }
    }
    if !series.is_empty() {
        let name = format!("bench_{}.svg", r.name);
        let svg = svg::chart(
            &format!("{}: work-precision", r.name),
            "error (largest relative RMS over the outputs)",
            "wall time (s)",
            &series,
            true,
            true,
        );
        let path = figures.join(&name);
        std::fs::write(&path, svg).map_err(|e| CliError::failed(format!("cannot write {}: {e}", path.display())))?;
        let _ = writeln!(d, "![{name}](figures/{name})\n");
    }
    let cells = |outcome: &Result<Measured, String>| match outcome {
        Ok(m) => {
            let e = precision::max_error(&m.errors);
            let worst = m.errors.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1)).map_or(0, |w| w.0);
            let shown = |v: f64| if v < floor { format!("< {}", sci(floor)) } else { sci(v) };
            vec![
                format!("{:.3}", m.wall),
                format!("{:.0}", m.wall / window),
                m.trace.steps.to_string(),
                m.trace.rhs.to_string(),
                m.trace.rejected.to_string(),
                shown(e),
                shown(precision::torque_skew_error(&m.errors)),
                format!("`{}`", OUTPUTS[worst].0),
            ]
        }
        Err(e) => std::iter::once(format!("failed: {e}"))
            .chain(std::iter::repeat_n(String::new(), 7))
            .collect(),
    };
    let mut rows = Vec::new();
    for x in &r.runs {
        let mut row = vec![x.method.short_family().to_string(), x.method.label()];
        row.extend(cells(&x.outcome));
        rows.push(row);
    }
    for (fidelity, outcome) in &r.fidelities {
        let what = OTHER_FIDELITIES.iter().find(|f| f.0 == *fidelity).map_or("", |f| f.1);
        let mut row = vec![what.to_string(), "default".to_string()];
        row.extend(cells(outcome));
        rows.push(row);
    }
    d.push_str(&table(
        &[
            "method",
            "setting",
            "wall (s)",
            "wall per simulated s",
            "steps",
            "RHS",
            "rejected",
            "error",
            "torque/skew error",
            "worst output",
        ],
        &rows,
    ));
    d.push('\n');
    Ok(())
}
