"""Collision statistics from the observer datasets of ``kinetic.edmd.simulate``, and the
free-flight densities of ``kinetic.dsmc.simulate_free_flights`` batches
(``combine_free_flights``).

Unit conversion happens here and nowhere else: time in units of the *measured* mean free
time τ = 1/ω with ω = 2 C / (N T) (C pair collisions in a production time T, each counting
for two particles), lengths in units of the mean free path l = ⟨|v|⟩ τ with the Maxwellian
mean speed of the measured temperature (visco2008 Eq. 15: l = ⟨v⟩/ω; the mean of the
free paths equals it exactly in theory).

Error bars come from independent realizations (standard error of the mean over the
``realization`` axis), π(n) included (``ERRORS``).
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence

import numpy as np
import xarray as xr

from kinetic import io
from kinetic.analysis.statistics import error_against_cpu, mean_and_sem
from kinetic.batches import combine

__all__ = [
    "ERRORS",
    "bin_averaged_density",
    "bin_edges",
    "collision_frequency",
    "combine_free_flights",
    "count_large_deviation",
    "count_ldf_estimate",
    "cumulant_dataset",
    "cumulant_table",
    "error_against_cpu_time",
    "extrapolated_cumulants",
    "flight_time_pdf",
    "free_path_pdf",
    "histogram_cumulants",
    "ldf_chi2_per_dof",
    "mean_free_path",
    "mean_free_time",
    "scaled_cumulants",
]


def histogram_cumulants(histogram, axis: int = -1) -> np.ndarray:
    """Cumulants p = 1, 2, 3 of integer counts n = 0, 1, ... given their histogram along
    ``axis``. Returns an array whose first axis is p (mean, variance, third central
    moment; plain 1/n normalisation), NaN where the histogram is empty."""
    histogram = np.moveaxis(np.asarray(histogram, dtype=float), axis, -1)
    n = np.arange(histogram.shape[-1], dtype=float)
    total = histogram.sum(axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = (histogram * n).sum(axis=-1) / total
        centred = n - mean[..., None]
        second = (histogram * centred**2).sum(axis=-1) / total
        third = (histogram * centred**3).sum(axis=-1) / total
    return np.stack([mean, second, third])


def collision_frequency(dataset, checkpoint: int = -1) -> np.ndarray:
    """ω per realization (collisions per particle per unit time) up to a checkpoint."""
    n = dataset.attrs["n_particles"]
    collisions = dataset["collisions"].values[:, checkpoint]
    duration = dataset["production_time"].values[:, checkpoint]
    return 2.0 * collisions / (n * duration)


def mean_free_time(dataset) -> float:
    """Measured mean free time of all realizations pooled (full production)."""
    n = dataset.attrs["n_particles"]
    return float(
        n
        * dataset["production_time"].values[:, -1].sum()
        / (2.0 * dataset["collisions"].values[:, -1].sum())
    )


def mean_free_path(dataset) -> float:
    """l = ⟨|v|⟩ τ with the Maxwellian mean speed of the measured temperature."""
    dimension = dataset.attrs["dimension"]
    temperature = float(dataset["temperature"].values[:, -1].mean())
    if dimension == 2:
        speed = math.sqrt(math.pi * temperature / 2.0)
    else:
        speed = math.sqrt(8.0 * temperature / math.pi)
    return speed * mean_free_time(dataset)


def scaled_cumulants(dataset, checkpoint: int = -1) -> np.ndarray:
    """⟨N^p⟩_c / t per realization: array (realization, window, order p = 1..3).

    t = (window length in simulation time) × ω of that realization's production up to the
    checkpoint, i.e. time in units of the measured mean free time, so ⟨N⟩/t ≈ 1 up to the
    windows cut off at the end of the run.
    """
    histogram = dataset["window_histogram"].values[:, checkpoint]  # (r, w, count)
    cumulants = histogram_cumulants(histogram)  # (p, r, w)
    omega = collision_frequency(dataset, checkpoint)  # (r,)
    t = dataset["window_time"].values * omega[:, None]  # (r, w)
    return np.moveaxis(cumulants / t[None], 0, -1)


def cumulant_table(dataset, checkpoint: int = -1) -> dict:
    """Mean and standard error over realizations of ⟨N^p⟩_c / t: arrays (window, order)."""
    values = scaled_cumulants(dataset, checkpoint)
    mean, sem = mean_and_sem(values, axis=0)
    return {
        "window": dataset["window"].values,
        "order": np.arange(1, 4),
        "scaled_cumulant": mean,
        "scaled_cumulant_sem": sem,
    }


def extrapolated_cumulants(dataset, windows, checkpoint: int = -1) -> dict:
    """⟨N^p⟩_c/t extrapolated to t -> ∞ by a fit k_p(t) = k_p(∞) + c_p/t over ``windows``.

    For a stationary count with integrable correlations Var N_t = 2 D t - C + o(1), and
    likewise for the third cumulant, so the finite-t cumulants approach their limit as
    1/t once t exceeds the correlation time of the free flights (a few mean free times).
    The fit is made realization by realization (least squares in 1/t, with t that
    realization's window in measured mean free times), and the spread of the intercepts
    over the independent realizations gives the error: the windows of one realization
    share their collisions, so their cumulants are correlated and a pooled fit would not
    give an honest error.

    Returns a dict: ``order`` (p = 1, 2, 3), ``value`` and ``sem`` of k_p(∞), ``slope`` and
    ``slope_sem`` of c_p, ``windows`` (the t used).
    """
    windows = np.asarray(windows, dtype=float)
    if windows.size < 2:
        raise ValueError(f"need at least two windows to extrapolate in 1/t, got {windows}")
    index = np.array([int(np.argmin(np.abs(dataset["window"].values - w))) for w in windows])
    if not np.allclose(dataset["window"].values[index], windows):
        raise ValueError(f"windows {list(windows)} not all observed: {dataset['window'].values}")
    values = scaled_cumulants(dataset, checkpoint)[:, index, :]  # (r, w, p)
    omega = collision_frequency(dataset, checkpoint)
    inverse_t = 1.0 / (dataset["window_time"].values[:, index] * omega[:, None])  # (r, w)
    intercepts, slopes = [], []
    for r in range(values.shape[0]):
        design = np.stack([np.ones_like(inverse_t[r]), inverse_t[r]], axis=1)
        coefficients, *_ = np.linalg.lstsq(design, values[r], rcond=None)  # (2, p)
        intercepts.append(coefficients[0])
        slopes.append(coefficients[1])
    value, sem = mean_and_sem(np.array(intercepts), axis=0)
    slope, slope_sem = mean_and_sem(np.array(slopes), axis=0)
    return {
        "order": np.arange(1, 4),
        "value": value,
        "sem": sem,
        "slope": slope,
        "slope_sem": slope_sem,
        "windows": windows,
    }


def _pdf(histograms, totals, bin_width):
    """Per-realization densities -> pooled density and SEM over realizations."""
    histograms = np.asarray(histograms, dtype=float)
    totals = np.asarray(totals, dtype=float)
    per_realization = histograms / (totals[:, None] * bin_width)
    pooled = histograms.sum(axis=0) / (totals.sum() * bin_width)
    _, sem = mean_and_sem(per_realization, axis=0)
    return pooled, sem


def bin_edges(centres) -> np.ndarray:
    """Edges of uniform bins given their centres."""
    centres = np.asarray(centres, dtype=float)
    width = centres[1] - centres[0]
    return np.append(centres - 0.5 * width, centres[-1] + 0.5 * width)


def bin_averaged_density(grid, survival, edges) -> np.ndarray:
    """Bin averages (S(a) - S(b))/(b - a) of a density from its survival function S
    tabulated on ``grid``: exactly what a histogram estimates. ln S is interpolated by a
    cubic spline (ln S is close to linear in the tails, and S is smooth at 0 where the
    density itself may have an x ln x term); bins beyond the grid are NaN."""
    from scipy.interpolate import CubicSpline

    grid, survival, edges = (np.asarray(a, dtype=float) for a in (grid, survival, edges))
    keep = survival > 0
    spline = CubicSpline(grid[keep], np.log(survival[keep]))
    inside = (edges >= grid[keep][0]) & (edges <= grid[keep][-1])
    values = np.where(inside, np.exp(spline(np.clip(edges, grid[0], grid[keep][-1]))), np.nan)
    return (values[:-1] - values[1:]) / np.diff(edges)


def flight_time_pdf(dataset) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """P_FFT(t) with t in measured mean free times: (bin centres, density, SEM)."""
    tau = mean_free_time(dataset)
    width = dataset.attrs["flight_time_bin_width"] / tau
    centres = dataset["flight_time"].values / tau
    density, sem = _pdf(
        dataset["flight_time_histogram"].values, dataset["flight_count"].values, width
    )
    return centres, density, sem


def free_path_pdf(dataset) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """P_FPL(x) with x in mean free paths l: (bin centres, density, SEM)."""
    length = mean_free_path(dataset)
    width = dataset.attrs["free_path_bin_width"] / length
    centres = dataset["free_path"].values / length
    density, sem = _pdf(
        dataset["free_path_histogram"].values, dataset["flight_count"].values, width
    )
    return centres, density, sem


ERRORS = ("realizations", "counting")
"""How ``count_ldf_estimate`` errs π_t(n): the spread of the realizations' histograms, or
the pooled counting error 1/(t √count), which treats every particle-window as
independent, and leaves out the normalisation by the mode. In the default build's MD (64
realizations of 1000 disks, revision 7d10f92), with the realizations' error of ln P(k)
alone (before 2026-12-01, also without the normalisation), the two agreed: their ratio was
0.8-1.2 over the bins at t = 10 and 50 and both densities (median 0.94-1.00), so the
particles' shared windows and partners add no measurable scatter; Fig. 9's caption now
gives the ratio to the error with the normalisation. Until then the realizations counted
in windows of the mean free time each had measured while equilibrating, 1.4 % apart, and
the spread of the window lengths made the realizations' histograms scatter 16-40 times
more than Poisson (the ratio was 3-4 in the centre): the realizations' spread is the error
that sees such a defect."""


def count_large_deviation(
    dataset, window: float, checkpoint: int = -1, *, min_count: int = 1, errors="realizations"
):
    """Finite-time estimate of π(n) from the pooled count histogram at window length t:

        π_t(n) = (1/t) ln[P(N = n t) / max_k P(N = k)],   n = N / t,

    with t in measured mean free times (pooled ω). Returns (n, π_t, error) for counts
    observed at least ``min_count`` times; ``errors`` as in :func:`count_ldf_estimate`.
    """
    estimate = count_ldf_estimate(dataset, window, checkpoint, min_count=min_count, errors=errors)
    return estimate["rate"], estimate["ldf"], estimate["error"]


def count_ldf_estimate(
    dataset, window: float, checkpoint: int = -1, *, min_count: int = 1, errors="realizations"
):
    """π_t(n) of ``count_large_deviation`` with its bookkeeping, as a dict: ``count`` (k),
    ``rate`` (n = k/t), ``ldf``, ``error``, ``t`` (window in measured mean free times),
    ``total`` (pooled counts), ``dropped`` (observed bins with fewer than ``min_count``),
    ``realizations``.

    ``errors`` (``ERRORS``): ``"realizations"`` (default) errs ln(P(k)/P(mode)) by the
    standard error over realizations of P_r(k)/P(k) − P_r(mode)/P(mode), with P_r(k) =
    h_r(k)/Σ h_r each realization's fraction (the delta method, the mode's error 0);
    ``"counting"`` by 1/√count, which understates it (``ERRORS``).

    Bins seen fewer than ``min_count`` times are left out: a bin seen once sits at the
    floor ln(1/total)/t whatever its probability (a false plateau at the ends of the
    range), and its counting error is far from Gaussian.
    """
    if min_count < 1:
        raise ValueError(f"min_count must be >= 1, got {min_count}")
    if errors not in ERRORS:
        raise ValueError(f"errors must be one of {ERRORS}, got {errors!r}")
    index = int(np.argmin(np.abs(dataset["window"].values - window)))
    per_realization = dataset["window_histogram"].values[:, checkpoint, index].astype(float)
    histogram = per_realization.sum(axis=0)
    n_particles = dataset.attrs["n_particles"]
    omega = (
        2.0
        * dataset["collisions"].values[:, checkpoint].sum()
        / (n_particles * dataset["production_time"].values[:, checkpoint].sum())
    )
    t = float(dataset["window_time"].values[:, index].mean() * omega)
    counts = np.arange(histogram.size)
    kept = histogram >= min_count
    probability = histogram[kept] / histogram.sum()
    if errors == "counting":
        error = 1.0 / (t * np.sqrt(histogram[kept]))
    else:
        # π_t = ln(P(k)/P(mode))/t: to first order its deviation in a realization is that
        # of f(k)/P(k) − f(mode)/P(mode); the normalisation's own scatter and its
        # covariance with P(k) (negative: the fractions sum to 1) were left out, which
        # made the errors near the mode 0.75-0.8 times the estimate's scatter, and gave
        # the mode, 0 by construction, an error
        fractions = per_realization[:, kept] / per_realization.sum(axis=1, keepdims=True)
        mode = int(np.argmax(probability))
        relative = fractions / probability - (fractions[:, mode] / probability[mode])[:, None]
        _, sem = mean_and_sem(relative, axis=0)
        error = sem / t
    return {
        "count": counts[kept],
        "rate": counts[kept] / t,
        "ldf": np.log(probability / probability.max()) / t,
        "error": error,
        "t": t,
        "total": int(histogram.sum()),
        "dropped": int(np.sum((histogram > 0) & ~kept)),
        "realizations": int(per_realization.shape[0]),
    }


def error_against_cpu_time(dataset, window: float = 10.0) -> dict:
    """Standard error of ⟨N²⟩_c/t and ⟨N³⟩_c/t at one window length against CPU time.

    One row per checkpoint (production length per realization): the cumulative histograms
    at that checkpoint give each realization's estimate, the spread over realizations the
    standard error; the CPU time is the sum over realizations (equilibration included).
    """
    index = int(np.argmin(np.abs(dataset["window"].values - window)))
    checkpoints = np.arange(dataset.sizes["checkpoint"])

    def estimate(c):
        mean, sem = mean_and_sem(scaled_cumulants(dataset, c)[:, index, :], axis=0)
        return mean[1:], sem[1:]

    curve = error_against_cpu(
        checkpoints, estimate, lambda c: dataset["cpu_time"].values[:, c].sum()
    )
    return {
        "production_length": dataset["checkpoint"].values.astype(float),
        "realizations": np.full(checkpoints.size, dataset.sizes["realization"]),
        "collisions": dataset["collisions"].values.sum(axis=0).astype(int),
        "cpu_time": curve.cpu_seconds,
        "k2": curve.value[:, 0],
        "k2_sem": curve.error[:, 0],
        "k3": curve.value[:, 1],
        "k3_sem": curve.error[:, 1],
    }


def cumulant_dataset(dataset, windows=None, extrapolation_windows=None) -> xr.Dataset:
    """Table I input: ⟨N^p⟩_c/t and its standard error for the requested windows.

    Coordinates ``window`` (t, mean free times) and ``order`` (p = 1, 2, 3); data variables
    ``scaled_cumulant`` and ``scaled_cumulant_sem``; global attribute ``density`` (ρσ²).
    With ``extrapolation_windows``, also ``extrapolated_cumulant`` and
    ``extrapolated_cumulant_sem`` (order): the t -> ∞ values of ``extrapolated_cumulants``,
    and the attribute ``extrapolation_windows``.
    """
    table = cumulant_table(dataset)
    index = np.arange(table["window"].size)
    if windows is not None:
        index = np.array([int(np.argmin(np.abs(table["window"] - w))) for w in windows])
        if not np.allclose(table["window"][index], windows):
            raise ValueError(f"windows {list(windows)} not all observed: {table['window']}")
    parameters = io.parameters_of(dataset)
    variables = {}
    attrs = {"density": float(parameters["density"])}
    if extrapolation_windows is not None:
        limit = extrapolated_cumulants(dataset, extrapolation_windows)
        variables = {
            "extrapolated_cumulant": (
                "order",
                limit["value"],
                "1",
                "<N^p>_c / t extrapolated to t -> infinity (fit in 1/t per realization)",
            ),
            "extrapolated_cumulant_sem": (
                "order",
                limit["sem"],
                "1",
                "standard error over independent realizations of the extrapolation",
            ),
        }
        attrs["extrapolation_windows"] = limit["windows"]
    result = io.make_dataset(
        {
            **variables,
            "scaled_cumulant": (
                ("window", "order"),
                table["scaled_cumulant"][index],
                "1",
                "<N^p>_c / t, t in measured mean free times (MD)",
            ),
            "scaled_cumulant_sem": (
                ("window", "order"),
                table["scaled_cumulant_sem"][index],
                "1",
                "standard error over independent realizations",
            ),
        },
        coords={
            "window": ("window", table["window"][index], "mean free times", "counting window t"),
            "order": ("order", table["order"], "1", "cumulant order p"),
        },
        attrs=attrs,
    )
    return io.stamp(
        result,
        parameters={**parameters, "density": float(parameters["density"])},
        seed=int(dataset.attrs["seed"]),
        config=json.loads(dataset.attrs.get("config", "{}")),
    )


def combine_free_flights(
    batches: Sequence[xr.Dataset], *, names: Sequence[str] | None = None
) -> xr.Dataset:
    """Free-flight densities over every realization of ``simulate_free_flights`` batches.

    The batches must share their parameters except the realization range, and hold
    distinct realizations (two or more in all); an error names the batches by ``names``
    (e.g. their files, as ``kinetic.batches.combine``). Returns a dataset with the densities
    ``time_pdf``/``path_pdf`` (mean over realizations) and their standard errors
    ``time_pdf_sem``/``path_pdf_sem`` on the bin centres ``flight_time`` (1/ω) and
    ``free_path`` (l), the per-realization densities, the measured collision frequency
    (mean and sem), and totals of flights, unresolved paths and CPU seconds.
    """
    # one run's parameters and seed, distinct realizations
    run = combine(list(batches), names=names)
    realizations = run.realization.values
    time_pdf = run.time_pdf.values
    path_pdf = run.path_pdf.values
    frequency = run.collision_frequency.values
    time_mean, time_sem = mean_and_sem(time_pdf)
    path_mean, path_sem = mean_and_sem(path_pdf)
    frequency_mean, frequency_sem = mean_and_sem(frequency)

    def total(name: str):
        return sum(batch[name].values.sum() for batch in batches)

    dataset = io.make_dataset(
        {
            "time_pdf": (
                "flight_time",
                time_mean,
                "omega",
                "free-flight time density P_FFT, mean over realizations",
            ),
            "time_pdf_sem": ("flight_time", time_sem, "omega", "standard error of time_pdf"),
            "path_pdf": (
                "free_path",
                path_mean,
                "1/l",
                "free-path density P_FPL, mean over realizations",
            ),
            "path_pdf_sem": ("free_path", path_sem, "1/l", "standard error of path_pdf"),
            "time_pdf_by_realization": (
                ("realization", "flight_time"),
                time_pdf,
                "omega",
                "free-flight time density of each realization",
            ),
            "path_pdf_by_realization": (
                ("realization", "free_path"),
                path_pdf,
                "1/l",
                "free-path density of each realization",
            ),
            "time_edges": (
                "flight_time_edge",
                run.time_edges.values,
                "1/omega",
                "flight-time bin edges",
            ),
            "path_edges": ("free_path_edge", run.path_edges.values, "l", "free-path bin edges"),
            "collision_frequency": (
                (),
                frequency_mean,
                "omega",
                "measured collisions per particle per unit time",
            ),
            "collision_frequency_sem": (
                (),
                frequency_sem,
                "omega",
                "standard error of collision_frequency",
            ),
            "flights": ((), total("flights"), "1", "recorded free flights, all realizations"),
            "unresolved_paths": (
                (),
                total("unresolved_paths"),
                "1",
                "open flights of unknown free path, all realizations",
            ),
            "cpu_seconds": ((), total("cpu_seconds"), "s", "CPU time of all realizations"),
        },
        coords={
            "realization": ("realization", realizations, "1", "realization index"),
            "flight_time": (
                "flight_time",
                run.flight_time.values,
                "1/omega",
                "free-flight time (bin centre)",
            ),
            "free_path": ("free_path", run.free_path.values, "l", "free path (bin centre)"),
            "flight_time_edge": (
                "flight_time_edge",
                run.flight_time_edge.values,
                "1/omega",
                "bin edge",
            ),
            "free_path_edge": ("free_path_edge", run.free_path_edge.values, "l", "bin edge"),
        },
        attrs={"engine": "kinetic.dsmc", "units": run.attrs["units"]},
    )
    parameters = io.parameters_of(run)
    parameters.pop("first_realization", None)
    return io.stamp(dataset, parameters=parameters, seed=int(run.attrs["seed"]))


def ldf_chi2_per_dof(rate, ldf, error, theory_rate, theory) -> float:
    """χ²/dof of a measured large-deviation function (``ldf`` with ``error`` at ``rate``,
    :func:`count_ldf_estimate`) against a curve (``theory`` on ``theory_rate``),
    interpolated at the data's rates, over the rates the curve covers."""
    from kinetic.analysis.statistics import chi2_per_dof

    theory_rate, theory = np.asarray(theory_rate, dtype=float), np.asarray(theory, dtype=float)
    ok = np.isfinite(theory)
    values = np.interp(rate, theory_rate[ok], theory[ok], left=np.nan, right=np.nan)
    return chi2_per_dof(ldf, error, values)[0]
