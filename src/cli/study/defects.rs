//! `trb study defects`: the vibration signature of a local defect. For each defect location
//! (cup, cone, one roller), the dynamic model (fidelity 1) of the default bearing on a 10 kg
//! housing runs with a spall where the load is, and the healthy bearing under the same load
//! for reference; the accelerometer signal on the housing is sampled at 20 kHz. Writes `docs/defects.md` and
//! `docs/figures/defects_*.svg`: the time signal, its spectrum and its envelope spectrum with
//! the characteristic frequencies of the kinematic formulas marked, and a table of the
//! envelope's peaks against those formulas.

use super::{f, pct, Writer};
use crate::cli::report::{self, table};
use crate::cli::svg::{self, Mark, Series};
use crate::cli::CliError;
use rustfft::{num_complex::Complex, FftPlanner};
use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;
use trb::bearing::Bearing;
use trb::model::Outputs;
use trb::simulation::Simulation;
use trb::variables as var;

/// The default bearing.
const PRESET: &str = "TRB130x230";
/// Shaft speed (rpm), axial and radial load (N): the radial load centred on +y (azimuth 0),
/// enough axial load that every roller stays loaded around the orbit (a preloaded tapered
/// bearing), so that rollers roll without gross slip everywhere and a roller defect's strikes
/// keep the rhythm of its spin (under Fa 20 kN and Fy 40 kN the rollers leaving the load zone
/// spin down, docs/model.md, "Local defects").
const SPEED_RPM: f64 = 3500.0;
const FA: f64 = 60e3;
const FY: f64 = 20e3;
/// The loads (Fa, Fy; N) of the healthy bearing's varying compliance: a load zone, out of
/// which the rollers run unloaded, so that the load line's passes ring clearly (under Fa 60 kN
/// and Fy 20 kN every roller carries nearly the same load and the line is weak).
const LOAD_ZONE: (f64, f64) = (20e3, 40e3);
/// Mass of the cup and the housing moving with it (kg), on the default support
/// (`housing.stiffness`, `housing.damping`): the accelerometer's mount.
const HOUSING_MASS: f64 = 10.0;
/// Communication step (s): the sampling interval of the signal, 20 kHz.
const STEP: f64 = 50e-6;
/// Simulated time (s) per run: the frequency resolution is its inverse.
const DURATION: f64 = 0.2;
const DURATION_QUICK: f64 = 0.05;
/// The squared envelope is demodulated from this band of the signal (Hz): above the
/// characteristic frequencies and their first harmonics, where the impacts ring the bearing.
const BAND: (f64, f64) = (1000.0, 9000.0);
/// The envelope spectrum is shown up to this frequency (Hz).
const ENVELOPE_MAX: f64 = 1500.0;

/// The signal the study analyses, with its name and unit, from the element's outputs: the one
/// place that chooses it. An accelerometer on the housing, along the radial load.
fn sensor(o: &Outputs) -> (f64, &'static str, &'static str) {
    (o.cup_ay, "cup.ay", "m/s²")
}

/// A spall where the load is at t = 0 (on the cup and the cone at azimuth 0, on roller 1
/// facing the cup): 1.5 mm long, 10 mm wide, 0.1 mm deep, sharp edges (a roller of this
/// bearing drops at most R_e − √(R_e² − (L/2)²), 24–30 µm, into it).
const SPALL: [(u32, f64); 4] = [
    (var::DEFECT_ANGLE, 0.0),
    (var::DEFECT_LENGTH, 1.5e-3),
    (var::DEFECT_WIDTH, 10e-3),
    (var::DEFECT_DEPTH, 0.1e-3),
];

/// One defect location: its `defect.ring` value and the lines where the envelope of its
/// signal should peak.
struct Location {
    /// Name in the figures' file names (`defects_{key}_*.svg`).
    key: &'static str,
    title: &'static str,
    ring: i32,
    lines: fn(&Kinematics) -> Vec<Line>,
}

