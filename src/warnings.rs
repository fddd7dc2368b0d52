//! Conditions in which the element's results hold but the user should know of them: each is
//! reported once per instance (the FMI adapter logs it with category `logStatusWarning`, the
//! standalone program prints it). They come from the outputs, the inputs and the last
//! solve's report; nothing here changes a result.
//!
//! - **Static safety below 1** (ISO 76): s0 = C_0r / P_0r < 1 means a contact stress above
//!   4000 MPa, where the rings take a permanent deformation of more than 1e-4 of the roller
//!   diameter. The model stays elastic up to twice that stress (`model::load_within_range`).
//! - **Speed above the limiting speed**: see [`LIMITING_NDM`]. Its first purpose is to catch a
//!   speed typed in rpm where the FMU takes rad/s (9.55 times too fast).
//! - **Boundary lubrication**: the smallest raceway film ratio Λ (`filmRatio.raceway`) below
//!   [`BOUNDARY_FILM_RATIO`], where the [W25] regime law puts the whole load on the
//!   asperities: the friction is the boundary law's, and the wear, scuffing and surface
//!   distress that shorten the life there are not modelled.
//! - **Start-up**: no steady running state found for `startSteady`, or the run-in did not
//!   reach its power balance (`dynamic/run_in.rs`).
//! - **Quasi-dynamic seat held**: a fidelity-2 step whose balance did not converge with the
//!   rollers' seats free kept them at the quasi-static seat (`quasi_dynamic`), which leaves
//!   out the raceway tractions' share of the in-plane forces for that step.

use crate::bearing::Bearing;
use crate::model::{Inputs, Lubrication, Outputs, Parameters, SolveReport};

/// The product n d_m (rpm times mm of pitch diameter) above which a tapered roller bearing
/// runs faster than its design allows: 1.0e6 mm/min. Catalogue limiting speeds, the mechanical
/// limit of a standard bearing's cage and rib contact with oil lubrication, lie below it for
/// standard tapered roller bearings (n d_m of about 0.5e6 to 0.7e6 mm/min), and only
/// bearings and lubrication designed for high speed (oil jets, special cages) pass it. A speed
/// entered in rpm where rad/s are expected is 9.55 times too high, so a bearing meant to run
/// at more than a tenth of its limiting speed is caught.
pub const LIMITING_NDM: f64 = 1.0e6;

/// The same for a cylindrical roller bearing: 4.0e6 mm/min. Without ribs carrying an axial
/// load, jet-oil lubricated cylindrical bearings of aero-engine main shafts run at n d_m up to
/// about 3.5e6 (the CRB-TRILOBE preset: 3.4e6 at 40 000 rpm).
pub const LIMITING_NDM_CYLINDRICAL: f64 = 4.0e6;

/// The film ratio below which the [W25] regime law is in pure boundary lubrication.
pub const BOUNDARY_FILM_RATIO: f64 = 0.01;

/// One cause of a warning.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Warning {
    StaticSafety = 0,
    SpeedLimit = 1,
    BoundaryFilm = 2,
    SteadyStartFailed = 3,
    RunInUnbalanced = 4,
    SeatHeld = 5,
}

impl Warning {
    pub const ALL: [Warning; 6] = [
        Warning::StaticSafety,
        Warning::SpeedLimit,
        Warning::BoundaryFilm,
        Warning::SteadyStartFailed,
        Warning::RunInUnbalanced,
        Warning::SeatHeld,
    ];

    /// This cause's bit in a set of causes.
    pub fn bit(self) -> u32 {
        1 << self as u32
    }
}

/// The limiting speed of `bearing` by [`LIMITING_NDM`] or [`LIMITING_NDM_CYLINDRICAL`] (rad/s).
pub fn limiting_speed(bearing: &Bearing) -> f64 {
    limiting_ndm(bearing) / (bearing.pitch_diameter * 1e3) * std::f64::consts::PI / 30.0
}

fn limiting_ndm(bearing: &Bearing) -> f64 {
    match bearing.kind {
        crate::bearing::Kind::Tapered => LIMITING_NDM,
        _ => LIMITING_NDM_CYLINDRICAL,
    }
}

