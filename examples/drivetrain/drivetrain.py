"""A shaft on two tapered roller bearings in an O arrangement, co-simulated with fmpy.

Components (see README.md):
- `Shaft.fmu` (examples/drivetrain/shaft, built by this project): quasi-static rigid 5-DOF
  shaft, gear mesh force F(t), one Newton step per communication step from the bearings'
  reactions and tangent stiffness matrices.
- two instances of the bearing FMU of preset TRB130x230-W25 (`cargo run --release -- fmu
  --bearing TRB130x230-W25`) in displacement causality (`causality` = 1), bearing A in the
  shaft frame, bearing B mirrored. That preset keeps every roller of both bearings loaded in
  this arrangement, so its reactions are a function of the displacements alone and one Newton
  step per communication step holds the equilibrium to 1e-6 (README.md, "The bearing").

The master here is a fixed-step Gauss-Seidel loop on fmpy's FMU2Slave: shaft step, its
outputs to the bearings, bearing steps, their outputs to the shaft. `direct_solve` is an
independent check: a full Newton solve of the same equilibrium that uses one bearing FMU as
a function R(d), K(d).

    python examples/drivetrain/drivetrain.py [--plot OUT.png]
"""

from __future__ import annotations

import argparse
import math
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
BEARING_PRESET = "TRB130x230-W25"
BEARING_FMU = REPO / "target" / "fmu" / f"{BEARING_PRESET}.fmu"
SHAFT_DIR = HERE / "shaft"
SHAFT_FMU = SHAFT_DIR / "target" / "fmu" / "Shaft.fmu"

REACTION = ["Fx", "Fy", "Fz", "My", "Mz"]
STIFFNESS = [f"stiffness[{i},{j}]" for i in range(1, 6) for j in range(1, 6)]
CONE = ["cone.x", "cone.y", "cone.z"]
DISPLACEMENT = ["displacement.x", "displacement.y", "displacement.z", "xi", "zeta"]
BEARINGS = ["bearingA", "bearingB"]
SIGMA = [1.0, -1.0]  # bearing B is mirrored in the Y-Z plane

# Shaft parameters of the example (the Shaft FMU's start values, repeated in system.ssd).
SHAFT_PARAMETERS = {
    "bearingA.position": -0.15,
    "bearingB.position": 0.15,
    "preload.displacement": 40e-6,
    "mesh.position": 0.05,
    "mesh.radius": 0.2,
    "mesh.Fa": 8000.0,
    "mesh.Fr": 20000.0,
    "mesh.Ft": 40000.0,
    "mesh.modulation": 0.2,
    "mesh.frequency": 1.0,
    "mesh.rampTime": 0.0,
    "relaxation": 1.0,
    "shaft.speed": 300.0,
    "thermal.expansion": 11.7e-6,
    "thermal.radialLength": 0.0,
    "maxStep.translation": 20e-6,
    "maxStep.tilt": 5e-4,
}


def build_shaft_fmu() -> Path:
    """`cargo run --release` in examples/drivetrain/shaft (a no-op when up to date)."""
    subprocess.run(
        ["cargo", "run", "--release", "--quiet", "--manifest-path", str(SHAFT_DIR / "Cargo.toml")],
        check=True,
        cwd=REPO,
        capture_output=True,
    )
    return SHAFT_FMU


def build_bearing_fmu() -> Path:
    if not BEARING_FMU.is_file():
        subprocess.run(
            ["cargo", "run", "--release", "--quiet", "--", "fmu", "--bearing", BEARING_PRESET, "--out", str(BEARING_FMU)],
            check=True,
            cwd=REPO,
        )
    return BEARING_FMU


