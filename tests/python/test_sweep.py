"""`trb-sweep` (python/trb, sweeps/README.md): sweeps of the element on Dask.

- a 2-worker LocalCluster sweep gives the very floats of single `trb simulate` runs of its
  cases (final values and window statistics), and records a refused case with its message;
- an extended rerun runs only the new cases (the runs are counted by a wrapper around the
  `trb` program that logs every `simulate`);
- a sweep whose client is killed mid-sweep resumes: the rerun runs exactly the cases not in
  its part files;
- a worker process killed mid-sweep (a LocalCluster with processes, reached by
  --scheduler) loses no finished case, and the case it was running is run again elsewhere;
- the Palmgren-Miner life and the time-weighted mean on synthetic data, and over a spectrum;
- bad sweep files: exit code 2, the field named, no traceback;
- the shipped examples in sweeps/ are valid.
"""

from __future__ import annotations

import json
import math
import os
import signal
import statistics
import subprocess
import sys
import time
from fractions import Fraction
from pathlib import Path

import pyarrow.parquet as pq
import pytest

from conftest import REPO, TRB, ensure_built, read_csv, run_cli, write_json

TRB_SWEEP = Path(sys.executable).parent / "trb-sweep"
SPEED = [209.43951023931953, 366.51914291880917]
BASE = {"scenario": {"stop_time": 0.001, "step": 0.001}}  # a one-step base scenario


# ---------------------------------------------------------------------------------------
# Helpers
# ---------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def trb_program() -> Path:
    ensure_built()
    assert TRB_SWEEP.is_file(), f"{TRB_SWEEP} is missing: the venv phase of scripts/test.sh installs python/ editable"
    return TRB


class Counter:
    """A wrapper around the trb program that logs each `simulate` of a case it runs: the md5
    of the scenario file (the case), the parent pid (the Dask worker process) and its own pid.
    The one-step check of the first case before a sweep (trb.spec.check_scenario, in a
    directory trb-sweep-check-*) is not a case and is not logged. With `delay` (s) every case
    takes at least that long (a sleep before the program), so the tests that kill a sweep or a
    worker mid-way find one in the middle on a fast machine as on a slow one."""

    def __init__(self, directory: Path, real: Path, delay: float = 0.0):
        self.log = directory / "runs.log"
        self.path = directory / "trb-counting"
        self.path.write_text(
            "#!/bin/sh\n"
            'case "$1 $2" in simulate*trb-sweep-check-*) exec "' + str(real) + '" "$@";; esac\n'
            'if [ "$1" = simulate ]; then\n'
            f'  echo "start $(md5sum < "$2" | cut -c1-32) $PPID $$" >> "{self.log}"\n'
            + (f"  sleep {delay}\n" if delay > 0 else "")
            + "fi\n"
            f'"{real}" "$@"\n'
            "rc=$?\n"
            f'[ "$1" = simulate ] && echo "end - $PPID $$" >> "{self.log}"\n'
            "exit $rc\n"
        )
        self.path.chmod(0o755)

    def starts(self) -> list[tuple[str, int, int]]:
        if not self.log.is_file():
            return []
        out = []
        for line in self.log.read_text().splitlines():
            fields = line.split()
            if len(fields) == 4 and fields[0] == "start":  # (a line being written is skipped)
                out.append((fields[1], int(fields[2]), int(fields[3])))
        return out

    def running(self) -> list[tuple[str, int, int]]:
        """Runs started and not ended."""
        if not self.log.is_file():
            return []
        ended = {int(f[3]) for f in map(str.split, self.log.read_text().splitlines()) if len(f) == 4 and f[0] == "end"}
        return [s for s in self.starts() if s[2] not in ended]

    def reset(self):
        self.log.unlink(missing_ok=True)


def sweep_cli(*args, timeout: float = 120, check: bool = True) -> subprocess.CompletedProcess:
    proc = subprocess.run([str(TRB_SWEEP), *map(str, args), "--no-progress"], capture_output=True, text=True, timeout=timeout)
    if check and proc.returncode != 0:
        raise AssertionError(f"trb-sweep {args} exited with {proc.returncode}\n--- stdout\n{proc.stdout}\n--- stderr\n{proc.stderr}")
    return proc


