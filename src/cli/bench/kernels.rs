//! Timed kernels of the targets table: one right-hand-side evaluation of the
//! dynamic model, one quasi-static doStep, and the FMI adapter's bookkeeping per doStep
//! (fmi2DoStep through the C ABI minus `Simulation::do_step` on an identical element).
//! Each is the median over samples of many calls (criterion measures the same kernels in
//! `benches/`; this is the self-contained version the report needs).

use super::precision::median;
use std::ffi::CString;
use std::time::Instant;
use trb::bearing::Bearing;
use trb::dynamic::Dynamic;
use trb::fmi::exports as fmi;
use trb::fmi::types::{Fmi2CallbackFunctions, FMI2_CO_SIMULATION, FMI2_FALSE, FMI2_OK};
use trb::model::{Fidelity, Inputs, Parameters};
use trb::simulation::Simulation;

/// Median seconds per call of `f`, from `samples` samples of `calls` calls each.
fn per_call(samples: usize, calls: usize, mut f: impl FnMut()) -> f64 {
    let mut t = Vec::with_capacity(samples);
    for _ in 0..samples {
        let started = Instant::now();
        for _ in 0..calls {
            f();
        }
        t.push(started.elapsed().as_secs_f64() / calls as f64);
    }
    median(&t)
}

/// Median seconds of one dynamic right-hand side of the default bearing (the [W25] case:
/// 3500 rpm, Fa 30 kN) with `slices` slices and the radial load `fy`, at the quasi-static
/// start state.
pub fn rhs_seconds(slices: usize, fy: f64, quick: bool) -> Result<f64, String> {
    let b = Bearing::default_preset();
    let mut p = Parameters::from_bearing(&b);
    p.fidelity = Fidelity::Dynamic;
    p.slices = slices;
    let mut i = Inputs::from_bearing(&b);
    i.fy = fy;
    let (mut d, st) = Dynamic::at_quasi_static_start(&b, &p, &i).map_err(|e| e.to_string())?;
    let mut dy = vec![0.0; st.y.len()];
    let (samples, calls) = if quick { (3, 20) } else { (15, 200) };
    Ok(per_call(samples, calls, || {
        d.rhs(&i, &st.y, &mut dy);
        std::hint::black_box(&dy);
    }))
}

/// A default element (the [W25] case at fidelity 0) initialized and stepped 10 times (warm start).
fn settled_simulation() -> Result<(Simulation, f64), String> {
    let mut sim = Simulation::new(Bearing::default_preset());
    sim.initialize(0.0).map_err(|e| e.to_string())?;
    let h = 1e-3;
    let mut t = 0.0;
    for _ in 0..10 {
        sim.do_step(t, h).map_err(|e| e.to_string())?;
        t += h;
    }
    Ok((sim, t))
}

/// Median seconds of one quasi-static `Simulation::do_step` of the default bearing (the
/// [W25] case, 20 slices, communication step 1 ms).
pub fn quasi_static_step_seconds(quick: bool) -> Result<f64, String> {
    let (mut sim, mut t) = settled_simulation()?;
    let h = 1e-3;
    let mut failed = None;
    let (samples, calls) = if quick { (3, 200) } else { (21, 2000) };
    let s = per_call(samples, calls, || {
        if let Err(e) = sim.do_step(t, h) {
            failed = Some(e.to_string());
        }
        t += h;
    });
    failed.map_or(Ok(s), Err)
}

/// What the FMI adapter adds to one doStep (seconds).
pub struct Bookkeeping {
    /// Median of fmi2DoStep through the exported C function.
    pub through_fmi: f64,
    /// Median of `Simulation::do_step` on an element in the same state.
    pub direct: f64,
    /// The adapter's share: the difference of the two fastest samples (the least disturbed
    /// by the machine), and half the interquartile range of the paired differences of
    /// alternating samples (the resolution of the measurement on this machine).
    pub added: f64,
    pub spread: f64,
}

/// Times fmi2DoStep against `Simulation::do_step` on the default element ([W25] case,
/// fidelity 0, 1 ms steps), alternating samples.
pub fn fmi_do_step_seconds(quick: bool) -> Result<Bookkeeping, String> {
    let bearing = Bearing::default_preset();
    let guid = CString::new(trb::model_description::guid(&bearing)).map_err(|e| e.to_string())?;
    let name = CString::new("bench").map_err(|e| e.to_string())?;
    let callbacks = Fmi2CallbackFunctions {
        logger: None,
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: std::ptr::null_mut(),
    };
    // SAFETY: valid C strings and callbacks that outlive the instance; the resource location
    // may be NULL (the compiled-in preset); the instance is freed below.
    let c = unsafe {
        fmi::fmi2Instantiate(
            name.as_ptr(),
            FMI2_CO_SIMULATION,
            guid.as_ptr(),
            std::ptr::null(),
            &callbacks,
            FMI2_FALSE,
            FMI2_FALSE,
        )
    };
    if c.is_null() {
        return Err("fmi2Instantiate returned NULL".into());
    }
    let h = 1e-3;
    let mut t = 0.0;
    let mut ok = true;
    // SAFETY: `c` is a live instance until fmi2FreeInstance at the end.
    unsafe {
        ok &= fmi::fmi2SetupExperiment(c, FMI2_FALSE, 0.0, 0.0, FMI2_FALSE, 0.0) == FMI2_OK;
        ok &= fmi::fmi2EnterInitializationMode(c) == FMI2_OK;
        ok &= fmi::fmi2ExitInitializationMode(c) == FMI2_OK;
        for _ in 0..10 {
            ok &= fmi::fmi2DoStep(c, t, h, FMI2_FALSE) == FMI2_OK;
            t += h;
        }
    }
    let (mut sim, mut t_sim) = settled_simulation()?;
    let (samples, calls) = if quick { (5, 200) } else { (41, 2000) };
    let (mut through_fmi, mut direct) = (Vec::new(), Vec::new());
    for _ in 0..samples {
        through_fmi.push(per_call(1, calls, || {
            // SAFETY: as above.
            ok &= unsafe { fmi::fmi2DoStep(c, t, h, FMI2_FALSE) } == FMI2_OK;
            t += h;
        }));
        direct.push(per_call(1, calls, || {
            ok &= sim.do_step(t_sim, h).is_ok();
            t_sim += h;
        }));
    }
    // SAFETY: frees the instance made above, once.
    unsafe { fmi::fmi2FreeInstance(c) };
    if !ok {
        return Err("a doStep of the bookkeeping benchmark failed".into());
    }
    let mut paired: Vec<f64> = through_fmi.iter().zip(&direct).map(|(a, b)| a - b).collect();
    paired.sort_by(f64::total_cmp);
    let quartile = |q: f64| paired[((paired.len() - 1) as f64 * q).round() as usize];
    let fastest = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
    Ok(Bookkeeping {
        through_fmi: median(&through_fmi),
        direct: median(&direct),
        added: fastest(&through_fmi) - fastest(&direct),
        spread: 0.5 * (quartile(0.75) - quartile(0.25)),
    })
}
