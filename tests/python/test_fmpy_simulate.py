"""fmpy's high-level `simulate_fmu` runs the FMU with its default start values, and the
results are finite and physically sensible."""

import json
import math

import numpy as np
import pytest
from fmpy import simulate_fmu

from conftest import PRESETS, REPO


def preset(name):
    return json.loads((REPO / "presets" / f"{name}.json").read_text())


def test_default_pure_axial_case(fmu_path, model):
    """TRB130x230 at its operating point: 3500 rpm, Fx = 30 kN, no radial load, no deflection."""
    res = simulate_fmu(str(fmu_path), stop_time=0.1, output_interval=0.001)
    names = res.dtype.names
    assert len(res) == 101
    assert np.allclose(res["time"], np.linspace(0.0, 0.1, 101), rtol=0, atol=1e-12)
    for n in names:
        assert np.all(np.isfinite(res[n])), f"{n} is not finite"

    p = preset("TRB130x230")
    z = p["rollers"]["count"]
    fx = model.start("Fx")
    speed = model.start("speed")
    assert fx == 30000.0 and math.isclose(speed, 3500 * math.pi / 30)
    alpha_o = math.radians(p["cup_angle_deg"])

    assert np.allclose(res["reaction.Fx"], fx, rtol=1e-6, atol=0)
    # The cup carries Fx, shared equally: Qo = Fx / (Z sin alpha_o).
    assert np.allclose(res["Qo.max"], fx / (z * math.sin(alpha_o)), rtol=1e-6, atol=0)
    for j in range(1, z + 1):
        assert np.allclose(res[f"roller[{j}].Qo"], res["Qo.max"], rtol=1e-9, atol=0)
    assert np.all(res["loadedRollers"] == z)
    # No radial displacement nor moment under pure axial load.
    assert np.all(np.abs(res["cone.y"]) <= 1e-9 * np.abs(res["cone.x"]))
    assert np.all(np.abs(res["cone.z"]) <= 1e-9 * np.abs(res["cone.x"]))
    assert np.all(np.abs(res["reaction.My"]) <= 1e-9 * fx * 0.2)
    assert np.all(res["cone.x"] > 0)
    # Friction: positive, its parts add up, power = torque * speed.
    t = res["frictionTorque"]
    assert np.all(t > 0)
    parts = res["frictionTorque.raceway"] + res["frictionTorque.flange"] + res["frictionTorque.cage"]
    assert np.allclose(parts, t, rtol=1e-9, atol=0)
    assert np.allclose(res["powerLoss"], t * speed, rtol=1e-9, atol=0)
    # Cage between standstill and the cone speed (epicyclic, about 0.4-0.5 of it).
    cage = res["cage.speed"]
    assert np.all((cage > 0.3 * speed) & (cage < 0.6 * speed))
    # Steady state: outputs do not depend on time (axisymmetric load).
    assert np.allclose(t, t[0], rtol=1e-9, atol=0)
    # The cage turns at cage.speed: roller 1 starts at cage.angle0 = 0.
    az = np.unwrap(res["roller[1].azimuth"])
    assert np.allclose(az, cage[0] * res["time"], rtol=1e-9, atol=1e-12)
    # Roller j is (j-1)/Z of a turn ahead of roller 1.
    two_pi = 2 * math.pi
    for j in (2, z):
        d = np.mod(res[f"roller[{j}].azimuth"] - res["roller[1].azimuth"], two_pi)
        assert np.allclose(d, two_pi * (j - 1) / z, rtol=0, atol=1e-9)


@pytest.mark.parametrize("name", PRESETS)
def test_every_preset_runs_at_its_operating_point(package_preset, models, name):
    path = package_preset(name)
    m = models(name)
    res = simulate_fmu(str(path), stop_time=0.002, output_interval=0.0005)
    assert len(res) == 5
    for n in res.dtype.names:
        assert np.all(np.isfinite(res[n])), f"{name}: {n} is not finite"
    z = m.z
    assert np.all((res["loadedRollers"] >= 1) & (res["loadedRollers"] <= z))
    assert np.all(res["solver.residual"] <= 1e-6)
    assert np.all(res["frictionTorque"] > 0)
    fx = m.start("Fx")
    if preset(name)["kind"] == "tapered":
        assert np.allclose(res["reaction.Fx"], fx, rtol=1e-6)
    else:
        # A cylindrical roller bearing carries no axial load in this model.
        assert np.all(res["reaction.Fx"] == 0.0)


def test_a_speed_ramp_with_input_derivatives_turns_the_cage_by_its_integral(fmu_path, model):
    """fmpy's `simulate_fmu(set_input_derivatives=True)` (canInterpolateInputs): the speed
    ramps within each communication step instead of being held, so the quasi-static cage,
    which follows the speed linearly, turns by exactly the integral of its speed, 0.5 a t^2
    from rest at a constant acceleration; held, it lags by half a step of speed per step.

    fmpy 0.3.32 sizes its buffer of input derivatives for exactly 9 continuous inputs
    (`(value_type * 9)()` in `fmpy.simulation.Input`), so the signal carries 9: the speed
    ramp and 8 more at their start values."""
    accel = 1000.0  # rad/s^2
    stop, step = 0.1, 0.01
    held_inputs = ["Fx", "Fy", "Fz", "xi", "zeta", "cupSpeed", "axialDisplacement", "oilTemperature"]
    dtype = [("time", np.float64), ("speed", np.float64)] + [(n, np.float64) for n in held_inputs]
    starts = tuple(model.start(n) for n in held_inputs)
    signal = np.array([(-1.0, -accel) + starts, (1.0, accel) + starts], dtype=dtype)
    results = {}
    for derivatives in (True, False):
        res = simulate_fmu(
            str(fmu_path), stop_time=stop, output_interval=step, input=signal, set_input_derivatives=derivatives,
            output=["speed", "cage.speed", "roller[1].azimuth"],
        )
        results[derivatives] = res
    ramped, held = results[True], results[False]
    # fmpy records a step's outputs before it sets the next inputs: ramped, the FMU's speed
    # has reached the signal's at the step's end; held, it is still the step's start value
    assert np.allclose(ramped["speed"], accel * ramped["time"], rtol=1e-12, atol=1e-9)
    assert np.allclose(held["speed"][1:], accel * (held["time"][1:] - step), rtol=1e-12, atol=1e-9)
    ratio = ramped["cage.speed"][-1] / ramped["speed"][-1]
    turned = np.unwrap(ramped["roller[1].azimuth"]) - ramped["roller[1].azimuth"][0]
    assert np.allclose(turned, 0.5 * ratio * accel * ramped["time"] ** 2, rtol=1e-9, atol=1e-12)
    lag = 0.5 * ratio * accel * step * ramped["time"]
    held_turned = np.unwrap(held["roller[1].azimuth"]) - held["roller[1].azimuth"][0]
    assert np.allclose(turned - held_turned, lag, rtol=1e-9, atol=1e-12)
