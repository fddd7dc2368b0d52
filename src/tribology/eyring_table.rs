//! The thermal Eyring film equation's root as a table, the start of the lane kernels' single
//! Halley step (`pair_lanes.rs`).
//!
//! The shear stress of the heated Eyring film is tau = tau_0 y, where y solves
//! y = asinh(X e^(-B y)) (`traction.rs`: Eyring 1936 with the film's shear heating, the form
//! Johnson & Greenwood, Wear 61 (1980) 353 solve across the film; X = eta gamma_dot / tau_0,
//! B = beta_p tau_0 dT / tau). The root depends on ln X and B alone, whatever the oil, so one
//! table serves every contact. It holds y at the nodes of a grid in ln X (step 1/4, -12 to
//! 12.25) and in c = 1 / (1 + B) (step 1/32, 0.125 to 1.0625: B from 7 down to a little
//! below zero). In c the large-X branch y = ln(2X) / (1 + B) is linear, so a cubic in c
//! follows it where a cubic in B would not (1/(1 + B) has large derivatives near B = 0).
//! Below the table (X < e^-12, B <= 7) the small-X closed form X / (1 + B X) is within
//! (B X)^2 / 2 < 1e-9 of the root and serves as the start of the same single step.
//!
//! Read by bicubic Lagrange interpolation (the 4 x 4 nodes around a point), the table gives y
//! within 1.3e-4 of the root (relative, over the grid's cells), and one Halley step from
//! there, whose error is of the cube of its start's, within 1e-14 (the test below samples
//! the cells). Where the iterative solver (`traction::solve_thermal_eyring_halley`) takes 2
//! or 3 evaluations of asinh(e^g) (an exponential, a square root, a logarithm and two
//! divisions each) to reach and confirm the root, the table and one step take one.
//!
//! Each node stores the four values of its column of the stencil (c nodes j - 1 .. j + 2),
//! so a point's 16 values are contiguous: two eight-value loads per lane
//! (`simd_math::F4::gather8_at`), built once per process (about 1.5 ms) from
//! the pure-Rust `libm` (the same bits on every platform).
//!
//! Grid: 100 x 32 nodes, 4 values each (102 kB).

use std::sync::OnceLock;

#[cfg(test)]
use crate::fastmath::lagrange4_weights as weights;

/// First node of the grid in ln X, its step and the nodes.
pub(crate) const FIRST_LN_X: f64 = -12.25;
pub(crate) const STEP_LN_X: f64 = 0.25;
pub(crate) const NODES_LN_X: usize = 100;
/// First node of the grid in c = 1 / (1 + B), its step and the nodes.
pub(crate) const FIRST_C: f64 = 0.125 - STEP_C;
pub(crate) const STEP_C: f64 = 1.0 / 32.0;
pub(crate) const NODES_C: usize = 32;

/// The table: at 4 (j NODES_LN_X + i) + r the root at ln X node i and c node j - 1 + r
/// (j in 1 ..= NODES_C - 3; other j hold zeros and are never read).
pub(crate) fn table() -> &'static [f64] {
    static TABLE: OnceLock<Vec<f64>> = OnceLock::new();
    TABLE.get_or_init(|| {
        // the roots at the nodes, c major
        let nodes: Vec<f64> = (0..NODES_C * NODES_LN_X)
            .map(|n| {
                root(
                    FIRST_LN_X + (n % NODES_LN_X) as f64 * STEP_LN_X,
                    1.0 / (FIRST_C + (n / NODES_LN_X) as f64 * STEP_C) - 1.0,
                )
            })
            .collect();
        let mut t = vec![0.0; 4 * NODES_LN_X * NODES_C];
        for j in 1..NODES_C - 2 {
            for i in 0..NODES_LN_X {
                for r in 0..4 {
                    t[4 * (j * NODES_LN_X + i) + r] = nodes[(j + r - 1) * NODES_LN_X + i];
                }
            }
        }
        t
    })
}

