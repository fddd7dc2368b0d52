//! `trb study validate [--quick]`: where the product meets the papers and an independent
//! model, number by number. Writes `docs/validation.md`:
//!
//! 1. [W25]: every number its text states (Figs. 6, 7, 10, 11), its stated trends and the
//!    measured skew range it cites, against the dynamic model (fidelity 1) run on the
//!    scenarios of `scenarios/w25_dynamic/`, and the time-averaged energy balance per run;
//! 2. [D19] §3: roller counts, critical friction coefficients, pocket-clearance changes and
//!    the skew's share of the torque (32018X dry, skew model);
//! 3. [L22] Table 3 and its statements on the torque and sliding friction of rollers with
//!    diameter deviations (32008, `scenarios/l22_*.json`);
//! 4. [Y22]: the stated trends of its results section (CRB-TRILOBE, `scenarios/y22_*.json`);
//! 5. the friction torque against the SKF frictional-moment model (`trb::skf_friction`);
//! 6. [L22]'s torque statements (it gives torques in figures only);
//! 7. in plain words, where the product differs and where that is documented.
//!
//! Every lubricated product number is given for both `traction` laws (0 thermal Eyring, the
//! default; 1 the isothermal Newtonian–Eyring law, kept for comparison with the studies), set
//! through the FMU parameter exactly as a scenario file sets it. The cases are the shipped
//! ones: the [W25] runs go through `w25::run_case` with a [`Variant`]; the quasi-static
//! cases are the shipped scenario files with the FMU parameters and inputs of the case
//! changed ([`Scenario::set_parameter`], [`Scenario::set_input`]); the dry [D19] sweeps are
//! `trb::quasi_static::studies::d19`. Everything runs one case at a time.

mod supply;

use super::w25::{self, CaseResult, Variant};
use crate::cli::report::{self, table};
use crate::cli::scenario::Scenario;
use crate::cli::simulate::prepare;
use crate::cli::CliError;
use serde_json::json;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;
use trb::model::Outputs;
use trb::quasi_static::studies::{self, D19Preload, Y22State};
use trb::skf_friction::{self, SkfMoment, SkfTrb};

const DEG: f64 = 180.0 / std::f64::consts::PI;
/// rpm → rad/s.
const RPM: f64 = std::f64::consts::PI / 30.0;
/// The values of the FMU parameter `traction`, in column order.
const TRACTIONS: [i32; 2] = [0, 1];
/// Product columns of a lubricated case (one per traction law).
const LUBRICATED: &[&str] = &["product, traction 0", "product, traction 1"];
/// Product column of a dry case (the traction law does not enter).
const DRY: &[&str] = &["product (dry)"];
/// A ratio product/reference outside 1 ± this is called a difference in section 7.
const OFF_BY: f64 = 0.3;

// =============================================================================================
// What to run
// =============================================================================================

/// The full comparison, or `--quick`: 10 ms dynamic runs instead of the scenarios' 50 ms,
/// three dynamic cases, and fewer points in every sweep.
#[derive(Debug, Clone, Copy)]
struct Plan {
    quick: bool,
}

impl Plan {
    /// A [W25] run with the `traction` law (and 10 ms long in quick mode).
    fn dynamic_variant(&self, traction: i32) -> Variant {
        Variant {
            traction: Some(traction),
            fidelity: None,
            stop_time: self.quick.then_some(0.01),
            contact_law: None,
            parameters: &[],
        }
    }

    /// The [W25] deflection cases run again with Johnson's law as the book writes it
    /// (indices into `W25_DEFLECTION`).
    fn book_law_cases(&self) -> Vec<usize> {
        if self.quick {
            vec![0, 4]
        } else {
            (0..W25_DEFLECTION.len()).collect()
        }
    }

    fn run_length_ms(&self) -> f64 {
        if self.quick {
            10.0
        } else {
            50.0
        }
    }

    fn pick(&self, full: &[f64], quick: &[f64]) -> Vec<f64> {
        if self.quick {
            quick.to_vec()
        } else {
            full.to_vec()
        }
    }

    /// The [W25] scenario files to run, each once per traction law.
    fn w25_cases(&self) -> Vec<&'static str> {
        if self.quick {
            return W25_QUICK.to_vec();
        }
        let mut v: Vec<&'static str> = Vec::new();
        for n in W25_DEFLECTION
            .iter()
            .chain(&W25_SPEED_ALIGNED)
            .chain(&W25_SPEED_DEFLECTED)
            .chain(&W25_AXIAL_ALIGNED)
            .chain(&W25_AXIAL_DEFLECTED)
            .chain(&W25_PRELOAD)
        {
            if !v.contains(n) {
                v.push(n);
            }
        }
        v
    }
}

// =============================================================================================
// The ledger: every comparison, for section 7
// =============================================================================================

struct RatioEntry {
    source: &'static str,
    what: String,
    /// (product column, product / reference)
    ratios: Vec<(&'static str, f64)>,
}

struct CheckEntry {
    source: &'static str,
    what: String,
    /// (product column, holds)
    holds: Vec<(&'static str, bool)>,
}

/// Every comparison the document makes, and what could not be computed.
#[derive(Default)]
struct Ledger {
    ratios: Vec<RatioEntry>,
    checks: Vec<CheckEntry>,
    failures: Vec<String>,
    /// Computed observations for section 7, by source.
    facts: Vec<(&'static str, String)>,
}

impl Ledger {
    fn fact(&mut self, source: &'static str, text: String) {
        self.facts.push((source, text));
    }
}

// =============================================================================================
// Formatting
// =============================================================================================

/// A number with about three significant digits; integers as integers; never "NaN".
fn num(v: f64) -> String {
    if !v.is_finite() {
        return "—".into();
    }
    let a = v.abs();
    if v.fract() == 0.0 && a < 1e6 {
        format!("{v:.0}")
    } else if a >= 1e5 || a < 1e-2 {
        format!("{v:.2e}")
    } else if a >= 100.0 {
        format!("{v:.1}")
    } else if a >= 10.0 {
        format!("{v:.2}")
    } else if a >= 1.0 {
        format!("{v:.3}")
    } else {
        format!("{v:.4}")
    }
}

fn opt(v: Option<f64>) -> String {
    v.map(num).unwrap_or_else(|| "—".into())
}

fn ratio(product: Option<f64>, reference: f64) -> Option<f64> {
    let p = product?;
    (reference != 0.0 && reference.is_finite() && p.is_finite()).then(|| p / reference)
}

fn ratio_text(r: Option<f64>) -> String {
    r.map(|r| format!("{r:.3}")).unwrap_or_else(|| "—".into())
}

/// A number with four significant digits (for values that differ in the fourth).
fn num4(v: f64) -> String {
    let a = v.abs();
    if !v.is_finite() {
        "—".into()
    } else if v.fract() == 0.0 && a < 1e6 {
        format!("{v:.0}")
    } else if a >= 1e5 || a < 1e-2 {
        format!("{v:.3e}")
    } else {
        let d = (3 - a.log10().floor() as i32).max(0) as usize;
        format!("{v:.d$}")
    }
}

/// "a → b → c" of a few values.
fn chain(v: &[f64]) -> String {
    v.iter().map(|x| num4(*x)).collect::<Vec<_>>().join(" → ")
}

/// "a → b (monotone)" of a long sweep: first and last value, and whether every step goes the
/// same way.
fn ends(v: &[f64]) -> String {
    let (a, b) = (v[0], v[v.len() - 1]);
    let monotone = if b >= a { non_decreasing(v) } else { non_increasing(v) };
    format!("{} → {}{}", num4(a), num4(b), if monotone { "" } else { " (not monotone)" })
}

/// Equal within a millionth of the largest magnitude (solver noise).
fn tol(v: &[f64]) -> f64 {
    1e-6 * v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

fn non_decreasing(v: &[f64]) -> bool {
    let e = tol(v);
    v.windows(2).all(|w| w[1] >= w[0] - e)
}

fn non_increasing(v: &[f64]) -> bool {
    let e = tol(v);
    v.windows(2).all(|w| w[1] <= w[0] + e)
}

fn increasing(v: &[f64]) -> bool {
    v.windows(2).all(|w| w[1] > w[0])
}

fn decreasing(v: &[f64]) -> bool {
    v.windows(2).all(|w| w[1] < w[0])
}

/// Falls to a minimum inside the range, then rises.
fn falls_then_rises(v: &[f64]) -> bool {
    let k = v.iter().enumerate().fold(0, |best, (i, x)| if *x < v[best] { i } else { best });
    k > 0 && k + 1 < v.len() && decreasing(&v[..=k]) && increasing(&v[k..])
}

/// A table of a study's numbers beside the product's: per product column the value and the
/// ratio product / study.
struct Compare {
    source: &'static str,
    columns: &'static [&'static str],
    rows: Vec<Vec<String>>,
}

impl Compare {
    fn new(source: &'static str, columns: &'static [&'static str]) -> Compare {
        Compare {
            source,
            columns,
            rows: Vec::new(),
        }
    }

    /// One number of the study (`reference`; 0 = "unchanged", no ratio) against the
    /// product's values (`None`: not run).
    fn row(&mut self, ledger: &mut Ledger, what: &str, reference: f64, product: &[Option<f64>]) {
        let mut r = vec![what.to_string(), num(reference)];
        let mut ratios = Vec::new();
        for (c, p) in self.columns.iter().zip(product) {
            let q = ratio(*p, reference);
            r.push(opt(*p));
            r.push(ratio_text(q));
            if let Some(q) = q {
                ratios.push((*c, q));
            }
        }
        if !ratios.is_empty() {
            ledger.ratios.push(RatioEntry {
                source: self.source,
                what: what.to_string(),
                ratios,
            });
        }
        self.rows.push(r);
    }

    fn text(&self) -> String {
        let mut head = vec!["quantity", "study"];
        for c in self.columns {
            head.push(c);
            head.push("ratio");
        }
        table(&head, &self.rows) + "\n"
    }
}

/// A table of a study's statements, each with the product's verdict and numbers per column.
struct Checks {
    source: &'static str,
    columns: &'static [&'static str],
    rows: Vec<Vec<String>>,
}

impl Checks {
    fn new(source: &'static str, columns: &'static [&'static str]) -> Checks {
        Checks {
            source,
            columns,
            rows: Vec::new(),
        }
    }

    /// A statement with the product's verdict per column (`None`: not run).
    fn row(&mut self, ledger: &mut Ledger, statement: &str, verdicts: Vec<Option<(bool, String)>>) {
        self.push(Some(ledger), statement, verdicts);
    }

    /// A row that depends on a sign convention the study does not state: shown, not counted.
    fn info(&mut self, statement: &str, verdicts: Vec<Option<(bool, String)>>) {
        self.push(None, statement, verdicts);
    }

    fn push(&mut self, ledger: Option<&mut Ledger>, statement: &str, verdicts: Vec<Option<(bool, String)>>) {
        let mut r = vec![statement.to_string()];
        let mut holds = Vec::new();
        for (c, v) in self.columns.iter().zip(&verdicts) {
            r.push(match v {
                Some((b, detail)) => {
                    holds.push((*c, *b));
                    format!("**{}**: {detail}", if *b { "yes" } else { "no" })
                }
                None => "not run".into(),
            });
        }
        if let Some(l) = ledger {
            if !holds.is_empty() {
                l.checks.push(CheckEntry {
                    source: self.source,
                    what: statement.to_string(),
                    holds,
                });
            }
        }
        self.rows.push(r);
    }

    fn text(&self) -> String {
        let mut head = vec!["the study states"];
        head.extend(self.columns.iter().copied());
        table(&head, &self.rows) + "\n"
    }
}

/// `f` per traction law (index into [`TRACTIONS`]).
fn per_traction<T>(f: impl FnMut(usize) -> Option<T>) -> Vec<Option<T>> {
    (0..TRACTIONS.len()).map(f).collect()
}

// =============================================================================================
// Running the shipped cases
// =============================================================================================

fn scenarios_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios")
}

/// A shipped scenario file (path relative to `scenarios/`).
fn shipped(file: &str) -> Result<Scenario, CliError> {
    Scenario::load(&scenarios_dir().join(file))
}

/// The element's state at the start of `scenario` (quasi-static: one solve).
fn operating_point(scenario: &Scenario) -> Result<Outputs, CliError> {
    Ok(prepare(scenario)?.last_outputs().clone())
}

/// A shipped case with some FMU parameters and inputs changed (the same mechanism as a
/// scenario file's `parameters` and `inputs`), solved at its start.
fn shipped_case_with(base: &Scenario, parameters: &[(&str, serde_json::Value)], inputs: &[(&str, f64)]) -> Result<Outputs, CliError> {
    let mut s = base.clone();
    for (name, v) in parameters {
        s.set_parameter(name, v.clone()).map_err(CliError::invalid)?;
    }
    for (name, v) in inputs {
        s.set_input(name, *v).map_err(CliError::invalid)?;
    }
    operating_point(&s)
}

// =============================================================================================
// 1. [W25]
// =============================================================================================

const W25_DEFLECTION: [&str; 7] = [
    "deflection_xi0.000",
    "deflection_xi0.001",
    "deflection_xi0.002",
    "deflection_xi0.003",
    "deflection_xi0.004",
    "deflection_xi0.005",
    "deflection_xi0.006",
];
const W25_XI_DEG: [f64; 7] = [0.0, 0.001, 0.002, 0.003, 0.004, 0.005, 0.006];
/// §4.1 (Fig. 6): mean and largest tilt (deg) at each shaft deflection.
const W25_TILT_AVG: [f64; 7] = [2.20e-4, 3.51e-4, 6.48e-4, 9.55e-4, 1.26e-3, 1.57e-3, 1.88e-3];
const W25_TILT_MAX: [f64; 7] = [2.21e-4, 7.17e-4, 1.22e-3, 1.72e-3, 2.22e-3, 2.72e-3, 3.22e-3];
/// §4.1: mean and largest skew at ξ = 0 (deg).
const W25_SKEW_ALIGNED: f64 = 0.47;
/// Fig. 7: the largest cone raceway load of a roller (N).
const W25_SUM_QI_MAX: f64 = 6974.90;
const W25_SPEEDS_RPM: [f64; 5] = [500.0, 1500.0, 2500.0, 3500.0, 4500.0];
const W25_SPEED_ALIGNED: [&str; 5] = [
    "speed_500rpm_xi0.000",
    "speed_1500rpm_xi0.000",
    "speed_2500rpm_xi0.000",
    "deflection_xi0.000",
    "speed_4500rpm_xi0.000",
];
const W25_SPEED_DEFLECTED: [&str; 5] = [
    "speed_500rpm_xi0.004",
    "speed_1500rpm_xi0.004",
    "speed_2500rpm_xi0.004",
    "deflection_xi0.004",
    "speed_4500rpm_xi0.004",
];
/// §4.2.1 (Fig. 10): largest skew (deg) at 500 … 4500 rpm, aligned and ξ = 0.004 deg.
const W25_SKEW_MAX_ALIGNED: [f64; 5] = [0.12, 0.23, 0.34, 0.47, 0.60];
const W25_SKEW_MAX_DEFLECTED: [f64; 5] = [0.13, 0.25, 0.39, 0.53, 0.68];
const W25_AXIAL_KN: [f64; 4] = [12.0, 21.0, 30.0, 39.0];
const W25_AXIAL_ALIGNED: [&str; 4] = ["axial_12kN", "axial_21kN", "deflection_xi0.000", "axial_39kN"];
const W25_AXIAL_DEFLECTED: [&str; 4] = [
    "axial_12kN_xi0.004",
    "axial_21kN_xi0.004",
    "deflection_xi0.004",
    "axial_39kN_xi0.004",
];
/// Fig. 13: displacement preload 10 µm, Fr 15 and 45 kN, aligned.
const W25_PRELOAD: [&str; 2] = ["preload_fr15kN_xi0.000", "preload_fr45kN_xi0.000"];
const W25_QUICK: [&str; 3] = ["deflection_xi0.000", "deflection_xi0.004", "speed_500rpm_xi0.000"];
/// Roller skew measured in TRBs, as [W25] §4.1 cites it (deg): [8], [25, 26], [27].
const MEASURED_SKEW_DEG: (f64, f64) = (0.07, 0.6);

/// Dynamic runs of the default TRB130x230, apex-consistent (`scenarios/validate/`), full mode only.
const APEX_DYNAMIC: [&str; 2] = ["apex_dynamic_500rpm", "apex_dynamic_3500rpm"];

/// Dynamic runs: per scenario, one result per traction law (`None`: not run or failed).
struct W25Runs {
    cases: BTreeMap<&'static str, Vec<Option<CaseResult>>>,
}

impl W25Runs {
    /// Run the scenarios `names` of `dir` (the [W25] ones by default), once per traction law.
    fn run(plan: &Plan, dir: &Path, names: Vec<&'static str>, what: &str, ledger: &mut Ledger) -> W25Runs {
        eprintln!(
            "{what}: {} dynamic cases × {} traction laws, {} ms each, one at a time",
            names.len(),
            TRACTIONS.len(),
            plan.run_length_ms()
        );
        let mut cases = BTreeMap::new();
        for name in names {
            let results = TRACTIONS
                .iter()
                .map(|&t| match w25::run_case(dir, name, plan.dynamic_variant(t)) {
                    Ok(r) => {
                        eprintln!("  {name:<24} traction {t}: {:6.1} s wall", r.wall);
                        Some(r)
                    }
                    Err(e) => {
                        eprintln!("  {name:<24} traction {t}: failed: {e}");
                        ledger.failures.push(format!("{what} `{name}`, traction {t}: {e}"));
                        None
                    }
                })
                .collect();
            cases.insert(name, results);
        }
        W25Runs { cases }
    }

