"""Estimators of the montanero2007 heat-flux study: DSMC samples -> numbers with error bars.

Inputs are the window averages and histograms of :func:`kinetic.dsmc.simulate_homogeneous`
(velocities c = V/v0, time in τ, field ε*).  Every estimate comes with the standard
error from independent realizations (axis 0 of every per-realization array):

- kappa'/kappa0 from the heat flux (Eq. 3.9 over Eq. 2.47);
- b'_k, k = 1..3, by Eq. (3.10) (``full``: <c_x L_k^(3/2)(c^2)>) and by Eq. (3.12)
  (``marginal``: <c_x L_k^(1/2)(c_x^2)>), and their paired difference;
- the odd part of the marginal g(V_x) (Eq. 3.15), phi(c_x^2) (Eq. 4.3), the truncated
  series phi_p (Eq. 4.5) with the measured b'_k, and beta_1(c_x^2)/b'_1 (Eq. 4.6);
- a2 (Eq. 2.13), the thermostat rate, and the exactness of the thermostat.

Array-level functions take numpy arrays; ``*_of`` functions take a run's dataset.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Sequence
from typing import Any

import numpy as np

from kinetic.analysis import checks as check
from kinetic.analysis.checks import Check, tolerance_factor
from kinetic.analysis.statistics import cpu_for_error, mean_and_sem
from kinetic.io import parameters_of
from kinetic.theory import montanero2007 as theory

__all__ = [
    "FIELD_EVEN_KEYS",
    "N_SONINE",
    "b_estimates",
    "beta1_estimate",
    "beta1_ratio_estimate",
    "checks",
    "departure_from_linear_response",
    "distributions_of",
    "error_budget",
    "extrapolated_b3_over_b2",
    "field_extrapolation",
    "kappa_prime_estimate",
    "linear_response_fit",
    "load_runs",
    "odd_marginal_estimate",
    "particle_number_bias",
    "phi_estimate",
    "rebin",
    "rows_with_field_bias",
    "steady_average",
    "steady_summary_of",
    "summary_row",
    "time_series_of",
    "time_step_bias_fit",
    "tolerance_factor",
]

N_SONINE = 3
ROUTES = ("full", "marginal")


# ------------------------------------------------------------------- array level


def steady_average(series, times, t_start: float):
    """Time average of each realization over the windows with ``times >= t_start``.

    ``series``: (..., n_times) (last axis is time); returns (...,).
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