const fn location(key: &'static str, title: &'static str, ring: i32, lines: fn(&Kinematics) -> Vec<Line>) -> Location {
    Location { key, title, ring, lines }
}

/// The defect locations the study runs, one line each (the roller defect on roller 1, the
/// default `defect.roller`).
const LOCATIONS: &[Location] = &[
    location("cup", "Cup (outer race)", 1, Kinematics::cup_lines),
    location("cone", "Cone (inner race)", 2, Kinematics::cone_lines),
    location("roller", "Roller", 3, Kinematics::roller_lines),
];

/// A characteristic frequency (Hz) and its name.
#[derive(Debug, Clone)]
struct Line {
    label: String,
    f: f64,
}

fn line(label: impl Into<String>, f: f64) -> Line {
    Line { label: label.into(), f }
}

/// The characteristic frequencies of a bearing whose rollers roll without slip on a fixed
/// cup, from the geometry alone (not from the model's motion). With the shaft rate f_s, Z
/// rollers, the pitch diameter d_m and the roller diameter D at contact angle α (Randall &
/// Antoni, "Rolling element bearing diagnostics—A tutorial", Mech. Syst. Signal Process. 25
/// (2011) 485):
///
/// - cage (fundamental train) frequency FTF = (f_s / 2) (1 − D cos α / d_m);
/// - outer-race (ball pass) frequency BPFO = (Z f_s / 2) (1 − D cos α / d_m) = Z FTF;
/// - inner-race frequency BPFI = (Z f_s / 2) (1 + D cos α / d_m);
/// - roller spin frequency BSF = (d_m / 2D) f_s (1 − (D cos α / d_m)²); a roller defect strikes
///   both races once per spin, at 2 × BSF.
///
/// For the tapered bearing they are taken at the middle slice of the contact lines, with the
/// cone and cup contact radii r_i, r_o (distance from the bearing axis): d_m = r_i + r_o,
/// D cos α = r_o − r_i, and D the roller's diameter there. Rolling without slip on these radii
/// gives the same numbers (FTF = f_s r_i / d_m, BSF = 2 f_s r_i r_o / (D d_m)).
#[derive(Debug, Clone, Copy)]
struct Kinematics {
    z: usize,
    /// Shaft rate (Hz).
    fs: f64,
    ftf: f64,
    bpfo: f64,
    bpfi: f64,
    bsf: f64,
    /// The inputs of the formulas (m).
    ri: f64,
    ro: f64,
    d: f64,
}

impl Kinematics {
    fn new(b: &Bearing, speed_rpm: f64) -> Kinematics {
        let g = trb::geometry::Geometry::new(b, &trb::geometry::RollerProfile::of_bearing(b));
        let mid = g.slices / 2;
        let (ri, ro) = (g.cone.raceway_radius[mid], g.cup.raceway_radius[mid]);
        let d = 2.0 * g.slice_radius[mid];
        let (dm, d_cos) = (ri + ro, ro - ri);
        let fs = speed_rpm / 60.0;
        let z = b.roller_count;
        let ratio = d_cos / dm;
        Kinematics {
            z,
            fs,
            ftf: 0.5 * fs * (1.0 - ratio),
            bpfo: 0.5 * z as f64 * fs * (1.0 - ratio),
            bpfi: 0.5 * z as f64 * fs * (1.0 + ratio),
            bsf: dm / (2.0 * d) * fs * (1.0 - ratio * ratio),
            ri,
            ro,
            d,
        }
    }

    /// A cup defect: every roller strikes it, at BPFO and its harmonics (the cup does not turn,
    /// so no sidebands).
    fn cup_lines(&self) -> Vec<Line> {
        vec![
            line("BPFO", self.bpfo),
            line("2 × BPFO", 2.0 * self.bpfo),
            line("3 × BPFO", 3.0 * self.bpfo),
        ]
    }

