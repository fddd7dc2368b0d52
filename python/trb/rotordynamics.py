"""Rotordynamics with ROSS on the bearing FMU's tangent stiffness (examples/rotordynamics).

- `bearing_stiffness(fmu, speeds, Fx, Fz)`: the FMU's 5x5 `stiffness[i,j]` = d(reaction_i)/d(q_j),
  q = (x, y, z, xi, zeta), x the bearing axis, solved in force causality at each speed (rad/s),
  one fresh instance per operating point (initialization solves the quasi-static equilibrium).
- `ross_bearing(n, K, speeds, damping)`: a `ross.BearingElement` from those matrices. Axes:
  ROSS's shaft axis is its z, so FMU (x, y, z) -> ROSS (z, x, y) (a cyclic permutation, both
  right-handed): ROSS kxx = K[y,y], kyy = K[z,z], kxy = K[y,z], kyx = K[z,y]. The axial stiffness K[x,x]
  has no place in ROSS 1.5's 2 x 2 bearing element (its rotor has no axial degree of freedom).
  The tilt rows/columns (xi, zeta) and the radial-axial and radial-tilt couplings are dropped:
  a ROSS bearing element is a 3x3 (x, y, z) translational spring and damper, no moment stiffness.
  Our stiffness has no damping: `damping` (N s/m, the same in x and y) is the documented choice.
- `rotor_geometry`, `build_rotor(...)`: a slender steel shaft with bore-size journals and a central
  disk on two bearing elements; `rotor_weight_share`: each bearing's radial load (N).
- `campbell(rotor, speeds)` / `critical_speeds(speeds, wd)`: ROSS's Campbell diagram and its
  crossings with the 1x synchronous line (linear interpolation between speeds).
- `gravity_sag(rotor)`: the static deflection under gravity on the elastic bearings (ROSS's own
  `run_static` uses rigid supports, so it is solved here from ROSS's K(0) and weight vector).

ROSS is imported lazily (it is heavy: numba, pandas, plotly, ccp): importing `trb` stays light.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

# Index of the FMU's generalized coordinates in `stiffness[i,j]` (1-based in the FMU names).
X, Y, Z, XI, ZETA = range(5)


def bearing_stiffness(fmu_path, speeds, Fx: float, Fz: float, Fy: float = 0.0, parameters=None, callbacks=None) -> np.ndarray:
    """The FMU's tangent stiffness (N/m, N, N m/rad) at each speed: array (len(speeds), 5, 5).

    Force causality (the default): axial load `Fx` (> 0 loads the bearing), radial loads `Fy`,
    `Fz` on the cone; `parameters` are extra start values (e.g. {"fidelity": 0}). Each operating
    point is a fresh instance, initialized (the quasi-static solve) and read, no time step.
    """
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    md = read_model_description(str(fmu_path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    names = [f"stiffness[{i},{j}]" for i in range(1, 6) for j in range(1, 6)]
    k_refs = [vr[n] for n in names]
    unzipdir = extract(str(fmu_path))
    out = np.empty((len(speeds), 5, 5))
    for s, speed in enumerate(speeds):
        fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier=md.coSimulation.modelIdentifier, instanceName="rotor")
        if callbacks is None:
            fmu.instantiate()
        else:
            fmu.instantiate(callbacks=callbacks)
        try:
            fmu.setupExperiment(startTime=0.0)
            start = {"speed": float(speed), "Fx": float(Fx), "Fy": float(Fy), "Fz": float(Fz)}
            start.update(parameters or {})
            for name, value in start.items():
                if md.modelVariables[[v.name for v in md.modelVariables].index(name)].type == "Real":
                    fmu.setReal([vr[name]], [float(value)])
                else:
                    fmu.setInteger([vr[name]], [int(value)])
            fmu.enterInitializationMode()
            fmu.exitInitializationMode()
            out[s] = np.array(fmu.getReal(k_refs)).reshape(5, 5)
            fmu.terminate()
        finally:
            fmu.freeInstance()
    return out


def ross_bearing(n: int, K: np.ndarray, speeds, damping: float = 0.0, tag: str | None = None):
    """A ROSS BearingElement at node `n` from the FMU stiffness K (len(speeds), 5, 5).

    Speed-dependent coefficients over `speeds` (rad/s; ROSS interpolates them in speed). Only the
    radial block is used (see the module docstring for the axes).
    """
    import ross as rs

    K = np.asarray(K)
    freq = np.asarray(speeds, dtype=float)
    c = [float(damping)] * len(freq)
    return rs.BearingElement(
        n=n,
        kxx=K[:, Y, Y],
        kyy=K[:, Z, Z],
        kxy=K[:, Y, Z],
        kyx=K[:, Z, Y],
        cxx=c,
        cyy=c,
        frequency=freq,
        tag=tag,
    )


def rotor_geometry(length: float = 1.0, diameter: float = 0.06, journal_diameter: float = 0.13, journal_length: float = 0.06,
                   n_elements: int = 8, disk_diameter: float = 0.5, disk_width: float = 0.05) -> dict:
    """The example rotor's dimensions (m): a shaft of `length` between the bearing centres, slender
    (`diameter`) in `n_elements` beams between two journals (`journal_diameter` = the bearing bore,
    `journal_length` each), a steel disk at mid-span."""
    return dict(length=length, diameter=diameter, journal_diameter=journal_diameter, journal_length=journal_length,
                n_elements=n_elements, disk_diameter=disk_diameter, disk_width=disk_width)


def build_rotor(bearing_left, bearing_right, geometry: dict | None = None):
    """The ROSS rotor of `rotor_geometry`: nodes 0 and N (the journals' outer ends) carry the bearings
    made by `bearing_left(n)`/`bearing_right(n)`; the disk sits at the middle node."""
    import ross as rs

    g = geometry or rotor_geometry()
    steel = rs.materials.steel
    n = g["n_elements"]
    if n % 2:
        raise ValueError("n_elements must be even (the disk sits at the middle node)")
    le = (g["length"] - 2 * g["journal_length"]) / n

    def beam(L, d):
        return rs.ShaftElement(L=L, idl=0.0, odl=d, material=steel, shear_effects=True, rotary_inertia=True, gyroscopic=True)

    shaft = [beam(g["journal_length"], g["journal_diameter"])]
    shaft += [beam(le, g["diameter"]) for _ in range(n)]
    shaft += [beam(g["journal_length"], g["journal_diameter"])]
    disk = rs.DiskElement.from_geometry(n=1 + n // 2, material=steel, width=g["disk_width"], i_d=g["diameter"], o_d=g["disk_diameter"])
    return rs.Rotor(shaft, [disk], [bearing_left(0), bearing_right(n + 2)])


def rotor_weight_share(geometry: dict | None = None, density: float = 7810.0, g: float = 9.8065) -> float:
    """Half the weight (N) of `build_rotor`'s shaft and disk (steel, ROSS's density): the radial
    load of each bearing (the rotor is symmetric)."""
    G = geometry or rotor_geometry()
    area = lambda d: math.pi * d**2 / 4  # noqa: E731
    shaft = area(G["diameter"]) * (G["length"] - 2 * G["journal_length"]) + 2 * area(G["journal_diameter"]) * G["journal_length"]
    disk = (area(G["disk_diameter"]) - area(G["diameter"])) * G["disk_width"]
    return 0.5 * g * density * (shaft + disk)


def campbell(rotor, speeds, frequencies: int = 6):
    """ROSS's Campbell diagram (undamped natural frequencies, rad/s) over `speeds` (rad/s)."""
    return rotor.run_campbell(np.asarray(speeds, dtype=float), frequencies=frequencies, frequency_type="wn")


