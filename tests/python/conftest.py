"""Shared fixtures and helpers of the Python test harness of the TaperedRollerBearing FMU.

- The FMU under test is `target/fmu/TaperedRollerBearing.fmu`, packaged by
  `cargo run --release -- fmu`; the session fixture `fmu_path` builds it when it is missing
  or older than the sources.
- `package_preset(name)` packages another preset (`--bearing NAME --out TMP`) once per session.
- `run_cli(...)` runs the standalone program (the `trb` binary that `cargo build --release`
  made at the start of the session); `cargo_run(...)` is literally `cargo run --release -- ...`.
- `read_csv(path)` reads a `simulate` CSV exactly (Python's float() is correctly rounded, the
  program prints shortest round-trip text, so the values are the program's bits).
- `LogHub`: one fmi2 logger callback that lives for the whole session. fmpy formats FMU
  messages in a small C proxy (vsnprintf) that keeps *one global* pointer to the Python
  logger; whoever called `addLoggerProxy` last owns it. The hub re-installs itself after
  anything else (e.g. `simulate_fmu(logger=...)`) took it over, so no FMU ever calls a
  freed ctypes thunk.
- `Slaves`: create fmpy `FMU2Slave` instances that are freed at the end of the test.
"""

from __future__ import annotations

import csv
import ctypes
import json
import math
import os
import re
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
    fmi2Integer,
    fmi2Real,
    fmi2ValueReference,
)

REPO = Path(__file__).resolve().parents[2]
FMU_PATH = REPO / "target" / "fmu" / "TaperedRollerBearing.fmu"
MODEL_IDENTIFIER = "TaperedRollerBearing"
PRESETS = ["TRB130x230", "32018X", "32008", "CRB-TRILOBE"]
DEFAULT_PRESET = "TRB130x230"
SCENARIOS = REPO / "scenarios"

# Sources whose change makes a packaged FMU stale.
_SOURCES = ["src", "presets", "modelDescription", "scenarios", "build.rs", "Cargo.toml", "Cargo.lock"]

FMI2_OK, FMI2_WARNING, FMI2_DISCARD, FMI2_ERROR, FMI2_FATAL = 0, 1, 2, 3, 4


# ---------------------------------------------------------------------------------------
# The standalone program
# ---------------------------------------------------------------------------------------


def cargo_env() -> dict:
    """The environment for cargo: the default target/ (the FMU path contract)."""
    env = dict(os.environ)
    env.pop("CARGO_TARGET_DIR", None)
    return env


TRB = REPO / "target" / "release" / "trb"
_BUILT = False


def cargo(*args, timeout: float = 1800) -> subprocess.CompletedProcess:
    """Run cargo in the repository root; fails the test with its output if cargo fails."""
    cmd = ["cargo", *map(str, args)]
    proc = subprocess.run(cmd, cwd=REPO, env=cargo_env(), capture_output=True, text=True, timeout=timeout)
    if proc.returncode != 0:
        raise AssertionError(f"{' '.join(cmd)} exited with {proc.returncode}\n--- stdout\n{proc.stdout}\n--- stderr\n{proc.stderr}")
    return proc


def ensure_built():
    """`cargo build --release` once per session (a no-op when up to date): the program and
    the FMU's shared library then come from the same build for the whole session."""
    global _BUILT
    if not _BUILT:
        cargo("build", "--release", "--quiet")
        assert TRB.is_file(), f"cargo build --release did not produce {TRB}"
        _BUILT = True


def run_cli(*args, check: bool = True, timeout: float = 600) -> subprocess.CompletedProcess:
    """The standalone program (`cargo run --release -- ARGS`, run here as the binary cargo
    built, target/release/trb, to avoid cargo's overhead per call), output captured."""
    ensure_built()
    cmd = [str(TRB), *map(str, args)]
    proc = subprocess.run(cmd, cwd=REPO, env=cargo_env(), capture_output=True, text=True, timeout=timeout)
    if check and proc.returncode != 0:
        raise AssertionError(
            f"trb {' '.join(map(str, args))} exited with {proc.returncode}\n--- stdout\n{proc.stdout}\n--- stderr\n{proc.stderr}"
        )
    return proc


