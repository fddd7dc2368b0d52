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

/// (case id, text in the failure reason) of known fidelity-2 failures of the CI subset
/// (docs/robustness.md, "Findings", F17 and F18). Each is a refusal with fmi2Discard and a
/// message naming the quasi-dynamic balance, its iterations and its largest correction, or an
/// averaged balance that does not close; none is a crash, a NaN or an unbounded step.
const KNOWN_2: &[(&str, &str)] = &[
    // through the rollers' standstill (run-up from rest, a stop, a reversal): the regularised friction is stiffest there, the limitation of a start from rest (F17a); TRB130x230's stop and reversal pass
    ("TRB130x230/transient/run-up from rest to n_lim", "did not converge"),
    ("32018X/transient/run-up from rest to n_lim", "did not converge"),
    ("32018X/transient/sudden stop from n_lim", "did not converge"),
    ("32018X/transient/reversal +n_lim to -n_lim", "did not converge"),
    ("32008/transient/run-up from rest to n_lim", "did not converge"),
    ("32008/transient/sudden stop from n_lim", "did not converge"),
    ("32008/transient/reversal +n_lim to -n_lim", "did not converge"),
    // a tenfold speed step within one step (F17b)
    ("32008/transient/speed step 0.1 to 1 n_lim", "did not converge"),
    // 32018X, 26 rollers at 60 rpm, with a load zone or changing inputs: the balance fails from its first step, mostly with corrections of 1e4 to 1e7 times their limits (F17c)
    ("32018X/load-radial-held/0.3C0", "did not converge"),
    ("32018X/load-combined/0.3C0", "did not converge"),
    ("32018X/load-radial-held/0.6C0", "did not converge"),
    ("32018X/load-combined/0.6C0", "did not converge"),
    ("32018X/load-radial-held/1C0", "did not converge"),
    ("32018X/load-combined/1C0", "did not converge"),
    ("32018X/speed/-1n_lim", "did not converge"),
    ("32018X/speed/-0.3n_lim", "did not converge"),
    ("32018X/speed/0.3n_lim", "did not converge"),
    ("32018X/speed/1n_lim", "did not converge"),
    ("32018X/transient/speed step 0.1 to 1 n_lim", "did not converge"),
    ("32018X/transient/load step 0.05 to 0.5 C0", "did not converge"),
    ("32018X/transient/load step 0.5 to 0.05 C0", "did not converge"),
    ("32018X/transient/deflection step 0 to 0.05 deg", "did not converge"),
    ("32018X/transient/rotating radial load", "did not converge"),
    ("32018X/deflection/xi 0.01 deg", "did not converge"),
    ("32018X/deflection/xi 0.05 deg", "did not converge"),
    ("32018X/deflection/zeta -0.05 deg", "did not converge"),
    ("32018X/step-size/h = 1e-6 s", "did not converge"),
    ("32018X/step-size/h = 1e-5 s", "did not converge"),
    ("32018X/step-size/h = 1e-4 s", "did not converge"),
    ("32018X/step-size/h = 1e-3 s", "did not converge"),
    ("32018X/step-size/h = 1e-2 s", "did not converge"),
    ("32018X/step-size/h = 1e-1 s", "did not converge"),
    ("32018X/slices/2 slices", "did not converge"),
    ("32018X/slices/3 slices", "did not converge"),
    ("32018X/slices/5 slices", "did not converge"),
    ("32018X/slices/50 slices", "did not converge"),
    ("32018X/slices/100 slices", "did not converge"),
    ("32018X/slices/200 slices", "did not converge"),
    ("32018X/long/0.05 s, h = 10 ms, varying", "did not converge"),
    ("32018X/long/0.05 s, h = 1 ms, constant", "did not converge"),
    ("32018X/unloaded/small load zone (Fa = 1.1 Fr tan a + 2 Fa_min)", "did not converge"),
    ("32018X/dynamic/energy balance, 0.1 C0 combined, constant", "did not converge"),
    ("32018X/dynamic/energy balance, 0.3 C0 combined, xi 0.05 deg", "did not converge"),
    (
        "32018X/dynamic/cage impacts: rotating 0.01 C0 at n_lim, pocket clearance 1 mm",
        "did not converge",
    ),
    (
        "32018X/dynamic/pure radial 0.05 C0, cone held at zero axial displacement (unloaded rollers)",
        "did not converge",
    ),
    ("32018X/parameters/dry, mu = 2", "did not converge"),
    ("32018X/parameters/oil.eta0 = 100 Pa s", "did not converge"),
    ("32018X/parameters/oil.alpha = 1e-7", "did not converge"),
    ("32018X/parameters/cageSlipRate = 0", "did not converge"),
    ("32018X/parameters/cageSlipRate = 1", "did not converge"),
    ("32018X/parameters/tolerance = 1e-14", "did not converge"),
    ("32018X/parameters/tolerance = 0.1", "did not converge"),
    ("32018X/parameters/clearance = +5 % D", "did not converge"),
    ("32018X/parameters/crownDrop = 5 % D", "did not converge"),
    ("32018X/parameters/roller[2].dD = -1 % D", "did not converge"),
    ("32018X/parameters/no centrifugal, no gyroscopic", "did not converge"),
    ("32018X/parameters/cage.angle0 = 1e6 rad", "did not converge"),
    ("32018X/dynamic/startSteady = false, 0.1 C0 combined", "did not converge"),
    // long communication steps (0.01 and 0.1 s) under a moving load zone (F17d)
    ("TRB130x230/step-size/h = 1e-1 s", "did not converge"),
    ("32008/step-size/h = 1e-2 s", "did not converge"),
    ("32008/step-size/h = 1e-1 s", "did not converge"),
    // 32008 at constant inputs under a load zone: refused after 16 to 35 good steps of 1 ms (F17e)
    ("32008/dynamic/energy balance, 0.1 C0 combined, constant", "did not converge"),
    (
        "32008/dynamic/pure radial 0.05 C0, cone held at zero axial displacement (unloaded rollers)",
        "did not converge",
    ),
    // parameters at the ends of their ranges: dry friction with mu = 2, extreme viscosities, a pressure-viscosity coefficient of 0, a 5 % D crown (F17f)
    ("TRB130x230/parameters/dry, mu = 2", "did not converge"),
    ("32008/parameters/dry, mu = 2", "did not converge"),
    ("32008/parameters/oil.eta0 = 100 Pa s", "did not converge"),
    ("32008/parameters/crownDrop = 5 % D", "did not converge"),
    // CRB-TRILOBE at 40 000 rpm with a deflected shaft: refused at its first or second step (F17g)
    ("CRB-TRILOBE/deflection/xi 0.01 deg", "did not converge"),
    ("CRB-TRILOBE/deflection/zeta -0.05 deg", "did not converge"),
    // steps whose balance converges only on the held quasi-static seat (warning SeatHeld): the mean reaction.Fx misses Fx by 3.2 % (F18)
    ("32008/dynamic/energy balance, 0.3 C0 combined, xi 0.05 deg", "mean reaction.Fx"),
];

