//! Fatigue rating of the bearing: the basic dynamic load rating and basic rating life of
//! ISO 281, and the reference rating life of ISO/TS 16281 from lamina (slice) loads.
//! Pure functions of the geometry and of loads; nothing here knows a solver.
//!
//! Sources (Lundberg–Palmgren line-contact theory as the standards write it):
//! - ISO 281:2007, clause 7 (radial roller bearings): C_r = b_m f_c (i L_we cos α)^(7/9)
//!   Z^(3/4) D_we^(29/27) in N and mm, b_m = 1.1 for tapered and cylindrical roller bearings,
//!   f_c of its Table 7. f_c is computed here from the closed form ISO/TR 1281-1 gives for
//!   that table, f_c = λν · 207.9 γ^(2/9) (1−γ)^(29/27) (1+γ)^(−1/4)
//!   · [1 + (1.04 ((1−γ)/(1+γ))^(143/108))^(9/2)]^(−2/9) with λν = 0.83 and γ = D_we cos α / D_pw
//!   (`tests`: against the published table to 0.2 %).
//!   Dynamic equivalent load of a single-row radial roller bearing with α ≠ 0: e = 1.5 tan α;
//!   P = F_r for F_a/F_r ≤ e, else P = 0.4 F_r + 0.4 cot α F_a; with α = 0 (cylindrical) the
//!   bearing carries radial load alone, P = F_r. L10 = (C_r / P)^(10/3) million revolutions.
//!   For a tapered roller bearing α is the cup (outer raceway) angle and D_we the roller's
//!   mean diameter.
//! - ISO/TS 16281:2008, clause 7 (roller bearings): the rings' roller-load ratings
//!   Q_ci = C_r / (λν 0.378 Z cos α i^(7/9)) [1 + (1.038 ((1−γ)/(1+γ))^(143/108))^(9/2)]^(2/9),
//!   Q_ce = C_r / (λν 0.364 Z cos α i^(7/9)) [1 + (1.038 ((1−γ)/(1+γ))^(143/108))^(−9/2)]^(2/9)
//!   (λν = 0.83, the standard's eq. (49), divided out: the lamina loads carry the stress
//!   concentrations the reduction factor stands for; at ISO 281's rating condition the method
//!   then gives Lundberg–Palmgren's (C_r/(λν F_r))^4, `tests`), a lamina's share q_c = Q_c (1/n_s)^(7/9); the equivalent lamina load of the
//!   ring that rotates relative to the load q_e = (Σ_j q_jk^4 / Z)^(1/4), of the ring that
//!   stands q_e = (Σ_j q_jk^4.5 / Z)^(1/4.5); L10r = [Σ_k (q_eik/q_cik)^(9/2) + (q_eek/q_cek)^(9/2)]^(−8/9)
//!   million revolutions. Its load–life exponent is 4 (scale every lamina load by s: L10r
//!   scales by s^−4), against ISO 281's 10/3.
//!
//! - ISO 76:2006, clause 6 (radial roller bearings): the basic static radial load rating
//!   C_0r = 44 (1 − D_we cos α / D_pw) i Z L_we D_we cos α in N and mm, the load that makes a
//!   calculated contact stress of 4000 MPa at the centre of the most heavily loaded roller
//!   contact (a permanent deformation of about 1e-4 of the roller diameter); the static
//!   equivalent load of a single-row radial roller bearing with α ≠ 0,
//!   P_0r = 0.5 F_r + 0.22 cot α F_a, and P_0r = F_r where that is less; with α = 0,
//!   P_0r = F_r. The static safety factor s_0 = C_0r / P_0r.
//!
//! - ISO 281:2007, clause 9 and Annex B: the modified rating life L10m = a_ISO L10 (a1 = 1,
//!   90 % reliability). For radial roller bearings a_ISO = 0.1 [1 − (1.5859 − c2 / κ^c3)
//!   (e_C C_u / P)^0.4]^(−9.185) with (c2, c3) = (1.3993, 0.054381) for 0.1 ≤ κ < 0.4,
//!   (1.2348, 0.19087) for 0.4 ≤ κ < 1 and (1.2348, 0.071739) for 1 ≤ κ ≤ 4 (the pieces meet:
//!   `tests`); κ is taken as 0.1 below and 4 above that range, and a_ISO is capped at 50. The
//!   viscosity ratio κ = ν / ν1 with the rated viscosity ν1 = 45000 n^(−0.83) D_pw^(−0.5) for
//!   n < 1000 r/min and 4500 n^(−0.5) D_pw^(−0.5) above (mm²/s, r/min, mm). The fatigue load limit
//!   of roller bearings from their static rating (Annex B): C_u = C_0 / 8.2, times
//!   (100 / D_pw)^0.3 for D_pw > 100 mm. The contamination factor e_C (ISO 281 Table 13, for
//!   D_pw < 100 mm and ≥ 100 mm): extreme cleanliness 1; high cleanliness 0.8–0.6 and 0.9–0.8;
//!   normal cleanliness 0.6–0.5 and 0.8–0.6; slight contamination 0.5–0.3 and 0.6–0.4;
//!   typical contamination 0.3–0.1 and 0.4–0.2; severe contamination 0.1–0 (both); very
//!   severe 0. (The formula's constants are the standard's as the public implementations and
//!   the MESYS manual quote them; no worked example of the standard or a maker was at hand to
//!   check a_ISO against, `docs/model.md`.)
//!
//! What this product feeds in: the lamina loads are the model's own slice loads on the cone
//! and on the cup (its contact law, roller profile, diameter deviations, misalignment and
//! clearance), each raceway with its own normal loads; the standard's edge-stress factor
//! (its eq. 60, for a profile the load distribution does not resolve) is not applied. The
//! reference life is the *basic* reference rating life (a1 = 1, a_ISO = 1): lubrication and
//! contamination enter through an a_ISO a user multiplies in.

