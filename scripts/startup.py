#!/usr/bin/env python3
"""Start-up of the FMU through fmpy, as an importer meets it: read the model description from
the archive, extract the archive, load the library and instantiate, initialise, one 1 ms step,
and simulate_fmu's whole call for that step. Each run is a fresh Python process (fmpy imported
before the clock starts), the FMU extracted into a new temporary directory; medians over the
runs, in milliseconds.

    .venv/bin/python scripts/startup.py [FMU] [--runs N]

FMU: target/fmu/TaperedRollerBearing.fmu by default. Needs fmpy (tests/python/requirements.txt).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

PHASES = ["read modelDescription", "extract", "instantiate", "initialise", "first doStep", "total", "simulate_fmu"]

# One run, in its own process: prints the phases' times (s) as JSON.
_ONE_RUN = r"""
import json, shutil, sys, time
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi2 import FMU2Slave

fmu = sys.argv[1]
t = {}
t0 = time.perf_counter()
md = read_model_description(fmu)
t1 = time.perf_counter()
unzipdir = extract(fmu)
t2 = time.perf_counter()
slave = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="startup")
slave.instantiate()
t3 = time.perf_counter()
slave.setupExperiment(startTime=0.0)
slave.enterInitializationMode()
slave.exitInitializationMode()
t4 = time.perf_counter()
slave.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
t5 = time.perf_counter()
slave.terminate()
slave.freeInstance()
shutil.rmtree(unzipdir, ignore_errors=True)
t6 = time.perf_counter()
simulate_fmu(fmu, stop_time=1e-3, output_interval=1e-3, output=["frictionTorque"])
t7 = time.perf_counter()
print(json.dumps({
    "read modelDescription": t1 - t0, "extract": t2 - t1, "instantiate": t3 - t2,
    "initialise": t4 - t3, "first doStep": t5 - t4, "total": t5 - t0, "simulate_fmu": t7 - t6,
}))
"""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("fmu", nargs="?", default="target/fmu/TaperedRollerBearing.fmu")
    parser.add_argument("--runs", type=int, default=11)
    args = parser.parse_args()
    fmu = Path(args.fmu)
    if not fmu.is_file():
        print(f"no FMU at {fmu}: cargo run --release -- fmu", file=sys.stderr)
        return 2
    runs = []
    for _ in range(args.runs):
        out = subprocess.run([sys.executable, "-c", _ONE_RUN, str(fmu)], capture_output=True, text=True, check=True)
        runs.append(json.loads(out.stdout.strip().splitlines()[-1]))
    print(f"{fmu}: {os.path.getsize(fmu) / 1e6:.2f} MB, medians of {len(runs)} runs (min–max), ms")
    for phase in PHASES:
        values = [1e3 * r[phase] for r in runs]
        print(f"  {phase:22s} {statistics.median(values):8.2f}  ({min(values):.2f}–{max(values):.2f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
