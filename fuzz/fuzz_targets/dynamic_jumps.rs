//! libFuzzer target `dynamic_jumps` (cargo fuzz run dynamic_jumps); the body is `trb_fuzz::targets::dynamic_jumps`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| trb_fuzz::targets::dynamic_jumps(data));
