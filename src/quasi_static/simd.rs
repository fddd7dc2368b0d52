//! The Newton evaluation's slice loop two slices at a time (SSE2, part of every x86-64 CPU).
//!
//! Per slice the loop forms the interference, applies the contact law (Johnson: one ln;
//! Palmgren: one ln and one exp) and accumulates six sums. The scalar loop
//! (`QuasiStatic::line_sums_with`) spends most of its instructions in the table-based `ln` of
//! `fastmath`, which does not vectorise (table look-ups). Here ln and exp are fdlibm's
//! polynomial forms (`crate::simd_math`: Sun's e_log.c / e_exp.c, error below 1 ulp, no
//! tables), evaluated in both lanes at once; unloaded slices are masked instead of branched over.
//!
//! What differs from the scalar loop: the logarithm and exponential round differently (both
//! are within 1 ulp of the exact value), and the six sums are accumulated separately over
//! even and odd slices and then added, so the sums differ from the scalar loop's in the last
//! bits. Where the scalar loop does something special (a NaN interference, the Johnson law
//! beyond its validity, an interference outside the normal range of f64) the kernel returns
//! `None` and the scalar loop does the line.

use super::{LineSums, SliceTable};
#[cfg(target_arch = "x86_64")]
use crate::simd_math::{exp_pd, ln_pd};

#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::*;

/// The contact law of a line as the kernel takes it.
#[derive(Clone, Copy)]
pub(super) enum Law<'a> {
    /// q = c delta / (ln(8R) - ln delta - 1), per slice ln(8R) (padded like the table).
    Johnson { c: f64, ln_8r: &'a [f64] },
    /// q = k delta^(10/9).
    Palmgren { k: f64 },
}

/// The sums of one contact line (see `QuasiStatic::line_sums`), two slices at a time; slice
/// loads to `loads` (length n). `None`: the scalar loop must do this line.
#[cfg(target_arch = "x86_64")]
pub(super) fn line_sums(t: &SliceTable, n: usize, law: Law, base: f64, theta: f64, gamma: f64, loads: &mut [f64]) -> Option<LineSums> {
    let padded = (n + 1) & !1;
    if t.lever.len() < padded || t.lever_s.len() < padded || t.chi.len() < padded || t.crown.len() < padded || loads.len() != n {
        return None;
    }
    // SAFETY: SSE2 is part of x86-64; every load reads within the padded tables (checked
    // above), a store of two values only where k + 2 <= n.
    unsafe {
        match law {
            Law::Johnson { c, ln_8r } => {
                if ln_8r.len() < padded {
                    return None;
                }
                let vc = _mm_set1_pd(c);
                let one = _mm_set1_pd(1.0);
                let ln_8r = ln_8r.as_ptr();
                kernel(t, n, base, theta, gamma, loads, t.johnson_limit, |k, d, lnd| {
                    let lg = _mm_sub_pd(_mm_loadu_pd(ln_8r.add(k)), lnd);
                    let inv = _mm_div_pd(one, _mm_sub_pd(lg, one));
                    (
                        _mm_mul_pd(_mm_mul_pd(vc, d), inv),
                        _mm_mul_pd(_mm_mul_pd(_mm_mul_pd(vc, lg), inv), inv),
                    )
                })
            }
            Law::Palmgren { k: kp } => {
                let (vk, vk10) = (_mm_set1_pd(kp), _mm_set1_pd(kp * (10.0 / 9.0)));
                kernel(t, n, base, theta, gamma, loads, 1e300, |_, d, lnd| {
                    let d19 = exp_pd(_mm_mul_pd(lnd, _mm_set1_pd(1.0 / 9.0)));
                    (_mm_mul_pd(_mm_mul_pd(vk, d), d19), _mm_mul_pd(vk10, d19))
                })
            }
        }
    }
}

