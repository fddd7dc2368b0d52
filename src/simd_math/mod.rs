//! Two-lane f64 arithmetic on SSE2 (part of every x86-64 CPU, so the same instructions and
//! the same results on every x86-64 machine; no FMA, no AVX) and fdlibm's ln and exp on it,
//! shared by the quasi-static slice kernel (`quasi_static/simd.rs`) and the dynamic model's
//! raceway traction (`tribology::pair`).
//!
//! ln and exp are fdlibm's polynomial forms (Sun's e_log.c / e_exp.c, error below 1 ulp, no
//! tables), evaluated in both lanes at once; the scalar code's table-based `fastmath` kernels
//! round differently (both within 1 ulp of the exact value). Only for x86-64 (`lib.rs`); other
//! architectures take the scalar paths. [`x4`] holds the same in four lanes on AVX2, for CPUs
//! that have it: lane for lane the same operations, so the same results.

use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

pub(crate) mod x4;

/// Two f64 lanes.
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub(crate) struct F2(pub __m128d);

/// A two-lane mask (all bits of a lane set: true).
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub(crate) struct M2(pub __m128d);

// SAFETY (every `unsafe` block below): SSE2 is part of the x86-64 baseline.
impl F2 {
    /// Lanes.
    pub const N: usize = 2;
    /// Lane i is `f(i)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> f64) -> F2 {
        let a = f(0);
        F2::new(a, f(1))
    }
    /// The lanes in order.
    #[inline(always)]
    pub fn to_array(self) -> [f64; 2] {
        self.lanes()
    }
    /// Lanes 2h and 2h + 1 (h = 0: the two lanes), as the four-lane type's halves.
    #[inline(always)]
    pub fn half(self, h: usize) -> F2 {
        debug_assert_eq!(h, 0);
        self
    }
    #[inline(always)]
    pub fn splat(v: f64) -> F2 {
        F2(unsafe { _mm_set1_pd(v) })
    }
    /// The first two values of `v` (at least two long: checked).
    #[inline(always)]
    pub fn load(v: &[f64]) -> F2 {
        let v = &v[..2];
        // SAFETY: two values in bounds (above).
        F2(unsafe { _mm_loadu_pd(v.as_ptr()) })
    }
    /// Vector j (j < 8) holds `base[start_i + j]` in lane i, `start_i` lane i of `start`.
    ///
    /// # Safety
    /// Every lane of `start` is a whole number with `0 <= start_i` and
    /// `start_i + 8 <= base.len()`.
    #[inline(always)]
    pub unsafe fn gather8_at(base: &[f64], start: F2) -> [F2; 8] {
        let [s0, s1] = start.lanes();
        let (a, b) = (base.as_ptr().add(s0 as usize), base.as_ptr().add(s1 as usize));
        std::array::from_fn(|j| F2::new(*a.add(j), *b.add(j)))
    }
    /// Every lane truncated towards zero, as f64 and as i32, for lanes within the range of
    /// i32 (others: i32::MIN, as the instruction gives).
    #[inline(always)]
    pub fn trunc_i32(self) -> (F2, [i32; 2]) {
        unsafe {
            let i = _mm_cvttpd_epi32(self.0);
            let mut out = [0i32; 4];
            _mm_storeu_si128(out.as_mut_ptr() as *mut __m128i, i);
            (F2(_mm_cvtepi32_pd(i)), [out[0], out[1]])
        }
    }
    /// Lanes (a, b).
    #[inline(always)]
    pub fn new(a: f64, b: f64) -> F2 {
        F2(unsafe { _mm_set_pd(b, a) })
    }
    #[inline(always)]
    pub fn lanes(self) -> [f64; 2] {
        let mut out = [0.0; 2];
        unsafe { _mm_storeu_pd(out.as_mut_ptr(), self.0) };
        out
    }
    /// Lane 0 + lane 1.
    #[inline(always)]
    pub fn lane_sum(self) -> f64 {
        let [a, b] = self.lanes();
        a + b
    }
    #[inline(always)]
    pub fn max(self, o: F2) -> F2 {
        F2(unsafe { _mm_max_pd(self.0, o.0) })
    }
    #[inline(always)]
    pub fn min(self, o: F2) -> F2 {
        F2(unsafe { _mm_min_pd(self.0, o.0) })
    }
    #[inline(always)]
    pub fn sqrt(self) -> F2 {
        F2(unsafe { _mm_sqrt_pd(self.0) })
    }
    #[inline(always)]
    pub fn abs(self) -> F2 {
        F2(unsafe { _mm_andnot_pd(_mm_set1_pd(-0.0), self.0) })
    }
    #[inline(always)]
    pub fn gt(self, o: F2) -> M2 {
        M2(unsafe { _mm_cmpgt_pd(self.0, o.0) })
    }
    #[inline(always)]
    pub fn ge(self, o: F2) -> M2 {
        M2(unsafe { _mm_cmpge_pd(self.0, o.0) })
    }
    #[inline(always)]
    pub fn lt(self, o: F2) -> M2 {
        M2(unsafe { _mm_cmplt_pd(self.0, o.0) })
    }
    #[inline(always)]
    pub fn le(self, o: F2) -> M2 {
        M2(unsafe { _mm_cmple_pd(self.0, o.0) })
    }
}

