"""Duty-cycle aggregation over the bins of a load spectrum (pure functions).

- `miner_life(shares, lives)`: the Palmgren-Miner life of a duty cycle,
  L = 1 / sum_i (t_i / L_i), with t_i the time shares normalised to sum 1 and L_i the life at
  bin i alone (e.g. `life.L10r`, ISO/TS 16281, hours). A bin with zero share adds no damage
  whatever its life; a bin with infinite life adds none either (L = inf if no bin does).
- `time_weighted_mean(shares, values)`: sum_i t_i x_i, e.g. the mean power loss (W).

Both raise ValueError naming the bin for input they cannot use (negative or non-finite
shares, shares summing to 0, a missing or non-positive life in a bin with a share).
"""

from __future__ import annotations

import math
from collections.abc import Sequence


def normalised(shares: Sequence[float]) -> list[float]:
    """Time shares divided by their sum."""
    if not shares:
        raise ValueError("no bins")
    for i, t in enumerate(shares):
        if t is None or not math.isfinite(t) or t < 0:
            raise ValueError(f"bin {i}: time share must be a finite number >= 0, got {t!r}")
    total = math.fsum(shares)
    if total <= 0:
        raise ValueError("the time shares sum to 0")
    return [t / total for t in shares]


def miner_life(shares: Sequence[float], lives: Sequence[float | None]) -> float:
    """Palmgren-Miner life of the duty cycle (see the module docstring); same unit as lives."""
    if len(shares) != len(lives):
        raise ValueError(f"{len(shares)} time shares but {len(lives)} lives")
    t = normalised(shares)
    damage = []
    for i, (ti, li) in enumerate(zip(t, lives)):
        if ti == 0:
            continue
        if li is None or math.isnan(li) or li <= 0:
            raise ValueError(f"bin {i}: life must be a number > 0, got {li!r}")
        damage.append(ti / li)  # 0 for an infinite life
    total = math.fsum(damage)
    return math.inf if total == 0 else 1.0 / total


def time_weighted_mean(shares: Sequence[float], values: Sequence[float | None]) -> float:
    """sum_i t_i x_i with normalised time shares t_i."""
    if len(shares) != len(values):
        raise ValueError(f"{len(shares)} time shares but {len(values)} values")
    t = normalised(shares)
    terms = []
    for i, (ti, xi) in enumerate(zip(t, values)):
        if ti == 0:
            continue
        if xi is None or not math.isfinite(xi):
            raise ValueError(f"bin {i}: value must be a finite number, got {xi!r}")
        terms.append(ti * xi)
    return math.fsum(terms)
