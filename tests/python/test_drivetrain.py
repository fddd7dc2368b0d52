"""examples/drivetrain: a shaft (Shaft.fmu, built from examples/drivetrain/shaft) on two
instances of the bearing FMU in an O arrangement, co-simulated with fmpy.

- The shaft's equilibrium holds to 1e-6 of the applied load along a time-varying mesh force.
- The pair's load sharing (all five reactions of each bearing) equals a direct quasi-static
  Newton solve of the two bearings to 1e-4 of the applied load.
- Mirror symmetry: a mesh force in the plane between the bearings loads both alike (their
  reactions in their own frames agree), which checks the mirrored signs of x, xi and zeta.
"""

import sys
import time

import numpy as np
import pytest

from conftest import REPO, run_cli

sys.path.insert(0, str(REPO / "examples" / "drivetrain"))
import drivetrain as dt  # noqa: E402


@pytest.fixture(scope="module")
def fmus(package_preset):
    return package_preset(dt.BEARING_PRESET), dt.build_shaft_fmu()


@pytest.fixture(scope="module")
def integer_bearing_fmu(fmus, tmp_path_factory):
    """The bearing FMU for the SSP: its Enumeration parameters declared as Integers."""
    out = tmp_path_factory.mktemp("integers") / "bearing-integers.fmu"
    run_cli("fmu", "--bearing", dt.BEARING_PRESET, "--enumerations-as-integers", "--out", out)
    return out


def run(fmus, **kw):
    bearing, shaft = fmus
    return dt.cosimulate(bearing_fmu=bearing, shaft_fmu=shaft, **kw).arrays()


def scale(p, t):
    """Per-component scale of the applied load: |F| for forces, |F| * span for moments."""
    f = np.linalg.norm(dt.mesh_force(p, t))
    span = p["bearingB.position"] - p["bearingA.position"]
    return np.array([f, f, f, f * span, f * span])


def test_equilibrium_and_load_sharing_against_direct_solve(fmus):
    p = dict(dt.SHAFT_PARAMETERS)
    t0 = time.perf_counter()
    res = run(fmus, stop=1.0, step=0.002)
    wall = time.perf_counter() - t0
    # After the first Newton steps every communication point is in equilibrium.
    worst = res["residual"][2:].max()
    assert worst <= 1e-6, f"largest relative shaft residual {worst:.3e}"
    assert res["shaft_residual"][-1] <= 1e-6
    # The load varies: the check is not of a constant state.
    fy = res["force"][:, 1]
    assert fy.max() - fy.min() > 0.3 * p["mesh.Fr"]

    bearing = dt.BearingFunction(fmus[0], p["shaft.speed"], None, p["preload.displacement"])
    try:
        worst_share = 0.0
        for k in [2, 60, 125, 250, 375, 499]:
            t = res["time"][k]
            q, reactions = dt.direct_solve(p, t, bearing)
            for i in range(2):
                diff = np.abs(res["reactions"][k][i] - reactions[i]) / scale(p, t)
                worst_share = max(worst_share, diff.max())
            np.testing.assert_allclose(res["q"][k], q, rtol=1e-3, atol=1e-9)
    finally:
        bearing.free()
    assert worst_share <= 1e-4, f"load sharing differs from the direct solve by {worst_share:.3e} of the load"
    print(f"residual {worst:.2e}, sharing {worst_share:.2e}, {len(res['time'])} steps in {wall:.2f} s")


def test_mirror_symmetry(fmus):
    """Mesh point at X = 0 between symmetric bearings, no axial force: the mirrored bearing
    B carries in its own frame exactly what A carries in its own."""
    res = run(fmus, shaft_parameters={"mesh.position": 0.0, "mesh.Fa": 0.0, "mesh.modulation": 0.0}, stop=0.05, step=0.01)
    a, b = res["reactions"][-1]
    p = dict(dt.SHAFT_PARAMETERS, **{"mesh.Fa": 0.0, "mesh.modulation": 0.0})
    rel = np.abs(a - b) / scale(p, 0.0)
    assert rel.max() <= 1e-6, f"A {a}, B {b}"
    # ... and the tilts are those of a symmetric load: the shaft translates, it does not tilt
    assert np.abs(res["q"][-1][3:]).max() <= 1e-9, res["q"][-1]
    # while an off-centre mesh point shares the radial load unequally (lever rule side)
    res = run(fmus, shaft_parameters={"mesh.modulation": 0.0}, stop=0.05, step=0.01)
    a, b = res["reactions"][-1]
    assert dt.radial(a) < dt.radial(b)


