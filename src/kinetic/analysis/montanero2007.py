"""Observers and estimators of the montanero2007 heat-flux study (DSMC samples -> numbers).

Two layers:

1. jitted *observers* that reduce one velocity snapshot ``velocities[i, j]`` (particle i,
   Cartesian component j, x = component 0, peculiar velocity V in units of the thermal
   speed v_0 = sqrt(2T/m) once multiplied by ``inv_v0``) to the per-particle averages the
   paper measures, and accumulate the histogram of c_x in the steady state;
2. numpy *estimators* that turn per-realization observations into the paper's numbers
   with error bars from independent realizations: kappa'/kappa0 (Eq. 3.9 over Eq. 2.47),
   b'_k by Eq. (3.10) and by Eq. (3.12), the odd part of the marginal g(V_x) (Eq. 3.15),
   phi(c_x^2) (Eq. 4.3) and beta_1(c_x^2) (Eq. 4.6).

Snapshot moments (index of :data:`MOMENTS`, all dimensionless, averages over particles):
``cx = <c_x>``, ``c2 = <c^2>``, ``cx2 = <c_x^2>``, ``c4 = <c^4>``, ``c2cx = <c^2 c_x>``,
``full_k = <c_x L_k^(d/2)(c^2)>`` and ``marginal_k = <c_x L_k^(1/2)(c_x^2)>`` for k = 1..3.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from kinetic.analysis.statistics import mean_and_sem
from kinetic.theory import montanero2007 as theory

__all__ = [
    "MOMENTS",
    "N_SONINE",
    "accumulate_cx_histogram",
    "b_estimates",
    "beta1_estimate",
    "beta1_ratio_estimate",
    "histogram_edges",
    "kappa_prime_estimate",
    "odd_marginal_estimate",
    "phi_estimate",
    "snapshot_moments",
    "steady_average",
]

N_SONINE = 3
MOMENTS = (
    "cx",
    "c2",
    "cx2",
    "c4",
    "c2cx",
    *(f"full_{k}" for k in range(1, N_SONINE + 1)),
    *(f"marginal_{k}" for k in range(1, N_SONINE + 1)),
)
_FULL0 = MOMENTS.index("full_1")
_MARGINAL0 = MOMENTS.index("marginal_1")


@njit(cache=True, inline="always")
def _laguerre_123(p, x):
    """``(L_1^(p)(x), L_2^(p)(x), L_3^(p)(x))`` by the explicit polynomials."""
    l1 = 1.0 + p - x
    l2 = 0.5 * (p + 1.0) * (p + 2.0) - (p + 2.0) * x + 0.5 * x * x
    l3 = (
        (p + 1.0) * (p + 2.0) * (p + 3.0) / 6.0
        - 0.5 * (p + 2.0) * (p + 3.0) * x
        + 0.5 * (p + 3.0) * x * x
        - x * x * x / 6.0
    )
    return l1, l2, l3


@njit(cache=True)
def snapshot_moments(velocities, inv_v0, out):
    """Fill ``out[m]`` with the particle average of moment ``MOMENTS[m]`` of one snapshot.

    ``velocities``: (N, d) float64 peculiar velocities (any layout; x is column 0);
    ``inv_v0``: 1 / v_0 so that c = V * inv_v0; ``out``: (len(MOMENTS),) float64,
    overwritten.  Sonine orders 1..3 with p = d/2 (Eq. 3.10) and p = 1/2 (Eq. 3.12).
    """
    n, d = velocities.shape
    p_full = 0.5 * d
    for m in range(out.shape[0]):
        out[m] = 0.0
    for i in range(n):
        cx = velocities[i, 0] * inv_v0
        c2 = 0.0
        for j in range(d):
            cj = velocities[i, j] * inv_v0
            c2 += cj * cj
        cx2 = cx * cx
        out[0] += cx
        out[1] += c2
        out[2] += cx2
        out[3] += c2 * c2
        out[4] += c2 * cx
        f1, f2, f3 = _laguerre_123(p_full, c2)
        out[5] += cx * f1
        out[6] += cx * f2
        out[7] += cx * f3
        g1, g2, g3 = _laguerre_123(0.5, cx2)
        out[8] += cx * g1
        out[9] += cx * g2
        out[10] += cx * g3
    for m in range(out.shape[0]):
        out[m] /= n


def histogram_edges(c_max: float, n_bins: int) -> np.ndarray:
    """Symmetric bin edges of c_x on [-c_max, c_max]; ``n_bins`` even so 0 is an edge."""
    if n_bins < 2 or n_bins % 2:
        raise ValueError(f"n_bins must be an even integer >= 2, got {n_bins}")
    if not c_max > 0:
        raise ValueError(f"c_max must be > 0, got {c_max}")
    return np.linspace(-c_max, c_max, n_bins + 1)


@njit(cache=True)
def accumulate_cx_histogram(velocities, inv_v0, c_max, counts, weights, outside):
    """Add one snapshot to the c_x histogram and to the beta_1 weights.

    ``counts[b]`` += number of particles with c_x in bin b of ``histogram_edges(c_max,
    len(counts))``; ``weights[b]`` += sum over them of ``c_x (3/2 - c_x^2)`` (the
    integrand of Eq. 4.6, so that beta_1 at the bin edges needs no interpolation);
    particles with |c_x| >= c_max go to ``outside[0]`` (count) and ``outside[1]`` (weight).
    """
    n = velocities.shape[0]
    n_bins = counts.shape[0]
    scale = n_bins / (2.0 * c_max)
    for i in range(n):
        cx = velocities[i, 0] * inv_v0
        w = cx * (1.5 - cx * cx)
        b = int(np.floor((cx + c_max) * scale))
        if 0 <= b < n_bins:
            counts[b] += 1.0
            weights[b] += w
        else:
            outside[0] += 1.0
            outside[1] += w


# --------------------------------------------------------------------- estimators


def steady_average(series, times, t_start: float):
    """Time average of each realization over ``times >= t_start``.

    ``series``: (..., n_times) samples (last axis is time); returns (...,).
    """
    times = np.asarray(times, dtype=float)
    mask = times >= t_start
    if mask.sum() < 1:
        raise ValueError(f"no sample at or after t_start = {t_start} (last time {times[-1]})")
    return np.asarray(series, dtype=float)[..., mask].mean(axis=-1)


def kappa_prime_estimate(c2cx, eps_star: float, d: int = 3):
    """kappa'/kappa0 (Eq. 3.9 over Eq. 2.47) from per-realization ``<c^2 c_x>``.

    ``c2cx``: (R, ...) independent realizations along axis 0.  Returns (mean, sem).
    """
    ratio = theory.kappa_prime_ratio_from_heat_flux(c2cx, eps_star, d)
    return mean_and_sem(ratio, axis=0)


def b_estimates(moments, eps_star: float, route: str, d: int = 3):
    """b'_k from per-realization averages, Eq. (3.10) (``route="full"``) or (3.12).

    ``moments``: (R, ..., K) with ``<c_x L_k(.)>`` for k = 1..K on the last axis.
    Returns (mean, sem), each (..., K).
    """
    b = theory.b_coefficients(moments, eps_star, route, d)
    return mean_and_sem(b, axis=0)


def _odd_part(counts):
    """For symmetric bins, (counts[+] - counts[-]) / 2 on the positive half (..., n/2)."""
    counts = np.asarray(counts, dtype=float)
    half = counts.shape[-1] // 2
    return 0.5 * (counts[..., half:] - counts[..., :half][..., ::-1])


def odd_marginal_estimate(counts, n_samples, edges):
    """Odd part ``g1(c_x) = [g(c_x) - g(-c_x)] / 2`` of the reduced marginal, Eq. (3.15).

    ``counts``: (R, n_bins) histogram of c_x per realization; ``n_samples``: (R,) number of
    particle observations behind each histogram; ``edges``: (n_bins + 1,) symmetric edges.
    ``g`` is the probability density of c_x (so ``g(V_x) = n / v_0 * g(c_x)``).
    Returns ``(centres, g_mean, g_sem, odd_mean, odd_sem)`` with g on every bin and the
    odd part on the bins with c_x > 0.
    """
    counts = np.asarray(counts, dtype=float)
    n_samples = np.asarray(n_samples, dtype=float)[:, None]
    widths = np.diff(edges)
    density = counts / (n_samples * widths)
    odd = _odd_part(density)
    g_mean, g_sem = mean_and_sem(density, axis=0)
    odd_mean, odd_sem = mean_and_sem(odd, axis=0)
    centres = 0.5 * (edges[1:] + edges[:-1])
    return centres, g_mean, g_sem, odd_mean, odd_sem


def phi_estimate(counts, n_samples, edges, eps_star: float):
    """phi(c_x^2) of Eq. (4.3) from the odd part of the c_x histogram, per bin c_x > 0.

    On a bin [a, b] Eq. (4.3) integrates to ``P_odd = phi eps* (e^{-a^2} - e^{-b^2}) /
    (2 sqrt(pi))`` when phi is constant on the bin, so
    ``phi = 2 sqrt(pi) P_odd / (eps* (e^{-a^2} - e^{-b^2}))`` (no division by c_x -> 0).
    Returns ``(cx2_centres, mean, sem)``: the bin centres in c_x^2 (squared centre of the
    bin in c_x) and phi over realizations.
    """
    counts = np.asarray(counts, dtype=float)
    n_samples = np.asarray(n_samples, dtype=float)[:, None]
    half = counts.shape[-1] // 2
    positive = edges[half:]
    odd_probability = _odd_part(counts / n_samples)
    gaussian_mass = np.exp(-(positive[:-1] ** 2)) - np.exp(-(positive[1:] ** 2))
    with np.errstate(divide="ignore", invalid="ignore"):
        phi = 2.0 * np.sqrt(np.pi) * odd_probability / (eps_star * gaussian_mass)
    mean, sem = mean_and_sem(phi, axis=0)
    centres = 0.5 * (positive[1:] + positive[:-1])
    return centres**2, mean, sem


def _cumulative_folded(weights):
    """Fold signed-bin sums onto |c_x| and accumulate from 0: (half, (R, half + 1))."""
    weights = np.asarray(weights, dtype=float)
    half = weights.shape[-1] // 2
    folded = weights[..., half:] + weights[..., :half][..., ::-1]
    zero = np.zeros((*folded.shape[:-1], 1))
    return half, np.concatenate([zero, np.cumsum(folded, axis=-1)], axis=-1)


def beta1_estimate(weights, outside_weight, n_samples, edges, eps_star: float):
    """beta_1(c_x^2) of Eq. (4.6) at the bin edges c_x^2 = e^2, e >= 0, and its limit b'_1.

    beta_1(X) = 4/(3 eps*) <c_x (3/2 - c_x^2) 1[c_x^2 < X]> (Eq. 4.6 rewritten with
    Eq. 4.3, see :func:`kinetic.theory.montanero2007.beta1`).  ``weights``: (R, n_bins)
    sums of c_x (3/2 - c_x^2) per c_x bin; ``outside_weight``: (R,) the same beyond the
    histogram; ``n_samples``: (R,).  Returns ``(cx2_edges, mean, sem, b1_mean, b1_sem)``
    where b1 (all particles, the k = 1 marginal route) normalises Fig. 7's ratio.
    """
    n_samples = np.asarray(n_samples, dtype=float)
    half, cumulative = _cumulative_folded(weights)
    per_realization = 4.0 / (3.0 * eps_star) * cumulative / n_samples[:, None]
    total = 4.0 / (3.0 * eps_star) * (cumulative[:, -1] + np.asarray(outside_weight)) / n_samples
    mean, sem = mean_and_sem(per_realization, axis=0)
    b1_mean, b1_sem = mean_and_sem(total, axis=0)
    return edges[half:] ** 2, mean, sem, b1_mean, b1_sem


def beta1_ratio_estimate(weights, outside_weight, n_samples, edges, eps_star: float):
    """Fig. 7: beta_1(c_x^2) / b'_1 per realization ratio of sums, mean and sem.

    The ratio is formed from the realization-averaged numerator and denominator
    (a ratio of means, error by first-order propagation with their covariance), which is
    unbiased to O(1/R) unlike a mean of per-realization ratios when b'_1 is noisy.
    Returns ``(cx2_edges, ratio, ratio_sem)``.
    """
    n_samples = np.asarray(n_samples, dtype=float)
    half, cumulative = _cumulative_folded(weights)
    numerator = cumulative / n_samples[:, None]
    denominator = (cumulative[:, -1] + np.asarray(outside_weight)) / n_samples
    r = numerator.shape[0]
    num_mean = numerator.mean(axis=0)
    den_mean = denominator.mean()
    ratio = num_mean / den_mean
    # delta method: var(N/D) ~ [var N - 2 ratio cov(N, D) + ratio^2 var D] / (D^2 R)
    dn = numerator - num_mean
    dd = (denominator - den_mean)[:, None]
    var_n = (dn**2).sum(axis=0) / (r - 1)
    var_d = (dd**2).sum(axis=0) / (r - 1)
    cov = (dn * dd).sum(axis=0) / (r - 1)
    variance = (var_n - 2 * ratio * cov + ratio**2 * var_d) / (den_mean**2 * r)
    return edges[half:] ** 2, ratio, np.sqrt(np.maximum(variance, 0.0))
