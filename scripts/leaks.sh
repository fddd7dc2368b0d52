#!/usr/bin/env bash
# Memory check of the packaged FMU: a C driver (scripts/leaks_driver.c) loads
# binaries/linux64/TaperedRollerBearing.so of target/fmu/TaperedRollerBearing.fmu with dlopen
# and runs ITERATIONS instantiate ... free life cycles (with FMU states, error paths and
# refused instantiations) under valgrind; any definitely or indirectly lost byte, or any
# invalid memory access, fails.
#
#   scripts/leaks.sh [ITERATIONS]       (default 20; needs gcc, valgrind and the packaged FMU)
#
# Without valgrind on the machine the script says so and exits 0 (Debian: apt-get install
# valgrind); set LEAKS_REQUIRED=1 to make that an error.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
ROOT="$(pwd)"
iterations="${1:-20}"
fmu="$ROOT/target/fmu/TaperedRollerBearing.fmu"

if ! command -v valgrind >/dev/null 2>&1; then
    echo "valgrind not found: leak check skipped (apt-get install valgrind)"
    [ "${LEAKS_REQUIRED:-0}" = "1" ] && exit 1
    exit 0
fi
[ -f "$fmu" ] || { echo "no $fmu: run cargo run --release -- fmu first" >&2; exit 1; }

work="$ROOT/target/leaks"
rm -rf "$work"
mkdir -p "$work/fmu"
python3 -c 'import sys, zipfile; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])' "$fmu" "$work/fmu"
# The library in the FMU is stripped; its debug file (written beside the FMU by `trb fmu`, named
# by the library's .gnu_debuglink) goes beside the extracted library, where valgrind finds it
# and names functions and lines in a report.
debug="${fmu%.fmu}.linux64.debug"
if [ -f "$debug" ]; then
    cp "$debug" "$work/fmu/binaries/linux64/"
fi
guid="$(python3 -c 'import re, sys; print(re.search(r"guid=\"([^\"]+)\"", open(sys.argv[1]).read()).group(1))' "$work/fmu/modelDescription.xml")"
gcc -O1 -g -Wall -Wextra -o "$work/driver" scripts/leaks_driver.c -ldl

valgrind --quiet --leak-check=full --show-leak-kinds=definite,indirect --errors-for-leak-kinds=definite,indirect \
    --error-exitcode=99 --log-file="$work/valgrind.log" \
    "$work/driver" "$work/fmu/binaries/linux64/TaperedRollerBearing.so" "$guid" "file://$work/fmu/resources" "$iterations" || {
    status=$?
    cat "$work/valgrind.log" >&2
    echo "leak check FAILED (exit $status): see $work/valgrind.log" >&2
    exit 1
}
if [ -s "$work/valgrind.log" ]; then
    cat "$work/valgrind.log"
fi
echo "leak check: no leaks and no invalid accesses in $iterations life cycles (valgrind)"
