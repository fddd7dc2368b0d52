//! Four-lane f64 arithmetic on AVX2 with the API of the two-lane [`F2`]: the same IEEE
//! operations lane for lane (no FMA: a product and a sum round apart, as in two lanes), and
//! fdlibm's ln and exp with the same constants and the same order of operations as
//! [`super::ln_pd`] and [`super::exp_pd`], so every lane gets the bits the two-lane code gives
//! it. A kernel written for both widths (`tribology::pair`, the dynamic model's raceway slices)
//! then gives the same results on every x86-64 CPU, with or without AVX2.
//!
//! These values may only be made inside functions compiled with
//! `#[target_feature(enable = "avx2")]`, which their callers enter after
//! `is_x86_feature_detected!("avx2")` ([`available`]): the methods are `#[inline(always)]` so
//! that they and the intrinsics compile into those functions.

use super::{V3x2, F2, M2};
use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Whether this CPU runs the four-lane code.
pub(crate) fn available() -> bool {
    is_x86_feature_detected!("avx2")
}

/// Four f64 lanes.
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub(crate) struct F4(pub __m256d);

/// A four-lane mask (all bits of a lane set: true).
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub(crate) struct M4(pub __m256d);

// SAFETY (every `unsafe` block below): AVX2 is present, the module's contract.
impl F4 {
    /// Lanes.
    pub const N: usize = 4;
    #[inline(always)]
    pub fn splat(v: f64) -> F4 {
        F4(unsafe { _mm256_set1_pd(v) })
    }
    /// Lane i is `f(i)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> f64) -> F4 {
        let (a, b, c) = (f(0), f(1), f(2));
        F4(unsafe { _mm256_set_pd(f(3), c, b, a) })
    }
    /// The first four values of `v` (at least four long: checked).
    #[inline(always)]
    pub fn load(v: &[f64]) -> F4 {
        let v = &v[..4];
        // SAFETY: four values in bounds (above).
        F4(unsafe { _mm256_loadu_pd(v.as_ptr()) })
    }
    /// Vector j (j < 8) holds `base[start_i + j]` in lane i, `start_i` lane i of `start`: each
    /// lane's eight values loaded as two contiguous vectors and transposed (two 4 x 4
    /// transposes), a fraction of the time of eight gather instructions on Zen 3.
    ///
    /// # Safety
    /// Every lane of `start` is a whole number with `0 <= start_i` and
    /// `start_i + 8 <= base.len() < 2^31`.
    #[inline(always)]
    pub unsafe fn gather8_at(base: &[f64], start: F4) -> [F4; 8] {
        let mut at = [0i32; 4];
        _mm_storeu_si128(at.as_mut_ptr() as *mut __m128i, _mm256_cvttpd_epi32(start.0));
        let half = |h: usize| transpose4(at.map(|s| _mm256_loadu_pd(base.as_ptr().add(s as usize + 4 * h))));
        let ([v0, v1, v2, v3], [v4, v5, v6, v7]) = (half(0), half(1));
        [v0, v1, v2, v3, v4, v5, v6, v7].map(F4)
    }
    /// Every lane truncated towards zero, as f64 and as i32, for lanes within the range of
    /// i32 (others: i32::MIN, as the instruction gives).
    #[inline(always)]
    pub fn trunc_i32(self) -> (F4, [i32; 4]) {
        unsafe {
            let i = _mm256_cvttpd_epi32(self.0);
            let mut out = [0i32; 4];
            _mm_storeu_si128(out.as_mut_ptr() as *mut __m128i, i);
            (F4(_mm256_cvtepi32_pd(i)), out)
        }
    }
    /// The lanes in order.
    #[inline(always)]
    pub fn to_array(self) -> [f64; 4] {
        let mut out = [0.0; 4];
        unsafe { _mm256_storeu_pd(out.as_mut_ptr(), self.0) };
        out
    }
    /// Lanes 2h and 2h + 1.
    #[inline(always)]
    pub fn half(self, h: usize) -> F2 {
        F2(unsafe {
            if h == 0 {
                _mm256_castpd256_pd128(self.0)
            } else {
                _mm256_extractf128_pd::<1>(self.0)
            }
        })
    }
    #[inline(always)]
    pub fn max(self, o: F4) -> F4 {
        F4(unsafe { _mm256_max_pd(self.0, o.0) })
    }
    #[inline(always)]
    pub fn min(self, o: F4) -> F4 {
        F4(unsafe { _mm256_min_pd(self.0, o.0) })
    }
    #[inline(always)]
    pub fn sqrt(self) -> F4 {
        F4(unsafe { _mm256_sqrt_pd(self.0) })
    }
    #[inline(always)]
    pub fn abs(self) -> F4 {
        F4(unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), self.0) })
    }
    #[inline(always)]
    pub fn gt(self, o: F4) -> M4 {
        M4(unsafe { _mm256_cmp_pd::<_CMP_GT_OQ>(self.0, o.0) })
    }
    #[inline(always)]
    pub fn ge(self, o: F4) -> M4 {
        M4(unsafe { _mm256_cmp_pd::<_CMP_GE_OQ>(self.0, o.0) })
    }
    #[inline(always)]
    pub fn lt(self, o: F4) -> M4 {
        M4(unsafe { _mm256_cmp_pd::<_CMP_LT_OQ>(self.0, o.0) })
    }
    #[inline(always)]
    pub fn le(self, o: F4) -> M4 {
        M4(unsafe { _mm256_cmp_pd::<_CMP_LE_OQ>(self.0, o.0) })
    }
}

