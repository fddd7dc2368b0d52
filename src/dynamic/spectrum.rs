//! Where the dynamic model's stiffness sits: the eigenvalues of the
//! right-hand side's Jacobian on a settled state, each assigned to the group of degrees of
//! freedom its eigenvector lives in, and the largest step each group allows the default
//! integrator (Dormand–Prince 5(4): |R(h λ)| ≤ 1 with R(z) = Σ_{k≤5} z^k/k! + z^6/600, the
//! stability function of its fifth-order solution, Hairer, Nørsett & Wanner I, II.4).
//!
//! Method: central differences of the RHS in the coordinates the error control sees
//! (each state divided by its absolute tolerance, so the eigenvectors compare like with like);
//! eigenvalues by the real Schur form (nalgebra); each eigenvector by one inverse iteration
//! with a shifted complex LU; participation of a group = the share of |v|² on its states.
//!
//! Run: `cargo test --release --lib dynamic::spectrum -- --ignored --nocapture`
//! (`SPECTRUM_CASE` = w25 (default) | combined | dry; `SPECTRUM_SETTLE` = seconds of settling).

use super::{tolerances, Dynamic, CAGE, PER_ROLLER, ROLLERS};
use crate::bearing::Bearing;
use crate::model::{Fidelity, Inputs, Lubrication, Parameters};
use nalgebra::{Complex, DMatrix, DVector};

/// The groups of degrees of freedom, by state index.
fn group_of(i: usize) -> usize {
    if i < CAGE {
        0
    } else if i < ROLLERS {
        1
    } else {
        match (i - ROLLERS) % PER_ROLLER {
            0 | 1 | 3 | 4 => 2, // x, dr and rates: the contact normal directions
            2 | 5 => 3,         // psi, psi': the orbit (traction, cage pocket)
            6 => 4,             // tilt
            7 => 5,             // skew
            8 => 6,             // w_x: about the bearing axis (spin)
            9 => 7,             // w_r: skew rate
            _ => 8,             // w_t: tilt rate
        }
    }
}

const GROUPS: [&str; 9] = [
    "cone translation (x, y, z, rates)",
    "cage (y, z, psi, rates)",
    "roller x, dr and rates (raceway normal)",
    "roller orbit psi, psi'",
    "roller tilt angle",
    "roller skew angle",
    "roller w_x (spin about the bearing axis)",
    "roller w_r",
    "roller w_t",
];

/// Dormand–Prince 5(4)'s stability function (its fifth-order solution).
fn dopri_r(z: Complex<f64>) -> f64 {
    let mut term = Complex::new(1.0, 0.0);
    let mut sum = term;
    for k in 1..=5 {
        term = term * z / k as f64;
        sum += term;
    }
    (sum + z.powi(6) / 600.0).norm()
}