    /// A cone defect: struck at BPFI, carried through the load zone once per shaft turn
    /// (sidebands at the shaft rate).
    fn cone_lines(&self) -> Vec<Line> {
        vec![
            line("BPFI − f_s", self.bpfi - self.fs),
            line("BPFI", self.bpfi),
            line("BPFI + f_s", self.bpfi + self.fs),
            line("2 × BPFI", 2.0 * self.bpfi),
        ]
    }

    /// A roller defect: it strikes cone and cup once each per spin (2 × BSF), carried through
    /// the load zone with the cage (sidebands at FTF).
    fn roller_lines(&self) -> Vec<Line> {
        vec![
            line("BSF", self.bsf),
            line("2 × BSF − FTF", 2.0 * self.bsf - self.ftf),
            line("2 × BSF", 2.0 * self.bsf),
            line("2 × BSF + FTF", 2.0 * self.bsf + self.ftf),
        ]
    }

    /// The healthy bearing's varying compliance: the rollers pass the load line at Z × FTF.
    fn compliance(&self) -> f64 {
        self.z as f64 * self.ftf
    }

    /// The lines marked on every figure.
    fn marks(&self) -> Vec<Mark> {
        vec![
            Mark::new(self.ftf, "FTF"),
            Mark::new(self.fs, "f_s"),
            Mark::new(self.bsf, "BSF"),
            Mark::new(2.0 * self.bsf, "2×BSF"),
            Mark::new(self.bpfo, "BPFO"),
            Mark::new(self.bpfi, "BPFI"),
            Mark::new(2.0 * self.bpfo, "2×BPFO"),
            Mark::new(2.0 * self.bpfi, "2×BPFI"),
            Mark::new(3.0 * self.bpfo, "3×BPFO"),
        ]
    }
}

/// One run's sensor signal.
struct Run {
    signal: Vec<f64>,
    /// The cage's mean rate over the run (Hz), from `cage.speed`.
    cage_rate: f64,
    wall: f64,
}

/// Fidelity 1 with `defect.ring` = `ring` (0: the healthy bearing) and the spall, `duration`
/// seconds sampled every STEP.
fn run(ring: i32, duration: f64, (fa, fy): (f64, f64)) -> Result<Run, CliError> {
    let fail = |e: String| CliError::failed(format!("defect.ring = {ring}: {e}"));
    let b = Bearing::preset(PRESET).map_err(|e| fail(e.to_string()))?;
    let mut s = Simulation::new(b);
    s.set_integer(var::FIDELITY, 1).map_err(|e| fail(e.to_string()))?;
    s.set_integer(var::DEFECT_RING, ring).map_err(|e| fail(e.to_string()))?;
    let reals = [
        (var::SPEED, SPEED_RPM * PI / 30.0),
        (var::FX, fa),
        (var::FY, fy),
        (var::HOUSING_MASS, HOUSING_MASS),
    ];
    for (vr, v) in reals.into_iter().chain(SPALL) {
        s.set_real(vr, v).map_err(|e| fail(e.to_string()))?;
    }
    let started = Instant::now();
    s.initialize(0.0).map_err(|e| fail(e.to_string()))?;
    let n = (duration / STEP).round() as usize;
    let (mut signal, mut cage) = (Vec::with_capacity(n), 0.0);
    for k in 0..n {
        let t = k as f64 * STEP;
        s.do_step(t, STEP).map_err(|e| fail(format!("t = {t} s: {e}")))?;
        let o = s.outputs().map_err(|e| fail(e.to_string()))?;
        signal.push(sensor(o).0);
        cage += o.cage_speed;
    }
    Ok(Run {
        signal,
        cage_rate: cage / n as f64 / TAU,
        wall: started.elapsed().as_secs_f64(),
    })
}