    fn case(&self, name: &str, t: usize) -> Option<&CaseResult> {
        self.cases.get(name).and_then(|v| v[t].as_ref())
    }

    /// A quantity of one case, per traction law.
    fn value(&self, name: &str, get: impl Fn(&CaseResult) -> f64) -> Vec<Option<f64>> {
        per_traction(|t| self.case(name, t).map(&get))
    }

    /// Every case of `names` for traction law `t`, or `None` if one did not run.
    fn all(&self, names: &[&str], t: usize) -> Option<Vec<&CaseResult>> {
        names.iter().map(|n| self.case(n, t)).collect()
    }

    /// A statement about the cases `names`, judged per traction law.
    fn verdicts(&self, names: &[&str], judge: impl Fn(&[&CaseResult]) -> (bool, String)) -> Vec<Option<(bool, String)>> {
        per_traction(|t| self.all(names, t).map(|rs| judge(&rs)))
    }

    fn names(&self) -> impl Iterator<Item = &&'static str> {
        self.cases.keys()
    }
}

fn tilt_avg_deg(r: &CaseResult) -> f64 {
    r.tilt_abs_mean * DEG
}
fn tilt_max_deg(r: &CaseResult) -> f64 {
    r.tilt_max * DEG
}
fn skew_avg_deg(r: &CaseResult) -> f64 {
    r.skew_abs_mean * DEG
}
fn skew_max_deg(r: &CaseResult) -> f64 {
    r.skew_max * DEG
}

fn w25_section(runs: &W25Runs, book: &[(usize, Option<CaseResult>)], plan: &Plan, ledger: &mut Ledger) -> String {
    let mut md = format!(
        "## 1. [W25] Roller tilt and skew under shaft deflection (TRB130x230-W25, dynamic model)\n\n\
         The product's dynamic model (`fidelity` = 1, docs/dynamic.md) on the scenarios of `scenarios/w25_dynamic/` \
         (TRB130x230-W25, [W25] Table 1 and Eq. (1) as printed, 20 slices, the default automatic integrator at tolerance 1e-6), each run {} ms, once \
         per traction law, from the steady running state where there is one (`startSteady`: no radial load, no \
         deflection) and run in at the initial inputs otherwise (docs/dynamic.md); statistics over the second half of each run \
         (`src/cli/study/w25.rs`). θavg, ϕavg: mean of |tilt|, |skew| over the rollers and the samples; θmax, ϕmax: \
         the largest |tilt|, |skew| of any roller at any sample. Angles in degrees.\n\n\
         **Signs.** The product's skew ϕ is the rotation of the roller axis about its in-plane normal, positive when \
         the small end moves towards −e_t (against the orbit at positive speed, docs/dynamic.md); its tilt θ is \
         positive outwards (from +x towards +r, docs/model.md). [W25] does not define its signs in the text (Fig. 4: \
         at ξ = 0 the roller is tilted negative and skewed positive; under deflection it is 'always in a negative \
         skewed state'), and its stated numbers are magnitudes, so magnitudes are compared; rows that depend on a \
         sign are shown in the product's convention and not counted in section 7.{}\n\n",
        num(plan.run_length_ms()),
        if plan.quick {
            " **Quick mode**: three cases, 10 ms runs; rows needing other cases say \"—\" / \"not run\"."
        } else {
            ""
        }
    );
    md += &w25_tilt_against_deflection(runs, ledger);
    md += &w25_tilt_with_the_books_law(runs, book);
    md += &w25_skew_against_speed(runs, ledger);
    md += &w25_angles_against_axial_load(runs, ledger);
    md += &w25_stated_trends(runs, ledger);
    md += &w25_every_run(runs);
    md += &w25_energy_balance(runs);
    let balance: Vec<f64> = runs
        .cases
        .values()
        .flatten()
        .flatten()
        .map(|r| r.torque * r.speed_rpm * RPM / r.power)
        .collect();
    if !balance.is_empty() {
        ledger.fact(
            "[W25]",
            format!(
                "energy balance: torque × speed / power loss {} … {} over the {} runs (time averages)",
                ratio_text(Some(balance.iter().cloned().fold(f64::INFINITY, f64::min))),
                ratio_text(Some(balance.iter().cloned().fold(0.0, f64::max))),
                balance.len()
            ),
        );
    }
    for (angle, symbol) in [("tilt", 'θ'), ("skew", 'ϕ')] {
        let spans: Vec<String> = LUBRICATED
            .iter()
            .zip(TRACTIONS)
            .filter_map(|(c, t)| {
                let q: Vec<f64> = ledger
                    .ratios
                    .iter()
                    .filter(|r| r.source == "[W25]" && r.what.contains(symbol))
                    .flat_map(|r| r.ratios.iter().filter(|(k, _)| k == c).map(|(_, q)| *q))
                    .collect();
                (!q.is_empty()).then(|| {
                    let (lo, hi) = (
                        q.iter().cloned().fold(f64::INFINITY, f64::min),
                        q.iter().cloned().fold(0.0, f64::max),
                    );
                    format!(
                        "{} … {} (traction {t}, {} numbers)",
                        ratio_text(Some(lo)),
                        ratio_text(Some(hi)),
                        q.len()
                    )
                })
            })
            .collect();
        if !spans.is_empty() {
            ledger.fact("[W25]", format!("{angle} angles, product/study: {}", spans.join("; ")));
        }
    }
    md
}

/// The statistics of every run, both traction laws.
fn w25_every_run(runs: &W25Runs) -> String {
    let rows: Vec<Vec<String>> = runs
        .cases
        .iter()
        .map(|(name, rs)| {
            let mut row = vec![format!("`{name}`")];
            for r in rs {
                match r {
                    Some(r) => row.extend([
                        num(skew_avg_deg(r)),
                        num(skew_max_deg(r)),
                        num(tilt_avg_deg(r)),
                        num(tilt_max_deg(r)),
                        format!("{}–{}", r.loaded_min, r.loaded_max),
                    ]),
                    None => row.extend((0..5).map(|_| "—".to_string())),
                }
            }
            row
        })
        .collect();
    format!(
        "### Every run

Angles in degrees; rollers: fewest–most rollers in contact over the second half.

{}
",
        table(
            &[
                "case",
                "ϕavg, traction 0",
                "ϕmax",
                "θavg",
                "θmax",
                "rollers",
                "ϕavg, traction 1",
                "ϕmax",
                "θavg",
                "θmax",
                "rollers",
            ],
            &rows
        )
    )
}

/// Fig. 6, §4.1 and Fig. 7: Fa 30 kN, Fr 0, 3500 rpm, ξ = 0 … 0.006 deg.
fn w25_tilt_against_deflection(runs: &W25Runs, ledger: &mut Ledger) -> String {
    let mut c = Compare::new("[W25]", LUBRICATED);
    for (k, name) in W25_DEFLECTION.iter().enumerate() {
        c.row(
            ledger,
            &format!("θavg, ξ = {:.3} deg", W25_XI_DEG[k]),
            W25_TILT_AVG[k],
            &runs.value(name, tilt_avg_deg),
        );
    }
    for (k, name) in W25_DEFLECTION.iter().enumerate() {
        c.row(
            ledger,
            &format!("θmax, ξ = {:.3} deg", W25_XI_DEG[k]),
            W25_TILT_MAX[k],
            &runs.value(name, tilt_max_deg),
        );
    }
    let aligned = W25_DEFLECTION[0];
    c.row(ledger, "ϕavg, ξ = 0", W25_SKEW_ALIGNED, &runs.value(aligned, skew_avg_deg));
    c.row(ledger, "ϕmax, ξ = 0", W25_SKEW_ALIGNED, &runs.value(aligned, skew_max_deg));
    c.row(
        ledger,
        "Fig. 7: (Σqi)max (N), largest cone load of a roller, ξ = 0.006 deg",
        W25_SUM_QI_MAX,
        &runs.value(W25_DEFLECTION[6], |r| r.qi_peak),
    );
    c.row(
        ledger,
        "Fig. 7: (Σqi)max (N), the same at ξ = 0",
        W25_SUM_QI_MAX,
        &runs.value(aligned, |r| r.qi_peak),
    );

    let mut k = Checks::new("[W25]", LUBRICATED);
    let deflected = &W25_DEFLECTION[1..];
    k.row(
        ledger,
        "§4.1: θmax exceeds the shaft deflection ξ (ξ = 0.001 … 0.006 deg)",
        runs.verdicts(deflected, |rs| {
            let q: Vec<f64> = rs.iter().map(|r| r.tilt_max * DEG / r.xi_deg).collect();
            let (lo, hi) = (
                q.iter().cloned().fold(f64::INFINITY, f64::min),
                q.iter().cloned().fold(0.0, f64::max),
            );
            (lo > 1.0, format!("θmax/ξ = {} … {}", num(lo), num(hi)))
        }),
    );
    let ends = [W25_DEFLECTION[0], W25_DEFLECTION[6]];
    k.row(
        ledger,
        "§4.1: the deflection's effect on ϕavg is mild, on ϕmax apparent (ξ 0 → 0.006 deg)",
        runs.verdicts(&ends, |rs| {
            let avg = pct_change(skew_avg_deg(rs[0]), skew_avg_deg(rs[1]));
            let max = pct_change(skew_max_deg(rs[0]), skew_max_deg(rs[1]));
            (max.abs() > avg.abs(), format!("ϕavg {avg:+.1} %, ϕmax {max:+.1} %"))
        }),
    );
    k.row(
        ledger,
        "Fig. 4: under deflection the skew keeps one sign (ξ = 0.001 … 0.006 deg)",
        runs.verdicts(deflected, |rs| {
            let lo = rs.iter().map(|r| r.skew_lo).fold(f64::INFINITY, f64::min) * DEG;
            let hi = rs.iter().map(|r| r.skew_hi).fold(f64::NEG_INFINITY, f64::max) * DEG;
            (lo * hi > 0.0, format!("skew from {} to {} deg", num(lo), num(hi)))
        }),
    );
    k.info(
        "Fig. 4: aligned, the roller is tilted negative and skewed positive (signs in the product's convention)",
        runs.verdicts(&[W25_DEFLECTION[0]], |rs| {
            let (t, s) = (rs[0].tilt_mean * DEG, rs[0].skew_mean * DEG);
            (t < 0.0 && s > 0.0, format!("mean tilt {} deg, mean skew {} deg", num(t), num(s)))
        }),
    );
    format!(
        "### Fig. 6, §4.1, Fig. 7: against shaft deflection (Fa 30 kN, Fr 0, 3500 rpm)\n\n{}{}",
        c.text(),
        k.text()
    )
}

/// The [W25] deflection cases with Johnson's law as the book writes it (`contact_law`
/// `johnson`, half the stiffness of [W25] Eq. (1) as printed), traction 0: (index into
/// `W25_DEFLECTION`, result).
fn w25_book_law_runs(plan: &Plan, ledger: &mut Ledger) -> Vec<(usize, Option<CaseResult>)> {
    let variant = Variant {
        contact_law: Some(trb::bearing::ContactLaw::Johnson),
        ..plan.dynamic_variant(0)
    };
    eprintln!(
        "[W25] with Johnson's law as the book writes it: {} cases, traction 0",
        plan.book_law_cases().len()
    );
    plan.book_law_cases()
        .into_iter()
        .map(|k| {
            let name = W25_DEFLECTION[k];
            (k, w25_run_or_note(name, variant, "with contact_law johnson", ledger))
        })
        .collect()
}

/// The [W25] case `name` run as `variant` says, or None with its failure in the ledger
/// (`what` says how the run differs from the section's).
fn w25_run_or_note(name: &str, variant: Variant, what: &str, ledger: &mut Ledger) -> Option<CaseResult> {
    run_or_note(&w25::scenario_dir(), "[W25] ", name, variant, what, ledger)
}

/// The case `dir/name.json` run as `variant` says, or `None` with why in the ledger's
/// failures (`source` leading the line, `what` naming the variant).
fn run_or_note(dir: &Path, source: &str, name: &str, variant: Variant, what: &str, ledger: &mut Ledger) -> Option<CaseResult> {
    w25::run_case(dir, name, variant)
        .map_err(|e| ledger.failures.push(format!("{source}`{name}` {what}: {e}")))
        .ok()
}

/// The fidelities the [W25] cases are run at beside the dynamic model's runs of the section:
/// the quasi-static and the quasi-dynamic model.
const OTHER_FIDELITIES: [i32; 2] = [0, 2];

/// The [W25] cases at fidelities 0 and 2 (traction 0), each case's runs in the order of
/// `OTHER_FIDELITIES`.
fn w25_fidelity_runs(plan: &Plan, ledger: &mut Ledger) -> Vec<(&'static str, Vec<Option<CaseResult>>)> {
    let names = plan.w25_cases();
    eprintln!("[W25] at fidelities 0 and 2: {} cases, traction 0", names.len());
    names
        .into_iter()
        .map(|name| {
            let runs = OTHER_FIDELITIES
                .iter()
                .map(|&fidelity| {
                    let variant = Variant {
                        fidelity: Some(fidelity),
                        ..plan.dynamic_variant(0)
                    };
                    w25_run_or_note(name, variant, &format!("at fidelity {fidelity}"), ledger)
                })
                .collect();
            (name, runs)
        })
        .collect()
}

/// The quantities the [W25] cases are compared by across fidelities and tolerances, in the
/// table's order (θavg, θmax, ϕavg, ϕmax, ϕload in degrees, T, Qi), each with whether
/// fidelity 0 computes it (no lubricated skew there).
const FIDELITY_QUANTITIES: [(fn(&CaseResult) -> f64, bool); 7] = [
    (tilt_avg_deg, true),
    (tilt_max_deg, true),
    (skew_avg_deg, false),
    (skew_max_deg, false),
    (|r| r.skew_loaded_mean * DEG, false),
    (|r| r.torque, true),
    (|r| r.qi_peak, true),
];

/// Every [W25] case at the three fidelities (traction 0): the angles, the torque and the largest
/// cone load of the quasi-static (0) and quasi-dynamic (2) models as ratios to the dynamic
/// model's (1), and each one's wall time per simulated second.
fn w25_at_three_fidelities(runs: &W25Runs, other: &[(&'static str, Vec<Option<CaseResult>>)]) -> String {
    let mut md = String::from(
        "### The [W25] cases at the three fidelities\n\n\
         Every case above (traction 0) run again at `fidelity` = 0 (quasi-static, docs/model.md) and 2 (quasi-dynamic: \
         seat, skew, pocket and spin in balance at each 1 ms communication step, the cage and the spins integrated, \
         src/quasi_dynamic/), with the same statistics over the second half of the run. Each quantity is given at \
         fidelity 1 (the dynamic model of the rows above) and as the ratios fidelity 0 / 1 and 2 / 1; fidelity 0 has \
         no skew in lubricated contact (its skew model applies to dry contact, docs/model.md), so its skew ratios \
         read 0. θ, ϕ in degrees; T the friction torque (N m); Qi the largest cone load of any roller at any sample \
         (N); ϕload: the signed mean skew of the rollers that carry a cone load, over those rollers and the \
         samples (degrees); wall: seconds of wall time per simulated second in this run, one thread, start included (fidelity 0 | 1 | 2; a rough figure, the machine may have been shared: docs/performance.md has the timed ones).\n\n\
         | case | θavg | 0/1 | 2/1 | θmax | 0/1 | 2/1 | ϕavg | 2/1 | ϕmax | 2/1 | ϕload | 2/1 | T | 0/1 | 2/1 | Qi | 0/1 | 2/1 | wall 0 \\| 1 \\| 2 |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for (name, runs_at) in other {
        let Some(dynamic) = runs.case(name, 0) else {
            continue;
        };
        let (f0, f2) = (runs_at[0].as_ref(), runs_at[1].as_ref());
        let mut row = format!("| `{name}` |");
        for (get, with_f0) in FIDELITY_QUANTITIES {
            let v = get(dynamic);
            row += &format!(" {} |", num(v));
            if with_f0 {
                row += &format!(" {} |", ratio_text(ratio(f0.map(get), v)));
            }
            row += &format!(" {} |", ratio_text(ratio(f2.map(get), v)));
        }
        let wall = |r: Option<&CaseResult>| r.map_or("—".to_string(), |r| format!("{:.3}", r.wall / r.simulated));
        row += &format!(" {} \\| {} \\| {} |\n", wall(f0), wall(Some(dynamic)), wall(f2));
        md += &row;
    }
    md + "\n**Skew as a balance and as a vibration.** Fidelity 2 gives each roller's skew in balance at every \
          instant; at fidelity 1 a roller also vibrates in skew about that balance, a mode excited as the roller \
          enters and leaves the load zone and little damped inside it (docs/validation-notes.md, 'Skew at \
          fidelity 2 against fidelity 1'). ϕavg and ϕmax count that vibration's amplitude, which a \
          balance cannot have; ϕload averages it out and compares the balances themselves. Where the load zone's \
          ends are sharp (a large radial load on a preloaded set), ϕavg at fidelity 2 is therefore lower than at \
          fidelity 1 while ϕload agrees; out of the load zone, where only the rib's centrifugal load holds a \
          roller's skew and its skew mode is slow against the time it takes to cross the unloaded arc, the \
          balance is not reached at fidelity 1 either.\n\n"
}

/// The checks of fidelity 2 that the [W25] table does not make: the dynamic reference's own
/// tolerance (its cases at a hundred times tighter) and the cage's slip on a lightly loaded
/// bearing, whose cage speed only the traction sets (fidelities 1 and 2, settled over 2 s,
/// against the cage speed without slip from fidelity 0 at `cageSlipRate` 0).
fn fidelity_two_checks(plan: &Plan, runs: &W25Runs, ledger: &mut Ledger) -> String {
    const TIGHT: [&str; 2] = ["deflection_xi0.004", "preload_fr45kN_xi0.000"];
    let mut md = String::from(
        "**The reference's tolerance.** The fidelity-1 runs above use the automatic integrator at tolerance 1e-6. \
         Rerun at 1e-8, their statistics change by (largest relative change of θavg, θmax, ϕavg, ϕmax, ϕload, T, Qi):\n\n",
    );
    for name in TIGHT.iter().filter(|n| plan.w25_cases().contains(n)) {
        let variant = Variant {
            parameters: &[("tolerance", 1e-8)],
            ..plan.dynamic_variant(0)
        };
        let (Some(loose), Some(tight)) = (runs.case(name, 0), w25_run_or_note(name, variant, "at tolerance 1e-8", ledger)) else {
            continue;
        };
        let change = FIDELITY_QUANTITIES
            .iter()
            .map(|(g, _)| ((g(loose) - g(&tight)) / g(&tight)).abs())
            .fold(0.0, f64::max);
        md += &format!("- `{name}`: {change:.1e}\n");
    }
    md += "\n";
    md + &cage_slip_check(plan, ledger)
}

/// The cage's slip at light load (`scenarios/validate/light_load_skidding.json`) at
/// fidelities 1 and 2, settled: the mean over the second half of a 2 s run.
fn cage_slip_check(plan: &Plan, ledger: &mut Ledger) -> String {
    let dir = scenarios_dir().join("validate");
    let name = "light_load_skidding";
    let stop = if plan.quick { 0.02 } else { 2.0 };
    let run = |fidelity: i32, parameters: &'static [(&'static str, f64)], stop_time: f64, ledger: &mut Ledger| {
        let variant = Variant {
            fidelity: Some(fidelity),
            stop_time: Some(stop_time),
            parameters,
            ..Default::default()
        };
        run_or_note(&dir, "", name, variant, &format!("at fidelity {fidelity}"), ledger)
    };
    let kinematic = run(0, &[("cageSlipRate", 0.0)], 0.002, ledger);
    let (f1, f2) = (run(1, &[], stop, ledger), run(2, &[], stop, ledger));
    let (Some(kinematic), Some(f1), Some(f2)) = (kinematic, f1, f2) else {
        return "**Cage slip at light load.** Not computed (see the differences below).\n\n".into();
    };
    let slip = |r: &CaseResult| 1.0 - r.cage_speed / kinematic.cage_speed;
    format!(
        "**Cage slip at light load.** TRB130x230-W25 at 3500 rpm under Fa 3 kN and Fr 2 kN: rollers out of the \
         load zone slow down and the cage lags the speed it would have without slip ({} rad/s, fidelity 0 at \
         `cageSlipRate` 0). Over the second half of a {stop} s run in 1 ms steps (the cage's slip settles in about \
         1 s):\n\n\
         | fidelity | cage speed (rad/s) | cage slip | T (N m) | wall (s per simulated s) |\n|---|---|---|---|---|\n\
         | 1 | {} | {} | {} | {:.2} |\n| 2 | {} | {} | {} | {:.2} |\n| 2/1 | {} | {} | {} | |\n\n",
        num4(kinematic.cage_speed),
        num4(f1.cage_speed),
        num(slip(&f1)),
        num4(f1.torque),
        f1.wall / f1.simulated,
        num4(f2.cage_speed),
        num(slip(&f2)),
        num4(f2.torque),
        f2.wall / f2.simulated,
        ratio_text(ratio(Some(f2.cage_speed), f1.cage_speed)),
        ratio_text(ratio(Some(slip(&f2)), slip(&f1))),
        ratio_text(ratio(Some(f2.torque), f1.torque)),
    )
}

/// The tilts of the deflection cases under [W25]'s printed law and under the book's, against
/// the study (traction 0).
fn w25_tilt_with_the_books_law(runs: &W25Runs, book: &[(usize, Option<CaseResult>)]) -> String {
    let mut md = String::from(
        "**With Johnson's law as the book writes it.** [W25] Eq. (1) as printed takes Ē = 2E*, twice the stiffness of \
         Johnson's line contact with the contact modulus of *Contact Mechanics* (`contact_law` `johnson`; docs/model.md, \
         Contact laws). The same cases with the book's law on the same printed geometry, traction 0 (ratios to the \
         study in parentheses):\n\n\
         | ξ (deg) | study θavg | `johnson-w25` θavg | `johnson` θavg | study θmax | `johnson-w25` θmax | `johnson` θmax |\n\
         |---|---|---|---|---|---|---|\n",
    );
    let cell = |v: Option<f64>, reference: f64| match v {
        Some(v) => format!("{} ({})", num(v), ratio_text(ratio(Some(v), reference))),
        None => "not run".to_string(),
    };
    for (k, r) in book {
        let printed = runs.case(W25_DEFLECTION[*k], 0);
        md += &format!(
            "| {:.3} | {} | {} | {} | {} | {} | {} |\n",
            W25_XI_DEG[*k],
            num(W25_TILT_AVG[*k]),
            cell(printed.map(tilt_avg_deg), W25_TILT_AVG[*k]),
            cell(r.as_ref().map(tilt_avg_deg), W25_TILT_AVG[*k]),
            num(W25_TILT_MAX[*k]),
            cell(printed.map(tilt_max_deg), W25_TILT_MAX[*k]),
            cell(r.as_ref().map(tilt_max_deg), W25_TILT_MAX[*k]),
        );
    }
    md + "\nThe book's law moves every tilt away from the study, most where the tilt is elastic (aligned: the \
          rib and traction moments over the rollers' tilt stiffness, which half the contact stiffness nearly doubles) \
          and least where the imposed misalignment sets it. That the printed law agrees better is evidence that [W25] \
          computed with it; the rows above therefore keep it (docs/validation-notes.md).\n\n"
}

fn pct_change(from: f64, to: f64) -> f64 {
    if from != 0.0 {
        100.0 * (to - from) / from
    } else {
        0.0
    }
}

/// Fig. 10, §4.2.1: Fa 30 kN, Fr 0, 500 … 4500 rpm, ξ = 0 and 0.004 deg.
fn w25_skew_against_speed(runs: &W25Runs, ledger: &mut Ledger) -> String {
    let mut c = Compare::new("[W25]", LUBRICATED);
    for (k, name) in W25_SPEED_ALIGNED.iter().enumerate() {
        c.row(
            ledger,
            &format!("ϕmax, {} rpm, ξ = 0", W25_SPEEDS_RPM[k]),
            W25_SKEW_MAX_ALIGNED[k],
            &runs.value(name, skew_max_deg),
        );
    }
    for (k, name) in W25_SPEED_DEFLECTED.iter().enumerate() {
        c.row(
            ledger,
            &format!("ϕmax, {} rpm, ξ = 0.004 deg", W25_SPEEDS_RPM[k]),
            W25_SKEW_MAX_DEFLECTED[k],
            &runs.value(name, skew_max_deg),
        );
    }
    let mut k = Checks::new("[W25]", LUBRICATED);
    let listed = |rs: &[&CaseResult], get: fn(&CaseResult) -> f64| rs.iter().map(|r| get(r)).collect::<Vec<f64>>();
    k.row(
        ledger,
        "ξ = 0: θmax and θavg are very close at every speed",
        runs.verdicts(&W25_SPEED_ALIGNED, |rs| {
            let q = rs.iter().map(|r| r.tilt_abs_mean / r.tilt_max).fold(f64::INFINITY, f64::min);
            (q >= 0.9, format!("smallest θavg/θmax {}", num(q)))
        }),
    );
    for (names, xi) in [(&W25_SPEED_ALIGNED, "0"), (&W25_SPEED_DEFLECTED, "0.004 deg")] {
        k.row(
            ledger,
            &format!("ξ = {xi}: θmax first falls, then rises with speed"),
            runs.verdicts(names, |rs| {
                let v = listed(rs, tilt_max_deg);
                (falls_then_rises(&v), format!("{} deg", chain(&v)))
            }),
        );
    }
    k.info(
        "ξ = 0: the tilt is negative at 500 rpm and positive at 4500 rpm (gyroscopic effect; signs in the product's convention)",
        runs.verdicts(&[W25_SPEED_ALIGNED[0], W25_SPEED_ALIGNED[4]], |rs| {
            let (a, b) = (rs[0].tilt_mean * DEG, rs[1].tilt_mean * DEG);
            (a < 0.0 && b > 0.0, format!("mean tilt {} → {} deg", num(a), num(b)))
        }),
    );
    k.row(
        ledger,
        "ξ = 0: the tilt changes sign between 500 and 4500 rpm (the convention-free part of the row above)",
        runs.verdicts(&[W25_SPEED_ALIGNED[0], W25_SPEED_ALIGNED[4]], |rs| {
            let (a, b) = (rs[0].tilt_mean * DEG, rs[1].tilt_mean * DEG);
            (a * b < 0.0, format!("mean tilt {} → {} deg", num(a), num(b)))
        }),
    );
    k.row(
        ledger,
        "ξ = 0.004 deg: θavg falls with speed",
        runs.verdicts(&W25_SPEED_DEFLECTED, |rs| {
            let v = listed(rs, tilt_avg_deg);
            (decreasing(&v), format!("{} deg", chain(&v)))
        }),
    );
    let both: Vec<&str> = W25_SPEED_ALIGNED.iter().chain(&W25_SPEED_DEFLECTED).copied().collect();
    k.row(
        ledger,
        "θmax at ξ = 0.004 deg is one order of magnitude above θmax at ξ = 0 (ratio within 10^±0.5 of 10)",
        runs.verdicts(&both, |rs| {
            let q: Vec<f64> = (0..5).map(|i| rs[5 + i].tilt_max / rs[i].tilt_max).collect();
            let ok = q.iter().all(|x| (10f64.sqrt()..=10.0 * 10f64.sqrt()).contains(x));
            (ok, format!("ratio {}", chain(&q)))
        }),
    );
    for (names, xi) in [(&W25_SPEED_ALIGNED, "0"), (&W25_SPEED_DEFLECTED, "0.004 deg")] {
        k.row(
            ledger,
            &format!("ξ = {xi}: the skew grows with speed"),
            runs.verdicts(names, |rs| {
                let v = listed(rs, skew_max_deg);
                (increasing(&v), format!("ϕmax {} deg", chain(&v)))
            }),
        );
    }
    k.row(
        ledger,
        "the skew amplitude differs little between ξ = 0 and 0.004 deg (ϕmax ratio within 0.8–1.25; the study's own: 1.08–1.15)",
        runs.verdicts(&both, |rs| {
            let q: Vec<f64> = (0..5).map(|i| rs[5 + i].skew_max / rs[i].skew_max).collect();
            (q.iter().all(|x| (0.8..=1.25).contains(x)), format!("ratio {}", chain(&q)))
        }),
    );
    format!("### Fig. 10, §4.2.1: against speed (Fa 30 kN, Fr 0)\n\n{}{}", c.text(), k.text())
}

/// Fig. 11, §4.2.2: pure axial 12 … 39 kN, 3500 rpm, ξ = 0 and 0.004 deg.
fn w25_angles_against_axial_load(runs: &W25Runs, ledger: &mut Ledger) -> String {
    let mut c = Compare::new("[W25]", LUBRICATED);
    let (first, last) = (W25_AXIAL_ALIGNED[0], W25_AXIAL_ALIGNED[3]);
    c.row(ledger, "ξ = 0: θmax at 12 kN", 2.10e-5, &runs.value(first, tilt_max_deg));
    c.row(ledger, "ξ = 0: θmax at 39 kN", 3.37e-4, &runs.value(last, tilt_max_deg));
    c.row(ledger, "ξ = 0: ϕmax at 12 kN", 0.27, &runs.value(first, skew_max_deg));
    c.row(ledger, "ξ = 0: ϕmax at 39 kN", 0.55, &runs.value(last, skew_max_deg));
    let over_loads = |get: fn(&CaseResult) -> f64, pick_max: bool| -> Vec<Option<f64>> {
        per_traction(|t| {
            runs.all(&W25_AXIAL_DEFLECTED, t).map(|rs| {
                let v = rs.iter().map(|r| get(r));
                if pick_max {
                    v.fold(f64::NEG_INFINITY, f64::max)
                } else {
                    v.fold(f64::INFINITY, f64::min)
                }
            })
        })
    };
    c.row(
        ledger,
        "ξ = 0.004 deg: smallest θmax over 12 … 39 kN",
        2.00e-3,
        &over_loads(tilt_max_deg, false),
    );
    c.row(
        ledger,
        "ξ = 0.004 deg: largest θmax over 12 … 39 kN",
        2.33e-3,
        &over_loads(tilt_max_deg, true),
    );
    c.row(
        ledger,
        "ξ = 0.004 deg: smallest ϕmax over 12 … 39 kN",
        0.38,
        &over_loads(skew_max_deg, false),
    );
    c.row(
        ledger,
        "ξ = 0.004 deg: largest ϕmax over 12 … 39 kN",
        0.60,
        &over_loads(skew_max_deg, true),
    );

    let mut k = Checks::new("[W25]", LUBRICATED);
    for (names, xi) in [(&W25_AXIAL_ALIGNED, "0"), (&W25_AXIAL_DEFLECTED, "0.004 deg")] {
        k.row(
            ledger,
            &format!("ξ = {xi}: the skew grows with the axial load (12, 21, 30, 39 kN)"),
            runs.verdicts(names, |rs| {
                let v: Vec<f64> = rs.iter().map(|r| skew_max_deg(r)).collect();
                (increasing(&v), format!("ϕmax {} deg", chain(&v)))
            }),
        );
    }
    k.row(
        ledger,
        "ξ = 0.004 deg: the axial load raises the skew much more than the tilt (relative rise 12 → 39 kN)",
        runs.verdicts(&W25_AXIAL_DEFLECTED, |rs| {
            let dt = pct_change(rs[0].tilt_max, rs[3].tilt_max);
            let ds = pct_change(rs[0].skew_max, rs[3].skew_max);
            (ds > dt, format!("θmax {dt:+.0} %, ϕmax {ds:+.0} %"))
        }),
    );
    let both: Vec<&str> = W25_AXIAL_ALIGNED.iter().chain(&W25_AXIAL_DEFLECTED).copied().collect();
    k.row(
        ledger,
        "ϕavg at ξ = 0.004 deg is close to ϕavg at ξ = 0, at each axial load (within 20 %)",
        runs.verdicts(&both, |rs| {
            let q: Vec<f64> = (0..4).map(|i| rs[4 + i].skew_abs_mean / rs[i].skew_abs_mean).collect();
            (q.iter().all(|x| (0.8..=1.2).contains(x)), format!("ratio {}", chain(&q)))
        }),
    );
    format!(
        "### Fig. 11, §4.2.2: against the axial load (Fr 0, 3500 rpm)\n\n{}{}",
        c.text(),
        k.text()
    )
}

/// The abstract's and conclusions' statements, the measured skew range, Fig. 13.
fn w25_stated_trends(runs: &W25Runs, ledger: &mut Ledger) -> String {
    let mut k = Checks::new("[W25]", LUBRICATED);
    let reference = W25_DEFLECTION[0];
    k.row(
        ledger,
        "the tilt angle is orders of magnitude below the skew angle (ϕavg/θavg ≥ 100, ξ = 0, 3500 rpm)",
        runs.verdicts(&[reference], |rs| {
            let q = rs[0].skew_abs_mean / rs[0].tilt_abs_mean;
            (q >= 100.0, format!("ϕavg/θavg = {}", num(q)))
        }),
    );
    // The largest deflection run (0.006 deg; 0.004 deg in quick mode).
    let deflected = W25_DEFLECTION
        .iter()
        .rev()
        .find(|n| runs.cases.contains_key(**n) && **n != reference)
        .copied()
        .unwrap_or(W25_DEFLECTION[6]);
    k.row(
        ledger,
        &format!(
            "the shaft deflection raises the largest tilt and skew (ξ 0 → {} deg)",
            deflected.trim_start_matches("deflection_xi")
        ),
        runs.verdicts(&[reference, deflected], |rs| {
            let (t0, t1, s0, s1) = (tilt_max_deg(rs[0]), tilt_max_deg(rs[1]), skew_max_deg(rs[0]), skew_max_deg(rs[1]));
            (
                t1 > t0 && s1 > s0,
                format!("θmax {} → {} deg, ϕmax {} → {} deg", num(t0), num(t1), num(s0), num(s1)),
            )
        }),
    );
    k.row(
        ledger,
        "the skew grows with speed (ξ = 0, 500 … 4500 rpm)",
        runs.verdicts(&W25_SPEED_ALIGNED, |rs| {
            let v: Vec<f64> = rs.iter().map(|r| skew_max_deg(r)).collect();
            (increasing(&v), format!("ϕmax {} deg", chain(&v)))
        }),
    );
    k.row(
        ledger,
        "the skew grows with the axial load (ξ = 0, 12 … 39 kN)",
        runs.verdicts(&W25_AXIAL_ALIGNED, |rs| {
            let v: Vec<f64> = rs.iter().map(|r| skew_max_deg(r)).collect();
            (increasing(&v), format!("ϕmax {} deg", chain(&v)))
        }),
    );
    let (lo, hi) = MEASURED_SKEW_DEG;
    k.row(
        ledger,
        &format!(
            "measured TRB skew ({}–{} deg, as cited in §4.1): ϕavg of the reference case (ξ = 0, 3500 rpm, 30 kN) lies in it",
            lo, hi
        ),
        runs.verdicts(&[reference], |rs| {
            let v = skew_avg_deg(rs[0]);
            (v >= lo && v <= hi, format!("ϕavg = {} deg", num(v)))
        }),
    );
    let all: Vec<&str> = runs.names().copied().collect();
    k.row(
        ledger,
        &format!("measured TRB skew ({lo}–{hi} deg): ϕmax of every run lies in it"),
        runs.verdicts(&all, |rs| {
            let inside = rs.iter().filter(|r| (lo..=hi).contains(&skew_max_deg(r))).count();
            let range = (
                rs.iter().map(|r| skew_max_deg(r)).fold(f64::INFINITY, f64::min),
                rs.iter().map(|r| skew_max_deg(r)).fold(0.0, f64::max),
            );
            (
                inside == rs.len(),
                format!("{inside} of {} runs; ϕmax {} … {} deg", rs.len(), num(range.0), num(range.1)),
            )
        }),
    );
    k.row(
        ledger,
        "Fig. 13 (displacement preload 10 µm, ξ = 0): at Fr = 15 kN all rollers carry load",
        runs.verdicts(&[W25_PRELOAD[0]], |rs| {
            let z = rs[0].final_loads.len() as i32;
            (
                rs[0].loaded_min == z,
                format!("{}–{} of {z} rollers in contact", rs[0].loaded_min, rs[0].loaded_max),
            )
        }),
    );
    k.row(
        ledger,
        "Fig. 13: at Fr = 45 kN a major and a minor ('relaxed') load zone (a roller below 10 % of the largest cup load at the end of the run)",
        runs.verdicts(&[W25_PRELOAD[1]], |rs| {
            let qo: Vec<f64> = rs[0].final_loads.iter().map(|l| l.2).collect();
            let (lo, hi) = (qo.iter().cloned().fold(f64::INFINITY, f64::min), qo.iter().cloned().fold(0.0, f64::max));
            (
                lo < 0.1 * hi,
                format!("cup loads {} … {} N; {}–{} rollers in contact", num(lo), num(hi), rs[0].loaded_min, rs[0].loaded_max),
            )
        }),
    );
    format!(
        "### Stated trends (abstract, §4, conclusions) and the measured skew range\n\n{}",
        k.text()
    )
}

/// Torque × speed against the dissipated power, time-averaged over the second half.
fn w25_energy_balance(runs: &W25Runs) -> String {
    let rows: Vec<Vec<String>> = runs
        .cases
        .iter()
        .map(|(name, rs)| {
            let mut row = vec![format!("`{name}`")];
            for r in rs {
                match r {
                    Some(r) => {
                        let tw = r.torque * r.speed_rpm * RPM;
                        row.extend([num(r.torque), num(tw), num(r.power), ratio_text(ratio(Some(tw), r.power))]);
                    }
                    None => row.extend(["—".to_string(), "—".into(), "—".into(), "—".into()]),
                }
            }
            row
        })
        .collect();
    format!(
        "### Energy balance per run\n\nTime averages over the second half of each run: the friction torque T times the \
         shaft speed ω against the dissipated power P (`powerLoss`). They differ instantaneously by the rate of change \
         of kinetic and elastic energy and agree on a long average (docs/dynamic.md); a short or unsettled run shows \
         the difference.\n\n{}\n",
        table(
            &[
                "case",
                "T (N m), traction 0",
                "T ω (W)",
                "P (W)",
                "T ω / P",
                "T (N m), traction 1",
                "T ω (W)",
                "P (W)",
                "T ω / P",
            ],
            &rows
        )
    )
}

// =============================================================================================
// 2. [D19]
// =============================================================================================

const D19_PRELOADS: [D19Preload; 2] = [D19Preload::Force, D19Preload::Displacement];

/// The [D19] sweeps (index 0 force preload, 1 displacement preload).
struct D19Runs {
    mu: Vec<f64>,
    by_mu: [Vec<Outputs>; 2],
    pocket: Vec<f64>,
    by_pocket: [Vec<Outputs>; 2],
    /// μ 0.6, pocket 0.9 mm (`scenarios/d19_skew_*_preload.json`): skew model on, off.
    skew_on: [Outputs; 2],
    skew_off: [Outputs; 2],
}

impl D19Runs {
    fn run(plan: &Plan) -> Result<D19Runs, CliError> {
        let mu = plan.pick(&studies::D19_MU, &[0.05, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5, 0.6]);
        let pocket = plan.pick(&studies::D19_POCKET, &[0.3e-3, 0.9e-3, 1.2e-3, 1.5e-3, 1.8e-3]);
        let err = |e: trb::model::ModelError| CliError::failed(format!("[D19]: {e}"));
        let sweep = |p: D19Preload, xs: &[f64], f: &dyn Fn(D19Preload, f64) -> Result<Outputs, trb::model::ModelError>| {
            xs.iter().map(|x| f(p, *x)).collect::<Result<Vec<_>, _>>().map_err(err)
        };
        eprintln!(
            "[D19]: {} friction coefficients and {} pocket clearances, two preloads",
            mu.len(),
            pocket.len()
        );
        let by_mu = [
            sweep(D19Preload::Force, &mu, &|p, m| studies::d19(p, m, 0.9e-3))?,
            sweep(D19Preload::Displacement, &mu, &|p, m| studies::d19(p, m, 0.9e-3))?,
        ];
        let by_pocket = [
            sweep(D19Preload::Force, &pocket, &|p, c| studies::d19(p, 0.5, c))?,
            sweep(D19Preload::Displacement, &pocket, &|p, c| studies::d19(p, 0.5, c))?,
        ];
        let files = ["d19_skew_force_preload.json", "d19_skew_displacement_preload.json"];
        let with_skew = |on: bool| -> Result<[Outputs; 2], CliError> {
            let a = shipped_case_with(&shipped(files[0])?, &[("skewModel", json!(on))], &[])?;
            let b = shipped_case_with(&shipped(files[1])?, &[("skewModel", json!(on))], &[])?;
            Ok([a, b])
        };
        Ok(D19Runs {
            skew_on: with_skew(true)?,
            skew_off: with_skew(false)?,
            mu,
            by_mu,
            pocket,
            by_pocket,
        })
    }

