//! Friction torque and power loss of the quasi-static model (MODEL.md section 7), from the
//! converged contact loads and the epicyclic kinematics with cage slip (outer-raceway
//! control [L22]: pure rolling on the cup at mid-roller, sliding S_c omega_i R_i on the cone).
//!
//! Traction is evaluated per contact (cone line, cup line, flange), as in Harris and [L22]:
//! film thickness from the contact's line load over its loaded length, film ratio, one
//! traction coefficient from the load-weighted mean slide-to-roll ratio. The slice-level
//! sliding speeds still enter exactly through two sums the solver accumulates in its slice
//! loop at no extra cost: sum q |v_s| (sliding power) and sum q s sgn(v_s) (skew moment of
//! the traction forces, N = -s F_t about the roller centre).
//!
//! Power = rolling resistance x rolling speed + traction x sliding speed, summed over all
//! contacts; the torque needed to drive the cone is power / speed, computed from speed
//! ratios so it stays finite and continuous through zero speed.
//!
//! Both rings may turn (`cupSpeed`): every contact speed is a surface speed relative to the
//! cage, and in the cage frame the cone turns at omega_i - omega_c = (1 - c) (omega_i -
//! omega_o) and the cup at omega_o - omega_c = -c (omega_i - omega_o) (c the cage ratio), so
//! all of them, the traction and the dissipated power follow the relative speed
//! omega_i - omega_o alone: "speed" and "per unit cone speed" below mean that relative speed
//! (the cone's speed when the cup stands). The torque the power is divided by is then the
//! torque between the rings (the cone's with a standing cup), zero power when they turn
//! together.
//!
//! EHL (`lubrication` = 0): Hamrock film, boundary/mixed/full-film traction of [W25],
//! Zhou-Hoeprich rolling resistance; flange: asperity share mu0 exp(-1.8 Lambda^1.2) of the
//! load plus the viscous film traction over the Hertz ellipse. Dry (`lubrication` = 1): one
//! Coulomb coefficient, smoothly regularised, at raceways and flange [D19].

use super::load_table::LoadTable;
use super::{LineSums, RollerEval};
use crate::bearing::Bearing;
use crate::contact::line_contact_half_width;
use crate::fastmath as fm;
use crate::geometry::{ContactLine, Geometry};
use crate::model::{Inputs, Lubrication, Outputs, Parameters};
use crate::tribology as tr;

/// Per-slice weights the solver multiplies with the slice loads.
#[derive(Debug, Clone)]
pub struct SliceWeights {
    /// |sliding speed| per unit cone speed.
    pub slide: Vec<f64>,
    /// Entrainment speed per unit cone speed.
    pub entrain: Vec<f64>,
    /// Axial station times the sign of the sliding speed.
    pub skew: Vec<f64>,
    /// Sign of the sliding speed.
    pub sign: Vec<f64>,
}

/// Kinematics of one contact point per unit cone speed, in the cage frame.
#[derive(Debug, Clone, Copy, Default)]
struct Kinematics {
    /// Sliding speed (roller surface minus ring surface, along the rolling direction).
    slide: f64,
    /// Entrainment speed (mean of the two surface speeds, magnitude).
    entrain: f64,
}

impl Kinematics {
    fn new(roller: f64, ring: f64) -> Kinematics {
        Kinematics {
            slide: roller - ring,
            entrain: 0.5 * (roller + ring).abs(),
        }
    }
}

/// Torque parts (N m) needed to drive the cone.
#[derive(Debug, Clone, Copy, Default)]
pub struct TorqueParts {
    pub raceway: f64,
    pub flange: f64,
    /// Torque the cone feels ([L22] M_inner) and the cup feels ([L22] M_outer), with the sign of speed.
    pub cone: f64,
    pub cup: f64,
}

/// Friction of one raceway contact of one roller.
#[derive(Debug, Clone, Copy, Default)]
struct RacewayFriction {
    /// Friction power per unit cone speed (N m).
    torque: f64,
    /// Skew moment of the traction on the roller (N m).
    skew: f64,
    /// Net sliding traction force on the ring along its direction of motion e_t (N).
    slide_force: f64,
    /// Rolling resistance (N, >= 0).
    rolling: f64,
}

/// Per-contact data of one raceway line.
#[derive(Debug, Clone)]
struct LineFriction {
    /// Kinematics at mid-roller.
    mid: Kinematics,
    /// Equivalent radius at mid-roller.
    r_bar: f64,
}

/// What a raceway slice's friction needs of the speed, the oil and the slice's position only:
/// every roller has the same kinematics, so these are computed once per slice position and
/// raceway (and kept while the speed does not change) instead of per roller and slice. Each
/// value is the one the per-slice formula computes (same operations in the same order); only
/// the load-dependent part remains per slice (read from the table at fidelity 0).
#[derive(Debug, Clone, Copy, Default)]
struct SliceConst {
    /// Entrainment and sliding speed (m/s), ln of the sliding speed (-inf at zero).
    u_e: f64,
    v_s: f64,
    ln_vs: f64,
    /// Kinematic slide-to-roll ratio of the boundary law.
    boundary_slide_roll: f64,
    /// Inlet heating (Gupta et al.): L^0.42 of the numerator and the whole denominator
    /// 1 + 0.213 (1 + 2.23 s^0.83) L^0.64; `heated` false when L = 0 (factor 1).
    heated: bool,
    l042: f64,
    heat_den: f64,
    /// Hamrock film: r 2.922 U^0.692 G^0.470 (times W^-0.166 per slice) and E' r.
    film_a: f64,
    e_r: f64,
    /// Rolling resistance: 29.2 r / alpha (G U)^0.648 (times W^0.246 l per slice), E' r l;
    /// `rolls` false where the law gives zero whatever the load.
    rolls: bool,
    roll_a: f64,
    e_r_l: f64,
    /// Largest load read from the friction table (`TABLE_PRESSURE`); above it the laws are
    /// evaluated directly.
    table_max: f64,
    /// The mixed law at this speed (`tribology::mixed`).
    mixed: tr::Mixed,
}

/// Hertz pressure up to which the slice laws are read from the table: beyond the 4 GPa of
/// ISO 76's static rating for roller bearings, where the film laws' viscosity and limiting
/// shear turn sharply and interpolation loses accuracy, every slice is evaluated directly.
const TABLE_PRESSURE: f64 = 4.5e9;

/// What the lane read of the friction table (`friction_lanes.rs`) takes of a raceway's slice
/// positions, in groups of four slices (the last padded with zeros): each group's quantities
/// in fixed arrays, so that a group of lanes is read with one bounds check.
#[derive(Debug, Clone, Default)]
struct LineLanes {
    groups: Vec<LaneGroup>,
}

