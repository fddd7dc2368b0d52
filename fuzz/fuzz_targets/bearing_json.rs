//! libFuzzer target `bearing_json` (cargo fuzz run bearing_json); the body is `trb_fuzz::targets::bearing_json`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| trb_fuzz::targets::bearing_json(data));
