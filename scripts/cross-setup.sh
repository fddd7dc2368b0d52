#!/usr/bin/env bash
# Install the tools of `trb fmu --portable` (linux64 for glibc >= 2.17, win64) and of its test
# under wine (docs: README "Platforms"; recipe: zig as the Linux linker, Debian's Rust with the
# std sources and mingw-w64 for Windows).
#
#   scripts/cross-setup.sh
#
# 1. .venv-cross (Python 3.11): ziglang and cargo-zigbuild pinned in
#    scripts/cross-requirements.txt, (re)created when missing or when that file changed.
# 2. Debian packages (when running as root with apt-get): rustc-web cargo-web rust-web-src
#    (Debian's Rust 1.96 with the std sources, for -Zbuild-std), gcc-mingw-w64-x86-64 (the
#    Windows linker, also builds the test driver) and wine64 (runs the test driver).
#
# Whatever cannot be installed here (no root, no apt-get, no network) is skipped with a
# message naming what is missing; the script then exits 0 and `trb fmu --portable` reports the
# missing tool itself. Set CROSS_REQUIRED=1 to make any skip an error.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

REQUIREMENTS="scripts/cross-requirements.txt"
VENV=".venv-cross"
STAMP="$VENV/.requirements.sha256"
APT_PACKAGES=(rustc-web cargo-web rust-web-src gcc-mingw-w64-x86-64 wine64)
skipped=0

skip() {
    printf 'cross-setup: SKIPPED: %s\n' "$1"
    skipped=1
}

# --- 1. zig and cargo-zigbuild (PyPI) -------------------------------------------------------
want_hash="$( (sha256sum "$REQUIREMENTS" 2>/dev/null || shasum -a 256 "$REQUIREMENTS") | cut -d' ' -f1)"
have_hash="$(cat "$STAMP" 2>/dev/null || true)"
if [ -x "$VENV/bin/cargo-zigbuild" ] && [ "$want_hash" = "$have_hash" ]; then
    echo "cross-setup: $VENV is up to date with $REQUIREMENTS"
else
    PYTHON=""
    for candidate in python3.11 python3; do
        if command -v "$candidate" >/dev/null 2>&1; then
            PYTHON="$(command -v "$candidate")"
            break
        fi
    done
    if [ -z "$PYTHON" ]; then
        skip "no python3: cannot install $REQUIREMENTS (zig, cargo-zigbuild)"
    else
        echo "cross-setup: creating $VENV with $PYTHON; installing $REQUIREMENTS"
        rm -rf "$VENV"
        ok=0
        if "$PYTHON" -m venv "$VENV" 2>/dev/null; then
            "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check -r "$REQUIREMENTS" && ok=1
        else
            # No ensurepip (Debian without python3.11-venv): a venv filled by the interpreter's pip.
            rm -rf "$VENV"
            "$PYTHON" -m venv --without-pip "$VENV" &&
                "$PYTHON" -m pip --python "$VENV/bin/python" install --quiet --disable-pip-version-check \
                    -r "$REQUIREMENTS" && ok=1
        fi
        if [ "$ok" = 1 ] && [ -x "$VENV/bin/cargo-zigbuild" ]; then
            echo "$want_hash" >"$STAMP"
        else
            rm -rf "$VENV"
            skip "cannot install $REQUIREMENTS into $VENV (is PyPI reachable?)"
        fi
    fi
fi

# --- 2. Debian packages ------------------------------------------------------------------------
missing=()
for p in "${APT_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
    echo "cross-setup: Debian packages present: ${APT_PACKAGES[*]}"
elif ! command -v apt-get >/dev/null 2>&1; then
    skip "no apt-get: install ${missing[*]} (or their equivalents) by hand"
elif [ "$(id -u)" != 0 ]; then
    skip "not root: run as root, or: sudo apt-get install ${missing[*]}"
else
    echo "cross-setup: apt-get install ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    if ! apt-get update -qq; then
        skip "apt-get update failed (no network?): ${missing[*]} not installed"
    elif ! apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null; then
        skip "apt-get install ${missing[*]} failed"
    fi
fi

# --- What is there now ----------------------------------------------------------------------------
[ -x /usr/bin/cargo ] && echo "cross-setup: $(/usr/bin/cargo --version) ($(/usr/bin/rustc --version)) at /usr/bin"
command -v x86_64-w64-mingw32-gcc >/dev/null 2>&1 &&
    echo "cross-setup: $(x86_64-w64-mingw32-gcc --version | head -1)"
for w in wine64 /usr/lib/wine/wine64 wine; do
    if command -v "$w" >/dev/null 2>&1; then
        echo "cross-setup: $("$w" --version 2>/dev/null) ($w)"
        break
    fi
done
[ -x "$VENV/bin/cargo-zigbuild" ] &&
    echo "cross-setup: $("$VENV/bin/cargo-zigbuild" --version), zig $("$VENV/bin/python" -m ziglang version)"

if [ "$skipped" = 1 ] && [ "${CROSS_REQUIRED:-0}" = 1 ]; then
    echo "cross-setup: CROSS_REQUIRED=1 and a step was skipped" >&2
    exit 1
fi
exit 0
