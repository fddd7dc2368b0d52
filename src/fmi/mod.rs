//! FMI 2.0 Co-Simulation adapter (C ABI). To be written.
