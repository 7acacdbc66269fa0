"""Combine batch datasets of the cloning Monte Carlo into tables and datasets.

- ``combine_points``: batches of one (kernel, λ, N_c) point -> one record (all its
  realizations, joined by ``kinetic.batches.combine``);
- ``extrapolate_points``: per (kernel, λ), the weighted 1/N_c -> 0 fit of μ, μ_rate, T, a2;
- ``scan_table`` / ``scan_dataset``: results/visco2008/cloning.csv and .nc;
- ``error_versus_cpu`` / ``error_table`` / ``error_dataset``: statistical error and
  finite-N_c bias against CPU time (error-against-CPU-time study).

T and a2 of a point whose population collapsed onto a few clones (large λ, flag
``diversity_collapse`` of the front) are not estimates of the eigenfunction: they are
left empty in the table; μ is kept. The extrapolation of a (kernel, λ) fits only the
populations larger than every collapsed one (collapse comes first to the smallest).
"""

from __future__ import annotations

from collections import defaultdict
from typing import Any

import numpy as np
import pandas as pd

from kinetic import batches, io
from kinetic.analysis.statistics import (
    cpu_for_error,
    error_against_cpu,
    mean_and_sem,
    weighted_line,
)
from kinetic.batches import REALIZATION
from kinetic.cloning.estimators import (
    extrapolate_population,
    observables_from_sums,
    summarize_realizations,
)
from kinetic.cloning.front import is_collapsed
from kinetic.cloning.kernels import BLOCK_FIELDS

__all__ = [
    "BIAS_RESOLVED_SIGMAS",
    "OBSERVABLES",
    "TABLE_COLUMNS",
    "combine_points",
    "error_dataset",
    "error_table",
    "error_versus_cpu",
    "extrapolate_points",
    "scan_dataset",
    "scan_table",
]

TABLE_COLUMNS = ["kernel", "lambda", "mu", "mu_err", "T", "T_err", "a2", "a2_err", "n_c"]
"""Columns of results/visco2008/cloning.csv (read by other tools: keep the names)."""

OBSERVABLES = ("mu", "mu_rate", "temperature", "a2")

BIAS_RESOLVED_SIGMAS = 3.0
"""A finite-population bias of the error table counts as resolved beyond this many of its
errors (at 2, one of 14 points, λ = -0.5 at N_c = 1600, was flagged at z = -2.05 where the
1/N_c line predicts a bias 20 times smaller, and given a spurious crossover)."""


def combine_points(datasets, names=None) -> list[dict[str, Any]]:
    """Group batch datasets by point and join each point's batches.

    The batches of one (kernel, λ, N_c) point are joined by ``kinetic.batches.combine``
    (same parameters and seed, no realization in two batches; the error names both
    batches, by ``names``, e.g. their paths, or by position). Returns one record per
    point, sorted by (kernel, λ, N_c).
    """
    datasets = list(datasets)
    names = list(names) if names is not None else [f"batch {i}" for i in range(len(datasets))]
    groups = defaultdict(list)
    for name, dataset in zip(names, datasets, strict=True):
        parameters = io.parameters_of(dataset)
        key = (parameters["kernel_label"], float(parameters["lam"]), int(parameters["population"]))
        groups[key].append((name, dataset))
    records = []
    for (label, lam, population), members in sorted(groups.items()):
        joined = batches.combine([m for _, m in members], names=[n for n, _ in members])
        parameters = io.parameters_of(joined)
        count = joined.sizes[REALIZATION]
        blocks = np.stack([joined[name].values for name in BLOCK_FIELDS], axis=-1)
        measured = joined["measured"].values.astype(bool)
        dimension = int(parameters["dimension"])
        summary = summarize_realizations(blocks, measured, population, dimension, lam)
        density = joined["velocity_density"].values
        distinct = joined["distinct_velocities"].values
        records.append(
            {
                "kernel": label,
                "lam": lam,
                "population": population,
                "dimension": dimension,
                "n_realizations": int(count),
                "duration": float(parameters["duration"]),
                "transient": float(parameters["transient"]),
                "blocks": blocks,
                "measured": measured,
                "cpu_seconds": joined["cpu_seconds"].values,
                "velocity": joined["velocity"].values,
                "density": density.mean(axis=0),
                "density_err": density.std(axis=0, ddof=1) / np.sqrt(count)
                if count > 1
                else np.full(density.shape[1], np.nan),
                "distinct_min": int(distinct.min()),
                "collapsed": is_collapsed(distinct.min(), population),
                **{k: v for k, v in summary.items() if k != "error_method"},
                "error_method": summary["error_method"],
            }
        )
    return records