impl M2 {
    /// All lanes set, as [`M2::bits`].
    pub const FULL: i32 = 3;
    /// Lanes 2h and 2h + 1 (h = 0: the two lanes).
    #[inline(always)]
    pub fn half(self, h: usize) -> M2 {
        debug_assert_eq!(h, 0);
        self
    }
    /// Every lane `b`.
    #[inline(always)]
    pub fn splat(b: bool) -> M2 {
        M2(unsafe { _mm_castsi128_pd(_mm_set1_epi64x(if b { -1 } else { 0 })) })
    }
    /// `a` where the mask is set, `b` elsewhere.
    #[inline(always)]
    pub fn select(self, a: F2, b: F2) -> F2 {
        F2(unsafe { _mm_or_pd(_mm_and_pd(self.0, a.0), _mm_andnot_pd(self.0, b.0)) })
    }
    /// Bit 0: lane 0 set, bit 1: lane 1 set.
    #[inline(always)]
    pub fn bits(self) -> i32 {
        unsafe { _mm_movemask_pd(self.0) }
    }
    #[inline(always)]
    pub fn any(self) -> bool {
        self.bits() != 0
    }
    #[inline(always)]
    pub fn all(self) -> bool {
        self.bits() == 3
    }
}

impl BitAnd for M2 {
    type Output = M2;
    #[inline(always)]
    fn bitand(self, o: M2) -> M2 {
        M2(unsafe { _mm_and_pd(self.0, o.0) })
    }
}

impl BitOr for M2 {
    type Output = M2;
    #[inline(always)]
    fn bitor(self, o: M2) -> M2 {
        M2(unsafe { _mm_or_pd(self.0, o.0) })
    }
}

impl Not for M2 {
    type Output = M2;
    #[inline(always)]
    fn not(self) -> M2 {
        M2(unsafe { _mm_xor_pd(self.0, _mm_castsi128_pd(_mm_set1_epi64x(-1))) })
    }
}

impl Neg for F2 {
    type Output = F2;
    #[inline(always)]
    fn neg(self) -> F2 {
        F2(unsafe { _mm_xor_pd(self.0, _mm_set1_pd(-0.0)) })
    }
}

macro_rules! lanewise {
    ($trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for F2 {
            type Output = F2;
            #[inline(always)]
            fn $method(self, o: F2) -> F2 {
                F2(unsafe { $intrinsic(self.0, o.0) })
            }
        }
        impl $trait<f64> for F2 {
            type Output = F2;
            #[inline(always)]
            fn $method(self, o: f64) -> F2 {
                F2(unsafe { $intrinsic(self.0, _mm_set1_pd(o)) })
            }
        }
        impl $trait<F2> for f64 {
            type Output = F2;
            #[inline(always)]
            fn $method(self, o: F2) -> F2 {
                F2(unsafe { $intrinsic(_mm_set1_pd(self), o.0) })
            }
        }
    };
}
lanewise!(Add, add, _mm_add_pd);
lanewise!(Sub, sub, _mm_sub_pd);
lanewise!(Mul, mul, _mm_mul_pd);
lanewise!(Div, div, _mm_div_pd);

/// A 3-vector in each of two lanes (components as [`F2`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct V3x2 {
    pub x: F2,
    pub y: F2,
    pub z: F2,
}