    fn at_mu(&self, p: usize, mu: f64) -> Option<&Outputs> {
        self.mu.iter().position(|m| (m - mu).abs() < 1e-9).map(|i| &self.by_mu[p][i])
    }

    fn at_pocket(&self, p: usize, c: f64) -> Option<&Outputs> {
        self.pocket.iter().position(|x| (x - c).abs() < 1e-9).map(|i| &self.by_pocket[p][i])
    }
}

/// Rollers carrying more than 1 % of the largest roller (cup) load.
fn rollers_above_one_percent(o: &Outputs) -> usize {
    o.qo.iter().filter(|q| **q > 0.01 * o.qo_max).count()
}

/// Rollers held by their pocket (skew at the pocket limit, roller–cage force > 0).
fn rollers_at_pocket_limit(o: &Outputs) -> usize {
    o.qc.iter().filter(|q| **q > 0.0).count()
}

/// The first swept μ at which rollers reach their pockets (roller–cage torque > 0).
fn friction_where_rollers_reach_the_pocket(mu: &[f64], sweep: &[Outputs]) -> Option<f64> {
    mu.iter().zip(sweep).find(|(_, o)| o.friction_torque_cage > 0.0).map(|(m, _)| *m)
}

/// The swept μ after which the torque's slope dT/dμ rises by the largest factor.
fn friction_where_the_torque_slope_jumps(mu: &[f64], sweep: &[Outputs]) -> Option<f64> {
    let slope: Vec<f64> = (1..mu.len())
        .map(|i| (sweep[i].friction_torque - sweep[i - 1].friction_torque) / (mu[i] - mu[i - 1]))
        .collect();
    (1..slope.len())
        .filter(|i| slope[i - 1] > 0.0)
        .max_by(|a, b| (slope[*a] / slope[a - 1]).total_cmp(&(slope[*b] / slope[b - 1])))
        .map(|i| mu[i])
}

/// The rows that hang on the sense of the friction thrust on the cone: the product's follows
/// from the skewed roller's kinematics and loads the cone along the applied axial load, [D19]'s
/// offsets it (docs/model.md, 'Differences from [D19]', item 1).
const D19_SENSE: &str = "differs; the product's sense follows from the kinematics (docs/model.md)";

/// A row's note on the thrust's sense, with what the model gives with that sense reversed (an
/// experiment the product does not run: docs/model.md, 'Differences from [D19]', item 1,
/// measured 2026-11-28).
fn d19_sense(reversed: &str) -> String {
    format!(" — {D19_SENSE}; with the sense reversed {reversed}")
}

fn d19_section(d: &D19Runs, ledger: &mut Ledger) -> String {
    let mut md = String::from(
        "## 2. [D19] §3: roller skew and dry friction torque (32018X)\n\n\
         32018X dry (one Coulomb coefficient μ at every contact), skew model on, radial 35 kN, 60 rpm, force preload \
         12,970 N or displacement preload 0.01 mm, pocket clearance 0.9 mm unless swept (`trb::quasi_static::studies::d19`, \
         the cases of `scenarios/d19_*.json`; docs/model.md, 'Roller skew and dry friction torque'). The traction law does \
         not apply to dry contacts: one product column. Torques in N m. Rollers are counted twice: the product's \
         `loadedRollers` (every roller touching both raceways, down to hundredths of a newton) and the rollers carrying \
         more than 1 % of the largest roller (cup) load. The skew's share of the torque compares the skew model with \
         `skewModel` = false on the same case, whose dry torque is the in-plane Coulomb one (docs/model.md, 'Friction \
         torque and power loss', Dry).\n\n",
    );
    let mut c = Compare::new("[D19]", DRY);
    for (p, label, paper) in [(0, "force", 13.0), (1, "displacement", 15.0)] {
        let o = d.at_mu(p, 0.5);
        // under force preload the count hangs on the thrust's sense
        let sense = |reversed: &str| if p == 0 { d19_sense(reversed) } else { String::new() };
        c.row(
            ledger,
            &format!(
                "rollers in contact, {label} preload, μ 0.5: `loadedRollers`{}",
                sense("13 at μ 0.3–0.4, 11 at 0.45, no equilibrium at 0.5")
            ),
            paper,
            &[o.map(|o| o.loaded_rollers as f64)],
        );
        c.row(
            ledger,
            &format!(
                "rollers in contact, {label} preload, μ 0.5: above 1 % of the largest load{}",
                sense("13 at μ 0.2–0.4, 11 at 0.45, no equilibrium at 0.5")
            ),
            paper,
            &[o.map(|o| rollers_above_one_percent(o) as f64)],
        );
    }
    for (p, label, paper) in [(1, "displacement", 0.25), (0, "force", 0.3)] {
        c.row(
            ledger,
            &format!("μ where the torque's rate of increase changes, {label} preload: rollers reach the pocket"),
            paper,
            &[friction_where_rollers_reach_the_pocket(&d.mu, &d.by_mu[p])],
        );
        c.row(
            ledger,
            &format!("μ where the torque's rate of increase changes, {label} preload: largest rise of dT/dμ"),
            paper,
            &[friction_where_the_torque_slope_jumps(&d.mu, &d.by_mu[p])],
        );
    }
    c.row(
        ledger,
        "rollers at the pocket limit at μ 0.25, displacement preload",
        11.0,
        &[d.at_mu(1, 0.25).map(|o| rollers_at_pocket_limit(o) as f64)],
    );
    let change = |p: usize, get: fn(&Outputs) -> f64| -> Option<f64> { Some(get(d.at_pocket(p, 1.8e-3)?) - get(d.at_pocket(p, 0.3e-3)?)) };
    for (part, get, paper) in [
        (
            "T_end-rib",
            (|o: &Outputs| o.friction_torque_flange) as fn(&Outputs) -> f64,
            [0.0, -4.4],
        ),
        ("T_roller-cage", |o: &Outputs| o.friction_torque_cage, [-29.3, -26.5]),
        ("T_roller-race", |o: &Outputs| o.friction_torque_raceway, [7.5, 7.2]),
    ] {
        for (p, label) in [(1, "displacement"), (0, "force")] {
            let paper = paper[if p == 1 { 0 } else { 1 }];
            c.row(
                ledger,
                &format!(
                    "change of {part}, pocket 0.3 → 1.8 mm, μ 0.5, {label} preload (N m){}",
                    if paper == 0.0 { " — the study: unchanged" } else { "" }
                ),
                paper,
                &[change(p, get)],
            );
        }
    }
    for (p, label) in [(0, "force"), (1, "displacement")] {
        let free = d
            .pocket
            .iter()
            .zip(&d.by_pocket[p])
            .find(|(_, o)| o.qc_max == 0.0)
            .map(|(c, _)| c * 1e3);
        c.row(
            ledger,
            &format!("smallest swept pocket clearance with every roller free of its pocket, μ 0.5, {label} preload (mm)"),
            1.5,
            &[free],
        );
    }
    for p in [1, 0] {
        let gain = pct_change(d.skew_off[p].friction_torque, d.skew_on[p].friction_torque);
        c.row(
            ledger,
            &format!(
                "torque increase by the skew (skew model on against off), μ 0.6, {} (%)",
                D19_PRELOADS[p].label()
            ),
            24.0,
            &[Some(gain)],
        );
    }

    let mut k = Checks::new("[D19]", DRY);
    let lower = |xs: &[f64], a: &[Outputs], b: &[Outputs], unit: &str| -> (bool, String) {
        let n = a.iter().zip(b).filter(|(f, d)| f.friction_torque < d.friction_torque).count();
        let higher: Vec<(f64, f64, f64)> = xs
            .iter()
            .zip(a.iter().zip(b))
            .filter(|(_, (f, d))| f.friction_torque >= d.friction_torque)
            .map(|(x, (f, d))| (*x, f.friction_torque, d.friction_torque))
            .collect();
        let detail = match higher.last() {
            None => String::new(),
            Some((x, f, d)) => format!(
                "; not at {}{unit} (at {}{unit}: {} against {} N m)",
                higher.iter().map(|h| num(h.0)).collect::<Vec<_>>().join(", "),
                num(*x),
                num(*f),
                num(*d)
            ),
        };
        (n == xs.len(), format!("force preload lower at {n} of {} points{detail}", xs.len()))
    };
    k.row(
        ledger,
        &format!(
            "§3.2: the force preload gives the lower total torque at every μ (pocket 0.9 mm){}",
            d19_sense(
                "lower wherever an equilibrium exists: 6.69 against 6.94 N m at μ 0.3, 9.29 against 9.87 at 0.4, \
                 15.1 against 16.8 at 0.45; none at 0.5"
            )
        ),
        vec![Some(lower(&d.mu, &d.by_mu[0], &d.by_mu[1], ""))],
    );
    let pocket_mm: Vec<f64> = d.pocket.iter().map(|c| c * 1e3).collect();
    k.row(
        ledger,
        &format!(
            "§3.3: the force preload gives the lower total torque at every pocket clearance (μ 0.5){}",
            d19_sense(
                "an equilibrium exists at 7 of the 16 clearances (not at 0.9 mm), and at each the force preload's torque \
                 is the lower (0.3 mm: 14.8 against 15.9 N m)"
            )
        ),
        vec![Some(lower(&pocket_mm, &d.by_pocket[0], &d.by_pocket[1], " mm"))],
    );
    k.row(
        ledger,
        "§3.2: T_roller-cage exceeds T_roller-race at μ 0.6 (displacement preload)",
        vec![d.at_mu(1, 0.6).map(|o| {
            (
                o.friction_torque_cage > o.friction_torque_raceway,
                format!("{} vs {} N m", num(o.friction_torque_cage), num(o.friction_torque_raceway)),
            )
        })],
    );
    k.row(
        ledger,
        "§3.2: T_end-rib and T_roller-race grow linearly with μ (displacement preload; linear through zero: T(0.6)/T(0.3) = 2)",
        vec![(|| {
            let (a, b) = (d.at_mu(1, 0.3)?, d.at_mu(1, 0.6)?);
            let (rf, rr) = (
                b.friction_torque_flange / a.friction_torque_flange,
                b.friction_torque_raceway / a.friction_torque_raceway,
            );
            Some((
                (rf - 2.0).abs() < 0.2 && (rr - 2.0).abs() < 0.2,
                format!("T(0.6)/T(0.3): end–rib {}, roller–race {}", num(rf), num(rr)),
            ))
        })()],
    );
    for (p, label) in [(0, "force"), (1, "displacement")] {
        k.row(
            ledger,
            &format!("§3.3: the total torque falls as the pocket clearance grows ({label} preload, μ 0.5)"),
            vec![Some({
                let v: Vec<f64> = d.by_pocket[p].iter().map(|o| o.friction_torque).collect();
                (decreasing(&v), format!("{} N m", chain(&[v[0], v[v.len() / 2], v[v.len() - 1]])))
            })],
        );
    }
    k.row(
        ledger,
        "§3.3 (Fig. 13): larger pocket clearance, larger skew and smaller roller–cage forces (force preload, μ 0.5)",
        vec![Some({
            let s: Vec<f64> = d.by_pocket[0].iter().map(|o| o.skew_max * DEG).collect();
            let q: Vec<f64> = d.by_pocket[0].iter().map(|o| o.qc_max).collect();
            let ok = non_decreasing(&s) && non_increasing(&q);
            (ok, format!("skew.max {} deg; Qc.max {} N", ends(&s), ends(&q)))
        })],
    );
    k.row(
        ledger,
        "§3.2 (Fig. 11): Q_f and Q_o fall as μ grows (force preload) — in the product the peaks fall because the \
         load zone widens (docs/model.md); with the thrust's sense reversed they rise: Qo.max 5.51 → 5.73 kN, Qf.max \
         288 → 300 N from μ 0.05 to 0.4, no equilibrium at 0.5",
        vec![Some({
            let (a, b) = (&d.by_mu[0][0], d.by_mu[0].last().expect("swept"));
            (
                b.qo_max < a.qo_max && b.qf_max < a.qf_max,
                format!(
                    "μ {} → {}: Qo.max {} → {} N, Qf.max {} → {} N",
                    num(d.mu[0]),
                    num(*d.mu.last().expect("swept")),
                    num(a.qo_max),
                    num(b.qo_max),
                    num(a.qf_max),
                    num(b.qf_max)
                ),
            )
        })],
    );
    md += &c.text();
    md += &k.text();
    md += "The sense of the friction thrust on the cone, and with it the roller counts and the order of the two \
           preloads' torques, is where the model departs from [D19] on purpose: in the product it follows from the \
           skewed roller's kinematics and loads the cone along the applied axial load at every speed, μ and preload \
           (docs/model.md, 'Differences from [D19]', item 1). The numbers 'with the sense reversed' are the model with \
           that sense reversed, an experiment the product does not run (docs/model.md, measured 2026-11-28).\n\n";
    ledger.fact(
        "[D19]",
        format!(
            "at μ 0.5 the product has {} / {} rollers in contact (`loadedRollers`, force / displacement preload) and {} / {} \
             above 1 % of the largest load, against [D19]'s 13 / 15",
            opt(d.at_mu(0, 0.5).map(|o| o.loaded_rollers as f64)),
            opt(d.at_mu(1, 0.5).map(|o| o.loaded_rollers as f64)),
            opt(d.at_mu(0, 0.5).map(|o| rollers_above_one_percent(o) as f64)),
            opt(d.at_mu(1, 0.5).map(|o| rollers_above_one_percent(o) as f64)),
        ),
    );
    md
}

// =============================================================================================
// 3. [L22] and 6. its torques
// =============================================================================================

/// [L22] Table 3 at 10 kN: largest contact force (kN) and its variance (kN²), series 1 … 6.
const L22_MAX_FORCE_KN: [f64; 6] = [2.026, 2.013, 2.280, 2.253, 2.539, 2.495];
const L22_VARIANCE_KN2: [f64; 6] = [0.0162, 0.0096, 0.0645, 0.0383, 0.1441, 0.0856];

/// The shipped [L22] case of deviation series `s` (0 = ideal rollers) at `kn` kN.
fn l22_file(s: usize, kn: u32) -> String {
    if s == 0 {
        format!("l22_ideal_{kn}kN.json")
    } else {
        format!("l22_series{s}_{kn}kN.json")
    }
}

/// The [L22] cases, per traction law: series 0 (ideal) … 6.
struct L22Runs {
    at_10kn: Vec<Vec<Outputs>>,
    at_2kn: Vec<Vec<Outputs>>,
    /// cage slip rate 0.05 % (the files: 0.01 %)
    at_10kn_slip: Vec<Vec<Outputs>>,
    at_2kn_slip: Vec<Vec<Outputs>>,
    speeds: Vec<f64>,
    /// per traction law: ideal, series 5, series 6 over `speeds` (10 kN, slip 0.01 %)
    by_speed: Vec<[Vec<Outputs>; 3]>,
    slips: Vec<f64>,
    /// per traction law: ideal rollers at 10 kN, 1000 rpm over `slips`
    by_slip: Vec<Vec<Outputs>>,
}

const L22_SLIP: f64 = 5e-4;

impl L22Runs {
    fn run(plan: &Plan) -> Result<L22Runs, CliError> {
        let speeds = plan.pick(&[250.0, 500.0, 1000.0, 1500.0, 2000.0, 3000.0, 4000.0], &[250.0, 1000.0, 4000.0]);
        let slips = vec![0.0, 1e-4, 5e-4, 1e-3];
        eprintln!(
            "[L22]: 7 roller sets at 10 and 2 kN, 2 slip rates, {} speeds, 2 traction laws",
            speeds.len()
        );
        let mut r = L22Runs {
            at_10kn: Vec::new(),
            at_2kn: Vec::new(),
            at_10kn_slip: Vec::new(),
            at_2kn_slip: Vec::new(),
            speeds: speeds.clone(),
            by_speed: Vec::new(),
            slips: slips.clone(),
            by_slip: Vec::new(),
        };
        for t in TRACTIONS {
            let set = |kn: u32, slip: Option<f64>| -> Result<Vec<Outputs>, CliError> {
                (0..=6)
                    .map(|s| {
                        let mut p = vec![("traction", json!(t))];
                        if let Some(x) = slip {
                            p.push(("cageSlipRate", json!(x)));
                        }
                        shipped_case_with(&shipped(&l22_file(s, kn))?, &p, &[])
                    })
                    .collect()
            };
            r.at_10kn.push(set(10, None)?);
            r.at_2kn.push(set(2, None)?);
            r.at_10kn_slip.push(set(10, Some(L22_SLIP))?);
            r.at_2kn_slip.push(set(2, Some(L22_SLIP))?);
            let over_speed = |s: usize| -> Result<Vec<Outputs>, CliError> {
                let base = shipped(&l22_file(s, 10))?;
                speeds
                    .iter()
                    .map(|n| shipped_case_with(&base, &[("traction", json!(t))], &[("speed", n * RPM)]))
                    .collect()
            };
            r.by_speed.push([over_speed(0)?, over_speed(5)?, over_speed(6)?]);
            let base = shipped(&l22_file(0, 10))?;
            r.by_slip.push(
                slips
                    .iter()
                    .map(|x| shipped_case_with(&base, &[("traction", json!(t)), ("cageSlipRate", json!(x))], &[]))
                    .collect::<Result<_, _>>()?,
            );
        }
        Ok(r)
    }
}

fn kn(v: f64) -> f64 {
    v * 1e-3
}

fn l22_section(l: &L22Runs, ledger: &mut Ledger) -> String {
    let mut md = String::from(
        "## 3. [L22] Table 3 and the effect of roller diameter deviations (32008)\n\n\
         The shipped cases `scenarios/l22_*.json` (32008 preset, pure axial load, 1000 rpm, cage slip rate 0.01 %, \
         the deviation series of `roller_deviations_32008.csv`; docs/results-studies.md), once per traction law. \
         [L22]'s Fig. 4 and Table 3 are the roller–outer raceway (cup) contact forces: the product's Qo. Variance: \
         population variance over the 23 rollers (`studies::variance`). [L22]'s text names TRB 30228J in §2.3 but \
         tabulates 32008J (Table 1); the product uses the 32008 preset.\n\n",
    );
    let ideal = per_traction(|t| Some(kn(l.at_10kn[t][0].qo_max)));
    let mut c = Compare::new("[L22]", LUBRICATED);
    for s in 1..=6 {
        c.row(
            ledger,
            &format!("series {s}: largest contact force (kN)"),
            L22_MAX_FORCE_KN[s - 1],
            &per_traction(|t| Some(kn(l.at_10kn[t][s].qo_max))),
        );
    }
    for s in 1..=6 {
        c.row(
            ledger,
            &format!("series {s}: variance of the contact forces (kN²)"),
            L22_VARIANCE_KN2[s - 1],
            &per_traction(|t| Some(studies::variance(&l.at_10kn[t][s].qo) * 1e-6)),
        );
    }
    md += &format!(
        "### Table 3 (axial 10 kN, 1000 rpm)\n\nIdeal rollers carry {} kN each in the product (traction 0; {} with traction 1).\n\n",
        opt(ideal[0]),
        opt(ideal[1])
    );
    md += &c.text();

    // Fig. 6 and 7 statements.
    let mut k = Checks::new("[L22]", LUBRICATED);
    let d_torque = |t: usize, s: usize, get: fn(&Outputs) -> f64| pct_change(get(&l.at_10kn[t][0]), get(&l.at_10kn[t][s]));
    let rings: [(&str, fn(&Outputs) -> f64); 3] = [
        ("total", |o| o.friction_torque),
        ("cone", |o| o.friction_torque_cone),
        ("cup", |o| o.friction_torque_cup),
    ];
    // The ring torques ([L22]'s M_inner, M_outer): cone and cup.
    let ring_changes = |t: usize| -> Vec<f64> {
        (1..=6)
            .flat_map(|s| [d_torque(t, s, rings[1].1), d_torque(t, s, rings[2].1)])
            .collect()
    };
    k.row(
        ledger,
        "§3.2 (Fig. 6): the deviations lower the friction torque on the rings (cone and cup, series 1–6, 10 kN, slip 0.01 %)",
        per_traction(|t| {
            let all = ring_changes(t);
            let falls = all.iter().filter(|v| **v < 0.0).count();
            Some((
                falls == all.len(),
                format!(
                    "{falls} of {} changes negative; series 5: cone {:+.4} %, cup {:+.4} % (total {:+.4} %)",
                    all.len(),
                    d_torque(t, 5, rings[1].1),
                    d_torque(t, 5, rings[2].1),
                    d_torque(t, 5, rings[0].1)
                ),
            ))
        }),
    );
    k.row(
        ledger,
        "§3.2: the ring torque change is of order 10⁻² % (largest |change| of cone and cup within 10^±0.5 of 0.01 %)",
        per_traction(|t| {
            let m = ring_changes(t).iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            let total = (1..=6).map(|s| d_torque(t, s, rings[0].1).abs()).fold(0.0, f64::max);
            Some((
                (0.01 / 10f64.sqrt()..=0.01 * 10f64.sqrt()).contains(&m),
                format!("largest |change| {} % (total torque: {} %)", num(m), num(total)),
            ))
        }),
    );
    k.row(
        ledger,
        "§3.2: the deviation value changes the ring torques more than the distribution form (|series 5 − series 1| against |series 5 − series 6|, cone torque)",
        per_traction(|t| {
            let g = rings[1].1;
            let value = (d_torque(t, 5, g) - d_torque(t, 1, g)).abs();
            let form = (d_torque(t, 5, g) - d_torque(t, 6, g)).abs();
            Some((value > form, format!("value {} %, form {} %", num(value), num(form))))
        }),
    );
    let dt_speed = |t: usize, s: usize, g: fn(&Outputs) -> f64| -> Vec<f64> {
        l.by_speed[t][0]
            .iter()
            .zip(&l.by_speed[t][s])
            .map(|(a, b)| pct_change(g(a), g(b)))
            .collect()
    };
    let n = l.speeds.len();
    k.row(
        ledger,
        "§3.2 (Fig. 6a): the inner-ring torque change depends on speed while the rib is in mixed lubrication, then stays constant (series 5: change over the lowest speeds larger than over the highest)",
        per_traction(|t| {
            let v = dt_speed(t, 1, rings[1].1);
            let (low, high) = ((v[1] - v[0]).abs(), (v[n - 1] - v[n - 2]).abs());
            Some((low > high, format!("{} % at {} rpm", chain(&v), chain(&l.speeds))))
        }),
    );
    k.row(
        ledger,
        "§3.2 (Fig. 6b): the outer-ring torque change does not depend on speed (series 5: spread below 10 % of its mean)",
        per_traction(|t| {
            let v = dt_speed(t, 1, rings[2].1);
            let (lo, hi) = (
                v.iter().cloned().fold(f64::INFINITY, f64::min),
                v.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
            );
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            Some(((hi - lo).abs() <= 0.1 * mean.abs(), format!("{} %", chain(&v))))
        }),
    );
    // Sliding friction (Fig. 7).
    let d_slide = |set: &Vec<Vec<Outputs>>, t: usize, s: usize| pct_change(set[t][0].sliding_friction_max, set[t][s].sliding_friction_max);
    let inc_slide = |set: &Vec<Vec<Outputs>>, t: usize, s: usize| set[t][s].sliding_friction_max - set[t][0].sliding_friction_max;
    k.row(
        ledger,
        "§3.2 (Fig. 7a): the deviation value raises the largest roller sliding friction markedly (series 1, 3, 5)",
        per_traction(|t| {
            let v: Vec<f64> = [1, 3, 5].iter().map(|s| d_slide(&l.at_10kn, t, *s)).collect();
            Some((increasing(&v) && v[0] > 0.0, format!("{} %", chain(&v))))
        }),
    );
    k.row(
        ledger,
        "§3.2 (Fig. 7a): the distribution form changes it little (series 5 against 6, pairs 1/2, 3/4: within a quarter of the increase)",
        per_traction(|t| {
            let pairs: Vec<(f64, f64)> = [(1, 2), (3, 4), (5, 6)]
                .iter()
                .map(|(a, b)| (d_slide(&l.at_10kn, t, *a), d_slide(&l.at_10kn, t, *b)))
                .collect();
            let ok = pairs.iter().all(|(a, b)| (a - b).abs() <= 0.25 * a.abs().max(b.abs()));
            Some((
                ok,
                pairs
                    .iter()
                    .map(|(a, b)| format!("{a:+.1} / {b:+.1} %"))
                    .collect::<Vec<_>>()
                    .join(", "),
            ))
        }),
    );
    k.row(
        ledger,
        "§3.2 (Fig. 7a,b): the increment grows with the cage slip rate (0.01 → 0.05 %), its ratio stays (series 5, 10 kN; within 10 %)",
        per_traction(|t| {
            let (i1, i5) = (inc_slide(&l.at_10kn, t, 5), inc_slide(&l.at_10kn_slip, t, 5));
            let (r1, r5) = (d_slide(&l.at_10kn, t, 5), d_slide(&l.at_10kn_slip, t, 5));
            Some((
                i5 > i1 && (r5 - r1).abs() <= 0.1 * r1.abs(),
                format!("increment {} → {} N, ratio {r1:+.2} → {r5:+.2} %", num(i1), num(i5)),
            ))
        }),
    );
    k.row(
        ledger,
        "§3.2 (Fig. 7b,c): increment and ratio grow from 2 kN to 10 kN (series 5, slip 0.05 %; the conclusions say the opposite: 'more pronounced under light axial load')",
        per_traction(|t| {
            let (i2, i10) = (inc_slide(&l.at_2kn_slip, t, 5), inc_slide(&l.at_10kn_slip, t, 5));
            let (r2, r10) = (d_slide(&l.at_2kn_slip, t, 5), d_slide(&l.at_10kn_slip, t, 5));
            Some((
                i10 > i2 && r10 > r2,
                format!("increment {} → {} N, ratio {r2:+.2} → {r10:+.2} %", num(i2), num(i10)),
            ))
        }),
    );
    md += "### Statements of §3.2 on the deviations (Figs. 6, 7)\n\n";
    md += &k.text();
    md += "`slidingFriction.max` is the largest total sliding friction on one roller (cone, cup and rib); [L22]'s Fig. 7 is \
           the roller–inner raceway part, which the product does not output on its own.\n\n";
    md
}

fn l22_torque_section(l: &L22Runs, ledger: &mut Ledger) -> String {
    let mut md = String::from(
        "## 6. [L22]'s friction torques against the product\n\n\
         [L22] states no torque value in its text: its torques are in Figs. 5–7 only, which the text extraction does \
         not hold. So the product's torques of the 32008 at [L22]'s operating point are listed, and [L22]'s Fig. 5 \
         statements are checked as trends (Fig. 6 and 7: section 3). `frictionTorque` is the energy-consistent \
         torque (power/speed), `frictionTorque.cone` / `.cup` the moments the rings feel ([L22]'s M_inner, M_outer; \
         docs/model.md).\n\n",
    );
    let rows: Vec<Vec<String>> = l
        .slips
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let mut r = vec![format!("{} %", num(s * 100.0))];
            for t in 0..TRACTIONS.len() {
                let o = &l.by_slip[t][i];
                r.extend([
                    num(o.friction_torque * 1e3),
                    num(o.friction_torque_cone * 1e3),
                    num(o.friction_torque_cup * 1e3),
                ]);
            }
            r
        })
        .collect();
    md += "### Ideal rollers, axial 10 kN, 1000 rpm, against the cage slip rate (N mm)\n\n";
    md += &table(
        &["cage slip rate", "T, traction 0", "cone", "cup", "T, traction 1", "cone", "cup"],
        &rows,
    );
    md.push('\n');
    let rows: Vec<Vec<String>> = l
        .speeds
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let mut r = vec![num(*n)];
            for t in 0..TRACTIONS.len() {
                let o = &l.by_speed[t][0][i];
                r.extend([
                    num(o.friction_torque * 1e3),
                    num(o.friction_torque_cone * 1e3),
                    num(o.friction_torque_cup * 1e3),
                    num(o.friction_torque_flange * 1e3),
                ]);
            }
            r
        })
        .collect();
    md += "### Ideal rollers, axial 10 kN, slip 0.01 %, against speed (N mm)\n\n";
    md += &table(
        &[
            "speed (rpm)",
            "T, traction 0",
            "cone",
            "cup",
            "rib part",
            "T, traction 1",
            "cone",
            "cup",
            "rib part",
        ],
        &rows,
    );
    md.push('\n');
    let mut k = Checks::new("[L22]", LUBRICATED);
    let (a, b) = (1, 2); // slip 0.01 % and 0.05 %
    k.row(
        ledger,
        "§3.2 (Fig. 5): the cage slip rate changes the inner-ring torque markedly, the outer-ring torque hardly (0.01 → 0.05 %)",
        per_traction(|t| {
            let (x, y) = (&l.by_slip[t][a], &l.by_slip[t][b]);
            let dc = pct_change(x.friction_torque_cone, y.friction_torque_cone);
            let du = pct_change(x.friction_torque_cup, y.friction_torque_cup);
            Some((dc.abs() > 5.0 * du.abs(), format!("cone {dc:+.1} %, cup {du:+.1} %")))
        }),
    );
    k.row(
        ledger,
        "§3.2 (Fig. 5): the inner-ring torque first falls with speed (rib: mixed lubrication → full film)",
        per_traction(|t| {
            let v: Vec<f64> = l.by_speed[t][0].iter().map(|o| o.friction_torque_cone * 1e3).collect();
            Some((v[1] < v[0], format!("{} N mm", chain(&v))))
        }),
    );
    md += &k.text();
    for t in 0..TRACTIONS.len() {
        let o = &l.by_slip[t][1];
        ledger.fact(
            "[L22]",
            format!(
                "traction {}: at 10 kN, 1000 rpm, slip 0.01 % (ideal rollers) the cone feels {} N mm and the cup {} N mm \
                 (`frictionTorque.cone` / `.cup`), {} and {} times the energy-consistent `frictionTorque` ({} N mm)",
                TRACTIONS[t],
                num(o.friction_torque_cone * 1e3),
                num(o.friction_torque_cup * 1e3),
                num(o.friction_torque_cone / o.friction_torque),
                num(o.friction_torque_cup / o.friction_torque),
                num(o.friction_torque * 1e3)
            ),
        );
    }
    md
}