def _fit(sizes, values, errors):
    """The 1/N_c -> 0 fit of one point's values (``extrapolate_population``), and
    ``deviation_err``: each input value's error as a deviation from the intercept
    (:func:`deviation_from_extrapolation_err`; NaN for the values left out)."""
    sizes, values, errors = map(np.asarray, (sizes, values, errors))
    usable = np.isfinite(values) & np.isfinite(errors)
    deviation_err = np.full(usable.size, np.nan)
    sizes, values, errors = sizes[usable], values[usable], errors[usable]
    if np.unique(sizes).size < 2:
        return None
    if np.all(errors == 0):  # exact values (μ = 0 at λ = 0)
        if np.ptp(values) == 0:
            deviation_err[usable] = 0.0
            return {
                "value": float(values[0]),
                "err": 0.0,
                "slope": 0.0,
                "slope_err": 0.0,
                "covariance": 0.0,
                "chi2": 0.0,
                "dof": int(values.size - 2),
                "deviation_err": deviation_err,
            }
        return None
    errors = np.where(errors > 0, errors, errors[errors > 0].min())
    fit = extrapolate_population(sizes, values, errors)
    birge = max(1.0, fit.chi2 / fit.dof) if fit.dof > 0 else 1.0
    deviation_err[usable] = [
        np.sqrt(birge) * deviation_from_extrapolation_err(sizes, errors, i)
        for i in range(sizes.size)
    ]
    return {
        "value": fit.intercept,
        "err": fit.intercept_err,
        "slope": fit.slope,
        "slope_err": fit.slope_err,
        "covariance": fit.covariance,
        "chi2": fit.chi2,
        "dof": fit.dof,
        "deviation_err": deviation_err,
    }


def extrapolate_points(records) -> list[dict[str, Any]]:
    """Per (kernel, λ): weighted linear fits in 1/N_c of μ, μ_rate, T and a2.

    Only the populations larger than every one that collapsed onto a few clones enter
    the fits (a collapsed population's bias comes from its few surviving clones, not a
    1/N_c law, and its T and a2 are not estimates of the eigenfunction); the fit's
    ``deviation_err`` is NaN for the others. Missing fits are None: fewer than two
    population sizes left (e.g. the largest collapsed).
    """
    by_point = defaultdict(list)
    for record in records:
        by_point[(record["kernel"], record["lam"])].append(record)
    results = []
    for (label, lam), members in sorted(by_point.items()):
        floor = max((m["population"] for m in members if m["collapsed"]), default=0)
        entry = {
            "kernel": label,
            "lam": lam,
            "populations": [m["population"] for m in members],
            "fitted_populations": [m["population"] for m in members if m["population"] > floor],
            "collapsed": floor > 0,
        }
        for name in OBSERVABLES:
            entry[name] = _fit(
                [m["population"] for m in members],
                [m[name] if m["population"] > floor else np.nan for m in members],
                [m[f"{name}_err"] for m in members],
            )
        results.append(entry)
    return results


