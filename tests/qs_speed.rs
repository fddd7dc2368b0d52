//! Cost of one quasi-static doStep (fidelity 0) in its benchmark cases: for every
//! preset the combined-load, deflected and dry cases, warm-started, 1 ms communication steps.
//! All tests here are ignored (they measure, they do not check):
//!
//!     cargo test --release --test qs_speed -- --ignored --nocapture instructions
//!
//! runs each case under callgrind (valgrind) and prints instructions per doStep (machine
//! independent, repeatable under load; 20 steps after 10, or QS_WARM, warm-up steps), Newton
//! iterations per step and the in-process median wall time per doStep over 300 steps (a
//! cross-check only: it depends on the machine and its load).
//!
//!     QS_DUMP=/tmp/qs_ref.txt cargo test --release --test qs_speed -- --ignored --nocapture dump
//!     QS_REF=/tmp/qs_ref.txt  cargo test --release --test qs_speed -- --ignored --nocapture dump
//!
//! write every Real output of 20 steps of every case to a file, or compare with such a file
//! (largest difference of each output over the steps and rollers, relative to the output's
//! largest magnitude). QS_TOL sets the solver tolerance (1e-10: a tightly converged reference);
//! QS_CMP=file compares that file with QS_REF instead of this run.
//!
//! Cases (speed, Fx as the preset's operating point; Fy, xi, lubrication as named):
//! - `combined`: radial load Fy (TRB130x230 10 kN, 32018X 35 kN, 32008 5 kN, CRB-TRILOBE
//!   1 kN), aligned shaft, EHL;
//! - `deflected`: the preset's operating point (its Fy) with shaft deflection xi = 0.004 deg, EHL;
//! - `dry`: the combined case with `lubrication` = 1;
//! - `TRB130x230 bench`: Fy 10 kN and xi 0.004 deg (the criterion bench's "combined").

use std::time::Instant;
use trb::bearing::Bearing;
use trb::simulation::Simulation;
use trb::variables as var;

const H: f64 = 1e-3;
const MEASURED_STEPS: usize = 20;

/// Steps before the measured ones: 10, or QS_WARM (the warm start's azimuth table fills over
/// the first tens of steps: QS_WARM=200 measures the steady state of a long run).
fn warm_steps() -> usize {
    std::env::var("QS_WARM").ok().and_then(|s| s.parse().ok()).unwrap_or(10)
}

/// (preset, case, Fy or None for the preset's, xi (rad), lubrication)
fn cases() -> Vec<(&'static str, &'static str, Option<f64>, f64, i32)> {
    let xi = 0.004_f64.to_radians();
    let mut v = Vec::new();
    for (preset, fy) in [("TRB130x230", 10e3), ("32018X", 35e3), ("32008", 5e3), ("CRB-TRILOBE", 1e3)] {
        v.push((preset, "combined", Some(fy), 0.0, 0));
        v.push((preset, "deflected", None, xi, 0));
        v.push((preset, "dry", Some(fy), 0.0, 1));
    }
    v.push(("TRB130x230", "bench", Some(10e3), xi, 0));
    v
}

fn build(preset: &str, fy: Option<f64>, xi: f64, lubrication: i32) -> Simulation {
    let mut s = Simulation::new(Bearing::preset(preset).unwrap());
    s.set_integer(var::FIDELITY, 0).unwrap();
    s.set_integer(var::LUBRICATION, lubrication).unwrap();
    if let Some(fy) = fy {
        s.set_real(var::FY, fy).unwrap();
    }
    s.set_real(var::XI, xi).unwrap();
    if let Some(tol) = std::env::var("QS_TOL").ok().and_then(|t| t.parse().ok()) {
        // the solver's tolerance (for a tightly converged reference)
        s.set_real(var::TOLERANCE, tol).unwrap();
    }
    s.initialize(0.0).unwrap();
    for k in 0..warm_steps() {
        s.do_step(k as f64 * H, H).unwrap();
    }
    s
}

fn case_sim(name: &str) -> Simulation {
    let (p, c, fy, xi, l) = cases()
        .into_iter()
        .find(|(p, c, ..)| format!("{p}/{c}") == name)
        .unwrap_or_else(|| panic!("no case {name}"));
    let _ = (p, c);
    build(p, fy, xi, l)
}

/// The measured steps: callgrind collects inside this function only.
#[inline(never)]
fn qs_measured_steps(s: &mut Simulation, n: usize) -> i32 {
    let mut iterations = 0;
    for k in 0..n {
        let t = (warm_steps() + k) as f64 * H;
        s.do_step(t, H).unwrap();
        iterations += s.last_outputs().solver_iterations;
    }
    iterations
}

