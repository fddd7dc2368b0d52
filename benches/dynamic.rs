//! Criterion benchmarks of the dynamic model's kernel (fidelity 1): one right-hand-side
//! evaluation (all contact forces, film and traction of 17 rollers x 20 slices x 2 raceways,
//! flanges, cage pockets and land, and the accelerations) for the default bearing at the
//! quasi-static start state of the [W25] case and under combined load, on one thread and on
//! two (`threads` = 2).
//!
//! Run: `cargo bench --bench dynamic`. The `bench` command measures the same kernel for the
//! report in docs/performance.md.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use trb::bearing::Bearing;
use trb::dynamic::Dynamic;
use trb::model::{Fidelity, Inputs, Parameters};

/// One right-hand side at the quasi-static start state with radial load `fy`, the rollers on
/// `threads` threads.
fn rhs(fy: f64, threads: u32) -> impl FnMut() {
    let b = Bearing::default_preset();
    let mut p = Parameters::from_bearing(&b);
    p.fidelity = Fidelity::Dynamic;
    p.threads = threads;
    let mut i = Inputs::from_bearing(&b);
    i.fy = fy;
    let (mut d, st) = Dynamic::at_quasi_static_start(&b, &p, &i).unwrap();
    let mut dy = vec![0.0; st.y.len()];
    move || {
        d.rhs(&i, &st.y, &mut dy);
        black_box(&dy);
    }
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("dynamic_rhs");
    let mut f = rhs(0.0, 1);
    g.bench_function("TRB130x230_axial_30kN_3500rpm_20slices", |b| b.iter(&mut f));
    let mut f = rhs(25_000.0, 1);
    g.bench_function("TRB130x230_combined_Fy25kN_20slices", |b| b.iter(&mut f));
    // the same on two threads (parameter `threads`), the ratio measured in the same run
    let mut f = rhs(0.0, 2);
    g.bench_function("TRB130x230_axial_30kN_3500rpm_20slices_2threads", |b| b.iter(&mut f));
    let mut f = rhs(25_000.0, 2);
    g.bench_function("TRB130x230_combined_Fy25kN_20slices_2threads", |b| b.iter(&mut f));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
