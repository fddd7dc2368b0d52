"""Robustness through a real importer: fmpy's `simulate_fmu` drives the FMU with
time tables that a system model produces -- a run-up from rest, a sudden stop, a reversal
through zero, load steps and a shaft deflection ramp -- with communication steps from 1e-5 to
0.05 s. Every output stays finite, the energy balance holds (powerLoss = frictionTorque x
speed >= 0), and an input outside the model's range stops the run with a clear message
instead of NaN. The full stress matrix runs in Rust (`cargo run --release -- stress`,
tests/stress.rs); this is the same kind of case through fmpy's own master loop."""

import math

import numpy as np
import pytest
from fmpy import simulate_fmu

RPM = math.pi / 30


def table(rows):
    """A structured input array for simulate_fmu: rows of (time, speed, Fx, Fy, xi)."""
    dtype = [("time", float), ("speed", float), ("Fx", float), ("Fy", float), ("xi", float)]
    return np.array([tuple(r) for r in rows], dtype=dtype)


N = 3500 * RPM
CASES = {
    # name: (input rows, stop time, communication step)
    "run-up-from-rest": ([(0, 0, 30e3, 20e3, 0), (0.2, N, 30e3, 20e3, 0)], 0.2, 1e-3),
    "sudden-stop": ([(0, N, 30e3, 20e3, 0), (0.05, N, 30e3, 20e3, 0), (0.0501, 0, 30e3, 20e3, 0), (0.1, 0, 30e3, 20e3, 0)], 0.1, 1e-3),
    "reversal": ([(0, N, 30e3, 10e3, 0), (0.1, -N, 30e3, 10e3, 0)], 0.1, 1e-3),
    "load-steps": ([(0, N, 5e3, 2e3, 0), (0.02, N, 5e3, 2e3, 0), (0.0201, N, 150e3, 200e3, 0), (0.04, N, 150e3, 200e3, 0), (0.0401, N, 5e3, 2e3, 0), (0.06, N, 5e3, 2e3, 0)], 0.06, 1e-3),
    "deflection-ramp": ([(0, N, 30e3, 20e3, 0), (0.05, N, 30e3, 20e3, math.radians(0.05))], 0.05, 1e-3),
    "tiny-steps": ([(0, N, 30e3, 20e3, 0), (1e-3, 0.5 * N, 30e3, 25e3, 0)], 1e-3, 1e-5),
    "large-steps": ([(0, 0, 30e3, 20e3, 0), (1.0, N, 30e3, 20e3, 0)], 1.0, 0.05),
}


@pytest.mark.parametrize("name", list(CASES))
def test_time_tables_through_fmpy_stay_finite_and_balanced(fmu_path, name):
    rows, stop, step = CASES[name]
    res = simulate_fmu(
        str(fmu_path),
        stop_time=stop,
        step_size=step,
        output_interval=step,
        input=table(rows),
        output=["speed", "frictionTorque", "powerLoss", "Qo.max", "reaction.Fx", "loadedRollers", "cone.x"],
    )
    assert len(res) >= 2
    for n in res.dtype.names:
        assert np.all(np.isfinite(res[n])), f"{name}: {n} is not finite"
    power, torque, speed = res["powerLoss"], res["frictionTorque"], res["speed"]
    assert np.all(power >= 0), f"{name}: negative power loss"
    assert np.allclose(power, torque * speed, rtol=1e-12, atol=1e-12), f"{name}: powerLoss != frictionTorque x speed"
    assert np.all((res["loadedRollers"] >= 0) & (res["loadedRollers"] <= 17))


def test_an_input_beyond_the_range_stops_the_run_with_a_message_not_nan(fmu_path):
    """speed = 1e300 rad/s is refused, naming the input, rather than giving NaN outputs from a
    successful step."""
    rows = [(0, N, 30e3, 20e3, 0), (0.01, N, 30e3, 20e3, 0), (0.0101, 1e300, 30e3, 20e3, 0), (0.02, 1e300, 30e3, 20e3, 0)]
    messages = []

    def logger(component, instance, status, category, message):
        messages.append(message.decode("utf-8", "replace"))

    with pytest.raises(Exception):
        simulate_fmu(str(fmu_path), stop_time=0.02, step_size=1e-3, input=table(rows), logger=logger, debug_logging=False)
    assert any("input speed" in m and "exceeds the model's range" in m for m in messages), messages