// =============================================================================================
// 4. [Y22]
// =============================================================================================

const Y22_STATES: [Y22State; 2] = [Y22State::Single, Y22State::Double];

/// One sweep of [Y22]: per traction law and state, the outputs over `xs`.
struct Y22Sweep {
    what: &'static str,
    unit: &'static str,
    xs: Vec<f64>,
    runs: Vec<[Vec<Outputs>; 2]>,
}

/// The [Y22] case at the defaults with one quantity changed.
#[derive(Clone, Copy)]
enum Y22Knob {
    Clearance,
    Waveform,
    RadialLoad,
    Speed,
}

fn y22_file(state: Y22State) -> &'static str {
    match state {
        Y22State::Single => "y22_single_pressed.json",
        Y22State::Double => "y22_double_pressed.json",
    }
}

/// The shipped [Y22] case of `state` with `knob` at `x` (µm, N or rpm), the rest at the
/// study's defaults (clearance −10 µm, waveform 20 µm, Fy 100 N, 40,000 rpm).
fn y22_case(base: &Scenario, traction: i32, knob: Y22Knob, x: f64) -> Result<Outputs, CliError> {
    let (mut c, mut ee, mut fy, mut n) = (studies::Y22_CLEARANCE, studies::Y22_WAVEFORM, studies::Y22_FY, studies::Y22_RPM);
    match knob {
        Y22Knob::Clearance => c = x * 1e-6,
        Y22Knob::Waveform => ee = x * 1e-6,
        Y22Knob::RadialLoad => fy = x,
        Y22Knob::Speed => n = x,
    }
    shipped_case_with(
        base,
        &[
            ("traction", json!(traction)),
            ("clearance", json!(c)),
            ("outer.waveform", json!(ee)),
        ],
        &[("Fy", fy), ("speed", n * RPM)],
    )
}

