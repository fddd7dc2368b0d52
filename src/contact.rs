//! Contact laws (MODEL.md section 3): load-deflection of a roller slice on a raceway
//! (Johnson line contact [W25], Palmgren [D19, Y22, L22]) and Hertz point contact of the
//! spherical roller end on the rib with the Hamrock-Brewe ellipticity approximation [W25].
//!
//! Every law returns the load and its derivative with respect to the interference, so the
//! Newton solver gets an exact Jacobian. Loads are zero for non-positive interference.

use std::f64::consts::PI;

/// Effective (plane-strain, combined) modulus E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2).
/// MODEL.md writes it as E_bar with 1/E_bar = 0.5 ((1 - nu_r^2)/E_r + (1 - nu_b^2)/E_b).
pub fn effective_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    2.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)
}

/// Hertz's maximum pressure of a line contact, p0 = sqrt(w E* / (pi R)) (Johnson, Contact
/// Mechanics, eq. 4.45), for load per length `w`, effective modulus `e_prime` = E' = 2 E* and
/// relative radius of curvature `r_bar`.
pub fn line_contact_pressure(w: f64, e_prime: f64, r_bar: f64) -> f64 {
    if w > 0.0 {
        (w * e_prime / (2.0 * PI * r_bar)).sqrt()
    } else {
        0.0
    }
}

/// Palmgren's roller stiffness in SI: Q = K delta^(10/9) with K = 8.06e4 l^(8/9) in N and mm,
/// i.e. 8.06e4 * 1000^(8/9 + 10/9) = 8.06e10 l^(8/9) with l and delta in metres.
pub fn palmgren_roller_stiffness(length: f64) -> f64 {
    8.06e10 * libm::pow(length, 8.0 / 9.0)
}

/// Where the Johnson law stops being trusted: ln(8 R / delta) - 1 >= 3, i.e. delta <= 8 R e^-4
/// (about 0.15 R, far beyond any real interference). Beyond it the law continues linearly.
pub(crate) const JOHNSON_LOG_FLOOR: f64 = 3.0;

/// Load-deflection law of one slice, constants precomputed per slice.
#[derive(Debug, Clone)]
pub enum LineLaw {
    /// q = c delta / (ln(8 R / delta) - 1), c = pi (l/s) E* (Johnson) or pi (l/s) E' ([W25] as
    /// printed); per slice `ln_8r` = ln(8 R_bar).
    Johnson { c: f64, ln_8r: Vec<f64> },
    /// q = k delta^(10/9), k = K / s: the whole-roller stiffness split over the slices,
    /// so the total load at uniform interference does not depend on s.
    Palmgren { k: f64 },
}

impl LineLaw {
    /// Johnson's line contact (Contact Mechanics, 1985, section 5.3): the approach of a
    /// cylinder's axis towards the contact under a load q per length is
    /// delta = q (1 − ν²)/(π E) (2 ln(4 R / a) − 1) for each body, so the pair's compliance is
    /// Σ (1 − ν²)/E = 1/E* (E* the contact modulus, E' = 2 E*). With one cylinder of the
    /// equivalent radius R̄ and the half-width a = sqrt(2 R̄ δ) where the undeformed profiles
    /// meet, 2 ln(4 R̄ / a) − 1 = ln(8 R̄ / δ) − 1: the slice law of [W25] Eq. (1),
    /// q = π (l/s) E* δ / (ln(8 R̄/δ) − 1). `e_prime` is E' = 2 E*.
    pub fn johnson(e_prime: f64, slice_len: f64, r_bar: &[f64]) -> LineLaw {
        LineLaw::Johnson {
            c: PI * slice_len * 0.5 * e_prime,
            ln_8r: r_bar.iter().map(|r| libm::log(8.0 * r)).collect(),
        }
    }