/// The discrete Fourier transform of `x` in place: X_k = Σ_n x_n e^{∓2πi kn/N}, the minus sign
/// forward, the plus sign with `inverse` (which also divides by N), by the rustfft crate.
fn fft(x: &mut [Complex<f64>], inverse: bool) {
    let mut planner = FftPlanner::new();
    if inverse {
        planner.plan_fft_inverse(x.len()).process(x);
        let scale = 1.0 / x.len() as f64;
        x.iter_mut().for_each(|v| *v *= scale);
    } else {
        planner.plan_fft_forward(x.len()).process(x);
    }
}

/// The one-sided amplitude spectrum of `x` (sampled every `dt`) up to `f_max`, Hann window,
/// its mean removed: (frequency, amplitude) per bin, the amplitude of a sine at a bin's
/// frequency read as that sine's amplitude.
fn spectrum(x: &[f64], dt: f64, f_max: f64) -> Vec<(f64, f64)> {
    let n = x.len();
    let mean = x.iter().sum::<f64>() / n as f64;
    let w: Vec<f64> = (0..n).map(|k| 0.5 - 0.5 * libm::cos(TAU * k as f64 / n as f64)).collect();
    let gain: f64 = w.iter().sum();
    let mut z: Vec<Complex<f64>> = x.iter().zip(&w).map(|(v, w)| Complex::new((v - mean) * w, 0.0)).collect();
    fft(&mut z, false);
    let df = 1.0 / (n as f64 * dt);
    let top = ((f_max / df) as usize).min(n / 2);
    (0..=top)
        .map(|k| (k as f64 * df, 2.0 * libm::sqrt(z[k].norm_sqr()) / gain))
        .collect()
}

/// The squared envelope of `x` (Randall & Antoni 2011, envelope analysis): the squared magnitude of
/// the analytic signal of `x` band-passed to `band` (Hz), where the impacts ring the bearing;
/// it repeats at the rate the impacts do.
fn squared_envelope(x: &[f64], dt: f64, band: (f64, f64)) -> Vec<f64> {
    let n = x.len();
    let mean = x.iter().sum::<f64>() / n as f64;
    let mut z: Vec<Complex<f64>> = x.iter().map(|v| Complex::new(v - mean, 0.0)).collect();
    fft(&mut z, false);
    let df = 1.0 / (n as f64 * dt);
    for (k, v) in z.iter_mut().enumerate() {
        // the analytic signal keeps the positive frequencies in the band, doubled
        let f = k as f64 * df;
        let keep = k > 0 && k < n.div_ceil(2) && f >= band.0 && f <= band.1;
        *v *= if keep { 2.0 } else { 0.0 };
    }
    fft(&mut z, true);
    z.iter().map(|v| v.norm_sqr()).collect()
}

/// A peak of `spectrum` (bins of spacing df from 0) near `f`, within `half` (Hz): the largest
/// bin, its frequency refined by a parabola through the log amplitudes of it and its two
/// neighbours, and its amplitude.
fn peak(spectrum: &[(f64, f64)], f: f64, half: f64) -> Option<(f64, f64)> {
    let df = spectrum.get(1)?.0;
    let lo = ((f - half) / df).ceil().max(1.0) as usize;
    let hi = ((f + half) / df).floor() as usize;
    if hi + 1 >= spectrum.len() || lo > hi {
        return None;
    }
    let k = (lo..=hi).max_by(|i, j| spectrum[*i].1.total_cmp(&spectrum[*j].1))?;
    let (l, m, r) = (libm::log(spectrum[k - 1].1), libm::log(spectrum[k].1), libm::log(spectrum[k + 1].1));
    let shift = 0.5 * (l - r) / (l - 2.0 * m + r);
    let shift = if shift.is_finite() { shift.clamp(-1.0, 1.0) } else { 0.0 };
    Some((spectrum[k].0 + shift * df, spectrum[k].1))
}