struct Y22Runs {
    defaults: Vec<[Outputs; 2]>,
    clearance: Y22Sweep,
    waveform: Y22Sweep,
    radial_load: Y22Sweep,
    speed: Y22Sweep,
}

impl Y22Runs {
    fn run(plan: &Plan) -> Result<Y22Runs, CliError> {
        let bases = [shipped(y22_file(Y22State::Single))?, shipped(y22_file(Y22State::Double))?];
        let sweep = |what, unit, knob: Y22Knob, xs: Vec<f64>| -> Result<Y22Sweep, CliError> {
            let runs = TRACTIONS
                .iter()
                .map(|&t| -> Result<[Vec<Outputs>; 2], CliError> {
                    let one = |b: &Scenario| xs.iter().map(|x| y22_case(b, t, knob, *x)).collect::<Result<Vec<_>, _>>();
                    Ok([one(&bases[0])?, one(&bases[1])?])
                })
                .collect::<Result<_, _>>()?;
            Ok(Y22Sweep { what, unit, xs, runs })
        };
        let clearance: Vec<f64> = if plan.quick {
            vec![-20.0, -10.0, 0.0, 10.0]
        } else {
            (0..=15).map(|k| -20.0 + 2.0 * k as f64).collect()
        };
        let waveform: Vec<f64> = if plan.quick {
            vec![0.0, 20.0, 40.0]
        } else {
            (0..=10).map(|k| 4.0 * k as f64).collect()
        };
        let loads = plan.pick(
            &[0.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, 3000.0, 5000.0],
            &[100.0, 1000.0, 5000.0],
        );
        let speeds: Vec<f64> = if plan.quick {
            vec![10_000.0, 40_000.0, 60_000.0]
        } else {
            (1..=12).map(|k| 5000.0 * k as f64).collect()
        };
        eprintln!("[Y22]: defaults and four sweeps, two roller positions, two traction laws");
        let defaults = TRACTIONS
            .iter()
            .map(|&t| -> Result<[Outputs; 2], CliError> {
                Ok([
                    y22_case(&bases[0], t, Y22Knob::RadialLoad, studies::Y22_FY)?,
                    y22_case(&bases[1], t, Y22Knob::RadialLoad, studies::Y22_FY)?,
                ])
            })
            .collect::<Result<_, _>>()?;
        Ok(Y22Runs {
            defaults,
            clearance: sweep("mounting clearance", "µm", Y22Knob::Clearance, clearance)?,
            waveform: sweep("waveform value ee", "µm", Y22Knob::Waveform, waveform)?,
            radial_load: sweep("radial load", "N", Y22Knob::RadialLoad, loads)?,
            speed: sweep("speed", "rpm", Y22Knob::Speed, speeds)?,
        })
    }
}