/// Runs the case named by QS_CASE (`preset/case`) for QS_STEPS steps (under callgrind).
#[test]
#[ignore]
fn kernel() {
    let name = std::env::var("QS_CASE").expect("QS_CASE");
    let n: usize = std::env::var("QS_STEPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(MEASURED_STEPS);
    let mut s = case_sim(&name);
    if std::env::var_os("QS_SEQ").is_some() {
        let mut seq = Vec::new();
        for k in 0..n {
            s.do_step((warm_steps() + k) as f64 * H, H).unwrap();
            seq.push(s.last_outputs().solver_iterations);
        }
        println!("iterations per step {seq:?}");
        return;
    }
    let it = qs_measured_steps(&mut s, n);
    println!("iterations {it}");
}

fn callgrind_instructions(name: &str, n: usize) -> Option<f64> {
    let exe = std::env::current_exe().ok()?;
    let out = std::env::temp_dir().join(format!("qs_speed_{}.callgrind", name.replace('/', "_")));
    let status = std::process::Command::new("valgrind")
        .args([
            "--tool=callgrind",
            "--collect-atstart=no",
            "--toggle-collect=*qs_measured_steps*",
            &format!("--callgrind-out-file={}", out.display()),
        ])
        .arg(&exe)
        .args(["--ignored", "--exact", "kernel", "--test-threads=1", "--nocapture"])
        .env("QS_CASE", name)
        .env("QS_WARM", warm_steps().to_string())
        .env("QS_STEPS", n.to_string())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .ok()?;
    if !status.success() {
        return None;
    }
    let text = std::fs::read_to_string(&out).ok()?;
    let total: f64 = text
        .lines()
        .find_map(|l| l.strip_prefix("summary:").or_else(|| l.strip_prefix("totals:")))?
        .trim()
        .parse()
        .ok()?;
    Some(total / n as f64)
}

/// Instructions (callgrind), Newton iterations and wall time per doStep of every case.
#[test]
#[ignore]
fn instructions() {
    let only = std::env::var("QS_ONLY").ok();
    println!(
        "{:<26} {:>14} {:>12} {:>12} {:>12}",
        "case", "instr/doStep", "iter/step", "max iter", "median us"
    );
    for (p, c, ..) in cases() {
        let name = format!("{p}/{c}");
        if let Some(o) = &only {
            if !name.contains(o.as_str()) {
                continue;
            }
        }
        let instr = callgrind_instructions(&name, MEASURED_STEPS);
        // iterations and wall time in process
        let mut s = case_sim(&name);
        let mut times = Vec::new();
        let mut its = Vec::new();
        for k in 0..300 {
            let t = (warm_steps() + k) as f64 * H;
            let t0 = Instant::now();
            s.do_step(t, H).unwrap();
            times.push(t0.elapsed().as_secs_f64());
            its.push(s.last_outputs().solver_iterations);
        }
        times.sort_by(|a, b| a.partial_cmp(b).unwrap());
        let mean_it = its.iter().sum::<i32>() as f64 / its.len() as f64;
        println!(
            "{:<26} {:>14} {:>12.2} {:>12} {:>12.2}",
            name,
            instr.map(|i| format!("{i:.0}")).unwrap_or_else(|| "n/a".into()),
            mean_it,
            its.iter().max().unwrap(),
            times[times.len() / 2] * 1e6
        );
    }
}

/// Every Real output of `MEASURED_STEPS` steps of every case: written to QS_DUMP, or compared
/// with the file QS_REF.
#[test]
#[ignore]
fn dump() {
    let mut text = String::new();
    for (p, c, ..) in cases() {
        let name = format!("{p}/{c}");
        let mut s = case_sim(&name);
        let vars = var::expanded(s.n_rollers());
        for k in 0..MEASURED_STEPS {
            let t = (warm_steps() + k) as f64 * H;
            s.do_step(t, H).unwrap();
            for (vr, vname, row) in &vars {
                if row.causality == var::Causality::Output && row.ty == var::VarType::Real {
                    let v = s.last_real(*vr).unwrap();
                    text.push_str(&format!("{name} {k} {} {vname} {v:?}\n", row.name));
                }
            }
        }
    }
    if let Ok(path) = std::env::var("QS_DUMP") {
        std::fs::write(path, &text).unwrap();
    }
    if let Ok(path) = std::env::var("QS_CMP") {
        // compare that file instead of this run
        text = std::fs::read_to_string(path).unwrap();
    }
    if let Ok(path) = std::env::var("QS_REF") {
        let reference = std::fs::read_to_string(path).unwrap();
        // (case, row) -> (largest |ref|, largest |diff|, worst variable)
        let mut worst: std::collections::BTreeMap<(String, String), (f64, f64, String)> = Default::default();
        for (a, b) in text.lines().zip(reference.lines()) {
            let fa: Vec<&str> = a.split(' ').collect();
            let fb: Vec<&str> = b.split(' ').collect();
            assert_eq!(fa[..4], fb[..4], "dump layouts differ");
            let (va, vb): (f64, f64) = (fa[4].parse().unwrap(), fb[4].parse().unwrap());
            let e = worst
                .entry((fa[0].to_string(), fa[2].to_string()))
                .or_insert((0.0, 0.0, String::new()));
            e.0 = e.0.max(vb.abs());
            if (va - vb).abs() > e.1 {
                e.1 = (va - vb).abs();
                e.2 = format!("{} step {}: {va:?} vs {vb:?}", fa[3], fa[1]);
            }
        }
        // relative to the output's scale: its largest magnitude over steps and rollers, but at
        // least 1e-6 of the largest magnitude of any output of the same unit in the case (a
        // moment that is zero by symmetry has no scale of its own); solver.residual left out
        let unit_of = |name: &str| -> String {
            ["TRB130x230", "32018X", "32008", "CRB-TRILOBE"]
                .iter()
                .find_map(|p| {
                    let z = Bearing::preset(p).unwrap().roller_count;
                    var::expanded(z)
                        .into_iter()
                        .find(|(_, _, row)| row.name == name)
                        .map(|(_, _, row)| row.unit.unwrap_or("1").to_string())
                })
                .unwrap_or_default()
        };
        let mut unit_scale: std::collections::BTreeMap<(String, String), f64> = Default::default();
        for ((case, row), (scale, _, _)) in &worst {
            let e = unit_scale.entry((case.clone(), unit_of(row))).or_insert(0.0);
            *e = e.max(*scale);
        }
        let mut overall: f64 = 0.0;
        let mut per_case: std::collections::BTreeMap<String, (f64, String)> = Default::default();
        // and against the largest output of the same unit alone (forces against the largest
        // force, moments against the largest moment, ...)
        let mut per_case_unit: std::collections::BTreeMap<String, (f64, String)> = Default::default();
        for ((case, row), (scale, diff, what)) in &worst {
            if row == "solver.residual" {
                continue;
            }
            let unit = unit_scale[&(case.clone(), unit_of(row))];
            let e = per_case_unit.entry(case.clone()).or_insert((0.0, String::new()));
            if unit > 0.0 && diff / unit > e.0 {
                *e = (diff / unit, row.clone());
            }
            let floor = 1e-6 * unit;
            let scale = scale.max(floor);
            let rel = if scale > 0.0 { diff / scale } else { *diff };
            let e = per_case.entry(case.clone()).or_insert((0.0, String::new()));
            if rel > e.0 {
                *e = (rel, format!("{row} ({what})"));
            }
            overall = overall.max(rel);
        }
        for (case, (rel, what)) in per_case {
            println!("{case:<26} max rel change {rel:.3e}  {what}");
        }
        let mut overall_unit: f64 = 0.0;
        for (case, (rel, row)) in per_case_unit {
            println!("{case:<26} max change / largest output of its unit {rel:.3e}  {row}");
            overall_unit = overall_unit.max(rel);
        }
        println!("overall max change relative to the largest output of its unit {overall_unit:.3e}");
        println!("overall max relative change {overall:.3e}");
    }
}

/// Newton iterations per step in a smooth time table: every preset's combined case with the
/// radial load varying as Fy (1 + 0.2 sin(2 pi t / 0.1 s)) and, for the deflected case, xi
/// as 0.004 deg (1 + 0.2 sin(...)), 1 ms steps, 300 steps after 10; with QS_SMOOTH_SPEED set,
/// the shaft speed too.
#[test]
#[ignore]
fn smooth() {
    println!("{:<26} {:>10} {:>9} {:>11}", "case", "iter/step", "max iter", "median us");
    for (p, c, fy, xi, l) in cases() {
        if c == "dry" || std::env::var("QS_ONLY").map_or(false, |o| !format!("{p}/{c}").contains(&o)) {
            continue;
        }
        let mut s = build(p, fy, xi, l);
        let fy0 = s.inputs().fy;
        let xi0 = s.inputs().xi;
        let speed0 = s.inputs().speed;
        // QS_SMOOTH_SPEED: the shaft speed follows the same table (the friction table is
        // rebuilt at every new speed)
        let vary_speed = std::env::var_os("QS_SMOOTH_SPEED").is_some();
        let mut its = Vec::new();
        let mut times = Vec::new();
        for k in 0..300 {
            let t = (warm_steps() + k) as f64 * H;
            let f = 1.0 + 0.2 * (std::f64::consts::TAU * t / 0.1).sin();
            s.set_real(var::FY, fy0 * f).unwrap();
            s.set_real(var::XI, xi0 * f).unwrap();
            if vary_speed {
                s.set_real(var::SPEED, speed0 * f).unwrap();
            }
            let t0 = Instant::now();
            s.do_step(t, H).unwrap();
            times.push(t0.elapsed().as_secs_f64());
            its.push(s.last_outputs().solver_iterations);
        }
        times.sort_by(|a, b| a.partial_cmp(b).unwrap());
        println!(
            "{:<26} {:>10.2} {:>9} {:>11.2}",
            format!("{p}/{c}"),
            its.iter().sum::<i32>() as f64 / its.len() as f64,
            its.iter().max().unwrap(),
            times[times.len() / 2] * 1e6
        );
    }
}