def cargo_run(*args, timeout: float = 1800) -> subprocess.CompletedProcess:
    """Literally `cargo run --release --quiet -- ARGS` (exit code not checked)."""
    cmd = ["cargo", "run", "--release", "--quiet", "--", *map(str, args)]
    return subprocess.run(cmd, cwd=REPO, env=cargo_env(), capture_output=True, text=True, timeout=timeout)


def _newest_source_mtime() -> float:
    newest = 0.0
    for name in _SOURCES:
        p = REPO / name
        if p.is_file():
            newest = max(newest, p.stat().st_mtime)
        elif p.is_dir():
            for f in p.rglob("*"):
                if f.is_file():
                    newest = max(newest, f.stat().st_mtime)
    return newest


def read_csv(path) -> tuple[list[str], list[list[float]]]:
    """Header and rows of a `simulate` CSV; every cell parsed with float() (exact)."""
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = [[float(x) for x in row] for row in reader if row]
    for i, row in enumerate(rows):
        assert len(row) == len(header), f"{path}: row {i + 1} has {len(row)} cells, header {len(header)}"
    return header, rows


def write_json(path: Path, data) -> Path:
    path.write_text(json.dumps(data, indent=2))
    return path


# ---------------------------------------------------------------------------------------
# Logging
# ---------------------------------------------------------------------------------------


@dataclass
class LogRecord:
    instance: str
    status: int
    category: str
    message: str


class LogHub:
    """The session's fmi2 logger (see the module docstring)."""

    def __init__(self):
        from fmpy import calloc, free

        self.records: list[LogRecord] = []
        self.echo = False
        # Every ctypes object a C caller may still hold stays referenced by the hub.
        self._thunk = fmi2CallbackLoggerTYPE(self._log)
        self._alloc = fmi2CallbackAllocateMemoryTYPE(calloc)
        self._free = fmi2CallbackFreeMemoryTYPE(free)
        self._all_callbacks: list[fmi2CallbackFunctions] = []
        self.callbacks = self.install()

    def _log(self, env, instance, status, category, message):
        rec = LogRecord(
            instance=(instance or b"").decode("utf-8", "replace"),
            status=int(status),
            category=(category or b"").decode("utf-8", "replace"),
            message=(message or b"").decode("utf-8", "replace"),
        )
        self.records.append(rec)
        if self.echo:
            print(f"[{rec.instance}] {rec.status} {rec.category}: {rec.message}")

    def install(self) -> fmi2CallbackFunctions:
        """(Re)make fmpy's formatting proxy call this hub; returns the callbacks to pass to
        fmi2Instantiate (their logger is fmpy's proxy, which calls the hub)."""
        from fmpy.logging import addLoggerProxy

        cb = fmi2CallbackFunctions()
        cb.logger = self._thunk
        cb.allocateMemory = self._alloc
        cb.freeMemory = self._free
        addLoggerProxy(ctypes.byref(cb))
        self._all_callbacks.append(cb)
        self.callbacks = cb
        return cb

    def mark(self) -> int:
        return len(self.records)

    def since(self, mark: int) -> list[LogRecord]:
        return self.records[mark:]


_HUB: LogHub | None = None


def log_hub() -> LogHub:
    global _HUB
    if _HUB is None:
        _HUB = LogHub()
    return _HUB


@pytest.fixture(scope="session")
def hub() -> LogHub:
    return log_hub()


# ---------------------------------------------------------------------------------------
# The FMU
# ---------------------------------------------------------------------------------------


@pytest.fixture(scope="session")
def fmu_path() -> Path:
    """The default FMU, packaged if missing or older than the sources or the build."""
    ensure_built()
    newest = max(_newest_source_mtime(), TRB.stat().st_mtime)
    if not FMU_PATH.is_file() or FMU_PATH.stat().st_mtime < newest:
        run_cli("fmu")
    assert FMU_PATH.is_file(), f"`cargo run --release -- fmu` did not write {FMU_PATH}"
    return FMU_PATH