    /// The same law as [W25] Eq. (1) prints it, with Ē, 1/Ē = ½ Σ (1 − ν²)/E: Ē = E' = 2 E*,
    /// twice Johnson's stiffness (kept to reproduce the study).
    pub fn johnson_w25(e_prime: f64, slice_len: f64, r_bar: &[f64]) -> LineLaw {
        LineLaw::Johnson {
            c: PI * slice_len * e_prime,
            ln_8r: r_bar.iter().map(|r| libm::log(8.0 * r)).collect(),
        }
    }

    pub fn palmgren(length: f64, slices: usize) -> LineLaw {
        LineLaw::Palmgren {
            k: palmgren_roller_stiffness(length) / slices as f64,
        }
    }

    /// Load of slice `k` at interference `delta`, its derivative, and whether the law was
    /// extrapolated beyond its validity range.
    #[inline(always)]
    pub fn load(&self, k: usize, delta: f64) -> (f64, f64, bool) {
        if delta <= 0.0 {
            return (0.0, 0.0, false);
        }
        match self {
            LineLaw::Johnson { c, ln_8r } => johnson(*c, ln_8r[k], delta),
            LineLaw::Palmgren { k: kp } => palmgren(*kp, delta),
        }
    }

    /// Interference at which slice `k` carries `q` (inverse law; for start values and tests).
    pub fn deflection(&self, k: usize, q: f64) -> f64 {
        if q <= 0.0 {
            return 0.0;
        }
        match self {
            LineLaw::Palmgren { k: kp } => libm::pow(q / kp, 0.9),
            LineLaw::Johnson { .. } => {
                // Monotone: Newton from a power-law estimate, safeguarded by bisection.
                let (mut lo, mut hi) = (0.0_f64, 1e-6_f64);
                while self.load(k, hi).0 < q {
                    lo = hi;
                    hi *= 2.0;
                    if hi > 1.0 {
                        break;
                    }
                }
                let mut d = 0.5 * (lo + hi);
                for _ in 0..100 {
                    let (f, df, _) = self.load(k, d);
                    let r = f - q;
                    if r > 0.0 {
                        hi = d
                    } else {
                        lo = d
                    }
                    let mut next = if df > 0.0 { d - r / df } else { 0.5 * (lo + hi) };
                    if !(next > lo && next < hi) {
                        next = 0.5 * (lo + hi);
                    }
                    if (next - d).abs() <= 1e-15 * d {
                        return next;
                    }
                    d = next;
                }
                d
            }
        }
    }
}

/// Palmgren slice law q = k delta^(10/9) and its derivative (delta > 0).
#[inline(always)]
pub fn palmgren(k: f64, delta: f64) -> (f64, f64, bool) {
    let d19 = crate::fastmath::ninth_root(delta);
    (k * delta * d19, k * (10.0 / 9.0) * d19, false)
}

/// Johnson slice law q = c delta / (ln(8R/delta) - 1) and its derivative (delta > 0),
/// continued linearly beyond its validity range (flagged).
#[inline(always)]
pub fn johnson(c: f64, ln_8r: f64, delta: f64) -> (f64, f64, bool) {
    let lg = ln_8r - crate::fastmath::ln(delta);
    let den = lg - 1.0;
    if den >= JOHNSON_LOG_FLOOR {
        let inv = 1.0 / den;
        // d/d delta [delta / (ln(8R/delta) - 1)] = (den + 1) / den^2 = lg / den^2
        (c * delta * inv, c * lg * inv * inv, false)
    } else {
        // Linear continuation from the edge of validity (C1).
        let d0 = libm::exp(ln_8r - (JOHNSON_LOG_FLOOR + 1.0));
        let den0 = JOHNSON_LOG_FLOOR;
        let q0 = c * d0 / den0;
        let k0 = c * (den0 + 1.0) / (den0 * den0);
        (q0 + k0 * (delta - d0), k0, true)
    }
}

