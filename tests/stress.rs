//! The quick subset of the numerical stress matrix: the same cases as
//! `cargo run --release -- stress`, with shorter time-dependent runs, through `Simulation`
//! and (a representative subset) through the FMU's C ABI, compared bitwise.
//!
//! Failures that are known and reported (physics or validation, not owned by the matrix) are
//! listed in [`KNOWN`] with the text their reason must contain; any other failure fails the
//! test. A known failure that no longer occurs is printed, so the list can be pruned.
#![cfg(all(target_os = "linux", any(target_arch = "x86_64", target_arch = "aarch64")))]

#[allow(dead_code)]
#[path = "../src/cli/stress/matrix.rs"]
mod matrix;

/// (case id, text in the failure reason) of the failures known and documented (see
/// docs/robustness.md, "Findings").
const KNOWN: &[(&str, &str)] = &[
    // F1-F5 of docs/robustness.md are fixed in the quasi-static solver and validation; add
    // entries here only with a documented finding.
];

fn threads() -> usize {
    std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1)
}

/// Run `cases` in the scratch folder `scratch`, print the counts under `label`, name known
/// failures that no longer occur, and fail on any failure that is not in `known`.
fn run_without_new_failures(label: &str, cases: Vec<matrix::Case>, scratch: &str, known: &[(&str, &str)]) -> matrix::Run {
    let scratch = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(scratch);
    let started = std::time::Instant::now();
    let run = matrix::Run::execute(cases, threads(), &scratch);
    let failures = run.failures();
    eprintln!(
        "{label}{} cases in {:.1} s: {} passed, {} refused with a clear message, {} FAILED ({} known); FMU subset {} cases",
        run.cases.len(),
        started.elapsed().as_secs_f64(),
        run.count("passed"),
        run.count("refused"),
        failures.len(),
        known.len(),
        run.fmu.len()
    );
    let is_known = |f: &str| known.iter().any(|(id, why)| f.starts_with(&format!("{id}: ")) && f.contains(why));
    let new: Vec<&String> = failures.iter().filter(|f| !is_known(f)).collect();
    for (id, _) in known {
        if !failures.iter().any(|f| f.starts_with(&format!("{id}: "))) {
            eprintln!("known failure no longer occurs (remove it from the known list): {id}");
        }
    }
    assert!(
        new.is_empty(),
        "new {label}stress failures:\n{}",
        new.iter().map(|s| s.as_str()).collect::<Vec<_>>().join("\n")
    );
    run
}

#[test]
fn quick_stress_matrix_has_no_new_failures() {
    let cases = matrix::cases(0, true);
    assert!(cases.len() >= 200, "only {} cases", cases.len());
    let run = run_without_new_failures("", cases, "stress", KNOWN);
    // Nothing non-finite, ever: a refusal leaves finite outputs (checked per case), and
    // every passing case checked every output after every step.
    assert!(run.count("passed") > run.cases.len() / 2);
}

/// (case id, text in the failure reason) of known fidelity-1 failures (docs/robustness.md,
/// "Findings").
const KNOWN_1: &[(&str, &str)] = &[];

/// The CI subset of the quick fidelity-1 list: the cheap groups (loads up to 0.1 C0 in every
/// direction, speeds up to n_lim, unloaded rollers, out-of-range refusals and their messages,
/// random load jumps to 100 C_r on the tapered presets,
/// the light-load dynamic cases) on every preset, and a run-up from rest and a sudden stop
/// (through standstill, F11) on TRB130x230. The dynamic model costs up to seconds per
/// simulated ms under heavy load; the full list runs with
/// `stress --fidelity 1`.
fn ci_subset(c: &matrix::Case) -> bool {
    let what = c.what.as_str();
    let load = |max: f64| {
        what.strip_suffix("C0")
            .and_then(|f| f.parse::<f64>().ok())
            .is_some_and(|f| f <= max)
    };
    match c.group {
        "load-axial" | "load-radial" | "load-radial-held" | "load-combined" => load(0.1),
        "speed" => what
            .strip_suffix("n_lim")
            .and_then(|f| f.parse::<f64>().ok())
            .is_some_and(|f| f.abs() <= 0.3),
        "unloaded" | "out-of-range" => true,
        "dynamic" => what.contains("kinematic cage") || what.contains("unloaded rollers"),
        // random load jumps up to 100 C_r (each doStep within its wall-clock bound), but on
        // CRB-TRILOBE, whose 40 000 rpm cost about a minute per case
        "jumps" => !c.id.starts_with("CRB-TRILOBE/"),
        // through standstill (F11) on the cheapest preset
        "transient" => {
            c.id.starts_with("TRB130x230/") && (what.starts_with("run-up from rest to n_lim") || what.starts_with("sudden stop"))
        }
        _ => false,
    }
}

#[test]
fn fidelity_1_quick_subset_has_no_new_failures() {
    let f1 = matrix::cases(1, true);
    assert!(f1.len() >= 200, "only {} fidelity-1 cases", f1.len());
    assert!(f1
        .iter()
        .all(|c| c.params.first() == Some(&("fidelity", matrix::Value::Integer(1)))));
    let cases: Vec<matrix::Case> = f1.into_iter().filter(ci_subset).collect();
    let run = run_without_new_failures("fidelity 1: ", cases, "stress-1", KNOWN_1);
    assert_eq!(run.count("not available"), 0);
    assert!(run.cases.len() >= 40 && run.count("passed") > run.cases.len() / 3);
    assert!(
        run.count("refused") > 0,
        "the subset includes refusals (their messages are checked)"
    );
}

#[test]
fn static_capacities_and_limiting_speeds_are_sane() {
    for p in matrix::presets() {
        // C0 of a bearing of this size: hundreds of N per mm^2 of roller projection.
        let b = &p.bearing;
        let projected = b.roller_count as f64 * b.roller_length * b.roller_mean_diameter * 1e6;
        assert!(p.c0 > 20.0 * projected && p.c0 < 50.0 * projected, "{}: C0 = {}", p.name(), p.c0);
        assert!(p.n_lim > 0.0 && p.n_lim.is_finite());
        if p.tapered() {
            assert!(p.fa0 > 0.0 && p.seating_fx_min(p.speed) >= 0.0);
        }
    }
}