/// The amplitude of `spectrum` at the bin nearest `f`.
fn at(spectrum: &[(f64, f64)], f: f64) -> f64 {
    let df = spectrum[1].0;
    spectrum.get((f / df).round() as usize).map_or(f64::NAN, |p| p.1)
}

/// What one location's run gives.
struct Analysed {
    time: Vec<(f64, f64)>,
    spectrum: Vec<(f64, f64)>,
    envelope: Vec<(f64, f64)>,
}

fn analyse(r: &Run) -> Analysed {
    let n = r.signal.len();
    Analysed {
        time: (0..n).map(|k| ((k + 1) as f64 * STEP, r.signal[k])).collect(),
        spectrum: spectrum(&r.signal, STEP, 0.5 / STEP),
        envelope: spectrum(&squared_envelope(&r.signal, STEP, BAND), STEP, ENVELOPE_MAX),
    }
}

/// The points of a spectrum from `f_min` on, amplitudes below 1e-7 of the largest left out
/// (a logarithmic axis).
fn shown(spectrum: &[(f64, f64)], f_min: f64) -> Vec<(f64, f64)> {
    let top = spectrum.iter().filter(|p| p.0 >= f_min).map(|p| p.1).fold(0.0, f64::max);
    spectrum.iter().filter(|p| p.0 >= f_min && p.1 > 1e-7 * top).copied().collect()
}

