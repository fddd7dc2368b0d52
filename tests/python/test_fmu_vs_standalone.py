"""The FMU and the standalone program agree: `simulate` writes a CSV, and an FMI master that
makes the calls the CSV's semantics describe (scenarios/README.md) reproduces every output.

Replay with fmpy's low-level FMU2Slave:
  instantiate; setupExperiment(t_0, t_N); set the scenario's parameters; set the inputs of
  row 0; enter/exit initialization mode; get outputs -> row 0;
  for k = 0..N-1: [with `interpolate_inputs`: setRealInputDerivatives of order 1, the secants
  (u_{k+1} - u_k) / (t_{k+1} - t_k) of the input columns;] doStep(t_k, t_{k+1} - t_k); set the
  inputs of row k+1; get outputs -> row k+1.
"""

import copy
import json
import math

import pytest

from conftest import SCENARIOS, Model, close_enough, read_csv, run_cli, set_values, write_json


def _load(name):
    return json.loads((SCENARIOS / name).read_text())


def _with_tables(base: str, stop: float, step: float, tables: dict, **extra) -> dict:
    """A study scenario with some inputs replaced by time tables, so they change during the run."""
    s = copy.deepcopy(_load(base))
    s["description"] = f"test: {base} with time tables on {', '.join(tables)}"
    s["stop_time"] = stop
    s["step"] = step
    s["inputs"].update(tables)
    s.update(extra)
    return s


def _cases():
    return {
        # The default bearing: the demo (Fy ramp, then a xi ramp), as shipped.
        "TRB130x230-demo": lambda: _load("demo.json"),
        # Displacement preload, Fy ramp and a fixed deflection, as shipped.
        "TRB130x230-displacement-preload": lambda: _load("w25_preload_xi0.003.json"),
        # 32018X, dry friction: radial load and deflection change during the run.
        "32018X-dry": lambda: _with_tables(
            "d19_force_preload.json", 0.3, 0.01,
            {
                "Fy": {"time": [0.0, 0.1, 0.3], "values": [35000.0, 35000.0, 20000.0]},
                "xi": {"time": [0.0, 0.15, 0.3], "values": [0.0, 3e-5, 3e-5]},
            },
        ),
        # 32008 with per-roller diameter deviations (parameters roller[j].dD).
        "32008-roller-deviations": lambda: _with_tables(
            "l22_series1_10kN.json", 0.06, 0.001,
            {
                "Fy": {"time": [0.0, 0.02, 0.06], "values": [0.0, 0.0, 3000.0]},
                "zeta": {"time": [0.0, 0.04, 0.06], "values": [0.0, 0.0, 2e-5]},
            },
        ),
        # The dynamic model (fidelity 1): radial load and deflection change during the run;
        # integrator state (including its stored derivative) must evolve identically.
        "TRB130x230-dynamic": lambda: {
            "description": "test: [W25] case at fidelity 1 with a radial load ramp and a deflection step",
            "bearing": "TRB130x230",
            "parameters": {"fidelity": 1, "slices": 8},
            "inputs": {
                "speed": 366.51914291880917,
                "Fx": 30000.0,
                "Fy": {"time": [0.0, 0.001], "values": [0.0, 6000.0]},
                "xi": {"time": [0.0, 0.0006, 0.0007], "values": [0.0, 0.0, 7e-5]},
            },
            "stop_time": 0.001,
            "step": 0.0001,
        },
        # Inputs ramped over each step (fmi2SetRealInputDerivatives), quasi-static and dynamic.
        "32018X-dry-interpolated": lambda: _with_tables(
            "d19_force_preload.json", 0.3, 0.01,
            {
                "Fy": {"time": [0.0, 0.1, 0.3], "values": [35000.0, 35000.0, 20000.0]},
                "speed": {"time": [0.0, 0.3], "values": [6.283185307179585, 20.0]},
            },
            interpolate_inputs=True,
        ),
        "TRB130x230-dynamic-interpolated": lambda: {
            "description": "test: [W25] case at fidelity 1 with radial load and deflection ramped within the steps",
            "bearing": "TRB130x230",
            "parameters": {"fidelity": 1, "slices": 8},
            "inputs": {
                "speed": {"time": [0.0, 0.001], "values": [366.51914291880917, 380.0]},
                "Fx": 30000.0,
                "Fy": {"time": [0.0, 0.001], "values": [0.0, 6000.0]},
                "xi": {"time": [0.0, 0.0006, 0.0007], "values": [0.0, 0.0, 7e-5]},
            },
            "stop_time": 0.001,
            "step": 0.0001,
            "interpolate_inputs": True,
        },
        # The cylindrical lobed bearing, cage followed over a roller pitch.
        "CRB-TRILOBE-lobed": lambda: _with_tables(
            "y22_single_pressed.json", 0.00014, 2e-6,
            {"Fy": {"time": [0.0, 0.00014], "values": [100.0, 300.0]}},
        ),
    }


