"""Campbell diagram and critical speeds of a rotor on two TRBs (examples/rotordynamics/README.md).

    .venv/bin/python examples/rotordynamics/rotor.py [--fmu PATH] [--preload N] [--rpm MIN MAX N]
                                                    [--damping N_S_PER_M] [--out PATH]

The bearing FMU (target/fmu/TaperedRollerBearing.fmu, `cargo run --release -- fmu`) gives the
5x5 tangent stiffness at each speed, in force causality: axial preload `--preload` (N) and the
radial load = half the rotor's weight (downwards, FMU -z = ROSS -y). Both bearings get that
matrix (mirroring the second one, x -> -x, leaves the radial block and the axial diagonal used
here unchanged). ROSS computes the Campbell diagram; the script prints the critical speeds
(crossings with 1x), the same with rigid supports, the gravity sag check, and what is dropped
(the tilt block), and writes the plot (default target/rotordynamics/campbell.svg).
"""

from __future__ import annotations

import argparse
import math
import warnings
from pathlib import Path

import numpy as np

from trb import rotordynamics as rd

REPO = Path(__file__).resolve().parents[2]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fmu", default=str(REPO / "target" / "fmu" / "TaperedRollerBearing.fmu"))
    ap.add_argument("--preload", type=float, default=10e3, help="axial load Fx of each bearing (N)")
    ap.add_argument("--rpm", type=float, nargs=3, default=[500, 6000, 23], metavar=("MIN", "MAX", "N"))
    ap.add_argument("--damping", type=float, default=0.0, help="radial damping cxx = cyy of each bearing (N s/m)")
    ap.add_argument("--out", default=str(REPO / "target" / "rotordynamics" / "campbell.svg"))
    a = ap.parse_args(argv)

    rpm = np.linspace(a.rpm[0], a.rpm[1], int(a.rpm[2]))
    speeds = rpm * 2 * math.pi / 60
    W = rd.rotor_weight_share()
    K = rd.bearing_stiffness(a.fmu, speeds, Fx=a.preload, Fz=-W)
    np.set_printoptions(precision=4, linewidth=140)
    print(f"operating point: Fx = {a.preload:.0f} N, Fz = {-W:.1f} N (half the rotor weight)")
    print(f"FMU stiffness at {rpm[0]:.0f} rpm (N/m, N, N m/rad; q = x, y, z, xi, zeta):\n{K[0]}")
    kt = K[:, 3:, 3:] - K[:, 3:, :3] @ np.linalg.solve(K[:, :3, :3], K[:, :3, 3:])
    print(f"radial kyy, kzz: {K[0, 1, 1]:.4g} .. {K[-1, 1, 1]:.4g}, {K[0, 2, 2]:.4g} .. {K[-1, 2, 2]:.4g} N/m "
          f"({rpm[0]:.0f} .. {rpm[-1]:.0f} rpm); axial {K[0, 0, 0]:.4g} N/m")
    print(f"dropped: condensed tilt stiffness (translations free) {kt[0, 0, 0]:.4g} N m/rad per bearing")

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rotor = rd.build_rotor(lambda n: rd.ross_bearing(n, K, speeds, a.damping, tag="TRB left"),
                               lambda n: rd.ross_bearing(n, K, speeds, a.damping, tag="TRB right"))
        uy, F = rd.gravity_sag(rotor)
        print(f"gravity sag: bearings {uy[0] * 1e6:.4f} um (W/2 / kzz = {-W / K[0, 2, 2] * 1e6:.4f} um), "
              f"mid-span {uy.min() * 1e6:.2f} um; bearing forces {F[0]:.1f}, {F[1]:.1f} N")
        camp = rd.campbell(rotor, speeds)
        crits = rd.critical_speeds(speeds, camp.wd)

        rigid = rd.build_rotor(lambda n: rd.ross_bearing(n, 1e13 * np.eye(5)[None], [0.0]),
                               lambda n: rd.ross_bearing(n, 1e13 * np.eye(5)[None], [0.0]))
        crits_rigid = rd.critical_speeds(speeds, rd.campbell(rigid, speeds).wd)
    for name, cs in (("FMU bearings", crits), ("rigid supports", crits_rigid)):
        print(f"critical speeds, {name}: " + ", ".join(f"{s * 60 / (2 * math.pi):.1f} rpm (mode {m})" for s, m in cs))
    rd.plot_campbell(a.out, speeds, camp.wd, crits,
                     title=f"Rotor on two TRB130x230, preload {a.preload / 1e3:.0f} kN (ROSS, FMU stiffness)")
    print(f"wrote {a.out}")
    return crits


if __name__ == "__main__":
    main()