class Slave:
    """An instantiated FMU with access by variable name."""

    _unzipped: dict[Path, tuple] = {}

    def __init__(self, path: Path, name: str, callbacks=None):
        path = Path(path)
        if path not in Slave._unzipped:
            Slave._unzipped[path] = (read_model_description(str(path)), extract(str(path)))
        self.md, self.unzipdir = Slave._unzipped[path]
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.types = {v.name: v.type for v in self.md.modelVariables}
        self.fmu = FMU2Slave(
            guid=self.md.guid,
            unzipDirectory=self.unzipdir,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName=name,
        )
        self.fmu.instantiate(callbacks=callbacks)

    def set(self, values: dict):
        reals = {n: v for n, v in values.items() if self.types[n] == "Real"}
        ints = {n: v for n, v in values.items() if self.types[n] in ("Integer", "Enumeration")}
        if reals:
            self.fmu.setReal([self.vr[n] for n in reals], [float(v) for v in reals.values()])
        if ints:
            self.fmu.setInteger([self.vr[n] for n in ints], [int(v) for v in ints.values()])

    def get(self, names: list[str]) -> np.ndarray:
        return np.array(self.fmu.getReal([self.vr[n] for n in names]))

    def initialize(self, values: dict, start: float = 0.0):
        self.fmu.setupExperiment(startTime=start)
        self.set(values)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()

    def free(self):
        self.fmu.terminate()
        self.fmu.freeInstance()


# ---------------------------------------------------------------------------------------
# The shaft's kinematics, written again in Python for the direct solve
# ---------------------------------------------------------------------------------------


def t_matrix(s: float, sigma: float) -> np.ndarray:
    """Bearing (x, y, z, xi, zeta) from the shaft's q = (u, v, w, thetaY, thetaZ) at X = 0."""
    return np.array(
        [
            [sigma, 0, 0, 0, 0],
            [0, 1, 0, 0, s],
            [0, 0, 1, -s, 0],
            [0, 0, 0, sigma, 0],
            [0, 0, 0, 0, sigma],
        ],
        dtype=float,
    )


def preload(p: dict, delta_t: float = 0.0) -> float:
    """The pair's interference with the thermal part (as the Shaft FMU computes it)."""
    span = p["bearingB.position"] - p["bearingA.position"]
    return p["preload.displacement"] + p["thermal.expansion"] * delta_t * (p["thermal.radialLength"] - span)


def mesh_force(p: dict, t: float) -> np.ndarray:
    ramp = min(1.0, max(0.0, t / p["mesh.rampTime"])) if p["mesh.rampTime"] > 0 else 1.0
    f = ramp * (1.0 + p["mesh.modulation"] * math.sin(2 * math.pi * p["mesh.frequency"] * t))
    return f * np.array([p["mesh.Fa"], p["mesh.Fr"], p["mesh.Ft"]])


def applied(p: dict, t: float) -> np.ndarray:
    """Generalised force of the mesh force at (g, rho, 0)."""
    fx, fy, fz = mesh_force(p, t)
    g, rho = p["mesh.position"], p["mesh.radius"]
    return np.array([fx, fy, fz, -g * fz, g * fy - rho * fx])


def residual(p: dict, t: float, reactions: list[np.ndarray]) -> np.ndarray:
    r = applied(p, t)
    for i, name in enumerate(BEARINGS):
        r = r - t_matrix(p[f"{name}.position"], SIGMA[i]).T @ reactions[i]
    return r


def relative(p: dict, r: np.ndarray, f: np.ndarray, reactions: list[np.ndarray]) -> float:
    """As the Shaft FMU's residual.relative."""
    span = p["bearingB.position"] - p["bearingA.position"]
    w = np.array([1, 1, 1, 1 / span, 1 / span])
    scale = np.linalg.norm(f * w)
    if scale == 0.0:
        scale = max(np.linalg.norm(x * w) for x in reactions)
    return float(np.linalg.norm(r * w) / (scale if scale > 0 else 1.0))


# ---------------------------------------------------------------------------------------
# Co-simulation
# ---------------------------------------------------------------------------------------


@dataclass
class Result:
    time: list = field(default_factory=list)
    force: list = field(default_factory=list)  # mesh force (3)
    reactions: list = field(default_factory=list)  # [2][5] per row
    residual: list = field(default_factory=list)  # relative, recomputed from the outputs
    shaft_residual: list = field(default_factory=list)  # the shaft FMU's residual.relative
    friction: list = field(default_factory=list)  # [2]
    power: list = field(default_factory=list)  # [2]
    l10: list = field(default_factory=list)  # [2]
    l10r: list = field(default_factory=list)  # [2]
    q: list = field(default_factory=list)

    def arrays(self) -> dict:
        return {k: np.array(v) for k, v in self.__dict__.items()}


