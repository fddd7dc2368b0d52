"""One case, run on a Dask worker: `trb simulate SCENARIO.json --out X.csv --quiet`.

`run_case(task)` takes the plain-data task built by `trb.spec` and returns a plain-data
record. It writes the scenario (and the bearing file, if any) into a temporary directory,
runs the `trb` program, and reads the CSV exactly (the program prints shortest round-trip
floats, Python's float() parses them back to the same bits). From the CSV it takes the final
value of each requested output (the last row) and the statistics over the window: the
samples at the communication points t with t0 <= t <= t1, their mean (math.fsum / n), max,
min and RMS (sqrt(fsum(x^2) / n)).

The program's exit code is the case's status: 0 `ok`; 1 `refused` (the model found no
solution; its message is kept); 2 `invalid` (the scenario was refused, naming the field);
anything else (a signal, a missing program, a timeout) `error`. A refused or invalid case is
a result like any other; an `error` is not, and a rerun tries it again.
"""

from __future__ import annotations

import csv
import json
import math
import os
import socket
import subprocess
import tempfile
import time
from pathlib import Path

FINAL_STATUSES = ("ok", "refused", "invalid")


def _worker_name() -> str:
    try:
        from distributed import get_worker

        return get_worker().address
    except (ImportError, ValueError):
        return f"{socket.gethostname()}:{os.getpid()}"


def _message(proc: subprocess.CompletedProcess) -> str:
    text = (proc.stderr or "").strip() or (proc.stdout or "").strip()
    return text[-4000:]


def statistic(function: str, xs: list[float]) -> float:
    """One statistic of the window's samples (see the module docstring)."""
    if function == "mean":
        return math.fsum(xs) / len(xs)
    if function == "max":
        return max(xs)
    if function == "min":
        return min(xs)
    if function == "rms":
        return math.sqrt(math.fsum(x * x for x in xs) / len(xs))
    raise ValueError(f"unknown statistic {function!r}")


def extract(header: list[str], rows: list[list[float]], final: list[str], statistics: dict | None) -> dict:
    """The values of a finished run: final outputs and statistics, by results column."""
    col = {name: i for i, name in enumerate(header)}
    values = {name: rows[-1][col[name]] for name in final}
    if statistics:
        t0, t1 = statistics["window"]
        window = [r for r in rows if t0 <= r[0] <= t1]
        for name in statistics["outputs"]:
            xs = [r[col[name]] for r in window]
            for f in statistics["functions"]:
                values[f"{name}:{f}"] = statistic(f, xs) if xs else None
    return values


def read_csv(path: Path) -> tuple[list[str], list[list[float]]]:
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = [[float(x) for x in row] for row in reader if row]
    return header, rows


def run_case(task: dict, trb: str, timeout: float | None = None) -> dict:
    """Run one case (see the module docstring); never raises for a case the model or the
    program refuses."""
    start = time.perf_counter()
    record = {"id": task["id"], "status": "error", "message": None, "values": {}, "worker": _worker_name()}
    with tempfile.TemporaryDirectory(prefix="trb-case-") as tmp:
        tmp = Path(tmp)
        if task.get("bearing_text") is not None:
            (tmp / "bearing.json").write_text(task["bearing_text"])
        scenario = tmp / "scenario.json"
        scenario.write_text(json.dumps(task["scenario"], indent=1))
        out = tmp / "out.csv"
        try:
            proc = subprocess.run(
                [trb, "simulate", str(scenario), "--out", str(out), "--quiet"],
                capture_output=True,
                text=True,
                timeout=timeout,
            )
        except subprocess.TimeoutExpired:
            record["message"] = f"timed out after {timeout} s"
        except OSError as e:
            record["message"] = f"cannot run the trb program {trb}: {e}"
        else:
            if proc.returncode == 0:
                try:
                    header, rows = read_csv(out)
                    record["values"] = extract(header, rows, task["final"], task["statistics"])
                    record["status"] = "ok"
                except (OSError, ValueError, KeyError, IndexError, StopIteration) as e:
                    record["message"] = f"cannot read the program's CSV: {type(e).__name__}: {e}"
            elif proc.returncode == 1:
                record["status"], record["message"] = "refused", _message(proc)
            elif proc.returncode == 2:
                record["status"], record["message"] = "invalid", _message(proc)
            else:
                how = f"signal {-proc.returncode}" if proc.returncode < 0 else f"exit code {proc.returncode}"
                record["message"] = f"trb simulate ended with {how}: {_message(proc)}"
    record["wall_time"] = time.perf_counter() - start
    return record
