//! The numerical stress matrix: hundreds of operating cases per fidelity, each run
//! through [`Simulation`] (the code the FMU runs) and, for a representative subset, through
//! the FMU's C ABI as well, with every output checked after every step.
//!
//! This file depends only on the `trb` library, so the `stress` command (`src/cli/stress.rs`)
//! and the test `tests/stress.rs` include the same code.
//!
//! # Cases
//!
//! [`cases`] lists the cases of one fidelity for all four presets. Loads are given as
//! fractions of the static capacity C0 of each preset ([`Preset::c0`], ISO 76), speeds as
//! fractions of a limiting speed ([`Preset::n_lim`]). Each case says what is acceptable:
//! - [`Expect::Pass`]: physically fine and inside the model's documented range: every step
//!   must succeed; a refusal is a failure;
//! - [`Expect::PassOrRefuse`]: beyond the static capacity or the limiting speed, or a physical
//!   impossibility of the single bearing (no axial force under radial load): either result is
//!   fine, a refusal must say why;
//! - [`Expect::Refuse`]: outside the model's validity range: it must be refused, saying why.
//!
//! Fidelity 1 and 2 cases are the same list with `fidelity` set and durations of their own
//! ([`Durations`]), and a `dynamic` group of their own; in a build without the dynamic model
//! they are reported as not available.
//!
//! # Checks after every successful step
//!
//! All Real outputs finite; `powerLoss = frictionTorque × speed` (relative 1e-12) and
//! `powerLoss >= 0`; `frictionTorque` = sum of its parts; contact loads >= 0; `loadedRollers`
//! in [0, Z]; in force preload of a tapered bearing `reaction.Fx = Fx` (the equilibrium holds).
//! After a refusal the outputs the element still returns (those of its last successful solve)
//! must be finite too.

use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use trb::bearing::{Bearing, Kind, PRESETS};
use trb::fmi::*;
use trb::model::Severity;
use trb::model_description;
use trb::simulation::Simulation;
use trb::variables::{self as var, Causality, VarType};

// ---------------------------------------------------------------------------------------
// Presets: static capacity and limiting speed
// ---------------------------------------------------------------------------------------

/// A preset with the reference values the cases are scaled by.
#[derive(Debug, Clone)]
pub struct Preset {
    pub bearing: Bearing,
    /// Basic static radial load rating C0r (N), ISO 76 (`rating.C0`, `src/bearing/rating.rs`).
    pub c0: f64,
    /// Axial load equivalent to C0r (N): P0 = Y0 Fa with Y0 = 0.22 cot a (ISO 76), so
    /// Fa0 = C0r tan a / 0.22. A cylindrical bearing carries no axial load: 0.
    pub fa0: f64,
    /// Limiting speed estimate (rad/s): n dm = 700 000 mm/min for an oil-lubricated tapered
    /// roller bearing, 3 500 000 for a high-speed (jet-oil) cylindrical roller bearing.
    pub n_lim: f64,
    /// The preset's operating speed (rad/s).
    pub speed: f64,
    /// Per unit of speed squared: the axial force below which the rollers' centrifugal force
    /// pushes the cone out through the flange, Fa_min = k w^2 with
    /// k = Z m r_c (w_c/w)^2 tan(a_o) (a roller seated on cup and flange: Q_f,x = Q_o sin a_o,
    /// Q_o ~ F_c).
    pub seating_k: f64,
}

impl Preset {
    pub fn new(bearing: Bearing) -> Preset {
        let dpw = bearing.pitch_diameter * 1e3;
        let a = bearing.cup_angle;
        let z = bearing.roller_count as f64;
        let c0 = trb::rating::BearingRating::new(&bearing, bearing.slices).c_0r;
        let fa0 = if bearing.kind == Kind::Tapered { c0 * a.tan() / 0.22 } else { 0.0 };
        let ndm = if bearing.kind == Kind::Tapered { 700_000.0 } else { 3_500_000.0 };
        let n_lim = ndm / dpw * std::f64::consts::PI / 30.0;
        let speed = bearing.speed;
        let g = trb::geometry::Geometry::new(&bearing, &trb::geometry::RollerProfile::of_bearing(&bearing));
        let (ri, ro) = g.pitch_contact_radii();
        let cage_ratio = (1.0 - bearing.cage_slip_rate) * ri / (ri + ro);
        let rc = g.center[1] + g.cm_offset * g.axis[1];
        let seating_k = if bearing.kind == Kind::Tapered {
            z * g.roller_mass * rc * cage_ratio * cage_ratio * a.tan()
        } else {
            0.0
        };
        Preset {
            bearing,
            c0,
            fa0,
            n_lim,
            speed,
            seating_k,
        }
    }

    pub fn name(&self) -> &str {
        &self.bearing.name
    }

    pub fn tapered(&self) -> bool {
        self.bearing.kind == Kind::Tapered
    }

    /// Axial force that seats the bearing under radial load `fr` with a load zone a little
    /// over half the circumference (Fa = 1.5 Fr tan a); for a cylindrical bearing 0.
    pub fn seating_fx(&self, fr: f64) -> f64 {
        1.5 * fr * self.bearing.cup_angle.tan()
    }

    /// Estimated smallest axial force that keeps a tapered bearing seated at `speed`.
    pub fn seating_fx_min(&self, speed: f64) -> f64 {
        self.seating_k * speed * speed
    }

    /// A light axial preload by displacement: 2e-4 of the roller diameter.
    pub fn preload_displacement(&self) -> f64 {
        2e-4 * self.bearing.roller_mean_diameter
    }
}

/// The presets the matrix runs: all but TRB130x230-W25, [W25] Table 1 as printed, which
/// differs from the default TRB130x230 only in its angles and contact law (the matrix's loads
/// and speeds would repeat the default's cases).
pub fn presets() -> Vec<Preset> {
    PRESETS
        .iter()
        .filter(|(name, _)| *name != "TRB130x230-W25")
        .map(|(name, _)| Preset::new(Bearing::preset(name).expect("presets are valid")))
        .collect()
}

// ---------------------------------------------------------------------------------------
// Cases
// ---------------------------------------------------------------------------------------

pub use trb::variables::Value;

/// An input signal: a constant or a table interpolated linearly, held outside.
#[derive(Debug, Clone, PartialEq)]
pub enum Signal {
    Const(f64),
    Table(Vec<(f64, f64)>),
}

impl Signal {
    pub fn at(&self, t: f64) -> f64 {
        match self {
            Signal::Const(v) => *v,
            Signal::Table(points) => {
                let (first, last) = (points[0], points[points.len() - 1]);
                if t <= first.0 {
                    return first.1;
                }
                if t >= last.0 {
                    return last.1;
                }
                let i = points.partition_point(|p| p.0 <= t);
                let ((t0, v0), (t1, v1)) = (points[i - 1], points[i]);
                v0 + (v1 - v0) * ((t - t0) / (t1 - t0))
            }
        }
    }
}

/// What outcome of a case is acceptable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Expect {
    Pass,
    PassOrRefuse,
    Refuse,
}

impl Expect {
    pub fn label(self) -> &'static str {
        match self {
            Expect::Pass => "pass",
            Expect::PassOrRefuse => "pass or refuse",
            Expect::Refuse => "refuse",
        }
    }
}