def bearing_parameters(speed: float, oil_temperature: float | None, preload: float) -> dict:
    p = {"causality": 1, "fidelity": 0, "speed": speed, "displacement.x": preload / 2}
    if oil_temperature is not None:
        p["oilTemperature"] = oil_temperature
    return p


def transfer_to_shaft(shaft: Slave, bearings: list[Slave]) -> list[np.ndarray]:
    """The bearings' reactions, stiffness and cone displacements to the shaft's inputs;
    returns the reactions."""
    reactions = []
    for name, b in zip(BEARINGS, bearings):
        values = b.get([f"reaction.{r}" for r in REACTION] + STIFFNESS + CONE)
        names = [f"{name}.reaction.{r}" for r in REACTION] + [f"{name}.{s}" for s in STIFFNESS] + [f"{name}.{c}" for c in CONE]
        shaft.set(dict(zip(names, values)))
        reactions.append(values[:5])
    return reactions


def cosimulate(
    shaft_parameters: dict | None = None,
    stop: float = 1.0,
    step: float = 0.01,
    oil_temperature: float | None = None,
    delta_t: float = 0.0,
    bearing_fmu: Path = BEARING_FMU,
    shaft_fmu: Path = SHAFT_FMU,
) -> Result:
    """Fixed-step Gauss-Seidel co-simulation: shaft, then the two bearings."""
    p = dict(SHAFT_PARAMETERS, **(shaft_parameters or {}))
    shaft = Slave(shaft_fmu, "shaft")
    bearings = [Slave(bearing_fmu, name) for name in BEARINGS]
    try:
        shaft.initialize(dict(p, **{"thermal.deltaT": delta_t}))
        for b in bearings:
            b.initialize(bearing_parameters(p["shaft.speed"], oil_temperature, preload(p, delta_t)))
        # The bearings' initial outputs (preloaded, at rest) to the shaft's inputs.
        transfer_to_shaft(shaft, bearings)
        out = Result()
        n = int(round(stop / step))
        for k in range(n):
            t = k * step
            shaft.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=step)
            speed = shaft.get(["speed"])[0]
            for name, b in zip(BEARINGS, bearings):
                d = shaft.get([f"{name}.{v}" for v in DISPLACEMENT])
                b.set(dict(zip(DISPLACEMENT, d)) | {"speed": speed})
                b.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=step)
            reactions = transfer_to_shaft(shaft, bearings)
            tn = t + step
            out.time.append(tn)
            out.force.append(shaft.get(["mesh.Fx", "mesh.Fy", "mesh.Fz"]))
            out.reactions.append(reactions)
            out.residual.append(relative(p, residual(p, tn, reactions), applied(p, tn), reactions))
            out.q.append(shaft.get(["shaft.u", "shaft.v", "shaft.w", "shaft.thetaY", "shaft.thetaZ"]))
            extra = [b.get(["frictionTorque", "powerLoss", "life.L10", "life.L10r"]) for b in bearings]
            out.friction.append([e[0] for e in extra])
            out.power.append([e[1] for e in extra])
            out.l10.append([e[2] for e in extra])
            out.l10r.append([e[3] for e in extra])
        # The shaft's own residual of the last bearing outputs: one more shaft step.
        shaft.fmu.doStep(currentCommunicationPoint=n * step, communicationStepSize=step)
        out.shaft_residual.append(shaft.get(["residual.relative"])[0])
        return out
    finally:
        shaft.free()
        for b in bearings:
            b.free()


# ---------------------------------------------------------------------------------------
# The direct quasi-static solve
# ---------------------------------------------------------------------------------------


