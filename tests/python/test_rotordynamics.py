"""The rotordynamics example (examples/rotordynamics, trb.rotordynamics): FMU stiffness -> ROSS.

A small version: 3 speeds, a coarse rotor. The shaft is made stiff (130 mm, the bearing bore,
1 m, a 380 kg disk) so that the bearings' compliance moves the first critical speed by a
resolvable amount (the example's slender 60 mm shaft makes the TRBs look rigid).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

rd = pytest.importorskip("trb.rotordynamics")
pytest.importorskip("ross")

RPM = np.array([4500.0, 5500.0, 6500.0])
SPEEDS = RPM * 2 * math.pi / 60
GEOMETRY = dict(length=1.0, diameter=0.13, journal_diameter=0.13, journal_length=0.1, n_elements=4,
                disk_diameter=0.8, disk_width=0.1)
PRELOADS = (15e3, 40e3)  # N; at 6500 rpm the centrifugal push-out is about 4.2 kN


@pytest.fixture(scope="module")
def stiffness(fmu_path, hub):
    W = rd.rotor_weight_share(GEOMETRY)
    return W, {p: rd.bearing_stiffness(fmu_path, SPEEDS, Fx=p, Fz=-W, callbacks=hub.install()) for p in PRELOADS}


def rotor_on(K, speeds=SPEEDS):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return rd.build_rotor(lambda n: rd.ross_bearing(n, K, speeds), lambda n: rd.ross_bearing(n, K, speeds), GEOMETRY)


def first_critical(rotor):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        wn = rd.campbell(rotor, SPEEDS, frequencies=4).wd
    crits = rd.critical_speeds(SPEEDS, wn)
    assert crits, f"no 1x crossing in {RPM} rpm: {wn[:, :4] * 60 / (2 * math.pi)} rpm"
    return crits[0][0]


def test_fmu_stiffness_is_a_usable_bearing_matrix(stiffness):
    """Radial and axial entries positive, the radial block isotropic-ish and symmetric, softer
    with more speed (the centrifugal force unloads the cone raceway), stiffer with more preload."""
    _, Ks = stiffness
    for K in Ks.values():
        for k in K:
            assert k[0, 0] > 1e8 and k[1, 1] > 1e9 and k[2, 2] > 1e9
            scale = np.abs(k[:3, :3]).max()
            assert np.abs(k[:3, :3] - k[:3, :3].T).max() < 1e-6 * scale
            assert abs(k[1, 2]) < 1e-6 * k[1, 1] and abs(k[1, 1] - k[2, 2]) < 0.01 * k[1, 1]
        assert K[-1, 1, 1] < K[0, 1, 1]
    assert np.all(Ks[40e3][:, 1, 1] > 1.05 * Ks[15e3][:, 1, 1])


def test_mapping_to_ross_axes(stiffness):
    """FMU (y, z) -> ROSS (x, y): ROSS kxx = K[y,y], kyy = K[z,z] (ROSS 1.5 has no axial bearing stiffness)."""
    _, Ks = stiffness
    K = Ks[15e3].copy()
    K[:, 1, 1] *= 1.5  # make y and z distinguishable
    b = rd.ross_bearing(0, K, SPEEDS)
    Kr = b.K(SPEEDS[1])
    assert Kr[0, 0] == pytest.approx(K[1, 1, 1], rel=1e-9)
    assert Kr[1, 1] == pytest.approx(K[1, 2, 2], rel=1e-9)
    assert Kr.shape == (2, 2)
    assert Kr[0, 1] == pytest.approx(K[1, 1, 2], abs=1e-9 * K[1, 1, 1])


def test_gravity_sag_matches_bearing_stiffness(stiffness):
    """On the elastic bearings, each bearing node sinks by its share of the weight over kyy
    (= the FMU's kzz at speed 0 extrapolated: ROSS interpolates in speed), and the bearing
    forces carry the whole weight; the shaft's own bending adds the mid-span sag on top."""
    W, Ks = stiffness
    rotor = rotor_on(Ks[15e3])
    uy, F = rd.gravity_sag(rotor)
    k0 = float(rotor.bearing_elements[0].kyy_interpolated(0.0))
    assert k0 == pytest.approx(Ks[15e3][0, 2, 2], rel=0.02)
    assert uy[0] == pytest.approx(-W / k0, rel=1e-3)
    assert uy[-1] == pytest.approx(-W / k0, rel=1e-3)
    assert F.sum() == pytest.approx(2 * W, rel=1e-3)
    assert uy.min() < 2 * uy[0]  # the shaft bends more than the bearings yield


def test_first_critical_speed_between_flexible_and_rigid(stiffness):
    """The first critical speed rises with the bearing stiffness (preload 15 -> 40 kN) and stays
    below the rigid-support value; the shifts follow springs in series: with the disk's modal
    stiffness k_s and two bearings of k_b, 1/w^2 = 1/w_rigid^2 + m/(2 k_b), so the shifts of
    1/w^2 scale as 1/k_b (hand estimate, to 15 %)."""
    _, Ks = stiffness
    w = {p: first_critical(rotor_on(Ks[p])) for p in PRELOADS}
    w_rigid = first_critical(rotor_on(1e14 * np.eye(5)[None], [0.0]))
    assert w[15e3] < w[40e3] < w_rigid
    assert w_rigid < SPEEDS[-1] and w[15e3] > SPEEDS[0]
    shift = {p: 1 / w[p] ** 2 - 1 / w_rigid**2 for p in PRELOADS}
    i = int(np.searchsorted(SPEEDS, w[15e3]))  # the stiffness near the critical speed
    kb = {p: 0.5 * (Ks[p][i - 1, 1, 1] + Ks[p][i, 1, 1]) for p in PRELOADS}
    assert shift[15e3] / shift[40e3] == pytest.approx(kb[40e3] / kb[15e3], rel=0.15)
