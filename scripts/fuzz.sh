#!/usr/bin/env bash
# Fuzzing of the bearing element: the bearing JSON parser and random FMI call
# sequences (fuzz/src/targets.rs).
#
#   scripts/fuzz.sh [SECONDS]               stable seeded driver, SECONDS per target (default 10)
#   scripts/fuzz.sh --libfuzzer [SECONDS]   cargo-fuzz / libFuzzer with AddressSanitizer,
#                                           SECONDS per target (default 300)
#
# The stable driver (what CI runs, via scripts/test.sh) mutates the seeds in fuzz/seeds/ with
# a fixed seed; no coverage feedback. libFuzzer is coverage guided; it needs cargo-fuzz
# (installed here, pinned, into target/tools) and RUSTC_BOOTSTRAP=1 for the -Z flags on the
# stable toolchain; its first build takes several minutes. Either way a crashing input lands
# in fuzz/artifacts/<target>/: copy it to fuzz/regressions/<target>/ so that
# `cargo test --test fuzz_regressions` keeps replaying it.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
unset CARGO_TARGET_DIR

CARGO_FUZZ_VERSION=0.13.2
TARGETS=(bearing_json fmi_calls dynamic_jumps)

if [ "${1:-}" = "--libfuzzer" ]; then
    seconds="${2:-300}"
    tools="$(pwd)/target/tools"
    if [ ! -x "$tools/bin/cargo-fuzz" ] || ! "$tools/bin/cargo-fuzz" --version | grep -q "$CARGO_FUZZ_VERSION"; then
        cargo install cargo-fuzz --version "$CARGO_FUZZ_VERSION" --locked --root "$tools"
    fi
    cd fuzz
    for t in "${TARGETS[@]}"; do
        mkdir -p "corpus/$t"
        RUSTC_BOOTSTRAP=1 CARGO_TARGET_DIR=../target/fuzz-libfuzzer "$tools/bin/cargo-fuzz" run --features libfuzzer -O "$t" \
            "corpus/$t" "seeds/$t" -- -max_total_time="$seconds" -timeout=30 -rss_limit_mb=4096 -print_final_stats=1
    done
    exit 0
fi

seconds="${1:-10}"
# The main target directory: only trb (as a dependency) and the driver are compiled anew.
cp Cargo.lock fuzz/Cargo.lock
CARGO_TARGET_DIR="$(pwd)/target" cargo build --release --quiet --manifest-path fuzz/Cargo.toml --bin drive
for t in "${TARGETS[@]}"; do
    target/release/drive "$t" "$seconds" 1
done