use super::file::Bearing;
use std::f64::consts::PI;

/// Life factor of ISO 281 for tapered and cylindrical roller bearings.
const B_M: f64 = 1.1;
/// λν of ISO/TR 1281-1 for radial roller bearings (reduction for edge stresses and
/// non-ideal load distribution).
const LAMBDA_NU: f64 = 0.83;
/// Largest life the outputs report (hours): a bearing that does not turn relative to its
/// load, or carries none, accumulates no rolling fatigue; this finite cap (1e12 h, 10^8
/// years) stands for "unlimited" so that no infinity leaves the element and a
/// Palmgren–Miner sum over a duty cycle stays finite.
pub const LIFE_CAP_HOURS: f64 = 1e12;

/// The geometry ISO 281 rates (SI units: m, rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RatingGeometry {
    /// Number of rollers per row.
    pub z: usize,
    /// Roller diameter (the mean diameter of a tapered roller), m.
    pub d_we: f64,
    /// Effective roller length, m.
    pub l_we: f64,
    /// Pitch diameter, m.
    pub d_pw: f64,
    /// Nominal contact angle (the cup angle of a tapered roller bearing), rad.
    pub alpha: f64,
}

impl RatingGeometry {
    /// γ = D_we cos α / D_pw.
    pub fn gamma(&self) -> f64 {
        self.d_we * libm::cos(self.alpha) / self.d_pw
    }
}

/// f_c of ISO 281 Table 7 (radial roller bearings) from its closed form (ISO/TR 1281-1).
pub fn f_c(gamma: f64) -> f64 {
    let g = gamma;
    let ratio = libm::pow((1.0 - g) / (1.0 + g), 143.0 / 108.0);
    LAMBDA_NU * 207.9 * libm::pow(g, 2.0 / 9.0) * libm::pow(1.0 - g, 29.0 / 27.0) / libm::pow(1.0 + g, 0.25)
        * libm::pow(1.0 + libm::pow(1.04 * ratio, 4.5), -2.0 / 9.0)
}

/// Basic dynamic radial load rating C_r of ISO 281 (N), one row.
pub fn basic_dynamic_load_rating(g: &RatingGeometry) -> f64 {
    let mm = 1e3;
    B_M * f_c(g.gamma())
        * libm::pow(g.l_we * mm * libm::cos(g.alpha), 7.0 / 9.0)
        * libm::pow(g.z as f64, 0.75)
        * libm::pow(g.d_we * mm, 29.0 / 27.0)
}

/// The effective roller length L_we (m) at which [`basic_dynamic_load_rating`] gives `c_r`
/// (N) for the rest of `g` (its `l_we` unused): the rating solved for the length,
/// L_we = (C_r / (b_m f_c Z^(3/4) D_we^(29/27)))^(9/7) / cos α in N and mm.
pub fn roller_length_for_rating(c_r: f64, g: &RatingGeometry) -> f64 {
    let mm = 1e3;
    let l_cos_mm = libm::pow(
        c_r / (B_M * f_c(g.gamma()) * libm::pow(g.z as f64, 0.75) * libm::pow(g.d_we * mm, 29.0 / 27.0)),
        9.0 / 7.0,
    );
    l_cos_mm / libm::cos(g.alpha) / mm
}

/// Calculated contact stress at the centre of the most heavily loaded roller contact under
/// the basic static load rating (ISO 76 for roller bearings), Pa.
pub const STATIC_LIMIT_STRESS: f64 = 4000e6;

/// Largest static safety factor the outputs report: a bearing without load (P_0r = 0) has no
/// static limit, and this finite cap stands for that, so that no infinity leaves the element.
pub const SAFETY_CAP: f64 = 1e9;

/// Basic static radial load rating C_0r of ISO 76 (N), one row.
pub fn basic_static_load_rating(g: &RatingGeometry) -> f64 {
    let mm = 1e3;
    let cos_a = libm::cos(g.alpha);
    44.0 * (1.0 - g.gamma()) * g.z as f64 * g.l_we * mm * g.d_we * mm * cos_a
}