/// "falls" / "rises" / "stays" of the first and last value, and whether every step goes
/// that way (ties allowed).
fn direction(v: &[f64]) -> (&'static str, bool) {
    let (a, b) = (v[0], v[v.len() - 1]);
    let e = tol(v);
    if b > a + e {
        ("rises", non_decreasing(v))
    } else if b < a - e {
        ("falls", non_increasing(v))
    } else {
        ("stays", v.windows(2).all(|w| (w[1] - w[0]).abs() <= e))
    }
}

/// The product's behaviour over one sweep for one state: the inner-raceway load, the
/// loaded-roller count and the preload, compared with what [Y22] states.
fn y22_sweep_verdict(s: &Y22Sweep, t: usize, state: usize, load: &str, count: &str, preload_kept: bool) -> (bool, String) {
    let runs = &s.runs[t][state];
    let q: Vec<f64> = runs.iter().map(|o| o.qi_max).collect();
    let n: Vec<f64> = runs.iter().map(|o| o.loaded_rollers as f64).collect();
    let lost =
        s.xs.iter()
            .zip(runs)
            .find(|(_, o)| !studies::y22_preloaded(o, Y22_STATES[state]))
            .map(|(x, _)| *x);
    let (qd, qm) = direction(&q);
    let (nd, _) = direction(&n);
    let ok = qd == load && nd == count && (lost.is_none() == preload_kept);
    (
        ok,
        format!(
            "Qi.max {} {} N{}; rollers {} {}; preload {}",
            qd,
            chain(&[q[0], q[q.len() - 1]]),
            if qm { "" } else { " (not monotone)" },
            nd,
            chain(&[n[0], n[n.len() - 1]]),
            match lost {
                Some(x) => format!("lost at {} {}", num(x), s.unit),
                None => "kept".into(),
            }
        ),
    )
}