def scan_table(records, extrapolations) -> pd.DataFrame:
    """The rows of cloning.csv: one per (kernel, λ, N_c), then one per (kernel, λ) with
    n_c empty holding the 1/N_c -> 0 extrapolation (where there is one)."""
    rows = []
    for record in records:
        keep = not record["collapsed"]
        rows.append(
            {
                "kernel": record["kernel"],
                "lambda": record["lam"],
                "mu": record["mu"],
                "mu_err": record["mu_err"],
                "T": record["temperature"] if keep else np.nan,
                "T_err": record["temperature_err"] if keep else np.nan,
                "a2": record["a2"] if keep else np.nan,
                "a2_err": record["a2_err"] if keep else np.nan,
                "n_c": record["population"],
            }
        )
    for entry in extrapolations:
        if all(entry[name] is None for name in OBSERVABLES):
            continue  # fewer than two population sizes to fit

        def pick(name, field, entry=entry):
            fit = entry[name]
            return np.nan if fit is None else fit[field]

        rows.append(
            {
                "kernel": entry["kernel"],
                "lambda": entry["lam"],
                "mu": pick("mu", "value"),
                "mu_err": pick("mu", "err"),
                "T": pick("temperature", "value"),
                "T_err": pick("temperature", "err"),
                "a2": pick("a2", "value"),
                "a2_err": pick("a2", "err"),
                "n_c": pd.NA,
            }
        )
    frame = pd.DataFrame(rows, columns=TABLE_COLUMNS)
    frame["n_c"] = frame["n_c"].astype("Int64")
    return frame


def scan_dataset(records, extrapolations):
    """Dataset of every point (dim ``point``) and every extrapolation (dim ``limit``)."""
    point = np.arange(len(records))
    limit = np.arange(len(extrapolations))
    velocity = records[0]["velocity"]

    def column(name):
        return np.array([r[name] for r in records])

    data = {
        "point_kernel": ("point", column("kernel").astype(str), "1", "collision kernel"),
        "point_lambda": ("point", column("lam"), "1", "counting field lambda"),
        "point_population": ("point", column("population"), "1", "population size N_c"),
        "point_realizations": (
            "point",
            column("n_realizations"),
            "1",
            "independent realizations",
        ),
        "point_duration": (
            "point",
            column("duration"),
            "1/omega",
            "measured time per realization",
        ),
        "point_transient": (
            "point",
            column("transient"),
            "1/omega",
            "discarded time per realization",
        ),
        "point_collapse": (
            "point",
            column("collapsed").astype(np.int8),
            "1",
            "1 if a realization ended as a few clones (T, a2 not estimable)",
        ),
        "point_distinct_min": (
            "point",
            column("distinct_min"),
            "1",
            "fewest distinct velocities at the end of a realization",
        ),
        "velocity_density": (
            ("point", "velocity"),
            np.stack(column("density")),
            "1/sqrt(T0/m)",
            "density of a velocity component, mean of the realizations",
        ),
        "velocity_density_err": (
            ("point", "velocity"),
            np.stack(column("density_err")),
            "1/sqrt(T0/m)",
            "standard error of velocity_density",
        ),
    }
    units = {"mu": "omega", "mu_rate": "omega", "temperature": "T0", "a2": "1"}
    names = {
        "mu": "mu(lambda), compensation rate",
        "mu_rate": "mu(lambda), (e^-lambda - 1)<r>",
        "temperature": "T(lambda)",
        "a2": "a2(lambda)",
    }
    for name in OBSERVABLES:
        data[f"point_{name}"] = ("point", column(name), units[name], names[name])
        data[f"point_{name}_err"] = (
            "point",
            column(f"{name}_err"),
            units[name],
            f"standard error of {names[name]}",
        )

        def fitted(field, name=name):
            return np.array([np.nan if e[name] is None else e[name][field] for e in extrapolations])

        data[f"limit_{name}"] = (
            "limit",
            fitted("value"),
            units[name],
            f"{names[name]}, extrapolated to 1/N_c = 0",
        )
        data[f"limit_{name}_err"] = (
            "limit",
            fitted("err"),
            units[name],
            "standard error of the extrapolation",
        )
        data[f"limit_{name}_slope"] = (
            "limit",
            fitted("slope"),
            units[name],
            "slope d/d(1/N_c) of the extrapolation",
        )
        data[f"limit_{name}_slope_err"] = (
            "limit",
            fitted("slope_err"),
            units[name],
            "standard error of the slope",
        )
        data[f"limit_{name}_covariance"] = (
            "limit",
            fitted("covariance"),
            f"{units[name]}^2" if units[name] != "1" else "1",
            "covariance of the extrapolation's intercept and slope (its line's error band)",
        )
        data[f"limit_{name}_chi2"] = ("limit", fitted("chi2"), "1", "chi-square of the fit")
    data["limit_kernel"] = (
        "limit",
        np.array([e["kernel"] for e in extrapolations]),
        "1",
        "collision kernel",
    )
    data["limit_lambda"] = (
        "limit",
        np.array([e["lam"] for e in extrapolations]),
        "1",
        "counting field lambda",
    )
    data["limit_smallest_population"] = (
        "limit",
        np.array([min(e["fitted_populations"], default=0) for e in extrapolations]),
        "1",
        "smallest N_c in the fit (those at and below a collapsed population are left out; 0: none)",
    )
    coords = {
        "point": ("point", point, "1", "index of a (kernel, lambda, N_c) point"),
        "limit": ("limit", limit, "1", "index of a (kernel, lambda) extrapolation"),
        "velocity": ("velocity", velocity, "sqrt(T0/m)", "velocity component (bin centre)"),
    }
    return io.make_dataset(data, coords, {"title": "cloning Monte Carlo, visco2008 Figs 4-8"})


