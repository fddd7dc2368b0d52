// The raceway slices of `contacts.rs` in lanes, written once for the lane types `F`, `M`, `V`
// (`F::N` lanes; sums kept in two lanes, `V3x2`/`F2`) with the traction kernels `pair`, and
// included in `contacts::lanes2` (two lanes, SSE2) and `contacts::lanes4` (four, AVX2).

/// [`race_slices`] for a raceway without lobes (extra gap `extra` everywhere, no slope)
/// `F::N` slices at a time: slices k, k + 1, ... in the lanes through the geometry, the
/// contact law ([`contact_law_lanes`]), the traction ([`slice_traction_lanes`], lanes it does not take by
/// [`slice_traction`]) and the sums. The sums gather the even and the odd slices apart, in
/// slice order, and add them at the end: lanes 2h and 2h + 1 of every group of `F::N` are
/// added as the h-th pair, so two and four lanes add the same numbers in the same order (a
/// pair with no live slice adds exact zeros, which change no sum that starts at +0). The same
/// formulas in the same order as [`race_slices`]: the sums agree with its to rounding.
#[inline(always)]
pub(super) fn race_slices_lanes(c: &Constants, race: &Race, dd: f64, mut slice_loads: Option<&mut [f64]>, extra: f64) -> LineSum {
    use crate::simd_math::{V3x2, F2};
    const N: usize = F::N;
    let line = race.line;
    let (r0, r1) = (line.reference[0], line.reference[1]);
    let (n0, n1) = (line.normal[0], line.normal[1]);
    // the velocity fields of `race_slices`
    let ring_c = race.ring_v0 + race.ring_omega.cross(&race.pos);
    let pt_c = race.pt_v0 + race.pt_omega.cross(&race.pos);
    let v_c = V::splat(&(race.vel - ring_c));
    let w_rel_s = race.w - race.ring_omega;
    let w_rel = V::splat(&w_rel_s);
    let u_c = V::splat(&((race.vel + ring_c) * 0.5 - pt_c));
    let w_e = V::splat(&((race.w + race.ring_omega) * 0.5 - race.pt_omega));
    let (pos, a) = (V::splat(&race.pos), V::splat(&race.a));
    if let Some(loads) = slice_loads.as_deref_mut() {
        loads.fill(0.0);
    }
    let zero = F::splat(0.0);
    let (mut f, mut m, mut traction) = (V3x2::splat(&V3::zeros()), V3x2::splat(&V3::zeros()), V3x2::splat(&V3::zeros()));
    let (mut q_sum, mut power) = (F2::splat(0.0), F2::splat(0.0));
    let mut extrapolated = false;
    let ns = c.s_cm.len();
    let mut k = 0;
    while k < ns {
        let (idx, lanes) = slice_group(k, ns);
        let pick = |v: &[f64]| F::from_fn(|i| v[idx[i]]);
        let rad = pick(&c.radius) + dd - pick(&c.shrink);
        let cl = pos.add(&a.scale(pick(&c.s_cm)));
        let rho_c = (cl.y * cl.y + cl.z * cl.z).sqrt();
        // the cheap gap test
        let bound = -((cl.x - r0) * n0 + (rho_c - r1) * n1) + rad + race.gap_max;
        let mut live = lanes & !bound.lt(F::splat(-1e-12));
        if !live.any() {
            k += N;
            continue;
        }
        let centre_off = rho_c.gt(zero);
        let inv = 1.0 / rho_c;
        let (ey, ez) = (centre_off.select(cl.y * inv, F::splat(1.0)), centre_off.select(cl.z * inv, zero));
        // deepest rim point: towards the raceway projected on the disc plane
        let g = V::new(F::splat(-n0), -(ey * n1), -(ez * n1));
        let d = g.sub(&a.scale(g.dot(&a)));
        let dn = d.norm();
        live = live & !dn.le(zero);
        let d = d.scale(1.0 / dn);
        let pl = cl.add(&d.scale(rad));
        let rho_p = (pl.y * pl.y + pl.z * pl.z).sqrt();
        let point_off = rho_p.gt(zero);
        let (py, pz) = (point_off.select(pl.y / rho_p, F::splat(1.0)), point_off.select(pl.z / rho_p, zero));
        let delta = -((pl.x - r0) * n0 + (rho_p - r1) * n1) + extra;
        live = live & !delta.le(zero);
        let bits = live.bits();
        if bits == 0 {
            k += N;
            continue;
        }
        let (q_el, dq) = contact_law_lanes(&line.law, idx, delta, live, &mut extrapolated);
        let n = V::new(F::splat(n0), py * n1, pz * n1);
        let lever = pl.sub(&pos);
        let v_rel = v_c.add(&w_rel.cross(&lever));
        let vn = v_rel.dot(&n);
        let c_damp = c.damping_factor * dq.sqrt();
        let q = live.select((q_el - c_damp * vn).max(zero), zero);
        let damping_power = (q - q_el) * (-vn);
        let v_t = v_rel.sub(&n.scale(vn));
        let ue_vec = u_c.add(&w_e.cross(&lever));
        let u_e = ue_vec.sub(&n.scale(ue_vec.dot(&n))).norm();
        let vs = v_t.norm();
        // traction: every lane the lane law takes at once
        let regular = q.gt(zero)
            & vs.gt(zero)
            & u_e.ge(F::splat(1e-6))
            & q.lt(F::splat(f64::INFINITY))
            & vs.lt(F::splat(f64::INFINITY))
            & u_e.lt(F::splat(f64::INFINITY));
        let (mut coef, mut couple, mut done) = (zero, zero, !live);
        if c.paired_traction && regular.any() {
            let (cf, cp, ok) = slice_traction_lanes(
                c,
                line,
                race.starved,
                idx,
                regular.select(q, F::splat(1.0)),
                regular.select(vs, F::splat(1.0)),
                regular.select(u_e, F::splat(1.0)),
            );
            let took = regular & ok;
            (coef, couple, done) = (took.select(cf, zero), took.select(cp, zero), done | took);
        }
        let done_bits = done.bits();
        if done_bits != M::FULL {
            let (q, vs, u_e) = (q.to_array(), vs.to_array(), u_e.to_array());
            let (mut cf, mut cp) = (coef.to_array(), couple.to_array());
            for i in 0..N {
                if done_bits & (1 << i) == 0 {
                    (cf[i], cp[i]) = slice_traction(c, line, race.starved, idx[i], q[i], vs[i], u_e[i]);
                }
            }
            (coef, couple) = (F::from_fn(|i| cf[i]), F::from_fn(|i| cp[i]));
        }
        // the slices' shares (dead lanes: zero)
        let fk = n.scale(q).sub(&v_t.scale(coef)).masked(live);
        let mk = lever.cross(&fk).masked(live);
        let tk = v_t.scale(coef).masked(live);
        let pk = live.select(coef * vs * vs + damping_power.max(zero), zero);
        let rolls = live & couple.gt(zero);
        let (mut m_roll, mut p_roll) = (V::splat(&V3::zeros()), zero);
        if rolls.any() {
            // EHL rolling resistance (see `race_slices`)
            let w_roll = w_rel.sub(&n.scale(w_rel.dot(&n)));
            let norm = (w_roll.norm_squared() + pick(&line.roll_eps2)).sqrt();
            m_roll = w_roll.scale(-couple / norm).masked(rolls);
            p_roll = rolls.select(-m_roll.dot(&w_roll), zero);
        }
        // the sums, pair by pair
        for h in 0..N / 2 {
            f = f.add(&fk.half(h));
            m = m.add(&mk.half(h));
            q_sum = q_sum + q.half(h);
            traction = traction.sub(&tk.half(h));
            power = power + pk.half(h);
            if rolls.half(h).any() {
                m = m.add(&m_roll.half(h));
                power = power + p_roll.half(h);
            }
        }
        if let Some(loads) = slice_loads.as_deref_mut() {
            let q = q.to_array();
            for i in 0..N {
                if bits & (1 << i) != 0 {
                    loads[idx[i]] = q[i];
                }
            }
        }
        k += N;
    }
    LineSum {
        f: f.lane_sum(),
        m: m.lane_sum(),
        q: q_sum.lane_sum(),
        traction: traction.lane_sum(),
        power: power.lane_sum(),
        extrapolated,
    }
}