def critical_speeds(speeds, wn) -> list[tuple[float, int]]:
    """Crossings of the natural frequencies wn (len(speeds), modes; rad/s) with the 1x line
    omega = speed: (speed, mode), sorted by speed, by linear interpolation of wn - speed."""
    speeds = np.asarray(speeds, dtype=float)
    wn = np.asarray(wn, dtype=float)
    found = []
    for m in range(wn.shape[1]):
        d = wn[:, m] - speeds
        for i in range(len(speeds) - 1):
            if d[i] == 0.0:
                found.append((float(speeds[i]), m))
            elif d[i] * d[i + 1] < 0:
                t = d[i] / (d[i] - d[i + 1])
                found.append((float(speeds[i] + t * (speeds[i + 1] - speeds[i])), m))
    return sorted(found)


def gravity_sag(rotor, g: float = 9.80665) -> tuple[np.ndarray, np.ndarray]:
    """Static lateral deflection under gravity (-y) on the elastic bearings at speed 0:
    (y displacement per node (m), bearing force per bearing (N, +y on the shaft) = -kyy u_y).
    Solved from the rotor's own matrices, K(0) u = M a_g with a_g = -g on every node's y
    translation (ROSS 1.5: 4 degrees of freedom per node, x, y and the two rotations)."""
    dof = rotor.number_dof
    K = np.asarray(rotor.K(0))
    M = np.asarray(rotor.M())
    a = np.zeros(K.shape[0])
    a[1::dof] = -g
    u = np.linalg.solve(K, M @ a)
    uy = u[1::dof]
    forces = np.array([-float(b.kyy_interpolated(0.0)) * uy[b.n] for b in rotor.bearing_elements])
    return uy, forces


def plot_campbell(path, speeds, wn, crits, title: str = ""):
    """Campbell diagram (rpm against Hz) with the 1x line and the critical speeds, to `path`."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rpm = np.asarray(speeds) * 60 / (2 * math.pi)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for m in range(wn.shape[1]):
        ax.plot(rpm, wn[:, m] / (2 * math.pi), lw=1.2)
    ax.plot(rpm, np.asarray(speeds) / (2 * math.pi), "k--", lw=1, label="1x")
    for s, _ in crits:
        ax.plot(s * 60 / (2 * math.pi), s / (2 * math.pi), "ro")
        ax.annotate(f"{s * 60 / (2 * math.pi):.0f} rpm", (s * 60 / (2 * math.pi), s / (2 * math.pi)),
                    textcoords="offset points", xytext=(6, -12), fontsize=8)
    ax.set_xlabel("rotor speed (rpm)")
    ax.set_ylabel("natural frequency (Hz)")
    ax.set_title(title)
    ax.legend(loc="upper left")
    ax.grid(alpha=0.3)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
