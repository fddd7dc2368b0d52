//! Viscosity of the oil against pressure (and, for the traction law, temperature).
//!
//! - Barus (1893): eta = eta0 exp(alpha p), `alpha` the pressure-viscosity coefficient of the
//!   oil's data sheet (the coefficient [W25] Table 1 gives, "in the Barus model").
//! - Roelands (1966): eta = eta0 exp((ln eta0 + 9.67)(-1 + (1 + 5.1e-9 p)^z)), with
//!   z = alpha / (5.1e-9 (ln eta0 + 9.67)) so that both laws have the same slope alpha at
//!   p = 0 ([W25] uses Roelands with z = 0.4 at the rib; with its oil, eta0 = 0.033 Pa s,
//!   that z is exactly its alpha = 1.28e-8 1/Pa). Roelands bends below Barus: at 0.55 GPa it
//!   gives 110 eta0 against Barus' 1150 eta0 for that oil. Measured isotherms of lubricants
//!   do not bend down like that above about 0.3 GPa (Bair, "High Pressure Rheology for
//!   Quantitative Elastohydrodynamics", Elsevier 2007, ch. 6: the local pressure-viscosity
//!   coefficient falls at first and rises again, so ln eta grows at least linearly at
//!   Hertzian pressures); the traction law therefore uses Barus by default
//!   (`oil.piezoviscosity`), Roelands stays selectable and is what the Newtonian law of
//!   [W25]'s rib, `traction` = 1, always uses.
//! - Temperature: eta(p, T) = eta(p, T0) exp(-beta (T - T0)) with the oil's
//!   temperature-viscosity coefficient `beta` (used by the thermal traction and the inlet
//!   shear-heating film reduction, about the oil's bulk temperature).
//! - Bulk oil temperature (`oilTemperature`, [`OilGrade`]): the kinematic viscosity by
//!   Walther's equation as ASTM D341 writes it, log10 log10(nu + 0.7) = A - B log10 T (nu in
//!   mm2/s, T in K), with A and B through the two points of the oil's data sheet, nu at 40 and
//!   100 degC (`oil.nu40`, `oil.nu100`); the density falls linearly from its 15 degC value,
//!   rho(T) = rho15 (1 - 6.5e-4 (T - 288.15 K)) (the thermal expansion of mineral and ester
//!   lubricants, 6-7e-4 1/K, ASTM D1250's tables for lubricating oils); eta = rho nu.

use crate::fastmath as fm;

/// Pressure-viscosity law of the oil (parameter `oil.piezoviscosity`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Piezoviscosity {
    /// eta0 exp(alpha p).
    Barus = 0,
    /// Roelands with the index z matched to alpha at p = 0.
    Roelands = 1,
}

/// Roelands viscosity at pressure `p` (z0 = 0.4), as written in [W25] for the rib.
pub fn roelands_viscosity(eta0: f64, p: f64) -> f64 {
    roelands_viscosity_with(eta0, fm::ln(eta0) + 9.67, p)
}

/// [`roelands_viscosity`] with `ln_eta0_967` = ln(eta0) + 9.67 precomputed.
#[inline]
pub fn roelands_viscosity_with(eta0: f64, ln_eta0_967: f64, p: f64) -> f64 {
    roelands_viscosity_z(eta0, ln_eta0_967, 0.4, p)
}

/// Roelands viscosity with pressure-viscosity index `z`.
#[inline]
pub fn roelands_viscosity_z(eta0: f64, ln_eta0_967: f64, z: f64, p: f64) -> f64 {
    let p = p.max(0.0);
    let expo = ln_eta0_967 * (-1.0 + fm::powf(1.0 + 5.1e-9 * p, z));
    eta0 * fm::exp(expo.min(60.0))
}

/// The Roelands index z that gives the initial slope `alpha` for viscosity `eta0`; floored at
/// 0.05 (alpha -> 0: an almost pressure-independent oil) and capped at 1.5.
pub fn roelands_index(eta0: f64, alpha: f64) -> f64 {
    let s = (libm::log(eta0) + 9.67).max(1e-3);
    (alpha / (5.1e-9 * s)).clamp(0.05, 1.5)
}

/// Roelands viscosity tabulated in ln(eta) against pressure for one oil (step 1 MPa up to
/// 5 GPa, linear interpolation: relative error below 1e-5; the formula beyond the table), or
/// the Barus law in closed form.
#[derive(Debug, Clone)]
pub struct ViscosityTable {
    eta0: f64,
    ln_eta0: f64,
    ln_eta0_967: f64,
    z: f64,
    /// Barus coefficient; `None` for Roelands.
    barus: Option<f64>,
    /// ln eta at k STEP (fixed length: the interpolation needs no bounds checks); empty
    /// (length 0) for Barus, which needs no table.
    ln_eta: Box<[f64]>,
}

impl ViscosityTable {
    const STEP: f64 = 1e6;
    const N: usize = 5001;

