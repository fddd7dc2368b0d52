"""The studies' presets as FMUs: each packages into a valid FMU (fmpy validate) that runs its
study scenario with fmpy's simulate_fmu, agrees with the standalone program on the same
scenario, and shows the study's key behaviour ([D19] skew at the pocket limit with roller-cage
torque, [L22] unequal roller loads from diameter deviations, [Y22] preload in three lobe zones
and different loaded-roller counts single- vs double-pressed)."""

import json
import math

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.validation import validate_fmu

from conftest import SCENARIOS, read_csv, run_cli

CASES = [
    ("32018X", "d19_skew_force_preload.json"),
    ("32018X", "d19_skew_displacement_preload.json"),
    ("32008", "l22_series5_2kN.json"),
    ("CRB-TRILOBE", "y22_single_pressed.json"),
    ("CRB-TRILOBE", "y22_double_pressed.json"),
]

KEYS = ["frictionTorque", "frictionTorque.raceway", "frictionTorque.flange", "frictionTorque.cage", "frictionTorque.cone",
        "frictionTorque.cup", "slidingFriction.max", "Qo.max", "Qc.max", "skew.max", "loadedRollers", "cone.x", "cone.y"]


def scenario(name):
    return json.loads((SCENARIOS / name).read_text())


def run_fmu(path, sc, stop=None):
    """simulate_fmu with the scenario's parameters and (constant) inputs."""
    start = dict(sc.get("parameters", {}))
    for k, v in sc.get("inputs", {}).items():
        assert not isinstance(v, dict), f"{k}: time tables are not used here"
        start[k] = v
    stop = sc["stop_time"] if stop is None else stop
    return simulate_fmu(str(path), start_time=sc.get("start_time", 0.0), stop_time=stop, output_interval=sc["step"],
                        start_values=start)


@pytest.mark.parametrize("preset", ["32018X", "32008", "CRB-TRILOBE"])
def test_study_preset_fmu_is_valid(package_preset, preset):
    problems = validate_fmu(str(package_preset(preset)))
    assert problems == [], f"{preset}: " + "\n".join(problems)


@pytest.mark.parametrize("preset, name", CASES)
def test_study_scenario_runs_in_the_fmu_as_in_the_standalone_program(package_preset, tmp_path, preset, name):
    sc = scenario(name)
    assert sc["bearing"] == preset
    res = run_fmu(package_preset(preset), sc)
    for n in res.dtype.names:
        assert np.all(np.isfinite(res[n])), f"{name}: {n} is not finite"
    run_cli("simulate", SCENARIOS / name, "--out", tmp_path / "out.csv", "--quiet")
    header, rows = read_csv(tmp_path / "out.csv")
    last = dict(zip(header, rows[-1]))
    for k in KEYS:
        a, b = float(res[k][-1]), last[k]
        assert math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12), f"{name}: {k} FMU {a} vs standalone {b}"


def test_d19_skew_reaches_the_pocket_and_the_torque_parts_add_up(package_preset):
    sc = scenario("d19_skew_force_preload.json")
    res = run_fmu(package_preset("32018X"), sc)
    phi_max = sc["parameters"]["cage.pocketClearance"] / (0.5 * 20.96e-3)
    assert np.allclose(res["skew.max"], phi_max, rtol=1e-9)
    assert np.all(res["Qc.max"] > 0) and np.all(res["frictionTorque.cage"] > 0)
    parts = res["frictionTorque.raceway"] + res["frictionTorque.flange"] + res["frictionTorque.cage"]
    assert np.allclose(parts, res["frictionTorque"], rtol=1e-12)
    z = 26
    qc = np.array([res[f"roller[{j}].Qc"][-1] for j in range(1, z + 1)])
    skew = np.array([res[f"roller[{j}].skew"][-1] for j in range(1, z + 1)])
    # The rollers at their pockets are the ones at the skew limit.
    assert np.all((qc > 0) <= (np.abs(skew) >= phi_max * (1 - 1e-12)))
    # Skew moments balance per roller (cone + cup + flange + pocket couple).
    for j in range(1, z + 1):
        m = res[f"roller[{j}].Nis"][-1] + res[f"roller[{j}].Nos"][-1] + res[f"roller[{j}].Nfs"][-1]
        assert math.isclose(m, np.sign(skew[j - 1]) * qc[j - 1] * 20.96e-3, rel_tol=1e-3, abs_tol=5e-4), j


def test_l22_deviations_spread_the_loads_but_not_the_torque(package_preset):
    path = package_preset("32008")
    dev = run_fmu(path, scenario("l22_series5_2kN.json"), stop=0.001)
    ideal_sc = scenario("l22_ideal_2kN.json")
    ideal = run_fmu(path, ideal_sc, stop=0.001)
    q_dev = np.array([dev[f"roller[{j}].Qo"][-1] for j in range(1, 24)])
    q_ideal = np.array([ideal[f"roller[{j}].Qo"][-1] for j in range(1, 24)])
    assert np.ptp(q_ideal) <= 1e-9 * q_ideal.max()
    assert q_dev.max() > 1.5 * q_ideal.max()
    assert dev["slidingFriction.max"][-1] > ideal["slidingFriction.max"][-1]
    # At 2 kN the deviations unload 2 of 23 rollers; the EHL rolling resistance, most of the
    # torque here, grows only as load^0.246 per contact (Zhou & Hoeprich), so concentrating the
    # load lowers the torque: measured -7.1 % (the [L22] statement of 1e-2 % is at 10 kN, where
    # tests/studies.rs asserts < 2 %).
    assert abs(dev["frictionTorque"][-1] / ideal["frictionTorque"][-1] - 1) < 0.10


def test_y22_single_and_double_pressed_states(package_preset):
    path = package_preset("CRB-TRILOBE")
    single = run_fmu(path, scenario("y22_single_pressed.json"), stop=2e-6)
    double = run_fmu(path, scenario("y22_double_pressed.json"), stop=2e-6)
    assert single["loadedRollers"][0] != double["loadedRollers"][0]
    # Three preload zones: rollers touching the cone near 0, 120 and 240 deg.
    for res, angle0 in [(single, 0.0), (double, math.pi / 24)]:
        zones = set()
        for j in range(1, 25):
            if res[f"roller[{j}].Qi"][0] > 0:
                psi = (angle0 + 2 * math.pi * (j - 1) / 24) % (2 * math.pi)
                zones.add(int(((psi + math.pi / 3) // (2 * math.pi / 3)) % 3))
        assert zones == {0, 1, 2}