/// Four slice positions of a [`LineLanes`].
#[derive(Debug, Clone, Copy, Default)]
struct LaneGroup {
    /// `SliceConst::table_max` where the slice slides, else -1 (no load is read).
    table_max: [f64; 4],
    /// 1 where the slice rolls (`SliceConst::rolls`), else 0.
    rolls: [f64; 4],
    /// The [`SliceWeights`].
    slide: [f64; 4],
    entrain: [f64; 4],
    skew: [f64; 4],
    sign: [f64; 4],
}

impl LineLanes {
    fn fill(&mut self, consts: &[SliceConst], w: &SliceWeights) {
        self.groups.clear();
        self.groups.resize(consts.len().div_ceil(4), LaneGroup::default());
        for (k, c) in consts.iter().enumerate() {
            let (g, i) = (&mut self.groups[k / 4], k % 4);
            g.table_max[i] = if c.v_s > 0.0 { c.table_max } else { -1.0 };
            g.rolls[i] = if c.rolls { 1.0 } else { 0.0 };
            g.slide[i] = w.slide[k];
            g.entrain[i] = w.entrain[k];
            g.skew[i] = w.skew[k];
            g.sign[i] = w.sign[k];
        }
    }
}

/// [`SliceConst`] of both raceways at one speed.
#[derive(Debug, Clone, Default)]
struct SpeedCache {
    /// |speed| the slice constants were computed for (NaN: none yet).
    speed: f64,
    /// |speed| the tables were built for (NaN: none yet).
    table_speed: f64,
    cone: Vec<SliceConst>,
    cup: Vec<SliceConst>,
    cone_lanes: LineLanes,
    cup_lanes: LineLanes,
    /// Traction coefficient and rolling resistance per unit load of every slice position of
    /// both raceways (cone lines, then cup lines), and the flange's friction force per unit
    /// load, at this speed, tabulated over the load as the solves need them (fidelity 0).
    raceways: LoadTable,
    flange: LoadTable,
}

/// Precomputed kinematics and oil data.
#[derive(Debug, Clone)]
pub struct FrictionModel {
    pub cone_weights: SliceWeights,
    pub cup_weights: SliceWeights,
    cone: LineFriction,
    cup: LineFriction,
    flange: Kinematics,
    /// Axial station of the flange contact along the roller axis (for its skew moment).
    flange_s: f64,
    /// Cone and cup raceway radii at mid-roller (lever arms of the ring torques).
    ring_radii: (f64, f64),
    slice_len: f64,
    eta0: f64,
    alpha: f64,
    sigma: f64,
    mu: f64,
    flange_mu0: f64,
    /// Coulomb coefficient of the rib contact (`flange.mu`); `None`: the rib's own law.
    rib_coulomb: Option<f64>,
    /// Full-film traction law; for law 0 the lubricated contact laws' data.
    traction: tr::TractionLaw,
    lubricant: tr::Lubricant,
    /// The lubricant supply: starved films and rolling resistance (`tribology::supply`).
    supply: tr::SupplyLaw,
    /// Per-slice-position constants at the last speed (`traction` = 0 with EHL).
    cache: SpeedCache,
    /// Solve the thermal Eyring film equation by Halley's method (fidelity 0); Newton's, as
    /// the dynamic model does, for the quasi-static start of the dynamic model (its outputs
    /// keep Newton's bits).
    halley: bool,
    /// Read the friction table four slices at a time (the CPU has AVX2), else two.
    four_lanes: bool,
}

impl FrictionModel {
    pub fn new(b: &Bearing, p: &Parameters, g: &Geometry, cage_ratio: f64, spin_ratio: f64) -> FrictionModel {
        // Cone surface moves at (1 - c) r in the cage frame; the roller surface facing it at
        // -w R (w < 0 is the roller spin about its axis from the large to the small end).
        let cone_kin = |k: usize| Kinematics::new(-spin_ratio * g.slice_radius[k], (1.0 - cage_ratio) * g.cone.raceway_radius[k]);
        // The cup is fixed: -c r in the cage frame; the roller surface facing it at w R.
        let cup_kin = |k: usize| Kinematics::new(spin_ratio * g.slice_radius[k], -cage_ratio * g.cup.raceway_radius[k]);
        let weights = |kin: &dyn Fn(usize) -> Kinematics| SliceWeights {
            slide: (0..g.slices).map(|k| kin(k).slide.abs()).collect(),
            entrain: (0..g.slices).map(|k| kin(k).entrain).collect(),
            skew: (0..g.slices).map(|k| g.slice_s[k] * kin(k).slide.signum()).collect(),
            sign: (0..g.slices).map(|k| kin(k).slide.signum()).collect(),
        };
        let mid = g.slices / 2;
        let line = |l: &ContactLine, kin: &dyn Fn(usize) -> Kinematics| LineFriction {
            mid: if g.slices % 2 == 1 {
                kin(mid)
            } else {
                let (a, b) = (kin(mid - 1), kin(mid));
                Kinematics {
                    slide: 0.5 * (a.slide + b.slide),
                    entrain: 0.5 * (a.entrain + b.entrain),
                }
            },
            r_bar: if g.slices % 2 == 1 {
                l.r_bar[mid]
            } else {
                0.5 * (l.r_bar[mid - 1] + l.r_bar[mid])
            },
        };
        let (flange, flange_s) = match &g.flange {
            Some(f) => {
                let ring = (1.0 - cage_ratio) * f.rib_radius;
                let roller = spin_ratio * f.offset;
                let rel = [f.point[0] - g.center[0], f.point[1] - g.center[1]];
                (Kinematics::new(roller, ring), rel[0] * g.axis[0] + rel[1] * g.axis[1])
            }
            None => (Kinematics::default(), 0.0),
        };
        FrictionModel {
            cone_weights: weights(&cone_kin),
            cup_weights: weights(&cup_kin),
            cone: line(&g.cone, &cone_kin),
            cup: line(&g.cup, &cup_kin),
            flange,
            flange_s,
            ring_radii: g.pitch_contact_radii(),
            slice_len: g.slice_len,
            eta0: p.eta0,
            alpha: p.alpha,
            sigma: p.roughness,
            mu: p.mu,
            flange_mu0: p.flange_mu0,
            rib_coulomb: p.rib_coulomb(),
            traction: p.traction,
            lubricant: p.lubricant(g.e_prime),
            supply: p.supply_law(b),
            cache: SpeedCache {
                speed: f64::NAN,
                table_speed: f64::NAN,
                ..SpeedCache::default()
            },
            halley: p.fidelity == crate::model::Fidelity::QuasiStatic,
            four_lanes: four_lanes_available(),
        }
    }