def error_versus_cpu(record, steps: int = 12):
    """Statistical error of μ and μ_rate against total CPU time for one point.

    Uses the first k measured blocks of every realization (k spread geometrically up to
    all of them); the CPU time of k blocks is the realizations' process time prorated by
    simulated time, with the transient included. Returns (cpu_seconds, mu_err, mu_rate_err), each of
    length <= steps.
    """
    blocks, measured = record["blocks"], record["measured"]
    n_transient = int((~measured).sum())
    n_measured = int(measured.sum())
    # process time is prorated by simulated time (transient blocks may be longer)
    elapsed = blocks[:, :, BLOCK_FIELDS.index("elapsed_time")].sum(axis=0)
    cpu_per_time = record["cpu_seconds"].sum() / elapsed.sum()
    transient_time = elapsed[:n_transient].sum()
    measured_time = np.cumsum(elapsed[n_transient:])
    counts = np.unique(np.geomspace(1, n_measured, steps).round().astype(int))

    def estimate(k):
        sums = blocks[:, n_transient : n_transient + k, :].sum(axis=1)
        mu, _, _, mu_rate = observables_from_sums(
            sums, record["population"], record["dimension"], record["lam"]
        )
        if mu.size < 2:
            return None
        (mu_mean, mu_sem), (rate_mean, rate_sem) = mean_and_sem(mu), mean_and_sem(mu_rate)
        return (mu_mean, rate_mean), (mu_sem, rate_sem)

    curve = error_against_cpu(
        counts, estimate, lambda k: cpu_per_time * (transient_time + measured_time[k - 1])
    )
    return curve.cpu_seconds, curve.error_of(0), curve.error_of(1)


def deviation_from_extrapolation_err(population_sizes, errors, index: int) -> float:
    """Error of y_i - a, point ``index``'s deviation from the intercept a of the weighted
    1/N_c fit (``extrapolate_population``) through it: a = Σ_j w_j (S_xx - S_x x_j) y_j/D,
    so cov(y_i, a) = (S_xx - S_x x_i)/D and var = σ_i² + S_xx/D - 2 (S_xx - S_x x_i)/D,
    all times the fit's Birge factor χ²/dof where it exceeds 1 (as its intercept error).
    Adding σ_i and the intercept's error as if independent overstated it up to twice at
    the large populations, whose points pull the intercept, and understated it at the
    smallest."""
    x = 1.0 / np.asarray(population_sizes, dtype=float)
    sigma = np.asarray(errors, dtype=float)
    fit = weighted_line(x, np.zeros_like(x), sigma)  # the covariances need no values
    with_point = fit.intercept_err**2 + x[index] * fit.covariance  # (S_xx - S_x x_i)/D
    variance = sigma[index] ** 2 + fit.intercept_err**2 - 2 * with_point
    return float(np.sqrt(max(variance, 0.0)))


