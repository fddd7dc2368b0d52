#!/usr/bin/env bash
# The project's test command: every Rust test, then the Python harness (fmpy, libcosim,
# fmu-manipulation-toolbox) against the packaged FMU.
#
#   ./scripts/test.sh [extra pytest arguments]
#
# 1. the project venv .venv (made with the first python3 on PATH that is 3.11 or newer),
#    (re)created when missing or when tests/python/requirements.txt or python/pyproject.toml
#    changed (their hash is kept in .venv), with the project's Python package python/ (trb,
#    the trb-sweep console script) installed editable;
# 2. cargo test --release (all Rust unit and integration tests);
# 3. cargo run --release -- fmu (target/fmu/TaperedRollerBearing.fmu), then its leak check
#    under valgrind (scripts/leaks.sh) and a bounded fuzzing run (scripts/fuzz.sh); then the
#    portable FMU (cargo run --release -- fmu --portable, tools by scripts/cross-setup.sh) and
#    its tests (tests/portable: glibc 2.17, the win64 DLL under wine against linux64);
# 4. pytest tests/python (Ecos's runtime libtbb12 installed first, as root with apt-get).
# Needs only Rust (cargo), Python 3.11 or newer with pip (and venv), and a C toolchain for
# cargo; the portable FMU's tools are installed by scripts/cross-setup.sh (Debian packages
# only as root).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
ROOT="$(pwd)"
# The FMU path contract is target/fmu/: use cargo's default target directory.
unset CARGO_TARGET_DIR

REQUIREMENTS="tests/python/requirements.txt"
PYPROJECT="python/pyproject.toml"
VENV=".venv"
STAMP="$VENV/.requirements.sha256"