    /// The film ratio Λ = h / σ of the rib contact of geometry `g` carrying load `qf` at cone
    /// speed `speed` relative to the cup, as the rib's friction law takes it: with `traction`
    /// 0 the film reduced by inlet shear heating over the roller end / rib roughness, with 1
    /// the isothermal film over the raceway roughness ([L22]'s rib law). Infinite without a
    /// loaded rib or roughness.
    pub fn flange_film_ratio(&self, g: &crate::geometry::Geometry, qf: f64, speed: f64) -> f64 {
        let Some(f) = &g.flange else {
            return f64::INFINITY;
        };
        if !(qf > 0.0) {
            return f64::INFINITY;
        }
        let kin = self.flange;
        let u_e = speed.abs() * kin.entrain;
        let h = self.rib_film(g, f, u_e, qf, self.supply.starvation(speed).rib);
        match self.traction {
            tr::TractionLaw::ThermalEyring => {
                let (_, _, p_h) = f.hertz.ellipse(qf);
                self.lubricant.rib_film_ratio(speed.abs() * kin.slide.abs(), u_e, h, p_h)
            }
            tr::TractionLaw::NewtonianEyring => self.isothermal_rib_film_ratio(h),
        }
    }

    /// [L22]'s rib film ratio (`traction` 1): the isothermal film `h` over the raceway
    /// roughness; infinite without roughness.
    fn isothermal_rib_film_ratio(&self, h: f64) -> f64 {
        if self.sigma > 0.0 {
            h / self.sigma
        } else {
            f64::INFINITY
        }
    }

    /// The film ratio Λ = h / σ of the raceway slice `k` of `line` (with its `weights`)
    /// carrying load `q` at cone speed `speed` relative to the cup: Hamrock's central film
    /// reduced by inlet shear heating, as the traction law takes it, over the composite
    /// roughness. Without roughness, or without load or entrainment, infinite or 0.
    pub fn film_ratio(&self, line: &ContactLine, weights: &SliceWeights, k: usize, q: f64, speed: f64) -> f64 {
        let w = q / self.slice_len;
        let u_e = speed.abs() * weights.entrain[k];
        if !(w > 0.0) {
            return f64::INFINITY;
        }
        let e_prime = self.lubricant.e_prime;
        let (b, _) = line_contact_half_width(w, line.r_bar[k], e_prime);
        let p_h = if b > 0.0 { 2.0 * w / (std::f64::consts::PI * b) } else { 0.0 };
        let v_s = speed.abs() * weights.slide[k];
        let slide_roll = if u_e > 0.0 { v_s / u_e } else { 0.0 };
        let heating = tr::thermal_reduction(self.lubricant.inlet_heating * u_e * u_e, p_h / e_prime, slide_roll);
        heating * tr::film_line(self.eta0, self.alpha, e_prime, u_e, line.r_bar[k], w) * self.supply.starvation(speed).raceway / self.sigma
    }

    /// The rib film at entrainment speed `u_e` and load `q`: Chittenden's flooded film of the
    /// roller end on rib `f`, times the supply's starvation factor `starved` of the rib.
    fn rib_film(&self, g: &Geometry, f: &crate::geometry::FlangeContact, u_e: f64, q: f64, starved: f64) -> f64 {
        tr::film_point(self.eta0, self.alpha, g.e_prime, u_e, f.hertz.ry, f.hertz.rx, q) * starved
    }

    /// Whether [`FrictionModel::evaluate`] needs the converged slice loads (`traction` = 0
    /// with EHL: the traction law is evaluated slice by slice).
    pub fn needs_slice_loads(&self, lubrication: Lubrication) -> bool {
        lubrication == Lubrication::Ehl && self.traction == tr::TractionLaw::ThermalEyring
    }

    /// The speed-dependent constants of every slice position of one raceway (see
    /// [`SliceConst`]), at |speed| `speed_abs` > 0.
    fn slice_consts(&self, line: &ContactLine, weights: &SliceWeights, speed_abs: f64, out: &mut Vec<SliceConst>) {
        let e_prime = self.lubricant.e_prime;
        let starved = self.supply.starvation(speed_abs);
        out.clear();
        for k in 0..weights.entrain.len() {
            let u_e = speed_abs * weights.entrain[k];
            let v_s = speed_abs * weights.slide[k];
            let r_bar = line.r_bar[k];
            let mut c = SliceConst {
                u_e,
                v_s,
                // p_h = sqrt(w E' / (2 pi r)) for a line load w on the reduced radius r
                table_max: 2.0 * std::f64::consts::PI * r_bar * TABLE_PRESSURE * TABLE_PRESSURE / e_prime * self.slice_len,
                ln_vs: if v_s > 0.0 { fm::ln(v_s) } else { f64::NEG_INFINITY },
                boundary_slide_roll: if weights.entrain[k] > 0.0 {
                    weights.slide[k] / weights.entrain[k]
                } else {
                    0.0
                },
                mixed: starved.mixed,
                ..SliceConst::default()
            };
            if u_e > 0.0 {
                // tr::thermal_reduction(load, ph_e, v_s / u_e) without its load-dependent part
                let load = self.lubricant.inlet_heating * u_e * u_e;
                if load > 0.0 {
                    let ln_l = fm::ln(load);
                    let s = (v_s / u_e).abs().min(2.0);
                    let s083 = if s > 0.0 { fm::exp(0.83 * fm::ln(s)) } else { 0.0 };
                    c.heated = true;
                    c.l042 = fm::exp(0.42 * ln_l);
                    c.heat_den = 1.0 + 0.213 * (1.0 + 2.23 * s083) * fm::exp(0.64 * ln_l);
                }
                // tr::film_line up to its load factor
                let u = self.eta0 * u_e / (e_prime * r_bar);
                let g = self.alpha * e_prime;
                c.film_a = r_bar * 2.922 * fm::powf(u, 0.692) * fm::powf(g, 0.470) * starved.raceway;
                c.e_r = e_prime * r_bar;
                // tr::rolling_resistance up to its load factor
                let l = self.slice_len;
                if self.alpha > 0.0 && l > 0.0 {
                    let gu = self.alpha * self.eta0 * u_e / r_bar;
                    c.rolls = true;
                    c.roll_a = 29.2 * r_bar / self.alpha * fm::powf(gu, 0.648) * starved.rolling;
                    c.e_r_l = e_prime * r_bar * l;
                }
            }
            out.push(c);
        }
    }

