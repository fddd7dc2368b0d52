#![allow(clippy::needless_range_loop)] // index loops are the clearest form of 5x5 matrix code

//! The shaft of the drivetrain example (`examples/drivetrain/`): a quasi-static rigid 5-DOF
//! shaft on two tapered roller bearings in an O arrangement, loaded by a time-varying gear
//! mesh force, exported as an FMI 2.0 Co-Simulation FMU (`Shaft.fmu`).
//!
//! - `model`: the shaft's statics (mirroring, mapping, one Newton step per communication step).
//! - `variables`: the variable table, the FMU's and the model description's one source.
//! - `fmi`: the hand-written FMI 2.0 CS adapter.
//! - `model_description`: modelDescription.xml from the table.

pub mod fmi;
pub mod model;
pub mod model_description;
pub mod variables;
