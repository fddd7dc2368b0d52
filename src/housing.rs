//! The radial support of the cup: the cup and the housing around it as one rigid mass on a
//! spring and a damper to ground in y and z (parameters `housing.*`; fidelity 1). Off (a rigid
//! housing) by default.
//!
//! With `housing.mass` m > 0 the cup translates radially by u = (u_y, u_z) and
//!
//! m u'' = F_b − k u − c u'
//!
//! where F_b is the bearing's force on the cup (the rollers' contacts and the cage land,
//! `housing.Fy`, `housing.Fz`), k `housing.stiffness`, c `housing.damping`. The contacts see the
//! rollers and the cage relative to the displaced cup. The outputs `cup.ay`, `cup.az` are u'',
//! what an accelerometer on the housing reads; the support's spring energy ½ k |u|² and the
//! housing's kinetic energy ½ m |u'|² are stored energy, c |u'|² is dissipated outside the
//! bearing (not in `powerLoss`). This is the single-degree-of-freedom pedestal of the
//! localized-defect models (Sawalhi & Randall, Mech. Syst. Signal Process. 22 (2008) 1924),
//! in its two radial directions. At fidelity 0 (quasi-static) the housing has no effect.
//!
//! Defaults the papers do not give, argued:
//! - stiffness 1e9 N/m: a steel housing seating a cup of 50–250 mm outer diameter is about as
//!   stiff radially as the bearing itself under its rating load (TRB130x230: 2–5e9 N/m,
//!   `stiffness[2,2]`), and the support of a pedestal or gearbox wall softer still;
//! - damping 2000 N s/m: 1 % of critical for a 10 kg housing on 1e9 N/m (bolted steel
//!   structures 0.5–2 %). With such a housing the support rings at 1.6 kHz, in the band of
//!   1–5 kHz where the housing resonances that envelope analysis demodulates lie.

/// The housing parameters as the user sets them.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct HousingParameters {
    /// Mass of the cup and the housing moving with it (kg); 0: a rigid housing.
    pub mass: f64,
    /// Radial stiffness of the support (N/m), the same in y and z.
    pub stiffness: f64,
    /// Radial viscous damping of the support (N s/m).
    pub damping: f64,
}

impl Default for HousingParameters {
    fn default() -> HousingParameters {
        HousingParameters {
            mass: 0.0,
            stiffness: 1e9,
            damping: 2000.0,
        }
    }
}

impl HousingParameters {
    /// Whether the cup moves on its support (a mass is set).
    pub fn is_flexible(&self) -> bool {
        self.mass > 0.0
    }

    /// The first bad value: its parameter's name and what is wrong.
    pub fn validate(&self) -> Result<(), (&'static str, String)> {
        if !(self.mass.is_finite() && self.mass >= 0.0) {
            return Err((
                "housing.mass",
                format!("must be finite and at least 0 (0: a rigid housing), got {} kg", self.mass),
            ));
        }
        if !(self.stiffness.is_finite() && self.stiffness > 0.0) {
            return Err((
                "housing.stiffness",
                format!("must be positive and finite, got {} N/m", self.stiffness),
            ));
        }
        if !(self.damping.is_finite() && self.damping >= 0.0) {
            return Err((
                "housing.damping",
                format!("must be finite and at least 0, got {} N s/m", self.damping),
            ));
        }
        Ok(())
    }
}