def rows_by_id(path: Path) -> dict[str, dict]:
    return {r["id"]: r for r in pq.read_table(path).to_pylist()}


def part_ids(out: Path) -> set[str]:
    parts = out.with_name(out.name + ".parts")
    ids = set()
    for f in parts.glob("part-*.parquet"):
        ids |= set(pq.read_table(f).column("id").to_pylist())
    return ids


def wait_for(predicate, timeout: float, what: str, poll: float = 0.01):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(poll)
    raise AssertionError(f"timed out after {timeout} s waiting for {what}")


def slow_sweep(n_speeds: int) -> dict:
    """Quasi-static cases of 120 communication steps (each re-solves: ~0.1-0.2 s a case)."""
    return {
        "scenario": {"parameters": {"fidelity": 0}, "inputs": {"Fx": 30000.0}, "stop_time": 0.12, "step": 0.001},
        "grid": {"speed": [100.0 + 20.0 * k for k in range(n_speeds)], "Fy": [0.0, 8000.0]},
        "outputs": ["frictionTorque", "powerLoss"],
    }


# ---------------------------------------------------------------------------------------
# Aggregation (pure functions)
# ---------------------------------------------------------------------------------------


def test_miner_life_and_time_weighted_mean_on_synthetic_data():
    from trb.aggregate import miner_life, time_weighted_mean

    # L = 1 / sum(t_i / L_i), shares normalised: exact against rational arithmetic.
    shares, lives = [10.0, 30.0, 60.0], [2000.0, 8000.0, 50000.0]
    exact = 1 / sum(Fraction(t) / 100 / Fraction(L) for t, L in zip(shares, lives))
    assert miner_life(shares, lives) == pytest.approx(float(exact), rel=1e-15)
    assert float(exact) == pytest.approx(1 / (0.1 / 2000 + 0.3 / 8000 + 0.6 / 50000))
    # The shares' scale does not matter; one bin alone gives its own life.
    assert miner_life([1.0, 3.0, 6.0], lives) == pytest.approx(miner_life(shares, lives), rel=1e-15)
    assert miner_life([5.0], [1234.5]) == 1234.5
    # Equal lives give that life whatever the shares.
    assert miner_life([0.2, 0.8], [700.0, 700.0]) == pytest.approx(700.0, rel=1e-15)
    # The duty-cycle life lies between the shortest and the longest bin life, below the
    # time-weighted mean of lives (Miner is a harmonic mean).
    L = miner_life(shares, lives)
    assert min(lives) < L < time_weighted_mean(shares, lives) < max(lives)
    # A bin with infinite life or zero share adds no damage; a bin without life and no share is ignored.
    assert miner_life([1.0, 1.0], [math.inf, 500.0]) == pytest.approx(1000.0, rel=1e-15)
    assert miner_life([0.0, 2.0], [None, 500.0]) == 500.0
    assert miner_life([1.0], [math.inf]) == math.inf
    # Mean power loss.
    assert time_weighted_mean([1.0, 3.0], [100.0, 200.0]) == 175.0
    for bad_shares, bad_lives, msg in [
        ([1.0, -1.0], [1.0, 1.0], "bin 1: time share"),
        ([0.0, 0.0], [1.0, 1.0], "sum to 0"),
        ([1.0, 1.0], [1.0, 0.0], "bin 1: life"),
        ([1.0, 1.0], [None, 1.0], "bin 0: life"),
        ([1.0, math.nan], [1.0, 1.0], "bin 1: time share"),
        ([1.0], [1.0, 2.0], "1 time shares but 2 lives"),
    ]:
        with pytest.raises(ValueError, match=msg):
            miner_life(bad_shares, bad_lives)


