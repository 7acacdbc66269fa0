"""Figures of visco2008 Figs 4-8 and the cloning studies: read the aggregated scan
(results/visco2008/cloning.nc), never simulate, and draw it in the cloning style.

The plotted Monte Carlo value at each λ is the 1/N_c -> 0 extrapolation when the scan has
two or more population sizes there (and, for T and a2, no diversity collapse); otherwise
the largest population's value, drawn with another marker. Kept out of the cloning
package: a change here reruns no simulation and leaves numba's cache of the kernels valid.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kinetic import io, plotting

__all__ = ["Series", "collapsed_points", "data_limits", "draw_series", "finite", "scan_series"]

_POINT_NAMES = {"mu": "mu", "T": "temperature", "a2": "a2", "mu_rate": "mu_rate"}


@dataclass
class Series:
    """Monte Carlo values of one observable against λ: extrapolated (``limit_*``) and
    largest-N_c fallbacks (``single_*``), each sorted by λ."""

    limit_lambda: np.ndarray
    limit_value: np.ndarray
    limit_error: np.ndarray
    single_lambda: np.ndarray
    single_value: np.ndarray
    single_error: np.ndarray
    single_population: int


def scan_series(path, kernel: str, observable: str) -> Series:
    """Read results/visco2008/cloning.nc and return the series of ``observable``
    ('mu', 'mu_rate', 'T' or 'a2') of ``kernel`` ('hard_disks' or 'maxwell')."""
    ds = io.read_dataset(path)
    name = _POINT_NAMES[observable]
    point_kernel = ds["point_kernel"].values.astype(str)
    limit_kernel = ds["limit_kernel"].values.astype(str)
    limits = {}
    for k in np.flatnonzero(limit_kernel == kernel):
        value = float(ds[f"limit_{name}"].values[k])
        error = float(ds[f"limit_{name}_err"].values[k])
        if np.isfinite(value) and np.isfinite(error):
            limits[float(ds["limit_lambda"].values[k])] = (value, error)
    mine = np.flatnonzero(point_kernel == kernel)
    largest = int(ds["point_population"].values[mine].max())
    singles = {}
    for k in mine:
        lam = float(ds["point_lambda"].values[k])
        if lam in limits or int(ds["point_population"].values[k]) != largest:
            continue
        if name in ("temperature", "a2") and int(ds["point_collapse"].values[k]):
            continue
        singles[lam] = (
            float(ds[f"point_{name}"].values[k]),
            float(ds[f"point_{name}_err"].values[k]),
        )

    def arrays(table):
        lams = np.array(sorted(table))
        values = np.array([table[x][0] for x in lams]) if table else np.array([])
        errors = np.array([table[x][1] for x in lams]) if table else np.array([])
        return lams, values, errors

    return Series(*arrays(limits), *arrays(singles), largest)


def finite(x, y):
    """The points of a theory curve where it is defined (the Sonine closure ends at its
    fold near λ ≈ 1.61 and is NaN beyond)."""
    x, y = np.asarray(x), np.asarray(y)
    keep = np.isfinite(y)
    return x[keep], y[keep]


def collapsed_points(path, kernel: str, observable: str):
    """(λ, value, error) of the largest population's points whose runs collapsed onto a
    few clones: not estimates of the eigenfunction, shown only as such."""
    ds = io.read_dataset(path)
    name = _POINT_NAMES[observable]
    kernels = ds["point_kernel"].values.astype(str)
    population = ds["point_population"].values
    largest = population[kernels == kernel].max()
    chosen = np.flatnonzero(
        (kernels == kernel) & (population == largest) & (ds["point_collapse"].values == 1)
    )
    order = chosen[np.argsort(ds["point_lambda"].values[chosen])]
    return (
        ds["point_lambda"].values[order],
        ds[f"point_{name}"].values[order],
        ds[f"point_{name}_err"].values[order],
    )


def draw_series(ax, series: Series, *, scale=None, label="cloning", lam_max=np.inf, **kwargs):
    """Error bars of a Series up to ``lam_max`` in the cloning style (METHOD_STYLE):
    filled where extrapolated to 1/N_c -> 0, open where only the largest population was
    usable (finite-population values, which carry the 1/N_c bias). ``scale(lam, value,
    error) -> (value, error)`` transforms the values first. Returns the values drawn as a
    dict {"limit": (λ, value, error), "single": (...)} for axis limits and captions."""
    color = plotting.METHOD_STYLE["cloning"]["color"]
    parts = [
        (
            "limit",
            series.limit_lambda,
            series.limit_value,
            series.limit_error,
            {"mfc": color},
            rf"{label}, $N_c\to\infty$",
        ),
        (
            "single",
            series.single_lambda,
            series.single_value,
            series.single_error,
            {},
            rf"{label}, $N_c={series.single_population}$ only",
        ),
    ]
    drawn = {}
    for key, lam, value, error, fill, text in parts:
        shown = lam <= lam_max
        lam, value, error = lam[shown], value[shown], error[shown]
        if scale is not None and lam.size:
            value, error = scale(lam, value, error)
        drawn[key] = (lam, value, error)
        if lam.size == 0:
            continue
        plotting.method_errorbar(
            ax,
            "cloning",
            lam,
            value,
            error,
            label=text if label else None,
            zorder=5,
            **fill,
            **kwargs,
        )
    return drawn


def data_limits(drawn, *, pad: float = 0.06, include=()):
    """(low, high) covering every drawn point with its error bar (and the values in
    ``include``), padded: no point is clipped by the axis."""
    values = [np.asarray(include, dtype=float).ravel()]
    for _, value, error in drawn.values():
        ok = np.isfinite(value)
        values += [value[ok] - error[ok], value[ok] + error[ok]]
    values = np.concatenate(values)
    low, high = float(values.min()), float(values.max())
    margin = pad * (high - low)
    return low - margin, high + margin