/// Static equivalent radial load P_0r of ISO 76 for radial load `fr` >= 0 and axial load
/// `fa` >= 0 (N) on a single-row radial roller bearing of contact angle `alpha`.
pub fn static_equivalent_load(fr: f64, fa: f64, alpha: f64) -> f64 {
    if alpha <= 0.0 {
        return fr;
    }
    (0.5 * fr + 0.22 / libm::tan(alpha) * fa).max(fr)
}

/// Static safety factor s_0 = C_0r / P_0r, capped at [`SAFETY_CAP`].
pub fn static_safety(c0: f64, p0: f64) -> f64 {
    let s0 = c0 / p0;
    if s0.is_finite() && s0 >= 0.0 {
        s0.min(SAFETY_CAP)
    } else {
        SAFETY_CAP
    }
}

/// Dynamic equivalent radial load P of ISO 281 for radial load `fr` >= 0 and axial load
/// `fa` >= 0 (N) on a single-row radial roller bearing of contact angle `alpha`.
pub fn equivalent_load(fr: f64, fa: f64, alpha: f64) -> f64 {
    if alpha <= 0.0 {
        return fr;
    }
    let tan_a = libm::tan(alpha);
    let e = 1.5 * tan_a;
    if fa <= e * fr {
        fr
    } else {
        0.4 * fr + 0.4 / tan_a * fa
    }
}

/// Basic rating life L10 of ISO 281 in million revolutions ((C/P)^(10/3); P = 0: unlimited).
pub fn basic_rating_life(c: f64, p: f64) -> f64 {
    if p > 0.0 {
        libm::pow(c / p, 10.0 / 3.0)
    } else {
        f64::INFINITY
    }
}

/// Hours of a life of `million_revolutions` at relative ring speed `speed` (rad/s), capped
/// at [`LIFE_CAP_HOURS`].
pub fn hours(million_revolutions: f64, speed: f64) -> f64 {
    let rev_per_hour = speed.abs() / (2.0 * PI) * 3600.0;
    let h = million_revolutions * 1e6 / rev_per_hour;
    if h.is_finite() {
        h.min(LIFE_CAP_HOURS)
    } else {
        LIFE_CAP_HOURS
    }
}

/// Rated viscosity ν1 of ISO 281 (mm²/s) at relative ring speed `n_rpm` (r/min) for pitch
/// diameter `dpw_mm` (mm): the viscosity that separates the surfaces enough at that speed.
pub fn rated_viscosity(n_rpm: f64, dpw_mm: f64) -> f64 {
    if n_rpm < 1000.0 {
        45000.0 * libm::pow(n_rpm, -0.83) / libm::sqrt(dpw_mm)
    } else {
        4500.0 / libm::sqrt(n_rpm * dpw_mm)
    }
}

/// Fatigue load limit C_u of a roller bearing (N) from its static rating `c0` (N) and pitch
/// diameter `dpw` (m), ISO 281 Annex B.
pub fn fatigue_load_limit(c0: f64, dpw: f64) -> f64 {
    let dpw_mm = dpw * 1e3;
    let cu = c0 / 8.2;
    if dpw_mm > 100.0 {
        cu * libm::pow(100.0 / dpw_mm, 0.3)
    } else {
        cu
    }
}

/// Largest life modification factor ISO 281 allows.
pub const A_ISO_CAP: f64 = 50.0;

/// Life modification factor a_ISO of ISO 281 for radial roller bearings, from the viscosity
/// ratio `kappa` and `ec_cu_over_p` = e_C C_u / P (capped at [`A_ISO_CAP`]).
pub fn life_modification_factor(kappa: f64, ec_cu_over_p: f64) -> f64 {
    let k = if kappa.is_nan() { 0.1 } else { kappa.clamp(0.1, 4.0) };
    let (c2, c3) = if k < 0.4 {
        (1.3993, 0.054381)
    } else if k < 1.0 {
        (1.2348, 0.19087)
    } else {
        (1.2348, 0.071739)
    };
    let x = ec_cu_over_p.max(0.0);
    let bracket = 1.0 - (1.5859 - c2 / libm::pow(k, c3)) * libm::pow(x, 0.4);
    if bracket <= 0.0 {
        return A_ISO_CAP;
    }
    (0.1 * libm::pow(bracket, -9.185)).min(A_ISO_CAP)
}

/// ISO 281's modified rating life and the factors it took.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModifiedLife {
    /// L10m = a_ISO L10 (h), capped at [`LIFE_CAP_HOURS`].
    pub l10m: f64,
    pub a_iso: f64,
    /// Viscosity ratio κ = ν / ν1 (not clamped; 0 at standstill).
    pub kappa: f64,
}