def test_runner_records_an_invalid_scenario_with_the_programs_message(trb_program):
    """Exit code 2 of `trb simulate` (the scenario refused) is a result, not an exception."""
    from trb.runner import run_case

    task = {
        "id": "x",
        "scenario": {"inputs": {"Fy": {"time": [0.0, 0.0], "values": [1.0, 2.0]}}, "stop_time": 0.001, "step": 0.001},
        "bearing_text": None,
        "final": ["frictionTorque"],
        "statistics": None,
    }
    r = run_case(task, str(trb_program))
    assert r["status"] == "invalid" and "inputs.Fy.time" in r["message"], r
    r = run_case(task, "/nonexistent/trb")
    assert r["status"] == "error" and "/nonexistent/trb" in r["message"], r


# ---------------------------------------------------------------------------------------
# A sweep equals its single runs; an extended rerun runs the new cases only
# ---------------------------------------------------------------------------------------


def test_two_worker_sweep_equals_single_runs_and_rerun_runs_only_new_cases(tmp_path, trb_program):
    # An axial load ramp: the window's samples differ.
    ramp = {"time": [0.0, 0.004], "values": [30000.0, 34000.0]}
    base = {"parameters": {"fidelity": 0}, "inputs": {"Fx": ramp}, "stop_time": 0.004, "step": 0.001}
    sweep = {
        "scenario": base,
        "grid": {"speed": SPEED, "Fy": [5000.0, 1.0e6], "slices": [10, 20]},
        "outputs": ["frictionTorque", "powerLoss", "loadedRollers"],
        "statistics": {"window": [0.001, 0.003], "outputs": ["frictionTorque", "Qo.max"], "functions": ["mean", "max", "min", "rms"]},
    }
    counter = Counter(tmp_path, trb_program)
    out = tmp_path / "results.parquet"
    proc = sweep_cli(write_json(tmp_path / "sweep.json", sweep), "--out", out, "--workers", "2", "--trb", counter.path)
    assert "Dask scheduler" in proc.stdout and "with 2 workers" in proc.stdout, proc.stdout
    assert len(counter.starts()) == 8
    table = pq.read_table(out)
    rows = table.to_pylist()
    assert [r["case"] for r in rows] == list(range(8))
    assert table.column_names[:5] == ["case", "id", "speed", "Fy", "slices"]
    assert str(table.schema.field("slices").type) == "int64"
    assert not out.with_name(out.name + ".parts").exists(), "the parts are removed once combined"

    for r in rows:
        # The same case by hand: the base scenario with the case's values, run alone.
        scenario = json.loads(json.dumps(base))
        scenario["inputs"].update(speed=r["speed"], Fy=r["Fy"])
        scenario["parameters"]["slices"] = r["slices"]
        scenario["outputs"] = ["frictionTorque", "powerLoss", "loadedRollers", "Qo.max"]
        csv_path = tmp_path / f"single_{r['case']}.csv"
        single = run_cli("simulate", write_json(tmp_path / f"single_{r['case']}.json", scenario), "--out", csv_path, "--quiet", check=False)
        assert r["wall_time"] > 0 and r["worker"], r
        if r["Fy"] == 1.0e6:
            # Fy = 1 MN does not seat the bearing at Fx = 30 kN: refused, recorded, no values.
            assert single.returncode == 1
            assert r["status"] == "refused", r
            assert "no quasi-static equilibrium" in r["message"] and r["message"] in single.stderr
            assert r["frictionTorque"] is None and r["frictionTorque:mean"] is None
            continue
        assert single.returncode == 0 and r["status"] == "ok" and r["message"] is None, (single.stderr, r)
        header, data = read_csv(csv_path)
        col = {n: i for i, n in enumerate(header)}
        for name in ["frictionTorque", "powerLoss", "loadedRollers"]:
            assert r[name] == data[-1][col[name]], (name, r)  # bitwise: == on floats
        window = [row for row in data if 0.001 <= row[0] <= 0.003]
        assert len(window) == 3
        for name in ["frictionTorque", "Qo.max"]:
            xs = [row[col[name]] for row in window]
            assert r[f"{name}:mean"] == statistics.fmean(xs)
            assert r[f"{name}:max"] == max(xs) and r[f"{name}:min"] == min(xs)
            assert r[f"{name}:rms"] == math.sqrt(math.fsum(x * x for x in xs) / 3)
        assert r["frictionTorque:min"] < r["frictionTorque:max"], "the window holds distinct values"

    # Rerun with one more Fy value: only its 4 cases run; the others are reused as they were.
    before = rows_by_id(out)
    counter.reset()
    sweep["grid"]["Fy"].append(10000.0)
    proc = sweep_cli(write_json(tmp_path / "sweep.json", sweep), "--out", out, "--workers", "2", "--trb", counter.path)
    assert len(counter.starts()) == 4, proc.stdout
    assert "12 cases: 8 already in the results, 4 to run" in proc.stdout
    after = rows_by_id(out)
    assert len(after) == 12
    for cid, row in before.items():
        row.pop("case")  # the case numbers follow the new grid
        assert {k: after[cid][k] for k in row} == row, "a reused case is the row written before (same wall time: not recomputed)"
    # The same sweep again runs nothing.
    counter.reset()
    proc = sweep_cli(tmp_path / "sweep.json", "--out", out, "--workers", "2", "--trb", counter.path)
    assert counter.starts() == [] and "12 already in the results, 0 to run" in proc.stdout


