//! Bearing descriptions and what follows from them alone, bottom up (each file imports only
//! the ones above it):
//! - [`file`]: the preset / bearing-file schema, its catalogue block, the presets and the
//!   validated bearing in SI units ([`Bearing`]); re-exported here
//! - [`rating`]: ISO 281 / ISO 76 load ratings and lives, ISO/TS 16281 lamina life, of a
//!   geometry (also `crate::rating`)
//! - [`estimate`]: the internal geometry of a tapered bearing estimated from its catalogue
//!   data, and the documented defaults of every section a file may leave out (also
//!   `crate::catalogue`)
//! - `read`: a preset or a bearing file parsed, validated, estimated where it gives catalogue
//!   data, completed with the defaults and converted to SI ([`Bearing::from_json`])

pub mod estimate;
pub mod file;
pub mod rating;
mod read;

pub use file::*;
