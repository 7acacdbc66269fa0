"""Figures of visco2008 that compare a histogrammed density with theory (Figs 1, 2, 10, 12):
a linear panel near the origin, a logarithmic panel over the whole range, and under each
the residuals data / (bin-averaged theory) - 1, for every run given (e.g. both MD
densities). Reads arrays only; never simulates.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from kinetic import plotting
from kinetic.analysis.statistics import chi2_per_dof

__all__ = ["Curve", "Histogram", "comparison_figure"]

RESIDUAL_MAX_RELATIVE_ERROR = 0.2
"""Residual panels show the bins whose relative error is below this: beyond, a residual
says nothing and its error bar would set the axis range for all the others."""


@dataclass
class Histogram:
    """One measured density: bin edges (n + 1), values and standard errors (n)."""

    label: str
    edges: np.ndarray
    density: np.ndarray
    error: np.ndarray
    method: str = "md"
    style: dict = field(default_factory=dict)

    @property
    def centres(self):
        return 0.5 * (self.edges[:-1] + self.edges[1:])


@dataclass
class Curve:
    """A theory line on its grid, with an optional style (a METHOD_STYLE key or dict)."""

    label: str
    x: np.ndarray
    y: np.ndarray
    style: dict


def _residual_limits(values):
    low = min(-0.02, float(np.nanmin(values)))
    high = max(0.02, float(np.nanmax(values)))
    pad = 0.08 * (high - low)
    return low - pad, high + pad


def comparison_figure(
    histograms: list[Histogram],
    reference,
    curves: list[Curve],
    *,
    linear_max: float,
    xlabel: str,
    ylabel: str,
    reference_label: str,
    extra_residuals: list[Curve] = (),
    log_min: float | None = None,
):
    """Build the figure. ``reference(edges)`` returns the bin-averaged theory of the
    residuals on the given edges (NaN where it is not tabulated); it is also drawn as
    steps over the first histogram's bins. ``extra_residuals`` are lines drawn in the
    residual panels (e.g. another theory over the reference, minus 1).

    Returns (figure, numbers): numbers[label] = dict(chi2, dof, shown) of each histogram
    against the reference over the bins shown in the residual panels.
    """
    fig, axes = plotting.figure(
        2,
        2,
        figsize=(6.8, 4.4),
        sharex="col",
        gridspec_kw={"height_ratios": [2.1, 1.0], "hspace": 0.06, "wspace": 0.22},
    )
    numbers = {}
    residual_values = {0: [], 1: []}
    x_max = max(float(h.edges[-1]) for h in histograms)
    first = histograms[0]
    steps = reference(first.edges)
    for column, limit in enumerate((linear_max, x_max)):
        top, bottom = axes[0, column], axes[1, column]
        inside = first.edges[1:] <= limit
        plotting.theory_steps(
            top,
            first.edges[: inside.sum() + 1],
            steps[inside],
            label=f"{reference_label}, bin averages",
            linewidth=0.8,
            zorder=3,
        )
        for curve in curves:
            top.plot(curve.x, curve.y, label=curve.label, zorder=4, **curve.style)
        for histogram in histograms:
            theory = reference(histogram.edges)
            centres = histogram.centres
            shown = (centres <= limit) & (histogram.density > 0)
            plotting.method_errorbar(
                top,
                histogram.method,
                centres[shown],
                histogram.density[shown],
                histogram.error[shown],
                label=histogram.label,
                zorder=2,
                **histogram.style,
            )
            relative = histogram.error / np.where(histogram.density > 0, histogram.density, np.nan)
            kept = shown & (relative < RESIDUAL_MAX_RELATIVE_ERROR) & np.isfinite(theory)
            plotting.residual_panel(
                bottom,
                centres[kept],
                histogram.density[kept],
                histogram.error[kept],
                theory[kept],
                method=histogram.method,
                label=histogram.label,
                zorder=2,
                **histogram.style,
            )
            residual = histogram.density[kept] / theory[kept] - 1
            error = histogram.error[kept] / theory[kept]
            residual_values[column] += [residual - error, residual + error]
            if column == 1:
                chi2, dof = chi2_per_dof(residual, error, 0.0)
                numbers[histogram.label] = {
                    "chi2": chi2,
                    "dof": dof,
                    "x_last": float(centres[kept].max()) if kept.any() else np.nan,
                }
        for curve in extra_residuals:
            keep = curve.x <= limit
            bottom.plot(curve.x[keep], curve.y[keep], label=curve.label, zorder=4, **curve.style)
            residual_values[column].append(curve.y[keep])
        bottom.set_ylim(*_residual_limits(np.concatenate(residual_values[column])))
        bottom.set_xlabel(xlabel)
        top.set_xlim(0, limit)
    axes[0, 0].set_ylabel(ylabel)
    axes[1, 0].set_ylabel("data / theory − 1")
    axes[1, 1].set_ylabel("")
    axes[0, 1].set_yscale("log")
    positive = np.concatenate([h.density[h.density > 0] for h in histograms])
    axes[0, 1].set_ylim(log_min or 0.5 * float(positive.min()), 3.0)
    top_max = max(
        float(np.nanmax(h.density[h.centres <= linear_max] + h.error[h.centres <= linear_max]))
        for h in histograms
    )
    # the first curve is the theory the data are compared with; asymptotic forms that
    # diverge at small x may leave the linear panel
    curve_max = float(np.nanmax(curves[0].y[curves[0].x <= linear_max])) if curves else 0.0
    axes[0, 0].set_ylim(0, 1.08 * max(top_max, curve_max))
    handles, labels = axes[0, 0].get_legend_handles_labels()
    extra_handles, extra_labels = axes[1, 0].get_legend_handles_labels()
    for handle, label in zip(extra_handles, extra_labels, strict=True):
        if label not in labels:
            handles.append(handle)
            labels.append(label)
    fig.legend(handles, labels, loc="upper center", ncol=3, bbox_to_anchor=(0.5, 0.0))
    return fig, numbers