def test_cases_in_error_are_not_final_and_a_rerun_retries_them(tmp_path, trb_program):
    """A program that crashes (here: a stand-in exiting with 99) gives status `error` and
    exit code 1; a rerun with a working program runs those cases again."""
    broken = tmp_path / "trb-broken"
    broken.write_text(f'#!/bin/sh\n[ "$1" = simulate ] && {{ echo "boom" >&2; exit 99; }}\nexec "{trb_program}" "$@"\n')
    broken.chmod(0o755)
    sweep = write_json(tmp_path / "s.json", {**BASE, "cases": [{"Fy": 0.0}, {"Fy": 1000.0}], "outputs": ["frictionTorque"]})
    out = tmp_path / "r.parquet"
    proc = sweep_cli(sweep, "--out", out, "--workers", "1", "--trb", broken, check=False)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    rows = pq.read_table(out).to_pylist()
    assert [r["status"] for r in rows] == ["error", "error"]
    assert "exit code 99" in rows[0]["message"] and "boom" in rows[0]["message"]
    counter = Counter(tmp_path, trb_program)
    proc = sweep_cli(sweep, "--out", out, "--workers", "1", "--trb", counter.path)
    assert len(counter.starts()) == 2 and "0 already in the results, 2 to run" in proc.stdout
    assert [r["status"] for r in pq.read_table(out).to_pylist()] == ["ok", "ok"]


def test_scenario_file_and_bearing_file_travel_with_the_task(tmp_path, trb_program):
    """A base scenario given as a file (relative to the sweep file) and a bearing file: the
    task holds the bearing's text (a worker needs no access to it), and the text is part of
    the case's identity."""
    from trb import spec
    from trb.runner import run_case

    bearing = tmp_path / "b" / "apex.json"
    bearing.parent.mkdir()
    bearing.write_text((REPO / "tests" / "fixtures" / "TRB130x230-apex.json").read_text())
    scen = write_json(tmp_path / "base.json", {"parameters": {"fidelity": 0}, "inputs": {"Fx": 30000.0}, "stop_time": 0.001, "step": 0.001})
    path = write_json(tmp_path / "s.json", {"bearing": "b/apex.json", "scenario": "base.json", "grid": {"speed": SPEED}, "outputs": ["frictionTorque"]})
    s = spec.load(path, trb_program)
    task = s.cases[0].task
    assert task["scenario"]["bearing"] == "bearing.json" and task["bearing_text"] == bearing.read_text()
    assert task["scenario"]["inputs"] == {"Fx": 30000.0, "speed": SPEED[0]}
    r = run_case(task, str(trb_program))
    assert r["status"] == "ok", r
    # The same case run alone on the file gives the same bits.
    alone = json.loads(json.dumps(task["scenario"]))
    alone["bearing"] = str(bearing)
    run_cli("simulate", write_json(tmp_path / "alone.json", alone), "--out", tmp_path / "alone.csv", "--quiet")
    header, data = read_csv(tmp_path / "alone.csv")
    assert r["values"]["frictionTorque"] == data[-1][header.index("frictionTorque")]
    # Another bearing text (one more space): another id; the same text: the same id.
    assert spec.load(path, trb_program).cases[0].id == s.cases[0].id
    bearing.write_text(bearing.read_text() + " ")
    assert spec.load(path, trb_program).cases[0].id != s.cases[0].id