    /// Inlet heating factor of a slice at Hertz pressure over E' `ph_e` (tr::thermal_reduction).
    #[inline(always)]
    fn heating(c: &SliceConst, ph_e: f64) -> f64 {
        if !c.heated {
            return 1.0;
        }
        let num = 1.0 - 13.2 * ph_e * c.l042;
        (num / c.heat_den).max(tr::film::MIN_THERMAL_FACTOR)
    }

    /// Traction coefficient and rolling resistance (N) of one loaded raceway slice at load
    /// `q` > 0 (`traction` = 0 with EHL): its film, inlet heating, thermal Eyring traction and
    /// EHL rolling resistance from the slice position's speed constants `c` and radius `r_bar`.
    #[inline(always)]
    fn slice_friction<const HALLEY: bool>(&self, c: &SliceConst, r_bar: f64, q: f64) -> (f64, f64) {
        let e_prime = self.lubricant.e_prime;
        let w = q / self.slice_len;
        let (b, _) = line_contact_half_width(w, r_bar, e_prime);
        let p_mean = if b > 0.0 { w / (2.0 * b) } else { 0.0 };
        if c.u_e > 0.0 {
            let p_h = 4.0 / std::f64::consts::PI * p_mean;
            let heating = Self::heating(c, p_h / e_prime);
            let h_iso = c.film_a * fm::powf(w / c.e_r, -0.166);
            let mu = if w > 0.0 {
                let h = heating * h_iso;
                let ln_h = if h > 0.0 { fm::ln(h) } else { f64::NEG_INFINITY };
                let stress = if HALLEY {
                    tr::traction::thermal_eyring_stress_ln_halley
                } else {
                    tr::traction::thermal_eyring_stress_ln
                };
                self.lubricant
                    .raceway_mu_film_with(w, p_mean, h, ln_h, c.u_e, c.v_s, c.ln_vs, c.boundary_slide_roll, c.mixed, stress)
            } else {
                0.0
            };
            let rolling = if c.rolls {
                heating * (c.roll_a * fm::powf(q / c.e_r_l, 0.246) * self.slice_len)
            } else {
                0.0
            };
            (mu, rolling)
        } else {
            // no entrainment at this slice: no film, no rolling resistance
            (
                self.lubricant
                    .raceway_mu(w, p_mean, 0.0, 0.0, c.v_s, c.boundary_slide_roll, c.mixed),
                0.0,
            )
        }
    }

    /// One raceway contact, slice by slice (`traction` = 0): each loaded slice's traction at
    /// its own load, pressure, entrainment and sliding speed (the law is far from linear in
    /// the slide-to-roll ratio, so a mean over the line would misplace the plateau), and its
    /// EHL rolling resistance on both surfaces. `consts`: the line's [`SliceConst`] at this
    /// speed (empty at standstill: the laws' own zero-speed branches).
    fn raceway_sliced<const HALLEY: bool>(
        &self,
        line: &ContactLine,
        weights: &SliceWeights,
        consts: &[SliceConst],
        loads: &[f64],
        speed: f64,
    ) -> RacewayFriction {
        if consts.is_empty() {
            return self.raceway_sliced_generic(line, weights, loads, speed);
        }
        let sign = if speed < 0.0 { -1.0 } else { 1.0 };
        let mut f = RacewayFriction::default();
        for (k, &q) in loads.iter().enumerate() {
            if !(q > 0.0) {
                continue;
            }
            let (mu, rolling) = self.slice_friction::<HALLEY>(&consts[k], line.r_bar[k], q);
            f.torque += mu * q * weights.slide[k] + 2.0 * rolling * weights.entrain[k];
            f.skew += mu * q * sign * weights.skew[k];
            f.slide_force += mu * q * sign * weights.sign[k];
            f.rolling += rolling;
        }
        f
    }

    /// [`FrictionModel::raceway_sliced`] at fidelity 0 with the slice laws read from `table`
    /// (lines `first`.. for this raceway's slice positions): ln of the traction coefficient and
    /// the rolling resistance, interpolated in ln(load) (`load_table`: relative error below
    /// 6e-6 p⁴ for a law ~ q^p; loads outside its grid are evaluated directly).
    #[allow(clippy::too_many_arguments)]
    #[cfg_attr(all(target_arch = "x86_64", not(test)), allow(dead_code))]
    fn raceway_tabulated(
        &self,
        line: &ContactLine,
        weights: &SliceWeights,
        consts: &[SliceConst],
        table: &mut LoadTable,
        first: usize,
        loads: &[f64],
        speed: f64,
    ) -> RacewayFriction {
        let sign = if speed < 0.0 { -1.0 } else { 1.0 };
        let mut f = RacewayFriction::default();
        for (k, &q) in loads.iter().enumerate() {
            if !(q > 0.0) {
                continue;
            }
            let (c, r_bar) = (&consts[k], line.r_bar[k]);
            let (mu, rolling) = self
                .slice_friction_read(table, first + k, c, r_bar, q)
                .unwrap_or_else(|| self.slice_friction::<true>(c, r_bar, q));
            f.torque += mu * q * weights.slide[k] + 2.0 * rolling * weights.entrain[k];
            f.skew += mu * q * sign * weights.skew[k];
            f.slide_force += mu * q * sign * weights.sign[k];
            f.rolling += rolling;
        }
        f
    }

    /// [`FrictionModel::slice_friction`] (traction coefficient, rolling resistance) of a slice
    /// at load `q` read from line `line` of `table`; `None` where the table does not serve it
    /// (no sliding, above `table_max`, off the grid). The traction coefficient tabulated in
    /// its logarithm: the film's viscosity grows as exp(alpha p) with p ~ sqrt(q), which ln(mu)
    /// follows smoothly and mu itself does not; the rolling resistance as itself, a power law
    /// q^0.246 whose cubic read in ln q is within 2e-8 (no exponential to read).
    #[cfg_attr(all(target_arch = "x86_64", not(test)), allow(dead_code))]
    fn slice_friction_read(&self, table: &mut LoadTable, line: usize, c: &SliceConst, r_bar: f64, q: f64) -> Option<(f64, f64)> {
        if !(c.v_s > 0.0 && q <= c.table_max) {
            return None;
        }
        let [ln_mu, rolling] = table.get(line, q, |q| self.slice_node(c, r_bar, q))?;
        Some((fm::exp(ln_mu), if c.rolls { rolling } else { 0.0 }))
    }

    /// What the friction table holds for a slice at load `q` (a node): ln of the traction
    /// coefficient and, where the slice rolls, the rolling resistance itself (a power law
    /// q^0.246 times the inlet heating factor: smooth in ln q, its cubic read within 2e-8
    /// relative of the law where the heating factor is constant, and no exponential to read).
    fn slice_node(&self, c: &SliceConst, r_bar: f64, q: f64) -> [f64; 2] {
        let (mu, rolling) = self.slice_friction::<true>(c, r_bar, q);
        [fm::ln(mu), if c.rolls { rolling } else { 0.0 }]
    }