def test_committed_ssd_is_the_generated_one():
    import ssp

    assert ssp.SSD.read_text() == ssp.ssd_text(), "run python examples/drivetrain/ssp.py to rewrite SystemStructure.ssd"


def test_libcosim_runs_the_ssp_like_fmpy(fmus, integer_bearing_fmu, tmp_path):
    """The same system from SystemStructure.ssd in libcosim's fixed-step (Jacobi) algorithm:
    its bearing outputs at t + h are the equilibrium of the load at t (the Gauss-Seidel
    loop's at t), to 1e-5 of the load."""
    pytest.importorskip("libcosimpy.CosimExecution")
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level

    import ssp

    log_output_level(CosimLogLevel.WARNING)
    package = ssp.package_ssp(tmp_path / "drivetrain.ssp", bearing_fmu=integer_bearing_fmu, shaft_fmu=fmus[1])
    lc = ssp.run_libcosim(package, stop=1.0, step=0.002)
    fm = run(fmus, stop=1.0, step=0.002)
    p = dict(dt.SHAFT_PARAMETERS)
    worst = 0.0
    for j in range(4, len(fm["time"]) - 1):
        s = scale(p, fm["time"][j])
        for i in range(2):
            worst = max(worst, (np.abs(lc["reactions"][j + 1][i] - fm["reactions"][j][i]) / s).max())
    assert worst <= 1e-5, f"libcosim and fmpy differ by {worst:.3e} of the load"
    # the lives and torques come through as well
    assert np.all(lc["extra"][-1][:, 1] > 0) and np.all(np.isfinite(lc["extra"][-1]))


def test_thermal_preload_and_speed(fmus):
    """Without mesh force the pair stays centred and each bearing carries the preload of its
    interference: a warmer shaft (O arrangement, shaft growth only) lowers it as the bearing
    alone at the reduced interference says; speed raises it (the rollers' centrifugal force
    at fixed displacement)."""
    p = dict(dt.SHAFT_PARAMETERS, **{"mesh.Fa": 0.0, "mesh.Fr": 0.0, "mesh.Ft": 0.0})
    cold = run(fmus, shaft_parameters=p, stop=0.03, step=0.01)
    warm = run(fmus, shaft_parameters=p, stop=0.03, step=0.01, delta_t=5.0)
    a_cold, b_cold = cold["reactions"][-1]
    a_warm, b_warm = warm["reactions"][-1]
    assert abs(a_cold[0] - b_cold[0]) <= 1e-9 * a_cold[0] and abs(a_warm[0] - b_warm[0]) <= 1e-9 * a_warm[0]
    bearing = dt.BearingFunction(fmus[0], p["shaft.speed"], None, p["preload.displacement"])
    try:
        r, _ = bearing(np.array([dt.preload(p, 5.0) / 2, 0, 0, 0, 0]))
    finally:
        bearing.free()
    assert dt.preload(p, 5.0) < p["preload.displacement"]
    assert abs(a_warm[0] - r[0]) <= 1e-9 * r[0], (a_warm[0], r[0])
    assert a_warm[0] < 0.6 * a_cold[0]
    fast = run(fmus, shaft_parameters=dict(p, **{"shaft.speed": 600.0}), stop=0.03, step=0.01)
    assert fast["reactions"][-1][0][0] > a_cold[0]


def test_fmpy_ssp_master_runs_the_ssp(fmus, integer_bearing_fmu, tmp_path):
    """fmpy's SSP master (Jacobi, every connection starting at 0) on the same .ssp: after a
    start-up transient of a few steps, the equilibrium of the load one step back, as the
    Gauss-Seidel loop, to 1e-5 of the load."""
    import ssp

    package = ssp.package_ssp(tmp_path / "drivetrain.ssp", bearing_fmu=integer_bearing_fmu, shaft_fmu=fmus[1])
    fs = ssp.run_fmpy(package, stop=1.0, step=0.002)
    fm = run(fmus, stop=1.0, step=0.002)
    np.testing.assert_allclose(fs["time"], fm["time"], rtol=0, atol=1e-12)
    p = dict(dt.SHAFT_PARAMETERS)
    worst = 0.0
    for j in range(10, len(fm["time"])):
        s = scale(p, fm["time"][j - 1])
        for i in range(2):
            worst = max(worst, (np.abs(fs["reactions"][j][i] - fm["reactions"][j - 1][i]) / s).max())
    assert worst <= 1e-5, f"fmpy's SSP master and the Gauss-Seidel loop differ by {worst:.3e} of the load"