#[derive(Debug, Clone)]
pub struct Case {
    /// `preset/group/what`, unique.
    pub id: String,
    /// Index into [`presets`].
    pub preset: usize,
    pub fidelity: i32,
    pub group: &'static str,
    pub what: String,
    /// Parameters by FMU name (set before initialization, in this order).
    pub params: Vec<(&'static str, Value)>,
    /// Inputs by FMU name; inputs not named keep the preset's operating point.
    pub inputs: Vec<(&'static str, Signal)>,
    /// Communication step (s) and number of steps.
    pub h: f64,
    pub steps: usize,
    pub expect: Expect,
    /// A refusal's message must contain this text, or one of its `|`-separated parts (it
    /// says why); `None`: any message that passes [`clarity`].
    pub why: Option<&'static str>,
    /// Also run through the FMU's C ABI (and compare bitwise with `Simulation`).
    pub fmu: bool,
    /// Time-averaged balances over the second half of the run (the inputs must be constant
    /// there), to this relative tolerance: mean `frictionTorque × speed` = mean `powerLoss` +
    /// the change of the stored kinetic energy over the half divided by its duration (what
    /// drives the cone is dissipated or stored; the elastic energy is bounded and small) and,
    /// in force preload of a tapered bearing, mean `reaction.Fx` = `Fx`.
    pub average: Option<f64>,
}

/// Simulated durations of the time-dependent cases, per fidelity.
#[derive(Debug, Clone, Copy)]
pub struct Durations {
    /// Long runs (s).
    pub long: f64,
    /// Run-ups, stops, reversals (s).
    pub transient: f64,
    /// Steps of the constant-input cases.
    pub short_steps: usize,
}

impl Durations {
    pub fn of(fidelity: i32, quick: bool) -> Durations {
        match (fidelity, quick) {
            (0, false) => Durations {
                long: 10.0,
                transient: 1.0,
                short_steps: 5,
            },
            (0, true) => Durations {
                long: 1.0,
                transient: 0.2,
                short_steps: 3,
            },
            // The dynamic model costs ~0.05 s (operating point, 0.1 C0) to ~40 s (load
            // steps, near the limiting speed) of wall time per simulated ms with Rosenbrock-W
            // at 1e-4 on this machine: one 1 s long run per preset at its operating speed, 3 ms
            // transients, 2-step constant cases (docs/robustness.md, section 6).
            (1, false) => Durations {
                long: 1.0,
                transient: 0.003,
                short_steps: 2,
            },
            (1, true) => Durations {
                long: 0.01,
                transient: 0.002,
                short_steps: 1,
            },
            // The quasi-dynamic model costs 0.3 to 2 s of wall time per simulated s at 1 ms
            // steps (docs/performance.md, "The quasi-dynamic model (fidelity 2)"): a 1 s long
            // run, 50 ms transients (rather than fidelity 1's 3 ms: long enough for the cage
            // and the rollers' spin to follow a change), 3-step constant cases.
            (_, false) => Durations {
                long: 1.0,
                transient: 0.05,
                short_steps: 3,
            },
            (_, true) => Durations {
                long: 0.05,
                transient: 0.01,
                short_steps: 2,
            },
        }
    }
}

/// Presets whose dynamic model costs seconds of wall time per simulated ms (CRB-TRILOBE at
/// 40 000 rpm: 4.5 g rollers, 1.5-4 s per ms at 0.1 C0 with a 0.02 deg deflection,
/// Rosenbrock-W at 1e-4, the cage whirling on its land) and the fraction of the fidelity-1
/// step-size and long runs they run: the 1 s long run becomes 20 ms and the 0.1 s
/// communication step is left out (both run on the other presets).
pub const DYNAMIC_TIME_SCALE: &[(&str, f64)] = &[("CRB-TRILOBE", 0.02)];

/// Wall-clock bound of one doStep (s) of a bearing with `z` rollers of `slices` slices. The
/// work budget (`workBudget`) ends a 1 ms step of the dynamic model after 200 000 right-hand
/// sides, whose cost goes with the slices in contact: about 14 s for 17 rollers of 20 slices
/// on one core of the reference machine. The bound leaves a factor of 4 for a slower or busier
/// machine (the matrix runs cases on every core). A step over it is a failure: the budget did
/// not hold.
pub fn step_wall_bound(z: usize, slices: usize) -> f64 {
    60.0 * ((z * slices) as f64 / (17.0 * 20.0)).max(1.0)
}

/// Builds the cases of one preset.
struct Builder<'a> {
    index: usize,
    p: &'a Preset,
    fidelity: i32,
    d: Durations,
    out: Vec<Case>,
}

impl Builder<'_> {
    #[allow(clippy::too_many_arguments)]
    fn push(
        &mut self,
        group: &'static str,
        what: String,
        params: Vec<(&'static str, Value)>,
        inputs: Vec<(&'static str, Signal)>,
        h: f64,
        steps: usize,
        expect: Expect,
    ) {
        let mut all = Vec::new();
        if self.fidelity != 0 {
            all.push(("fidelity", Value::Integer(self.fidelity)));
        }
        if self.fidelity == 1 {
            // What a user runs at fidelity 1 unless the case says otherwise: the
            // Rosenbrock-W integrator (2) at tolerance 1e-4 (the explicit default, 0, is
            // stability-limited to ~10 us steps under load; see FIDELITY_1). Fidelity 2
            // integrates by backward Euler at the communication step and runs its defaults.
            if !params.iter().any(|(n, _)| *n == "integrator") {
                all.push(("integrator", Value::Integer(2)));
            }
            if !params.iter().any(|(n, _)| *n == "tolerance") {
                all.push(("tolerance", Value::Real(1e-4)));
            }
        }
        all.extend(params);
        self.out.push(Case {
            id: format!("{}/{group}/{what}", self.p.name()),
            preset: self.index,
            fidelity: self.fidelity,
            group,
            what,
            params: all,
            inputs,
            h,
            steps: steps.max(1),
            expect,
            why: None,
            fmu: false,
            average: None,
        });
    }

    /// Change the last case's expectation; a refusal's message must contain `why`.
    fn last_expect(&mut self, expect: Expect, why: &'static str) {
        let c = self.out.last_mut().expect("a case");
        c.expect = expect;
        c.why = Some(why);
    }

    /// Constant inputs for a few steps of 1 ms.
    fn constant(
        &mut self,
        group: &'static str,
        what: String,
        params: Vec<(&'static str, Value)>,
        inputs: Vec<(&'static str, f64)>,
        expect: Expect,
    ) {
        let inputs = inputs.into_iter().map(|(n, v)| (n, Signal::Const(v))).collect();
        let steps = self.d.short_steps;
        self.push(group, what, params, inputs, 1e-3, steps, expect);
    }

    /// The fraction of the step-size and long runs' simulated time that this preset runs at
    /// this fidelity: 1 but for presets whose dynamic model costs seconds per simulated ms
    /// ([`DYNAMIC_TIME_SCALE`]).
    fn time_scale(&self) -> f64 {
        if self.fidelity == 0 {
            return 1.0;
        }
        DYNAMIC_TIME_SCALE
            .iter()
            .find(|(n, _)| *n == self.p.name())
            .map_or(1.0, |(_, f)| *f)
    }

    /// Check the time-averaged balances of the last case (fidelity 1).
    fn last_average(&mut self, tol: f64) {
        self.out.last_mut().expect("a case").average = Some(tol);
    }

    /// A moderate combined load: Fr = f C0 at 30 deg from y towards z, Fx seating it.
    fn combined(&self, f: f64) -> Vec<(&'static str, f64)> {
        let fr = f * self.p.c0;
        let a = 30f64.to_radians();
        vec![
            ("Fy", fr * a.cos()),
            ("Fz", fr * a.sin()),
            ("Fx", if self.p.tapered() { self.p.seating_fx(fr) } else { 0.1 * fr }),
            ("speed", self.p.speed),
        ]
    }
}

fn fmt_f(f: f64) -> String {
    let s = format!("{f}");
    if s.len() > 8 {
        format!("{f:.3e}")
    } else {
        s
    }
}

/// Linear ramp table from `v0` at `t0` to `v1` at `t1`.
fn ramp(t0: f64, v0: f64, t1: f64, v1: f64) -> Signal {
    Signal::Table(vec![(t0, v0), (t1, v1)])
}

/// A step from `v0` to `v1` right after `t` (within one step `h`).
fn jump(t: f64, h: f64, v0: f64, v1: f64) -> Signal {
    Signal::Table(vec![(t, v0), (t + 0.5 * h, v1)])
}

/// Sampled `f(t)` on `[0, t_end]` with `n` points.
fn sampled(t_end: f64, n: usize, f: impl Fn(f64) -> f64) -> Signal {
    Signal::Table((0..=n).map(|i| t_end * i as f64 / n as f64).map(|t| (t, f(t))).collect())
}

fn steps_for(duration: f64, h: f64) -> usize {
    (duration / h).round().max(1.0) as usize
}

/// Every case of `fidelity` for every preset. `quick` shortens the time-dependent cases
/// (the same cases, shorter runs).
pub fn cases(fidelity: i32, quick: bool) -> Vec<Case> {
    let presets = presets();
    let mut all = Vec::new();
    for (index, p) in presets.iter().enumerate() {
        let mut b = Builder {
            index,
            p,
            fidelity,
            d: Durations::of(fidelity, quick),
            out: Vec::new(),
        };
        preset_cases(&mut b);
        all.extend(b.out);
    }
    // The representative subset that also runs through the FMU: the first case of every
    // group of every preset, and every long run.
    let mut seen = std::collections::HashSet::new();
    // At fidelity 1 the long runs cost minutes: only the smallest preset's go through the FMU.
    for c in &mut all {
        let long = c.group == "long" && (c.fidelity != 1 || c.id.starts_with("32008/"));
        if (seen.insert((c.preset, c.group)) && (c.group != "long" || long)) || long {
            c.fmu = true;
        }
    }
    all
}

/// Random input jumps over the whole load range: radial loads from 0.01 to 100 times C_r
/// (log-uniform, any direction in the radial plane), speeds from 0.1 to 1.5 n_lim, a new draw
/// at every communication point after the first (the preset's operating speed at 0.1 C0),
/// seeded per preset and case. The axial force of a tapered bearing seats it (one to three
/// times the seating force) in cases 0 and 1 and is drawn like the radial load in case 2.
/// Legal jumps are to be taken, the rest refused with a clear message, every step within
/// [`step_wall_bound`].
fn jump_cases(b: &mut Builder) {
    let p = b.p.clone();
    let c_r = trb::rating::BearingRating::new(&p.bearing, p.bearing.slices).c_r;
    let start = b.combined(0.1);
    let at_start = |name: &str| start.iter().find(|(n, _)| *n == name).map_or(0.0, |(_, v)| *v);
    let (h, steps) = (1e-3, 4);
    for case in 0..3u64 {
        let mut state = 0x9e37_79b9_7f4a_7c15u64 ^ ((b.index as u64) << 32 | case);
        let mut uniform = move || {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut load = move || c_r * 10f64.powf(-2.0 + 4.0 * uniform());
        let mut rows = vec![[at_start("Fx"), at_start("Fy"), at_start("Fz"), at_start("speed")]];
        for _ in 0..steps {
            let (fr, angle) = (load(), std::f64::consts::TAU * load() / c_r);
            let fx = match (p.tapered(), case) {
                (false, _) => 0.0,
                (true, 2) => load(),
                (true, _) => p.seating_fx(fr) * (1.0 + 2.0 * (load() / c_r).fract()),
            };
            let speed = p.n_lim * (0.1 + 1.4 * (load() / c_r).fract());
            rows.push([fx, fr * angle.cos(), fr * angle.sin(), speed]);
        }
        let column = |i: usize| Signal::Table(rows.iter().enumerate().map(|(k, r)| (k as f64 * h, r[i])).collect());
        b.push(
            "jumps",
            format!("random jumps {case}, 0.01 to 100 C_r"),
            vec![],
            vec![("Fx", column(0)), ("Fy", column(1)), ("Fz", column(2)), ("speed", column(3))],
            h,
            steps,
            Expect::PassOrRefuse,
        );
    }
}

fn preset_cases(b: &mut Builder) {
    jump_cases(b);
    let p = b.p.clone();
    let tapered = p.tapered();
    let d = b.d;
    let dm = p.bearing.roller_mean_diameter;
    let deg = |x: f64| x.to_radians();

    // --- Loads from zero to beyond C0: axial, radial, radial with the cone held, combined.
    // A tapered bearing at speed needs a minimum axial force to stay seated (below it the
    // rollers' centrifugal force pushes the cone out through the flange): cases below 1.5
    // times the estimate may be refused, saying so.
    let unseated = |fx: f64, fr: f64| tapered && fx < 1.5 * p.seating_fx_min(p.speed) + fr * p.bearing.cup_angle.tan();
    for f in [0.0, 0.001, 0.01, 0.1, 0.3, 0.6, 1.0, 1.5, 3.0] {
        let within = if f > 1.0 { Expect::PassOrRefuse } else { Expect::Pass };
        let tag = format!("{}C0", fmt_f(f));
        // Pure axial.
        let fa = if tapered { f * p.fa0 } else { 0.1 * f * p.c0 };
        b.constant(
            "load-axial",
            tag.clone(),
            vec![],
            vec![("Fx", fa), ("Fy", 0.0), ("Fz", 0.0)],
            within,
        );
        if unseated(fa, 0.0) {
            b.last_expect(Expect::PassOrRefuse, "seated");
        }
        // Pure radial in force preload: a single TRB needs an axial force of about Fr tan a.
        b.constant(
            "load-radial",
            tag.clone(),
            vec![],
            vec![("Fx", 0.0), ("Fy", f * p.c0), ("Fz", 0.0)],
            within,
        );
        if tapered {
            b.last_expect(Expect::PassOrRefuse, if f == 0.0 { "seated" } else { "Fr tan" });
        }
        // Pure radial with the cone held axially (displacement preload); along z here.
        b.constant(
            "load-radial-held",
            tag.clone(),
            vec![("preload", Value::Integer(1))],
            vec![("axialDisplacement", p.preload_displacement()), ("Fy", 0.0), ("Fz", f * p.c0)],
            within,
        );
        // Combined: Fr at 30 deg between y and z, Fa = 1.5 Fr tan a.
        let inputs = b.combined(f);
        let fx = inputs.iter().find(|(n, _)| *n == "Fx").map_or(0.0, |(_, v)| *v);
        b.constant("load-combined", tag, vec![], inputs, within);
        if unseated(fx, f * p.c0) {
            b.last_expect(Expect::PassOrRefuse, "seated|Fr tan");
        }
    }

    // --- Speeds from reverse through zero to above the limiting speed.
    for f in [-1.5, -1.0, -0.3, -1e-6, 0.0, 1e-6, 0.3, 1.0, 1.5, 3.0] {
        let mut inputs = b.combined(0.1);
        inputs.retain(|(n, _)| *n != "speed");
        inputs.push(("speed", f * p.n_lim));
        let e = if f64::abs(f) > 1.0 { Expect::PassOrRefuse } else { Expect::Pass };
        b.constant("speed", format!("{}n_lim", fmt_f(f)), vec![], inputs, e);
    }

    // --- Time tables: run-up, stop, reversal, load and speed steps, rotating load.
    let h = 1e-3;
    let t = d.transient;
    let n = steps_for(t, h);
    let load = |b: &Builder, f: f64| -> Vec<(&'static str, Signal)> {
        b.combined(f)
            .into_iter()
            .filter(|(n, _)| *n != "speed")
            .map(|(n, v)| (n, Signal::Const(v)))
            .collect()
    };
    let with = |mut v: Vec<(&'static str, Signal)>, extra: Vec<(&'static str, Signal)>| {
        v.retain(|(n, _)| !extra.iter().any(|(m, _)| m == n));
        v.extend(extra);
        v
    };
    let base = load(b, 0.1);
    b.push(
        "transient",
        "run-up from rest to n_lim".into(),
        vec![],
        with(base.clone(), vec![("speed", ramp(0.0, 0.0, t, p.n_lim))]),
        h,
        n,
        Expect::Pass,
    );
    b.push(
        "transient",
        "run-up from rest to 2 n_lim".into(),
        vec![],
        with(base.clone(), vec![("speed", ramp(0.0, 0.0, t, 2.0 * p.n_lim))]),
        h,
        n,
        Expect::PassOrRefuse,
    );
    b.push(
        "transient",
        "sudden stop from n_lim".into(),
        vec![],
        with(base.clone(), vec![("speed", jump(0.5 * t, h, p.n_lim, 0.0))]),
        h,
        n,
        Expect::Pass,
    );
    b.push(
        "transient",
        "reversal +n_lim to -n_lim".into(),
        vec![],
        with(base.clone(), vec![("speed", ramp(0.0, p.n_lim, t, -p.n_lim))]),
        h,
        n,
        Expect::Pass,
    );
    b.push(
        "transient",
        "speed step 0.1 to 1 n_lim".into(),
        vec![],
        with(base.clone(), vec![("speed", jump(0.5 * t, h, 0.1 * p.n_lim, p.n_lim))]),
        h,
        n,
        Expect::Pass,
    );
    let (lo, hi) = (load(b, 0.05), load(b, 0.5));
    let stepped = |up: bool| -> Vec<(&'static str, Signal)> {
        lo.iter()
            .zip(&hi)
            .map(|((name, l), (_, u))| {
                let (l, u) = match (l, u) {
                    (Signal::Const(l), Signal::Const(u)) => (*l, *u),
                    _ => unreachable!(),
                };
                let (a, c) = if up { (l, u) } else { (u, l) };
                (*name, jump(0.5 * t, h, a, c))
            })
            .collect()
    };
    b.push(
        "transient",
        "load step 0.05 to 0.5 C0".into(),
        vec![],
        with(stepped(true), vec![("speed", Signal::Const(p.speed))]),
        h,
        n,
        Expect::Pass,
    );
    b.push(
        "transient",
        "load step 0.5 to 0.05 C0".into(),
        vec![],
        with(stepped(false), vec![("speed", Signal::Const(p.speed))]),
        h,
        n,
        Expect::Pass,
    );
    let fr_end = 1.5 * p.c0;
    b.push(
        "transient",
        "load ramp 0 to 1.5 C0".into(),
        vec![],
        vec![
            ("Fy", ramp(0.0, 0.0, t, fr_end)),
            (
                "Fx",
                ramp(
                    0.0,
                    if tapered { 0.0 } else { 0.0 },
                    t,
                    if tapered { p.seating_fx(fr_end) } else { 0.0 },
                ),
            ),
            ("Fz", Signal::Const(0.0)),
            ("speed", Signal::Const(p.speed)),
        ],
        h,
        n,
        Expect::PassOrRefuse,
    );
    b.push(
        "transient",
        "deflection ramp 0 to 0.3 deg".into(),
        vec![],
        with(
            base.clone(),
            vec![("xi", ramp(0.0, 0.0, t, deg(0.3))), ("speed", Signal::Const(p.speed))],
        ),
        h,
        n,
        Expect::PassOrRefuse,
    );
    b.push(
        "transient",
        "deflection step 0 to 0.05 deg".into(),
        vec![],
        with(
            base.clone(),
            vec![("zeta", jump(0.5 * t, h, 0.0, deg(0.05))), ("speed", Signal::Const(p.speed))],
        ),
        h,
        n,
        Expect::Pass,
    );
    if tapered {
        // Losing the axial force under radial load: the bearing unseats, clearly refused.
        let fr = 0.1 * p.c0;
        b.push(
            "transient",
            "axial force lost under radial load".into(),
            vec![],
            vec![
                ("Fy", Signal::Const(fr)),
                ("Fx", jump(0.5 * t, h, p.seating_fx(fr), 0.0)),
                ("speed", Signal::Const(p.speed)),
            ],
            h,
            n,
            Expect::PassOrRefuse,
        );
    }
    {
        // A rotating radial load (unbalance) at 5 revolutions over the run.
        let fr = 0.1 * p.c0;
        let w = 5.0 * std::f64::consts::TAU / t;
        b.push(
            "transient",
            "rotating radial load".into(),
            vec![],
            vec![
                ("Fy", sampled(t, 200, move |s| fr * (w * s).cos())),
                ("Fz", sampled(t, 200, move |s| fr * (w * s).sin())),
                ("Fx", Signal::Const(if tapered { p.seating_fx(fr) } else { 0.0 })),
                ("speed", Signal::Const(p.speed)),
            ],
            h,
            n,
            Expect::Pass,
        );
    }

    // --- Shaft deflection up to 0.3 deg (0.5 deg is the model's documented limit).
    for (axis, angle) in [
        ("xi", 0.01),
        ("xi", 0.05),
        ("xi", 0.1),
        ("xi", 0.2),
        ("xi", 0.3),
        ("zeta", -0.05),
        ("zeta", -0.3),
        ("xi+zeta", 0.2),
    ] {
        let mut inputs = b.combined(0.1);
        if axis == "xi+zeta" {
            inputs.push(("xi", deg(angle)));
            inputs.push(("zeta", deg(angle)));
        } else {
            inputs.push((if axis == "xi" { "xi" } else { "zeta" }, deg(angle)));
        }
        let e = if angle.abs() <= 0.05 { Expect::Pass } else { Expect::PassOrRefuse };
        b.constant("deflection", format!("{axis} {angle} deg"), vec![], inputs, e);
    }

    // --- Communication steps from 1e-6 s to 0.1 s (10 steps each, moving load zone).
    for h in [1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.1] {
        if h > 0.05 && b.time_scale() < 1.0 {
            continue;
        }
        let mut inputs: Vec<(&'static str, Signal)> = b.combined(0.1).into_iter().map(|(n, v)| (n, Signal::Const(v))).collect();
        inputs.push(("xi", Signal::Const(deg(0.02))));
        // At fidelity 1 the long steps run 2 (0.1 s) or 3 (0.01 s) steps: minutes of wall time.
        let steps = match b.fidelity {
            1 if h >= 0.1 => 2,
            1 if h >= 0.01 => ((3.0 * b.time_scale()).round() as usize).max(1),
            _ => 10,
        };
        b.push("step-size", format!("h = {h:e} s"), vec![], inputs, h, steps, Expect::Pass);
    }

    // --- Very few and very many slices.
    for s in [1, 2, 3, 5, 50, 100, 200] {
        let mut inputs = b.combined(0.1);
        inputs.push(("xi", deg(0.02)));
        b.constant(
            "slices",
            format!("{s} slices"),
            vec![("slices", Value::Integer(s))],
            inputs,
            Expect::Pass,
        );
        if s == 1 {
            // One slice cannot carry a roller's tilt moment: refusing the value is fine.
            b.last_expect(Expect::PassOrRefuse, "slices");
        }
    }

    // --- Long runs: varying load, speed and deflection; and a constant case at 1 ms.
    {
        let t = d.long * b.time_scale();
        let fr = 0.2 * p.c0;
        let n_op = p.speed;
        let inputs = vec![
            ("Fy", sampled(t, 400, move |s| fr * (0.6 + 0.4 * (1.3 * s).sin()))),
            ("Fz", sampled(t, 400, move |s| 0.3 * fr * (0.7 * s).cos())),
            ("Fx", Signal::Const(if tapered { p.seating_fx(1.1 * fr) } else { 0.0 })),
            ("speed", sampled(t, 400, move |s| n_op * (0.5 + 0.5 * (0.9 * s).sin()))),
            ("xi", sampled(t, 400, move |s| deg(0.02) * (2.1 * s).sin())),
        ];
        b.push(
            "long",
            format!("{t} s, h = 10 ms, varying"),
            vec![],
            inputs,
            1e-2,
            steps_for(t, 1e-2),
            Expect::Pass,
        );
        let inputs = b.combined(0.1).into_iter().map(|(n, v)| (n, Signal::Const(v))).collect();
        // at fidelity 1: 50 ms (1 s at 1 ms steps restarts the integrator 1000 times)
        let t = if b.fidelity == 1 { 0.05 * t } else { t };
        b.push(
            "long",
            format!("{t} s, h = 1 ms, constant"),
            vec![],
            inputs,
            1e-3,
            steps_for(t, 1e-3),
            Expect::Pass,
        );
    }

    // --- Unloaded rollers: nothing or almost nothing carries load.
    let zero = vec![("Fx", 0.0), ("Fy", 0.0), ("Fz", 0.0)];
    b.constant(
        "unloaded",
        "no load at standstill".into(),
        vec![],
        with_speed(&zero, 0.0),
        Expect::Pass,
    );
    b.constant(
        "unloaded",
        "1 N axial at standstill".into(),
        vec![],
        with_speed(&[("Fx", 1.0), ("Fy", 0.0), ("Fz", 0.0)], 0.0),
        Expect::Pass,
    );
    if tapered {
        let fr = 0.1 * p.c0;
        let tan_a = p.bearing.cup_angle.tan();
        b.constant(
            "unloaded",
            "small load zone (Fa = 1.1 Fr tan a + 2 Fa_min)".into(),
            vec![],
            with_speed(
                &[("Fx", 1.1 * fr * tan_a + 2.0 * p.seating_fx_min(p.speed)), ("Fy", fr), ("Fz", 0.0)],
                p.speed,
            ),
            Expect::Pass,
        );
        // Below Fr tan a a single TRB has no equilibrium: refused, saying so.
        b.constant(
            "unloaded",
            "too little axial force (Fa = 0.6 Fr tan a)".into(),
            vec![],
            with_speed(&[("Fx", 0.6 * fr * tan_a), ("Fy", fr), ("Fz", 0.0)], p.speed),
            Expect::PassOrRefuse,
        );
        b.last_expect(Expect::PassOrRefuse, "Fr tan");
    }
    b.constant(
        "unloaded",
        "cone pulled back (displacement preload < 0), at speed".into(),
        vec![("preload", Value::Integer(1))],
        with_speed(&[("axialDisplacement", -0.01 * dm), ("Fy", 0.0), ("Fz", 0.0)], p.speed),
        Expect::Pass,
    );
    b.constant(
        "unloaded",
        "clearance 1 % D, small radial load".into(),
        vec![("clearance", Value::Real(0.01 * dm))],
        with_speed(
            &[("Fx", if tapered { 0.01 * p.fa0 } else { 0.0 }), ("Fy", 0.001 * p.c0), ("Fz", 0.0)],
            p.speed,
        ),
        Expect::Pass,
    );
    b.constant(
        "unloaded",
        "no load, no centrifugal force, at speed".into(),
        vec![("centrifugal", Value::Boolean(false)), ("gyroscopic", Value::Boolean(false))],
        with_speed(&zero, p.speed),
        if tapered { Expect::PassOrRefuse } else { Expect::Pass },
    );

    // --- Dynamic and quasi-dynamic models only: energy balance, rollers and cage accelerating
    // from rest, skidding at light load, cage impacts, unloaded rollers, each integrator.
    if b.fidelity != 0 {
        dynamic_cases(b);
    }

    // --- Parameters at the ends of their ranges, with a moderate combined load.
    let mut params: Vec<(String, Vec<(&'static str, Value)>, Expect)> = vec![
        (
            "dry, mu = 0".into(),
            vec![("lubrication", Value::Integer(1)), ("mu", Value::Real(0.0))],
            Expect::Pass,
        ),
        (
            "dry, mu = 2".into(),
            vec![("lubrication", Value::Integer(1)), ("mu", Value::Real(2.0))],
            Expect::Pass,
        ),
        ("EHL".into(), vec![("lubrication", Value::Integer(0))], Expect::Pass),
        (
            "oil.eta0 = 1e-4 Pa s".into(),
            vec![("lubrication", Value::Integer(0)), ("oil.eta0", Value::Real(1e-4))],
            Expect::Pass,
        ),
        (
            "oil.eta0 = 100 Pa s".into(),
            vec![("lubrication", Value::Integer(0)), ("oil.eta0", Value::Real(100.0))],
            Expect::Pass,
        ),
        (
            "oil.alpha = 0".into(),
            vec![("lubrication", Value::Integer(0)), ("oil.alpha", Value::Real(0.0))],
            Expect::Pass,
        ),
        (
            "oil.alpha = 1e-7".into(),
            vec![("lubrication", Value::Integer(0)), ("oil.alpha", Value::Real(1e-7))],
            Expect::Pass,
        ),
        (
            "roughness = 0".into(),
            vec![("lubrication", Value::Integer(0)), ("roughness", Value::Real(0.0))],
            Expect::Pass,
        ),
        (
            "roughness = 100 um".into(),
            vec![("lubrication", Value::Integer(0)), ("roughness", Value::Real(1e-4))],
            Expect::Pass,
        ),
        ("cageSlipRate = 0".into(), vec![("cageSlipRate", Value::Real(0.0))], Expect::Pass),
        ("cageSlipRate = 1".into(), vec![("cageSlipRate", Value::Real(1.0))], Expect::Pass),
        ("tolerance = 1e-14".into(), vec![("tolerance", Value::Real(1e-14))], Expect::Pass),
        ("tolerance = 0.1".into(), vec![("tolerance", Value::Real(0.1))], Expect::Pass),
        (
            "clearance = +5 % D".into(),
            vec![("clearance", Value::Real(0.05 * dm))],
            Expect::Pass,
        ),
        (
            "clearance = -5 % D".into(),
            vec![("clearance", Value::Real(-0.05 * dm))],
            Expect::PassOrRefuse,
        ),
        (
            "crownDrop = 5 % D".into(),
            vec![("roller.crownDrop", Value::Real(0.05 * dm))],
            Expect::Pass,
        ),
        (
            "roller[1].dD = +1 % D".into(),
            vec![("roller[1].dD", Value::Real(0.01 * dm))],
            Expect::PassOrRefuse,
        ),
        (
            "roller[2].dD = -1 % D".into(),
            vec![("roller[2].dD", Value::Real(-0.01 * dm))],
            Expect::Pass,
        ),
        (
            "64 lobes, waveform 5 % D".into(),
            vec![("outer.lobes", Value::Integer(64)), ("outer.waveform", Value::Real(0.05 * dm))],
            Expect::PassOrRefuse,
        ),
        (
            "no centrifugal, no gyroscopic".into(),
            vec![("centrifugal", Value::Boolean(false)), ("gyroscopic", Value::Boolean(false))],
            Expect::Pass,
        ),
        (
            "cage.angle0 = 1e6 rad".into(),
            vec![("cage.angle0", Value::Real(1e6))],
            Expect::Pass,
        ),
    ];
    if !tapered {
        params.push(("no lobes".into(), vec![("outer.lobes", Value::Integer(0))], Expect::Pass));
    }
    for (what, params, expect) in params {
        let mut inputs = b.combined(0.1);
        inputs.push(("xi", deg(0.01)));
        let thick_oil = what.starts_with("oil.eta0 = 100");
        b.constant("parameters", what, params, inputs, expect);
        if thick_oil && b.fidelity != 0 {
            // F16: the dynamic model's isothermal films (fidelities 1 and 2 share them) would
            // heat by thousands of kelvin at the cone's surface speed of the fast presets
            b.last_expect(Expect::PassOrRefuse, "isothermal oil films");
        }
    }

    // --- Outside the model's range: must be refused, saying why.
    let mut inputs = b.combined(0.1);
    inputs.push(("xi", deg(0.6)));
    b.constant("out-of-range", "xi = 0.6 deg".into(), vec![], inputs, Expect::Refuse);
    b.last_expect(Expect::Refuse, "input xi");
    let mut inputs = b.combined(0.1);
    inputs.push(("zeta", deg(-1.0)));
    b.constant("out-of-range", "zeta = -1 deg".into(), vec![], inputs, Expect::Refuse);
    b.last_expect(Expect::Refuse, "input zeta");
    b.constant(
        "out-of-range",
        "axialDisplacement = 10 % D".into(),
        vec![("preload", Value::Integer(1))],
        vec![("axialDisplacement", 0.1 * dm)],
        Expect::Refuse,
    );
    b.last_expect(Expect::Refuse, "input axialDisplacement");
    b.constant(
        "out-of-range",
        "Fy = Fx = 1e9 N".into(),
        vec![],
        vec![("Fy", 1e9), ("Fx", 1e9)],
        Expect::Refuse,
    );
    b.last_expect(Expect::Refuse, "beyond the model's range");
    b.constant("out-of-range", "Fy = 1e300 N".into(), vec![], vec![("Fy", 1e300)], Expect::Refuse);
    b.last_expect(Expect::Refuse, "input Fy");
    b.constant(
        "out-of-range",
        "speed = 1e9 rad/s".into(),
        vec![],
        vec![("speed", 1e9)],
        Expect::Refuse,
    );
    b.last_expect(Expect::Refuse, "input speed");
    // A cylindrical bearing carries no axial force: Fx is not used there.
    b.constant("out-of-range", "Fx = -1e9 N".into(), vec![], vec![("Fx", -1e9)], Expect::Refuse);
    if tapered {
        b.last_expect(Expect::Refuse, "seated|Fr tan");
    } else {
        b.last_expect(Expect::Pass, "");
    }
    b.constant("out-of-range", "Fx = -1e12 N".into(), vec![], vec![("Fx", -1e12)], Expect::Refuse);
    b.last_expect(Expect::Refuse, "input Fx");
    b.constant(
        "out-of-range",
        "tolerance = 0.5".into(),
        vec![("tolerance", Value::Real(0.5))],
        vec![],
        Expect::Refuse,
    );
    b.last_expect(Expect::Refuse, "parameter tolerance");
}

/// Cases of the dynamic and quasi-dynamic models (fidelities 1 and 2), 1 ms steps over the
/// transient duration.
fn dynamic_cases(b: &mut Builder) {
    let p = b.p.clone();
    let tapered = p.tapered();
    let h = 1e-3;
    let t = b.d.transient;
    let n = steps_for(t, h);
    let consts =
        |v: Vec<(&'static str, f64)>| -> Vec<(&'static str, Signal)> { v.into_iter().map(|(n, v)| (n, Signal::Const(v))).collect() };
    let at_speed = |mut v: Vec<(&'static str, f64)>, speed: f64| {
        v.retain(|(n, _)| *n != "speed");
        v.push(("speed", speed));
        v
    };
    // The averaged balances run 40 ms in 0.2 ms steps (the second half averaged: the
    // outputs are instantaneous values, and pocket impacts make powerLoss spiky, so 1 ms
    // samples leave ~3 % of sampling noise); the quick list runs them short (unchecked).
    // The quasi-dynamic model has no impacts, and its outputs at 1 ms are what it
    // integrates: 100 ms of 1 ms steps, checked to 1 % in both lists.
    let quasi_dynamic = b.fidelity == 2;
    let energy = if quasi_dynamic { 0.01 } else { 0.03 };
    let (h_avg, n_avg) = match (quasi_dynamic, b.d.long >= 1.0) {
        (true, _) => (h, 100),
        (false, true) => (h / 5.0, 200),
        (false, false) => (h, n),
    };
    b.push(
        "dynamic",
        "energy balance, 0.1 C0 combined, constant".into(),
        vec![],
        consts(b.combined(0.1)),
        h_avg,
        n_avg,
        Expect::Pass,
    );
    b.last_average(energy);
    b.push(
        "dynamic",
        "energy balance, 0.3 C0 combined, xi 0.05 deg".into(),
        vec![],
        consts({
            let mut v = b.combined(0.3);
            v.push(("xi", 0.05f64.to_radians()));
            v
        }),
        h_avg,
        n_avg,
        Expect::Pass,
    );
    b.last_average(energy);
    b.push(
        "dynamic",
        "rollers and cage start at rest (startFromRest), cone at the operating speed".into(),
        vec![("startFromRest", Value::Boolean(true))],
        consts(b.combined(0.1)),
        h,
        n,
        Expect::Pass,
    );
    // (the quasi-dynamic balance does not converge near the rollers' standstill, where the
    // regularised friction is stiffest: refused, saying so; docs/model.md)
    let from_rest = |b: &mut Builder| {
        if b.fidelity == 2 {
            b.last_expect(Expect::PassOrRefuse, "did not converge");
        }
    };
    from_rest(b);
    b.push(
        "dynamic",
        "startFromRest, cone ramped 0.01 to 1 n_lim".into(),
        vec![("startFromRest", Value::Boolean(true))],
        {
            let mut v = consts(b.combined(0.1));
            v.retain(|(n, _)| *n != "speed");
            v.push(("speed", ramp(0.0, 0.01 * p.n_lim, t, p.n_lim)));
            v
        },
        h,
        n,
        Expect::Pass,
    );
    from_rest(b);
    // Light load at the limiting speed: the rollers skid; the axial force keeps a tapered
    // bearing seated against the rollers' centrifugal force.
    let light = |b: &Builder, f: f64| {
        let mut v = b.combined(f);
        if tapered {
            for (name, x) in v.iter_mut() {
                if *name == "Fx" {
                    *x += 2.0 * p.seating_fx_min(p.n_lim);
                }
            }
        }
        at_speed(v, p.n_lim)
    };
    b.push(
        "dynamic",
        "light load 0.001 C0 at n_lim (skidding)".into(),
        vec![],
        consts(light(b, 0.001)),
        h,
        n,
        Expect::Pass,
    );
    b.push(
        "dynamic",
        "light load at n_lim, rollers from rest (skidding run-up)".into(),
        vec![("startFromRest", Value::Boolean(true))],
        consts(light(b, 0.001)),
        h,
        n,
        Expect::Pass,
    );
    from_rest(b);
    if quasi_dynamic {
        // the start at the seat with the epicyclic speeds (no steady balance first), which
        // settles over the first steps
        b.push(
            "dynamic",
            "startSteady = false, 0.1 C0 combined".into(),
            vec![("startSteady", Value::Boolean(false))],
            consts(b.combined(0.1)),
            h,
            n,
            Expect::Pass,
        );
    }
    // Cage impacts: a rotating light load drives the rollers through the load zone and the
    // cage against them; small and large pocket clearance.
    for (what, clearance) in [("pocket clearance 0.01 mm", 1e-5), ("pocket clearance 1 mm", 1e-3)] {
        let fr = 0.01 * p.c0;
        let w = 3.0 * std::f64::consts::TAU / t;
        b.push(
            "dynamic",
            format!("cage impacts: rotating 0.01 C0 at n_lim, {what}"),
            vec![("cage.pocketClearance", Value::Real(clearance))],
            vec![
                ("Fy", sampled(t, 100, move |s| fr * (w * s).cos())),
                ("Fz", sampled(t, 100, move |s| fr * (w * s).sin())),
                (
                    "Fx",
                    Signal::Const(if tapered {
                        p.seating_fx(fr) + 2.0 * p.seating_fx_min(p.n_lim)
                    } else {
                        0.0
                    }),
                ),
                ("speed", Signal::Const(p.n_lim)),
            ],
            h,
            n,
            Expect::Pass,
        );
    }
    // Unloaded rollers under a pure radial load: the cone held axially (tapered) or a
    // cylindrical bearing with clearance: half the rollers or more out of the load zone.
    let radial = |f: f64| vec![("Fy", f * p.c0), ("Fz", 0.0), ("speed", p.speed)];
    if tapered {
        let mut v = radial(0.05);
        v.push(("axialDisplacement", 0.0));
        b.push(
            "dynamic",
            "pure radial 0.05 C0, cone held at zero axial displacement (unloaded rollers)".into(),
            vec![("preload", Value::Integer(1))],
            consts(v),
            h_avg,
            n_avg,
            Expect::Pass,
        );
        // (F13: the rollers leaving and entering the load zone make the cage speed swing by
        // ~0.8 %; the kinetic energy that moves in and out, ~10 J, is in the balance.)
        b.last_average(energy);
        let mut v = radial(0.0);
        v.push(("axialDisplacement", -0.005 * p.bearing.roller_mean_diameter));
        b.push(
            "dynamic",
            "no load, cone pulled back 0.5 % D (every roller unloaded)".into(),
            vec![("preload", Value::Integer(1))],
            consts(v),
            h,
            n,
            Expect::Pass,
        );
    } else {
        b.push(
            "dynamic",
            "pure radial 0.05 C0 (unloaded rollers)".into(),
            vec![],
            consts(radial(0.05)),
            h_avg,
            n_avg,
            Expect::Pass,
        );
        b.last_average(energy);
        b.push(
            "dynamic",
            "pure radial 0.001 C0, clearance 1 % D (few loaded rollers)".into(),
            vec![("clearance", Value::Real(0.01 * p.bearing.roller_mean_diameter))],
            consts(radial(0.001)),
            h,
            n,
            Expect::Pass,
        );
    }
    // The other integrators and a kinematic cage, at 0.1 C0 (the explicit ones are
    // stability-limited under heavy load: that is the user's choice of integrator 2). The
    // quasi-dynamic model has no integrator to choose: only the kinematic cage.
    let short = 2;
    for (what, params) in [
        (
            "integrator 0 (Dormand-Prince, the default) at tolerance 1e-6",
            vec![("integrator", Value::Integer(0)), ("tolerance", Value::Real(1e-6))],
        ),
        (
            "integrator 1 (Milne-Hamming) at maxStep 1e-6",
            vec![("integrator", Value::Integer(1)), ("maxStep", Value::Real(1e-6))],
        ),
        (
            "kinematic cage (cage.dynamic = false)",
            vec![("cage.dynamic", Value::Boolean(false))],
        ),
    ] {
        if quasi_dynamic && what.starts_with("integrator") {
            continue;
        }
        b.push("dynamic", what.into(), params, consts(b.combined(0.1)), h, short, Expect::Pass);
        if what.starts_with("integrator 1") {
            // An explicit fixed step above the stability limit must be refused, saying so
            // (32018X: dry Coulomb contacts relax in ~70 ns).
            b.last_expect(Expect::PassOrRefuse, "unstable or too long");
        }
    }
}

fn with_speed(inputs: &[(&'static str, f64)], speed: f64) -> Vec<(&'static str, f64)> {
    let mut v = inputs.to_vec();
    v.push(("speed", speed));
    v
}

// ---------------------------------------------------------------------------------------
// Elements: Simulation and the FMU C ABI behind one interface
// ---------------------------------------------------------------------------------------

/// Why the element refused a call.
#[derive(Debug, Clone, PartialEq)]
pub struct Refusal {
    /// fmi2Discard (true) or fmi2Error.
    pub discard: bool,
    pub message: String,
}

/// What the runner needs from an element.
pub trait Element {
    fn set(&mut self, vr: u32, value: Value) -> Result<(), Refusal>;
    fn initialize(&mut self, t0: f64) -> Result<(), Refusal>;
    fn step(&mut self, t: f64, h: f64) -> Result<(), Refusal>;
    /// Read Real and Integer variables; `Err` with the values still written when the
    /// element refuses.
    fn read(&mut self, reals: &[u32], ints: &[u32], rv: &mut [f64], iv: &mut [i32]) -> Result<(), Refusal>;
    /// Kinetic energy stored in the element (J), where the element can tell (not through
    /// the FMU's variables).
    fn kinetic_energy(&self) -> Option<f64>;
}

impl Element for Simulation {
    fn set(&mut self, vr: u32, value: Value) -> Result<(), Refusal> {
        match value {
            Value::Real(x) => self.set_real(vr, x),
            Value::Integer(i) => self.set_integer(vr, i),
            Value::Boolean(b) => self.set_boolean(vr, b),
        }
        .map_err(|e| Refusal {
            discard: false,
            message: e.to_string(),
        })
    }

    fn initialize(&mut self, t0: f64) -> Result<(), Refusal> {
        Simulation::initialize(self, t0).map(|_| ()).map_err(model_refusal)
    }

    fn step(&mut self, t: f64, h: f64) -> Result<(), Refusal> {
        // As the FMU does: step from the element's own time to t + h.
        let now = self.time();
        self.do_step(now, (t + h) - now).map(|_| ()).map_err(model_refusal)
    }

    fn read(&mut self, reals: &[u32], ints: &[u32], rv: &mut [f64], iv: &mut [i32]) -> Result<(), Refusal> {
        // One solve (if inputs changed); after a failure the outputs of the last successful
        // solve, as the FMU returns them.
        let result = self.outputs().map(|_| ()).map_err(model_refusal);
        for (vr, v) in reals.iter().zip(rv.iter_mut()) {
            *v = self.last_real(*vr).unwrap_or(f64::NAN);
        }
        for (vr, v) in ints.iter().zip(iv.iter_mut()) {
            *v = self.last_integer(*vr).unwrap_or(i32::MIN);
        }
        result
    }

    fn kinetic_energy(&self) -> Option<f64> {
        Some(Simulation::kinetic_energy(self))
    }
}

fn model_refusal(e: trb::model::ModelError) -> Refusal {
    Refusal {
        discard: e.severity() == Severity::Discard,
        message: e.to_string(),
    }
}

/// The messages an FMU instance logged.
#[derive(Default)]
pub struct LogSink {
    records: Mutex<Vec<(c_int, String)>>,
}

impl LogSink {
    pub fn take(&self) -> Vec<(c_int, String)> {
        std::mem::take(&mut *self.records.lock().unwrap())
    }
}

extern "C" fn sink_logger(env: *mut c_void, _instance: *const c_char, status: c_int, _category: *const c_char, message: *const c_char) {
    if env.is_null() || message.is_null() {
        return;
    }
    // SAFETY: env is the LogSink passed to fmi2Instantiate, alive as long as the instance.
    let sink = unsafe { &*(env as *const LogSink) };
    let text = unsafe { CStr::from_ptr(message) }
        .to_string_lossy()
        .replace("%%", "%")
        .replace("##", "#");
    sink.records.lock().unwrap().push((status, text));
}

/// The FMU's logger type from a non-variadic function: the FMU passes the message as the
/// format string and no variadic arguments, which is ABI compatible on x86_64 SysV and
/// aarch64 Linux (see tests/fmi_abi.rs).
pub fn logger() -> Fmi2CallbackLogger {
    type Plain = extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char);
    let f: Plain = sink_logger;
    // SAFETY: see above.
    unsafe { std::mem::transmute::<Plain, Fmi2CallbackLogger>(f) }
}

/// A `resources/` directory holding the preset's `bearing.json`, and its file URI.
pub fn resources_for(root: &Path, preset: &str) -> (PathBuf, String) {
    let text = PRESETS.iter().find(|(n, _)| *n == preset).expect("a preset").1;
    let dir = root.join(preset).join("resources");
    std::fs::create_dir_all(&dir).expect("create the resources directory");
    std::fs::write(dir.join("bearing.json"), text).expect("write bearing.json");
    let uri = url::Url::from_directory_path(&dir).expect("absolute path").to_string();
    (dir, uri)
}

/// An FMU instance driven through the exported C functions, in process.
pub struct Fmu {
    c: Fmi2Component,
    sink: Box<LogSink>,
}

// SAFETY: one thread at a time uses an instance (the FMU allows instances on parallel threads).
unsafe impl Send for Fmu {}

impl Fmu {
    pub fn instantiate(name: &str, bearing: &Bearing, resource_uri: &str) -> Result<Fmu, String> {
        let sink = Box::<LogSink>::default();
        let cb = Fmi2CallbackFunctions {
            logger: Some(logger()),
            allocate_memory: None,
            free_memory: None,
            step_finished: None,
            component_environment: (&*sink as *const LogSink).cast_mut().cast(),
        };
        let name = CString::new(name).unwrap();
        let guid = CString::new(model_description::guid(bearing)).unwrap();
        let uri = CString::new(resource_uri).unwrap();
        let c = unsafe {
            fmi2Instantiate(
                name.as_ptr(),
                FMI2_CO_SIMULATION,
                guid.as_ptr(),
                uri.as_ptr(),
                &cb,
                FMI2_FALSE,
                FMI2_FALSE,
            )
        };
        if c.is_null() {
            let messages: Vec<String> = sink.take().into_iter().map(|(_, m)| m).collect();
            return Err(format!("fmi2Instantiate returned NULL: {}", messages.join("; ")));
        }
        Ok(Fmu { c, sink })
    }

    /// The instance handle, for calls the [`Element`] interface does not cover.
    #[allow(dead_code)] // tests/misuse.rs
    pub fn component(&self) -> Fmi2Component {
        self.c
    }

    /// The messages logged since the last call that reported them.
    #[allow(dead_code)] // tests/misuse.rs
    pub fn take_log(&self) -> Vec<(c_int, String)> {
        self.sink.take()
    }

    fn status(&self, status: Fmi2Status) -> Result<(), Refusal> {
        let logged = self.sink.take();
        match status {
            FMI2_OK | FMI2_WARNING => Ok(()),
            s => Err(Refusal {
                discard: s == FMI2_DISCARD,
                message: logged
                    .into_iter()
                    .filter(|(st, _)| *st >= FMI2_DISCARD)
                    .map(|(_, m)| m)
                    .collect::<Vec<_>>()
                    .join(" | "),
            }),
        }
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        unsafe { fmi2FreeInstance(self.c) };
    }
}

impl Element for Fmu {
    fn set(&mut self, vr: u32, value: Value) -> Result<(), Refusal> {
        let s = unsafe {
            match value {
                Value::Real(x) => fmi2SetReal(self.c, &vr, 1, &x),
                Value::Integer(i) => fmi2SetInteger(self.c, &vr, 1, &i),
                Value::Boolean(b) => fmi2SetBoolean(self.c, &vr, 1, &(b as Fmi2Boolean)),
            }
        };
        self.status(s)
    }

    fn initialize(&mut self, t0: f64) -> Result<(), Refusal> {
        let s = unsafe { fmi2SetupExperiment(self.c, FMI2_FALSE, 0.0, t0, FMI2_FALSE, 0.0) };
        self.status(s)?;
        let s = unsafe { fmi2EnterInitializationMode(self.c) };
        self.status(s)?;
        let s = unsafe { fmi2ExitInitializationMode(self.c) };
        self.status(s)
    }

    fn step(&mut self, t: f64, h: f64) -> Result<(), Refusal> {
        let s = unsafe { fmi2DoStep(self.c, t, h, FMI2_TRUE) };
        self.status(s)
    }

    fn read(&mut self, reals: &[u32], ints: &[u32], rv: &mut [f64], iv: &mut [i32]) -> Result<(), Refusal> {
        let s1 = unsafe { fmi2GetReal(self.c, reals.as_ptr(), reals.len(), rv.as_mut_ptr()) };
        let s2 = unsafe { fmi2GetInteger(self.c, ints.as_ptr(), ints.len(), iv.as_mut_ptr()) };
        self.status(s1.max(s2))
    }

    fn kinetic_energy(&self) -> Option<f64> {
        None
    }
}

// ---------------------------------------------------------------------------------------
// Running a case
// ---------------------------------------------------------------------------------------

/// How a case ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    Passed,
    /// Refused (fmi2Discard / fmi2Error) with a message that says why.
    Refused {
        at: f64,
        discard: bool,
        message: String,
    },
    /// Fidelity not available in this build.
    NotAvailable {
        message: String,
    },
    Failed {
        reason: String,
    },
}

impl Outcome {
    pub fn label(&self) -> &'static str {
        match self {
            Outcome::Passed => "passed",
            Outcome::Refused { .. } => "refused",
            Outcome::NotAvailable { .. } => "not available",
            Outcome::Failed { .. } => "FAILED",
        }
    }
}

/// The result of one case on one element.
#[derive(Debug, Clone)]
pub struct Record {
    pub outcome: Outcome,
    /// Successful communication steps.
    pub steps: usize,
    /// Largest `Qo.max` seen (N) and largest solver residual.
    pub qo_max: f64,
    pub residual_max: f64,
    /// Fewest loaded rollers seen.
    pub loaded_min: i32,
    /// FNV-1a hash of every output bit of every step (to compare elements).
    pub hash: u64,
    /// Wall time (s); not part of the report.
    pub seconds: f64,
}

/// Output value references of a bearing with `z` rollers: (reals, integers).
pub fn output_vrs(z: usize) -> (Vec<u32>, Vec<u32>) {
    let all = var::expanded(z);
    let pick = |ty| {
        all.iter()
            .filter(|(_, _, r)| r.causality == Causality::Output && r.ty == ty)
            .map(|(vr, _, _)| *vr)
            .collect()
    };
    (pick(VarType::Real), pick(VarType::Integer))
}

/// Index of a named output in the Real outputs.
fn index_of(reals: &[u32], vr: u32) -> usize {
    reals.iter().position(|v| *v == vr).expect("an output")
}

/// Does a refusal message say why? It must name the input or parameter, or (no
/// equilibrium) give a reason after the solver's statistics.
pub fn clarity(message: &str) -> Result<(), String> {
    let m = message.trim();
    if m.len() < 20 {
        return Err(format!("message too short: {m:?}"));
    }
    if m.contains("panicked") || m.contains("internal error") {
        return Err(format!("internal error: {m}"));
    }
    let names_variable = m.contains("input ") || m.contains("parameter ") || m.contains("value reference");
    // The solvers' refusals: a reason after the statistics, or the step budget; loads beyond
    // the model's range, with the reason.
    // (the quasi-dynamic balance's refusal names its Newton iterations and the largest
    // correction against its limit)
    let gives_reason = (m.contains("no quasi-static equilibrium") && m.contains("; "))
        || (m.contains("quasi-dynamic balance") && m.contains("did not converge") && m.contains("largest correction"))
        || (m.contains("dynamic integration failed") && (m.contains("; ") || m.contains("steps in one communication interval")))
        || m.contains("the load is beyond the model's range: ");
    if names_variable || gives_reason {
        Ok(())
    } else {
        Err(format!("message gives no reason: {m}"))
    }
}

/// Run `case` on `element` (a fresh one, with the case's bearing).
pub fn run_case<E: Element>(case: &Case, element: &mut E, z: usize, tapered: bool) -> Record {
    let mut record = Record {
        outcome: Outcome::Passed,
        steps: 0,
        qo_max: 0.0,
        residual_max: 0.0,
        loaded_min: i32::MAX,
        hash: 0xcbf2_9ce4_8422_2325,
        seconds: 0.0,
    };
    let started = std::time::Instant::now();
    let result = catch_unwind(AssertUnwindSafe(|| drive(case, element, z, tapered, &mut record)));
    record.outcome = match result {
        Ok(o) => o,
        Err(payload) => {
            let msg = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            Outcome::Failed {
                reason: format!("panic: {msg}"),
            }
        }
    };
    record.seconds = started.elapsed().as_secs_f64();
    if record.loaded_min == i32::MAX {
        record.loaded_min = 0;
    }
    record
}

fn drive<E: Element>(case: &Case, el: &mut E, z: usize, tapered: bool, rec: &mut Record) -> Outcome {
    let (reals, ints) = output_vrs(z);
    let mut rv = vec![0.0; reals.len()];
    let mut iv = vec![0; ints.len()];
    let i_torque = index_of(&reals, var::FRICTION_TORQUE);
    let i_parts = [var::FRICTION_TORQUE_RACEWAY, var::FRICTION_TORQUE_FLANGE, var::FRICTION_TORQUE_CAGE].map(|v| index_of(&reals, v));
    let i_power = index_of(&reals, var::POWER_LOSS);
    let i_rfx = index_of(&reals, var::REACTION_FX);
    let i_qo = index_of(&reals, var::QO_MAX);
    let i_res = index_of(&reals, var::SOLVER_RESIDUAL);
    let loads: Vec<usize> = [var::QI_MAX, var::QO_MAX, var::QF_MAX]
        .into_iter()
        .chain((0..z as u32).flat_map(|j| [var::ROLLER_QI + j, var::ROLLER_QO + j, var::ROLLER_QF + j]))
        .map(|v| index_of(&reals, v))
        .collect();
    let i_loaded = ints.iter().position(|v| *v == var::LOADED_ROLLERS).expect("loadedRollers");
    let slices = match case.params.iter().find(|(n, _)| *n == "slices") {
        Some((_, Value::Integer(s))) => (*s).max(1) as usize,
        _ => presets()[case.preset].bearing.slices,
    };

    let inputs: Vec<(u32, &Signal)> = case
        .inputs
        .iter()
        .map(|(name, s)| (var::find(name, z).unwrap_or_else(|| panic!("no input {name}")).0, s))
        .collect();
    let force_preload = !case.params.iter().any(|(n, v)| *n == "preload" && *v == Value::Integer(1));
    let fx_of = |t: f64| case.inputs.iter().find(|(n, _)| *n == "Fx").map(|(_, s)| s.at(t));
    let speed_of = |t: f64| case.inputs.iter().find(|(n, _)| *n == "speed").map(|(_, s)| s.at(t));

    // Refusal handling: acceptable unless a pass was expected; the message must be clear;
    // whatever the element still returns must be finite.
    let refused = |el: &mut E, at: f64, r: Refusal, rv: &mut [f64], iv: &mut [i32]| -> Outcome {
        let _ = el.read(&reals, &ints, rv, iv);
        if let Some(k) = rv.iter().position(|v| !v.is_finite()) {
            return Outcome::Failed {
                reason: format!("non-finite output after the refusal at t = {at}: vr {} is {}", reals[k], rv[k]),
            };
        }
        if r.message.contains("not available in this build") {
            return Outcome::NotAvailable { message: r.message };
        }
        if let Err(why) = clarity(&r.message) {
            return Outcome::Failed {
                reason: format!("refused at t = {at} with an unclear message: {why}"),
            };
        }
        if let Some(why) = case.why.filter(|w| !w.is_empty() && !w.split('|').any(|w| r.message.contains(w))) {
            return Outcome::Failed {
                reason: format!(
                    "refused at t = {at}, but the message does not say why (expected \"{why}\"): {}",
                    r.message
                ),
            };
        }
        if case.expect == Expect::Pass {
            return Outcome::Failed {
                reason: format!("unexpected refusal of a case inside the model's range at t = {at}: {}", r.message),
            };
        }
        Outcome::Refused {
            at,
            discard: r.discard,
            message: r.message,
        }
    };

    for (name, value) in &case.params {
        let (vr, _) = var::find(name, z).unwrap_or_else(|| panic!("no parameter {name}"));
        if let Err(r) = el.set(vr, *value) {
            return refused(el, 0.0, r, &mut rv, &mut iv);
        }
    }
    let t0 = 0.0;
    for (vr, s) in &inputs {
        if let Err(r) = el.set(*vr, Value::Real(s.at(t0))) {
            return refused(el, t0, r, &mut rv, &mut iv);
        }
    }
    if let Err(r) = el.initialize(t0) {
        return refused(el, t0, r, &mut rv, &mut iv);
    }
    // (frictionTorque x speed, powerLoss, reaction.Fx, Fx) after every step
    let mut samples: Vec<Sample> = Vec::new();
    // Step k: inputs at u(t_k), doStep(t_k, h), outputs at t_{k+1} (an FMI master's loop).
    for k in 0..=case.steps {
        let t = t0 + k as f64 * case.h;
        if k > 0 {
            let tp = t0 + (k - 1) as f64 * case.h;
            let started = std::time::Instant::now();
            let stepped = el.step(tp, case.h);
            let wall = started.elapsed().as_secs_f64();
            let bound = step_wall_bound(z, slices);
            if wall > bound {
                return Outcome::Failed {
                    reason: format!("the doStep from t = {tp} took {wall:.1} s, more than {bound:.0} s"),
                };
            }
            if let Err(r) = stepped {
                return refused(el, tp, r, &mut rv, &mut iv);
            }
            rec.steps += 1;
        }
        if let Err(r) = el.read(&reals, &ints, &mut rv, &mut iv) {
            return refused(el, t, r, &mut rv, &mut iv);
        }
        // The inputs the outputs belong to (held over the step).
        let tu = if k == 0 { t0 } else { t0 + (k - 1) as f64 * case.h };
        // The quasi-static balance holds exactly; a dynamic model stores energy and moves.
        let quasi_static = case.fidelity == 0;
        let fx = fx_of(tu).filter(|_| quasi_static && tapered && force_preload);
        let speed = speed_of(tu).filter(|_| quasi_static);
        if let Err(reason) = check(&rv, &iv, z, fx, speed, (i_torque, i_parts, i_power, i_rfx, i_loaded), &loads) {
            return Outcome::Failed {
                reason: format!("t = {t}: {reason}"),
            };
        }
        if k > 0 {
            samples.push(Sample {
                input: speed_of(tu).unwrap_or(f64::NAN) * rv[i_torque],
                loss: rv[i_power],
                reaction_fx: rv[i_rfx],
                fx: fx_of(tu),
                kinetic: el.kinetic_energy(),
            });
        }
        rec.qo_max = rec.qo_max.max(rv[i_qo]);
        rec.residual_max = rec.residual_max.max(rv[i_res]);
        rec.loaded_min = rec.loaded_min.min(iv[i_loaded]);
        for v in rv.iter().map(|v| v.to_bits()).chain(iv.iter().map(|i| *i as u64)) {
            for byte in v.to_le_bytes() {
                rec.hash = (rec.hash ^ byte as u64).wrapping_mul(0x0100_0000_01b3);
            }
        }
        if k < case.steps {
            // The next step holds the inputs at u(t_k).
            for (vr, s) in &inputs {
                if let Err(r) = el.set(*vr, Value::Real(s.at(t))) {
                    return refused(el, t, r, &mut rv, &mut iv);
                }
            }
        }
    }
    if case.expect == Expect::Refuse {
        return Outcome::Failed {
            reason: "accepted a case outside the model's range without complaint".into(),
        };
    }
    // (at least 20 steps in the second half, else the start transient dominates: not checked;
    // an element that cannot tell its kinetic energy, the FMU, is compared bitwise instead)
    let first = samples.len() / 2;
    let kinetic = |i: usize| samples.get(i).and_then(|s| s.kinetic);
    if let (Some(tol), Some(ke_start), Some(ke_end)) = (
        case.average.filter(|_| samples.len() >= 40),
        kinetic(first.wrapping_sub(1)),
        kinetic(samples.len().wrapping_sub(1)),
    ) {
        let tail = &samples[first..];
        let n = tail.len() as f64;
        let mean = |f: &dyn Fn(&Sample) -> f64| tail.iter().map(f).sum::<f64>() / n;
        let (input, loss) = (mean(&|s| s.input), mean(&|s| s.loss));
        // what drives the cone is dissipated or stored: input = loss + d(kinetic)/dt
        let stored = (ke_end - ke_start) / (n * case.h);
        if !((input - loss - stored).abs() <= tol * loss.abs().max(input.abs()) + 1e-9) {
            return Outcome::Failed {
                reason: format!(
                    "energy balance on average over the last {n} steps: frictionTorque x speed {input:.6e} W, powerLoss {loss:.6e} W, kinetic energy change {stored:.6e} W (tolerance {tol})"
                ),
            };
        }
        if tapered && force_preload {
            if let Some(fx) = tail[0].fx {
                let rfx = mean(&|s| s.reaction_fx);
                if !((rfx - fx).abs() <= tol * fx.abs().max(1.0)) {
                    return Outcome::Failed {
                        reason: format!("mean reaction.Fx {rfx:.6e} N over the last {n} steps but Fx = {fx:.6e} N (tolerance {tol})"),
                    };
                }
            }
        }
    }
    Outcome::Passed
}

/// The outputs of one communication point that the averaged balances use.
struct Sample {
    /// frictionTorque x speed (W).
    input: f64,
    /// powerLoss (W).
    loss: f64,
    reaction_fx: f64,
    /// The input Fx the outputs belong to (force preload of a tapered bearing).
    fx: Option<f64>,
    /// Kinetic energy at the communication point (J), where the element tells it.
    kinetic: Option<f64>,
}

#[allow(clippy::too_many_arguments)]
fn check(
    rv: &[f64],
    iv: &[i32],
    z: usize,
    fx: Option<f64>,
    speed: Option<f64>,
    (i_torque, i_parts, i_power, i_rfx, i_loaded): (usize, [usize; 3], usize, usize, usize),
    loads: &[usize],
) -> Result<(), String> {
    if let Some(k) = rv.iter().position(|v| !v.is_finite()) {
        return Err(format!("non-finite output: Real output {k} (modelDescription order) is {}", rv[k]));
    }
    let torque = rv[i_torque];
    let power = rv[i_power];
    if let Some(w) = speed {
        let expected = torque * w;
        if (power - expected).abs() > 1e-12 * expected.abs().max(1e-300) {
            return Err(format!("energy balance: powerLoss {power} != frictionTorque {torque} x speed {w}"));
        }
    }
    if power < 0.0 {
        return Err(format!("powerLoss {power} < 0"));
    }
    let parts: f64 = i_parts.iter().map(|i| rv[*i]).sum();
    if (parts - torque).abs() > 1e-9 * torque.abs().max(parts.abs()) + 1e-12 {
        return Err(format!("frictionTorque {torque} != sum of its parts {parts}"));
    }
    if let Some(k) = loads.iter().find(|k| rv[**k] < 0.0) {
        return Err(format!("negative contact load {}", rv[*k]));
    }
    let loaded = iv[i_loaded];
    if loaded < 0 || loaded as usize > z {
        return Err(format!("loadedRollers = {loaded} outside [0, {z}]"));
    }
    if let Some(fx) = fx {
        let rfx = rv[i_rfx];
        if (rfx - fx).abs() > 1e-6 * fx.abs().max(1.0) {
            return Err(format!("reaction.Fx = {rfx} but Fx = {fx}: the equilibrium does not hold"));
        }
    }
    Ok(())
}

/// Run `case` on a fresh `Simulation`.
pub fn run_on_simulation(case: &Case, presets: &[Preset]) -> Record {
    let p = &presets[case.preset];
    let mut sim = Simulation::new(p.bearing.clone());
    run_case(case, &mut sim, p.bearing.roller_count, p.tapered())
}

/// Run `case` on a fresh FMU instance; `uris[preset]` is the resource location.
pub fn run_on_fmu(case: &Case, presets: &[Preset], uris: &[String]) -> Record {
    let p = &presets[case.preset];
    match Fmu::instantiate(&case.id, &p.bearing, &uris[case.preset]) {
        Ok(mut fmu) => run_case(case, &mut fmu, p.bearing.roller_count, p.tapered()),
        Err(e) => Record {
            outcome: Outcome::Failed { reason: e },
            steps: 0,
            qo_max: 0.0,
            residual_max: 0.0,
            loaded_min: 0,
            hash: 0,
            seconds: 0.0,
        },
    }
}

/// Run `f` on every item on `threads` threads, results in input order.
pub fn parallel_map<T: Sync, R: Send>(items: &[T], threads: usize, f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let results: Mutex<Vec<Option<R>>> = Mutex::new((0..items.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads.max(1) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                if i >= items.len() {
                    break;
                }
                let r = f(&items[i]);
                results.lock().unwrap()[i] = Some(r);
            });
        }
    });
    results
        .into_inner()
        .unwrap()
        .into_iter()
        .map(|r| r.expect("every item ran"))
        .collect()
}

/// The matrix run: every case on `Simulation`, the FMU subset on the C ABI as well.
pub struct Run {
    pub presets: Vec<Preset>,
    pub cases: Vec<Case>,
    pub sim: Vec<Record>,
    /// (case index, FMU record) for the subset; a differing hash is a failure.
    pub fmu: Vec<(usize, Record)>,
}

impl Run {
    #[allow(dead_code)] // tests/stress.rs
    pub fn execute(cases: Vec<Case>, threads: usize, scratch: &Path) -> Run {
        Run::execute_with(cases, threads, scratch, |_, _, _| {})
    }

    /// As [`Run::execute`], calling `progress(case, record, through the FMU)` as each run ends.
    pub fn execute_with(cases: Vec<Case>, threads: usize, scratch: &Path, progress: impl Fn(&Case, &Record, bool) + Sync) -> Run {
        let presets = presets();
        let sim = parallel_map(&cases, threads, |c| {
            let r = run_on_simulation(c, &presets);
            progress(c, &r, false);
            r
        });
        let uris: Vec<String> = presets.iter().map(|p| resources_for(scratch, p.name()).1).collect();
        let subset: Vec<usize> = (0..cases.len()).filter(|i| cases[*i].fmu).collect();
        let fmu_records = parallel_map(&subset, threads, |i| {
            let r = run_on_fmu(&cases[*i], &presets, &uris);
            progress(&cases[*i], &r, true);
            r
        });
        let fmu = subset.into_iter().zip(fmu_records).collect();
        Run { presets, cases, sim, fmu }
    }

    /// Failures: the Simulation runs that failed, and FMU runs that failed or differ.
    pub fn failures(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (c, r) in self.cases.iter().zip(&self.sim) {
            if let Outcome::Failed { reason } = &r.outcome {
                out.push(format!("{}: {reason}", c.id));
            }
        }
        for (i, r) in &self.fmu {
            if let Some(why) = self.fmu_mismatch(*i, r) {
                out.push(format!("{} (FMU): {why}", self.cases[*i].id));
            }
        }
        out
    }

    /// Why the FMU run of case `i` does not agree with the Simulation run, if it does not.
    pub fn fmu_mismatch(&self, i: usize, r: &Record) -> Option<String> {
        let s = &self.sim[i];
        if let Outcome::Failed { reason } = &r.outcome {
            // The same failure as Simulation's is reported once, there.
            if !(s.outcome.label() == "FAILED" && s.hash == r.hash && s.steps == r.steps) {
                return Some(reason.clone());
            }
        }
        if r.outcome.label() != s.outcome.label() || r.steps != s.steps {
            return Some(format!(
                "FMU {} after {} steps, Simulation {} after {} steps",
                r.outcome.label(),
                r.steps,
                s.outcome.label(),
                s.steps
            ));
        }
        if r.hash != s.hash {
            return Some("outputs differ from Simulation's (bitwise)".into());
        }
        None
    }

    pub fn count(&self, label: &str) -> usize {
        self.sim.iter().filter(|r| r.outcome.label() == label).count()
    }
}

// ---------------------------------------------------------------------------------------
// Report
// ---------------------------------------------------------------------------------------

fn md_cell(s: &str) -> String {
    let s = s.replace('|', "\\|").replace('\n', " ");
    if s.chars().count() > 220 {
        format!("{}…", s.chars().take(220).collect::<String>())
    } else {
        s
    }
}

/// The generated part of docs/robustness.md (deterministic: no timings): the reference
/// values, and one part per fidelity that ran (the `stress` command keeps the parts of the
/// fidelities it did not run).
pub fn report(run: &Run, command: &str) -> (String, Vec<(i32, String)>) {
    use std::fmt::Write as _;
    let mut s = String::new();
    let fids: std::collections::BTreeSet<i32> = run.cases.iter().map(|c| c.fidelity).collect();
    let _ = writeln!(s, "Generated by the `stress` command; do not edit by hand.\n");
    let _ = writeln!(s, "### Reference values per preset\n");
    let _ = writeln!(
        s,
        "| preset | Z | C0r (ISO 76) | axial equivalent Fa0 = C0r tan a / 0.22 | limiting speed estimate | operating speed |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for p in &run.presets {
        let rpm = 30.0 / std::f64::consts::PI;
        let _ = writeln!(
            s,
            "| {} | {} | {:.0} N | {} | {:.0} rpm | {:.0} rpm |",
            p.name(),
            p.bearing.roller_count,
            p.c0,
            if p.fa0 > 0.0 {
                format!("{:.0} N", p.fa0)
            } else {
                "— (no axial load)".into()
            },
            p.n_lim * rpm,
            p.speed * rpm
        );
    }
    let parts = fids.iter().map(|f| (*f, fidelity_report(run, *f, command))).collect();
    (s, parts)
}

fn fidelity_report(run: &Run, f: i32, command: &str) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let of_f: Vec<usize> = (0..run.cases.len()).filter(|i| run.cases[*i].fidelity == f).collect();
    let _ = writeln!(s, "### Fidelity {f}\n");
    let _ = writeln!(s, "Generated by `{command}`.\n");
    if f == 1 {
        let _ = writeln!(
            s,
            "Every fidelity-1 case runs the Rosenbrock-W integrator (`integrator` = 2) at `tolerance` = 1e-4 unless its name says otherwise.\n"
        );
    }
    if f == 2 {
        let _ = writeln!(
            s,
            "Every fidelity-2 case runs the quasi-dynamic model at its default settings (backward Euler at the communication step, steps halved down to h/64 before a refusal) unless its name says otherwise.\n"
        );
    }
    let _ = writeln!(s, "| preset | cases | passed | refused (clear message) | not available | FAILED |");
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    let count = |idx: &[usize], l: &str| idx.iter().filter(|i| run.sim[**i].outcome.label() == l).count();
    for (pi, p) in run.presets.iter().enumerate() {
        let idx: Vec<usize> = of_f.iter().copied().filter(|i| run.cases[*i].preset == pi).collect();
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} |",
            p.name(),
            idx.len(),
            count(&idx, "passed"),
            count(&idx, "refused"),
            count(&idx, "not available"),
            count(&idx, "FAILED")
        );
    }
    let _ = writeln!(
        s,
        "| all | **{}** | **{}** | **{}** | **{}** | **{}** |",
        of_f.len(),
        count(&of_f, "passed"),
        count(&of_f, "refused"),
        count(&of_f, "not available"),
        count(&of_f, "FAILED")
    );
    let steps: usize = of_f.iter().map(|i| run.sim[*i].steps).sum();
    let fmu: Vec<&(usize, Record)> = run.fmu.iter().filter(|(i, _)| run.cases[*i].fidelity == f).collect();
    let fmu_bad = fmu.iter().filter(|(i, r)| run.fmu_mismatch(*i, r).is_some()).count();
    let _ = writeln!(
        s,
        "\n{steps} communication steps in all. Through the FMU's C ABI: {} of the cases (the first of every group of every preset, and the long runs{}), each compared bitwise with the `Simulation` run: {} differ or fail.\n",
        fmu.len(),
        if f == 1 { " of 32008" } else { "" },
        fmu_bad
    );
    let failures: Vec<String> = run
        .failures()
        .into_iter()
        .filter(|x| {
            of_f.iter()
                .any(|i| x.starts_with(&format!("{}: ", run.cases[*i].id)) || x.starts_with(&format!("{} (FMU): ", run.cases[*i].id)))
        })
        .collect();
    if !failures.is_empty() {
        let _ = writeln!(s, "#### Failures (fidelity {f})\n");
        for x in &failures {
            let _ = writeln!(s, "- {}", md_cell(x));
        }
        s.push('\n');
    }
    let _ = writeln!(s, "#### Every case (fidelity {f})\n");
    let _ = writeln!(
        s,
        "Columns: expectation, outcome, successful steps × step size, largest cup contact load Qo.max, fewest loaded rollers, largest relative solver residual; for refusals the time and the message (fmi2Discard or fmi2Error).\n"
    );
    let fmu_of: std::collections::HashMap<usize, &Record> = run.fmu.iter().map(|(i, r)| (*i, r)).collect();
    // One table per preset and group, in the order the groups first appear.
    let mut order: Vec<(usize, &str)> = Vec::new();
    for i in &of_f {
        let key = (run.cases[*i].preset, run.cases[*i].group);
        if !order.contains(&key) {
            order.push(key);
        }
    }
    for (preset, group) in order {
        let _ = writeln!(s, "\n##### {} · {} · fidelity {f}\n", run.presets[preset].name(), group);
        let _ = writeln!(
            s,
            "| case | expect | outcome | steps × h | Qo.max (N) | min loaded | residual | FMU | detail |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
        for i in of_f
            .iter()
            .copied()
            .filter(|i| run.cases[*i].preset == preset && run.cases[*i].group == group)
        {
            let (c, r) = (&run.cases[i], &run.sim[i]);
            let detail = match &r.outcome {
                Outcome::Passed => String::new(),
                Outcome::Refused { at, discard, message } => {
                    format!("t = {at}: {} {}", if *discard { "fmi2Discard:" } else { "fmi2Error:" }, message)
                }
                Outcome::NotAvailable { message } => message.clone(),
                Outcome::Failed { reason } => reason.clone(),
            };
            let fmu = match fmu_of.get(&i) {
                None => "",
                Some(fr) => match run.fmu_mismatch(i, fr) {
                    None => "same",
                    Some(_) => "DIFFERS",
                },
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} × {:e} s | {:.4e} | {} | {:.1e} | {} | {} |",
                md_cell(&c.what),
                c.expect.label(),
                r.outcome.label(),
                r.steps,
                c.h,
                r.qo_max,
                r.loaded_min,
                r.residual_max,
                fmu,
                md_cell(&detail)
            );
        }
    }
    s
}