    /// Roelands with z0 = 0.4 ([W25]'s rib law; the Newtonian traction law).
    pub fn new(eta0: f64) -> ViscosityTable {
        Self::roelands(eta0, 0.4)
    }

    /// The oil's law: Barus with `alpha`, or Roelands with z matched to `alpha`.
    pub fn for_oil(eta0: f64, alpha: f64, law: Piezoviscosity) -> ViscosityTable {
        match law {
            Piezoviscosity::Roelands => Self::roelands(eta0, roelands_index(eta0, alpha)),
            Piezoviscosity::Barus => ViscosityTable {
                eta0,
                ln_eta0: libm::log(eta0),
                ln_eta0_967: libm::log(eta0) + 9.67,
                z: 0.4,
                barus: Some(alpha),
                ln_eta: Box::new([]),
            },
        }
    }

    fn roelands(eta0: f64, z: f64) -> ViscosityTable {
        let ln_eta0_967 = libm::log(eta0) + 9.67;
        let ln_eta: Vec<f64> = (0..Self::N)
            .map(|k| libm::log(roelands_viscosity_z(eta0, ln_eta0_967, z, k as f64 * Self::STEP)))
            .collect();
        let ln_eta = ln_eta.into_boxed_slice();
        ViscosityTable {
            eta0,
            ln_eta0: libm::log(eta0),
            ln_eta0_967,
            z,
            barus: None,
            ln_eta,
        }
    }

    /// Viscosity at pressure `p` (Pa).
    #[inline]
    pub fn eta(&self, p: f64) -> f64 {
        if self.barus.is_some() {
            return fm::exp(self.ln_eta(p));
        }
        let u = p.max(0.0) / Self::STEP;
        // also catches p = +inf or NaN (u as usize would saturate or be 0)
        if !(u < (Self::N - 1) as f64) {
            return roelands_viscosity_z(self.eta0, self.ln_eta0_967, self.z, p);
        }
        let k = u as usize;
        let f = u - k as f64;
        fm::exp(self.ln_eta[k] + f * (self.ln_eta[k + 1] - self.ln_eta[k]))
    }

    /// ln eta0 and the Barus coefficient where the law is Barus' (`None`: Roelands' table).
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    #[inline(always)]
    pub(crate) fn barus_law(&self) -> Option<(f64, f64)> {
        self.barus.map(|alpha| (self.ln_eta0, alpha))
    }

    /// ln of [`ViscosityTable::eta`] (the interpolated logarithm itself inside the table).
    #[inline(always)]
    pub fn ln_eta(&self, p: f64) -> f64 {
        if let Some(alpha) = self.barus {
            // capped like the Roelands formula (exp(60) eta0): no overflow at absurd pressures
            return self.ln_eta0 + (alpha * p.max(0.0)).min(60.0);
        }
        let u = p.max(0.0) * (1.0 / Self::STEP);
        // beyond the last interval (k + 1 >= N): the formula
        if !(u < (Self::N - 1) as f64) {
            return self.ln_eta_outside(p);
        }
        // SAFETY: 0 <= u < N - 1 (p.max(0.0) is never NaN), so the truncation is in range
        let k: usize = unsafe { u.to_int_unchecked() };
        let f = u - k as f64;
        let table: &[f64; Self::N] = self.ln_eta[..].try_into().expect("Roelands table of length N");
        let (a, b) = (table[k], table[(k + 1).min(Self::N - 1)]);
        a + f * (b - a)
    }

    /// [`ViscosityTable::ln_eta`] above the table (out of line, rare).
    #[cold]
    #[inline(never)]
    fn ln_eta_outside(&self, p: f64) -> f64 {
        fm::ln(roelands_viscosity_z(self.eta0, self.ln_eta0_967, self.z, p))
    }
}

/// A lubricant's viscosity against its bulk temperature (Walther / ASTM D341, two-point fit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OilGrade {
    /// Walther constants: log10 log10(nu_mm2s + 0.7) = a - b log10(T).
    a: f64,
    b: f64,
    /// Density at 15 degC (kg/m3).
    rho15: f64,
}

/// Thermal expansion of lubricating oils (1/K) for the density's temperature dependence.
const OIL_EXPANSION: f64 = 6.5e-4;
const T15: f64 = 288.15;
const T40: f64 = 313.15;
const T100: f64 = 373.15;

/// Density (kg/m3) at `t` (K) of an oil of density `rho15` at 15 degC (thermal expansion
/// 6.5e-4 1/K).
pub fn oil_density(rho15: f64, t: f64) -> f64 {
    rho15 * (1.0 - OIL_EXPANSION * (t - T15))
}

impl OilGrade {
    /// The grade through nu at 40 degC and at 100 degC (m2/s, nu40 > nu100 > 0) with density
    /// `rho15` (kg/m3) at 15 degC.
    pub fn new(nu40: f64, nu100: f64, rho15: f64) -> OilGrade {
        let ww = |nu: f64| libm::log10(libm::log10(nu * 1e6 + 0.7));
        let (w40, w100) = (ww(nu40), ww(nu100));
        let b = (w40 - w100) / (libm::log10(T100) - libm::log10(T40));
        OilGrade {
            a: w40 + b * libm::log10(T40),
            b,
            rho15,
        }
    }