impl M4 {
    /// All lanes set, as [`M4::bits`].
    pub const FULL: i32 = 15;
    /// Every lane `b`.
    #[inline(always)]
    pub fn splat(b: bool) -> M4 {
        M4(unsafe { _mm256_castsi256_pd(_mm256_set1_epi64x(if b { -1 } else { 0 })) })
    }
    /// `a` where the mask is set, `b` elsewhere.
    #[inline(always)]
    pub fn select(self, a: F4, b: F4) -> F4 {
        F4(unsafe { _mm256_or_pd(_mm256_and_pd(self.0, a.0), _mm256_andnot_pd(self.0, b.0)) })
    }
    /// Bit i: lane i set.
    #[inline(always)]
    pub fn bits(self) -> i32 {
        unsafe { _mm256_movemask_pd(self.0) }
    }
    #[inline(always)]
    pub fn any(self) -> bool {
        self.bits() != 0
    }
    #[inline(always)]
    pub fn all(self) -> bool {
        self.bits() == Self::FULL
    }
    /// Lanes 2h and 2h + 1.
    #[inline(always)]
    pub fn half(self, h: usize) -> M2 {
        M2(F4(self.0).half(h).0)
    }
}

impl BitAnd for M4 {
    type Output = M4;
    #[inline(always)]
    fn bitand(self, o: M4) -> M4 {
        M4(unsafe { _mm256_and_pd(self.0, o.0) })
    }
}

impl BitOr for M4 {
    type Output = M4;
    #[inline(always)]
    fn bitor(self, o: M4) -> M4 {
        M4(unsafe { _mm256_or_pd(self.0, o.0) })
    }
}

impl Not for M4 {
    type Output = M4;
    #[inline(always)]
    fn not(self) -> M4 {
        M4(unsafe { _mm256_xor_pd(self.0, _mm256_castsi256_pd(_mm256_set1_epi64x(-1))) })
    }
}

impl Neg for F4 {
    type Output = F4;
    #[inline(always)]
    fn neg(self) -> F4 {
        F4(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
    }
}

macro_rules! lanewise {
    ($trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for F4 {
            type Output = F4;
            #[inline(always)]
            fn $method(self, o: F4) -> F4 {
                F4(unsafe { $intrinsic(self.0, o.0) })
            }
        }
        impl $trait<f64> for F4 {
            type Output = F4;
            #[inline(always)]
            fn $method(self, o: f64) -> F4 {
                F4(unsafe { $intrinsic(self.0, _mm256_set1_pd(o)) })
            }
        }
        impl $trait<F4> for f64 {
            type Output = F4;
            #[inline(always)]
            fn $method(self, o: F4) -> F4 {
                F4(unsafe { $intrinsic(_mm256_set1_pd(self), o.0) })
            }
        }
    };
}
lanewise!(Add, add, _mm256_add_pd);
lanewise!(Sub, sub, _mm256_sub_pd);
lanewise!(Mul, mul, _mm256_mul_pd);
lanewise!(Div, div, _mm256_div_pd);

/// A 3-vector in each of four lanes (components as [`F4`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct V3x4 {
    pub x: F4,
    pub y: F4,
    pub z: F4,
}

