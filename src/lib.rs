//! Tapered roller bearing element for system simulation, exported as an FMI 2.0
//! Co-Simulation FMU (`TaperedRollerBearing`).
//!
//! Layers, bottom up (physics never imports FMI):
//! - [`bearing`]: bearing descriptions (presets, JSON files) and their validation;
//!   [`catalogue`] (`bearing::estimate`): the internal geometry of a tapered bearing estimated
//!   from its catalogue data; [`rating`] (`bearing::rating`): ISO 281 load rating and life,
//!   ISO/TS 16281 lamina life
//! - [`geometry`]: derived geometry, slices, contact points, mass properties
//! - [`contact`]: contact laws (Johnson, Palmgren, Hertz point contact)
//! - [`tribology`]: film thickness, traction, rolling resistance; [`journal_film`]: the
//!   cage land's short-bearing oil film
//! - [`quasi_static`]: fidelity 0, the quasi-static equilibrium and friction torque
//! - [`dynamic`]: fidelity 1, roller/cage/cone dynamics with an adaptive integrator
//! - [`model`], [`simulation`]: parameters/inputs/outputs and the steppable element
//! - [`variables`], [`model_description`]: the variable table and modelDescription.xml
//! - [`fmi`]: the FMI 2.0 C ABI adapter

pub mod bearing;
pub mod contact;
pub mod defect;
pub mod dynamic;
pub mod ehl_line;
pub mod fastmath;
pub mod fmi;
pub mod geometry;
pub mod housing;
pub mod journal_film;
pub mod model;
pub mod model_description;
pub mod packaging;
pub mod quasi_dynamic;
pub mod quasi_static;
#[cfg(target_arch = "x86_64")]
pub(crate) mod simd_math;
pub mod simulation;
pub mod skf_friction;
pub mod tribology;
pub mod variables;
pub mod variables_doc;
pub mod warnings;

pub use bearing::{estimate as catalogue, rating};