    /// [`FrictionModel::raceway_tabulated`] in lanes: four where the CPU has AVX2, else two
    /// (SSE2); the same bits either way (`friction_lanes.rs`). Other architectures: the
    /// scalar read.
    #[allow(clippy::too_many_arguments)]
    fn raceway_tabulated_fast(
        &self,
        line: &ContactLine,
        weights: &SliceWeights,
        consts: &[SliceConst],
        lanes: &LineLanes,
        table: &mut LoadTable,
        first: usize,
        loads: &[f64],
        speed: f64,
    ) -> RacewayFriction {
        #[cfg(target_arch = "x86_64")]
        {
            let _ = weights;
            if self.four_lanes {
                // SAFETY: `four_lanes` is set only where the CPU has AVX2 (`FrictionModel::new`).
                unsafe { lanes4::raceway_tabulated_avx2(self, line, consts, lanes, table, first, loads, speed) }
            } else {
                lanes2::raceway_tabulated_lanes(self, line, consts, lanes, table, first, loads, speed)
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            let _ = lanes;
            self.raceway_tabulated(line, weights, consts, table, first, loads, speed)
        }
    }

    /// [`FrictionModel::raceway_sliced`] (Halley) with the laws in lanes: four slices at a
    /// time where the CPU has AVX2, else two (`friction_lanes.rs`); other architectures: the
    /// scalar laws.
    fn raceway_direct_fast(
        &self,
        line: &ContactLine,
        weights: &SliceWeights,
        consts: &[SliceConst],
        lanes: &LineLanes,
        loads: &[f64],
        speed: f64,
    ) -> RacewayFriction {
        #[cfg(target_arch = "x86_64")]
        {
            let _ = weights;
            if self.four_lanes {
                // SAFETY: `four_lanes` is set only where the CPU has AVX2 (`FrictionModel::new`).
                unsafe { lanes4::raceway_direct_avx2(self, line, consts, lanes, loads, speed) }
            } else {
                lanes2::raceway_direct_lanes(self, line, consts, lanes, loads, speed)
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            let _ = lanes;
            self.raceway_sliced::<true>(line, weights, consts, loads, speed)
        }
    }

    /// [`FrictionModel::raceway_sliced`] straight from the laws (at standstill).
    fn raceway_sliced_generic(&self, line: &ContactLine, weights: &SliceWeights, loads: &[f64], speed: f64) -> RacewayFriction {
        let sign = if speed < 0.0 { -1.0 } else { 1.0 };
        let e_prime = self.lubricant.e_prime;
        let starved = self.supply.starvation(speed);
        let mut f = RacewayFriction::default();
        for (k, &q) in loads.iter().enumerate() {
            if !(q > 0.0) {
                continue;
            }
            let w = q / self.slice_len;
            let u_e = speed.abs() * weights.entrain[k];
            let v_s = speed.abs() * weights.slide[k];
            let (b, _) = line_contact_half_width(w, line.r_bar[k], e_prime);
            let p_mean = if b > 0.0 { w / (2.0 * b) } else { 0.0 };
            let h_iso = tr::film_line(self.eta0, self.alpha, e_prime, u_e, line.r_bar[k], w) * starved.raceway;
            // the boundary law at the kinematic slide-to-roll ratio: finite at standstill
            let slide_roll = if weights.entrain[k] > 0.0 {
                weights.slide[k] / weights.entrain[k]
            } else {
                0.0
            };
            let mu = self.lubricant.raceway_mu(w, p_mean, h_iso, u_e, v_s, slide_roll, starved.mixed);
            let rolling = if u_e > 0.0 {
                let p_h = 4.0 / std::f64::consts::PI * p_mean;
                let heating = tr::thermal_reduction(self.lubricant.inlet_heating * u_e * u_e, p_h / e_prime, v_s / u_e);
                heating * tr::rolling_resistance(self.eta0, self.alpha, e_prime, u_e, line.r_bar[k], q, self.slice_len) * starved.rolling
            } else {
                0.0
            };
            f.torque += mu * q * weights.slide[k] + 2.0 * rolling * weights.entrain[k];
            f.skew += mu * q * sign * weights.skew[k];
            f.slide_force += mu * q * sign * weights.sign[k];
            f.rolling += rolling;
        }
        f
    }

    /// One raceway contact: friction power per unit speed, skew moment on the roller, net
    /// sliding traction on the ring and rolling resistance. `loads` the line's slice loads.
    #[allow(clippy::too_many_arguments)]
    fn raceway(
        &self,
        e_prime: f64,
        line: &LineFriction,
        weights: &SliceWeights,
        s: &LineSums,
        loads: &[f64],
        speed: f64,
        lubrication: Lubrication,
        starved: &tr::Starvation,
    ) -> RacewayFriction {
        if s.q <= 0.0 {
            return RacewayFriction::default();
        }
        let sign = if speed < 0.0 { -1.0 } else { 1.0 };
        // Sums of q |v_s| per unit cone speed (sliding power weight), q s sgn(v_s) (skew moment
        // weight) and q sgn(v_s) (net sliding traction per unit friction coefficient).
        // (unloaded slices add q x = +-0, which changes no sum)
        let (mut q_slide, mut q_skew, mut q_sign) = (0.0, 0.0, 0.0);
        for (((&q, &slide), &skew), &sign) in loads.iter().zip(&weights.slide).zip(&weights.skew).zip(&weights.sign) {
            q_slide += q * slide;
            q_skew += q * skew;
            q_sign += q * sign;
        }
        // Load-weighted mean sliding speed ratio along the line.
        let slide = q_slide / s.q;
        let (mu, f_roll) = match lubrication {
            Lubrication::Dry => (tr::dry_mu(self.mu, speed * slide).abs(), 0.0),
            Lubrication::Ehl => {
                let l = s.loaded as f64 * self.slice_len;
                let w = s.q / l;
                let u_e = speed.abs() * line.mid.entrain;
                let h = tr::film_line(self.eta0, self.alpha, e_prime, u_e, line.r_bar, w) * starved.raceway;
                let lambda = if self.sigma > 0.0 { h / self.sigma } else { f64::INFINITY };
                let slide_roll = if line.mid.entrain > 0.0 { slide / line.mid.entrain } else { 0.0 };
                let (b, _) = line_contact_half_width(w, line.r_bar, e_prime);
                let p_mean = if b > 0.0 { w / (2.0 * b) } else { 0.0 };
                let mu_fl = tr::full_film_mu(self.eta0, speed * slide, h, p_mean).abs();
                let mu = tr::traction_mu(lambda, slide_roll, mu_fl);
                (
                    mu,
                    tr::rolling_resistance(self.eta0, self.alpha, e_prime, u_e, line.r_bar, s.q, l) * starved.rolling,
                )
            }
        };
        RacewayFriction {
            // rolling resistance on both surfaces: 2 F u_e
            torque: mu * q_slide + 2.0 * f_roll * line.mid.entrain,
            skew: mu * sign * q_skew,
            // Traction on the ring = +mu q sgn(v_s) e_t with v_s = roller - ring.
            slide_force: mu * sign * q_sign,
            rolling: f_roll,
        }
    }

    /// Friction torque parts from the converged roller evaluations; fills the skew moments
    /// of `out`. With `evaluated` = 1 (axisymmetric solve) roller 1 stands for all rollers.
    pub(super) fn evaluate(
        &mut self,
        g: &Geometry,
        evals: &[RollerEval],
        evaluated: usize,
        inputs: &Inputs,
        lubrication: Lubrication,
        slice_loads: &[f64],
        speed_held: bool,
        out: &mut Outputs,
    ) -> TorqueParts {
        let speed = inputs.relative_speed();
        let sign = if speed < 0.0 { -1.0 } else { 1.0 };
        let mut parts = TorqueParts::default();
        let (ri, ro) = self.ring_radii;
        let sliced = self.needs_slice_loads(lubrication);
        let ns = g.slices;
        let mut cache = std::mem::take(&mut self.cache);
        if sliced && cache.speed.to_bits() != speed.abs().to_bits() {
            cache.speed = speed.abs();
            if speed != 0.0 {
                self.slice_consts(&g.cone, &self.cone_weights, speed.abs(), &mut cache.cone);
                self.slice_consts(&g.cup, &self.cup_weights, speed.abs(), &mut cache.cup);
                cache.cone_lanes.fill(&cache.cone, &self.cone_weights);
                cache.cup_lanes.fill(&cache.cup, &self.cup_weights);
            } else {
                cache.cone.clear();
                cache.cup.clear();
            }
        }
        // The tables serve a speed held since the last solve; a speed that changes every step
        // would rebuild them every step (a full film solve per node, four nodes per cell), so
        // there the laws are evaluated slice by slice.
        let tabulate = self.halley && speed_held && speed != 0.0;
        if sliced && tabulate && cache.table_speed.to_bits() != speed.abs().to_bits() {
            cache.table_speed = speed.abs();
            cache.raceways.reset(2 * ns);
            cache.flange.reset(1);
        }
        // the supply's starvation at this speed, for the rib and the mean-line raceway law
        let starved = self.supply.starvation(speed);
        for (j, e) in evals.iter().enumerate().take(evaluated) {
            // slice_loads: per roller, the cone's slices then the cup's
            let loads = &slice_loads[2 * ns * j..2 * ns * (j + 1)];
            let (cone, cup) = if sliced {
                let (cone, cup) = (&loads[..ns], &loads[ns..]);
                if tabulate && !cache.cone.is_empty() {
                    (
                        self.raceway_tabulated_fast(
                            &g.cone,
                            &self.cone_weights,
                            &cache.cone,
                            &cache.cone_lanes,
                            &mut cache.raceways,
                            0,
                            cone,
                            speed,
                        ),
                        self.raceway_tabulated_fast(
                            &g.cup,
                            &self.cup_weights,
                            &cache.cup,
                            &cache.cup_lanes,
                            &mut cache.raceways,
                            ns,
                            cup,
                            speed,
                        ),
                    )
                } else if self.halley && !cache.cone.is_empty() {
                    (
                        self.raceway_direct_fast(&g.cone, &self.cone_weights, &cache.cone, &cache.cone_lanes, cone, speed),
                        self.raceway_direct_fast(&g.cup, &self.cup_weights, &cache.cup, &cache.cup_lanes, cup, speed),
                    )
                } else if self.halley {
                    (
                        self.raceway_sliced::<true>(&g.cone, &self.cone_weights, &cache.cone, cone, speed),
                        self.raceway_sliced::<true>(&g.cup, &self.cup_weights, &cache.cup, cup, speed),
                    )
                } else {
                    (
                        self.raceway_sliced::<false>(&g.cone, &self.cone_weights, &cache.cone, cone, speed),
                        self.raceway_sliced::<false>(&g.cup, &self.cup_weights, &cache.cup, cup, speed),
                    )
                }
            } else {
                (
                    self.raceway(
                        g.e_prime,
                        &self.cone,
                        &self.cone_weights,
                        &e.cone,
                        &loads[..ns],
                        speed,
                        lubrication,
                        &starved,
                    ),
                    self.raceway(
                        g.e_prime,
                        &self.cup,
                        &self.cup_weights,
                        &e.cup,
                        &loads[ns..],
                        speed,
                        lubrication,
                        &starved,
                    ),
                )
            };
            parts.raceway += cone.torque + cup.torque;
            out.nis[j] = cone.skew;
            out.nos[j] = cup.skew;
            out.nfs[j] = 0.0;
            // [L22]: M_inner = (F_ro,i + F_rs,i) R_i + F_fs (R_i + e_r), M_outer = (F_ro,e - F_rs,e) R_e,
            // here with signed traction (force on the ring along e_t) and the sign of speed.
            parts.cone += (sign * cone.rolling - cone.slide_force) * ri;
            parts.cup += (sign * cup.rolling + cup.slide_force) * ro;
            let mut sliding = cone.slide_force.abs() + cup.slide_force.abs();
            let qf = e.qf;
            if let (Some(f), true) = (&g.flange, qf > 0.0) {
                let kin = self.flange;
                let v_s = speed * kin.slide;
                let f_total = match (self.rib_coulomb, lubrication) {
                    // `flange.mu`: Coulomb friction at the rib whatever the raceways' law
                    (Some(mu_f), _) => tr::dry_mu(mu_f, v_s).abs() * qf,
                    (None, Lubrication::Dry) => tr::dry_mu(self.mu, v_s).abs() * qf,
                    (None, Lubrication::Ehl) => {
                        let u_e = speed.abs() * kin.entrain;
                        // the contact ellipse and film at this load (not needed where the
                        // table serves the friction force)
                        let film = || {
                            let (a, b, p_h) = f.hertz.ellipse(qf);
                            (a, b, p_h, self.rib_film(g, f, u_e, qf, starved.rib))
                        };
                        match self.traction {
                            tr::TractionLaw::ThermalEyring => {
                                let slide_roll = if kin.entrain > 0.0 { kin.slide.abs() / kin.entrain } else { 2.0 };
                                if self.halley {
                                    let law = |q: f64| {
                                        let (a, b, p_h) = f.hertz.ellipse(q);
                                        let h = self.rib_film(g, f, u_e, q, starved.rib);
                                        self.lubricant.rib_force(
                                            q,
                                            v_s.abs(),
                                            u_e,
                                            slide_roll,
                                            h,
                                            a,
                                            b,
                                            p_h,
                                            starved.mixed,
                                            tr::rib::rib_film_traction_halley,
                                        )
                                    };
                                    // the table exists at this speed when the raceways' does
                                    let read = (sliced && tabulate)
                                        .then(|| cache.flange.get(0, qf, |q| [fm::ln(law(q) / q), 0.0]))
                                        .flatten();
                                    read.map_or_else(|| law(qf), |v| fm::exp(v[0]) * qf)
                                } else {
                                    let (a, b, p_h, h) = film();
                                    self.lubricant.rib_force(
                                        qf,
                                        v_s.abs(),
                                        u_e,
                                        slide_roll,
                                        h,
                                        a,
                                        b,
                                        p_h,
                                        starved.mixed,
                                        tr::rib_film_traction,
                                    )
                                }
                            }
                            tr::TractionLaw::NewtonianEyring => {
                                let (a, b, p_h, h) = film();
                                qf * tr::flange_boundary_mu(self.flange_mu0, self.isothermal_rib_film_ratio(h))
                                    + tr::flange_viscous_traction(self.eta0, v_s, h, a, b, p_h)
                            }
                        }
                    }
                };
                parts.flange += f_total * kin.slide.abs();
                // Traction on the roller opposes its sliding: F_t = -f sgn(v_s); N = -s F_t.
                out.nfs[j] = self.flange_s * f_total * sign * kin.slide.signum();
                parts.cone -= f_total * sign * kin.slide.signum() * f.rib_radius;
                sliding += f_total;
            }
            out.sliding_friction[j] = sliding;
        }
        self.cache = cache;
        let copies = evals.len() as f64 / evaluated as f64;
        for j in evaluated..evals.len() {
            out.nis[j] = out.nis[0];
            out.nos[j] = out.nos[0];
            out.nfs[j] = out.nfs[0];
            out.sliding_friction[j] = out.sliding_friction[0];
        }
        parts.raceway *= sign * copies;
        parts.flange *= sign * copies;
        parts.cone *= copies;
        parts.cup *= copies;
        parts
    }
}

/// Whether the friction table is read four slices at a time (x86-64 with AVX2).
fn four_lanes_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        crate::simd_math::x4::available()
    }
    #[cfg(not(target_arch = "x86_64"))]
    false
}