def error_table(records, exact: dict[float, float]) -> pd.DataFrame:
    """Per (λ, N_c): CPU time, statistical errors, finite-N_c bias of μ_rate against
    ``exact`` μ and against the extrapolation of these points, and the CPU time at which
    the statistical error of μ_rate (scaled as 1/√CPU) falls to the bias (empty where the
    bias is not resolved, |bias| < BIAS_RESOLVED_SIGMAS = 3 standard errors)."""
    extrapolated = {(e["kernel"], e["lam"]): e for e in extrapolate_points(records)}
    members = defaultdict(list)  # each (kernel, λ)'s records, in the order of its fit
    for record in records:
        members[(record["kernel"], record["lam"])].append(record)
    rows = []
    for record in records:
        cpu = float(record["cpu_seconds"].sum())
        lam = record["lam"]
        key = (record["kernel"], lam)
        limit = extrapolated[key]["mu_rate"] or {"value": np.nan, "err": np.nan}
        deviation_err = np.nan
        if "deviation_err" in limit:
            group = members[key]
            deviation_err = limit["deviation_err"][
                next(i for i, m in enumerate(group) if m is record)
            ]
        bias = record["mu_rate"] - exact[lam]
        resolved = abs(bias) > BIAS_RESOLVED_SIGMAS * record["mu_rate_err"]
        crossover = cpu_for_error(cpu, record["mu_rate_err"], abs(bias)) if resolved else np.nan
        rows.append(
            {
                "lambda": lam,
                "n_c": record["population"],
                "cpu_seconds": cpu,
                "mu": record["mu"],
                "mu_err": record["mu_err"],
                "mu_rate": record["mu_rate"],
                "mu_rate_err": record["mu_rate_err"],
                "mu_exact": exact[lam],
                "bias": bias,
                "bias_err": record["mu_rate_err"],
                "bias_vs_extrapolation": record["mu_rate"] - limit["value"],
                "bias_vs_extrapolation_err": float(deviation_err),
                "cpu_seconds_stat_err_equals_bias": crossover,
            }
        )
    return pd.DataFrame(rows)


def error_dataset(records, exact):
    """Error-against-CPU curves of every point (dims ``point``, ``step``)."""
    curves = [error_versus_cpu(r) for r in records]
    steps = max(c[0].size for c in curves)

    def padded(index):
        out = np.full((len(records), steps), np.nan)
        for row, curve in enumerate(curves):
            out[row, : curve[index].size] = curve[index]
        return out

    data = {
        "cpu_seconds": (("point", "step"), padded(0), "s", "CPU time spent on the realizations"),
        "mu_err": (("point", "step"), padded(1), "omega", "standard error of mu (compensations)"),
        "mu_rate_err": (
            ("point", "step"),
            padded(2),
            "omega",
            "standard error of mu_rate ((e^-lambda - 1)<r>)",
        ),
        "point_lambda": ("point", np.array([r["lam"] for r in records]), "1", "lambda"),
        "point_population": (
            "point",
            np.array([r["population"] for r in records]),
            "1",
            "population size N_c",
        ),
        "point_realizations": (
            "point",
            np.array([r["blocks"].shape[0] for r in records]),
            "1",
            "independent realizations behind each standard error",
        ),
        "mu_rate": (
            "point",
            np.array([r["mu_rate"] for r in records]),
            "omega",
            "mu(lambda) from all realizations, (e^-lambda - 1)<r>",
        ),
        "mu_rate_final_err": (
            "point",
            np.array([r["mu_rate_err"] for r in records]),
            "omega",
            "standard error of mu_rate from all realizations",
        ),
        "mu_exact": (
            "point",
            np.array([exact[r["lam"]] for r in records]),
            "omega",
            "mu(lambda), deterministic solution of Eq. 28",
        ),
    }
    coords = {
        "point": ("point", np.arange(len(records)), "1", "index of a (lambda, N_c) point"),
        "step": ("step", np.arange(steps), "1", "index along the realization length"),
    }
    return io.make_dataset(data, coords, {"title": "cloning error against CPU time"})