/// The largest h with |R(h λ)| ≤ 1 along the ray from 0 (bisection after a geometric
/// search). A mode that does not decay (Re λ ≥ 0: the free azimuth of cage and rollers, to
/// rounding) sets no stability limit: the method follows it.
fn dopri_step_limit(lambda: Complex<f64>) -> f64 {
    if lambda.re >= 0.0 {
        return f64::INFINITY;
    }
    let unit = 1.0 / lambda.norm();
    let mut hi = unit * 0.01;
    while dopri_r(lambda * hi) <= 1.0 + 1e-12 {
        hi *= 1.5;
        if hi > unit * 100.0 {
            return f64::INFINITY; // not on this ray: a growing mode the method follows
        }
    }
    let mut lo = 0.0;
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if dopri_r(lambda * mid) <= 1.0 + 1e-12 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

#[test]
#[ignore]
fn eigenvalues_by_group() {
    let case = std::env::var("SPECTRUM_CASE").unwrap_or_else(|_| "w25".into());
    let settle: f64 = std::env::var("SPECTRUM_SETTLE").ok().and_then(|s| s.parse().ok()).unwrap_or(0.02);
    let b = Bearing::preset("TRB130x230").unwrap();
    let mut p = Parameters::from_bearing(&b);
    p.fidelity = Fidelity::Dynamic;
    let mut inputs = Inputs::from_bearing(&b);
    inputs.fx = 30e3;
    match case.as_str() {
        "combined" => {
            inputs.fy = 10e3;
            inputs.xi = 0.004_f64.to_radians();
        }
        "dry" => {
            p.lubrication = Lubrication::Dry;
            inputs.fy = 5e3;
        }
        _ => {}
    }
    let (mut d, mut st) = Dynamic::at_quasi_static_start(&b, &p, &inputs).unwrap();
    let steps0 = st.counters.steps;
    d.advance(&mut st, &inputs, settle).unwrap();
    let mean_step = settle / (st.counters.steps - steps0).max(1) as f64;
    let n = st.y.len();
    let (atol, _) = tolerances(&d.g, &d.c, &d.p, inputs.speed.abs());
    // Jacobian of the scaled system s = y / atol: J_s = D^-1 J D
    let mut f1 = vec![0.0; n];
    let mut f2 = vec![0.0; n];
    let mut y = st.y.clone();
    let mut j = DMatrix::<f64>::zeros(n, n);
    for c in 0..n {
        let e = 1e-6 * atol[c] / d.p.tolerance.max(1e-12);
        y[c] = st.y[c] + e;
        d.rhs(&inputs, &y, &mut f1);
        y[c] = st.y[c] - e;
        d.rhs(&inputs, &y, &mut f2);
        y[c] = st.y[c];
        for r in 0..n {
            j[(r, c)] = (f1[r] - f2[r]) / (2.0 * e) * atol[c] / atol[r];
        }
    }
    let eig = j.clone().complex_eigenvalues();
    let jc: DMatrix<Complex<f64>> = j.map(|v| Complex::new(v, 0.0));
    // per eigenvalue: its group (largest share of |v|^2), the share, the step limit
    let mut rows: Vec<(Complex<f64>, usize, f64, f64)> = Vec::with_capacity(n);
    for lambda in eig.iter() {
        let shift = *lambda * Complex::new(1.0 + 1e-9, 1e-9) + Complex::new(1e-9, 0.0);
        let a = &jc - DMatrix::<Complex<f64>>::identity(n, n) * shift;
        let lu = a.lu();
        let mut v = DVector::<Complex<f64>>::from_element(n, Complex::new(1.0, 0.3));
        for _ in 0..2 {
            if let Some(w) = lu.solve(&v) {
                let norm = w.norm();
                v = w / Complex::new(norm, 0.0);
            }
        }
        let mut share = [0.0; GROUPS.len()];
        for (i, vi) in v.iter().enumerate() {
            share[group_of(i)] += vi.norm_sqr();
        }
        let total: f64 = share.iter().sum();
        let (g, s) = share
            .iter()
            .enumerate()
            .fold((0, 0.0), |b, (g, s)| if *s > b.1 { (g, *s) } else { b });
        rows.push((*lambda, g, s / total, dopri_step_limit(*lambda)));
    }
    println!(
        "case {case}: {n} states, settled {settle} s (Dormand–Prince mean step {:.3e} s over the settling), tolerance {:.0e}",
        mean_step, d.p.tolerance
    );
    println!("| group | eigenvalues | largest abs | real part range | imaginary range | DP5 step limit |");
    println!("|---|---|---|---|---|---|");
    for (g, name) in GROUPS.iter().enumerate() {
        let sel: Vec<_> = rows.iter().filter(|r| r.1 == g).collect();
        if sel.is_empty() {
            println!("| {name} | 0 | | | | |");
            continue;
        }
        let big = sel.iter().map(|r| r.0.norm()).fold(0.0, f64::max);
        let re = sel
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |a, r| (a.0.min(r.0.re), a.1.max(r.0.re)));
        let im = sel.iter().map(|r| r.0.im.abs()).fold(0.0, f64::max);
        let h = sel.iter().map(|r| r.3).fold(f64::INFINITY, f64::min);
        let mean_share = sel.iter().map(|r| r.2).sum::<f64>() / sel.len() as f64;
        println!(
            "| {name} | {} (mean share {:.0} %) | {big:.2e} | [{:.2e}, {:.2e}] | {im:.2e} | {h:.2e} s |",
            sel.len(),
            100.0 * mean_share,
            re.0,
            re.1
        );
    }
    let mut by_limit: Vec<_> = rows.iter().collect();
    by_limit.sort_by(|a, b| a.3.partial_cmp(&b.3).unwrap());
    println!("the ten eigenvalues that limit the explicit step most:");
    for r in by_limit.iter().take(10) {
        println!(
            "  {:11.3e} {:+11.3e}i  |{:.2e}|  {}  ({:.0} %)  h_max {:.3e} s",
            r.0.re,
            r.0.im,
            r.0.norm(),
            GROUPS[r.1],
            100.0 * r.2,
            r.3
        );
    }
    let unstable = rows.iter().filter(|r| r.0.re > 1.0).count();
    println!("eigenvalues with a real part above 1/s: {unstable}");
    // the step limit is a property of the spectrum, the measured step of the run: the
    // integrator cannot step beyond the smallest limit for long
    let h_min = by_limit[0].3;
    println!("mean step / smallest stability limit = {:.3}", mean_step / h_min);
    assert!(
        mean_step <= 2.0 * h_min,
        "mean step {mean_step:.3e} s against the stability limit {h_min:.3e} s"
    );
}