CASES = _cases()


def replay(fmu, model: Model, scenario: dict, header: list[str], rows: list[list[float]]) -> list[list[float]]:
    inputs = model.names("input")
    n_in = len(inputs)
    assert header[0] == "time" and header[1 : 1 + n_in] == inputs, header[: 1 + n_in]
    out_names = header[1 + n_in :]
    real_out = [(i, model.vr(n)) for i, n in enumerate(out_names) if model.vars[n].type == "Real"]
    int_out = [(i, model.vr(n)) for i, n in enumerate(out_names) if model.vars[n].type == "Integer"]
    assert len(real_out) + len(int_out) == len(out_names)
    in_vrs = [model.vr(n) for n in inputs]

    def outputs():
        row = [math.nan] * len(out_names)
        for (i, _), v in zip(real_out, fmu.getReal([vr for _, vr in real_out])):
            row[i] = v
        if int_out:
            for (i, _), v in zip(int_out, fmu.getInteger([vr for _, vr in int_out])):
                row[i] = float(v)
        return row

    t = [r[0] for r in rows]
    fmu.setupExperiment(startTime=t[0], stopTime=t[-1])
    set_values(fmu, scenario.get("parameters", {}))
    fmu.setReal(in_vrs, rows[0][1 : 1 + n_in])
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    got = [outputs()]
    for k in range(len(rows) - 1):
        if scenario.get("interpolate_inputs", False):
            h = t[k + 1] - t[k]
            rates = [(b - a) / h for a, b in zip(rows[k][1 : 1 + n_in], rows[k + 1][1 : 1 + n_in])]
            fmu.setRealInputDerivatives(in_vrs, [1] * n_in, rates)
        fmu.doStep(currentCommunicationPoint=t[k], communicationStepSize=t[k + 1] - t[k])
        fmu.setReal(in_vrs, rows[k + 1][1 : 1 + n_in])
        got.append(outputs())
    fmu.terminate()
    return got


@pytest.mark.parametrize("case", list(CASES))
def test_fmu_reproduces_the_standalone_csv(case, tmp_path, models, slaves):
    scenario = CASES[case]()
    path = write_json(tmp_path / f"{case}.json", scenario)
    csv_path = tmp_path / f"{case}.csv"
    run_cli("simulate", path, "--out", csv_path, "--quiet")
    header, rows = read_csv(csv_path)

    bearing = scenario.get("bearing", "TRB130x230")
    model = models(bearing)
    n_in = len(model.names("input"))
    out_names = header[1 + n_in :]
    assert len(out_names) == len(model.names("output")), "the CSV has every output by default"
    assert len(rows) == round((scenario["stop_time"] - scenario.get("start_time", 0.0)) / scenario["step"]) + 1
    assert rows[-1][0] == scenario["stop_time"]

    # The inputs really change during the run (the point of replaying row by row).
    changing = [n for i, n in enumerate(header[1 : 1 + n_in]) if len({r[1 + i] for r in rows}) > 1]
    assert changing, f"{case}: no input changes during the run"

    fmu = slaves.new(model, name=case)
    got = replay(fmu, model, scenario, header, rows)

    mismatches = []
    identical = 0
    for k, (row, mine) in enumerate(zip(rows, got)):
        for name, want, have in zip(out_names, row[1 + n_in :], mine):
            assert math.isfinite(have), f"{case}: t = {row[0]!r}: {name} = {have}"
            if want == have:
                identical += 1
            elif not close_enough(want, have):
                mismatches.append(f"t = {row[0]!r} ({k}): {name}: CSV {want!r}, FMU {have!r}")
    total = len(rows) * len(out_names)
    assert not mismatches, f"{case}: {len(mismatches)} of {total} values differ by more than 1e-12:\n" + "\n".join(mismatches[:20])
    print(f"{case}: {total} values, {identical} bit-identical")