declare -a PHASES=()
phase_start=0
begin() {
    phase_start=$(date +%s.%N)
    printf '\n==> %s\n' "$1"
}
end() {
    local secs
    secs=$(awk -v a="$phase_start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
    PHASES+=("$(printf '%-34s %7ss' "$1" "$secs")")
}
fail() {
    printf '\nFAILED: %s\n' "$1" >&2
    exit 1
}

# A full run leaves about 5.5 GB here (target/ 4 GB with the cross builds and the wine prefix,
# .venv 1.1 GB). Say so up front rather than fail half-way in a linker with "No space left".
NEED_KB=$((6 * 1024 * 1024))
FREE_KB=$(df -Pk . | awk 'NR == 2 { print $4 }')
if [ -n "$FREE_KB" ] && [ "$FREE_KB" -lt "$NEED_KB" ]; then
    printf 'warning: %s MB free on this file system; a full test run needs about 6000 MB.\n' \
        "$((FREE_KB / 1024))" >&2
fi

# --- 1. Python venv -----------------------------------------------------------------------
# The first of python3, python3.13, python3.12, python3.11 on PATH that runs and is 3.11 or newer
# (a name that is on PATH but does not run, e.g. a pyenv shim without its version, is passed over).
PYTHON_NAMES=(python3 python3.13 python3.12 python3.11)
find_python() {
    local candidate
    for candidate in "${PYTHON_NAMES[@]}"; do
        if command -v "$candidate" >/dev/null 2>&1 &&
            "$candidate" -c 'import sys; sys.exit(sys.version_info < (3, 11))' >/dev/null 2>&1; then
            command -v "$candidate"
            return 0
        fi
    done
    return 1
}
python_versions_found() {
    local candidate version found=""
    for candidate in "${PYTHON_NAMES[@]}"; do
        command -v "$candidate" >/dev/null 2>&1 || continue
        version="$("$candidate" -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null)" ||
            version="does not run"
        found="$found${found:+, }$candidate: $version"
    done
    echo "${found:-none of them is on PATH}"
}

begin "Python venv ($VENV)"
want_hash="$( (cat "$REQUIREMENTS" "$PYPROJECT" | (sha256sum 2>/dev/null || shasum -a 256)) | cut -d' ' -f1)"
have_hash="$(cat "$STAMP" 2>/dev/null || true)"
if [ ! -x "$VENV/bin/python" ] || [ "$want_hash" != "$have_hash" ]; then
    PYTHON="$(find_python)" ||
        fail "Python 3.11 or newer with pip and venv is needed to make $VENV; tried ${PYTHON_NAMES[*]} ($(python_versions_found))"
    echo "creating $VENV with $PYTHON ($("$PYTHON" --version 2>&1)); installing $REQUIREMENTS"
    rm -rf "$VENV"
    if "$PYTHON" -m venv "$VENV"; then
        PIP=("$VENV/bin/python" -m pip)
        "${PIP[@]}" install --quiet --disable-pip-version-check -r "$REQUIREMENTS"
    else
        # No ensurepip (e.g. Debian without python3.11-venv): a venv without pip, filled by
        # the interpreter's own pip.
        echo "python -m venv failed; retrying without pip in the venv"
        rm -rf "$VENV"
        "$PYTHON" -m venv --without-pip "$VENV" || fail "cannot create $VENV"
        PIP=("$PYTHON" -m pip --python "$VENV/bin/python")
        "${PIP[@]}" install --quiet --disable-pip-version-check -r "$REQUIREMENTS" ||
            fail "cannot install $REQUIREMENTS into $VENV"
    fi
    # The project's package, editable (its code is read from python/trb; setuptools is pinned
    # in the requirements, so no build environment is downloaded).
    "${PIP[@]}" install --quiet --disable-pip-version-check --no-deps --no-build-isolation -e ./python ||
        fail "cannot install python/ (the trb package) into $VENV"
    echo "$want_hash" >"$STAMP"
else
    echo "$VENV is up to date with $REQUIREMENTS and $PYPROJECT"
fi
"$VENV/bin/python" -c 'import fmpy, pytest, numpy, libcosimpy, fmu_manipulation_toolbox, dask, distributed, pyarrow, trb.sweep' ||
    fail "$VENV lacks a required package; remove $VENV and rerun"
[ -x "$VENV/bin/trb-sweep" ] || fail "$VENV/bin/trb-sweep is missing; remove $VENV and rerun"
end "Python venv"

# --- 2. Rust tests ----------------------------------------------------------------------------
begin "cargo test --release"
cargo test --release || fail "cargo test --release"
end "cargo test --release"

# --- 3. The FMU ---------------------------------------------------------------------------------
begin "cargo run --release -- fmu"
cargo run --release --quiet -- fmu || fail "cargo run --release -- fmu"
[ -f target/fmu/TaperedRollerBearing.fmu ] || fail "target/fmu/TaperedRollerBearing.fmu was not written"
end "cargo run --release -- fmu"

# --- 3b. Robustness: leak check of the packaged FMU, bounded fuzzing ---------------------
begin "leak check (valgrind)"
./scripts/leaks.sh 20 || fail "scripts/leaks.sh"
end "leak check (valgrind)"

begin "fuzz (stable driver, 3 x 10 s)"
./scripts/fuzz.sh 10 || fail "scripts/fuzz.sh (crash input in fuzz/artifacts/)"
end "fuzz (stable driver)"

# --- 3c. The portable FMU: linux64 for glibc >= 2.17 and win64 -------------------------
# Tools by scripts/cross-setup.sh (PyPI pins into .venv-cross; Debian packages when root). A
# tool that cannot be installed here skips the build and its tests, saying which; the rest runs.
PORTABLE_FMU="target/fmu-portable/TaperedRollerBearing.fmu"
begin "cross tools (scripts/cross-setup.sh)"
./scripts/cross-setup.sh || fail "scripts/cross-setup.sh"
end "cross tools (apt, pip)"

begin "cargo run --release -- fmu --portable"
rm -f "$PORTABLE_FMU"
portable_status=0
cargo run --release --quiet -- fmu --portable --out "$PORTABLE_FMU" || portable_status=$?
if [ "$portable_status" = 3 ]; then
    echo "SKIPPED: the portable FMU needs the tools named above; its tests are skipped too"
    end "fmu --portable (SKIPPED: tools)"
elif [ "$portable_status" != 0 ]; then
    fail "cargo run --release -- fmu --portable (exit $portable_status)"
else
    end "cargo run --release -- fmu --portable"
    begin "pytest tests/portable (glibc, wine)"
    PORTABLE_FMU="$PORTABLE_FMU" "$VENV/bin/python" -m pytest tests/portable -q -s -rs -p no:cacheprovider ||
        fail "pytest tests/portable"
    end "pytest tests/portable (glibc, wine)"
fi

# --- 4. Python harness ---------------------------------------------------------------------------
if [ -x "$ROOT/../shared/tools/fmuCheck.linux64" ] || [ -n "${TRB_FMUCHECK:-}" ]; then
    echo "FMU Compliance Checker: ${TRB_FMUCHECK:-$ROOT/../shared/tools/fmuCheck.linux64} (tests/python/test_package.py)"
else
    echo "NOTE: no FMU Compliance Checker at $ROOT/../shared/tools/fmuCheck.linux64 (set TRB_FMUCHECK): its checks are skipped"
fi
# Ecos (ecospy, tests/python/test_ecos.py) loads Debian's libtbb12: installed here as root with
# apt-get; elsewhere its tests are skipped with that reason.
if ldconfig -p 2>/dev/null | grep -q 'libtbb\.so\.12'; then
    echo "Ecos: libtbb12 is installed (tests/python/test_ecos.py)"
elif [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    if apt-get install -y -qq --no-install-recommends libtbb12 >/dev/null 2>&1 ||
        { apt-get update -qq >/dev/null 2>&1 && apt-get install -y -qq --no-install-recommends libtbb12 >/dev/null 2>&1; }; then
        echo "Ecos: installed libtbb12 with apt-get (tests/python/test_ecos.py)"
    else
        echo "NOTE: apt-get could not install libtbb12: the Ecos tests (tests/python/test_ecos.py) are skipped"
    fi
else
    echo "NOTE: Debian's libtbb12 is missing and cannot be installed here (not root or no apt-get): the Ecos tests (tests/python/test_ecos.py) are skipped"
fi
begin "pytest tests/python"
"$VENV/bin/python" -m pytest tests/python -q -p no:cacheprovider "$@" || fail "pytest tests/python"
end "pytest tests/python"

printf '\n==> Summary (%s)\n' "$ROOT"
for line in "${PHASES[@]}"; do
    printf '  %s\n' "$line"
done
echo "All tests passed."
