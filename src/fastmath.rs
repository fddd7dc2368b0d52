//! Inline natural logarithm and exponential for the contact-law hot loops (one `ln` per
//! Johnson slice, one `ln` + `exp` per Palmgren slice, every Newton evaluation). The libm
//! calls cost a function call plus register spills of the loop's accumulators; these
//! table-based kernels stay inline and are accurate to a few ulp over the range the contact
//! laws use (tests below compare them with `f64::ln`/`f64::exp`).
//!
//! ln: x = 2^e m, m in [1, 2); m = c_j (1 + t) with c_j = 1 + j/128 from the top 7 mantissa
//! bits and 0 <= t < 1/128; ln x = e ln 2 + ln c_j + ln(1 + t), the last by its series to t^9.
//! exp: y = k ln2/64 + r, |r| <= ln2/128; exp y = 2^(k/64) exp(r), with 2^(k/64) from a table
//! (exponent bits) and exp(r) by its Taylor series to r^7.
//!
//! Also the cubic Lagrange weights of the tables read in the hot loops (the quasi-static
//! friction table, the film equation's root), for f64 and for the lane types.

const LN2: f64 = std::f64::consts::LN_2;

// LN_C[j] = ln(1 + j/128), INV_C[j] = 1/(1 + j/128), POW2[j] = 2^(j/64), from build.rs.
include!(concat!(env!("OUT_DIR"), "/fastmath_tables.rs"));

/// 1.5 * 2^52: adding and subtracting it rounds to the nearest integer (|v| < 2^51).
const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// Natural logarithm of a positive, finite, normal `x`; other inputs fall back to `f64::ln`.
#[inline(always)]
pub fn ln(x: f64) -> f64 {
    let bits = x.to_bits();
    // positive, normal and finite: bits in [2^52, 0x7fef_ffff_ffff_ffff] (one unsigned compare)
    if bits.wrapping_sub(0x0010_0000_0000_0000) >= 0x7fe0_0000_0000_0000 {
        return ln_outside(x);
    }
    if (x - 1.0).abs() < 1.0 / 128.0 {
        // near 1 the table form would cancel: the series directly (x - 1 is exact here)
        return ln_1p_small(x - 1.0);
    }
    let e = (bits >> 52) as i64 - 1023;
    let j = ((bits >> 45) & 0x7f) as usize;
    let m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    // m = c_j (1 + u): u = (m - c_j) / c_j, exactly representable difference
    let c = 1.0 + j as f64 / 128.0;
    let u = (m - c) * INV_C[j];
    e as f64 * LN2 + LN_C[j] + ln_1p_small(u)
}

/// `f64::ln` for the inputs [`ln`] does not handle, out of line: a call in the hot path would
/// make the callers spill their floating-point registers around it.
#[cold]
#[inline(never)]
fn ln_outside(x: f64) -> f64 {
    libm::log(x)
}

/// ln(1 + u) = u - u^2/2 + u^3/3 - ... for |u| < 1/128: to u^10 the error is < 1e-21 u.
#[inline(always)]
fn ln_1p_small(u: f64) -> f64 {
    const C: [f64; 10] = [1.0, -0.5, 1.0 / 3.0, -0.25, 0.2, -1.0 / 6.0, 1.0 / 7.0, -0.125, 1.0 / 9.0, -0.1];
    let mut p = C[9];
    for c in C[..9].iter().rev() {
        p = c + u * p;
    }
    u * p
}

/// Exponential of `y` for |y| < 700; other inputs fall back to `f64::exp`.
#[inline(always)]
pub fn exp(y: f64) -> f64 {
    if !(y.abs() < 700.0) {
        return exp_outside(y);
    }
    // ln 2 / 64 split (fdlibm's ln2_hi/ln2_lo over 64): k * HI is exact for |k| < 2^21.
    const HI: f64 = 6.931_471_803_691_238_164_9e-1 / 64.0;
    const LO: f64 = 1.908_214_929_270_587_700_02e-10 / 64.0;
    let t = y * (64.0 / LN2) + ROUNDER;
    let k = t - ROUNDER;
    let r = (y - k * HI) - k * LO;
    // t = 1.5 2^52 + k has unit spacing: its bits less ROUNDER's are k (no float-to-int cast)
    let ki = (t.to_bits() as i64).wrapping_sub(ROUNDER.to_bits() as i64);
    let j = (ki & 63) as usize;
    let e = ki >> 6;
    // exp(r), |r| <= ln2/128 = 0.0054: Taylor to r^7, error < 1e-20
    let er = 1.0 + r * (1.0 + r * (0.5 + r * (1.0 / 6.0 + r * (1.0 / 24.0 + r * (1.0 / 120.0 + r * (1.0 / 720.0 + r / 5040.0))))));
    let scale = f64::from_bits(((e + 1023) as u64) << 52);
    POW2[j] * er * scale
}