/// Hertz point contact of two bodies with principal relative radii `rx`, `ry` (aligned axes).
/// The ellipticity and the complete elliptic integrals are solved exactly (AGM and
/// bisection, once at set-up); [`PointContact::hamrock_brewe`] gives the closed-form
/// approximation of Hamrock & Brewe (1983) for comparison.
#[derive(Debug, Clone, Copy)]
pub struct PointContact {
    /// Radius in the direction of the meridian (x) and circumferential (y) of the contact.
    pub rx: f64,
    pub ry: f64,
    /// Curvature-sum radius R = 1 / (1/rx + 1/ry).
    pub r: f64,
    /// Ellipticity a/b (semi-axis along the larger radius over the other), >= 1.
    pub k: f64,
    /// Complete elliptic integrals of the second (E) and first (F = K) kind of the ellipse.
    pub e_int: f64,
    pub f_int: f64,
    pub e_prime: f64,
    /// Q = stiffness * delta^(3/2).
    pub stiffness: f64,
}

/// Complete elliptic integrals K(m), E(m) of parameter m = e^2 by the arithmetic-geometric mean.
pub fn elliptic_integrals(m: f64) -> (f64, f64) {
    let mut a = 1.0_f64;
    let mut b = (1.0 - m).sqrt();
    let mut c = m.sqrt();
    let mut sum = 0.5 * c * c;
    let mut pow2 = 0.5;
    for _ in 0..40 {
        if c.abs() < 1e-16 {
            break;
        }
        let an = 0.5 * (a + b);
        let bn = (a * b).sqrt();
        c = 0.5 * (a - b);
        pow2 *= 2.0;
        sum += pow2 * c * c;
        a = an;
        b = bn;
    }
    let k = PI / (2.0 * a);
    (k, k * (1.0 - sum))
}