fn y22_section(y: &Y22Runs, ledger: &mut Ledger) -> String {
    let mut md = String::from(
        "## 4. [Y22] Cylindrical roller bearing with a triple-lobe outer raceway (CRB-TRILOBE)\n\n\
         The shipped cases `scenarios/y22_single_pressed.json` and `y22_double_pressed.json` (roller 1 on a lobe low \
         point, or half a pitch away) at [Y22]'s defaults (mounting clearance −10 µm, waveform 20 µm, Fy 100 N, \
         40,000 rpm), one quantity swept at a time, once per traction law. [Y22]'s maximum contact load is the inner \
         raceway's: `Qi.max`. Loaded rollers: `loadedRollers`. Preload: rollers loaded in all three lobe zones \
         (`studies::y22_preloaded`). [Y22] publishes no table of its bearing in the extraction, so CRB-TRILOBE is a \
         representative bearing (docs/model.md, 'Defaults the studies do not give'): counts and trends compare, loads \
         do not.\n\n",
    );
    let mut c = Compare::new("[Y22]", LUBRICATED);
    c.row(
        ledger,
        "loaded rollers, single-pressed",
        3.0,
        &per_traction(|t| Some(y.defaults[t][0].loaded_rollers as f64)),
    );
    c.row(
        ledger,
        "loaded rollers, double-pressed",
        6.0,
        &per_traction(|t| Some(y.defaults[t][1].loaded_rollers as f64)),
    );
    md += &c.text();
    let mut k = Checks::new("[Y22]", LUBRICATED);
    k.row(
        ledger,
        "§3: three preload areas, the largest along the radial load (single-pressed, defaults)",
        per_traction(|t| {
            let o = &y.defaults[t][0];
            let zones = studies::loaded_lobe_zones(o, Y22State::Single.cage_angle());
            let z = o.qi.len();
            let j = (0..z).max_by(|a, b| o.qi[*a].total_cmp(&o.qi[*b])).unwrap_or(0);
            let az = (Y22State::Single.cage_angle() + 2.0 * std::f64::consts::PI * j as f64 / z as f64).to_degrees();
            let az = if az > 180.0 { az - 360.0 } else { az };
            Some((
                zones == 3 && az.abs() <= 60.0,
                format!("{zones} lobe zones loaded; largest Qi at {} deg from the load", num(az)),
            ))
        }),
    );
    k.row(
        ledger,
        "§3: with more loaded rollers (double-pressed) the contact load is lower",
        per_traction(|t| {
            let (s, d) = (&y.defaults[t][0], &y.defaults[t][1]);
            let more = d.loaded_rollers > s.loaded_rollers;
            Some((
                (d.qi_max < s.qi_max) == more,
                format!(
                    "single {} rollers, Qi.max {} N; double {} rollers, Qi.max {} N",
                    s.loaded_rollers,
                    num(s.qi_max),
                    d.loaded_rollers,
                    num(d.qi_max)
                ),
            ))
        }),
    );
    let sweeps: [(&Y22Sweep, &str, [(&str, &str, bool); 2]); 4] = [
        (
            &y.clearance,
            "§3.1: with growing mounting clearance",
            [("falls", "falls", false), ("falls", "falls", false)],
        ),
        (
            &y.waveform,
            "§3.2: with growing waveform value",
            [("rises", "falls", true), ("falls", "falls", false)],
        ),
        (
            &y.radial_load,
            "§3.3: with growing radial load",
            [("rises", "stays", true), ("rises", "falls", false)],
        ),
        (
            &y.speed,
            "§3.4: with growing speed",
            [("falls", "stays", true), ("falls", "falls", false)],
        ),
    ];
    for (s, lead, expected) in sweeps {
        for (state, (load, count, kept)) in expected.iter().enumerate() {
            k.row(
                ledger,
                &format!(
                    "{lead} ({} {} … {} {}), {}: the largest inner-raceway load {load}, the loaded rollers {}, the preload {}",
                    s.what,
                    num(s.xs[0]),
                    num(s.xs[s.xs.len() - 1]),
                    s.unit,
                    Y22_STATES[state].label(),
                    if *count == "stays" { "stay" } else { "fall" },
                    if *kept { "is kept" } else { "is lost" }
                ),
                per_traction(|t| Some(y22_sweep_verdict(s, t, state, load, count, *kept))),
            );
        }
    }
    k.row(
        ledger,
        "§3.1: the double-pressed state loses its preload at a smaller clearance than the single-pressed one",
        per_traction(|t| {
            let lost = |state: usize| {
                y.clearance
                    .xs
                    .iter()
                    .zip(&y.clearance.runs[t][state])
                    .find(|(_, o)| !studies::y22_preloaded(o, Y22_STATES[state]))
                    .map(|(x, _)| *x)
            };
            let (s, d) = (lost(0), lost(1));
            let text = |v: Option<f64>| v.map(|x| format!("{} µm", num(x))).unwrap_or_else(|| "never".into());
            Some((
                matches!((s, d), (Some(s), Some(d)) if d < s) || (s.is_none() && d.is_some()),
                format!("double {}, single {}", text(d), text(s)),
            ))
        }),
    );
    md += &k.text();
    let same = (0..2).all(|state| y.defaults[0][state].qi == y.defaults[1][state].qi);
    ledger.fact(
        "[Y22]",
        format!(
            "the roller loads at the defaults are {} under both traction laws (the quasi-static load equilibrium of the \
             CRB carries no traction)",
            if same { "identical" } else { "not identical" }
        ),
    );
    md
}

// =============================================================================================
// 5. Against the SKF frictional-moment model
// =============================================================================================

/// One operating point against the SKF model: the product per traction law.
struct SkfPoint {
    x: f64,
    skf: SkfMoment,
    product: Vec<Option<(f64, f64, f64)>>,
}

/// SKF's moment at `rpm`, axial load `fa` and radial load `fr` (N).
fn skf_reference(bearing: &SkfTrb, eta0: f64, rpm: f64, fa: f64, fr: f64) -> SkfMoment {
    let lub = skf_friction::Lubrication::oil_bath(eta0, None);
    skf_friction::frictional_moment(bearing, &lub, rpm * RPM, fr, fa)
}

/// (total, raceway, flange) torque of a run (N m).
fn torque_parts(o: &Outputs) -> (f64, f64, f64) {
    (o.friction_torque, o.friction_torque_raceway, o.friction_torque_flange)
}

/// What an SKF table runs over: the speed (rpm), the axial or the radial load (kN).
#[derive(Clone, Copy)]
enum SkfOver {
    Speed,
    Axial,
    Radial,
}

/// The quasi-static product at (`rpm`, `fa`, `fr`) from the scenario `file` (the radial load
/// as `Fy`), against SKF.
fn skf_quasi_static(file: &str, bearing: &SkfTrb, points: &[(f64, f64, f64)], over: SkfOver) -> Result<Vec<SkfPoint>, CliError> {
    let base = shipped(file)?;
    let eta0 = base.bearing.bearing.eta0;
    points
        .iter()
        .map(|&(rpm, fa, fr)| {
            let product = TRACTIONS
                .iter()
                .map(|&t| {
                    let inputs = [("speed", rpm * RPM), ("Fx", fa), ("Fy", fr)];
                    shipped_case_with(&base, &[("traction", json!(t))], &inputs).map(|o| Some(torque_parts(&o)))
                })
                .collect::<Result<Vec<_>, _>>()?;
            Ok(SkfPoint {
                x: match over {
                    SkfOver::Speed => rpm,
                    SkfOver::Axial => fa * 1e-3,
                    SkfOver::Radial => fr * 1e-3,
                },
                skf: skf_reference(bearing, eta0, rpm, fa, fr),
                product,
            })
        })
        .collect()
}

fn skf_table(ledger: &mut Ledger, title: &str, x_label: &str, points: &[SkfPoint], fidelity: &str) -> String {
    let mut rows = Vec::new();
    for p in points {
        let mut r = vec![num(p.x), num(p.skf.rolling), num(p.skf.sliding), num(p.skf.total)];
        let mut ratios = Vec::new();
        for (c, v) in LUBRICATED.iter().zip(&p.product) {
            match v {
                Some((t, race, flange)) => {
                    let q = ratio(Some(*t), p.skf.total);
                    r.extend([num(*t), num(*race), num(*flange), ratio_text(q)]);
                    if let Some(q) = q {
                        ratios.push((*c, q));
                    }
                }
                None => r.extend(["—".to_string(), "—".into(), "—".into(), "—".into()]),
            }
        }
        if !ratios.is_empty() {
            ledger.ratios.push(RatioEntry {
                source: "SKF",
                what: format!("{title}, {fidelity}, {x_label} {}", num(p.x)),
                ratios,
            });
        }
        rows.push(r);
    }
    let spans: Vec<String> = (0..LUBRICATED.len())
        .filter_map(|t| {
            let q: Vec<f64> = points.iter().filter_map(|p| p.product[t].map(|v| v.0 / p.skf.total)).collect();
            (!q.is_empty()).then(|| {
                let (lo, hi) = (
                    q.iter().cloned().fold(f64::INFINITY, f64::min),
                    q.iter().cloned().fold(0.0, f64::max),
                );
                format!("{} … {} (traction {})", ratio_text(Some(lo)), ratio_text(Some(hi)), TRACTIONS[t])
            })
        })
        .collect();
    if !spans.is_empty() {
        ledger.fact("SKF", format!("{title} ({fidelity}): T/SKF {}", spans.join(", ")));
    }
    format!(
        "### {title} ({fidelity})\n\n{}\n",
        table(
            &[
                x_label,
                "SKF rolling",
                "SKF sliding",
                "SKF total",
                "product T, traction 0",
                "raceway",
                "flange",
                "T / SKF",
                "product T, traction 1",
                "raceway",
                "flange",
                "T / SKF",
            ],
            &rows
        )
    )
}

/// Why the product's torque and SKF's part ways over the radial load.
const SKF_RADIAL: &str = "**Over the radial load.** SKF's rolling and sliding moments grow with Fr + R·Y·Fa (the rolling one \
    to the power 0.31), an equivalent load of the whole bearing. The product sums its contacts. A roller's EHL rolling \
    resistance grows only as its load to the power 0.246 ([W25] Eq. 14, from Goksem and Hargreaves), and a roller out of \
    the load zone has none. The rib's sliding follows the rib loads, which the axial load sets. A radial load that narrows \
    the load zone gathers the same axial share on fewer rollers, and the raceway torque falls. The two models agree where \
    every roller is loaded, and the product falls below SKF once the load zone narrows. SKF's fit, made on whole \
    bearings, does not resolve the load zone; the product has no loss for a roller out of it (no drag or churning term, \
    and SKF's drag term is left out here). docs/validation-notes.md checks the mechanism roller by roller.\n\n";

