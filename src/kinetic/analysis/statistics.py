"""Means, standard errors and cumulants with error bars; error against CPU time.

Every simulated number that reaches a figure or table carries a standard error: either
from independent realizations (``mean_and_sem`` over the realization axis) or, for one
correlated time series, from block averages (``block_sem``). Every document's
error-against-run-time study draws the error of an estimate made from parts of its data
against the CPU time those parts cost (``error_against_cpu``), and asks what CPU time a
target error would take (``cpu_for_error``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import NamedTuple

import numpy as np

__all__ = [
    "ErrorCurve",
    "LineFit",
    "block_sem",
    "chi2_per_dof",
    "count_cumulants",
    "cpu_for_error",
    "error_against_cpu",
    "jackknife",
    "line_error",
    "mean_and_sem",
    "weighted_line",
]


def chi2_per_dof(values, errors, expected) -> tuple[float, int]:
    """χ²/dof of ``values`` with standard ``errors`` against ``expected`` over the entries
    where both the expectation and a positive error exist: ``(Σ z²/n, n)`` with
    z = (value − expected)/error (NaN for no entry)."""
    values, errors, expected = (np.asarray(a, dtype=float) for a in (values, errors, expected))
    expected = np.broadcast_to(expected, values.shape)
    used = np.isfinite(expected) & (errors > 0)
    count = int(used.sum())
    if count == 0:
        return float("nan"), 0
    z = (values[used] - expected[used]) / errors[used]
    return float(np.sum(z**2) / count), count


class LineFit(NamedTuple):
    """A weighted straight line y = intercept + slope x (:func:`weighted_line`)."""

    intercept: float
    intercept_err: float
    slope: float
    slope_err: float
    covariance: float
    """cov(intercept, slope): with the errors, the line's error at any x (:func:`line_error`)"""
    chi2: float
    dof: int


def weighted_line(x, y, errors) -> LineFit:
    """Least-squares line through ``y`` (standard ``errors``, finite and > 0) at ``x`` (at
    least two distinct values), weighted by 1/error²: the coefficients, their errors and
    covariance from the inverse normal matrix (no Birge factor: the callers choose),
    χ² and dof = len(x) - 2. The one fit of every extrapolation in 1/N (costantini2010's
    transport coefficients, the cloning populations of visco2008)."""
    x, y, sigma = (np.asarray(a, dtype=float) for a in (x, y, errors))
    if not (x.shape == y.shape == sigma.shape and x.ndim == 1):
        raise ValueError("x, y and errors must be 1-D and of equal length")
    if np.unique(x).size < 2:
        raise ValueError(f"need at least 2 distinct x for a line, got {x.tolist()}")
    if not (np.all(np.isfinite(y)) and np.all(np.isfinite(sigma) & (sigma > 0))):
        raise ValueError("values must be finite and errors finite and > 0 for a weighted fit")
    w = 1.0 / sigma**2
    s, sx, sxx = w.sum(), (w * x).sum(), (w * x * x).sum()
    sy, sxy = (w * y).sum(), (w * x * y).sum()
    det = s * sxx - sx * sx
    intercept = (sxx * sy - sx * sxy) / det
    slope = (s * sxy - sx * sy) / det
    return LineFit(
        intercept=float(intercept),
        intercept_err=float(np.sqrt(sxx / det)),
        slope=float(slope),
        slope_err=float(np.sqrt(s / det)),
        covariance=float(-sx / det),
        chi2=float((w * (y - intercept - slope * x) ** 2).sum()),
        dof=int(x.size - 2),
    )


def line_error(x, intercept_err, slope_err, covariance):
    """Standard error of a fitted line a + b x at ``x`` from the errors of a and b and
    their ``covariance``: √(σ_a² + 2x cov + x² σ_b²) (clipped at 0 against round-off).
    For points at x > 0 the covariance is negative, so the band is narrowest inside the
    data and widens toward x = 0, where it is σ_a."""
    x = np.asarray(x, dtype=float)
    variance = intercept_err**2 + 2.0 * x * covariance + (x * slope_err) ** 2
    return np.sqrt(np.clip(variance, 0.0, None))


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


