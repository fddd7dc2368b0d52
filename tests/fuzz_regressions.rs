//! The fuzz targets (fuzz/src/targets.rs) on their seeds (`fuzz/seeds/<target>/`) and on
//! every input that ever crashed them (`fuzz/regressions/<target>/`), plus a few hundred
//! deterministic pseudo-random inputs, as an ordinary test. Fuzzing itself: scripts/fuzz.sh.
#![cfg(all(target_os = "linux", any(target_arch = "x86_64", target_arch = "aarch64")))]

#[path = "../fuzz/src/targets.rs"]
mod targets;

use std::path::Path;

fn inputs(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .map(|d| d.filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.is_file()).collect())
        .unwrap_or_default();
    files.sort();
    files
        .into_iter()
        .map(|p| (p.display().to_string(), std::fs::read(&p).unwrap()))
        .collect()
}

#[test]
fn fuzz_seeds_and_regressions_run_clean() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz");
    for target in targets::TARGETS {
        let mut all = inputs(&root.join("seeds").join(target));
        assert!(!all.is_empty(), "no seeds for {target}");
        all.extend(inputs(&root.join("regressions").join(target)));
        for (name, data) in &all {
            let result = std::panic::catch_unwind(|| targets::run(target, data));
            assert!(result.is_ok(), "{target}: {name} panicked");
        }
    }
}

#[test]
fn fuzz_targets_survive_pseudo_random_inputs() {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        state.wrapping_mul(0x2545_f491_4f6c_dd1d)
    };
    let seeds = inputs(&Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/seeds/bearing_json"));
    for i in 0..300 {
        // FMI call streams: random bytes.
        let n = (next() % 160) as usize;
        let data: Vec<u8> = (0..n).map(|_| next() as u8).collect();
        let r = std::panic::catch_unwind(|| targets::fmi_calls(&data));
        assert!(r.is_ok(), "fmi_calls panicked on {data:?}");
        // Bearing files: a seed with a few bytes changed.
        let mut text = seeds[i % seeds.len()].1.clone();
        for _ in 0..1 + next() % 4 {
            let k = (next() as usize) % text.len();
            text[k] = b"0123456789.-e,:{}[]\" x"[(next() % 22) as usize];
        }
        let r = std::panic::catch_unwind(|| targets::bearing_json(&text));
        assert!(r.is_ok(), "bearing_json panicked on {}", String::from_utf8_lossy(&text));
    }
}