/// The causes that hold now, as a set of bits.
pub fn active(bearing: &Bearing, params: &Parameters, report: &SolveReport, out: &Outputs, inputs: &Inputs) -> u32 {
    let limit = limiting_speed(bearing);
    let mut set = 0;
    let mut add = |w: Warning, on: bool| {
        if on {
            set |= w.bit();
        }
    };
    add(Warning::StaticSafety, out.safety_s0 < 1.0);
    add(Warning::SpeedLimit, inputs.speed.abs().max(inputs.cup_speed.abs()) > limit);
    add(
        Warning::BoundaryFilm,
        params.lubrication == Lubrication::Ehl && inputs.relative_speed() != 0.0 && out.film_ratio_raceway < BOUNDARY_FILM_RATIO,
    );
    add(Warning::SteadyStartFailed, report.steady_start_failed);
    add(Warning::RunInUnbalanced, report.run_in_unbalanced);
    add(Warning::SeatHeld, report.seat_held);
    set
}

/// The message of cause `w` with the numbers that hold now, at time `t`.
pub fn message(w: Warning, t: f64, bearing: &Bearing, out: &Outputs, inputs: &Inputs) -> String {
    match w {
        Warning::StaticSafety => format!(
            "t = {t}: the static safety factor s0 = C0 / P0 = {:.3} is below 1 (ISO 76; C0 = {:.0} N): the largest contact pressure, {:.0} MPa, passes the static limit of 4000 MPa and the raceways deform permanently; the model stays elastic and refuses loads that pass twice the limit",
            out.safety_s0,
            out.rating_c0,
            out.pressure_max * 1e-6
        ),
        Warning::SpeedLimit => {
            let fastest = inputs.speed.abs().max(inputs.cup_speed.abs());
            format!(
                "t = {t}: a ring turns at {:.1} rad/s ({:.0} rpm), above the limiting speed {:.1} rad/s ({:.0} rpm, n dm = {:.1e} mm/min on a pitch diameter of {:.1} mm) of a {} roller bearing of this size; speeds are in rad/s (rpm x pi/30): was rpm meant?",
                fastest,
                fastest * 30.0 / std::f64::consts::PI,
                limiting_speed(bearing),
                limiting_speed(bearing) * 30.0 / std::f64::consts::PI,
                limiting_ndm(bearing),
                bearing.pitch_diameter * 1e3,
                match bearing.kind {
                    crate::bearing::Kind::Tapered => "tapered",
                    _ => "cylindrical",
                }
            )
        }
        Warning::BoundaryFilm => format!(
            "t = {t}: the raceway film ratio is {:.2e}, below {BOUNDARY_FILM_RATIO}: the contacts run in boundary lubrication, where the friction is the boundary law's and the wear and scuffing that follow are not modelled (oil viscosity {:.3e} Pa s, speed {:.1} rad/s)",
            out.film_ratio_raceway,
            out.oil_viscosity,
            inputs.relative_speed()
        ),
        Warning::SteadyStartFailed => format!(
            "t = {t}: startSteady: no steady running state found (Newton on the dynamic equations did not converge); the dynamic model is run in at its initial inputs instead (fidelity 1), or the quasi-dynamic model starts at the seat with the epicyclic speeds and settles over its first steps (fidelity 2)"
        ),
        Warning::RunInUnbalanced => format!(
            "t = {t}: startSteady: after running in for {} ms at the initial inputs, the shaft's input power and the contacts' dissipation still differ by more than {} %: the bearing starts before it runs steadily, and the first output samples carry the rest of its start-up transient",
            crate::dynamic::run_in::MAX_RUN_IN * 1e3,
            crate::dynamic::run_in::BALANCE * 100.0
        ),
        Warning::SeatHeld => format!(
            "t = {t}: quasi-dynamic step: the balance with the rollers' seats free did not converge, so the step kept them (and the cone) at the quasi-static seat, which leaves out the raceway tractions' share of the rollers' in-plane forces; reaction and torque may differ by a few per cent from the balanced ones until the seats converge again"
        ),
    }
}