# ---------------------------------------------------------------------------------------
# Resume after the client is killed; a killed worker loses nothing
# ---------------------------------------------------------------------------------------


def test_rerun_after_a_killed_sweep_runs_only_the_unfinished_cases(tmp_path, trb_program):
    sweep = write_json(tmp_path / "sweep.json", slow_sweep(10))  # 20 cases
    out = tmp_path / "results.parquet"
    counter = Counter(tmp_path, trb_program, delay=0.3)  # 20 cases on 2 workers: at least 3 s
    cmd = [str(TRB_SWEEP), str(sweep), "--out", str(out), "--workers", "2", "--trb", str(counter.path), "--no-progress"]
    (tmp_path / "tmp").mkdir()  # the killed client's last cases leave their directories here
    env = dict(os.environ, TMPDIR=str(tmp_path / "tmp"))
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        wait_for(lambda: part_ids(out), 60, "finished cases in the parts")
        proc.send_signal(signal.SIGKILL)  # the client and its in-process cluster, nothing flushed
    finally:
        proc.wait(timeout=30)
    assert proc.returncode == -signal.SIGKILL
    assert not out.exists(), "killed before the end: no results file yet"
    saved = part_ids(out)
    assert 1 <= len(saved) < 20, f"the kill came mid-sweep ({len(saved)} of 20 saved)"
    time.sleep(0.5)  # let the killed sweep's last trb processes end before counting anew

    counter.reset()
    done = sweep_cli(sweep, "--out", out, "--workers", "2", "--trb", counter.path)
    assert len(counter.starts()) == 20 - len(saved), done.stdout
    assert f"{len(saved)} already in the results, {20 - len(saved)} to run" in done.stdout
    rows = rows_by_id(out)
    assert len(rows) == 20 and all(r["status"] == "ok" for r in rows.values())
    assert saved <= set(rows)


@pytest.fixture
def process_cluster(tmp_path, monkeypatch):
    """A LocalCluster of 2 worker processes (1 thread each) on localhost, closed after the
    test. The workers' temporary directories are under tmp_path (a killed worker leaves its
    case's directory behind)."""
    from distributed import Client, LocalCluster

    import dask

    (tmp_path / "tmp").mkdir()
    monkeypatch.setenv("TMPDIR", str(tmp_path / "tmp"))
    with dask.config.set({"temporary-directory": str(tmp_path / "tmp")}):  # Dask's scratch space too
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None, host="127.0.0.1")
        client = Client(cluster)
        try:
            yield cluster, client
        finally:
            client.close()
            cluster.close()


def test_killed_worker_loses_no_finished_case(tmp_path, trb_program, process_cluster):
    cluster, client = process_cluster
    pids = client.run(os.getpid)  # worker address: pid
    sweep = write_json(tmp_path / "sweep.json", slow_sweep(10))  # 20 cases
    out = tmp_path / "results.parquet"
    counter = Counter(tmp_path, trb_program, delay=0.3)  # every case runs at least 0.3 s
    cmd = [str(TRB_SWEEP), str(sweep), "--out", str(out), "--scheduler", cluster.scheduler_address, "--trb", str(counter.path), "--no-progress"]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        wait_for(lambda: part_ids(out), 60, "finished cases in the parts")
        # A worker process in the middle of a case.
        busy = wait_for(lambda: [r for r in counter.running() if r[1] in pids.values()], 30, "a worker running a case")
        victim_case, victim_pid, _ = busy[-1]  # the latest start: the most time left
        os.kill(victim_pid, signal.SIGKILL)
        written = rows_by_id_parts(out)  # all finished before the kill, and maybe a few after
        stdout, stderr = proc.communicate(timeout=90)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 0, stdout + stderr
    assert len(written) < 20, "the worker was killed mid-sweep"
    rows = rows_by_id(out)
    assert len(rows) == 20 and all(r["status"] == "ok" for r in rows.values()), stdout + stderr
    # Every case written before the kill is in the results as written (not recomputed).
    for cid, row in written.items():
        assert {k: rows[cid][k] for k in row} == row
    # The case the killed worker was running ran again on a live worker.
    starts = counter.starts()
    assert [s for s in starts if s[0] == victim_case and s[1] != victim_pid], "the interrupted case was retried"
    assert len({s[0] for s in starts}) == 20
    assert len(starts) <= 20 + 2, f"{len(starts)} runs for 20 cases: finished cases were recomputed"