/// The friction table read two slices at a time (SSE2, every x86-64 CPU).
#[cfg(target_arch = "x86_64")]
mod lanes2 {
    use super::*;
    use crate::quasi_static::load_table::{LN_FIRST as LOAD_GRID_FIRST, NODES as LOAD_GRID_NODES, STEP as LOAD_GRID_STEP};
    use crate::simd_math::{exp, ln, F2 as F, M2 as M};
    use crate::tribology::pair::x2 as pair;
    include!("friction_lanes.rs");
}

/// The friction table read four slices at a time (AVX2), entered through
/// [`raceway_tabulated_avx2`](lanes4::raceway_tabulated_avx2).
#[cfg(target_arch = "x86_64")]
mod lanes4 {
    use super::*;
    use crate::quasi_static::load_table::{LN_FIRST as LOAD_GRID_FIRST, NODES as LOAD_GRID_NODES, STEP as LOAD_GRID_STEP};
    use crate::simd_math::x4::{exp, ln, F4 as F, M4 as M};
    use crate::tribology::pair::x4 as pair;
    include!("friction_lanes.rs");

    /// `raceway_tabulated_lanes` in four lanes, compiled for AVX2.
    ///
    /// # Safety
    /// The CPU has AVX2 (`simd_math::x4::available`).
    #[allow(clippy::too_many_arguments)]
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn raceway_tabulated_avx2(
        model: &FrictionModel,
        line: &ContactLine,
        consts: &[SliceConst],
        lanes: &LineLanes,
        table: &mut LoadTable,
        first: usize,
        loads: &[f64],
        speed: f64,
    ) -> RacewayFriction {
        raceway_tabulated_lanes(model, line, consts, lanes, table, first, loads, speed)
    }

