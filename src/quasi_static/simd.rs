//! The Newton evaluation's slice loop in lanes: four slices at a time where the CPU has AVX2,
//! two (SSE2, part of every x86-64 CPU) elsewhere, the same bits either way.
//!
//! Per slice the loop forms the interference, applies the contact law (Johnson: one ln;
//! Palmgren: one ln and one exp) and accumulates six sums. The scalar loop
//! (`QuasiStatic::line_sums_with`) spends most of its instructions in the table-based `ln` of
//! `fastmath`, which does not vectorise (table look-ups). Here ln and exp are fdlibm's
//! polynomial forms (`crate::simd_math`: Sun's e_log.c / e_exp.c, error below 1 ulp, no
//! tables), evaluated in every lane at once; unloaded slices are masked instead of branched
//! over. The loop is written once (`newton_lanes.rs`) and compiled for both widths; lane for
//! lane the same operations, and the sums gather slices k, k + 1 of every pair in two lanes
//! and add the pairs in slice order, so both widths add the same numbers in the same order.
//!
//! What differs from the scalar loop: the logarithm and exponential round differently (both
//! are within 1 ulp of the exact value), and the six sums are accumulated separately over
//! even and odd slices and then added, so the sums differ from the scalar loop's in the last
//! bits. Where the scalar loop does something special (a NaN interference, the Johnson law
//! beyond its validity, an interference outside the normal range of f64) the kernel returns
//! `None` and the scalar loop does the line.

use super::{LineSums, SliceTable};

/// The contact law of a line as the kernel takes it.
#[derive(Clone, Copy)]
pub(super) enum Law<'a> {
    /// q = c delta / (ln(8R) - ln delta - 1), per slice ln(8R) (padded like the table).
    Johnson { c: f64, ln_8r: &'a [f64] },
    /// q = k delta^(10/9).
    Palmgren { k: f64 },
}

/// Whether this CPU runs the four-lane loop.
pub(super) fn four_lanes_available() -> bool {
    crate::simd_math::x4::available()
}

/// The sums of one contact line (see `QuasiStatic::line_sums`) in lanes, four at a time
/// where `four` (the CPU has AVX2: [`four_lanes_available`]), else two; slice loads to
/// `loads` (length n). `None`: the scalar loop must do this line.
#[allow(clippy::too_many_arguments)]
pub(super) fn line_sums(
    t: &SliceTable,
    n: usize,
    law: Law,
    base: f64,
    theta: f64,
    gamma: f64,
    loads: &mut [f64],
    four: bool,
) -> Option<LineSums> {
    let padded = n.div_ceil(4) * 4;
    if t.lever.len() < padded || t.lever_s.len() < padded || t.chi.len() < padded || t.crown.len() < padded || loads.len() != n {
        return None;
    }
    if let Law::Johnson { ln_8r, .. } = law {
        if ln_8r.len() < padded {
            return None;
        }
    }
    if four && four_lanes_available() {
        // SAFETY: the CPU has AVX2 (checked).
        unsafe { lanes4::line_sums_avx2(t, n, law, base, theta, gamma, loads) }
    } else {
        lanes2::line_sums_lanes(t, n, law, base, theta, gamma, loads)
    }
}

/// The loop in two lanes (SSE2).
mod lanes2 {
    use super::*;
    use crate::simd_math::{exp, ln, F2 as F};
    include!("newton_lanes.rs");
}

/// The loop in four lanes (AVX2), entered through [`lanes4::line_sums_avx2`].
mod lanes4 {
    use super::*;
    use crate::simd_math::x4::{exp, ln, F4 as F};
    include!("newton_lanes.rs");

    /// `line_sums_lanes` compiled for AVX2.
    ///
    /// # Safety
    /// The CPU has AVX2 (`simd_math::x4::available`).
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn line_sums_avx2(
        t: &SliceTable,
        n: usize,
        law: Law,
        base: f64,
        theta: f64,
        gamma: f64,
        loads: &mut [f64],
    ) -> Option<LineSums> {
        line_sums_lanes(t, n, law, base, theta, gamma, loads)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two lanes and four lanes give the same sums and slice loads, bit for bit, for both
    /// contact laws and lines from separated to deeply loaded, odd and even slice counts.
    #[test]
    fn four_lanes_give_the_two_lane_bits() {
        if !four_lanes_available() {
            return;
        }
        let mut compared = 0;
        for n in [5usize, 8, 9, 20, 23] {
            let padded = n.div_ceil(4) * 4;
            let pad = |v: Vec<f64>, fill: f64| {
                let mut v = v;
                v.resize(padded, fill);
                v
            };
            let lever: Vec<f64> = (0..n).map(|k| (k as f64 - 0.5 * n as f64) * 1e-3).collect();
            let t = SliceTable {
                n,
                vector: true,
                four_lanes: true,
                ln_8r: pad((0..n).map(|k| (8.0 * (0.01 + 1e-4 * k as f64)).ln()).collect(), 0.0),
                johnson_limit: 1e-4,
                lever_s: pad(lever.iter().map(|l| l / 0.02).collect(), 0.0),
                lever: pad(lever, 0.0),
                chi: pad((0..n).map(|k| 0.05 + 1e-3 * k as f64).collect(), 0.0),
                crown: pad(
                    (0..n).map(|k| 1e-6 * ((k as f64 - 0.5 * n as f64) / n as f64).powi(4)).collect(),
                    f64::INFINITY,
                ),
            };
            let ln_8r = t.ln_8r.clone();
            for law in [Law::Johnson { c: 3e10, ln_8r: &ln_8r }, Law::Palmgren { k: 8e9 }] {
                for base in [-1e-6, 1e-8, 3e-6, 2e-5] {
                    for theta in [-2e-3, 0.0, 1e-3] {
                        let (mut l2, mut l4) = (vec![0.0; n], vec![0.0; n]);
                        let two = line_sums(&t, n, law, base, theta, 1e-4, &mut l2, false);
                        let four = line_sums(&t, n, law, base, theta, 1e-4, &mut l4, true);
                        let bits = |s: Option<LineSums>| {
                            s.map(|s| {
                                (
                                    [s.q, s.q_lever, s.q_chi, s.k, s.k_lever, s.k_lever2, s.max_delta].map(f64::to_bits),
                                    s.loaded,
                                )
                            })
                        };
                        assert_eq!(bits(two), bits(four), "n {n} base {base} theta {theta}");
                        assert_eq!(
                            l2.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                            l4.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
                        );
                        compared += two.is_some() as usize;
                    }
                }
            }
        }
        assert!(compared > 60, "{compared}");
    }
}