impl PointContact {
    pub fn new(rx: f64, ry: f64, e_prime: f64) -> PointContact {
        let (small, large) = if rx <= ry { (rx, ry) } else { (ry, rx) };
        let ratio = large / small;
        // Curvature ratio B/A of the ellipse with eccentricity e (m = e^2):
        // B/A = (E/(1-m) - K) / (K - E), increasing from 1 at m = 0.
        let curvature_ratio = |m: f64| {
            let (kk, ee) = elliptic_integrals(m);
            (ee / (1.0 - m) - kk) / (kk - ee)
        };
        let m = if ratio <= 1.0 + 1e-12 {
            0.0
        } else {
            let (mut lo, mut hi) = (0.0_f64, 1.0 - 1e-15);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if curvature_ratio(mid) < ratio {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            0.5 * (lo + hi)
        };
        let (f_int, e_int) = if m == 0.0 { (PI / 2.0, PI / 2.0) } else { elliptic_integrals(m) };
        Self::from_constants(rx, ry, e_prime, 1.0 / (1.0 - m).sqrt(), e_int, f_int)
    }

    /// The closed-form Hamrock-Brewe approximation (k = 1.0339 (Ry/Rx)^0.636,
    /// E = 1.0003 + 0.5968 Rx/Ry, F = 1.5277 + 0.6023 ln(Ry/Rx)).
    pub fn hamrock_brewe(rx: f64, ry: f64, e_prime: f64) -> PointContact {
        let (small, large) = if rx <= ry { (rx, ry) } else { (ry, rx) };
        let ratio = large / small;
        Self::from_constants(
            rx,
            ry,
            e_prime,
            1.0339 * libm::pow(ratio, 0.6360),
            1.0003 + 0.5968 / ratio,
            1.5277 + 0.6023 * libm::log(ratio),
        )
    }

    fn from_constants(rx: f64, ry: f64, e_prime: f64, k: f64, e_int: f64, f_int: f64) -> PointContact {
        let r = 1.0 / (1.0 / rx + 1.0 / ry);
        // delta = F [ 9/(2 E R) (Q/(pi k E'))^2 ]^(1/3)  =>  Q = pi k E' sqrt(2 E R / 9) (delta/F)^(3/2)
        let stiffness = PI * k * e_prime * (2.0 * e_int * r / 9.0).sqrt() / libm::pow(f_int, 1.5);
        PointContact {
            rx,
            ry,
            r,
            k,
            e_int,
            f_int,
            e_prime,
            stiffness,
        }
    }

    /// Load and its derivative at interference `delta`.
    #[inline]
    pub fn load(&self, delta: f64) -> (f64, f64) {
        if delta <= 0.0 {
            return (0.0, 0.0);
        }
        let sq = delta.sqrt();
        (self.stiffness * delta * sq, 1.5 * self.stiffness * sq)
    }

    /// Semi-axes (a along the larger radius, b) and maximum pressure at load `q`.
    pub fn ellipse(&self, q: f64) -> (f64, f64, f64) {
        if q <= 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let a = libm::cbrt(6.0 * self.k * self.k * self.e_int * self.r * q / (PI * self.e_prime));
        let b = libm::cbrt(6.0 * self.e_int * self.r * q / (PI * self.k * self.e_prime));
        let p_max = 1.5 * q / (PI * a * b);
        (a, b, p_max)
    }
}

/// Hertz line contact half-width and maximum pressure for load per unit length `w`.
pub fn line_contact_half_width(w: f64, r_bar: f64, e_prime: f64) -> (f64, f64) {
    if w <= 0.0 {
        return (0.0, 0.0);
    }
    let b = (8.0 * w * r_bar / (PI * e_prime)).sqrt();
    (b, 2.0 * w / (PI * b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palmgren_hand_value() {
        // 1000 N on a 20 mm roller: delta = 3.84e-5 Q^0.9 / l^0.8 mm (Palmgren).
        let law = LineLaw::palmgren(0.020, 1);
        let delta_mm = 3.84e-5 * 1000.0_f64.powf(0.9) / 20.0_f64.powf(0.8);
        let (q, _, _) = law.load(0, delta_mm * 1e-3);
        assert!((q - 1000.0).abs() < 0.5, "q = {q}"); // 8.06e4 rounds 3.84e-5^(-10/9)
        assert!((law.deflection(0, q) - delta_mm * 1e-3).abs() < 1e-15);
    }

    #[test]
    fn johnson_law_follows_the_book() {
        // Johnson, Contact Mechanics (1985), section 5.3: the axis of a cylinder of radius R
        // pressed by q per length approaches the contact by q (1 - nu^2)/(pi E) (2 ln(4R/a) - 1),
        // one such term per body. Steel on steel, one equivalent cylinder of R_bar = 5 mm, a
        // 10 mm slice at 5 um, a the half-width where the undeformed profiles meet.
        let (e, nu, l, r, d) = (208e9_f64, 0.3_f64, 0.01_f64, 0.005_f64, 5e-6_f64);
        let compliance = 2.0 * (1.0 - nu * nu) / e; // both bodies: 1/E*
        let a = (2.0 * r * d).sqrt();
        let q_book = PI * l * d / (compliance * (2.0 * (4.0 * r / a).ln() - 1.0));
        // by hand: E* = 114.29 GPa, a = 223.6 um, 2 ln(4R/a) - 1 = 7.987, q = 0.2248 MN/m x l
        assert!((q_book / l - 2.2476e5).abs() < 1e-4 * 2.2476e5, "{}", q_book / l);
        let e_prime = effective_modulus(e, nu, e, nu);
        let law = LineLaw::johnson(e_prime, l, &[r]);
        let (q, dq, ext) = law.load(0, d);
        assert!((q - q_book).abs() < 1e-12 * q_book, "{q} against {q_book}");
        assert!(!ext);
        let h = 1e-12;
        let fd = (law.load(0, d + h).0 - law.load(0, d - h).0) / (2.0 * h);
        assert!((dq - fd).abs() < 1e-5 * dq, "{dq} vs {fd}");
        assert!((law.deflection(0, q) - d).abs() < 1e-12 * d);
        // [W25] Eq. (1) as printed: 1/E_bar = (1/2) sum (1 - nu^2)/E, twice as stiff
        let w25 = LineLaw::johnson_w25(e_prime, l, &[r]);
        assert!((w25.load(0, d).0 - 2.0 * q_book).abs() < 1e-12 * q_book);
    }

    #[test]
    fn johnson_extrapolation_is_continuous_and_flagged() {
        let law = LineLaw::johnson(2e11, 0.01, &[0.005]);
        let d0 = 8.0 * 0.005 * (-4.0_f64).exp();
        let (a, ka, e1) = law.load(0, d0 * (1.0 - 1e-9));
        let (b, kb, e2) = law.load(0, d0 * (1.0 + 1e-9));
        assert!(!e1 && e2);
        assert!((a - b).abs() < 1e-6 * a);
        assert!((ka - kb).abs() < 1e-6 * ka);
    }

    #[test]
    fn no_load_without_interference() {
        for law in [LineLaw::palmgren(0.02, 10), LineLaw::johnson(2e11, 0.002, &[0.01])] {
            assert_eq!(law.load(0, 0.0).0, 0.0);
            assert_eq!(law.load(0, -1e-6).0, 0.0);
        }
        let pc = PointContact::new(0.1, 0.2, 2.2e11);
        assert_eq!(pc.load(-1e-6), (0.0, 0.0));
    }

    #[test]
    fn sphere_on_plane_matches_hertz() {
        // Sphere radius R on a plane: Q = 4/3 E* sqrt(R) delta^1.5 with E* = E'/2,
        // contact radius a = (3 Q R / (4 E*))^(1/3).
        let (r, e) = (0.15_f64, 2.2e11);
        // two equal principal relative radii r: a sphere of radius r on a plane
        let pc = PointContact::new(r, r, e);
        let delta = 1e-5_f64;
        let exact = 4.0 / 3.0 * (e / 2.0) * r.sqrt() * delta.powf(1.5);
        let (q, dq) = pc.load(delta);
        assert!((q - exact).abs() < 1e-12 * exact, "{q} vs {exact}");
        assert!((dq - 1.5 * q / delta).abs() < 1e-9 * dq);
        let (a, b, pmax) = pc.ellipse(q);
        let a_exact = (3.0 * q * r / (4.0 * e / 2.0)).cbrt();
        assert!((a - a_exact).abs() < 1e-12 * a_exact && (b - a_exact).abs() < 1e-12 * a_exact);
        assert!((pmax - 1.5 * q / (PI * a * b)).abs() < 1e-9 * pmax);
    }

    #[test]
    fn elliptic_integrals_hand_values() {
        // K(0.5) = 1.8540746773013719, E(0.5) = 1.3506438810476755 (Abramowitz & Stegun)
        let (k, e) = elliptic_integrals(0.5);
        assert!((k - 1.854_074_677_301_371_9).abs() < 1e-14);
        assert!((e - 1.350_643_881_047_675_5).abs() < 1e-14);
    }

    #[test]
    fn exact_ellipse_agrees_with_hamrock_brewe_within_its_accuracy() {
        // Hamrock & Brewe quote a few per cent over 1 <= Ry/Rx <= 100.
        for ratio in [1.3, 3.0, 10.0, 50.0] {
            let ex = PointContact::new(0.1, 0.1 * ratio, 2.2e11);
            let hb = PointContact::hamrock_brewe(0.1, 0.1 * ratio, 2.2e11);
            assert!((ex.k / hb.k - 1.0).abs() < 0.05, "k at {ratio}: {} vs {}", ex.k, hb.k);
            assert!(
                (ex.stiffness / hb.stiffness - 1.0).abs() < 0.10,
                "K at {ratio}: {} vs {}",
                ex.stiffness,
                hb.stiffness
            );
            // ellipse elongated along the larger radius
            let (a, b, _) = ex.ellipse(1000.0);
            assert!(a > b);
        }
    }

    #[test]
    fn line_contact_half_width_hand_value() {
        // b = sqrt(8 w R / (pi E')), p0 = 2 w / (pi b)
        let (b, p) = line_contact_half_width(1e6, 0.01, 2.2e11);
        assert!((b - (8.0e6 * 0.01 / (PI * 2.2e11)).sqrt()).abs() < 1e-15);
        assert!((p - 2.0e6 / (PI * b)).abs() < 1e-6 * p);
    }
}
