// The Newton evaluation's slice loop of `simd.rs`, written once for the lane type `F` and its
// `ln` and `exp`, and included in `simd::lanes2` (two lanes, SSE2) and `simd::lanes4` (four,
// AVX2).

/// [`super::line_sums`] in `F::N` lanes for one law.
#[inline(always)]
pub(super) fn line_sums_lanes(t: &SliceTable, n: usize, law: Law, base: f64, theta: f64, gamma: f64, loads: &mut [f64]) -> Option<LineSums> {
    const N: usize = F::N;
    match law {
        Law::Johnson { c, ln_8r } => {
            let (ln_8r, _) = ln_8r[..n.div_ceil(4) * 4].as_chunks::<N>();
            kernel(t, n, base, theta, gamma, loads, t.johnson_limit, |g, d, lnd| {
            let lg = F::load(&ln_8r[g]) - lnd;
            let inv = 1.0 / (lg - 1.0);
            (F::splat(c) * d * inv, F::splat(c) * lg * inv * inv)
        })
        }
        Law::Palmgren { k: kp } => kernel(t, n, base, theta, gamma, loads, 1e300, |_, d, lnd| {
            let d19 = exp(lnd * (1.0 / 9.0));
            (F::splat(kp) * d * d19, F::splat(kp * (10.0 / 9.0)) * d19)
        }),
    }
}

/// The loop of [`line_sums_lanes`] for one law: `law(g, delta, ln delta)` gives (q, dq/d delta)
/// of group g of `F::N` slices (slices g N, g N + 1, ...); `limit`: the largest interference the kernel may take (beyond it,
/// the scalar loop).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn kernel<L: Fn(usize, F, F) -> (F, F)>(t: &SliceTable, n: usize, base: f64, theta: f64, gamma: f64, loads: &mut [f64], limit: f64, law: L) -> Option<LineSums> {
    use crate::simd_math::F2;
    const N: usize = F::N;
    let padded = n.div_ceil(4) * 4;
    // the slice arrays in groups of N lanes (lengths checked by the caller; sliced to the
    // same count, so that the loop reads them without a bounds check)
    let (lever, _) = t.lever[..padded].as_chunks::<N>();
    let groups = lever.len();
    fn chunks<const N: usize>(v: &[f64], padded: usize, groups: usize) -> &[[f64; N]] {
        &v[..padded].as_chunks::<N>().0[..groups]
    }
    let (chi, crown, lever_s) = (
        chunks::<N>(&t.chi, padded, groups),
        chunks::<N>(&t.crown, padded, groups),
        chunks::<N>(&t.lever_s, padded, groups),
    );
    let (vbase, vtheta, vgamma) = (F::splat(base), F::splat(theta), F::splat(gamma));
    let zero = F::splat(0.0);
    let mut max_d = F::splat(f64::NEG_INFINITY);
    let z2 = F2::splat(0.0);
    let (mut sq, mut sql, mut sqc, mut sk, mut skl, mut skl2) = (z2, z2, z2, z2, z2, z2);
    let mut loaded = 0u32;
    for g in 0..groups {
        let k = g * N;
        let (lever, chi, crown) = (F::load(&lever[g]), F::load(&chi[g]), F::load(&crown[g]));
        // base - theta lever + gamma chi - crown, in the scalar loop's order
        let delta = vbase - vtheta * lever + vgamma * chi - crown;
        max_d = max_d.max(delta);
        // touching: delta > 0, or NaN (not <= 0: the NaN then reaches the sums, and the
        // scalar loop takes the line, as it does any NaN)
        let on = !delta.le(zero);
        let bits = on.bits();
        let q = if bits != 0 {
            let lever_s = F::load(&lever_s[g]);
            let d = on.select(delta, F::splat(1.0));
            // (a positive interference below the normal range, 2e-308 m, would take a wrong
            // logarithm here and give a load of the same nothing, ~1e-300 N)
            let (q, dq) = law(g, d, ln(d));
            let (q, dq) = (on.select(q, zero), on.select(dq, zero));
            let (ql, qc, dql) = (q * lever, q * chi, dq * lever_s);
            let dql2 = dql * lever_s;
            for h in 0..N / 2 {
                sq = sq + q.half(h);
                sql = sql + ql.half(h);
                sqc = sqc + qc.half(h);
                sk = sk + dq.half(h);
                skl = skl + dql.half(h);
                skl2 = skl2 + dql2.half(h);
            }
            // set lanes (no popcnt instruction assumed)
            loaded += (0..N).map(|i| (bits >> i) as u32 & 1).sum::<u32>();
            q
        } else {
            zero
        };
        // the line's slices of this group (none in a two-lane group of padding)
        let (live, q) = (n.saturating_sub(k).min(N), q.to_array());
        if live == N {
            loads[k..k + N].copy_from_slice(&q);
        } else if live > 0 {
            loads[k..k + live].copy_from_slice(&q[..live]);
        }
    }
    let max_delta = max_d.to_array().into_iter().fold(f64::NEG_INFINITY, f64::max);
    let (q, kk) = (sq.lane_sum(), sk.lane_sum());
    // NaN (in the sums), or beyond the law's range (Johnson: some slice may be past the
    // validity limit, conservatively by the largest interference): the scalar loop
    if !(q.is_finite() && kk.is_finite() && max_delta < limit) {
        return None;
    }
    Some(LineSums {
        q,
        q_lever: sql.lane_sum(),
        q_chi: sqc.lane_sum(),
        k: kk,
        k_lever: skl.lane_sum(),
        k_lever2: skl2.lane_sum(),
        loaded,
        max_delta,
        extrapolated: false,
    })
}
