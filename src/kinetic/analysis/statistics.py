"""Means, standard errors and cumulants with error bars.

Every simulated number that reaches a figure or table carries a standard error: either
from independent realizations (``mean_and_sem`` over the realization axis) or, for one
correlated time series, from block averages (``block_sem``).
"""

from __future__ import annotations

import numpy as np

__all__ = ["block_sem", "count_cumulants", "mean_and_sem"]


def mean_and_sem(samples, axis: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Mean and standard error of the mean of independent samples along ``axis``.

    Needs at least two samples; the standard error uses the unbiased variance.
    """
    samples = np.asarray(samples, dtype=float)
    count = samples.shape[axis]
    if count < 2:
        raise ValueError(f"need at least 2 independent samples for an error bar, got {count}")
    mean = samples.mean(axis=axis)
    sem = samples.std(axis=axis, ddof=1) / np.sqrt(count)
    return mean, sem


def block_sem(series, n_blocks: int = 20) -> tuple[float, float]:
    """Mean and standard error of a correlated time series from ``n_blocks`` block means.

    Blocks must be longer than the correlation time for the error to be honest; the
    caller chooses ``n_blocks`` accordingly (10 to 50 is usual).
    """
    series = np.asarray(series, dtype=float)
    if n_blocks < 2 or series.size < n_blocks:
        raise ValueError(f"cannot cut {series.size} samples into {n_blocks} blocks")
    usable = series.size - series.size % n_blocks
    blocks = series[:usable].reshape(n_blocks, -1).mean(axis=1)
    return mean_and_sem(blocks)


def count_cumulants(counts, axis: int = -1) -> np.ndarray:
    """First three cumulants of integer counts along ``axis``.

    Returns an array whose first axis is the cumulant order p = 1, 2, 3 (the mean, the
    variance and the third central moment, all with plain 1/n normalisation).
    """
    counts = np.asarray(counts, dtype=float)
    mean = counts.mean(axis=axis, keepdims=True)
    centred = counts - mean
    second = (centred**2).mean(axis=axis)
    third = (centred**3).mean(axis=axis)
    return np.stack([np.squeeze(mean, axis=axis), second, third])