    /// Kinematic viscosity (m2/s) at `t` (K).
    pub fn kinematic(&self, t: f64) -> f64 {
        let w = self.a - self.b * libm::log10(t);
        (libm::pow(10.0, libm::pow(10.0, w)) - 0.7) * 1e-6
    }

    /// Density (kg/m3) at `t` (K).
    pub fn density(&self, t: f64) -> f64 {
        oil_density(self.rho15, t)
    }

    /// Dynamic viscosity (Pa s) at ambient pressure and `t` (K).
    pub fn dynamic(&self, t: f64) -> f64 {
        self.density(t) * self.kinematic(t)
    }

    /// The temperature (K) at which the dynamic viscosity is `eta` (bisection on the monotonic
    /// law over -50..300 degC; the ends when `eta` lies outside).
    pub fn temperature_for(&self, eta: f64) -> f64 {
        let (mut lo, mut hi) = (223.15_f64, 573.15_f64);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if self.dynamic(mid) > eta {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viscosity_table_matches_roelands() {
        let t = ViscosityTable::new(0.033);
        for p in [0.0, 3.3e5, 1.7e8, 9.99e8, 2.5e9, 4.99e9, 6e9] {
            let (a, b) = (t.eta(p), roelands_viscosity(0.033, p));
            assert!((a - b).abs() < 1e-5 * b, "{p}: {a} vs {b}");
        }
    }

    /// A diverging state (an unstable fixed-step integrator) can produce an infinite pressure:
    /// the table must fall back to the formula, not index out of bounds.
    #[test]
    fn viscosity_table_survives_infinite_and_nan_pressure() {
        for t in [
            ViscosityTable::new(0.033),
            ViscosityTable::for_oil(0.033, 1.28e-8, Piezoviscosity::Barus),
        ] {
            assert!(t.eta(f64::INFINITY).is_finite());
            assert!(t.ln_eta(f64::INFINITY) >= t.ln_eta(5e9));
            assert_eq!(t.eta(f64::NAN), t.eta(0.0), "NaN pressure reads as zero");
            assert_eq!(t.eta(f64::NEG_INFINITY), t.eta(0.0));
        }
    }

    /// [W25]'s oil: Roelands z = 0.4 is the index its alpha = 1.28e-8 1/Pa implies, and both
    /// laws share that slope at p = 0 but part at Hertzian pressures.
    #[test]
    fn barus_and_roelands_share_the_initial_slope() {
        let (eta0, alpha) = (0.033, 1.28e-8);
        assert!((roelands_index(eta0, alpha) - 0.4).abs() < 2e-3);
        let b = ViscosityTable::for_oil(eta0, alpha, Piezoviscosity::Barus);
        let r = ViscosityTable::for_oil(eta0, alpha, Piezoviscosity::Roelands);
        let dp = 1e6;
        let slope = |t: &ViscosityTable| (t.ln_eta(dp) - t.ln_eta(0.0)) / dp;
        assert!((slope(&b) - alpha).abs() < 1e-3 * alpha);
        assert!((slope(&r) - alpha).abs() < 2e-2 * alpha, "{}", slope(&r));
        // 0.55 GPa: Barus about 1150 eta0, Roelands about 110 eta0
        let (eb, er) = (b.eta(5.5e8) / eta0, r.eta(5.5e8) / eta0);
        assert!((eb - (alpha * 5.5e8).exp()).abs() < 1e-9 * eb);
        assert!(er > 80.0 && er < 150.0, "{er}");
    }

    #[test]
    fn walther_fit_passes_through_its_points_and_matches_published_grades() {
        // ISO VG 68, VI 100 (ISO 3448 / ASTM D2270 tables): 68 and 8.6 mm2/s; at 70 degC the
        // viscosity-temperature charts of bearing catalogues (SKF's, VI 95) read about 20 mm2/s
        let oil = OilGrade::new(68e-6, 8.6e-6, 870.0);
        assert!((oil.kinematic(313.15) / 68e-6 - 1.0).abs() < 1e-12);
        assert!((oil.kinematic(373.15) / 8.6e-6 - 1.0).abs() < 1e-12);
        let nu70 = oil.kinematic(343.15) * 1e6;
        assert!(nu70 > 18.5 && nu70 < 21.5, "{nu70}");
        // monotonic, and the inverse
        let mut last = f64::INFINITY;
        for c in (-20..=150).step_by(10) {
            let t = 273.15 + c as f64;
            let eta = oil.dynamic(t);
            assert!(eta < last);
            last = eta;
            assert!((oil.temperature_for(eta) - t).abs() < 1e-9, "{c} degC");
        }
        // density: 870 at 15 degC, about 848 at 55 degC
        assert_eq!(oil.density(288.15), 870.0);
        assert!((oil.density(328.15) - 870.0 * (1.0 - 6.5e-4 * 40.0)).abs() < 1e-9);
    }
}