def error_of_sem(sem, samples):
    """The standard error of a standard error estimated from ``samples`` independent
    (Gaussian) samples, SE/√(2(n − 1)): the error bar of a point of an error-against-run-
    time curve."""
    samples = np.asarray(samples, dtype=float)
    return np.asarray(sem, dtype=float) / np.sqrt(2.0 * np.maximum(samples - 1.0, 1.0))


def jackknife(values, statistic: Callable) -> tuple[np.ndarray, np.ndarray]:
    """``statistic`` of the mean over the first axis of ``values`` and its jackknife error.

    ``statistic`` maps a mean (``values.shape[1:]``) to a float array; returns
    (estimate, standard error) as arrays of the statistic's shape.
    """
    values = np.asarray(values, dtype=float)
    count = values.shape[0]
    if count < 2:
        raise ValueError(f"a jackknife needs at least 2 blocks, got {count}")
    estimate = np.asarray(statistic(values.mean(axis=0)), dtype=float)
    total = values.sum(axis=0)
    leave_one_out = np.array(
        [statistic((total - values[i]) / (count - 1)) for i in range(count)], dtype=float
    )
    spread = leave_one_out - leave_one_out.mean(axis=0)
    error = np.sqrt((count - 1) / count * np.sum(spread**2, axis=0))
    return estimate, error


def ratio_and_sem(numerators, denominators) -> tuple[float, float]:
    """The pooled ratio R = Σa/Σb of independent samples (a_i, b_i) and its standard error
    by the delta method, √(Σ(a_i − R b_i)²/(n(n − 1)))/mean(b); the error is NaN for fewer
    than two samples."""
    a = np.asarray(numerators, dtype=float).ravel()
    b = np.asarray(denominators, dtype=float).ravel()
    ratio = float(a.sum() / b.sum()) if b.sum() > 0 else float("nan")
    if a.size < 2 or not np.isfinite(ratio):
        return ratio, float("nan")
    residual = a - ratio * b
    sem = float(np.sqrt(np.sum(residual**2) / (a.size * (a.size - 1))) / b.mean())
    return ratio, sem


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


class ErrorCurve(NamedTuple):
    """Estimates from parts of the data against what the parts cost: one row per part."""

    part: np.ndarray  # the parts kept (whatever ``error_against_cpu`` was given)
    cpu_seconds: np.ndarray  # CPU time of each part
    value: np.ndarray  # (parts, ...) estimates
    error: np.ndarray  # (parts, ...) their standard errors

    def error_of(self, k: int) -> np.ndarray:
        """Standard errors of the k-th estimate along the curve (empty for an empty curve)."""
        return self.error[:, k] if self.part.size else np.empty(0)


def error_against_cpu(
    parts: Iterable,
    estimate: Callable[[object], tuple[np.ndarray, np.ndarray] | None],
    cpu_seconds: Callable[[object], float],
) -> ErrorCurve:
    """The error-against-run-time curve of an estimate.

    ``parts`` names growing (or shrinking) parts of the data: the first k blocks of every
    realization, the first k realizations, a checkpoint. ``estimate(part)`` returns the
    estimates and their standard errors from that part alone, or ``None`` where the part is
    too small for an error bar (the curve stops there); ``cpu_seconds(part)`` the CPU time
    the part cost.
    """
    kept, cpu, values, errors = [], [], [], []
    for part in parts:
        result = estimate(part)
        if result is None:
            break
        kept.append(part)
        cpu.append(float(cpu_seconds(part)))
        values.append(np.asarray(result[0], dtype=float))
        errors.append(np.asarray(result[1], dtype=float))
    return ErrorCurve(np.array(kept), np.array(cpu), np.array(values), np.array(errors))


def cpu_for_error(cpu_seconds, error, target, bias=0.0):
    """CPU time at which a standard error ``error`` measured after ``cpu_seconds``, falling
    as 1/√(CPU time), brings the total error √(σ² + b²) down to ``target``, with a bias b
    that more statistics do not remove: C σ² / (E² − b²); infinite where |b| ≥ E."""
    margin = np.square(target) - np.square(bias)
    with np.errstate(divide="ignore"):
        needed = np.where(margin > 0, cpu_seconds * np.square(error) / margin, np.inf)
    return float(needed) if needed.ndim == 0 else needed
