//! Criterion benchmarks of the quasi-static model (fidelity 0): one co-simulation step
//! (`Simulation::do_step`: cage advance + Newton equilibrium + friction torque) for the
//! default bearing at 20 slices, in the axisymmetric [W25] case and under combined load
//! with misalignment (rollers move through the load zone every step), and the [D19] case.
//!
//! Run: `cargo bench --bench quasi_static`. Results are reported in docs/performance.md.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use trb::bearing::Bearing;
use trb::simulation::Simulation;
use trb::variables as var;

fn stepping(name: &str, setup: &[(u32, f64)]) -> impl FnMut() {
    stepping_int(name, setup, var::FIDELITY, 0)
}

/// [`stepping`] with one Integer parameter set too.
fn stepping_int(name: &str, setup: &[(u32, f64)], vr: u32, value: i32) -> impl FnMut() {
    let mut sim = Simulation::new(Bearing::preset(name).unwrap());
    sim.set_integer(vr, value).unwrap();
    for (vr, v) in setup {
        sim.set_real(*vr, *v).unwrap();
    }
    sim.initialize(0.0).unwrap();
    let h = 1e-3;
    let mut t = 0.0;
    // settle the warm start
    for _ in 0..10 {
        sim.do_step(t, h).unwrap();
        t += h;
    }
    move || {
        sim.do_step(t, h).unwrap();
        t += h;
        black_box(sim.last_outputs().friction_torque);
    }
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("quasi_static_do_step");
    let mut f = stepping("TRB130x230", &[]);
    g.bench_function("TRB130x230_axial_30kN_3500rpm_20slices", |b| b.iter(&mut f));
    let mut f = stepping("TRB130x230", &[(var::FY, 10_000.0), (var::XI, 0.004_f64.to_radians())]);
    g.bench_function("TRB130x230_combined_Fy10kN_xi0.004deg_20slices", |b| b.iter(&mut f));
    let mut f = stepping("32018X", &[]);
    g.bench_function("32018X_D19_radial35kN_axial12970N_20slices", |b| b.iter(&mut f));
    // the combined-load and dry cases of the other presets (tests/qs_speed.rs)
    let mut f = stepping("TRB130x230", &[(var::FY, 10_000.0)]);
    g.bench_function("TRB130x230_combined_Fy10kN_20slices", |b| b.iter(&mut f));
    let mut f = stepping_int("TRB130x230", &[(var::FY, 10_000.0)], var::LUBRICATION, 1);
    g.bench_function("TRB130x230_dry_Fy10kN_20slices", |b| b.iter(&mut f));
    let mut f = stepping("32008", &[(var::FY, 5_000.0)]);
    g.bench_function("32008_combined_Fy5kN_20slices", |b| b.iter(&mut f));
    let mut f = stepping("CRB-TRILOBE", &[(var::FY, 1_000.0)]);
    g.bench_function("CRB-TRILOBE_combined_Fy1kN_20slices", |b| b.iter(&mut f));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