impl V3x2 {
    /// The same vector `v` in both lanes.
    #[inline(always)]
    pub fn splat(v: &nalgebra::Vector3<f64>) -> V3x2 {
        V3x2 {
            x: F2::splat(v[0]),
            y: F2::splat(v[1]),
            z: F2::splat(v[2]),
        }
    }
    #[inline(always)]
    pub fn new(x: F2, y: F2, z: F2) -> V3x2 {
        V3x2 { x, y, z }
    }
    #[inline(always)]
    pub fn dot(&self, o: &V3x2) -> F2 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// The cross product in nalgebra's order of operations.
    #[inline(always)]
    pub fn cross(&self, o: &V3x2) -> V3x2 {
        V3x2 {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
    #[inline(always)]
    pub fn norm_squared(&self) -> F2 {
        self.dot(self)
    }
    #[inline(always)]
    pub fn norm(&self) -> F2 {
        self.norm_squared().sqrt()
    }
    #[inline(always)]
    pub fn scale(&self, s: F2) -> V3x2 {
        V3x2 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
    #[inline(always)]
    pub fn add(&self, o: &V3x2) -> V3x2 {
        V3x2 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
    #[inline(always)]
    pub fn sub(&self, o: &V3x2) -> V3x2 {
        V3x2 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
    /// `self` where `m` is set, zero elsewhere.
    #[inline(always)]
    pub fn masked(&self, m: M2) -> V3x2 {
        let zero = F2::splat(0.0);
        V3x2 {
            x: m.select(self.x, zero),
            y: m.select(self.y, zero),
            z: m.select(self.z, zero),
        }
    }
    /// Lanes 2h and 2h + 1 (h = 0: the two lanes).
    #[inline(always)]
    pub fn half(&self, h: usize) -> V3x2 {
        debug_assert_eq!(h, 0);
        *self
    }
    /// The sum of the two lanes.
    #[inline(always)]
    pub fn lane_sum(&self) -> nalgebra::Vector3<f64> {
        nalgebra::Vector3::new(self.x.lane_sum(), self.y.lane_sum(), self.z.lane_sum())
    }
}

/// ln in both lanes, positive, normal and finite (fdlibm, < 1 ulp).
#[inline(always)]
pub(crate) fn ln(x: F2) -> F2 {
    F2(unsafe { ln_pd(x.0) })
}

/// exp in both lanes for |y| < 700 (fdlibm, < 1 ulp).
#[inline(always)]
pub(crate) fn exp(y: F2) -> F2 {
    F2(unsafe { exp_pd(y.0) })
}

// fdlibm e_log.c
const LG1: f64 = 6.666_666_666_666_735_13e-01;
const LG2: f64 = 3.999_999_999_940_941_908e-01;
const LG3: f64 = 2.857_142_874_366_239_149e-01;
const LG4: f64 = 2.222_219_843_214_978_396e-01;
const LG5: f64 = 1.818_357_216_161_805_012e-01;
const LG6: f64 = 1.531_383_769_920_937_332e-01;
const LG7: f64 = 1.479_819_860_511_658_591e-01;
const LN2_HI: f64 = 6.931_471_803_691_238_164_90e-01;
const LN2_LO: f64 = 1.908_214_929_270_587_700_02e-10;
// fdlibm e_exp.c
const P1: f64 = 1.666_666_666_666_660_190_37e-01;
const P2: f64 = -2.777_777_777_701_559_338_42e-03;
const P3: f64 = 6.613_756_321_437_934_361_17e-05;
const P4: f64 = -1.653_390_220_546_525_153_90e-06;
const P5: f64 = 4.138_136_797_057_238_460_39e-08;
/// 1.5 * 2^52: adding and subtracting it rounds to the nearest integer.
const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// ln x in both lanes, x positive, normal and finite (fdlibm's algorithm, < 1 ulp).
#[inline(always)]
pub(crate) unsafe fn ln_pd(x: __m128d) -> __m128d {
    let bits = _mm_castpd_si128(x);
    // exponent as a double: (2^52 + biased exponent) - (2^52 + 1023)
    let e_bits = _mm_or_si128(_mm_srli_epi64::<52>(bits), _mm_castpd_si128(_mm_set1_pd(4_503_599_627_370_496.0)));
    let mut k = _mm_sub_pd(_mm_castsi128_pd(e_bits), _mm_set1_pd(4_503_599_627_370_496.0 + 1023.0));
    // mantissa in [1, 2)
    let m_bits = _mm_or_si128(
        _mm_and_si128(bits, _mm_set1_epi64x(0x000f_ffff_ffff_ffff)),
        _mm_set1_epi64x(0x3ff0_0000_0000_0000),
    );
    let mut m = _mm_castsi128_pd(m_bits);
    // into [sqrt(2)/2, sqrt(2)): halve (exactly) above sqrt(2)
    let big = _mm_cmpgt_pd(m, _mm_set1_pd(std::f64::consts::SQRT_2));
    m = _mm_or_pd(_mm_and_pd(big, _mm_mul_pd(m, _mm_set1_pd(0.5))), _mm_andnot_pd(big, m));
    k = _mm_add_pd(k, _mm_and_pd(big, _mm_set1_pd(1.0)));
    let f = _mm_sub_pd(m, _mm_set1_pd(1.0));
    let s = _mm_div_pd(f, _mm_add_pd(_mm_set1_pd(2.0), f));
    let z = _mm_mul_pd(s, s);
    let w = _mm_mul_pd(z, z);
    let set = |v: f64| _mm_set1_pd(v);
    let t1 = _mm_mul_pd(
        w,
        _mm_add_pd(set(LG2), _mm_mul_pd(w, _mm_add_pd(set(LG4), _mm_mul_pd(w, set(LG6))))),
    );
    let t2 = _mm_mul_pd(
        z,
        _mm_add_pd(
            set(LG1),
            _mm_mul_pd(
                w,
                _mm_add_pd(set(LG3), _mm_mul_pd(w, _mm_add_pd(set(LG5), _mm_mul_pd(w, set(LG7))))),
            ),
        ),
    );
    let r = _mm_add_pd(t2, t1);
    let hfsq = _mm_mul_pd(_mm_mul_pd(set(0.5), f), f);
    // k ln2_hi - ((hfsq - (s (hfsq + R) + k ln2_lo)) - f)
    let inner = _mm_add_pd(_mm_mul_pd(s, _mm_add_pd(hfsq, r)), _mm_mul_pd(k, set(LN2_LO)));
    _mm_sub_pd(_mm_mul_pd(k, set(LN2_HI)), _mm_sub_pd(_mm_sub_pd(hfsq, inner), f))
}

/// exp y in both lanes for |y| < 700 (fdlibm's algorithm, < 1 ulp).
#[inline(always)]
pub(crate) unsafe fn exp_pd(y: __m128d) -> __m128d {
    let set = |v: f64| _mm_set1_pd(v);
    let t = _mm_add_pd(_mm_mul_pd(y, set(std::f64::consts::LOG2_E)), set(ROUNDER));
    let k = _mm_sub_pd(t, set(ROUNDER));
    let hi = _mm_sub_pd(y, _mm_mul_pd(k, set(LN2_HI)));
    let lo = _mm_mul_pd(k, set(LN2_LO));
    let r = _mm_sub_pd(hi, lo);
    let r2 = _mm_mul_pd(r, r);
    let poly = _mm_add_pd(
        set(P1),
        _mm_mul_pd(
            r2,
            _mm_add_pd(
                set(P2),
                _mm_mul_pd(
                    r2,
                    _mm_add_pd(set(P3), _mm_mul_pd(r2, _mm_add_pd(set(P4), _mm_mul_pd(r2, set(P5))))),
                ),
            ),
        ),
    );
    let c = _mm_sub_pd(r, _mm_mul_pd(r2, poly));
    // 1 - ((lo - r c / (2 - c)) - hi)
    let q = _mm_div_pd(_mm_mul_pd(r, c), _mm_sub_pd(set(2.0), c));
    let e = _mm_sub_pd(set(1.0), _mm_sub_pd(_mm_sub_pd(lo, q), hi));
    // times 2^k: k is in the low bits of t (t = 1.5 2^52 + k)
    let ki = _mm_sub_epi64(_mm_castpd_si128(t), _mm_castpd_si128(set(ROUNDER)));
    _mm_castsi128_pd(_mm_add_epi64(_mm_castpd_si128(e), _mm_slli_epi64::<52>(ki)))
}

/// ln of every value of `x` with the kernel's logarithm (tests).
#[cfg(test)]
pub(crate) fn ln2(x: [f64; 2]) -> [f64; 2] {
    let mut out = [0.0; 2];
    unsafe { _mm_storeu_pd(out.as_mut_ptr(), ln_pd(_mm_loadu_pd(x.as_ptr()))) };
    out
}

/// exp of every value of `y` with the kernel's exponential (tests).
#[cfg(test)]
pub(crate) fn exp2(y: [f64; 2]) -> [f64; 2] {
    let mut out = [0.0; 2];
    unsafe { _mm_storeu_pd(out.as_mut_ptr(), exp_pd(_mm_loadu_pd(y.as_ptr()))) };
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ulps(a: f64, b: f64) -> f64 {
        ((a - b) / (b.abs() * f64::EPSILON)).abs()
    }

    #[test]
    fn vector_ln_and_exp_are_within_an_ulp_or_two() {
        let mut worst: f64 = 0.0;
        let mut x = 1e-300_f64;
        while x < 1e300 {
            for f in [1.0, 1.000_000_1, 1.37, 1.414_213_5, 1.414_213_6, 1.5, 1.999_999] {
                let v = x * f;
                let [a, b] = ln2([v, v * 1.1]);
                for (got, arg) in [(a, v), (b, v * 1.1)] {
                    let want = libm::log(arg);
                    let err = if want.abs() > 1e-3 {
                        ulps(got, want)
                    } else {
                        (got - want).abs() / f64::EPSILON
                    };
                    worst = worst.max(err);
                }
            }
            x *= 1.7;
        }
        assert!(worst < 2.0, "ln worst {worst} ulp");
        let mut worst: f64 = 0.0;
        let mut y = -699.0;
        while y < 699.0 {
            let [a, b] = exp2([y, -y * 0.37]);
            worst = worst.max(ulps(a, libm::exp(y))).max(ulps(b, libm::exp(-y * 0.37)));
            y += 0.0137;
        }
        assert!(worst < 2.0, "exp worst {worst} ulp");
    }
}