def rows_by_id_parts(out: Path) -> dict[str, dict]:
    parts = out.with_name(out.name + ".parts")
    rows = {}
    for f in parts.glob("part-*.parquet"):
        rows.update({r["id"]: r for r in pq.read_table(f).to_pylist()})
    return rows


# ---------------------------------------------------------------------------------------
# Duty cycle over a spectrum
# ---------------------------------------------------------------------------------------


def test_spectrum_aggregates_by_miner_and_time_weighted_mean(tmp_path, trb_program, model):
    from trb.aggregate import miner_life, time_weighted_mean

    bins = [
        {"share": 30, "values": {"speed": SPEED[0], "Fy": 20000.0}},
        {"share": 50, "values": {"speed": SPEED[1], "Fy": 5000.0}},
        {"share": 20, "values": {"speed": SPEED[1], "Fy": 0.0}},
    ]
    base = {"parameters": {"fidelity": 0}, "inputs": {"Fx": 30000.0}, "stop_time": 0.001, "step": 0.001}
    has_life = "life.L10r" in model.vars
    # The life column: life.L10r when the FMU has it; else a positive output stands in for
    # it (the mechanics of the aggregation are the same).
    life_col = "life.L10r" if has_life else "Qo.max"
    sweep = {"scenario": base, "spectrum": {"bins": bins}, "outputs": ["frictionTorque"], "aggregation": {"life": life_col}}
    out = tmp_path / "duty.parquet"
    proc = sweep_cli(write_json(tmp_path / "duty.json", sweep), "--out", out, "--workers", "1")
    rows = pq.read_table(out).to_pylist()
    assert [r["time_share"] for r in rows] == [0.3, 0.5, 0.2]
    agg = json.loads((tmp_path / "duty.aggregate.json").read_text())
    lives = [r[life_col] for r in rows]
    assert agg["life"]["value"] == miner_life([0.3, 0.5, 0.2], lives) and agg["life"]["column"] == life_col
    assert agg["power"]["value"] == time_weighted_mean([0.3, 0.5, 0.2], [r["powerLoss"] for r in rows])
    assert agg["power"]["unit"] == "W"
    assert json.loads(pq.read_schema(out).metadata[b"trb.aggregation"]) == agg
    assert "duty cycle life" in proc.stdout

    # The default life column is life.L10r: without it in the FMU, a clear error.
    del sweep["aggregation"]
    proc = sweep_cli(write_json(tmp_path / "duty2.json", sweep), "--out", tmp_path / "duty2.parquet", "--workers", "1", check=has_life)
    if not has_life:
        assert proc.returncode == 2
        assert "field `aggregation.life`: `life.L10r` is not an output of the FMU" in proc.stderr, proc.stderr


# ---------------------------------------------------------------------------------------
# Maps
# ---------------------------------------------------------------------------------------


