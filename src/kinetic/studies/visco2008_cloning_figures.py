"""Drawing helpers of visco2008 Figs 4-8 (cloning Monte Carlo against theory), kept out of
the cloning package so that a change of style never reruns a simulation."""

from __future__ import annotations

import numpy as np

from kinetic.cloning.figures import Series

__all__ = ["data_limits", "draw_series"]


def draw_series(ax, series: Series, *, scale=None, label="cloning", lam_max=np.inf, **kwargs):
    """Error bars of a Series up to ``lam_max`` in the cloning style (METHOD_STYLE):
    filled where extrapolated to 1/N_c -> 0, open where only the largest population was
    usable (finite-population values, which carry the 1/N_c bias). ``scale(lam, value,
    error) -> (value, error)`` transforms the values first. Returns the values drawn as a
    dict {"limit": (λ, value, error), "single": (...)} for axis limits and captions."""
    from kinetic import plotting

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