/// [`slice_traction`] with the thermal Eyring law in lanes (`tribology::pair`), slices `k`
/// with load `q`, sliding speed `vs`, entrainment speed `u_e` that [`Slice::paired`] takes:
/// the same formulas in the same order. (coef, couple, the lanes within the lane kernels'
/// range: the others want the scalar code.)
#[inline(always)]
pub(super) fn slice_traction_lanes(c: &Constants, line: &LineConst, st: Starved, k: [usize; F::N], q: F, vs: F, u_e: F) -> (F, F, M) {
    let pick = |v: &[f64]| F::from_fn(|i| v[k[i]]);
    let w = q * c.inv_slice_len;
    let (ln_ue, ln_w) = (ln(u_e), ln(w));
    let ln_h_iso = pick(&line.ln_film) + F::splat(st.ln_film) + 0.692 * ln_ue - 0.166 * ln_w;
    let p_mean = (w * pick(&line.k_pmean)).sqrt();
    let ln_vs = ln(vs);
    let (heating, mut ok) = if c.ln_inlet_heating > f64::NEG_INFINITY {
        pair::thermal_reduction_ln(c.ln_inlet_heating + 2.0 * ln_ue, 4.0 / PI * p_mean / c.e_prime, ln_vs - ln_ue)
    } else {
        (F::splat(1.0), M::splat(true))
    };
    ok = ok & pair::exp_range(ln_h_iso);
    let (h, ln_h) = (heating * exp(ln_h_iso), ln_h_iso + ln(heating));
    let boundary_slide_roll = vs / u_e.max(F::splat(MIN_BOUNDARY_ENTRAINMENT));
    let (mu, film_ok) = pair::raceway_mu_film(&c.lubricant, w, p_mean, h, ln_h, u_e, vs, ln_vs, boundary_slide_roll, st.mixed);
    ok = ok & film_ok;
    let coef = mu * q / vs;
    let couple = if c.rolling_resistance {
        let ln_couple = pick(&line.ln_roll) + F::splat(st.ln_roll) + 0.648 * ln_ue + 0.246 * ln_w;
        ok = ok & pair::exp_range(ln_couple);
        heating * exp(ln_couple)
    } else {
        F::splat(0.0)
    };
    (coef, couple, ok)
}