def test_grid_sweep_draws_its_maps(tmp_path, trb_program):
    sweep = {
        "scenario": {"parameters": {"fidelity": 0}, "inputs": {"Fx": 30000.0}, "stop_time": 0.001, "step": 0.001},
        "grid": {"speed": SPEED, "Fy": [0.0, 10000.0, 1.0e6], "mu": [0.1]},
        "outputs": ["frictionTorque"],
        "plots": [
            {"x": "speed", "y": "Fy", "z": "frictionTorque", "file": "torque.svg", "title": "torque map"},
            {"x": "Fy", "y": "speed", "z": "powerLoss", "file": "power.png"},
        ],
    }
    sweep["outputs"].append("powerLoss")
    out = tmp_path / "maps" / "r.parquet"
    proc = sweep_cli(write_json(tmp_path / "s.json", sweep), "--out", out, "--workers", "2")
    assert "map: " in proc.stdout
    svg = (tmp_path / "maps" / "torque.svg").read_text()
    assert svg.lstrip().startswith("<?xml") and "<svg" in svg and "torque map" in svg
    assert "frictionTorque [N.m]" in svg and "speed [rad/s]" in svg, "axes and colour bar carry the FMU's units"
    assert (tmp_path / "maps" / "power.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    statuses = [r["status"] for r in pq.read_table(out).to_pylist()]
    assert statuses.count("refused") == 2 and statuses.count("ok") == 4


# ---------------------------------------------------------------------------------------
# Bad sweep files
# ---------------------------------------------------------------------------------------


BAD = [
        ({**BASE, "grid": {"Fy": 5000.0}}, "grid.Fy", "non-empty list"),
        ({**BASE, "grid": {"Fy": [1.0, "2 kN"]}}, "grid.Fy[1]", "finite number"),
        ({**BASE, "grid": {"Fyy": [1.0]}}, "grid.Fyy", "did you mean `Fy`"),
        ({**BASE, "grid": {"frictionTorque": [1.0]}}, "grid.frictionTorque", "is an FMU output"),
        ({**BASE, "grid": {"mu": [0.1, 5.0]}}, "grid.mu[1]", "outside its range"),
        ({**BASE, "grid": {"slices": [10.5]}}, "grid.slices[0]", "integral"),
        ({**BASE, "grdi": {"Fy": [1.0]}}, "grdi", "unknown key"),
        ({**BASE, "grid": {"Fy": [1.0]}, "cases": [{"Fy": 1.0}]}, "cases", "exactly one of"),
        ({**BASE, "cases": [{"Fy": 1.0}, {"speed": True}]}, "cases[1].speed", "finite number"),
        ({**BASE, "spectrum": {"bins": [{"share": -1, "values": {}}]}}, "spectrum.bins[0].share", ">= 0"),
        ({**BASE, "grid": {"Fy": [1.0]}, "statistics": {"outputs": ["frictionTorque"], "window": [0.5, 0.6]}}, "statistics.window", "no communication point"),
        ({**BASE, "grid": {"Fy": [1.0]}, "outputs": ["torque"]}, "outputs[0]", "not an FMU output"),
        ({"scenario": {"stop_time": 0.001, "step": 0.001, "inputz": {}}, "grid": {"Fy": [1.0]}}, "scenario.inputz", "unknown key"),
        ({**BASE, "grid": {"Fy": [1.0]}, "bearing": "no-such-bearing.json"}, "bearing", "cannot read bearing file"),
        (
            {"scenario": {"stop_time": 0.001, "step": 0.001, "inputs": {"Fx": {"time": [0.0, 0.0], "values": [1.0, 2.0]}}}, "grid": {"Fy": [1.0]}},
            "scenario",
            "refuses the scenario of case 0: field `inputs.Fx.time`: must be strictly increasing",
        ),
        ({**BASE, "grid": {"Fy": [1.0, 2.0]}, "plots": [{"x": "Fy", "y": "speed", "z": "frictionTorque", "file": "m.svg"}]}, "plots[0].y", "not a grid variable"),
]


@pytest.mark.parametrize("sweep, field, text", BAD, ids=[field for _, field, _ in BAD])
def test_bad_sweep_file_names_the_field(tmp_path, trb_program, sweep, field, text):
    from trb.cli import main

    path = write_json(tmp_path / "bad.json", sweep)
    proc_err = _main_stderr(main, [str(path), "--out", str(tmp_path / "r.parquet"), "--trb", str(trb_program)])
    code, err = proc_err
    assert code == 2, err
    assert f"field `{field}`: " in err and text in err, err
    assert not (tmp_path / "r.parquet").exists()


def test_duplicate_keys_and_broken_json_are_refused(tmp_path, trb_program):
    from trb.cli import main

    path = tmp_path / "dup.json"
    path.write_text('{"scenario": {"stop_time": 0.001, "step": 0.001}, "grid": {"Fy": [1.0], "Fy": [2.0]}}')
    code, err = _main_stderr(main, [str(path), "--out", str(tmp_path / "r.parquet"), "--trb", str(trb_program)])
    assert code == 2 and "key `Fy` appears twice" in err, err
    path.write_text('{"scenario": {"stop_time": 0.001, "step": 0.001}, "grid": {"Fy": [1.0,]}}')
    code, err = _main_stderr(main, [str(path), "--out", str(tmp_path / "r.parquet"), "--trb", str(trb_program)])
    assert code == 2 and "is not valid JSON: " in err and "line 1" in err, err


def _main_stderr(main, argv) -> tuple[int, str]:
    import contextlib
    import io

    buf = io.StringIO()
    with contextlib.redirect_stderr(buf), contextlib.redirect_stdout(io.StringIO()):
        code = main(argv)
    return code, buf.getvalue()


def test_bad_sweep_file_from_the_console_script_exits_2_without_traceback(tmp_path, trb_program):
    path = write_json(tmp_path / "bad.json", {**BASE, "grid": {"Fy": "lots"}})
    proc = sweep_cli(path, "--out", tmp_path / "r.parquet", "--trb", trb_program, check=False)
    assert proc.returncode == 2
    assert proc.stderr.strip() == 'trb-sweep: error: field `grid.Fy`: must be a non-empty list of values, got "lots"'
    assert "Traceback" not in proc.stderr + proc.stdout
    proc = sweep_cli(tmp_path / "missing.json", "--out", tmp_path / "r.parquet", "--trb", trb_program, check=False)
    assert proc.returncode == 2 and "cannot read sweep file" in proc.stderr and "Traceback" not in proc.stderr
    proc = sweep_cli(path, "--out", tmp_path / "r.csv", check=False)
    assert proc.returncode == 2 and "option `--out`: must name a .parquet file" in proc.stderr
    proc = sweep_cli(path, "--out", tmp_path / "r.parquet", "--workers", "0", check=False)
    assert proc.returncode == 2 and "option `--workers`: must be at least 1" in proc.stderr


# ---------------------------------------------------------------------------------------
# The shipped examples
# ---------------------------------------------------------------------------------------


def test_shipped_sweeps_are_valid(trb_program, model):
    from trb import spec
    from trb.errors import SweepError

    files = sorted((REPO / "sweeps").glob("*.json"))
    assert len(files) >= 3
    modes = {}
    for f in files:
        try:
            s = spec.load(f, trb_program)
        except SweepError as e:
            # The duty cycle needs life.L10r, which the FMU may not have yet.
            assert "life.L10r" not in model.vars and e.field == "aggregation.life", f"{f.name}: {e}"
            modes[f.name] = "spectrum"
            continue
        modes[f.name] = s.mode
        fidelity = s.cases[0].task["scenario"]["parameters"].get("fidelity", 0)
        if fidelity == 1:
            assert len(s.cases) >= 8, f.name
            sc = s.cases[0].task["scenario"]
            assert sc["stop_time"] - sc.get("start_time", 0.0) <= 0.02, "dynamic example cases stay short"
    assert {"grid", "spectrum"} <= set(modes.values())


def test_dry_run_counts_the_cases_and_runs_nothing(tmp_path, trb_program):
    from trb.cli import main

    import contextlib
    import io

    buf = io.StringIO()
    out = tmp_path / "r.parquet"
    with contextlib.redirect_stdout(buf):
        code = main([str(REPO / "sweeps" / "qs_torque_map.json"), "--out", str(out), "--dry-run", "--trb", str(trb_program)])
    assert code == 0 and "dry run: 36 of 36 distinct cases would run" in buf.getvalue()
    assert not out.exists() and not (tmp_path / "r.parquet.parts").exists()
