"""The standalone program as the harness uses it: `simulate` CSV layout, `fmu --out`,
`demo`, and clear errors for bad scenarios."""

import json
import os

import pytest

from conftest import SCENARIOS, read_csv, run_cli, write_json


def test_simulate_csv_has_time_then_all_inputs_then_outputs(tmp_path, model):
    scenario = {
        "bearing": "TRB130x230",
        "inputs": {"Fy": {"time": [0.0, 0.004], "values": [0.0, 4000.0]}},
        "stop_time": 0.004,
        "step": 0.001,
        "outputs": ["Qo.max", "frictionTorque", "loadedRollers"],
    }
    out = tmp_path / "out.csv"
    run_cli("simulate", write_json(tmp_path / "s.json", scenario), "--out", out, "--quiet")
    header, rows = read_csv(out)
    assert header == ["time", *model.names("input"), "Qo.max", "frictionTorque", "loadedRollers"]
    assert [r[0] for r in rows] == [0.0, 0.001, 0.002, 0.003, 0.004]
    fy = header.index("Fy")
    assert [r[fy] for r in rows] == [0.0, 1000.0, 2000.0, 3000.0, 4000.0]
    # Unnamed inputs keep their start values.
    for name in ["speed", "Fx", "xi"]:
        assert all(r[header.index(name)] == model.start(name) for r in rows), name
    # Integers are printed as integers.
    text = out.read_text().splitlines()[1]
    assert text.split(",")[-1] == "17"


def test_every_shipped_scenario_is_valid(tmp_path):
    """Each scenario in scenarios/ parses (a one-step run of it, to keep this quick)."""
    files = sorted(SCENARIOS.glob("*.json"))
    assert files, "no scenarios shipped"
    for f in files:
        s = json.loads(f.read_text())
        s["stop_time"] = s.get("start_time", 0.0) + s["step"]
        p = write_json(tmp_path / f.name, s)
        run_cli("simulate", p, "--out", tmp_path / (f.stem + ".csv"), "--quiet")
        _, rows = read_csv(tmp_path / (f.stem + ".csv"))
        assert len(rows) == 2, f.name


@pytest.mark.parametrize(
    "change, field",
    [
        ({"step": -1.0}, "step"),
        ({"inputs": {"Fy": {"time": [0.0, 0.0], "values": [1.0, 2.0]}}}, "inputs.Fy.time"),
        ({"inputs": {"noSuchInput": 1.0}}, "noSuchInput"),
        ({"parameters": {"slices": "twenty"}}, "slices"),
        ({"bearing": "NO-SUCH-BEARING"}, "bearing"),
    ],
)
def test_bad_scenario_names_the_field(tmp_path, change, field):
    s = {"stop_time": 0.01, "step": 0.001}
    s.update(change)
    out = tmp_path / "out.csv"
    proc = run_cli("simulate", write_json(tmp_path / "bad.json", s), "--out", out, check=False)
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    assert field in proc.stderr and "panicked" not in proc.stderr, proc.stderr


def test_fmu_out_to_a_directory(tmp_path):
    proc = run_cli("fmu", "--bearing", "32008", "--out", tmp_path)
    assert (tmp_path / "TRB_32008.fmu").is_file()
    assert "32008" in proc.stdout and str(tmp_path / "TRB_32008.fmu") in proc.stdout
    # a directory that does not exist yet, named with a trailing separator, is created
    new = tmp_path / "new" / "fmus"
    run_cli("fmu", "--bearing", "32008", "--out", f"{new}{os.sep}")
    assert (new / "TRB_32008.fmu").is_file()


def test_demo_runs_and_prints_a_table(tmp_path):
    csv = tmp_path / "demo.csv"
    proc = run_cli("demo", "--csv", csv)
    header, rows = read_csv(csv)
    assert len(rows) == 201 and header[0] == "time"
    assert "frictionTorque" in header and "Qo.max" in header
    assert "torque" in proc.stdout and "TaperedRollerBearing.fmu" in proc.stdout
    # Part 2: the [W25] reference case in the dynamic model, 50 ms, with an SVG of skew and tilt.
    header, rows = read_csv(tmp_path / "demo_dynamic.csv")
    assert len(rows) == 101 and rows[-1][0] >= 0.05
    col = {name: i for i, name in enumerate(header)}
    assert max(r[col["integrator.steps"]] for r in rows) > 100, "the dynamic model integrated"
    assert all(r[col["frictionTorque"]] > 0 for r in rows)
    svg = (tmp_path / "demo_dynamic.svg").read_text()
    assert svg.startswith("<svg") and "Roller skew" in svg and "Roller tilt" in svg
    assert "skew.max [deg]" in proc.stdout and "wall time" in proc.stdout
