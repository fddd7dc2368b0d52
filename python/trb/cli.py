"""`trb-sweep`: run a sweep file on Dask and write one Parquet row per case.

    trb-sweep SWEEP.json --out RESULTS.parquet [--scheduler tcp://HOST:PORT] [--workers N]
              [--trb PATH] [--timeout S] [--no-progress] [--dry-run]

Exit codes: 0 every case finished (`ok`, `refused` or `invalid`: see the results' `status`);
1 some cases ended in `error` (a crash, a timeout, a lost worker: rerun to retry them);
2 a bad sweep file or option (the message names the field; nothing was run);
130 interrupted (finished cases are kept; rerun to resume).
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
from pathlib import Path

from .errors import SweepError


def default_trb() -> Path | None:
    """The `trb` program: $TRB_PROGRAM, else target/release/trb of the checkout this package
    lives in, else `trb` on PATH."""
    env = os.environ.get("TRB_PROGRAM")
    if env:
        return Path(env)
    repo = Path(__file__).resolve().parents[2] / "target" / "release" / "trb"
    if repo.is_file():
        return repo
    found = shutil.which("trb")
    return Path(found) if found else None


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="trb-sweep",
        description="Run the cases of a sweep file (sweeps/README.md) through `trb simulate` on Dask; "
        "one Parquet row per case. Finished cases are saved as they complete; a rerun with the same "
        "--out skips them.",
    )
    p.add_argument("sweep", type=Path, help="the sweep file (JSON)")
    p.add_argument("--out", type=Path, required=True, help="the results file (Parquet)")
    p.add_argument("--scheduler", help="address of a running Dask scheduler (tcp://HOST:PORT); default: an in-process LocalCluster")
    p.add_argument("--workers", type=int, help="workers of the local cluster (default: the CPU count)")
    p.add_argument("--trb", type=Path, help="the trb program (default: $TRB_PROGRAM, target/release/trb, or trb on PATH); "
                   "with --scheduler it must exist at this path on every worker")
    p.add_argument("--timeout", type=float, help="seconds a case may take before it is stopped (status error)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--dry-run", action="store_true", help="check the sweep file and count the cases; run nothing")
    return p


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        return _main(args)
    except SweepError as e:
        print(f"trb-sweep: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("trb-sweep: interrupted; the finished cases are kept, rerun the same command to resume", file=sys.stderr)
        return 130


def _main(args) -> int:
    from . import spec

    if args.workers is not None and args.workers < 1:
        raise SweepError("--workers", f"must be at least 1, got {args.workers}")
    if args.workers is not None and args.scheduler:
        raise SweepError("--workers", "applies to the local cluster only; the cluster at --scheduler has its own workers")
    if args.timeout is not None and not args.timeout > 0:
        raise SweepError("--timeout", f"must be > 0, got {args.timeout}")
    if args.out.suffix != ".parquet":
        raise SweepError("--out", f"must name a .parquet file, got {args.out}")
    trb = args.trb or default_trb()
    if trb is None or not trb.is_file():
        raise SweepError("--trb", f"the trb program was not found ({trb or 'not on PATH'}); build it with `cargo build --release` or name it with --trb")
    trb = trb.resolve()

    sweep = spec.load(args.sweep, trb)
    print(f"{args.sweep}: {sweep.mode}, {len(sweep.cases)} cases, bearing {sweep.bearing}, {len(sweep.value_columns)} value columns")
    if sweep.held:
        print(f"  held inputs, from the base scenario or else the bearing's operating point (a column each in the results): {', '.join(sweep.held)}")
    if args.dry_run:
        from .store import Store

        done = Store(args.out, sweep.value_columns).finished()
        left = len({c.id for c in sweep.cases} - set(done))
        print(f"dry run: {left} of {len({c.id for c in sweep.cases})} distinct cases would run")
        return 0

    from .sweep import run

    outcome = run(sweep, args.out, trb, scheduler=args.scheduler, workers=args.workers,
                  progress=not args.no_progress, timeout=args.timeout)
    counts = ", ".join(f"{n} {s}" for s, n in sorted(outcome.statuses.items()))
    print(f"wrote {args.out}: {outcome.table.num_rows} cases ({counts}); {outcome.ran} run, {outcome.reused} reused")
    if outcome.ran:
        print(f"  ran {outcome.ran} cases in {outcome.elapsed:.2f} s ({outcome.ran / outcome.elapsed:.1f} cases/s)")
    if outcome.aggregation:
        for key, e in outcome.aggregation.items():
            value = "n/a (" + e.get("reason", "") + ")" if e["value"] is None else f"{e['value']:.6g} {e['unit'] or ''}"
            print(f"  duty cycle {key} ({e['column']}): {value}")
    for p in outcome.plots:
        print(f"  map: {p}")
    return 1 if outcome.statuses.get("error") else 0


if __name__ == "__main__":
    sys.exit(main())