def rebin(counts, edges, factor: int):
    """Merge ``factor`` adjacent bins (symmetric about 0: the positive half is merged
    outward from 0).  ``counts``: (..., n_bins); returns (counts, edges)."""
    counts = np.asarray(counts)
    n_bins = counts.shape[-1]
    half = n_bins // 2
    if factor < 1 or half % factor:
        raise ValueError(f"rebin factor {factor} must divide the {half} bins of each half")
    positive = counts[..., half:].reshape(*counts.shape[:-1], half // factor, factor).sum(-1)
    negative = counts[..., :half][..., ::-1]
    negative = negative.reshape(*counts.shape[:-1], half // factor, factor).sum(-1)[..., ::-1]
    positive_edges = edges[half::factor]
    new_edges = np.concatenate([-positive_edges[:0:-1], positive_edges])
    return np.concatenate([negative, positive], axis=-1), new_edges


def _odd_part(values):
    """For symmetric bins, (values[+c] - values[-c]) / 2 on the positive half (..., n/2)."""
    values = np.asarray(values, dtype=float)
    half = values.shape[-1] // 2
    return 0.5 * (values[..., half:] - values[..., :half][..., ::-1])


def odd_marginal_estimate(counts, n_samples, edges):
    """Marginal density g(c_x) and its odd part ``[g(c_x) - g(-c_x)] / 2`` (Eq. 3.15).

    ``counts``: (R, n_bins) histogram of c_x per realization (symmetric ``edges``,
    (n_bins + 1,)); ``n_samples``: (R,) particle observations behind each histogram.
    g is the probability density of c_x (``g(V_x) = n g(c_x) / v0``).  Returns
    ``(centres, g_mean, g_sem, odd_mean, odd_sem)``, the odd part on the bins c_x > 0.
    """
    counts = np.asarray(counts, dtype=float)
    n_samples = np.asarray(n_samples, dtype=float)[:, None]
    density = counts / (n_samples * np.diff(edges))
    g_mean, g_sem = mean_and_sem(density, axis=0)
    odd_mean, odd_sem = mean_and_sem(_odd_part(density), axis=0)
    return 0.5 * (edges[1:] + edges[:-1]), g_mean, g_sem, odd_mean, odd_sem


def phi_estimate(counts, n_samples, edges, eps_star: float):
    """phi(c_x^2) of Eq. (4.3) from the odd part of the c_x histogram, per bin c_x > 0.

    On a bin [a, b], Eq. (4.3) integrates to ``P_odd = phi eps* (e^{-a^2} - e^{-b^2}) /
    (2 sqrt(pi))`` if phi is constant on the bin, so
    ``phi = 2 sqrt(pi) P_odd / (eps* (e^{-a^2} - e^{-b^2}))`` (no division by c_x -> 0).
    That is the mean of phi over the bin with the weight c_x e^{-c_x^2}, so the value is
    placed at the weighted mean of c_x^2, ``[(a^2+1) e^{-a^2} - (b^2+1) e^{-b^2}] /
    (e^{-a^2} - e^{-b^2})``: exact for phi linear in c_x^2, whatever the bin width.
    Returns ``(cx2, mean, sem)``.
    """
    counts = np.asarray(counts, dtype=float)
    n_samples = np.asarray(n_samples, dtype=float)[:, None]
    half = counts.shape[-1] // 2
    positive = edges[half:]
    odd_probability = _odd_part(counts / n_samples)
    gaussian_mass = np.exp(-(positive[:-1] ** 2)) - np.exp(-(positive[1:] ** 2))
    phi = 2.0 * np.sqrt(np.pi) * odd_probability / (eps_star * gaussian_mass)
    mean, sem = mean_and_sem(phi, axis=0)
    low, high = positive[:-1] ** 2, positive[1:] ** 2
    weighted = ((low + 1) * np.exp(-low) - (high + 1) * np.exp(-high)) / gaussian_mass
    return weighted, mean, sem


def _beta1_per_realization(counts, n_samples, edges, eps_star):
    """beta_1 at the positive edges, per realization: (R, n_bins/2 + 1).

    beta_1(X) = 4/(3 eps*) <c_x (3/2 - c_x^2) 1[c_x^2 < X]> (Eq. 4.6 rewritten with
    Eq. 4.3), the weight taken at each bin's centre.
    """
    counts = np.asarray(counts, dtype=float)
    centres = 0.5 * (edges[1:] + edges[:-1])
    weights = counts * centres * (1.5 - centres**2)
    half = weights.shape[-1] // 2
    folded = weights[..., half:] + weights[..., :half][..., ::-1]
    zero = np.zeros((*folded.shape[:-1], 1))
    cumulative = np.concatenate([zero, np.cumsum(folded, axis=-1)], axis=-1)
    return 4.0 / (3.0 * eps_star) * cumulative / np.asarray(n_samples, dtype=float)[:, None]


def beta1_estimate(counts, n_samples, edges, eps_star: float):
    """beta_1(c_x^2) of Eq. (4.6) at the bin edges c_x^2 = e^2 (e >= 0): (cx2, mean, sem).

    Bin-centre quadrature of the weight c_x (3/2 - c_x^2): relative error
    O((bin width)^2).  Tends to b'_1 (marginal route, k = 1) beyond the histogram.
    """
    per_realization = _beta1_per_realization(counts, n_samples, edges, eps_star)
    mean, sem = mean_and_sem(per_realization, axis=0)
    half = np.asarray(counts).shape[-1] // 2
    return edges[half:] ** 2, mean, sem


def beta1_ratio_estimate(counts, n_samples, edges, b1, eps_star: float):
    """Fig. 7: beta_1(c_x^2) / b'_1 as a ratio of realization means, with its error.

    ``b1``: (R,) b'_1 per realization from the same snapshots (marginal route, so that
    the ratio tends to 1).  Error by first-order propagation with the covariance of
    numerator and denominator.  Returns ``(cx2, ratio, sem)``.
    """
    numerator = _beta1_per_realization(counts, n_samples, edges, eps_star)
    denominator = np.asarray(b1, dtype=float)
    r = numerator.shape[0]
    num_mean = numerator.mean(axis=0)
    den_mean = denominator.mean()
    ratio = num_mean / den_mean
    dn = numerator - num_mean
    dd = (denominator - den_mean)[:, None]
    var_n = (dn**2).sum(axis=0) / (r - 1)
    var_d = (dd**2).sum(axis=0) / (r - 1)
    cov = (dn * dd).sum(axis=0) / (r - 1)
    variance = (var_n - 2.0 * ratio * cov + ratio**2 * var_d) / (den_mean**2 * r)
    half = np.asarray(counts).shape[-1] // 2
    return edges[half:] ** 2, ratio, np.sqrt(np.maximum(variance, 0.0))


# ----------------------------------------------------------------- dataset level


def _moment(ds, name: str) -> np.ndarray:
    """(R, T) window averages of one snapshot moment."""
    return np.asarray(ds["moments"].sel(moment=name).values, dtype=float)


def _sonine_moments(ds, route: str) -> np.ndarray:
    """(R, T, 3) <c_x L_k(.)> of one route."""
    return np.stack([_moment(ds, f"{route}_{k}") for k in range(1, N_SONINE + 1)], axis=-1)


def run_parameters(ds) -> dict[str, Any]:
    """Parameters of a run's dataset (those stamped by the engine plus the steady start)."""
    parameters = parameters_of(ds)
    parameters["steady_from_tau"] = float(ds.attrs["steady_from_tau"])
    return parameters


def time_series_of(ds) -> dict[str, np.ndarray]:
    """Realization means and errors of the time-dependent quantities (Figs 1 and 2).

    Keys: ``time`` (T,) [τ]; ``kappa_ratio``, ``kappa_ratio_err`` (T,) kappa'(t)/kappa0;
    ``b_full``, ``b_full_err``, ``b_marginal``, ``b_marginal_err`` (T, 3); ``a2``,
    ``a2_err`` (T,).
    """
    p = run_parameters(ds)
    eps = p["reduced_field"]
    out = {"time": np.asarray(ds["time"].values, dtype=float)}
    a2 = theory.reduced_a2_from_moment(_moment(ds, "c4"))
    out["a2"], out["a2_err"] = mean_and_sem(a2, axis=0)
    if eps > 0:
        out["kappa_ratio"], out["kappa_ratio_err"] = kappa_prime_estimate(_moment(ds, "c2cx"), eps)
        for route in ROUTES:
            out[f"b_{route}"], out[f"b_{route}_err"] = b_estimates(
                _sonine_moments(ds, route), eps, route
            )
    return out


def steady_summary_of(ds) -> dict[str, Any]:
    """Steady-state estimates of one run (time averages over t >= steady_from).

    Scalars (with ``_err``): ``kappa_ratio`` (kappa'/kappa0), ``a2``, ``thermostat_rate``
    and ``cooling_rate`` (at zero field the HCS ζ, free of the step's error) [1/τ],
    ``anisotropy`` (<c_x^2> - 1/2: O(eps*^2), the pressure tensor of Eq. 2.6);
    arrays (3,): ``b_full``, ``b_marginal`` (+ ``_err``) and ``route_difference``
    (paired b_full - b_marginal, + ``_err``); thermostat exactness ``max_abs_cx`` and
    ``max_abs_energy_error`` (max over windows of |<c_x>| and |<c^2> - d/2|); cost
    ``cpu_seconds`` (total), ``particle_tau`` (N x duration x R), ``collisions``; the
    run's parameters; per-realization arrays under ``per_realization``.
    """
    p = run_parameters(ds)
    eps, t0 = p["reduced_field"], p["steady_from_tau"]
    times = ds["time"].values
    steady = {}
    out: dict[str, Any] = {"parameters": p, "per_realization": steady}
    a2 = steady_average(theory.reduced_a2_from_moment(_moment(ds, "c4")), times, t0)
    steady["a2"] = a2
    out["a2"], out["a2_err"] = mean_and_sem(a2)
    rate = steady_average(ds["thermostat_rate"].values, times, t0)
    out["thermostat_rate"], out["thermostat_rate_err"] = mean_and_sem(rate)
    # at zero field the HCS ζ without time-step error (Haff's law within each step); the
    # thermostat's 2 ln s / δt is (2/δt) ln(1 + ζδt/2), 0.86 % low at α = 0.3, δt = 0.1τ
    cooling = steady_average(ds["cooling_rate"].values, times, t0)
    out["cooling_rate"], out["cooling_rate_err"] = mean_and_sem(cooling)
    anisotropy = steady_average(_moment(ds, "cx2"), times, t0) - 0.5
    out["anisotropy"], out["anisotropy_err"] = mean_and_sem(anisotropy)
    out["max_abs_cx"] = float(np.nanmax(np.abs(_moment(ds, "cx"))))
    out["max_abs_energy_error"] = float(np.nanmax(np.abs(_moment(ds, "c2") - 1.5)))
    if eps > 0:
        c2cx = steady_average(_moment(ds, "c2cx"), times, t0)
        steady["kappa_ratio"] = theory.kappa_prime_ratio_from_heat_flux(c2cx, eps)
        out["kappa_ratio"], out["kappa_ratio_err"] = mean_and_sem(steady["kappa_ratio"])
        for route in ROUTES:
            moments = steady_average(np.moveaxis(_sonine_moments(ds, route), -1, 1), times, t0)
            steady[f"b_{route}"] = theory.b_coefficients(moments, eps, route)
            out[f"b_{route}"], out[f"b_{route}_err"] = mean_and_sem(steady[f"b_{route}"])
        difference = steady["b_full"] - steady["b_marginal"]
        out["route_difference"], out["route_difference_err"] = mean_and_sem(difference)
    r = ds.sizes["realization"]
    out["cpu_seconds"] = float(np.sum(ds["cpu_seconds"].values))
    out["particle_tau"] = float(p["n_particles"] * p["duration_tau"] * r)
    out["steady_particle_tau"] = float(p["n_particles"] * (p["duration_tau"] - t0) * r)
    out["collisions"] = int(np.sum(ds["collisions"].values))
    out["realizations"] = int(r)
    return out


def distributions_of(ds, summary: dict[str, Any] | None = None, rebin_factor: int = 1):
    """phi(c_x^2), phi_p (p = 1..3 with the measured b'_k, Eq. 4.5), beta_1/b'_1, g(c_x).

    Keys: ``phi_cx2``, ``phi``, ``phi_err`` (bins c_x > 0); ``phi_p`` (3, n) at
    ``phi_cx2`` using the full-route b'_k (the paper's choice); ``beta_cx2``,
    ``beta_ratio``, ``beta_ratio_err``; ``cx``, ``g``, ``g_err``, ``odd``, ``odd_err``.
    """
    summary = summary or steady_summary_of(ds)
    eps = summary["parameters"]["reduced_field"]
    counts = np.asarray(ds["cx_counts"].values, dtype=float)
    edges = np.asarray(ds["cx_edges"].values, dtype=float)
    n_samples = np.asarray(ds["histogram_observations"].values, dtype=float)
    out: dict[str, Any] = {}
    beta_cx2, ratio, ratio_err = beta1_ratio_estimate(
        counts, n_samples, edges, summary["per_realization"]["b_marginal"][:, 0], eps
    )
    out.update(beta_cx2=beta_cx2, beta_ratio=ratio, beta_ratio_err=ratio_err)
    if rebin_factor > 1:
        counts, edges = rebin(counts, edges, rebin_factor)
    cx2, phi, phi_err = phi_estimate(counts, n_samples, edges, eps)
    out.update(phi_cx2=cx2, phi=phi, phi_err=phi_err)
    out["phi_p"] = np.stack(
        [theory.phi_sonine(cx2, summary["b_full"][:p]) for p in range(1, N_SONINE + 1)]
    )
    cx, g, g_err, odd, odd_err = odd_marginal_estimate(counts, n_samples, edges)
    out.update(cx=cx, g=g, g_err=g_err, odd=odd, odd_err=odd_err)
    return out


def summary_row(ds, summary: dict[str, Any] | None = None) -> dict[str, Any]:
    """One flat table row of a run: parameters, steady estimates, errors and cost.

    Columns: run, family, setting, alpha, reduced_field, time_step, force_step,
    n_particles, realizations, kappa_ratio(_err), b{k}_full(_err), b{k}_marginal(_err),
    b{k}_route_difference(_err) for k = 1..3, a2(_err), thermostat_rate(_err),
    cooling_rate(_err), anisotropy(_err), max_abs_cx, max_abs_energy_error, cpu_seconds,
    particle_tau, steady_particle_tau, collisions.
    """
    summary = summary or steady_summary_of(ds)
    p = summary["parameters"]
    row: dict[str, Any] = {
        "run": p.get("run", ""),
        "family": p.get("family", ""),
        "setting": p.get("setting", ""),
        "alpha": p["restitution"],
        "reduced_field": p["reduced_field"],
        "time_step": p["time_step_tau"],
        "force_step": p["force_step"],
        "splitting": p.get("splitting", "lie"),
        "n_particles": p["n_particles"],
        "realizations": summary["realizations"],
    }
    nan = float("nan")
    row["kappa_ratio"] = summary.get("kappa_ratio", nan)
    row["kappa_ratio_err"] = summary.get("kappa_ratio_err", nan)
    for key in ("b_full", "b_marginal", "route_difference"):
        values = summary.get(key, np.full(N_SONINE, nan))
        errors = summary.get(f"{key}_err", np.full(N_SONINE, nan))
        name = key.removeprefix("b_")
        for k in range(N_SONINE):
            row[f"b{k + 1}_{name}"] = float(values[k])
            row[f"b{k + 1}_{name}_err"] = float(errors[k])
    # b'_2 and b'_3 come from the same particles: the covariance of their means (b'_3/b'_2's
    # error; per realization they correlate at -0.8 in the default build)
    per = summary["per_realization"].get("b_full")
    row["b2_b3_full_cov"] = (
        float(np.cov(per[:, 1], per[:, 2])[0, 1] / per.shape[0])
        if per is not None and per.shape[0] > 1
        else nan
    )
    for key in ("a2", "thermostat_rate", "cooling_rate", "anisotropy"):
        row[key] = float(summary[key])
        row[f"{key}_err"] = float(summary[f"{key}_err"])
    for key in (
        "max_abs_cx",
        "max_abs_energy_error",
        "cpu_seconds",
        "particle_tau",
        "steady_particle_tau",
        "collisions",
    ):
        row[key] = summary[key]
    return row


def rows_with_field_bias(scan, partners) -> list[dict[str, Any]]:
    """Summary rows of the ``scan`` datasets, sorted by restitution, each with the bias
    and eps* -> 0 columns of :func:`field_extrapolation` against the dataset of
    ``partners`` at its restitution (both: iterables of run datasets)."""
    by_alpha = {}
    for ds in partners:
        row = summary_row(ds)
        by_alpha[row["alpha"]] = row
    rows = []
    for ds in scan:
        row = summary_row(ds)
        if row["alpha"] not in by_alpha:
            raise ValueError(f"no larger-field partner run at restitution {row['alpha']}")
        rows.append({**row, **field_extrapolation(row, by_alpha[row["alpha"]])})
    return sorted(rows, key=lambda row: row["alpha"])


# --------------------------------------------------------- error against run time


def _weighted_polyfit(x, y, err, degree: int):
    """Weighted least squares y = sum_j c_j x^j; returns (coefficients, covariance, chi2/dof)."""
    x, y, err = (np.asarray(a, dtype=float) for a in (x, y, err))
    design = np.vander(x, degree + 1, increasing=True) / err[:, None]
    rhs = y / err
    coefficients, *_ = np.linalg.lstsq(design, rhs, rcond=None)
    covariance = np.linalg.inv(design.T @ design)
    dof = max(len(x) - degree - 1, 1)
    chi2 = float(np.sum((design @ coefficients - rhs) ** 2)) / dof
    return coefficients, covariance, chi2


def _splitting(row) -> str:
    return row.get("splitting") or "lie"


def _bias_columns(time_step: float, splitting: str) -> np.ndarray:
    """Columns (k0, k1, k2, s2) of the bias model for one run: the Lie splitting of
    collisions and force biases kappa' at O(dt) (k1 dt + k2 dt^2), the Strang splitting
    at O(dt^2) (s2 dt^2); k0 is the dt -> 0 limit shared by both."""
    if splitting == "strang":
        return np.array([1.0, 0.0, 0.0, time_step**2])
    return np.array([1.0, time_step, time_step**2, 0.0])


def time_step_bias_fit(rows, n_particles: int):
    """Weighted fit of kappa'/kappa0 = k0 + (Lie) k1 dt + k2 dt^2 or (Strang) s2 dt^2.

    ``rows``: summary rows (:func:`summary_row`) of one alpha at ``n_particles``, both
    force steps (the force integrator only changes kappa' at O(eps^2)) and both
    splittings.  k2 is dropped (set to 0) unless the time steps leave a degree of freedom
    with it; s2 enters only with Strang runs.  Returns
    ``{"coefficients": (k0, k1, k2, s2), "covariance": (4, 4), "chi2_per_dof",
    "time_steps"}``.
    """
    chosen = [row for row in rows if row["n_particles"] == n_particles]
    lie = sorted({row["time_step"] for row in chosen if _splitting(row) == "lie"})
    strang = sorted({row["time_step"] for row in chosen if _splitting(row) == "strang"})
    if len(lie) < 2:
        raise ValueError(f"need Lie runs at >= 2 time steps with N = {n_particles}, got {lie}")
    used = [0, 1]
    if strang:
        used.append(3)
    if len(lie) + len(strang) >= len(used) + 2:
        used.insert(2, 2)
    design = np.array([_bias_columns(row["time_step"], _splitting(row)) for row in chosen])
    design = design[:, used]
    values = np.array([row["kappa_ratio"] for row in chosen])
    errors = np.array([row["kappa_ratio_err"] for row in chosen])
    weighted = design / errors[:, None]
    solution, *_ = np.linalg.lstsq(weighted, values / errors, rcond=None)
    covariance_used = np.linalg.inv(weighted.T @ weighted)
    dof = max(len(values) - len(used), 1)
    chi2 = float(np.sum((weighted @ solution - values / errors) ** 2)) / dof
    coefficients = np.zeros(4)
    coefficients[used] = solution
    covariance = np.zeros((4, 4))
    covariance[np.ix_(used, used)] = covariance_used
    return {
        "coefficients": coefficients,
        "covariance": covariance,
        "chi2_per_dof": chi2,
        "time_steps": {"lie": lie, "strang": strang},
    }


def particle_number_bias(rows, n_reference: int):
    """Finite-N bias c_N/N from runs at one time step and force step: returns (c_N, error).

    For each run with N != ``n_reference``, the difference to the run with N_reference at
    the same time step and force step estimates c_N (1/N - 1/N_ref); the generalised
    least-squares mean of those estimates is returned ((0, inf) if there is none). Two
    estimates against the same reference run share its error: with levers L_i, L_j and the
    reference's error s_ref their covariance is s_ref²/(L_i L_j), which the mean weighs in
    (as independent, two sizes against one reference had their error 3-6 % low).
    """
    # several runs of the reference size at one setting (the default config's protocol
    # and strang100 share theirs) are one reference, their inverse-variance mean (the
    # last of them alone was kept until 2026-12-01)
    same_setting = defaultdict(list)
    for row in rows:
        if row["n_particles"] == n_reference:
            same_setting[(row["time_step"], row["force_step"], _splitting(row))].append(row)
    reference = {}
    for key, runs in same_setting.items():
        weights = np.array([1.0 / run["kappa_ratio_err"] ** 2 for run in runs])
        values = np.array([run["kappa_ratio"] for run in runs])
        reference[key] = {
            "kappa_ratio": float(weights @ values / weights.sum()),
            "kappa_ratio_err": float(1.0 / np.sqrt(weights.sum())),
        }
    estimates, own, bases = [], [], []
    for row in rows:
        key = (row["time_step"], row["force_step"], _splitting(row))
        base = reference.get(key)
        if base is None or row["n_particles"] == n_reference:
            continue
        lever = 1.0 / row["n_particles"] - 1.0 / n_reference
        estimates.append((row["kappa_ratio"] - base["kappa_ratio"]) / lever)
        own.append(row["kappa_ratio_err"] / lever)
        bases.append((key, base["kappa_ratio_err"] / lever))
    if not estimates:
        return 0.0, float("inf")
    covariance = np.diag(np.square(own))
    for i, (key_i, shared_i) in enumerate(bases):
        for j, (key_j, shared_j) in enumerate(bases):
            if key_i == key_j:
                covariance[i, j] += shared_i * shared_j
    weights = np.linalg.solve(covariance, np.ones(len(estimates)))
    total = float(weights.sum())
    return float(weights @ np.asarray(estimates) / total), float(np.sqrt(1.0 / total))


def error_budget(rows, n_reference: int, target_errors):
    """The error-against-run-time study of one alpha.

    Bias model: kappa(dt, N) = k_inf + (Lie) k1 dt + k2 dt^2 or (Strang) s2 dt^2 + c_N / N,
    with (k0, k1, k2, s2) from :func:`time_step_bias_fit` at N = ``n_reference`` and c_N from
    :func:`particle_number_bias`, k_inf = k0 - c_N / n_reference.  Relative bias b and
    its error db per run (setting).

    Statistics: the variance of kappa' per steady particle-tau hardly depends on the time
    step, so it is pooled over the runs with the same N (weights: realizations - 1); a
    setting's inefficiency is I = s^2 C, the CPU seconds C it needs for a relative
    standard error s = 1, from that pooled variance and its own CPU time per steady
    particle-tau (transient included).  ``inefficiency_measured`` is its own s^2 C.
    CPU time for a total relative error E (more realizations of the same run):
    I / (E^2 - (|b| + 2 db)^2), the bias taken at its upper 2-sigma bound, when positive.
    Returns (per-setting rows, per-target rows, model).
    """
    fit = time_step_bias_fit(rows, n_reference)
    k0, k1, k2, s2 = fit["coefficients"]
    c_n, c_n_err = particle_number_bias(rows, n_reference)
    if not np.isfinite(c_n_err):
        c_n = 0.0
    k_inf = k0 - c_n / n_reference
    pooled = {}
    for n in {row["n_particles"] for row in rows}:
        same = [row for row in rows if row["n_particles"] == n]
        weights = np.array([row["realizations"] - 1.0 for row in same])
        variances = np.array(
            [
                (row["kappa_ratio_err"] / row["kappa_ratio"]) ** 2 * row["steady_particle_tau"]
                for row in same
            ]
        )
        pooled[n] = float(np.sum(weights * variances) / np.sum(weights))
    settings = []
    for row in rows:
        dt, n = row["time_step"], row["n_particles"]
        gradient = _bias_columns(dt, _splitting(row))
        dt_part = gradient.copy()
        dt_part[0] = 0.0
        # against k_inf: the fit's k0 is kappa(dt -> 0) at n_reference, which carries
        # c_N/n_reference (counted twice and left out of the bias until 2026-12-01)
        bias = float(dt_part @ fit["coefficients"]) + c_n / n
        bias_err = float(np.sqrt(dt_part @ fit["covariance"] @ dt_part))
        if np.isfinite(c_n_err):
            bias_err = float(np.hypot(bias_err, c_n_err / n))
        relative_stat = row["kappa_ratio_err"] / row["kappa_ratio"]
        settings.append(
            {
                "setting": row["setting"] or "protocol",
                "splitting": _splitting(row),
                "force_step": row["force_step"],
                "time_step": dt,
                "n_particles": n,
                "realizations": row["realizations"],
                "cpu_seconds": row["cpu_seconds"],
                "cpu_us_per_particle_tau": 1e6 * row["cpu_seconds"] / row["particle_tau"],
                "kappa_ratio": row["kappa_ratio"],
                "kappa_ratio_err": row["kappa_ratio_err"],
                "model": k_inf + bias,
                "relative_stat_err": relative_stat,
                "relative_bias": bias / k_inf,
                "relative_bias_err": bias_err / k_inf,
                "inefficiency": pooled[n] * row["cpu_seconds"] / row["steady_particle_tau"],
                "inefficiency_measured": relative_stat**2 * row["cpu_seconds"],
            }
        )

    def needed_cpu(setting, target):
        # the inefficiency is the CPU time of a relative standard error of 1
        bound = abs(setting["relative_bias"]) + 2.0 * setting["relative_bias_err"]
        return cpu_for_error(setting["inefficiency"], 1.0, target, bound)

    targets = []
    for target in target_errors:
        costs = [(needed_cpu(setting, target), setting) for setting in settings]
        cpu, best = min(costs, key=lambda pair: pair[0])
        found = np.isfinite(cpu)
        protocol = [c for c, s in costs if s["setting"] == "protocol"]
        targets.append(
            {
                "target_error": target,
                "cheapest_setting": best["setting"] if found else "",
                "splitting": best["splitting"] if found else "",
                "force_step": best["force_step"] if found else "",
                "time_step": best["time_step"] if found else float("nan"),
                "n_particles": best["n_particles"] if found else 0,
                "cpu_seconds_needed": cpu if found else float("nan"),
                "relative_bias": best["relative_bias"] if found else float("nan"),
                "relative_bias_err": best["relative_bias_err"] if found else float("nan"),
                "protocol_cpu_seconds": (
                    protocol[0] if protocol and np.isfinite(protocol[0]) else float("nan")
                ),
            }
        )
    k_inf_variance = fit["covariance"][0, 0]
    if np.isfinite(c_n_err):
        k_inf_variance += (c_n_err / n_reference) ** 2
    model = {
        "k_inf": k_inf,
        "k_inf_err": float(np.sqrt(k_inf_variance)),
        "k0": k0,
        "k1": k1,
        "k2": k2,
        "s2": s2,
        "covariance": fit["covariance"],
        "chi2_per_dof": fit["chi2_per_dof"],
        "c_n": c_n,
        "c_n_err": c_n_err,
        "pooled_variance": pooled,
    }
    return settings, targets, model


# ------------------------------------------------------------- beyond linear response

FIELD_EVEN_KEYS = ("kappa_ratio", "b1_full", "b2_full", "b3_full")
"""Summary-row estimates that are even in eps* (q_x and every <c_x L_k> are odd)."""


def field_extrapolation(low: dict, high: dict, keys=FIELD_EVEN_KEYS) -> dict[str, float]:
    """The O(eps*^2) bias of the estimates of ``low`` and their limit eps* -> 0.

    ``low`` and ``high`` are summary rows (:func:`summary_row`) of two independent runs at
    the same restitution and fields eps_1 < eps_2.  Each estimate X is even in eps*, so
    X(eps) = X_0 + c eps^2 + O(eps^4) and, with w = eps_1^2 / (eps_2^2 - eps_1^2),

        bias at eps_1 = X(eps_1) - X_0 = w (X(eps_2) - X(eps_1)),
        X_0 = X(eps_1) - bias = (1 + w) X(eps_1) - w X(eps_2),

    with errors propagated from the two independent standard errors.  Returns
    ``{key_bias, key_bias_err, key_extrapolated, key_extrapolated_err}`` per key, and the
    two fields as ``field_low``, ``field_high``.
    """
    if low["alpha"] != high["alpha"]:
        raise ValueError(f"field pair at different restitutions {low['alpha']}, {high['alpha']}")
    e1, e2 = float(low["reduced_field"]), float(high["reduced_field"])
    if not 0 < e1 < e2:
        raise ValueError(f"fields must satisfy 0 < eps_1 < eps_2, got {e1}, {e2}")
    w = e1**2 / (e2**2 - e1**2)
    out = {"field_low": e1, "field_high": e2}
    for key in keys:
        x1, s1 = low[key], low[f"{key}_err"]
        x2, s2 = high[key], high[f"{key}_err"]
        out[f"{key}_bias"] = w * (x2 - x1)
        out[f"{key}_bias_err"] = float(w * np.hypot(s1, s2))
        out[f"{key}_extrapolated"] = (1 + w) * x1 - w * x2
        out[f"{key}_extrapolated_err"] = float(np.hypot((1 + w) * s1, w * s2))
    if "b2_b3_full_cov" in low and "b2_b3_full_cov" in high:
        out["b2_b3_full_cov_extrapolated"] = (1 + w) ** 2 * low["b2_b3_full_cov"] + w**2 * high[
            "b2_b3_full_cov"
        ]
    return out


def extrapolated_b3_over_b2(row: dict) -> tuple[float, float]:
    """b'_3/b'_2 at eps* -> 0 (a row of :func:`rows_with_field_bias`) and its error by the
    delta method with the two coefficients' covariance (they come from the same particles:
    the error with the covariance left out was 1.45 times too large at alpha = 0.3)."""
    x, sx = row["b3_full_extrapolated"], row["b3_full_extrapolated_err"]
    y, sy = row["b2_full_extrapolated"], row["b2_full_extrapolated_err"]
    covariance = row.get("b2_b3_full_cov_extrapolated", 0.0)
    ratio = x / y
    relative = (sx / x) ** 2 + (sy / y) ** 2 - 2 * covariance / (x * y)
    return float(ratio), float(abs(ratio) * np.sqrt(max(relative, 0.0)))


def _linear_response_polyfit(fields, kappa, kappa_err, max_field: float):
    """The weighted fit kappa' = k0 + s eps*^2 to the fields <= ``max_field``: the arrays,
    the mask of fitted fields, the coefficients (k0, s) and their covariance."""
    fields, kappa, kappa_err = (np.asarray(a, dtype=float) for a in (fields, kappa, kappa_err))
    mask = fields <= max_field
    if mask.sum() < 2:
        raise ValueError(f"need >= 2 fields <= {max_field} for the linear-response fit")
    coefficients, covariance, _ = _weighted_polyfit(
        fields[mask] ** 2, kappa[mask], kappa_err[mask], 1
    )
    return fields, kappa, kappa_err, mask, coefficients, covariance


def linear_response_fit(fields, kappa, kappa_err, max_field: float):
    """Fit kappa'(eps*) = k0 (1 - C eps*^2) to the fields <= ``max_field``.

    q_x is odd in eps, so kappa' = -q_x/(T eps) is even: the first correction is O(eps*^2).
    Returns (k0, k0_err, C, C_err).
    """
    *_, coefficients, covariance = _linear_response_polyfit(fields, kappa, kappa_err, max_field)
    k0, slope = coefficients
    c = -slope / k0
    jacobian = np.array([slope / k0**2, -1.0 / k0])
    c_err = float(np.sqrt(jacobian @ covariance @ jacobian))
    return float(k0), float(np.sqrt(covariance[0, 0])), float(c), c_err


def departure_from_linear_response(fields, kappa, kappa_err, max_field: float) -> dict:
    """Each field's relative departure κ'/k0 - 1 from the linear-response fit
    (``linear_response_fit`` to the fields <= ``max_field``), with its error: the field's
    own, k0's, and, for a field inside the fit, their covariance (k0 is linear in the
    fitted κ'_i, cov(κ'_i, k0) = Cov[0, 0] + Cov[0, 1] ε*_i²). Returns ``k0``, ``k0_err``
    and the arrays ``departure``, ``departure_err``."""
    fields, kappa, kappa_err, mask, coefficients, covariance = _linear_response_polyfit(
        fields, kappa, kappa_err, max_field
    )
    k0, k0_var = float(coefficients[0]), float(covariance[0, 0])
    shared = np.where(mask, covariance[0, 0] + covariance[0, 1] * fields**2, 0.0)
    variance = kappa_err**2 / k0**2 + kappa**2 * k0_var / k0**4 - 2 * kappa * shared / k0**3
    return {
        "k0": k0,
        "k0_err": float(np.sqrt(k0_var)),
        "departure": kappa / k0 - 1.0,
        "departure_err": np.sqrt(variance),
    }


# ------------------------------------------------------------------- checks
def _field_partner(row, rows):
    """The run at ``row``'s restitution and a larger field that extrapolates it to
    eps* -> 0: the ``bias`` run, else the ``field`` run there; None without one."""
    for family in ("bias", "field"):
        for other in rows:
            if (
                other["family"] == family
                and other["alpha"] == row["alpha"]
                and other["reduced_field"] > row["reduced_field"]
            ):
                return other
    return None


def _combined_dof(errors, dofs) -> int:
    """Degrees of freedom of the errors ``errors`` of two independent runs combined
    (Welch-Satterthwaite), never below the smaller of ``dofs`` (which rounding could
    cross)."""
    return max(int(check.welch_dof(errors, dofs)), min(dofs)) if max(errors) > 0 else min(dofs)


def _linear_response(row, rows, key, claim):
    """(claim, value, error, degrees of freedom) of a claim of linear response about the
    estimate ``key`` of scan ``row``: at eps* -> 0 from ``row`` and its field partner
    (:func:`field_extrapolation`), or at ``row``'s field where it has none."""
    partner = _field_partner(row, rows)
    if partner is None:
        return claim, row[key], row[f"{key}_err"], row["realizations"] - 1
    limit = field_extrapolation(row, partner, keys=(key,))
    fields = f"{row['reduced_field']:g} and {partner['reduced_field']:g}"
    # the error's degrees of freedom (Welch-Satterthwaite): (1 + w) s1 and w s2 combine,
    # and the partner's, weighted by w = 1/3 at twice the field, counts for little
    w = limit["field_low"] ** 2 / (limit["field_high"] ** 2 - limit["field_low"] ** 2)
    errors = ((1 + w) * row[f"{key}_err"], w * partner[f"{key}_err"])
    dof = _combined_dof(errors, (row["realizations"] - 1, partner["realizations"] - 1))
    return (
        f"{claim} (eps* -> 0 from {fields})",
        limit[f"{key}_extrapolated"],
        limit[f"{key}_extrapolated_err"],
        dof,
    )


def _field_bias_checks(row, partner, tolerances, label) -> list[Check]:
    """Check 3 of :func:`checks` for scan ``row`` and its larger-field ``partner``: the
    bound on κ'/κ0's O(eps*^2) bias at the row's field, and the two fields' difference
    (reported)."""
    e1, e2 = row["reduced_field"], partner["reduced_field"]
    bias = field_extrapolation(row, partner, keys=("kappa_ratio",))
    value, error = bias["kappa_ratio_bias"], bias["kappa_ratio_bias_err"]
    dofs = (row["realizations"] - 1, partner["realizations"] - 1)
    errors = (row["kappa_ratio_err"], partner["kappa_ratio_err"])
    dof = _combined_dof(errors, dofs)
    share = tolerances["field_bias_tolerance"]
    limit = abs(bias["kappa_ratio_extrapolated"])
    tolerance = share * limit + tolerance_factor(tolerances["sigmas"], dof) * error
    claim = (
        f"linear response: the O(eps*^2) bias of kappa'/kappa0 at eps* = {e1:g} "
        f"(from {e1:g} and {e2:g}) is below {100 * share:g} % of it"
    )
    difference = partner["kappa_ratio"] - row["kappa_ratio"]
    return [
        check.within(label(row, claim), value, 0.0, tolerance, error),
        check.reported(
            label(row, f"kappa'/kappa0 at eps* = {e2:g} minus at {e1:g}"),
            difference,
            float(np.hypot(*errors)),
            0.0,
        ),
    ]


def checks(rows, tolerances) -> list[Check]:
    """The checks of the study on its ``summary_row`` rows (``kinetic.analysis.checks``).

    Statistical checks pass within ``tolerances["sigmas"]`` standard errors, widened to
    Student's t for the number of realizations behind each error (:func:`tolerance_factor`):
    1. κ'/κ0 at α = 1 agrees with 1.025218 (Ref. [37]);
    2. the two routes to b'_k (Eqs. 3.10 and 3.12) agree (paired differences);
    3. linear response ("practically linear in eps*", Fig. 1): κ'/κ0's O(eps*^2) bias at
       the run's field, from the run and its partner at a larger field
       (:func:`field_extrapolation`), stays within ``field_bias_tolerance`` |κ'/κ0| + sigmas
       errors, at every scan restitution that has a partner; the two fields' raw
       difference is reported beside it;
    4. the HCS a2 (zero field) agrees with Eq. (2.16) for α >= ``a2_alpha_min`` within
       ``a2_relative_tolerance`` |a2| + ``a2_absolute_floor`` + sigmas errors (reported
       below ``a2_alpha_min``); the floor is what Eq. (2.16) misses: the DSMC a2 lies
       0.0012-0.0023 below it at α = 0.5-0.9 (N = 2·10⁴, 16 realizations of 400 τ:
       errors of 1-1.5·10⁻⁴), 0.0020 at α = 0.7 where Eq. (2.16) gives 0.0013;
    5. the thermostat holds momentum and energy: |<c_x>|, |<c²> - 3/2| <=
       ``thermostat_tolerance``.
    Reported with no verdict: the HCS cooling rate against Eq. (2.14).

    Checks 1 and 2 are claims of linear response, which a finite field misses at
    O(eps*^2): at the paper's statistics and eps* = 0.025, κ'/κ0 at α = 1 is 1.0307 +-
    0.0010 and the routes to b'_2 and b'_3 differ by 5 to 11 errors (docs/reproduced.md);
    at α = 0.3, κ'/κ0 at eps* = 0.05 lies 0.0188 +- 0.0015 (13 errors) above the value at
    0.025, a bias of 0.48 % at 0.025, so check 3 bounds the bias rather than asking for
    none.
    Where the run has a partner at a larger field (family ``bias``, or the ``field`` run at
    its restitution), both are checked at eps* -> 0 (:func:`field_extrapolation`, with
    Welch-Satterthwaite degrees of freedom); otherwise at the run's field.
    """
    sigmas = tolerances["sigmas"]
    found = []

    def label(row, quantity):
        return f"{quantity}, run {row['run']} (alpha = {row['alpha']:g})"

    scan = {row["alpha"]: row for row in rows if row["family"] == "scan"}
    if 1.0 in scan:
        claim, value, error, dof = _linear_response(
            scan[1.0], rows, "kappa_ratio", "kappa'/kappa0 at alpha = 1 equals 1.025218 (Ref. [37])"
        )
        found.append(
            check.agrees(
                label(scan[1.0], claim),
                value,
                error,
                theory.KAPPA_ELASTIC_HIGHER_SONINE,
                tolerance_factor(sigmas, dof),
            )
        )
    for row in scan.values():
        for k in (1, 2, 3):
            claim, value, error, dof = _linear_response(
                row, rows, f"b{k}_route_difference", f"two routes to b'_{k} agree: (3.10) - (3.12)"
            )
            found.append(
                check.agrees(label(row, claim), value, error, 0.0, tolerance_factor(sigmas, dof))
            )
    for row in scan.values():
        partner = _field_partner(row, rows)
        if partner is None:
            continue
        found.extend(_field_bias_checks(row, partner, tolerances, label))
    for row in rows:
        if row["family"] != "hcs":
            continue
        expected = float(theory.hcs_a2(row["alpha"]))
        claim = label(row, "HCS a2 equals Eq. (2.16)")
        if row["alpha"] >= tolerances["a2_alpha_min"]:
            tolerance = (
                tolerances["a2_relative_tolerance"] * abs(expected)
                + tolerances["a2_absolute_floor"]
                + tolerance_factor(sigmas, row["realizations"] - 1) * row["a2_err"]
            )
            found.append(check.within(claim, row["a2"], expected, tolerance, row["a2_err"]))
        else:
            found.append(check.reported(claim, row["a2"], row["a2_err"], expected))
        zeta = float(theory.reduced_cooling_rate(row["alpha"], a2=row["a2"]) * theory.nu0_tau())
        found.append(
            check.reported(
                label(row, "HCS cooling rate zeta tau against Eq. (2.14)"),
                row["cooling_rate"],
                row["cooling_rate_err"],
                zeta,
            )
        )
    for row in rows:
        limit = tolerances["thermostat_tolerance"]
        found.append(
            check.within(
                label(row, "the thermostat holds the momentum: max |<c_x>|"),
                row["max_abs_cx"],
                0.0,
                limit,
            )
        )
        found.append(
            check.within(
                label(row, "the thermostat holds the energy: max |<c^2> - 3/2|"),
                row["max_abs_energy_error"],
                0.0,
                limit,
            )
        )
    return found


def load_runs(paths: Sequence[Any]) -> dict[str, Any]:
    """Read joined runs (one file a run, joined by ``kinetic.io.read_run``): ``{run name:
    dataset}``.

    The name of a run is the ``run`` parameter the workflow stamped into its batches; runs
    keep the order of ``paths``.
    """
    from kinetic import io

    runs: dict[str, Any] = {}
    for path in paths:
        dataset = io.read_dataset(path)
        name = io.parameters_of(dataset).get("run")
        if not name:
            raise ValueError(f"{path} has no 'run' parameter: not written by the workflow")
        if name in runs:
            raise ValueError(f"run {name!r} is read twice (again from {path})")
        runs[name] = dataset
    return runs
