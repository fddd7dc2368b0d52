//! Fuzz targets of the bearing element; see `targets.rs`.
pub mod targets;
