"""Run a resolved sweep on Dask: one task per case, results written as they complete.

The scheduler is never hidden: `connect(scheduler, workers)` gives a Client of an in-process
LocalCluster (`workers` worker threads, one task each; every task runs the `trb` program in
its own process) or of the cluster at a scheduler address. Each case not already in the
results (see `trb.store`) is one `client.submit(run_case, task, trb)` with the case's id as
the key; `as_completed` hands back finished cases, which are written as a part file within
WRITE_INTERVAL seconds. The client drops each future as soon as it has its result, so a
worker that dies later cannot take a finished case with it (the scheduler reruns the tasks
the dead worker held unfinished, up to `distributed.scheduler.allowed-failures` times;
`retries` covers exceptions raised in a task).
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import pyarrow as pa

from . import aggregate
from .errors import SweepError
from .runner import run_case
from .spec import Sweep
from .store import Store

TASK_RETRIES = 2
# Finished cases are written at most this many seconds after they arrive (one part file per
# write): a quasi-static sweep finishing hundreds of cases a second writes a few parts a second.
WRITE_INTERVAL = 0.25


@dataclass
class Outcome:
    table: pa.Table
    reused: int
    ran: int
    elapsed: float = 0.0  # s from the first submit to the last part written
    statuses: dict = field(default_factory=dict)
    aggregation: dict | None = None
    plots: list[Path] = field(default_factory=list)


@contextlib.contextmanager
def connect(scheduler: str | None, workers: int | None):
    """A dask.distributed Client: of the cluster at `scheduler`, or of a new in-process
    LocalCluster with `workers` workers (default: the machine's CPU count)."""
    from distributed import Client, LocalCluster

    if scheduler:
        try:
            client = Client(scheduler, timeout="10s")
        except (OSError, TimeoutError, ValueError) as e:
            raise SweepError("--scheduler", f"cannot connect to the Dask scheduler at {scheduler}: {e}") from None
        with client:
            yield client
    else:
        n = workers or os.cpu_count() or 1
        import dask

        # Dask's scratch space (locks, spilling) in a directory of this run, removed after it.
        with tempfile.TemporaryDirectory(prefix="trb-sweep-dask-") as scratch, dask.config.set(
            {"temporary-directory": scratch}
        ), LocalCluster(
            n_workers=n, threads_per_worker=1, processes=False, dashboard_address=None
        ) as cluster, Client(cluster) as client:
            yield client


def _error_record(case_id: str, exc) -> dict:
    return {
        "id": case_id,
        "status": "error",
        "message": f"{type(exc).__name__}: {exc}",
        "values": {},
        "wall_time": None,
        "worker": None,
    }


def run(sweep: Sweep, out: Path, trb: Path, scheduler: str | None = None, workers: int | None = None,
        progress: bool = True, timeout: float | None = None, log=print) -> Outcome:
    """Run every case of `sweep` not yet in `out`, then write `out` (see the module docstring)."""
    from distributed import as_completed
    from tqdm import tqdm

    store = Store(out, sweep.value_columns)
    done = store.finished()
    tasks = {}
    for case in sweep.cases:
        if case.id not in done:
            tasks.setdefault(case.id, case.task)
    reused = len({c.id for c in sweep.cases} - set(tasks))
    log(f"{len(sweep.cases)} cases: {reused} already in the results, {len(tasks)} to run")

    results = dict(done)
    elapsed = 0.0
    if tasks:
        with connect(scheduler, workers) as client:
            log(f"Dask scheduler {client.scheduler.address} with {len(client.scheduler_info(n_workers=-1)['workers'])} workers")
            t0 = time.perf_counter()
            futures = {
                client.submit(run_case, task, str(trb), timeout, key=f"trb-case-{cid}", retries=TASK_RETRIES, pure=False): cid
                for cid, task in tasks.items()
            }
            bar = tqdm(total=len(futures), unit="case", disable=not progress, file=sys.stderr, dynamic_ncols=True)
            pending: list[dict] = []
            last_write = time.monotonic()

            def write():
                nonlocal pending, last_write
                store.write_part(pending)
                for r in pending:
                    results[r["id"]] = store.record_row(r)
                bar.update(len(pending))
                pending, last_write = [], time.monotonic()

            try:
                ac = as_completed(list(futures), with_results=True, raise_errors=False)
                while not ac.is_empty():
                    # Wait for results; with results to write, only until the next write is due.
                    batch = ac.next_batch(block=not pending)
                    for fut, result in batch:
                        cid = futures.pop(fut)
                        if fut.status == "error":
                            result = _error_record(cid, result[1])
                        pending.append(result)
                        fut.release()
                    # Hold no finished future while waiting for the next batch (a held future
                    # whose worker dies would be recomputed).
                    batch = fut = result = None
                    if pending and (time.monotonic() - last_write >= WRITE_INTERVAL or ac.is_empty()):
                        write()
                    elif pending:
                        time.sleep(0.01)
                if pending:
                    write()
            except KeyboardInterrupt:
                if pending:
                    write()  # the cases already received are kept
                raise
            finally:
                bar.close()
            elapsed = time.perf_counter() - t0
    outcome = finish(sweep, store, results, reused, len(tasks), log)
    outcome.elapsed = elapsed
    return outcome


def finish(sweep: Sweep, store: Store, results: dict, reused: int, ran: int, log=print) -> Outcome:
    """Combine the results file, then the aggregation and the plots."""
    case_cols = [("case", pa.int64())]
    if sweep.mode == "spectrum":
        case_cols.append(("time_share", pa.float64()))
    types = {"Real": pa.float64(), "Integer": pa.int64(), "Enumeration": pa.int64(), "Boolean": pa.bool_()}
    case_cols += [(n, types[sweep.table.get(n).type]) for n in sweep.swept]
    rows = []
    for case in sweep.cases:
        row = {"case": case.index, "time_share": case.time_share}
        row.update({n: case.values.get(n) for n in sweep.swept})
        r = results.get(case.id) or store.record_row(_error_record(case.id, RuntimeError("no result")))
        row.update({k: v for k, v in r.items() if k != "id"})
        row["id"] = case.id
        rows.append(row)

    statuses: dict[str, int] = {}
    for r in rows:
        statuses[r["status"]] = statuses.get(r["status"], 0) + 1
    agg = aggregation(sweep, rows) if sweep.mode == "spectrum" else None
    metadata = {"trb.sweep": sweep.text, "trb.bearing": sweep.bearing}
    if agg is not None:
        metadata["trb.aggregation"] = agg
    table = store.combine(case_cols, rows, metadata)
    outcome = Outcome(table=table, reused=reused, ran=ran, statuses=statuses, aggregation=agg)
    if agg is not None:
        path = store.out.with_name(store.out.stem + ".aggregate.json")
        path.write_text(json.dumps(agg, indent=2, allow_nan=False) + "\n")
    if sweep.plots:
        from .plots import draw_map

        units = {n: sweep.unit(n) for n in sweep.swept + sweep.value_columns}
        for p in sweep.plots:
            outcome.plots.append(draw_map(rows, p, units, store.out.parent / p["file"]))
    return outcome


def aggregation(sweep: Sweep, rows: list[dict]) -> dict:
    """Duty-cycle life (Palmgren-Miner) and time-weighted means over the spectrum's bins;
    a value that cannot be computed is null with the reason."""
    shares = [r["time_share"] for r in rows]
    agg = {}
    for key, col in sweep.aggregation.items():
        if col is None:
            continue
        entry = {"column": col, "unit": sweep.unit(col), "value": None}
        bad = [r for r in rows if r["time_share"] > 0 and r["status"] != "ok"]
        if bad:
            entry["reason"] = f"bin {bad[0]['case']} is {bad[0]['status']}: {bad[0]['message']}"
        else:
            f = aggregate.miner_life if key == "life" else aggregate.time_weighted_mean
            try:
                value = f(shares, [r[col] for r in rows])
                entry["value"] = value if math.isfinite(value) else None
                if not math.isfinite(value):
                    entry["reason"] = "no bin adds damage (infinite life)"
            except ValueError as e:
                entry["reason"] = str(e)
        entry["method"] = "Palmgren-Miner: 1 / sum(t_i / L_i)" if key == "life" else "time-weighted mean: sum(t_i x_i)"
        agg[key] = entry
    return agg
