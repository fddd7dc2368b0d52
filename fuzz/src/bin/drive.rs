//! Stable-toolchain fuzz driver: a seeded, deterministic mutation loop over the seed corpus
//! (`fuzz/seeds/<target>/`, plus the working corpus `fuzz/corpus/<target>/` if present),
//! running a target for a time budget. Each input runs under `catch_unwind`; a panicking
//! input is written to `fuzz/artifacts/<target>/crash-<hash>` and the driver exits 1 (copy it
//! to `fuzz/regressions/<target>/` to keep it as a regression test of the main crate).
//! Inputs that reach new behaviour are not tracked (no coverage feedback on stable): this is
//! random testing with structure-aware mutations, not coverage-guided fuzzing.
//!
//!     cargo run --release --manifest-path fuzz/Cargo.toml --bin drive -- TARGET [SECONDS] [SEED]

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use trb_fuzz::targets;

/// xorshift64*: deterministic for a seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

fn read_dir(dir: &Path) -> Vec<Vec<u8>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| d.filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.is_file()).collect())
        .unwrap_or_default();
    files.sort();
    files.iter().filter_map(|p| std::fs::read(p).ok()).collect()
}

/// Numbers a bearing file should never contain, as JSON text.
const NUMBERS: [&str; 14] = [
    "0",
    "-0",
    "-1",
    "1e308",
    "-1e308",
    "1e-320",
    "4294967296",
    "9223372036854775807",
    "-9223372036854775808",
    "1e999",
    "0.5",
    "1000000",
    "null",
    "\"x\"",
];

/// One mutation of `input` (structure-aware for JSON-looking text).
fn mutate(input: &[u8], seeds: &[Vec<u8>], rng: &mut Rng) -> Vec<u8> {
    let mut v = input.to_vec();
    let rounds = 1 + rng.below(4);
    for _ in 0..rounds {
        match rng.below(9) {
            // Replace a number (or the value after a colon) by an extreme one.
            0..=2 if !v.is_empty() => {
                let at = rng.below(v.len());
                if let Some(start) = (at..v.len()).find(|&i| v[i] == b':') {
                    let end = (start + 1..v.len())
                        .find(|&i| matches!(v[i], b',' | b'}' | b']'))
                        .unwrap_or(v.len());
                    let value = NUMBERS[rng.below(NUMBERS.len())].as_bytes();
                    v.splice(start + 1..end, value.iter().copied());
                }
            }
            // Delete a key-value pair or a range.
            3 if !v.is_empty() => {
                let a = rng.below(v.len());
                let b = (a + 1 + rng.below(64)).min(v.len());
                v.drain(a..b);
            }
            // Flip bytes.
            4 if !v.is_empty() => {
                for _ in 0..1 + rng.below(8) {
                    let i = rng.below(v.len());
                    v[i] ^= 1 << rng.below(8);
                }
            }
            // Splice a piece of another seed in.
            5 if !seeds.is_empty() => {
                let other = &seeds[rng.below(seeds.len())];
                if !other.is_empty() {
                    let a = rng.below(other.len());
                    let b = (a + rng.below(256)).min(other.len());
                    let at = rng.below(v.len() + 1);
                    v.splice(at..at, other[a..b].iter().copied());
                }
            }
            // Random bytes (FMI call streams are byte-driven).
            6 => {
                let at = rng.below(v.len() + 1);
                let n = 1 + rng.below(32);
                let bytes: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
                v.splice(at..at, bytes);
            }
            // Duplicate a range (deep nesting, long strings, repeated calls).
            7 if !v.is_empty() => {
                let a = rng.below(v.len());
                let b = (a + 1 + rng.below(32)).min(v.len());
                let piece = v[a..b].to_vec();
                for _ in 0..1 + rng.below(16) {
                    v.splice(b..b, piece.iter().copied());
                }
            }
            _ => {
                let n = 1 + rng.below(64);
                v = (0..n).map(|_| rng.next() as u8).collect();
            }
        }
    }
    v.truncate(1 << 16);
    v
}

fn hash(data: &[u8]) -> u64 {
    data.iter()
        .fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ *b as u64).wrapping_mul(0x0100_0000_01b3))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let Some(target) = args.get(1).filter(|t| targets::TARGETS.contains(&t.as_str())) else {
        eprintln!("usage: drive TARGET [SECONDS] [SEED]; targets: {}", targets::TARGETS.join(", "));
        std::process::exit(2);
    };
    let seconds: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(10.0);
    let seed: u64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut seeds = read_dir(&root.join("seeds").join(target));
    seeds.extend(read_dir(&root.join("corpus").join(target)));
    seeds.extend(read_dir(&root.join("regressions").join(target)));
    if seeds.is_empty() {
        seeds.push(Vec::new());
    }
    // Quiet panics: a panic is reported once, with its input.
    std::panic::set_hook(Box::new(|_| {}));
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let budget = Duration::from_secs_f64(seconds);
    let started = Instant::now();
    let mut runs = 0u64;
    // Every seed first, unmodified; then mutations.
    let mut queue: Vec<Vec<u8>> = seeds.clone();
    while started.elapsed() < budget {
        let input = match queue.pop() {
            Some(i) => i,
            None => mutate(&seeds[rng.below(seeds.len())], &seeds, &mut rng),
        };
        let result = std::panic::catch_unwind(|| targets::run(target, &input));
        runs += 1;
        if let Err(payload) = result {
            let msg = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            let dir = root.join("artifacts").join(target);
            let _ = std::fs::create_dir_all(&dir);
            let path = dir.join(format!("crash-{:016x}", hash(&input)));
            let _ = std::fs::write(&path, &input);
            eprintln!("{target}: input {} panicked: {msg}", path.display());
            std::process::exit(1);
        }
    }
    println!(
        "{target}: {runs} inputs in {:.1} s (seed {seed}, {} seeds), no crash",
        started.elapsed().as_secs_f64(),
        seeds.len()
    );
}