/// The slice law (load, stiffness) of slices `idx` at interferences `delta`, loaded where
/// `live` (others: zero). The Johnson law in the lanes, [`crate::contact::johnson`]'s
/// operations in its order (its logarithm the lanes' fdlibm one, within 1 ulp of the scalar
/// table-based one); a lane beyond the law's validity (linear continuation, flagged in
/// `extrapolated`) and the Palmgren law per lane by the scalar law.
#[inline(always)]
fn contact_law_lanes(law: &LineLaw, idx: [usize; F::N], delta: F, live: M, extrapolated: &mut bool) -> (F, F) {
    let zero = F::splat(0.0);
    let mut scalar = live;
    let (mut q, mut dq) = (zero, zero);
    if let LineLaw::Johnson { c, ln_8r } = law {
        let d = live.select(delta, F::splat(1.0));
        let lg = F::from_fn(|i| ln_8r[idx[i]]) - ln(d);
        let den = lg - 1.0;
        let inv = 1.0 / den;
        let regular = live & den.ge(F::splat(crate::contact::JOHNSON_LOG_FLOOR));
        q = regular.select(F::splat(*c) * d * inv, zero);
        dq = regular.select(F::splat(*c) * lg * inv * inv, zero);
        scalar = live & !regular;
    }
    if !scalar.any() {
        return (q, dq);
    }
    let (bits, delta) = (scalar.bits(), delta.to_array());
    let (mut qa, mut ka) = (q.to_array(), dq.to_array());
    for i in 0..F::N {
        if bits & (1 << i) != 0 {
            let x;
            (qa[i], ka[i], x) = law.load(idx[i], delta[i]);
            *extrapolated |= x;
        }
    }
    (F::from_fn(|i| qa[i]), F::from_fn(|i| ka[i]))
}

