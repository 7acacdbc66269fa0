"""Collision rate of one member, r(v)/ω (visco2008 Eq. 6), and its table for the kernels.

Hard spheres, T0 = 1, ω = 1, with Kummer's transformation e^{-x} 1F1(a, b, x) =
1F1(b - a, b, -x) applied to the second term (SPEC §1), so large speeds do not overflow:

    r(v) = [v²/d · 1F1(1/2, 1 + d/2, -v²/2) + 1F1(1/2, d/2, -v²/2)] / √2.

Maxwell molecules: r(v) = 1.
"""

from __future__ import annotations

import numpy as np
from scipy.special import hyp1f1

__all__ = ["TABLE_MAX_SPEED", "TABLE_STEP", "collision_rate", "rate_table"]

TABLE_STEP = 1.0 / 256.0
"""Speed spacing of the kernels' rate table (linear interpolation error < 1e-6)."""
TABLE_MAX_SPEED = 16.0
"""Last tabulated speed; beyond it the kernels extrapolate linearly (r ~ K1 v)."""


def collision_rate(speed, dimension):
    """r(v)/ω of a hard sphere of speed ``speed`` (array-like, units √(T0/m)) in d dims."""
    x = 0.5 * np.asarray(speed, dtype=float) ** 2
    d = float(dimension)
    return (2.0 * x / d * hyp1f1(0.5, 1.0 + d / 2.0, -x) + hyp1f1(0.5, d / 2.0, -x)) / np.sqrt(2.0)


def rate_table(kernel: str, dimension: int) -> np.ndarray:
    """r(k · TABLE_STEP) for k = 0 .. TABLE_MAX_SPEED/TABLE_STEP (float64, C order)."""
    speeds = np.arange(0.0, TABLE_MAX_SPEED + 0.5 * TABLE_STEP, TABLE_STEP)
    if kernel == "maxwell":
        return np.ones_like(speeds)
    return np.ascontiguousarray(collision_rate(speeds, dimension))
