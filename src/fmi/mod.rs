//! FMI 2.0 Co-Simulation adapter (C ABI) for [`crate::simulation::Simulation`].
//!
//! A thin adapter in the manner of the Modelica Association Reference FMUs: a state
//! machine, value-reference dispatch to `Simulation`, logging through the importer's
//! callback, FMU states. No global mutable state: any number of instances, also on
//! parallel threads. Physics never imports this module.
//!
//! - [`types`]: the FMI 2.0 C types
//! - [`machine`]: states and the states each function may be called in
//! - [`logging`]: categories, message escaping, the logger
//! - [`resources`]: the bearing an instance simulates (`resources/bearing.json`)
//! - [`instance`]: one instance; every FMI function as a method
//! - [`snapshot`]: FMU states and their serialization
//! - [`exports`]: the 34 `extern "C"` functions

pub mod exports;
pub mod instance;
pub mod logging;
pub mod machine;
pub mod resources;
pub mod snapshot;
pub mod types;

pub use exports::*;
pub use types::*;
