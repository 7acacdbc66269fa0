"""Estimators of the cloning Monte Carlo: μ(λ), T(λ), a2(λ) with error bars, and the
extrapolation of finite-population results to 1/N_c → 0.

From one realization's measured blocks (after the discarded transient), with n members, d
dimensions, total measured time t and the block sums of ``kernels.BLOCK_FIELDS``:

- μ = (duplications - annihilations) / (n t): minus (plus) the compensation rate;
- m2 = ∫Σ|v|² dt / (n t), m4 = ∫Σ|v|⁴ dt / (n t): time averages of the population's
  moments, i.e. moments of the eigenfunction f̃(v, λ) of visco2008 Eq. (28);
- T = m2 / d: the variance per component (the mean vanishes by isotropy, so it is not
  subtracted; subtracting the sample mean would add an O(1/n) bias);
- a2 = d/(d+2) · m4/m2² - 1, from m4 = d(d+2) T² (1 + a2) (Eq. 49);
- μ_rate = (e^{-λ} - 1) ∫Σ r(|v_i|) dt / (n t): integrating Eq. (28) over v gives
  μ = (e^{-λ} - 1) <r>_f̃, and in the algorithm the compensations are a counting process
  with intensity |e^{-λ} - 1| Σ r(|v_i|), so both estimators have the same expectation
  (the same finite-n bias) and μ_rate lacks the counting noise (its error bar is several
  times smaller at small |λ|). ``mu`` stays the compensation rate of the paper.

Values and error bars: every estimate is its formula applied to the measured sums of
all realizations together, and its error the jackknife over the realizations (leave
one out), or over groups of a single realization's measured blocks. Averaging the
realizations' own values instead (until 2026-12-01) kept the bias of the ratio m4/m2²
of one realization's length, O(Var m2/m2²), which more realizations do not reduce; for
μ, T and μ_rate, ratios of sums over equal member-times, both give the same value and
error.
"""

from __future__ import annotations

import math

import numpy as np

from kinetic.analysis.statistics import LineFit, jackknife, weighted_line

__all__ = [
    "Extrapolation",
    "extrapolate_population",
    "observables_from_sums",
    "realization_observables",
    "summarize_realizations",
]


def observables_from_sums(sums, population, dimension, lam):
    """μ, T, a2, μ_rate from block sums ``sums[..., field]`` (fields in
    ``kernels.BLOCK_FIELDS``), elementwise over the leading axes."""
    from kinetic.cloning.kernels import BLOCK_FIELDS

    sums = np.asarray(sums, dtype=float)

    def field(name):
        return sums[..., BLOCK_FIELDS.index(name)]

    member_time = population * field("elapsed_time")
    mu = field("net_compensations") / member_time
    m2 = field("integral_v2") / member_time
    m4 = field("integral_v4") / member_time
    temperature = m2 / dimension
    a2 = dimension / (dimension + 2.0) * m4 / m2**2 - 1.0
    mu_rate = np.expm1(-lam) * field("integral_rate") / member_time
    return mu, temperature, a2, mu_rate


def realization_observables(blocks, measured, population, dimension, lam):
    """Per-realization μ, T, a2, μ_rate from ``blocks`` of shape (realization, block,
    field) summed over the blocks where ``measured`` is true."""
    kept = np.asarray(blocks)[:, np.asarray(measured, dtype=bool), :].sum(axis=1)
    return observables_from_sums(kept, population, dimension, lam)


def summarize_realizations(blocks, measured, population, dimension, lam, n_error_blocks=10):
    """μ, T, a2, μ_rate of all realizations' measured blocks together, with their
    jackknife errors over the realizations (or over groups of a single realization's
    measured blocks).

    Returns a dict with keys ``mu``, ``mu_err``, ``temperature``, ``temperature_err``,
    ``a2``, ``a2_err``, ``mu_rate``, ``mu_rate_err`` and ``error_method``
    ('realizations' or 'blocks'; a single realization's measured blocks are grouped into
    ``n_error_blocks`` nearly equal groups, every block counted).
    """
    blocks = np.asarray(blocks, dtype=float)
    measured = np.asarray(measured, dtype=bool)
    if blocks.shape[0] >= 2:
        samples = blocks[:, measured, :].sum(axis=1)
        method = "realizations"
    else:
        series = blocks[0, measured, :]
        groups = min(n_error_blocks, series.shape[0])
        if groups < 2:
            raise ValueError("need at least 2 realizations or 2 measured blocks for an error bar")
        samples = np.stack([part.sum(axis=0) for part in np.array_split(series, groups)])
        method = "blocks"

    def statistic(mean: np.ndarray) -> np.ndarray:
        return np.array(observables_from_sums(mean, population, dimension, lam))

    # a mean of the sums is their total over the count: the ratios are the same
    values, errors = jackknife(samples, statistic)
    summary: dict = {"error_method": method}
    for name, value, error in zip(
        ("mu", "temperature", "a2", "mu_rate"), values, errors, strict=True
    ):
        summary[name], summary[f"{name}_err"] = float(value), float(error)
    return summary


Extrapolation = LineFit
"""An extrapolation to 1/N_c → 0 (:func:`extrapolate_population`): the weighted straight
line y = intercept + slope / N_c of ``statistics.weighted_line``, whose
``intercept_err``, ``slope_err`` and ``covariance`` (cov(intercept, slope), for the line's
error band) are multiplied by the Birge ratio sqrt(chi2/dof) when that exceeds 1 (the
covariance by its square), so an imperfect 1/N_c law widens the error bar instead of
hiding it."""


def extrapolate_population(population_sizes, values, errors) -> Extrapolation:
    """Extrapolate finite-population estimates to 1/N_c → 0 by a weighted linear fit.

    ``population_sizes``, ``values`` and ``errors`` are 1-D sequences of equal length
    (at least 2 distinct sizes, errors finite and > 0: an infinite one gave a zero weight
    and, with one size left, a singular fit).
    """
    n_c = np.asarray(population_sizes, dtype=float)
    if n_c.ndim == 1 and np.unique(n_c).size < 2:
        raise ValueError(f"need at least 2 distinct population sizes, got {n_c.tolist()}")
    fit = weighted_line(1.0 / n_c, values, errors)
    birge = fit.chi2 / fit.dof if fit.dof > 0 and fit.chi2 > fit.dof else 1.0
    return fit._replace(
        intercept_err=fit.intercept_err * math.sqrt(birge),
        slope_err=fit.slope_err * math.sqrt(birge),
        covariance=fit.covariance * birge,
    )
