"""Sweep files: strict validation and resolution into cases (plain data).

A sweep file (JSON, format in `sweeps/README.md`) names a bearing and a base scenario (the
scenario format of `trb simulate`, `scenarios/README.md`), then the cases as a grid
(Cartesian product), a list, or a load spectrum (bins with time shares) over any FMU inputs
and parameters, the outputs to record (final values) and optional statistics over a time
window, the duty-cycle aggregation and the maps to plot.

`load(path, trb)` checks every key (unknown keys are refused, every error names its field),
checks variable names, types and ranges against the FMU that the `trb` program packages for
the bearing, has the program check the base scenario's values (one step of the first case),
and resolves every case into a task: a dict of plain data holding the complete
scenario that `trb simulate` runs, the bearing file's text if the bearing is a file, the
outputs and statistics to extract, and `id`, a stable hash of all of these (the identity of
a case for resuming).
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from .errors import SweepError
from .variables import VariableTable, package_table

FUNCTIONS = ("mean", "max", "min", "rms")
DEFAULT_FUNCTIONS = ["mean", "max", "rms"]
MODES = ("grid", "cases", "spectrum")
SWEEP_KEYS = {"description", "bearing", "scenario", "outputs", "statistics", "aggregation", "plots", *MODES}
SCENARIO_KEYS = {"description", "bearing", "parameters", "inputs", "start_time", "stop_time", "step", "outputs"}
STATISTICS_KEYS = {"outputs", "functions", "window"}
AGGREGATION_KEYS = {"life", "power"}
AGGREGATION_DEFAULTS = {"life": "life.L10r", "power": "powerLoss"}
PLOT_KEYS = {"x", "y", "z", "file", "title"}
BIN_KEYS = {"share", "values"}
PLOT_SUFFIXES = (".svg", ".png", ".pdf")
# Bumped when the meaning of a task changes (what is extracted, how): old results are not reused.
TASK_FORMAT = 1


@dataclass
class Case:
    """One case: its index, the values it sets (variable name: value), its task."""

    index: int
    values: dict
    task: dict
    time_share: float | None = None

    @property
    def id(self) -> str:
        return self.task["id"]


@dataclass
class Sweep:
    path: Path
    text: str
    mode: str
    bearing: str
    table: VariableTable
    swept: list[str]  # the swept variable names, in file order
    outputs: list[str]  # final values
    statistics: dict | None  # {"outputs", "functions", "window"}
    aggregation: dict | None  # {"life": column or None, "power": column or None}
    plots: list[dict]
    cases: list[Case] = field(default_factory=list)

    @property
    def value_columns(self) -> list[str]:
        return _value_columns(self.outputs, self.statistics)

    def unit(self, column: str) -> str | None:
        v = self.table.get(column.split(":")[0])
        return v.unit if v else None


def _value_columns(outputs: list[str], statistics: dict | None) -> list[str]:
    """The results columns of values: final outputs, then `output:function` statistics."""
    cols = list(outputs)
    if statistics:
        cols += [f"{o}:{f}" for o in statistics["outputs"] for f in statistics["functions"]]
    return cols


# ---------------------------------------------------------------------------------------
# Small checks
# ---------------------------------------------------------------------------------------


def _keys(obj, allowed: set, where: str, required: tuple = ()):
    if not isinstance(obj, dict):
        raise SweepError(where, f"must be an object, got {_kind(obj)}")
    for k in obj:
        if k not in allowed:
            name = f"{where}.{k}" if where else k
            raise SweepError(name, f"unknown key (allowed: {', '.join(sorted(allowed))})")
    for k in required:
        if k not in obj:
            name = f"{where}.{k}" if where else k
            raise SweepError(name, "missing (required)")


def _kind(v) -> str:
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "a boolean"
    if isinstance(v, (int, float)):
        return "a number"
    if isinstance(v, str):
        return "a string"
    if isinstance(v, list):
        return "a list"
    return "an object"


def _finite(v, where: str) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise SweepError(where, f"must be a finite number, got {json.dumps(v)}")
    return float(v)


def _string_list(v, where: str, allow_empty: bool = False) -> list[str]:
    if not isinstance(v, list) or (not v and not allow_empty):
        raise SweepError(where, f"must be a {'' if allow_empty else 'non-empty '}list of names, got {json.dumps(v)}")
    for i, s in enumerate(v):
        if not isinstance(s, str):
            raise SweepError(f"{where}[{i}]", f"must be a string, got {_kind(s)}")
    if len(set(v)) != len(v):
        dup = next(s for s in v if v.count(s) > 1)
        raise SweepError(where, f"`{dup}` is listed twice")
    return list(v)


def _is_file_ref(bearing: str) -> bool:
    return bearing.lower().endswith(".json") or "/" in bearing or "\\" in bearing


def _close_names(name: str, names: list[str]) -> str:
    import difflib

    near = difflib.get_close_matches(name, names, n=3, cutoff=0.6)
    return f" (did you mean {', '.join('`' + n + '`' for n in near)}?)" if near else ""


def _variable(table: VariableTable, name: str, where: str, causalities: tuple[str, ...]):
    v = table.get(name)
    if v is None:
        pool = [n for c in causalities for n in table.names(c)]
        raise SweepError(where, f"`{name}` is not an FMU {' or '.join(causalities)} of bearing {table.bearing}{_close_names(name, pool)}")
    if v.causality not in causalities:
        raise SweepError(where, f"`{name}` is an FMU {v.causality}, not {' or '.join(causalities)}")
    return v


def _typed(v, value, where: str):
    """A swept value checked against the variable's type and range (the FMU's min/max)."""
    if v.type == "Boolean":
        if not isinstance(value, bool):
            raise SweepError(where, f"`{v.name}` is a Boolean: must be true or false, got {json.dumps(value)}")
        return value
    x = _finite(value, where)
    if v.type in ("Integer", "Enumeration"):
        if x != math.floor(x):
            raise SweepError(where, f"`{v.name}` is an {v.type}: must be an integral number, got {json.dumps(value)}")
        x = int(x)
    if v.min is not None and x < v.min or v.max is not None and x > v.max:
        lo = "-inf" if v.min is None else f"{v.min:g}"
        hi = "inf" if v.max is None else f"{v.max:g}"
        raise SweepError(where, f"`{v.name}` = {json.dumps(value)} is outside its range [{lo}, {hi}]")
    return x


def _parse_json(text: str, path: Path, where: str):
    """JSON text; a duplicate key in an object is an error (json.loads would keep the last)."""

    def pairs(items):
        obj = {}
        for k, v in items:
            if k in obj:
                raise SweepError(where, f"{path}: key `{k}` appears twice in one object")
            obj[k] = v
        return obj

    try:
        return json.loads(text, object_pairs_hook=pairs)
    except json.JSONDecodeError as e:
        raise SweepError(where, f"{path} is not valid JSON: {e}") from None


# ---------------------------------------------------------------------------------------
# The base scenario
# ---------------------------------------------------------------------------------------


def _base_scenario(sweep: dict, base_dir: Path) -> tuple[dict, Path, str]:
    """The base scenario (a copy), the directory its relative bearing path is relative to,
    and its field name for errors."""
    if "scenario" not in sweep:
        raise SweepError("scenario", "missing (required): a scenario file name or an inline scenario object")
    s = sweep["scenario"]
    if isinstance(s, str):
        path = (base_dir / s).resolve()
        try:
            text = path.read_text()
        except OSError as e:
            raise SweepError("scenario", f"cannot read scenario file {path}: {e.strerror or e}") from None
        scen = _parse_json(text, path, "scenario")
        where, sdir = "scenario", path.parent
    else:
        scen, where, sdir = s, "scenario", base_dir
    _keys(scen, SCENARIO_KEYS, where, required=("stop_time", "step"))
    return copy.deepcopy(scen), sdir, where


def _time_grid(scen: dict, where: str) -> tuple[float, float, list[float]]:
    """start, stop and the communication times (the rule of scenarios/README.md)."""
    start = _finite(scen.get("start_time", 0.0), f"{where}.start_time")
    stop = _finite(scen["stop_time"], f"{where}.stop_time")
    step = _finite(scen["step"], f"{where}.step")
    if stop <= start:
        raise SweepError(f"{where}.stop_time", f"must be greater than start_time = {start!r}")
    if step <= 0:
        raise SweepError(f"{where}.step", "must be > 0")
    n = round((stop - start) / step)
    if n < 1 or n > 10_000_000:
        raise SweepError(f"{where}.step", f"{step!r} gives {n} steps over [{start!r}, {stop!r}]")
    return start, stop, [start + k * step for k in range(n)] + [stop]


# ---------------------------------------------------------------------------------------
# Loading
# ---------------------------------------------------------------------------------------


def load(path: Path, trb: Path) -> Sweep:
    """Read, validate and resolve a sweep file (see the module docstring)."""
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as e:
        raise SweepError("", f"cannot read sweep file {path}: {e.strerror or e}") from None
    raw = _parse_json(text, path, "")
    return resolve(raw, path.resolve().parent, trb, path=path, text=text)


def resolve(raw: dict, base_dir: Path, trb: Path, path: Path | None = None, text: str = "") -> Sweep:
    _keys(raw, SWEEP_KEYS, "")
    if "description" in raw and not isinstance(raw["description"], str):
        raise SweepError("description", f"must be a string, got {_kind(raw['description'])}")
    modes = [m for m in MODES if m in raw]
    if len(modes) != 1:
        raise SweepError(
            "grid" if not modes else modes[1],
            "a sweep has exactly one of `grid`, `cases`, `spectrum`" + (f"; this one has {', '.join(modes)}" if modes else ""),
        )
    mode = modes[0]

    scen, sdir, swhere = _base_scenario(raw, base_dir)

    # Bearing: the sweep's, else the scenario's, else the default preset.
    if "bearing" in raw:
        b, bdir, bwhere = raw["bearing"], base_dir, "bearing"
    else:
        b, bdir, bwhere = scen.get("bearing", "TRB130x230"), sdir, f"{swhere}.bearing"
    if not isinstance(b, str) or not b:
        raise SweepError(bwhere, f"must be a preset name or a bearing file, got {json.dumps(b)}")
    bearing_text = None
    if _is_file_ref(b):
        bpath = (bdir / b).resolve()
        try:
            bearing_text = bpath.read_text()
        except OSError as e:
            raise SweepError(bwhere, f"cannot read bearing file {bpath}: {e.strerror or e}") from None
        bearing_arg = str(bpath)
        scen["bearing"] = "bearing.json"  # the runner writes bearing_text there
    else:
        bearing_arg = b
        scen["bearing"] = b
    table = package_table(trb, bearing_arg, field=bwhere)

    # Names in the base scenario (values are checked by `trb simulate` itself).
    for section, causality in (("parameters", "parameter"), ("inputs", "input")):
        sec = scen.get(section, {})
        if not isinstance(sec, dict):
            raise SweepError(f"{swhere}.{section}", f"must be an object, got {_kind(sec)}")
        for name in sec:
            _variable(table, name, f"{swhere}.{section}.{name}", (causality,))
    start, stop, times = _time_grid(scen, swhere)
    scen.pop("description", None)  # free text: not part of a case's identity

    # Outputs (final values).
    if "outputs" in raw:
        outputs = _string_list(raw["outputs"], "outputs", allow_empty=True)
        owhere = "outputs"
    elif "outputs" in scen:
        outputs = _string_list(scen["outputs"], f"{swhere}.outputs", allow_empty=True)
        owhere = f"{swhere}.outputs"
    else:
        outputs = [n for n in table.names("output") if "[" not in n]
        owhere = "outputs"
    for i, name in enumerate(outputs):
        _variable(table, name, f"{owhere}[{i}]", ("output",))

    # Statistics over a window.
    statistics = None
    if "statistics" in raw:
        st = raw["statistics"]
        _keys(st, STATISTICS_KEYS, "statistics", required=("outputs",))
        souts = _string_list(st["outputs"], "statistics.outputs")
        for i, name in enumerate(souts):
            _variable(table, name, f"statistics.outputs[{i}]", ("output",))
        funcs = _string_list(st.get("functions", DEFAULT_FUNCTIONS), "statistics.functions")
        for i, f in enumerate(funcs):
            if f not in FUNCTIONS:
                raise SweepError(f"statistics.functions[{i}]", f"`{f}` is not one of {', '.join(FUNCTIONS)}")
        w = st.get("window", [start, stop])
        if not isinstance(w, list) or len(w) != 2:
            raise SweepError("statistics.window", f"must be [t0, t1] in s, got {json.dumps(w)}")
        t0, t1 = _finite(w[0], "statistics.window[0]"), _finite(w[1], "statistics.window[1]")
        if t1 < t0:
            raise SweepError("statistics.window", f"t1 = {t1!r} is before t0 = {t0!r}")
        inside = [t for t in times if t0 <= t <= t1]
        if not inside:
            raise SweepError(
                "statistics.window", f"[{t0!r}, {t1!r}] holds no communication point of the scenario ({start!r} .. {stop!r} s every {scen['step']!r} s)"
            )
        statistics = {"outputs": souts, "functions": funcs, "window": [t0, t1]}

    # The cases: lists of {name: value}.
    case_values, shares = _cases(raw, mode, table)
    swept: list[str] = []
    for values in case_values:
        for name in values:
            if name not in swept:
                swept.append(name)

    value_cols = _value_columns(outputs, statistics)

    # Aggregation (spectrum only).
    aggregation = None
    if "aggregation" in raw and mode != "spectrum":
        raise SweepError("aggregation", "applies to a `spectrum` only (duty-cycle life and mean power loss over its bins)")
    if mode == "spectrum":
        agg = raw.get("aggregation", {})
        _keys(agg, AGGREGATION_KEYS, "aggregation")
        aggregation = {}
        for key, default in AGGREGATION_DEFAULTS.items():
            col = agg.get(key, default)
            where = f"aggregation.{key}"
            if col is None:
                aggregation[key] = None
                continue
            if not isinstance(col, str):
                raise SweepError(where, f"must be a results column name or null, got {_kind(col)}")
            out_name = col.split(":")[0]
            v = table.get(out_name)
            if v is None or v.causality != "output":
                hint = "" if key in agg else f" (the default; set `{where}` to another column, or null to skip it)"
                near = _close_names(out_name, table.names("output"))
                raise SweepError(where, f"`{out_name}` is not an output of the FMU of bearing {table.bearing}{near}{hint}")
            if col not in value_cols:
                if ":" in col:
                    raise SweepError(where, f"`{col}` is not a statistics column of this sweep (statistics.outputs and .functions)")
                outputs.append(col)  # record its final value too
                value_cols = _value_columns(outputs, statistics)
            aggregation[key] = col

    # Plots (grid only).
    plots = []
    if "plots" in raw:
        if mode != "grid":
            raise SweepError("plots", "maps are drawn over a `grid` only")
        if not isinstance(raw["plots"], list):
            raise SweepError("plots", f"must be a list, got {_kind(raw['plots'])}")
        grid = raw["grid"]
        for i, p in enumerate(raw["plots"]):
            where = f"plots[{i}]"
            _keys(p, PLOT_KEYS, where, required=("x", "y", "z", "file"))
            for k in ("x", "y", "z", "file", "title"):
                if k in p and not isinstance(p[k], str):
                    raise SweepError(f"{where}.{k}", f"must be a string, got {_kind(p[k])}")
            for k in ("x", "y"):
                if p[k] not in grid:
                    raise SweepError(f"{where}.{k}", f"`{p[k]}` is not a grid variable ({', '.join(grid)})")
                if len(grid[p[k]]) < 2:
                    raise SweepError(f"{where}.{k}", f"`{p[k]}` needs at least 2 grid values for a map")
            if p["x"] == p["y"]:
                raise SweepError(f"{where}.y", "must differ from x")
            others = [n for n in grid if n not in (p["x"], p["y"]) and len(grid[n]) > 1]
            if others:
                raise SweepError(where, f"the grid also varies {', '.join(others)}: a map needs every other grid variable at one value")
            if p["z"] not in value_cols:
                raise SweepError(f"{where}.z", f"`{p['z']}` is not a results column of this sweep ({', '.join(value_cols)})")
            if not p["file"].lower().endswith(PLOT_SUFFIXES) or Path(p["file"]).name != p["file"]:
                raise SweepError(f"{where}.file", f"must be a file name ending in {', '.join(PLOT_SUFFIXES)} (written beside the results)")
            plots.append(dict(p))

    sweep = Sweep(
        path=path or Path("<inline>"),
        text=text,
        mode=mode,
        bearing=b,
        table=table,
        swept=swept,
        outputs=outputs,
        statistics=statistics,
        aggregation=aggregation,
        plots=plots,
    )

    # Tasks.
    record_outputs = list(dict.fromkeys(outputs + (statistics["outputs"] if statistics else [])))
    for index, values in enumerate(case_values):
        s = copy.deepcopy(scen)
        for name, value in values.items():
            section = "parameters" if table.get(name).causality == "parameter" else "inputs"
            s.setdefault(section, {})[name] = value
        s["outputs"] = record_outputs
        definition = {
            "format": TASK_FORMAT,
            "scenario": s,
            "bearing_text": bearing_text,
            "final": outputs,
            "statistics": statistics,
        }
        task = dict(definition, id=case_id(definition))
        sweep.cases.append(Case(index=index, values=values, task=task, time_share=shares[index] if shares else None))
    check_scenario(sweep.cases[0], trb)
    return sweep


def check_scenario(case: Case, trb: Path):
    """Let the program check the scenario format (the values of the base scenario, which
    this module does not read): one communication step of the first case. A scenario the
    program refuses (exit code 2) is a SweepError with its message; a model failure is left
    to the sweep, where it is a result."""
    import subprocess
    import tempfile

    scen = copy.deepcopy(case.task["scenario"])
    scen["stop_time"] = scen.get("start_time", 0.0) + scen["step"]
    with tempfile.TemporaryDirectory(prefix="trb-sweep-check-") as tmp:
        tmp = Path(tmp)
        if case.task["bearing_text"] is not None:
            (tmp / "bearing.json").write_text(case.task["bearing_text"])
        (tmp / "scenario.json").write_text(json.dumps(scen))
        try:
            proc = subprocess.run(
                [str(trb), "simulate", str(tmp / "scenario.json"), "--out", str(tmp / "out.csv"), "--quiet"],
                capture_output=True, text=True, timeout=600,
            )
        except (OSError, subprocess.TimeoutExpired):
            return  # the sweep will record it
    if proc.returncode == 2:
        msg = " ".join(proc.stderr.strip().splitlines())
        msg = msg.replace(f"error: scenario {tmp / 'scenario.json'}: ", "")  # the temporary file's name
        raise SweepError("scenario", f"`trb simulate` refuses the scenario of case 0: {msg}")


def case_id(definition: dict) -> str:
    """A stable hash of a case's full resolved definition: SHA-256 of its canonical JSON
    (sorted keys, no spaces, floats as shortest round-trip text), first 20 hex digits."""
    canon = json.dumps(definition, sort_keys=True, separators=(",", ":"), allow_nan=False)
    return hashlib.sha256(canon.encode()).hexdigest()[:20]


def _cases(raw: dict, mode: str, table: VariableTable) -> tuple[list[dict], list[float] | None]:
    causal = ("input", "parameter")
    if mode == "grid":
        grid = raw["grid"]
        if not isinstance(grid, dict) or not grid:
            raise SweepError("grid", "must be a non-empty object {variable: [values]}")
        axes = []
        for name, vals in grid.items():
            where = f"grid.{name}"
            v = _variable(table, name, where, causal)
            if not isinstance(vals, list) or not vals:
                raise SweepError(where, f"must be a non-empty list of values, got {json.dumps(vals)}")
            axes.append([_typed(v, x, f"{where}[{i}]") for i, x in enumerate(vals)])
        names = list(grid)
        return [dict(zip(names, combo)) for combo in itertools.product(*axes)], None

    if mode == "cases":
        cases = raw["cases"]
        if not isinstance(cases, list) or not cases:
            raise SweepError("cases", "must be a non-empty list of objects {variable: value}")
        out = []
        for i, c in enumerate(cases):
            where = f"cases[{i}]"
            if not isinstance(c, dict):
                raise SweepError(where, f"must be an object {{variable: value}}, got {_kind(c)}")
            out.append({name: _typed(_variable(table, name, f"{where}.{name}", causal), x, f"{where}.{name}") for name, x in c.items()})
        return out, None

    spec = raw["spectrum"]
    _keys(spec, {"bins"}, "spectrum", required=("bins",))
    bins = spec["bins"]
    if not isinstance(bins, list) or not bins:
        raise SweepError("spectrum.bins", "must be a non-empty list of {\"share\": ..., \"values\": {...}}")
    out, shares = [], []
    for i, b in enumerate(bins):
        where = f"spectrum.bins[{i}]"
        _keys(b, BIN_KEYS, where, required=("share", "values"))
        share = _finite(b["share"], f"{where}.share")
        if share < 0:
            raise SweepError(f"{where}.share", f"must be >= 0, got {share!r}")
        vals = b["values"]
        if not isinstance(vals, dict):
            raise SweepError(f"{where}.values", f"must be an object {{variable: value}}, got {_kind(vals)}")
        out.append({n: _typed(_variable(table, n, f"{where}.values.{n}", causal), x, f"{where}.values.{n}") for n, x in vals.items()})
        shares.append(share)
    total = math.fsum(shares)
    if total <= 0:
        raise SweepError("spectrum.bins", "the time shares sum to 0")
    return out, [s / total for s in shares]