fn skf_section(plan: &Plan, runs: &W25Runs, apex: &W25Runs, ledger: &mut Ledger) -> Result<String, CliError> {
    eprintln!("SKF: quasi-static sweeps of TRB130x230-W25 (as published), TRB130x230 (apex-consistent) and 32008");
    let trb = skf_friction::trb130x230_series();
    let small = skf_friction::series_32008();
    let speeds = plan.pick(&W25_SPEEDS_RPM, &[500.0, 3500.0]);
    let loads = plan.pick(&[12e3, 21e3, 30e3, 39e3], &[12e3, 39e3]);
    let speeds_32008 = plan.pick(&[500.0, 1000.0, 2000.0, 3000.0, 4000.0, 5000.0], &[500.0, 5000.0]);
    let at = |rpm: &[f64], fa: f64| rpm.iter().map(|n| (*n, fa, 0.0)).collect::<Vec<_>>();
    let at_loads = |rpm: f64| loads.iter().map(|fa| (rpm, *fa, 0.0)).collect::<Vec<_>>();
    let at_radial = |rpm: f64, fa: f64, frs: &[f64]| frs.iter().map(|fr| (rpm, fa, *fr)).collect::<Vec<_>>();
    let eta0 = shipped("validate/skf_trb130x230.json")?.bearing.bearing.eta0;
    let mut md = format!(
        "## 5. Friction torque against the SKF frictional-moment model\n\n\
         `trb::skf_friction` (src/skf_friction.rs): M = φ_ish φ_rs M_rr + M_sl of the SKF catalogue, an independent set \
         of correlations. Oil: the preset's η0 ({} Pa s) with density {} kg/m³ for ν; low-level oil bath / oil jet \
         (K_rs = {}); μ_bl = {}, μ_EHL = {}; no drag losses; Y from ISO 281 (0.4 cot α of the cup angle). TRB130x230 as \
         SKF 32226 (series 322), 32008 as SKF 32008 X (series 320 X). The product: pure axial load, force preload, the \
         scenarios of `scenarios/validate/` with `speed` and `Fx` set; fidelity 0 (quasi-static) everywhere, and \
         fidelity 1 (the [W25] runs of section 1, averaged over the second half) for TRB130x230. Torques in N m; \
         raceway / flange: `frictionTorque.raceway` / `.flange`.\n\n\
         The SKF model assumes a kinematically consistent TRB (cone, cup and roller axis meeting in one apex on the \
         bearing axis). The published TRB130x230 geometry (preset TRB130x230-W25) is not: its cone, cup and roller axis \
         meet the bearing axis 894, 373 and 512 mm from the pitch plane, so its rollers slide along the whole contact \
         line. The default preset TRB130x230 is the same bearing made apex-consistent (cup angle as published, roller \
         half-cone and cone angle derived, Palmgren's law, presets/TRB130x230.json); the SKF numbers are the same for \
         both (same envelope, cup angle and oil).\n\n",
        num(eta0),
        num(skf_friction::DEFAULT_OIL_DENSITY),
        num(skf_friction::K_RS_OIL_BATH_OR_JET),
        num(skf_friction::MU_BL),
        num(skf_friction::MU_EHL_TRB)
    );
    let published = "validate/skf_trb130x230.json";
    let apex_file = "validate/skf_trb130x230_apex.json";
    let p_speed = skf_quasi_static(published, &trb, &at(&speeds, 30e3), SkfOver::Speed)?;
    let p_load = skf_quasi_static(published, &trb, &at_loads(3500.0), SkfOver::Axial)?;
    let a_speed = skf_quasi_static(apex_file, &trb, &at(&speeds, 30e3), SkfOver::Speed)?;
    let a_load = skf_quasi_static(apex_file, &trb, &at_loads(3500.0), SkfOver::Axial)?;
    let radial_trb = plan.pick(&[0.0, 10e3, 20e3, 30e3, 45e3], &[0.0, 45e3]);
    let radial_32008 = plan.pick(&[0.0, 1e3, 2e3, 4e3, 6e3], &[0.0, 6e3]);
    let a_radial = skf_quasi_static(apex_file, &trb, &at_radial(3500.0, 30e3, &radial_trb), SkfOver::Radial)?;
    let s_radial = skf_quasi_static(
        "validate/skf_32008.json",
        &small,
        &at_radial(2000.0, 2e3, &radial_32008),
        SkfOver::Radial,
    )?;
    md += &skf_table(
        ledger,
        "TRB130x230-W25 (as published), Fa 30 kN",
        "speed (rpm)",
        &p_speed,
        "fidelity 0",
    );
    md += &skf_table(ledger, "TRB130x230-W25 (as published), 3500 rpm", "Fa (kN)", &p_load, "fidelity 0");
    md += &skf_table(
        ledger,
        "TRB130x230 (the default, apex-consistent), Fa 30 kN",
        "speed (rpm)",
        &a_speed,
        "fidelity 0",
    );
    md += &skf_table(
        ledger,
        "TRB130x230 (the default, apex-consistent), 3500 rpm",
        "Fa (kN)",
        &a_load,
        "fidelity 0",
    );
    md += &skf_table(
        ledger,
        "TRB130x230 (the default, apex-consistent), 3500 rpm, Fa 30 kN",
        "Fr (kN)",
        &a_radial,
        "fidelity 0",
    );
    md += &skf_table(ledger, "32008, 2000 rpm, Fa 2 kN", "Fr (kN)", &s_radial, "fidelity 0");
    md += SKF_RADIAL;
    for fa in [10e3, 2e3] {
        let pts = skf_quasi_static("validate/skf_32008.json", &small, &at(&speeds_32008, fa), SkfOver::Speed)?;
        md += &skf_table(
            ledger,
            &format!("32008, Fa {} kN", num(fa * 1e-3)),
            "speed (rpm)",
            &pts,
            "fidelity 0",
        );
    }
    // Fidelity 1: the [W25] runs at Fa 30 kN over speed and at 3500 rpm over the axial load.
    let dynamic = |runs: &W25Runs, names: &[&str], xs: &[f64], rpm: &dyn Fn(usize) -> f64, fa: &dyn Fn(usize) -> f64| -> Vec<SkfPoint> {
        names
            .iter()
            .enumerate()
            .filter(|(_, n)| runs.cases.contains_key(**n))
            .map(|(i, n)| SkfPoint {
                x: xs[i],
                skf: skf_reference(&trb, eta0, rpm(i), fa(i), 0.0),
                product: per_traction(|t| runs.case(n, t).map(|r| (r.torque, r.torque_raceway, r.torque_flange))),
            })
            .collect()
    };
    let d_speed = dynamic(runs, &W25_SPEED_ALIGNED, &W25_SPEEDS_RPM, &|i| W25_SPEEDS_RPM[i], &|_| 30e3);
    let d_load = dynamic(runs, &W25_AXIAL_ALIGNED, &W25_AXIAL_KN, &|_| 3500.0, &|i| W25_AXIAL_KN[i] * 1e3);
    let apex_speeds = [500.0, 3500.0];
    let d_apex = dynamic(apex, &APEX_DYNAMIC, &apex_speeds, &|i| apex_speeds[i], &|_| 30e3);
    md += &skf_table(
        ledger,
        "TRB130x230-W25 (as published), Fa 30 kN",
        "speed (rpm)",
        &d_speed,
        &format!("fidelity 1, {} ms runs", num(plan.run_length_ms())),
    );
    md += &skf_table(
        ledger,
        "TRB130x230-W25 (as published), 3500 rpm",
        "Fa (kN)",
        &d_load,
        &format!("fidelity 1, {} ms runs", num(plan.run_length_ms())),
    );
    if !d_apex.is_empty() {
        md += &skf_table(
            ledger,
            "TRB130x230 (the default, apex-consistent), Fa 30 kN",
            "speed (rpm)",
            &d_apex,
            &format!(
                "fidelity 1, {} ms runs (`scenarios/validate/apex_dynamic_*.json`)",
                num(plan.run_length_ms())
            ),
        );
    }

    // Facts for section 7: the apex variant at the [W25] reference point.
    let at3500 = |pts: &[SkfPoint]| pts.iter().find(|p| p.x == 3500.0).map(|p| (p.product.clone(), p.skf.total));
    if let (Some((pp, skf)), Some((ap, _))) = (at3500(&p_speed), at3500(&a_speed)) {
        for (t, (p, a)) in pp.iter().zip(&ap).enumerate() {
            if let (Some(p), Some(a)) = (p, a) {
                ledger.fact(
                    "SKF",
                    format!(
                        "at 3500 rpm and Fa 30 kN (fidelity 0, traction {}) the product gives {} N m for TRB130x230-W25 \
                         (as published) and {} N m for the default TRB130x230 (apex-consistent, {:+.0} %), SKF {} N m for both",
                        TRACTIONS[t],
                        num(p.0),
                        num(a.0),
                        pct_change(p.0, a.0),
                        num(skf)
                    ),
                );
            }
        }
    }
    Ok(md)
}

// =============================================================================================
// 7. Where we differ
// =============================================================================================

const SOURCES: [(&str, &str); 6] = [
    (
        "[W25]",
        "The dynamic model's laws and choices are in docs/dynamic.md; the full-film traction law that stands in for \
         [W25]'s unsourced regression (Wang, Yang & Wang 2004) is in docs/model.md ('Friction torque and power loss'). \
         docs/results-dynamic.md discusses the skew level of the published geometry.",
    ),
    (
        "[D19]",
        "docs/model.md, 'Differences from [D19]', items 1–5: the sense and magnitude of the friction thrust, the \
         restoring moment of the raceway loads, what counts as a roller in contact, the torque formulas lost in the \
         extraction.",
    ),
    (
        "[L22]",
        "docs/model.md: Palmgren contact law, diameter deviations applied exactly (not [L22]'s Taylor correction), the \
         Zhou–Hoeprich rolling resistance in place of [L22]'s garbled formula, and the ring torques.",
    ),
    (
        "[Y22]",
        "docs/model.md, 'Defaults the studies do not give': CRB-TRILOBE is a representative bearing, not [Y22]'s.",
    ),
    (
        "SKF",
        "src/skf_friction.rs: catalogue correlations with Y from ISO 281 (not the product tables), no drag losses; the \
         SKF model assumes a kinematically consistent bearing.",
    ),
    (
        supply::SOURCE,
        "docs/model.md, 'Lubricant supply' and 'Mixed lubrication'; docs/validation-notes.md, 'Lubricant supply': the \
         skew with the rib's whole load in boundary friction.",
    ),
];

fn differences_section(ledger: &Ledger) -> String {
    let mut md = format!(
        "## 7. In plain words: where we differ\n\n\
         Generated from the comparisons above: every ratio product/study (or product/SKF) outside 1 ± {} and every \
         statement the product does not reproduce, by source, with where the model's choices are documented. This \
         section states facts; it does not explain them.{}\n\n",
        OFF_BY,
        if Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/validation-notes.md").exists() {
            " Explanations checked by hand: docs/validation-notes.md."
        } else {
            ""
        }
    );
    for (source, pointer) in SOURCES {
        let ratios: Vec<&RatioEntry> = ledger.ratios.iter().filter(|r| r.source == source).collect();
        let checks: Vec<&CheckEntry> = ledger.checks.iter().filter(|c| c.source == source).collect();
        let _ = writeln!(md, "### {source}\n");
        let columns: Vec<&str> = match source {
            "[D19]" => DRY.to_vec(),
            supply::SOURCE => supply::COLUMNS.to_vec(),
            _ => LUBRICATED.to_vec(),
        };
        for c in &columns {
            let v: Vec<f64> = ratios
                .iter()
                .flat_map(|r| r.ratios.iter().filter(|(k, _)| k == c).map(|(_, q)| *q))
                .collect();
            if v.is_empty() {
                continue;
            }
            let within = v.iter().filter(|q| (**q - 1.0).abs() <= OFF_BY).count();
            let mut sorted = v.clone();
            sorted.sort_by(f64::total_cmp);
            let _ = writeln!(
                md,
                "- {c}: {within} of {} numbers within ±{:.0} %; ratios from {} to {}, median {}.",
                v.len(),
                OFF_BY * 100.0,
                ratio_text(Some(sorted[0])),
                ratio_text(Some(sorted[sorted.len() - 1])),
                ratio_text(Some(sorted[sorted.len() / 2]))
            );
        }
        for c in &columns {
            let n = checks.iter().filter(|k| k.holds.iter().any(|(x, _)| x == c)).count();
            let ok = checks.iter().filter(|k| k.holds.iter().any(|(x, h)| x == c && *h)).count();
            if n > 0 {
                let _ = writeln!(md, "- {c}: {ok} of {n} stated trends reproduced.");
            }
        }
        for (s, fact) in &ledger.facts {
            if *s == source {
                let _ = writeln!(md, "- {fact}.");
            }
        }
        md.push('\n');
        let off: Vec<Vec<String>> = ratios
            .iter()
            .filter(|r| r.ratios.iter().any(|(_, q)| (q - 1.0).abs() > OFF_BY))
            .map(|r| {
                let mut row = vec![r.what.clone()];
                for c in &columns {
                    row.push(ratio_text(r.ratios.iter().find(|(k, _)| k == c).map(|(_, q)| *q)));
                }
                row
            })
            .collect();
        if !off.is_empty() {
            let mut head = vec!["off by more than 30 %"];
            head.extend(columns.iter().map(|c| *c));
            md += &table(&head, &off);
            md.push('\n');
        }
        let missed: Vec<String> = checks
            .iter()
            .filter(|k| k.holds.iter().any(|(_, h)| !h))
            .map(|k| {
                let cols: Vec<&str> = k
                    .holds
                    .iter()
                    .filter(|(_, h)| !h)
                    .map(|(c, _)| {
                        c.trim_start_matches("product, ")
                            .trim_start_matches("product (")
                            .trim_end_matches(')')
                    })
                    .collect();
                format!("- not reproduced ({}): {}", cols.join(", "), k.what)
            })
            .collect();
        for m in &missed {
            let _ = writeln!(md, "{m}");
        }
        if !missed.is_empty() {
            md.push('\n');
        }
        let _ = writeln!(md, "Where the model's choices are documented: {pointer}\n");
    }
    if !ledger.failures.is_empty() {
        md += "### Not computed\n\n";
        for f in &ledger.failures {
            let _ = writeln!(md, "- {f}");
        }
        md.push('\n');
    }
    md
}

// =============================================================================================
// The document
// =============================================================================================

/// Run every comparison and write `docs/validation.md`.
pub fn report(docs: &Path, quick: bool) -> Result<(), CliError> {
    let started = Instant::now();
    let plan = Plan { quick };
    let mut ledger = Ledger::default();
    std::fs::create_dir_all(docs).map_err(|e| CliError::failed(format!("cannot create {}: {e}", docs.display())))?;

    let d19 = D19Runs::run(&plan)?;
    let l22 = L22Runs::run(&plan)?;
    let y22 = Y22Runs::run(&plan)?;
    let w25 = W25Runs::run(&plan, &w25::scenario_dir(), plan.w25_cases(), "[W25]", &mut ledger);
    let book = w25_book_law_runs(&plan, &mut ledger);
    let fidelities = w25_fidelity_runs(&plan, &mut ledger);
    let apex = if quick {
        W25Runs { cases: BTreeMap::new() }
    } else {
        W25Runs::run(
            &plan,
            &scenarios_dir().join("validate"),
            APEX_DYNAMIC.to_vec(),
            "the default TRB130x230 (apex-consistent)",
            &mut ledger,
        )
    };

    let mut body = String::new();
    body += &w25_section(&w25, &book, &plan, &mut ledger);
    body += &w25_at_three_fidelities(&w25, &fidelities);
    body += &fidelity_two_checks(&plan, &w25, &mut ledger);
    body += &d19_section(&d19, &mut ledger);
    body += &l22_section(&l22, &mut ledger);
    body += &y22_section(&y22, &mut ledger);
    body += &skf_section(&plan, &w25, &apex, &mut ledger)?;
    body += &l22_torque_section(&l22, &mut ledger);
    let supply = supply::section(&plan, &mut ledger)?;
    body += &differences_section(&ledger);
    body += &supply;

    let wall = started.elapsed().as_secs_f64();
    let doc = format!(
        "# Validation: the product against the studies and the SKF model\n\n\
         Written by `cargo run --release -- study validate{}` (src/cli/study/validate.rs); do not edit by hand. Every \
         number the four studies state in their text (`../shared/papers/`: [W25] Wu, Kang & Deng, Lubricants \
         13(10):438, 2025; [D19] Friction 7(6):551–563, 2019; [L22] Liu, Fan, Wang & Liu, Lubricants 10(7):154, 2022; \
         [Y22] Yu et al., Mechanics & Industry 23:19, 2022) beside the product's value and the ratio product/study, \
         their stated trends as yes/no rows with the product's numbers, and the friction torque against the SKF \
         frictional-moment model. Each lubricated number is given for both values of the FMU parameter `traction`: \
         **0** the thermal Eyring film with elastic entry and limiting shear (the default), **1** the isothermal \
         Newtonian–Eyring law (kept for comparison with the studies); it is set as a scenario file sets it. Cases are \
         the shipped scenarios (`scenarios/`), changed only where a study's case needs it (the change is named).\n\n\
         Run: {}, commit {}, {}; {} mode, {:.0} s wall time.\n\n",
        if quick { " --quick" } else { "" },
        report::date(),
        report::commit(),
        report::machine(),
        if quick { "quick (development)" } else { "full" },
        wall
    );
    let text = doc + &body;
    let path = docs.join("validation.md");
    std::fs::write(&path, text).map_err(|e| CliError::failed(format!("cannot write {}: {e}", path.display())))?;
    println!("wrote {} ({wall:.0} s)", path.display());
    Ok(())
}
