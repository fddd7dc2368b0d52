//! libFuzzer target `fmi_calls` (cargo fuzz run fmi_calls); the body is `trb_fuzz::targets::fmi_calls`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| trb_fuzz::targets::fmi_calls(data));