/// The lamina load ratings of both rings (ISO/TS 16281) for `laminae` laminae per roller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaminaRatings {
    /// Basic dynamic load rating of one lamina of the inner ring (cone), N.
    pub q_ci: f64,
    /// ... of the outer ring (cup), N.
    pub q_ce: f64,
    pub laminae: usize,
}

impl LaminaRatings {
    pub fn new(g: &RatingGeometry, c_r: f64, laminae: usize) -> LaminaRatings {
        let gamma = g.gamma();
        let conformity = 1.038 * libm::pow((1.0 - gamma) / (1.0 + gamma), 143.0 / 108.0);
        let base = c_r / (LAMBDA_NU * g.z as f64 * libm::cos(g.alpha));
        let q_ci_roller = base / 0.378 * libm::pow(1.0 + libm::pow(conformity, 4.5), 2.0 / 9.0);
        let q_ce_roller = base / 0.364 * libm::pow(1.0 + libm::pow(conformity, -4.5), 2.0 / 9.0);
        let share = libm::pow(1.0 / laminae as f64, 7.0 / 9.0);
        LaminaRatings {
            q_ci: q_ci_roller * share,
            q_ce: q_ce_roller * share,
            laminae,
        }
    }
}

/// Which ring turns relative to the load (the load is fixed in space in this element).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RotatingRing {
    Cone,
    Cup,
}

/// (q_e)^(9/2) of lamina `k` of one ring over the rollers: the power mean of q^4 (the ring
/// rotates relative to the load: each of its points meets every roller) or of q^4.5 (the ring
/// stands: a point sees the roller loads where it stands). `offset` picks the ring in the
/// per-roller layout [cone laminae | cup laminae].
fn lamina_equivalent_power(slice_loads: &[f64], laminae: usize, offset: usize, k: usize, rotating: bool) -> f64 {
    let mut mean = [0.0];
    lamina_equivalent_powers::<1>(slice_loads, laminae, offset, k, rotating, &mut mean);
    mean[0]
}

/// [`lamina_equivalent_power`] of laminae `k .. k + L` at once (each lamina's sum over the
/// rollers in the same order, so the same bits; the L laminae side by side in vector lanes).
fn lamina_equivalent_powers<const L: usize>(
    slice_loads: &[f64],
    laminae: usize,
    offset: usize,
    k: usize,
    rotating: bool,
    out: &mut [f64; L],
) {
    let stride = 2 * laminae;
    let rollers = slice_loads.len() / stride;
    let mut sum = [0.0; L];
    for roller in slice_loads.chunks_exact(stride) {
        let q: &[f64; L] = roller[offset + k..offset + k + L].try_into().unwrap();
        for i in 0..L {
            let q = q[i].max(0.0);
            let q2 = q * q;
            sum[i] += if rotating { q2 * q2 } else { q2 * q2 * q.sqrt() };
        }
    }
    for i in 0..L {
        let mean = sum[i] / rollers as f64;
        out[i] = if rotating {
            // mean^(9/8) = mean * mean^(1/8): three correctly rounded square roots
            mean * mean.sqrt().sqrt().sqrt()
        } else {
            mean
        };
    }
}

/// Basic reference rating life L10r of ISO/TS 16281 in million revolutions from the lamina
/// loads, per roller the cone's `laminae` loads then the cup's (the layout of both models'
/// slice loads), over the rollers given: all of the bearing's, or one roller standing for all
/// when the load is axisymmetric. No load: unlimited (infinity).
pub fn reference_rating_life(ratings: &LaminaRatings, slice_loads: &[f64], rotating: RotatingRing) -> f64 {
    let ns = ratings.laminae;
    debug_assert!(!slice_loads.is_empty() && slice_loads.len() % (2 * ns) == 0);
    let pow45 = |q: f64| q * q * (q * q) * q.sqrt();
    let (qi45, qe45) = (pow45(ratings.q_ci), pow45(ratings.q_ce));
    // the laminae four at a time (then one by one), added in lamina order
    const L: usize = 4;
    let (cone_turns, cup_turns) = (rotating == RotatingRing::Cone, rotating == RotatingRing::Cup);
    let mut damage = 0.0;
    let mut k = 0;
    while k < ns {
        let (mut cone, mut cup) = ([0.0; L], [0.0; L]);
        let width = if k + L <= ns {
            lamina_equivalent_powers(slice_loads, ns, 0, k, cone_turns, &mut cone);
            lamina_equivalent_powers(slice_loads, ns, ns, k, cup_turns, &mut cup);
            L
        } else {
            cone[0] = lamina_equivalent_power(slice_loads, ns, 0, k, cone_turns);
            cup[0] = lamina_equivalent_power(slice_loads, ns, ns, k, cup_turns);
            1
        };
        for i in 0..width {
            damage += cone[i] / qi45 + cup[i] / qe45;
        }
        k += width;
    }
    if damage > 0.0 {
        libm::pow(damage, -8.0 / 9.0)
    } else {
        f64::INFINITY
    }
}