/// Run the study and write `docs/defects.md` and `docs/figures/defects_*.svg`.
pub fn report(docs: &Path, quick: bool) -> Result<(), CliError> {
    let started = Instant::now();
    let (_, sensor_name, unit) = sensor(&Outputs::default());
    let figures = docs.join("figures");
    std::fs::create_dir_all(&figures).map_err(|e| CliError::failed(format!("cannot create {}: {e}", figures.display())))?;
    let w = Writer { figures };
    let duration = if quick { DURATION_QUICK } else { DURATION };
    let bearing = Bearing::preset(PRESET).map_err(|e| CliError::failed(e.to_string()))?;
    let kin = Kinematics::new(&bearing, SPEED_RPM);

    // the healthy bearing, every location, and the healthy bearing with a load zone, side by
    // side on the cores
    let cases: Vec<(i32, (f64, f64))> = std::iter::once((0, (FA, FY)))
        .chain(LOCATIONS.iter().map(|l| (l.ring, (FA, FY))))
        .chain(std::iter::once((0, LOAD_ZONE)))
        .collect();
    eprintln!(
        "running {} cases of {duration} s at fidelity 1 (the healthy bearing, {} defect location(s), the healthy bearing with a load zone)",
        cases.len(),
        LOCATIONS.len()
    );
    let runs: Vec<Run> = std::thread::scope(|scope| {
        let handles: Vec<_> = cases
            .iter()
            .map(|&(ring, loads)| scope.spawn(move || run(ring, duration, loads)))
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|_| Err(CliError::failed("a run panicked"))))
            .collect::<Result<Vec<_>, _>>()
    })?;
    let analysed: Vec<Analysed> = runs.iter().map(analyse).collect();
    let (healthy, healthy_run) = (&analysed[0], &runs[0]);
    let (zone, zone_run) = (&analysed[cases.len() - 1], &runs[cases.len() - 1]);
    let df = 1.0 / duration;
    let half = 0.4 * kin.ftf;

    let mut md = String::new();
    let _ = writeln!(
        md,
        "## The characteristic frequencies\n\n\
         From the geometry of {PRESET} at the middle slice: cone and cup contact radii r_i = {:.2} mm, \
         r_o = {:.2} mm, pitch diameter d_m = r_i + r_o = {:.2} mm, D cos α = r_o − r_i = {:.2} mm, roller \
         diameter D = {:.2} mm, Z = {} rollers; shaft rate f_s = {:.3} Hz ({SPEED_RPM} rpm). Formulas of \
         Randall & Antoni, Mech. Syst. Signal Process. 25 (2011) 485, for a fixed cup:\n",
        kin.ri * 1e3,
        kin.ro * 1e3,
        (kin.ri + kin.ro) * 1e3,
        (kin.ro - kin.ri) * 1e3,
        kin.d * 1e3,
        kin.z,
        kin.fs
    );
    let rows = vec![
        vec!["f_s, shaft rate".into(), "speed / 60".into(), f(kin.fs, 3)],
        vec!["FTF, cage".into(), "(f_s / 2)(1 − D cos α / d_m)".into(), f(kin.ftf, 3)],
        vec![
            "BPFO, outer race (cup)".into(),
            "(Z f_s / 2)(1 − D cos α / d_m)".into(),
            f(kin.bpfo, 3),
        ],
        vec![
            "BPFI, inner race (cone)".into(),
            "(Z f_s / 2)(1 + D cos α / d_m)".into(),
            f(kin.bpfi, 3),
        ],
        vec![
            "BSF, roller spin".into(),
            "(d_m / 2D) f_s (1 − (D cos α / d_m)²)".into(),
            f(kin.bsf, 3),
        ],
        vec!["2 × BSF, a roller defect".into(), "".into(), f(2.0 * kin.bsf, 3)],
        vec!["Z × FTF, varying compliance".into(), "".into(), f(kin.compliance(), 3)],
    ];
    md.push_str(&table(&["line", "formula", "frequency (Hz)"], &rows));
    let expect = |ls: Vec<Line>| {
        ls.iter()
            .map(|l| format!("{} ({:.1} Hz)", l.label, l.f))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let _ = writeln!(
        md,
        "\nWhere the envelope of a defect's signal should peak: cup {}; cone {}; roller {}.\n",
        expect(kin.cup_lines()),
        expect(kin.cone_lines()),
        expect(kin.roller_lines())
    );

    let mut marks = kin.marks();
    marks.retain(|m| m.x > 0.0);
    for (loc, (a, r)) in LOCATIONS.iter().zip(analysed.iter().zip(&runs).skip(1)) {
        let _ = writeln!(
            md,
            "## {}\n\n`defect.ring` = {}: the spall (`defect.angle` = 0, where the radial load is at t = 0; 1.5 mm long, \
             10 mm wide, 0.1 mm deep, sharp edges). Wall time {:.1} s against {:.1} s for the healthy bearing \
             ({duration} s simulated each).\n",
            loc.title, loc.ring, r.wall, healthy_run.wall
        );
        // the first 20 ms (about nine roller passes), about the run's mean
        let window = |t: &[(f64, f64)]| -> Vec<(f64, f64)> {
            let mean = t.iter().map(|p| p.1).sum::<f64>() / t.len() as f64;
            t.iter().filter(|p| p.0 <= 0.02).map(|p| (p.0 * 1e3, p.1 - mean)).collect()
        };
        md.push_str(&w.figure(
            &format!("defects_{}_time.svg", loc.key),
            svg::line_chart(
                &format!("{}: {} against time", loc.title, sensor_name),
                "time (ms)",
                &format!("{} about its mean ({})", sensor_name, unit),
                &[
                    Series::line("defect", window(&a.time)),
                    Series::line("healthy", window(&healthy.time)),
                ],
                false,
            ),
        )?);
        md.push_str(&w.figure(
            &format!("defects_{}_spectrum.svg", loc.key),
            svg::marked_chart(
                &format!("{}: spectrum of {} (Hann)", loc.title, sensor_name),
                "frequency (Hz)",
                &format!("amplitude ({})", unit),
                &[
                    Series::line("defect", shown(&a.spectrum, 10.0)),
                    Series::line("healthy", shown(&healthy.spectrum, 10.0)),
                ],
                &marks,
                true,
                true,
            ),
        )?);
        md.push_str(&w.figure(
            &format!("defects_{}_envelope.svg", loc.key),
            svg::marked_chart(
                &format!("{}: envelope spectrum", loc.title),
                "frequency (Hz)",
                &format!("squared envelope amplitude (({})²)", unit),
                &[
                    Series::line("defect", shown(&a.envelope, 5.0)),
                    Series::line("healthy", shown(&healthy.envelope, 5.0)),
                ],
                &marks,
                false,
                true,
            ),
        )?);
        let _ = writeln!(
            md,
            "\nPeaks of the envelope spectrum (the squared envelope of {} band-passed to {:.0}–{:.0} Hz; Hann window, \
             {df:.0} Hz bins, the largest bin within ±{half:.1} Hz of the kinematic line, its frequency refined by a \
             parabola through the log amplitudes of three bins):\n",
            sensor_name, BAND.0, BAND.1
        );
        let rows: Vec<Vec<String>> = (loc.lines)(&kin)
            .iter()
            .map(|l| match peak(&a.envelope, l.f, half) {
                Some((fp, amp)) => vec![
                    l.label.clone(),
                    f(l.f, 2),
                    f(fp, 2),
                    f(pct(fp, l.f), 2),
                    format!("{amp:.3e}"),
                    format!("{:.3e}", at(&healthy.envelope, fp)),
                    f(amp / at(&healthy.envelope, fp), 0),
                ],
                None => vec![
                    l.label.clone(),
                    f(l.f, 2),
                    "-".into(),
                    "-".into(),
                    "-".into(),
                    "-".into(),
                    "-".into(),
                ],
            })
            .collect();
        md.push_str(&table(
            &[
                "line",
                "kinematic (Hz)",
                "peak (Hz)",
                "error (%)",
                &format!("amplitude (({})²)", unit),
                "healthy there",
                "defect / healthy",
            ],
            &rows,
        ));
        md.push('\n');
    }

    // the healthy bearing's own line, with a load zone
    let measured = kin.z as f64 * zone_run.cage_rate;
    let healthy_rows: Vec<Vec<String>> = [
        ("Z × FTF (kinematic)", kin.compliance()),
        ("Z × mean `cage.speed` / 2π (the model's cage)", measured),
    ]
    .iter()
    .map(|(label, fl)| match peak(&zone.spectrum, *fl, half) {
        Some((fp, amp)) => vec![label.to_string(), f(*fl, 2), f(fp, 2), f(pct(fp, *fl), 2), format!("{amp:.3e}")],
        None => vec![label.to_string(), f(*fl, 2), "-".into(), "-".into(), "-".into()],
    })
    .collect();
    let _ = writeln!(
        md,
        "## The healthy bearing\n\n\
         Without a defect the signal rings at the rollers' pass over the load line, Z × FTF, the bearing's varying \
         compliance (the same frequency as BPFO for a fixed cup). It rings clearly where the bearing has a load zone: \
         the healthy bearing under Fa = {:.0} kN and Fy = {:.0} kN, the peak of its spectrum of {} near the line \
         ({df:.0} Hz bins, Hann window, refined as above):\n",
        LOAD_ZONE.0 / 1e3,
        LOAD_ZONE.1 / 1e3,
        sensor_name
    );
    md.push_str(&table(
        &["line", "frequency (Hz)", "peak (Hz)", "error (%)", &format!("amplitude ({})", unit)],
        &healthy_rows,
    ));

    let wall = started.elapsed().as_secs_f64();
    let doc = format!(
        "# The vibration signature of local defects\n\n\
         Written by `cargo run --release -- study defects{}` (src/cli/study/defects.rs); do not edit by hand. \
         {PRESET} at {SPEED_RPM} rpm under Fa = {:.0} kN and Fy = {:.0} kN (the radial load along azimuth 0; every roller loaded around the orbit), \
         the dynamic model (`fidelity` = 1) at the preset's settings, {duration} s per run sampled at {:.0} kHz \
         (communication step {:.0} µs), the cup on a {HOUSING_MASS} kg housing on the default support \
         (`housing.mass`; docs/model.md, \"The housing\"). The signal is the output `{}` (docs/variables.md), \
         what an accelerometer on the housing reads. Each defect location \
         (cup, cone, roller 1) runs with a spall where the radial load is at t = 0, and the healthy bearing under the \
         same load as reference (docs/model.md, \"Local defects\").\n\n\
         The spectra are one-sided amplitude spectra of the whole run with a Hann window (a sine of amplitude A \
         reads A at its bin). The envelope is the squared envelope (Randall & Antoni 2011): the \
         signal band-passed to {:.0}–{:.0} Hz, where the impacts ring the bearing, made analytic, and its squared \
         magnitude; its spectrum shows the rate at which the impacts repeat. The signal is the output at the \
         communication points, not filtered: content above {:.0} kHz (the roller contacts ring up to there and \
         beyond) folds back into the spectrum, as with a sensor sampled without an anti-aliasing filter.\n\n\
         Run: {}, commit {}, {}; {} mode, {wall:.0} s wall time.\n\n{md}",
        if quick { " --quick" } else { "" },
        FA / 1e3,
        FY / 1e3,
        1e-3 / STEP,
        STEP * 1e6,
        sensor_name,
        BAND.0,
        BAND.1,
        0.5e-3 / STEP,
        report::date(),
        report::commit(),
        report::machine(),
        if quick { "quick" } else { "full" },
    );
    let path = docs.join("defects.md");
    std::fs::write(&path, doc).map_err(|e| CliError::failed(format!("cannot write {}: {e}", path.display())))?;
    println!("wrote {} and {}/defects_*.svg ({wall:.0} s)", path.display(), w.figures.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sine's amplitude and frequency, off the bins, come back from the spectrum and the
    /// peak's parabola.
    #[test]
    fn a_sine_comes_back_at_its_frequency_and_amplitude() {
        let (dt, n, f0) = (STEP, 2000, 437.3);
        let x: Vec<f64> = (0..n).map(|k| 3.0 + 2.0 * libm::sin(TAU * f0 * k as f64 * dt)).collect();
        let s = spectrum(&x, dt, 2000.0);
        let (fp, amp) = peak(&s, f0, 10.0).unwrap();
        assert!((fp - f0).abs() < 0.2, "{fp}");
        assert!((amp / 2.0 - 1.0).abs() < 0.16, "{amp}");
    }

    /// The squared envelope of a carrier in the band, modulated at a low rate, holds that rate.
    #[test]
    fn the_envelope_of_a_modulated_carrier_repeats_at_the_modulation() {
        let (dt, n, fm) = (STEP, 2000, 120.0);
        let x: Vec<f64> = (0..n)
            .map(|k| {
                let t = k as f64 * dt;
                (1.0 + 0.5 * libm::cos(TAU * fm * t)) * libm::sin(TAU * 3000.0 * t)
            })
            .collect();
        let e = spectrum(&squared_envelope(&x, dt, BAND), dt, 1000.0);
        let (fp, _) = peak(&e, fm, 30.0).unwrap();
        assert!((fp - fm).abs() < 0.5, "{fp}");
    }

    /// The kinematic formulas agree with rolling without slip on the contact radii.
    #[test]
    fn the_formulas_are_rolling_without_slip() {
        let b = Bearing::preset(PRESET).unwrap();
        let k = Kinematics::new(&b, SPEED_RPM);
        let dm = k.ri + k.ro;
        assert!((k.ftf / (k.fs * k.ri / dm) - 1.0).abs() < 1e-12);
        assert!((k.bpfi / (k.z as f64 * k.fs * k.ro / dm) - 1.0).abs() < 1e-12);
        assert!((k.bsf / (2.0 * k.fs * k.ri * k.ro / (k.d * dm)) - 1.0).abs() < 1e-12);
    }
}