/// The loop of [`line_sums`] for one law: `law(k, delta, ln delta)` gives (q, dq/d delta) of
/// slices k, k + 1. `limit`: the largest interference the kernel may take (beyond it, the
/// scalar loop).
#[cfg(target_arch = "x86_64")]
#[allow(clippy::too_many_arguments)]
#[inline(always)]
unsafe fn kernel<F: Fn(usize, __m128d, __m128d) -> (__m128d, __m128d)>(
    t: &SliceTable,
    n: usize,
    base: f64,
    theta: f64,
    gamma: f64,
    loads: &mut [f64],
    limit: f64,
    law: F,
) -> Option<LineSums> {
    /// Number of set bits of a two-lane mask.
    const COUNT: [u32; 4] = [0, 1, 1, 2];
    let padded = (n + 1) & !1;
    let set = |v: f64| _mm_set1_pd(v);
    let (vbase, vtheta, vgamma) = (set(base), set(theta), set(gamma));
    let zero = _mm_setzero_pd();
    let mut max_d = set(f64::NEG_INFINITY);
    let (mut sq, mut sql, mut sqc, mut sk, mut skl, mut skl2) = (zero, zero, zero, zero, zero, zero);
    let mut loaded = 0u32;
    let mut k = 0;
    while k < padded {
        let lever = _mm_loadu_pd(t.lever.as_ptr().add(k));
        let chi = _mm_loadu_pd(t.chi.as_ptr().add(k));
        let crown = _mm_loadu_pd(t.crown.as_ptr().add(k));
        // base - theta lever + gamma chi - crown, in the scalar loop's order
        let delta = _mm_sub_pd(
            _mm_add_pd(_mm_sub_pd(vbase, _mm_mul_pd(vtheta, lever)), _mm_mul_pd(vgamma, chi)),
            crown,
        );
        max_d = _mm_max_pd(max_d, delta);
        // touching: delta > 0, or NaN (not <= 0: the NaN then reaches the sums, and the
        // scalar loop takes the line, as it does any NaN)
        let on = _mm_cmpnle_pd(delta, zero);
        let bits = _mm_movemask_pd(on);
        let q = if bits != 0 {
            let lever_s = _mm_loadu_pd(t.lever_s.as_ptr().add(k));
            let d = _mm_or_pd(_mm_and_pd(on, delta), _mm_andnot_pd(on, set(1.0)));
            // (a positive interference below the normal range, 2e-308 m, would take a wrong
            // logarithm here and give a load of the same nothing, ~1e-300 N)
            let (q, dq) = law(k, d, ln_pd(d));
            let q = _mm_and_pd(on, q);
            let dq = _mm_and_pd(on, dq);
            sq = _mm_add_pd(sq, q);
            sql = _mm_add_pd(sql, _mm_mul_pd(q, lever));
            sqc = _mm_add_pd(sqc, _mm_mul_pd(q, chi));
            sk = _mm_add_pd(sk, dq);
            let dql = _mm_mul_pd(dq, lever_s);
            skl = _mm_add_pd(skl, dql);
            skl2 = _mm_add_pd(skl2, _mm_mul_pd(dql, lever_s));
            loaded += COUNT[(bits & 3) as usize];
            q
        } else {
            zero
        };
        if k + 2 <= n {
            _mm_storeu_pd(loads.as_mut_ptr().add(k), q);
        } else {
            _mm_store_sd(loads.as_mut_ptr().add(k), q);
        }
        k += 2;
    }
    let h = |v: __m128d| {
        let mut pair = [0.0; 2];
        _mm_storeu_pd(pair.as_mut_ptr(), v);
        (pair[0], pair[1])
    };
    let sum = |v: __m128d| {
        let (a, b) = h(v);
        a + b
    };
    let (m0, m1) = h(max_d);
    let max_delta = m0.max(m1);
    let (q, kk) = (sum(sq), sum(sk));
    // NaN (in the sums), or beyond the law's range (Johnson: some slice may be past the
    // validity limit, conservatively by the largest interference): the scalar loop
    if !(q.is_finite() && kk.is_finite() && max_delta < limit) {
        return None;
    }
    Some(LineSums {
        q,
        q_lever: sum(sql),
        q_chi: sum(sqc),
        k: kk,
        k_lever: sum(skl),
        k_lever2: sum(skl2),
        loaded,
        max_delta,
        extrapolated: false,
    })
}
