"""Maps of a grid sweep with matplotlib: a results column over two grid variables.

`draw_map(rows, plot, units, path)` draws filled contours of `z` over `x` and `y` (the
cases that did not finish `ok` are left blank) with the case points marked (black dots; red crosses where a case is not `ok`), and writes an
SVG, PNG or PDF (by the file's suffix).
"""

from __future__ import annotations

import math
from pathlib import Path


def _label(name: str, unit: str | None) -> str:
    return f"{name} [{unit}]" if unit and unit != "1" else name


def draw_map(rows: list[dict], plot: dict, units: dict, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    x, y, z = plot["x"], plot["y"], plot["z"]
    xs = sorted({r[x] for r in rows})
    ys = sorted({r[y] for r in rows})
    grid = np.full((len(ys), len(xs)), np.nan)
    for r in rows:
        v = r.get(z)
        if r.get("status") == "ok" and v is not None and math.isfinite(v):
            grid[ys.index(r[y]), xs.index(r[x])] = v
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    data = np.ma.masked_invalid(grid)
    if data.count() >= 2 and np.nanmax(grid) > np.nanmin(grid):
        cs = ax.contourf(xs, ys, data, levels=12, cmap="viridis")
        fig.colorbar(cs, ax=ax, label=_label(z, units.get(z)))
    X, Y = np.meshgrid(xs, ys)
    ok = ~np.isnan(grid)
    ax.plot(X[ok], Y[ok], "k.", ms=3, clip_on=False)
    if (~ok).any():
        ax.plot(X[~ok], Y[~ok], "rx", ms=6, clip_on=False, label="case not ok")
        ax.legend(loc="upper right", fontsize="small")
    ax.set_xlabel(_label(x, units.get(x)))
    ax.set_ylabel(_label(y, units.get(y)))
    ax.set_title(plot.get("title", f"{z} over {x} and {y}"), fontsize="medium")
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path)
    plt.close(fig)
    return path