/// The root of y = asinh(e^(ln_x - b y)) to rounding, for b > -0.5 (f' = 1 + b e^u /
/// sqrt(1 + e^2u) >= 1 - |b| > 0: one root), by Halley's method from the regimes' closed
/// forms (f'' = -b^2 e^u / (1 + e^2u)^(3/2)).
fn root(ln_x: f64, b: f64) -> f64 {
    let mut y = if ln_x > 0.0 {
        (ln_x + std::f64::consts::LN_2) / (1.0 + b)
    } else {
        let x = libm::exp(ln_x);
        x / (1.0 + b * x)
    };
    for _ in 0..100 {
        let x = libm::exp(ln_x - b * y);
        let dz = x / libm::sqrt(1.0 + x * x);
        let f = y - libm::asinh(x);
        let (d1, d2) = (1.0 + b * dz, -b * b * dz / (1.0 + x * x));
        let step = 2.0 * f * d1 / (2.0 * d1 * d1 - f * d2);
        y -= step;
        if step.abs() <= 1e-16 * y.abs() {
            break;
        }
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One Halley step from `y` (as `pair_lanes.rs` takes it, with libm's asinh).
    fn halley_step(ln_x: f64, b: f64, y: f64) -> f64 {
        let x = libm::exp(ln_x - b * y);
        let (f, dz) = (y - libm::asinh(x), x / libm::sqrt(1.0 + x * x));
        let (d1, d2) = (1.0 + b * dz, -b * b * dz / (1.0 + x * x));
        y - 2.0 * f * d1 / (2.0 * d1 * d1 - f * d2)
    }

    /// The table read by bicubic interpolation and one Halley step (as the lane kernels take
    /// it) against the root: within 1e-14, relative, at 40 points in every cell of the grid's
    /// range (the start within 2e-4); the law's iterative solver within 3e-12 of the same root;
    /// below the table (ln X from -42 to -12, B to 7) the closed form and one step within 1e-14.
    #[test]
    fn one_halley_step_from_the_table_meets_the_root() {
        let t = table();
        let (mut worst_start, mut worst, mut worst_law): (f64, f64, f64) = (0.0, 0.0, 0.0);
        let mut state = 0x2545f4914f6cdd1d_u64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for i in 1..NODES_LN_X - 2 {
            for j in 1..NODES_C - 3 {
                for _ in 0..40 {
                    let (tg, tc) = (uniform(), uniform());
                    let ln_x = FIRST_LN_X + (i as f64 + tg) * STEP_LN_X;
                    let c = FIRST_C + (j as f64 + tc) * STEP_C;
                    if !(ln_x >= FIRST_LN_X + STEP_LN_X && c <= 1.0) {
                        continue;
                    }
                    let b = 1.0 / c - 1.0;
                    let (wg, wc) = (weights(tg), weights(tc));
                    let mut y0 = 0.0;
                    for (a, wa) in wg.iter().enumerate() {
                        let v = &t[4 * (j * NODES_LN_X + i + a - 1)..];
                        y0 += wa * (wc[0] * v[0] + wc[1] * v[1] + wc[2] * v[2] + wc[3] * v[3]);
                    }
                    let y1 = halley_step(ln_x, b, y0);
                    let exact = root(ln_x, b);
                    // the law's own solver, whose asinh takes a series below e^g = 0.1 (its
                    // truncation 2.2e-12 at 0.1)
                    let law = super::super::traction::solve_thermal_eyring_halley(ln_x, b);
                    worst_law = worst_law.max((law - exact).abs() / exact);
                    worst_start = worst_start.max((y0 - exact).abs() / exact);
                    worst = worst.max((y1 - exact).abs() / exact);
                }
            }
        }
        assert!(worst_start < 2e-4, "table start off by {worst_start:e}");
        assert!(worst < 1e-14, "one Halley step off by {worst:e} (start {worst_start:e})");
        assert!(worst_law < 3e-12, "the law's solver off by {worst_law:e}");
        // below the table: the small-X closed form and one step
        let mut worst_below: f64 = 0.0;
        for k in 0..4000 {
            let ln_x = -12.0 - 30.0 * uniform();
            let b = 7.0 * (k % 40) as f64 / 39.0;
            let x = libm::exp(ln_x);
            let y1 = halley_step(ln_x, b, x / (1.0 + b * x));
            worst_below = worst_below.max((y1 - root(ln_x, b)).abs() / root(ln_x, b));
        }
        assert!(worst_below < 1e-14, "below the table: one Halley step off by {worst_below:e}");
    }
}