impl V3x4 {
    /// The same vector `v` in every lane.
    #[inline(always)]
    pub fn splat(v: &nalgebra::Vector3<f64>) -> V3x4 {
        V3x4 {
            x: F4::splat(v[0]),
            y: F4::splat(v[1]),
            z: F4::splat(v[2]),
        }
    }
    #[inline(always)]
    pub fn new(x: F4, y: F4, z: F4) -> V3x4 {
        V3x4 { x, y, z }
    }
    #[inline(always)]
    pub fn dot(&self, o: &V3x4) -> F4 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// The cross product in nalgebra's order of operations.
    #[inline(always)]
    pub fn cross(&self, o: &V3x4) -> V3x4 {
        V3x4 {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
    #[inline(always)]
    pub fn norm_squared(&self) -> F4 {
        self.dot(self)
    }
    #[inline(always)]
    pub fn norm(&self) -> F4 {
        self.norm_squared().sqrt()
    }
    #[inline(always)]
    pub fn scale(&self, s: F4) -> V3x4 {
        V3x4 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
    #[inline(always)]
    pub fn add(&self, o: &V3x4) -> V3x4 {
        V3x4 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
    #[inline(always)]
    pub fn sub(&self, o: &V3x4) -> V3x4 {
        V3x4 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
    /// `self` where `m` is set, zero elsewhere.
    #[inline(always)]
    pub fn masked(&self, m: M4) -> V3x4 {
        let zero = F4::splat(0.0);
        V3x4 {
            x: m.select(self.x, zero),
            y: m.select(self.y, zero),
            z: m.select(self.z, zero),
        }
    }
    /// Lanes 2h and 2h + 1.
    #[inline(always)]
    pub fn half(&self, h: usize) -> V3x2 {
        V3x2::new(self.x.half(h), self.y.half(h), self.z.half(h))
    }
}

/// ln in every lane, positive, normal and finite (fdlibm, < 1 ulp; [`super::ln`]'s bits).
#[inline(always)]
pub(crate) fn ln(x: F4) -> F4 {
    F4(unsafe { ln_pd(x.0) })
}

/// exp in every lane for |y| < 700 (fdlibm, < 1 ulp; [`super::exp`]'s bits).
#[inline(always)]
pub(crate) fn exp(y: F4) -> F4 {
    F4(unsafe { exp_pd(y.0) })
}

use super::{LG1, LG2, LG3, LG4, LG5, LG6, LG7, LN2_HI, LN2_LO, P1, P2, P3, P4, P5, ROUNDER};

/// [`super::ln_pd`] in four lanes, operation for operation.
#[inline(always)]
unsafe fn ln_pd(x: __m256d) -> __m256d {
    let bits = _mm256_castpd_si256(x);
    let e_bits = _mm256_or_si256(
        _mm256_srli_epi64::<52>(bits),
        _mm256_castpd_si256(_mm256_set1_pd(4_503_599_627_370_496.0)),
    );
    let mut k = _mm256_sub_pd(_mm256_castsi256_pd(e_bits), _mm256_set1_pd(4_503_599_627_370_496.0 + 1023.0));
    let m_bits = _mm256_or_si256(
        _mm256_and_si256(bits, _mm256_set1_epi64x(0x000f_ffff_ffff_ffff)),
        _mm256_set1_epi64x(0x3ff0_0000_0000_0000),
    );
    let mut m = _mm256_castsi256_pd(m_bits);
    let big = _mm256_cmp_pd::<_CMP_GT_OQ>(m, _mm256_set1_pd(std::f64::consts::SQRT_2));
    m = _mm256_or_pd(_mm256_and_pd(big, _mm256_mul_pd(m, _mm256_set1_pd(0.5))), _mm256_andnot_pd(big, m));
    k = _mm256_add_pd(k, _mm256_and_pd(big, _mm256_set1_pd(1.0)));
    let f = _mm256_sub_pd(m, _mm256_set1_pd(1.0));
    let s = _mm256_div_pd(f, _mm256_add_pd(_mm256_set1_pd(2.0), f));
    let z = _mm256_mul_pd(s, s);
    let w = _mm256_mul_pd(z, z);
    let set = |v: f64| _mm256_set1_pd(v);
    let t1 = _mm256_mul_pd(
        w,
        _mm256_add_pd(set(LG2), _mm256_mul_pd(w, _mm256_add_pd(set(LG4), _mm256_mul_pd(w, set(LG6))))),
    );
    let t2 = _mm256_mul_pd(
        z,
        _mm256_add_pd(
            set(LG1),
            _mm256_mul_pd(
                w,
                _mm256_add_pd(set(LG3), _mm256_mul_pd(w, _mm256_add_pd(set(LG5), _mm256_mul_pd(w, set(LG7))))),
            ),
        ),
    );
    let r = _mm256_add_pd(t2, t1);
    let hfsq = _mm256_mul_pd(_mm256_mul_pd(set(0.5), f), f);
    let inner = _mm256_add_pd(_mm256_mul_pd(s, _mm256_add_pd(hfsq, r)), _mm256_mul_pd(k, set(LN2_LO)));
    _mm256_sub_pd(_mm256_mul_pd(k, set(LN2_HI)), _mm256_sub_pd(_mm256_sub_pd(hfsq, inner), f))
}

/// [`super::exp_pd`] in four lanes, operation for operation.
#[inline(always)]
unsafe fn exp_pd(y: __m256d) -> __m256d {
    let set = |v: f64| _mm256_set1_pd(v);
    let t = _mm256_add_pd(_mm256_mul_pd(y, set(std::f64::consts::LOG2_E)), set(ROUNDER));
    let k = _mm256_sub_pd(t, set(ROUNDER));
    let hi = _mm256_sub_pd(y, _mm256_mul_pd(k, set(LN2_HI)));
    let lo = _mm256_mul_pd(k, set(LN2_LO));
    let r = _mm256_sub_pd(hi, lo);
    let r2 = _mm256_mul_pd(r, r);
    let poly = _mm256_add_pd(
        set(P1),
        _mm256_mul_pd(
            r2,
            _mm256_add_pd(
                set(P2),
                _mm256_mul_pd(
                    r2,
                    _mm256_add_pd(set(P3), _mm256_mul_pd(r2, _mm256_add_pd(set(P4), _mm256_mul_pd(r2, set(P5))))),
                ),
            ),
        ),
    );
    let c = _mm256_sub_pd(r, _mm256_mul_pd(r2, poly));
    let q = _mm256_div_pd(_mm256_mul_pd(r, c), _mm256_sub_pd(set(2.0), c));
    let e = _mm256_sub_pd(set(1.0), _mm256_sub_pd(_mm256_sub_pd(lo, q), hi));
    let ki = _mm256_sub_epi64(_mm256_castpd_si256(t), _mm256_castpd_si256(set(ROUNDER)));
    _mm256_castsi256_pd(_mm256_add_epi64(_mm256_castpd_si256(e), _mm256_slli_epi64::<52>(ki)))
}

/// The 4 x 4 transpose: vector j of the result holds element j of `rows[i]` in lane i.
#[inline(always)]
unsafe fn transpose4(rows: [__m256d; 4]) -> [__m256d; 4] {
    let [a, b, c, d] = rows;
    // (a0 b0 a2 b2), (a1 b1 a3 b3), (c0 d0 c2 d2), (c1 d1 c3 d3)
    let (ab_even, ab_odd) = (_mm256_unpacklo_pd(a, b), _mm256_unpackhi_pd(a, b));
    let (cd_even, cd_odd) = (_mm256_unpacklo_pd(c, d), _mm256_unpackhi_pd(c, d));
    [
        _mm256_permute2f128_pd::<0x20>(ab_even, cd_even),
        _mm256_permute2f128_pd::<0x20>(ab_odd, cd_odd),
        _mm256_permute2f128_pd::<0x31>(ab_even, cd_even),
        _mm256_permute2f128_pd::<0x31>(ab_odd, cd_odd),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ln, exp, the arithmetic and the comparisons in four lanes give the two-lane bits.
    #[target_feature(enable = "avx2")]
    unsafe fn four_lanes(x: [f64; 4], y: [f64; 4]) -> [[f64; 4]; 6] {
        let (a, b) = (F4::from_fn(|i| x[i]), F4::from_fn(|i| y[i]));
        let gt = a.gt(b).select(a, b);
        [
            ln(a).to_array(),
            exp(b).to_array(),
            ((a * b + a) / (b - 0.5 * a)).to_array(),
            a.sqrt().to_array(),
            gt.to_array(),
            (-(a.min(b))).abs().to_array(),
        ]
    }

    fn two_lanes(x: [f64; 2], y: [f64; 2]) -> [[f64; 2]; 6] {
        let (a, b) = (F2::from_fn(|i| x[i]), F2::from_fn(|i| y[i]));
        let gt = a.gt(b).select(a, b);
        [
            super::super::ln(a).to_array(),
            super::super::exp(b).to_array(),
            ((a * b + a) / (b - 0.5 * a)).to_array(),
            a.sqrt().to_array(),
            gt.to_array(),
            (-(a.min(b))).abs().to_array(),
        ]
    }

    #[test]
    fn four_lanes_give_the_two_lane_bits() {
        if !available() {
            eprintln!("no AVX2 on this CPU: nothing to compare");
            return;
        }
        let mut v = 1.234e-7_f64;
        for _ in 0..400 {
            let x = [v, v * 3.7, v * 0.013, v * 91.0];
            let y = [-v.min(600.0), 0.37 * v.min(600.0), -300.0 / (1.0 + v), 1.5];
            let four = unsafe { four_lanes(x, y) };
            let (lo, hi) = (two_lanes([x[0], x[1]], [y[0], y[1]]), two_lanes([x[2], x[3]], [y[2], y[3]]));
            for r in 0..6 {
                let two = [lo[r][0], lo[r][1], hi[r][0], hi[r][1]];
                assert_eq!(four[r].map(f64::to_bits), two.map(f64::to_bits), "result {r} at {x:?}, {y:?}");
            }
            v *= 1.31;
        }
    }
}