/// `f64::exp` for |y| >= 700 and NaN, out of line (see [`ln_outside`]).
#[cold]
#[inline(never)]
fn exp_outside(y: f64) -> f64 {
    libm::exp(y)
}

/// x^p for positive, finite x (exp(p ln x); relative error about |p ln x| ulp).
#[inline(always)]
pub fn powf(x: f64, p: f64) -> f64 {
    exp(p * ln(x))
}

/// x^(1/9) for positive x (Palmgren's slice law).
#[inline(always)]
pub fn ninth_root(x: f64) -> f64 {
    exp(ln(x) * (1.0 / 9.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ulps(a: f64, b: f64) -> f64 {
        ((a - b) / (b.abs() * f64::EPSILON)).abs()
    }

    #[test]
    fn ln_matches_std_to_a_few_ulp() {
        let mut worst: f64 = 0.0;
        let mut x = 1e-300_f64;
        while x < 1e300 {
            for f in [1.0, 1.000_000_1, 1.37, 1.414_213_5, 1.5, 1.999_999] {
                let v = x * f;
                let (a, b) = (ln(v), v.ln());
                let err = if b.abs() > 1e-3 { ulps(a, b) } else { (a - b).abs() / f64::EPSILON };
                worst = worst.max(err);
            }
            x *= 1.7;
        }
        // around 1, ln x is tiny: absolute error counts
        for k in -1000..1000 {
            let v = 1.0 + k as f64 * 1e-6;
            assert!(
                (ln(v) - v.ln()).abs() < 4.0 * f64::EPSILON * v.ln().abs().max(1e-300) + 1e-22,
                "{v}"
            );
        }
        assert!(worst < 4.0, "worst {worst} ulp");
        assert_eq!(ln(1.0), 0.0);
        assert!(ln(0.0) == f64::NEG_INFINITY && ln(-1.0).is_nan() && ln(f64::NAN).is_nan());
    }

    #[test]
    fn exp_matches_std_to_a_few_ulp() {
        let mut worst: f64 = 0.0;
        let mut y = -699.0;
        while y < 699.0 {
            worst = worst.max(ulps(exp(y), y.exp()));
            y += 0.0137;
        }
        assert!(worst < 4.0, "worst {worst} ulp");
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(-800.0), 0.0);
        assert!(exp(800.0).is_infinite());
    }

    #[test]
    fn powf_matches_std() {
        for (x, p) in [(3.7e-7, 0.692), (1.2e-3, 0.47), (2.5e-5, -0.166), (1e6, 0.3635), (42.0, 0.658)] {
            assert!(ulps(powf(x, p), x.powf(p)) < 64.0, "{x}^{p}");
        }
    }

    #[test]
    fn ninth_root_matches_powf() {
        for k in 0..2000 {
            let x = 1e-12 * 1.02_f64.powi(k);
            let a = ninth_root(x);
            let b = x.powf(1.0 / 9.0);
            assert!(ulps(a, b) < 8.0, "{x}: {a} vs {b}");
        }
    }
}

/// The cubic Lagrange weights of the nodes at -1, 0, 1, 2 at position `t` in [0, 1) of a
/// cell, for f64 and for the lane types (the same operations in the same order in each).
#[inline(always)]
pub fn lagrange4_weights<T>(t: T) -> [T; 4]
where
    T: Copy
        + std::ops::Add<f64, Output = T>
        + std::ops::Sub<f64, Output = T>
        + std::ops::Mul<T, Output = T>
        + std::ops::Mul<f64, Output = T>
        + std::ops::Neg<Output = T>,
{
    let (tm, t1, t2) = (t + 1.0, t - 1.0, t - 2.0);
    [
        -t * t1 * t2 * (1.0 / 6.0),
        tm * t1 * t2 * 0.5,
        -tm * t * t2 * 0.5,
        tm * t * t1 * (1.0 / 6.0),
    ]
}