/// The ratings of one bearing for one slice count, and its lives from the loads it carries.
#[derive(Debug, Clone, PartialEq)]
pub struct BearingRating {
    pub geometry: RatingGeometry,
    /// Basic dynamic radial load rating (N).
    pub c_r: f64,
    /// Basic static radial load rating (N).
    pub c_0r: f64,
    pub laminae: LaminaRatings,
}

impl BearingRating {
    /// ISO 281's geometry of `b`: the cup angle as the contact angle, the roller's mean
    /// diameter and its length as the effective length; one lamina per slice.
    pub fn new(b: &Bearing, slices: usize) -> BearingRating {
        let geometry = RatingGeometry {
            z: b.roller_count,
            d_we: b.roller_mean_diameter,
            l_we: b.roller_length,
            d_pw: b.pitch_diameter,
            alpha: b.cup_angle,
        };
        let c_r = basic_dynamic_load_rating(&geometry);
        BearingRating {
            geometry,
            c_r,
            c_0r: basic_static_load_rating(&geometry),
            laminae: LaminaRatings::new(&geometry, c_r, slices),
        }
    }

    /// ISO 281 basic rating life (h) under carried radial load `fr` and axial load `fa` at
    /// cone speed `cone_speed` and cup speed `cup_speed` (rad/s).
    pub fn life_l10(&self, fr: f64, fa: f64, cone_speed: f64, cup_speed: f64) -> f64 {
        let p = equivalent_load(fr.abs(), fa.abs(), self.geometry.alpha);
        hours(basic_rating_life(self.c_r, p), cone_speed - cup_speed)
    }

    /// ISO 281 modified rating life of basic rating life `l10_hours` under carried radial load
    /// `fr` and axial load `fa`, oil of kinematic viscosity `nu` (m²/s) at the operating
    /// temperature, relative ring speed `relative_speed` (rad/s) and contamination factor `ec`.
    pub fn modified_life(&self, l10_hours: f64, fr: f64, fa: f64, nu: f64, relative_speed: f64, ec: f64) -> ModifiedLife {
        let n_rpm = relative_speed.abs() * 30.0 / PI;
        let dpw = self.geometry.d_pw;
        let kappa = if n_rpm > 0.0 {
            nu * 1e6 / rated_viscosity(n_rpm, dpw * 1e3)
        } else {
            0.0
        };
        let p = equivalent_load(fr.abs(), fa.abs(), self.geometry.alpha);
        let cu = fatigue_load_limit(self.c_0r, dpw);
        let a_iso = if p > 0.0 {
            life_modification_factor(kappa, ec * cu / p)
        } else {
            A_ISO_CAP
        };
        ModifiedLife {
            l10m: (a_iso * l10_hours).min(LIFE_CAP_HOURS),
            a_iso,
            kappa,
        }
    }

    /// ISO 76 static safety factor under carried radial load `fr` and axial load `fa`.
    pub fn static_safety(&self, fr: f64, fa: f64) -> f64 {
        static_safety(self.c_0r, static_equivalent_load(fr.abs(), fa.abs(), self.geometry.alpha))
    }