@pytest.fixture(scope="session")
def package_preset(fmu_path, tmp_path_factory):
    """Factory: path of the FMU of a preset (or bearing file), packaged once per session."""
    cache: dict[str, Path] = {DEFAULT_PRESET: fmu_path}
    root = tmp_path_factory.mktemp("presets")

    def package(name: str) -> Path:
        if name not in cache:
            out = root / f"{Path(name).stem}.fmu"
            run_cli("fmu", "--bearing", name, "--out", out)
            assert out.is_file(), f"`fmu --bearing {name} --out {out}` wrote nothing"
            cache[name] = out
        return cache[name]

    return package


class Model:
    """An extracted FMU: model description, variables by name, value references."""

    def __init__(self, path: Path, unzipdir: str):
        self.path = path
        self.unzipdir = unzipdir
        self.md = read_model_description(str(path))
        self.vars = {v.name: v for v in self.md.modelVariables}

    def vr(self, name: str) -> int:
        return self.vars[name].valueReference

    def names(self, causality: str) -> list[str]:
        return [v.name for v in self.md.modelVariables if v.causality == causality]

    def start(self, name: str):
        v = self.vars[name]
        if v.type == "Real":
            return float(v.start)
        if v.type in ("Integer", "Enumeration"):
            return int(v.start)
        if v.type == "Boolean":
            return v.start in ("true", "1", True)
        raise TypeError(v.type)

    @property
    def z(self) -> int:
        return sum(1 for n in self.vars if n.startswith("roller[") and n.endswith("].tilt"))


_MODELS: dict[Path, Model] = {}


def load_model(path: Path, tmp_root: Path) -> Model:
    path = Path(path)
    if path not in _MODELS:
        d = tmp_root / f"unzip_{len(_MODELS)}_{path.stem}"
        _MODELS[path] = Model(path, extract(str(path), unzipdir=str(d)))
    return _MODELS[path]


@pytest.fixture(scope="session")
def models(tmp_path_factory, package_preset):
    """Factory: the extracted `Model` of a preset (default: the default FMU)."""
    root = tmp_path_factory.mktemp("models")

    def get(name: str = DEFAULT_PRESET) -> Model:
        return load_model(package_preset(name), root)

    return get


@pytest.fixture(scope="session")
def model(models) -> Model:
    return models(DEFAULT_PRESET)


# ---------------------------------------------------------------------------------------
# FMU2Slave instances
# ---------------------------------------------------------------------------------------


class Slaves:
    """Creates instances (fmpy FMU2Slave, logging to the hub) and frees them at teardown."""

    def __init__(self, hub: LogHub):
        self.hub = hub
        self.live: list[FMU2Slave] = []

    def new(self, model: Model, name: str = "trb", logging_on: bool = False, instantiate: bool = True) -> FMU2Slave:
        fmu = FMU2Slave(
            guid=model.md.guid,
            unzipDirectory=model.unzipdir,
            modelIdentifier=model.md.coSimulation.modelIdentifier,
            instanceName=name,
        )
        fmu.model = model  # for the helpers below
        if instantiate:
            try:
                fmu.instantiate(callbacks=self.hub.callbacks, loggingOn=logging_on)
            except Exception:
                fmu.freeLibrary()
                raise
        self.live.append(fmu)
        return fmu

    def free(self, fmu: FMU2Slave):
        if fmu in self.live:
            self.live.remove(fmu)
            if fmu.component:
                fmu.freeInstance()
            else:
                fmu.freeLibrary()

    def close(self):
        for fmu in list(self.live):
            self.free(fmu)


@pytest.fixture
def slaves(hub):
    s = Slaves(hub)
    yield s
    s.close()


def set_values(fmu: FMU2Slave, values: dict):
    """Set variables by name with the setter of their type."""
    model: Model = fmu.model
    for name, value in values.items():
        v = model.vars[name]
        if v.type == "Real":
            fmu.setReal([v.valueReference], [float(value)])
        elif v.type in ("Integer", "Enumeration"):
            fmu.setInteger([v.valueReference], [int(value)])
        elif v.type == "Boolean":
            fmu.setBoolean([v.valueReference], [bool(value)])
        else:
            raise TypeError(f"{name}: {v.type}")