/// The CI subset of the quick fidelity-2 list: every case of the three tapered presets
/// (loads to 3 C0, speeds, transients, deflections, step sizes, slices, long runs, unloaded
/// rollers, parameter ends, out-of-range refusals, random jumps, the `dynamic` group) and,
/// on CRB-TRILOBE, whose 40 000 rpm cost most, the loads, speeds, deflections, unloaded
/// rollers, random jumps and out-of-range refusals. The whole quick list runs with
/// `stress --quick --fidelity 2` (about 90 s on 2 cores).
fn ci_subset_2(c: &matrix::Case) -> bool {
    !c.id.starts_with("CRB-TRILOBE/")
        || matches!(
            c.group,
            "load-axial"
                | "load-radial"
                | "load-radial-held"
                | "load-combined"
                | "speed"
                | "deflection"
                | "unloaded"
                | "out-of-range"
                | "jumps"
        )
}

#[test]
fn fidelity_2_quick_subset_has_no_new_failures() {
    let f2 = matrix::cases(2, true);
    assert!(f2.len() >= 200, "only {} fidelity-2 cases", f2.len());
    assert!(f2
        .iter()
        .all(|c| c.params.first() == Some(&("fidelity", matrix::Value::Integer(2)))));
    // the quasi-dynamic model runs its defaults: no integrator or tolerance set for it
    assert!(f2.iter().all(|c| !c.params.iter().any(|(n, _)| *n == "integrator")));
    let cases: Vec<matrix::Case> = f2.into_iter().filter(ci_subset_2).collect();
    let run = run_without_new_failures("fidelity 2: ", cases, "stress-2", KNOWN_2);
    assert_eq!(run.count("not available"), 0);
    assert!(run.cases.len() >= 300 && run.count("passed") > run.cases.len() / 3);
    assert!(
        run.count("refused") > 0,
        "the subset includes refusals (their messages are checked)"
    );
    // every refusal of a start from rest says that the balance did not converge (the
    // documented limitation), and the out-of-range inputs are refused before any balance
    for (c, r) in run.cases.iter().zip(&run.sim) {
        if let matrix::Outcome::Refused { message, discard, .. } = &r.outcome {
            if c.params
                .iter()
                .any(|(n, v)| *n == "startFromRest" && *v == matrix::Value::Boolean(true))
            {
                assert!(message.contains("did not converge") && *discard, "{}: {message}", c.id);
            }
        }
    }
    assert!(!run.fmu.is_empty());
}
