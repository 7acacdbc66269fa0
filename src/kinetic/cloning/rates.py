"""Table of the collision rate of one member, r(v)/ω, for the kernels' mean-rate estimator.

Hard spheres: visco2008 Eq. (6) from ``kinetic.theory.visco2008.collision_rate``
(T0 = 1, ω = 1, Kummer-transformed so large speeds do not overflow). Maxwell molecules:
r(v) = 1. The kernels interpolate linearly between the tabulated speeds.
"""

from __future__ import annotations

import numpy as np

from kinetic.theory.visco2008 import collision_rate

__all__ = ["TABLE_MAX_SPEED", "TABLE_STEP", "collision_rate", "rate_table"]

TABLE_STEP = 1.0 / 256.0
"""Speed spacing of the kernels' rate table (linear interpolation error < 1e-6)."""
TABLE_MAX_SPEED = 16.0
"""Last tabulated speed; beyond it the kernels extrapolate linearly (r ~ K1 v)."""


def rate_table(kernel: str, dimension: int) -> np.ndarray:
    """r(k · TABLE_STEP) for k = 0 .. TABLE_MAX_SPEED/TABLE_STEP (float64, C order)."""
    speeds = np.arange(0.0, TABLE_MAX_SPEED + 0.5 * TABLE_STEP, TABLE_STEP)
    if kernel == "maxwell":
        return np.ones_like(speeds)
    return np.ascontiguousarray(collision_rate(speeds, dimension), dtype=float)