/// [`pocket_sums`] `F::N` slices at a time where every slice lies farther than the critical
/// gap from both walls (the hydrodynamic force and drag alone); `None` where any does not (or
/// a gap is NaN): the scalar loop takes the roller. The same formulas per slice and wall, in
/// the same order, as [`pocket_sums`]; the sums gather the even and the odd slices apart and
/// add, pair by pair in slice order, the front wall's shares and then the back wall's, so two
/// and four lanes add the same numbers in the same order (lanes past the last slice add exact
/// zeros).
#[inline(always)]
pub(super) fn pocket_sums_lanes(c: &Constants, p: &PocketLine) -> Option<PocketSums> {
    use crate::simd_math::F2;
    const N: usize = F::N;
    let zero = F::splat(0.0);
    let crit = F::splat(c.crit_gap);
    let (k_hyd, k_drag) = (F::splat(p.k_hyd), F::splat(p.k_drag));
    // q, qs, c, cs, css, crad, csrad, crr, q_pocket, power
    let mut sums = [F2::splat(0.0); 10];
    let ns = c.s_cm.len();
    let mut k = 0;
    while k < ns {
        let (idx, lanes) = slice_group(k, ns);
        let pick = |v: &[f64]| F::from_fn(|i| v[idx[i]]);
        let (sk, rad) = (pick(&c.s_cm), pick(&c.radius));
        let tau = F::splat(p.tau0) + F::splat(p.tau1) * sk;
        let alpha = F::splat(p.aa) + sk * (F::splat(2.0 * p.ab) + sk * p.bb) + rad * rad * p.cc;
        let beta = 2.0 * rad * (F::splat(p.ac) + sk * p.bc);
        let mut wall = [[zero; 10]; 2];
        for (w, side) in [1.0_f64, -1.0].into_iter().enumerate() {
            let gap = F::splat(c.pocket_half) - tau * side;
            if !(gap.ge(crit) | !lanes).all() {
                return None;
            }
            let inv = 1.0 / gap;
            let qn = lanes.select(k_hyd * rad * rad * inv, zero);
            let drag = k_drag * rad * (rad * inv).sqrt();
            let vs2 = (alpha + beta * side).max(zero);
            let ct = (lanes & vs2.gt(zero)).select(drag / (vs2 + V_EPS * V_EPS).sqrt(), zero);
            let sq = qn * side;
            wall[w] = [
                sq,
                sq * sk,
                ct,
                ct * sk,
                ct * sk * sk,
                rad * side * ct,
                sk * side * rad * ct,
                ct * rad * rad,
                qn,
                ct * vs2,
            ];
        }
        for h in 0..N / 2 {
            for shares in &wall {
                for (s, v) in sums.iter_mut().zip(shares) {
                    *s = *s + v.half(h);
                }
            }
        }
        k += N;
    }
    let [q, qs, c_sum, cs, css, crad, csrad, crr, q_pocket, power] = sums.map(|s| s.lane_sum());
    Some(PocketSums {
        q,
        qs,
        c: c_sum,
        cs,
        css,
        crad,
        csrad,
        crr,
        q_pocket,
        power,
    })
}

/// The slices of the group of lanes from slice `k` of `ns`, and which lanes hold one: past the
/// last slice, lanes repeat it, masked out.
#[inline(always)]
fn slice_group(k: usize, ns: usize) -> ([usize; F::N], M) {
    let idx = std::array::from_fn(|i| (k + i).min(ns - 1));
    let lanes = F::from_fn(|i| if k + i < ns { 1.0 } else { 0.0 }).gt(F::splat(0.0));
    (idx, lanes)
}