class BearingFunction:
    """One bearing FMU in displacement causality used as the function d -> (R, K)."""

    def __init__(self, bearing_fmu: Path, speed: float, oil_temperature: float | None, preload: float):
        self.slave = Slave(bearing_fmu, "direct")
        self.slave.initialize(bearing_parameters(speed, oil_temperature, preload))
        self.t = 0.0

    def __call__(self, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        self.slave.set(dict(zip(DISPLACEMENT, d)))
        self.slave.fmu.doStep(currentCommunicationPoint=self.t, communicationStepSize=1e-3)
        self.t += 1e-3
        v = self.slave.get([f"reaction.{r}" for r in REACTION] + STIFFNESS)
        return v[:5], v[5:].reshape(5, 5)

    def free(self):
        self.slave.free()


def direct_solve(p: dict, t: float, bearing: BearingFunction, q0=None, tol: float = 1e-9, max_iter: int = 50, delta_t: float = 0.0):
    """Newton on Q_F(t) - sum T_i^T R_i(T_i q + d0) = 0 to |residual| <= tol |Q_F| (the
    bearing's reactions are exact to a few 1e-10 of the load: its own Newton tolerance)."""
    q = np.zeros(5) if q0 is None else np.array(q0, dtype=float)
    f = applied(p, t)
    d0 = np.array([preload(p, delta_t) / 2, 0, 0, 0, 0])
    for _ in range(max_iter):
        reactions, k = [], np.zeros((5, 5))
        for i, name in enumerate(BEARINGS):
            tm = t_matrix(p[f"{name}.position"], SIGMA[i])
            r, ki = bearing(tm @ q + d0)
            reactions.append(r)
            k += tm.T @ ki @ tm
        res = residual(p, t, reactions)
        if relative(p, res, f, reactions) <= tol:
            return q, reactions
        q = q + np.linalg.solve(k, res)
    raise RuntimeError(f"direct solve did not converge: relative residual {relative(p, res, f, reactions)}")


# ---------------------------------------------------------------------------------------
# Command line: a run, load sharing, lives and a plot
# ---------------------------------------------------------------------------------------


def preload_sweep(speeds, delta_ts, oil_temperatures, bearing_fmu: Path = BEARING_FMU, shaft_fmu: Path = SHAFT_FMU) -> dict:
    """The pair without mesh force: preload (bearing A's reaction.Fx, B's equal by symmetry)
    and the pair's friction torque against speed, for each shaft-housing temperature
    difference (at the oil's reference temperature) and each oil temperature (at deltaT 0)."""
    unloaded = {"mesh.Fa": 0.0, "mesh.Fr": 0.0, "mesh.Ft": 0.0}
    out = {"speed": np.array(speeds, dtype=float), "deltaT": {}, "oil": {}}
    for dT in delta_ts:
        rows = []
        for w in speeds:
            r = cosimulate(dict(unloaded, **{"shaft.speed": w}), stop=0.03, step=0.01, delta_t=dT, bearing_fmu=bearing_fmu, shaft_fmu=shaft_fmu).arrays()
            rows.append((r["reactions"][-1][0][0], r["friction"][-1].sum()))
        out["deltaT"][dT] = np.array(rows)
    for temp in oil_temperatures:
        rows = []
        for w in speeds:
            r = cosimulate(dict(unloaded, **{"shaft.speed": w}), stop=0.03, step=0.01, oil_temperature=temp, bearing_fmu=bearing_fmu, shaft_fmu=shaft_fmu).arrays()
            rows.append((r["reactions"][-1][0][0], r["friction"][-1].sum()))
        out["oil"][temp] = np.array(rows)
    return out


def radial(r: np.ndarray) -> float:
    return float(math.hypot(r[1], r[2]))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--stop", type=float, default=2.0)
    ap.add_argument("--step", type=float, default=0.01)
    ap.add_argument("--plot", type=Path, default=None)
    args = ap.parse_args()
    build_bearing_fmu()
    build_shaft_fmu()
    t0 = time.perf_counter()
    res = cosimulate(stop=args.stop, step=args.step).arrays()
    wall = time.perf_counter() - t0
    rA = res["reactions"][:, 0, :]
    rB = res["reactions"][:, 1, :]
    share = np.array([radial(a) / (radial(a) + radial(b)) for a, b in zip(rA, rB)])
    print(f"{len(res['time'])} steps of {args.step} s in {wall:.2f} s wall")
    print(f"largest relative equilibrium residual after the first 3 steps: {res['residual'][3:].max():.2e}")
    print(f"radial load share of bearing A: {share.min():.4f} .. {share.max():.4f}")
    print(f"axial loads: A {rA[:, 0].min():.0f} .. {rA[:, 0].max():.0f} N, B {rB[:, 0].min():.0f} .. {rB[:, 0].max():.0f} N")
    print(f"friction torque (sum): {res['friction'].sum(axis=1).min():.2f} .. {res['friction'].sum(axis=1).max():.2f} N.m")
    print(f"L10 A, B at the end: {res['l10'][-1][0]:.0f} h, {res['l10'][-1][1]:.0f} h; L10r {res['l10r'][-1][0]:.0f} h, {res['l10r'][-1][1]:.0f} h")
    speeds = [0.0, 50.0, 100.0, 200.0, 300.0, 400.0, 500.0, 600.0]
    sweep = preload_sweep(speeds, [0.0, 2.0, 5.0, 8.0], [303.15, 333.15, 363.15])
    print("preload (N) of the unloaded pair against speed", [int(w) for w in speeds], "rad/s:")
    for dT, rows in sweep["deltaT"].items():
        print(f"  shaft - housing {dT:4.1f} K: {np.round(rows[:, 0]).astype(int).tolist()}")
    for temp, rows in sweep["oil"].items():
        print(f"  oil {temp - 273.15:5.1f} degC: preload {np.round(rows[:, 0]).astype(int).tolist()}, pair friction torque {np.round(rows[:, 1], 1).tolist()} N.m")
    if args.plot:
        plot(res, sweep, args.plot)
        print(f"plot: {args.plot}")


def plot(res: dict, sweep: dict, path: Path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rA = res["reactions"][:, 0, :]
    rB = res["reactions"][:, 1, :]
    t = res["time"]
    fig, ax = plt.subplots(2, 2, figsize=(12, 8))
    ax[0, 0].plot(t, [radial(a) for a in rA], label="A radial")
    ax[0, 0].plot(t, [radial(b) for b in rB], label="B radial")
    ax[0, 0].plot(t, rA[:, 0], "--", label="A axial")
    ax[0, 0].plot(t, rB[:, 0], "--", label="B axial")
    ax[0, 0].set_ylabel("load carried (N)")
    ax[0, 0].set_xlabel("time (s)")
    ax[0, 0].set_title("load sharing under the mesh force")
    ax[0, 0].legend()
    ax[0, 1].semilogy(t, res["l10"][:, 0], label="L10 A")
    ax[0, 1].semilogy(t, res["l10"][:, 1], label="L10 B")
    ax[0, 1].semilogy(t, res["l10r"][:, 0], "--", label="L10r A")
    ax[0, 1].semilogy(t, res["l10r"][:, 1], "--", label="L10r B")
    ax[0, 1].set_ylabel("rating life (h)")
    ax[0, 1].set_xlabel("time (s)")
    ax[0, 1].set_title("lives (ISO 281, ISO/TS 16281)")
    ax[0, 1].legend()
    w = sweep["speed"]
    for dT, rows in sweep["deltaT"].items():
        ax[1, 0].plot(w, rows[:, 0], "o-", label=f"shaft - housing {dT:g} K")
    ax[1, 0].set_xlabel("speed (rad/s)")
    ax[1, 0].set_ylabel("preload (N)")
    ax[1, 0].set_title("preload of the unloaded pair")
    ax[1, 0].legend()
    for temp, rows in sweep["oil"].items():  # from the first speed > 0: at rest the breakaway torque
        ax[1, 1].plot(w[w > 0], rows[w > 0, 1], "o-", label=f"oil {temp - 273.15:g} degC")
    ax[1, 1].set_xlabel("speed (rad/s)")
    ax[1, 1].set_ylabel("friction torque of the pair (N.m)")
    ax[1, 1].set_title("friction torque of the unloaded pair")
    ax[1, 1].legend()
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)

if __name__ == "__main__":
    main()