    /// `raceway_direct_lanes` in four lanes, compiled for AVX2.
    ///
    /// # Safety
    /// The CPU has AVX2 (`simd_math::x4::available`).
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn raceway_direct_avx2(
        model: &FrictionModel,
        line: &ContactLine,
        consts: &[SliceConst],
        lanes: &LineLanes,
        loads: &[f64],
        speed: f64,
    ) -> RacewayFriction {
        raceway_direct_lanes(model, line, consts, lanes, loads, speed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bearing::Bearing;

    /// The tabulated slice laws as `raceway_tabulated` reads them against the laws themselves,
    /// every slice position of both raceways of every preset at its speed, over loads from
    /// 2 µN up to the table's limit (a Hertz pressure of 4.5 GPa): the traction coefficient
    /// (absolute: where it is small, ~1e-3 at near-zero sliding, it rises as steeply as q^5
    /// and its relative error is largest, but its force is negligible there) and the rolling
    /// resistance and the flange's friction force (relative).
    #[test]
    fn tabulated_slice_friction_follows_the_laws() {
        for name in ["TRB130x230", "32018X", "32008", "CRB-TRILOBE"] {
            let b = Bearing::preset(name).unwrap();
            let p = Parameters::from_bearing(&b);
            let qs = super::super::QuasiStatic::new(&b, &p).unwrap();
            let (g, fr) = (&qs.geometry, &qs.friction);
            let speed = Inputs::from_bearing(&b).speed.abs();
            let (mut mu_abs, mut mu_rel, mut roll_rel, mut n) = (0.0_f64, 0.0_f64, 0.0_f64, 0);
            for (line, weights) in [(&g.cone, &fr.cone_weights), (&g.cup, &fr.cup_weights)] {
                let mut consts = Vec::new();
                fr.slice_consts(line, weights, speed, &mut consts);
                let mut table = LoadTable::default();
                table.reset(consts.len());
                for (k, c) in consts.iter().enumerate().filter(|(_, c)| c.v_s > 0.0) {
                    let law = |q: f64| fr.slice_friction::<true>(c, line.r_bar[k], q);
                    for q in (0..).map(|m| 2e-6 * 1.0233_f64.powi(m)).take_while(|q| *q <= c.table_max) {
                        let (mu, rolling) = law(q);
                        let (mu_read, rolling_read) = fr
                            .slice_friction_read(&mut table, k, c, line.r_bar[k], q)
                            .expect("every load up to the limit is tabulated");
                        n += 1;
                        mu_abs = mu_abs.max((mu_read - mu).abs());
                        if mu > 0.01 {
                            mu_rel = mu_rel.max((mu_read / mu - 1.0).abs());
                        }
                        if c.rolls {
                            roll_rel = roll_rel.max((rolling_read / rolling - 1.0).abs());
                        }
                    }
                }
            }
            // the flange's friction force per unit load, 1 N to 20 kN
            let mut flange_rel = 0.0_f64;
            if let Some(f) = &g.flange {
                let kin = fr.flange;
                let u_e = speed * kin.entrain;
                let v_s = speed * kin.slide.abs();
                let slide_roll = kin.slide.abs() / kin.entrain;
                let law = |q: f64| {
                    let (a, b, p_h) = f.hertz.ellipse(q);
                    let h = tr::film_point(fr.eta0, fr.alpha, g.e_prime, u_e, f.hertz.ry, f.hertz.rx, q);
                    fr.lubricant.rib_force(
                        q,
                        v_s,
                        u_e,
                        slide_roll,
                        h,
                        a,
                        b,
                        p_h,
                        tr::Mixed::FilmRatio,
                        tr::rib::rib_film_traction_halley,
                    )
                };
                let mut table = LoadTable::default();
                table.reset(1);
                for q in (0..430).map(|m| 1.0233_f64.powi(m)) {
                    let read = table.get(0, q, |q| [fm::ln(law(q) / q), 0.0]).unwrap();
                    flange_rel = flange_rel.max((fm::exp(read[0]) * q / law(q) - 1.0).abs());
                }
            }
            eprintln!(
                "{name}: {n} loads; traction coefficient within {mu_abs:.1e} (relative {mu_rel:.1e} where above 0.01), rolling resistance {roll_rel:.1e}, flange friction {flange_rel:.1e}"
            );
            assert!(mu_abs < 2e-6 && mu_rel < 1e-4 && roll_rel < 2e-5 && flange_rel < 1e-6, "{name}");
        }
    }

    /// The lane read of the friction table (`friction_lanes.rs`) against the scalar read, and
    /// the laws in lanes against the scalar laws, every preset, both raceways, lines of slice
    /// loads that mix unloaded slices, loads below the table's grid, ordinary loads and loads
    /// above its pressure limit: the same friction to rounding (the logarithm and exponential
    /// round differently, the sums are added in another order; the film equation's iteration
    /// may stop a step apart, within its 1e-9 step rule), and two lanes and four lanes the
    /// same bits.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_lane_read_gives_the_scalar_read() {
        let (mut lines, mut worst_direct) = (0, 0.0_f64);
        for name in ["TRB130x230", "32018X", "32008", "CRB-TRILOBE"] {
            let b = Bearing::preset(name).unwrap();
            let p = Parameters::from_bearing(&b);
            let qs = super::super::QuasiStatic::new(&b, &p).unwrap();
            let (g, fr) = (&qs.geometry, &qs.friction);
            let speed = Inputs::from_bearing(&b).speed;
            for (first, line, weights) in [(0, &g.cone, &fr.cone_weights), (g.slices, &g.cup, &fr.cup_weights)] {
                let mut consts = Vec::new();
                fr.slice_consts(line, weights, speed.abs(), &mut consts);
                let mut lanes = LineLanes::default();
                lanes.fill(&consts, weights);
                let q_max = consts.iter().map(|c| c.table_max).fold(0.0, f64::max);
                let mut table = LoadTable::default();
                table.reset(2 * g.slices);
                for case in 0..40usize {
                    // a load profile along the line: a ramp from `low` to `high` (log scale),
                    // some slices unloaded
                    let (low, high) = (1e-5 * 10f64.powi((case % 5) as i32), q_max * [0.01, 0.3, 1.5][case % 3]);
                    let loads: Vec<f64> = (0..g.slices)
                        .map(|k| {
                            let f = k as f64 / (g.slices - 1) as f64;
                            if (k + case) % 7 == 3 {
                                0.0
                            } else {
                                low * (high / low).powf(if case % 2 == 0 { f } else { 1.0 - f })
                            }
                        })
                        .collect();
                    for sp in [speed, -speed] {
                        let scalar = fr.raceway_tabulated(line, weights, &consts, &mut table, first, &loads, sp);
                        let two = lanes2::raceway_tabulated_lanes(fr, line, &consts, &lanes, &mut table, first, &loads, sp);
                        // relative to each value (the sums here do not cancel to below 1e-3
                        // of their terms)
                        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
                        let agree = close(two.torque, scalar.torque)
                            && close(two.skew, scalar.skew)
                            && close(two.slide_force, scalar.slide_force)
                            && close(two.rolling, scalar.rolling);
                        assert!(agree, "{name} {case}: {two:?} vs {scalar:?}");
                        // the laws themselves in lanes against the scalar laws
                        let laws = fr.raceway_sliced::<true>(line, weights, &consts, &loads, sp);
                        let direct = lanes2::raceway_direct_lanes(fr, line, &consts, &lanes, &loads, sp);
                        let near = |a: f64, b: f64| (a - b).abs() <= 1e-11 * b.abs();
                        let agree = near(direct.torque, laws.torque)
                            && near(direct.skew, laws.skew)
                            && near(direct.slide_force, laws.slide_force)
                            && near(direct.rolling, laws.rolling);
                        assert!(agree, "{name} {case}: {direct:?} vs {laws:?}");
                        worst_direct = worst_direct.max((direct.torque / laws.torque - 1.0).abs());
                        if crate::simd_math::x4::available() {
                            // SAFETY: the CPU has AVX2 (checked)
                            let four = unsafe { lanes4::raceway_tabulated_avx2(fr, line, &consts, &lanes, &mut table, first, &loads, sp) };
                            let bits = |f: &RacewayFriction| [f.torque, f.skew, f.slide_force, f.rolling].map(f64::to_bits);
                            assert_eq!(bits(&four), bits(&two), "{name} {case}");
                            // SAFETY: as above
                            let four = unsafe { lanes4::raceway_direct_avx2(fr, line, &consts, &lanes, &loads, sp) };
                            assert_eq!(bits(&four), bits(&direct), "{name} {case}");
                        }
                    }
                    lines += 1;
                }
            }
        }
        assert_eq!(lines, 4 * 2 * 40);
        eprintln!("the laws in lanes: friction torque within {worst_direct:.1e} of the scalar laws");
    }
}