def get_values(fmu: FMU2Slave, names: list[str]) -> dict:
    """Get variables by name (Real and Integer)."""
    model: Model = fmu.model
    reals = [n for n in names if model.vars[n].type == "Real"]
    ints = [n for n in names if model.vars[n].type in ("Integer", "Enumeration")]
    out = {}
    if reals:
        out.update(zip(reals, fmu.getReal([model.vr(n) for n in reals])))
    if ints:
        out.update(zip(ints, fmu.getInteger([model.vr(n) for n in ints])))
    return {n: out[n] for n in names}


def get_real_raw(fmu: FMU2Slave, vrs: list[int]) -> tuple[int, list[float]]:
    """fmi2GetReal returning (status, values) instead of raising, so the values the FMU wrote
    with a non-OK status can be inspected."""
    vr = (fmi2ValueReference * len(vrs))(*vrs)
    value = (fmi2Real * len(vrs))(*([math.pi] * len(vrs)))
    try:
        status = fmu.fmi2GetReal(fmu.component, vr, len(vrs), value)
    except FMICallException as e:
        status = e.status
    return status, list(value)


def get_integer_raw(fmu: FMU2Slave, vrs: list[int]) -> tuple[int, list[int]]:
    vr = (fmi2ValueReference * len(vrs))(*vrs)
    value = (fmi2Integer * len(vrs))(*([-12345] * len(vrs)))
    try:
        status = fmu.fmi2GetInteger(fmu.component, vr, len(vrs), value)
    except FMICallException as e:
        status = e.status
    return status, list(value)


def call_status(f, *args) -> int:
    """Status of an fmpy call: 0/1 if it returned, the FMICallException's status if it raised."""
    try:
        r = f(*args)
    except FMICallException as e:
        return e.status
    return r if isinstance(r, int) else FMI2_OK


def initialize(fmu: FMU2Slave, params: dict | None = None, inputs: dict | None = None, start: float = 0.0, stop=None):
    """setupExperiment, parameters, inputs, enter/exit initialization mode."""
    fmu.setupExperiment(startTime=start, stopTime=stop)
    set_values(fmu, params or {})
    set_values(fmu, inputs or {})
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()


def all_outputs(model: Model) -> list[str]:
    return model.names("output")


def close_enough(a: float, b: float, rel: float = 1e-12, abs_: float = 1e-12) -> bool:
    return a == b or abs(a - b) <= max(rel * max(abs(a), abs(b)), abs_)


def pytest_report_header(config):
    return f"FMU under test: {FMU_PATH.relative_to(REPO)} (repo {REPO})"


# The FMU Compliance Checker (../shared/tools/fmuCheck.linux64); TRB_FMUCHECK names another copy.
FMUCHECK = Path(os.environ.get("TRB_FMUCHECK", REPO.parent / "shared" / "tools" / "fmuCheck.linux64"))


def fmu_check_passes(fmu: Path, workdir: Path, stop_time: float) -> str:
    """fmuCheck -k cs on `fmu`: the XML checks and a co-simulation to `stop_time` in 1 ms
    steps at log level 3 (warnings); asserts that the FMU and the checker both report zero
    warnings and errors and that it wrote its results; returns what it printed."""
    proc = subprocess.run(
        [str(FMUCHECK), "-k", "cs", "-h", "1e-3", "-s", str(stop_time), "-l", "3", "-o", str(workdir / "out.csv"), "-t", str(workdir), str(fmu)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, f"fmuCheck exited with {proc.returncode}:\n{out}"
    assert "FMU check summary" in out, out
    assert re.search(r"FMU reported:\s*0 warning\(s\) and error\(s\)", out), out
    assert re.search(r"Checker reported:\s*0 Warning\(s\)\s*0 Error\(s\)", out), out
    assert (workdir / "out.csv").stat().st_size > 0
    return out