    /// ISO/TS 16281 basic reference rating life (h) from the slice loads (layout of
    /// [`reference_rating_life`]); the ring turning faster turns relative to the load.
    pub fn life_l10r(&self, slice_loads: &[f64], cone_speed: f64, cup_speed: f64) -> f64 {
        let rotating = if cone_speed.abs() >= cup_speed.abs() {
            RotatingRing::Cone
        } else {
            RotatingRing::Cup
        };
        hours(reference_rating_life(&self.laminae, slice_loads, rotating), cone_speed - cup_speed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ISO 281:2007 Table 7, f_c of radial roller bearings, against γ.
    const TABLE_7: [(f64, f64); 20] = [
        (0.01, 52.1),
        (0.02, 60.8),
        (0.03, 66.5),
        (0.04, 70.7),
        (0.05, 74.1),
        (0.06, 76.9),
        (0.07, 79.2),
        (0.08, 81.2),
        (0.09, 82.8),
        (0.10, 84.2),
        (0.12, 86.4),
        (0.14, 87.7),
        (0.16, 88.5),
        (0.18, 88.8),
        (0.20, 88.7),
        (0.22, 88.2),
        (0.24, 87.5),
        (0.26, 86.4),
        (0.28, 85.2),
        (0.30, 83.8),
    ];

    #[test]
    fn f_c_reproduces_the_published_table() {
        for (g, want) in TABLE_7 {
            let got = f_c(g);
            assert!((got / want - 1.0).abs() < 2e-3, "gamma {g}: f_c {got:.2}, ISO 281 Table 7 {want}");
        }
    }

    fn trb() -> RatingGeometry {
        RatingGeometry {
            z: 17,
            d_we: 21.37e-3,
            l_we: 42.06e-3,
            d_pw: 177.91e-3,
            alpha: 15f64.to_radians(),
        }
    }

    #[test]
    fn load_rating_by_hand() {
        // gamma = 21.37 cos 15 / 177.91 = 0.11602; the formula written out in mm and N
        let g = trb();
        let gamma = 21.37 * 15f64.to_radians().cos() / 177.91;
        let want = 1.1 * f_c(gamma) * (42.06 * 15f64.to_radians().cos()).powf(7.0 / 9.0) * 17f64.powf(0.75) * 21.37f64.powf(29.0 / 27.0);
        let c = basic_dynamic_load_rating(&g);
        assert!((c / want - 1.0).abs() < 1e-12, "{c} vs {want}");
        // and the table read by linear interpolation between 0.10 and 0.12
        let fc_table = 84.2 + (86.4 - 84.2) * (gamma - 0.10) / 0.02;
        assert!((f_c(gamma) / fc_table - 1.0).abs() < 3e-3);
        assert!(c > 3.5e5 && c < 4.1e5, "{c}");
    }

    #[test]
    fn equivalent_load_follows_iso_281_single_row_rules() {
        let a = 15f64.to_radians();
        let e = 1.5 * a.tan();
        // at and below e: the radial load alone
        assert_eq!(equivalent_load(10e3, 0.99 * e * 10e3, a), 10e3);
        assert_eq!(equivalent_load(10e3, e * 10e3, a), 10e3);
        // above e: X = 0.4, Y = 0.4 cot(alpha)
        let p = equivalent_load(10e3, 20e3, a);
        assert!((p - (0.4 * 10e3 + 0.4 / a.tan() * 20e3)).abs() < 1e-9);
        // pure axial load
        assert!((equivalent_load(0.0, 30e3, a) - 0.4 / a.tan() * 30e3).abs() < 1e-9);
        // cylindrical roller bearing: radial load only
        assert_eq!(equivalent_load(7e3, 0.0, 0.0), 7e3);
        // continuity at e is not a property of the standard: P jumps there by design
        let below = equivalent_load(10e3, e * 10e3, a);
        let above = equivalent_load(10e3, e * 10e3 * (1.0 + 1e-12), a);
        assert!(above >= below * 0.99);
    }

    /// a_ISO by hand at κ = 1, e_C C_u / P = 0.1: 0.1 [1 − (1.5859 − 1.2348) 0.1^0.4]^−9.185.
    #[test]
    fn life_modification_factor_by_hand() {
        let bracket: f64 = 1.0 - (1.5859 - 1.2348) * 0.1_f64.powf(0.4);
        let by_hand = 0.1 * bracket.powf(-9.185);
        assert!((by_hand - 0.3987).abs() < 1e-4, "{by_hand}");
        assert!((life_modification_factor(1.0, 0.1) - by_hand).abs() < 1e-12);
    }

    /// The standard's three pieces meet at κ = 0.4 and κ = 1 (to the constants' five digits):
    /// a check of the transcribed constants.
    #[test]
    fn life_modification_factor_is_continuous_in_kappa() {
        for x in [0.02, 0.1, 0.3, 0.6] {
            for k in [0.4, 1.0] {
                let below = life_modification_factor(k * (1.0 - 1e-12), x);
                let above = life_modification_factor(k, x);
                assert!(
                    (below / above - 1.0).abs() < 2e-4,
                    "kappa {k}, eC Cu/P {x}: {below} against {above}"
                );
            }
        }
    }

    /// Its bounds: a_ISO rises with κ and with e_C C_u / P, reaches the cap of 50 for a clean,
    /// well-lubricated, lightly loaded bearing (κ beyond 4 counts as 4), and falls to 0.1 for
    /// e_C → 0 whatever the lubrication.
    #[test]
    fn life_modification_factor_bounds() {
        assert_eq!(life_modification_factor(1e6, 10.0), A_ISO_CAP);
        assert_eq!(life_modification_factor(1e6, 0.5), life_modification_factor(4.0, 0.5));
        assert_eq!(life_modification_factor(1e-3, 0.5), life_modification_factor(0.1, 0.5));
        for k in [0.1, 0.5, 2.0, 4.0] {
            assert!((life_modification_factor(k, 0.0) - 0.1).abs() < 1e-15, "kappa {k}");
        }
        let mut last = 0.0;
        for k in [0.1, 0.2, 0.4, 0.7, 1.0, 2.0, 4.0] {
            let a = life_modification_factor(k, 0.2);
            assert!(a > last, "kappa {k}: {a}");
            last = a;
        }
        assert!(life_modification_factor(1.0, 0.3) > life_modification_factor(1.0, 0.2));
    }

    /// ν1 of ISO 281 at its two speed ranges, and C_u with its size factor above 100 mm.
    #[test]
    fn rated_viscosity_and_fatigue_load_limit() {
        assert!((rated_viscosity(500.0, 100.0) - 45000.0 * 500f64.powf(-0.83) / 10.0).abs() < 1e-9);
        assert!((rated_viscosity(3600.0, 100.0) - 7.5).abs() < 1e-12);
        assert!((fatigue_load_limit(82_000.0, 0.05) - 10_000.0).abs() < 1e-9);
        assert!((fatigue_load_limit(82_000.0, 0.2) - 10_000.0 * 0.5f64.powf(0.3)).abs() < 1e-9);
    }

    #[test]
    fn basic_life_exponent_is_ten_thirds() {
        let c = 100e3;
        let l1 = basic_rating_life(c, 10e3);
        let l2 = basic_rating_life(c, 20e3);
        assert!((l1 / l2 - 2f64.powf(10.0 / 3.0)).abs() < 1e-9);
        assert!((l1 - 10f64.powf(10.0 / 3.0)).abs() < 1e-9 * l1);
        assert_eq!(basic_rating_life(c, 0.0), f64::INFINITY);
        // hours: 1 million revolutions at 1000 rpm is 16.67 h
        let h = hours(1.0, 1000.0 * PI / 30.0);
        assert!((h - 1e6 / 60e3).abs() < 1e-9);
        assert_eq!(hours(1.0, 0.0), LIFE_CAP_HOURS);
        assert_eq!(hours(f64::INFINITY, 100.0), LIFE_CAP_HOURS);
    }

    /// The per-roller layout [cone laminae | cup laminae] from separate arrays.
    fn interleave(cone: &[f64], cup: &[f64], ns: usize) -> Vec<f64> {
        cone.chunks(ns)
            .zip(cup.chunks(ns))
            .flat_map(|(a, b)| a.iter().chain(b).copied())
            .collect()
    }

    #[test]
    fn lamina_life_of_uniform_loads_by_hand() {
        // every roller and lamina carries the same load: q_e = q on both rings, and
        // L10r = [n_s ((q/q_ci)^4.5 + (q/q_ce)^4.5)]^(-8/9)
        let g = trb();
        let c = basic_dynamic_load_rating(&g);
        let ns = 20;
        let r = LaminaRatings::new(&g, c, ns);
        let q = 500.0;
        let loads = vec![q; g.z * ns];
        let want = (ns as f64 * ((q / r.q_ci).powf(4.5) + (q / r.q_ce).powf(4.5))).powf(-8.0 / 9.0);
        for ring in [RotatingRing::Cone, RotatingRing::Cup] {
            let l = reference_rating_life(&r, &interleave(&loads, &loads, ns), ring);
            assert!((l / want - 1.0).abs() < 1e-12, "{l} vs {want}");
        }
        // one roller standing for all (axisymmetric load) gives the same
        let l1 = reference_rating_life(&r, &loads[..2 * ns], RotatingRing::Cone);
        assert!((l1 / want - 1.0).abs() < 1e-12);
        // the ratings by hand: Q_ci / Q_ce = 0.364/0.378 [1+a^4.5]^(2/9) / [1+a^-4.5]^(2/9) = (0.364/0.378) a
        let gamma = g.gamma();
        let a = 1.038 * ((1.0 - gamma) / (1.0 + gamma)).powf(143.0 / 108.0);
        assert!((r.q_ci / r.q_ce - 0.364 / 0.378 * a).abs() < 1e-12);
    }

    #[test]
    fn lamina_life_does_not_depend_on_the_number_of_laminae() {
        // a uniform line load cut into n_s laminae: q = Q / n_s, q_c ~ n_s^(-7/9)
        let g = trb();
        let c = basic_dynamic_load_rating(&g);
        let roller_load = 8e3;
        let mut lives = Vec::new();
        for ns in [5, 20, 80] {
            let r = LaminaRatings::new(&g, c, ns);
            let loads = vec![roller_load / ns as f64; g.z * ns];
            lives.push(reference_rating_life(&r, &interleave(&loads, &loads, ns), RotatingRing::Cone));
        }
        for l in &lives[1..] {
            assert!((l / lives[0] - 1.0).abs() < 1e-10, "{lives:?}");
        }
    }

    #[test]
    fn lamina_load_life_exponent_is_four() {
        // any distribution, scaled by s: L10r scales by s^-4
        let g = trb();
        let c = basic_dynamic_load_rating(&g);
        let ns = 10;
        let r = LaminaRatings::new(&g, c, ns);
        let cone: Vec<f64> = (0..g.z * ns)
            .map(|i| (300.0 + 97.0 * (i % 7) as f64) * ((i / ns) % 3) as f64)
            .collect();
        let cup: Vec<f64> = cone.iter().map(|q| 1.05 * q).collect();
        let l1 = reference_rating_life(&r, &interleave(&cone, &cup, ns), RotatingRing::Cone);
        let s = 1.7;
        let cone2: Vec<f64> = cone.iter().map(|q| q * s).collect();
        let cup2: Vec<f64> = cup.iter().map(|q| q * s).collect();
        let l2 = reference_rating_life(&r, &interleave(&cone2, &cup2, ns), RotatingRing::Cone);
        assert!((l1 / l2 - s.powf(4.0)).abs() < 1e-9 * s.powf(4.0), "{}", l1 / l2);
    }

    #[test]
    fn lamina_method_at_the_rating_condition_is_lundberg_palmgren_without_lambda_nu() {
        // ISO 281's rating condition of a radial roller bearing: pure radial load, zero
        // clearance, ideal line contact (uniform along the roller), the cone turning: roller
        // loads Q_max cos(psi)^(10/9) over half the circle (load zone epsilon = 0.5). Many
        // rollers stand for Lundberg–Palmgren's integrals.
        let g = RatingGeometry { z: 3600, ..trb() };
        let c = basic_dynamic_load_rating(&g);
        let ns = 4;
        let r = LaminaRatings::new(&g, c, ns);
        let q_max = 1.0;
        let roller: Vec<f64> = (0..g.z)
            .map(|j| {
                let psi = 2.0 * PI * (j as f64 + 0.5) / g.z as f64;
                q_max * psi.cos().max(0.0).powf(10.0 / 9.0)
            })
            .collect();
        let z = g.z as f64;
        let j_r = roller
            .iter()
            .enumerate()
            .map(|(j, q)| q * (2.0 * PI * (j as f64 + 0.5) / z).cos())
            .sum::<f64>()
            / (z * q_max);
        let j_1 = (roller.iter().map(|q| q.powi(4)).sum::<f64>() / z).powf(0.25) / q_max;
        let j_2 = (roller.iter().map(|q| q.powf(4.5)).sum::<f64>() / z).powf(1.0 / 4.5) / q_max;
        // the standard's 0.378 and 0.364 are these integrals' ratios (rotating and standing ring)
        assert!((j_r / j_1 / 0.378 - 1.0).abs() < 5e-3, "J_r/J_1 = {}", j_r / j_1);
        assert!((j_r / j_2 / 0.364 - 1.0).abs() < 5e-3, "J_r/J_2 = {}", j_r / j_2);
        // the life: (C_r / (lambda nu F_r))^4 to the rounding of those two constants (1.4 % at
        // most in the fourth power): the lamina method reads C_r without ISO 281's reduction
        // lambda nu for edge stresses, which the lamina loads resolve themselves
        let f_r = z * q_max * j_r * g.alpha.cos();
        let loads: Vec<f64> = roller.iter().flat_map(|q| std::iter::repeat_n(q / ns as f64, 2 * ns)).collect();
        let l = reference_rating_life(&r, &loads, RotatingRing::Cone);
        let lp = (c / (LAMBDA_NU * f_r)).powi(4);
        assert!(
            (l / lp - 1.0).abs() < 0.02,
            "L10r {l:.4e} vs Lundberg–Palmgren {lp:.4e}: {}",
            l / lp
        );
        // so at P = C_r the reference life is lambda nu^-4 = 2.11 million revolutions, not 1
        let at_c = l * (f_r / c).powi(4);
        assert!((at_c - LAMBDA_NU.powi(-4)).abs() < 0.02 * at_c, "{at_c}");
    }

    #[test]
    fn concentrated_load_shortens_the_lamina_life() {
        // the same total load on half the laminae (an edge load): a shorter life, and the
        // standing ring's mean (q^4.5) weighs an uneven roller distribution more than the
        // rotating ring's (q^4)
        let g = trb();
        let c = basic_dynamic_load_rating(&g);
        let ns = 20;
        let r = LaminaRatings::new(&g, c, ns);
        let uniform = vec![400.0; g.z * ns];
        let edge: Vec<f64> = (0..g.z * ns).map(|i| if i % ns < ns / 2 { 800.0 } else { 0.0 }).collect();
        let lu = reference_rating_life(&r, &interleave(&uniform, &uniform, ns), RotatingRing::Cone);
        let le = reference_rating_life(&r, &interleave(&edge, &edge, ns), RotatingRing::Cone);
        assert!(le < 0.2 * lu, "{le} vs {lu}");
        assert_eq!(reference_rating_life(&r, &vec![0.0; 2 * ns], RotatingRing::Cone), f64::INFINITY);
        let uneven: Vec<f64> = (0..g.z * ns).map(|i| if (i / ns) % 2 == 0 { 800.0 } else { 0.0 }).collect();
        let zero = vec![0.0; g.z * ns];
        let cone_rot = reference_rating_life(&r, &interleave(&zero, &uneven, ns), RotatingRing::Cone); // cup stands
        let cup_rot = reference_rating_life(&r, &interleave(&zero, &uneven, ns), RotatingRing::Cup); // cup rotates
        assert!(cone_rot < cup_rot, "{cone_rot} vs {cup_rot}");
    }
}
