"""Shared figure style and helpers; rendering is headless (Agg).

Usage in a figure script::

    from kinetic import plotting
    fig, ax = plotting.figure()
    ...
    plotting.save(fig, "results/visco2008/fig03.pdf")   # writes the .png twin too
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import matplotlib
import numpy as np

matplotlib.use("Agg")

import matplotlib.pyplot as plt

__all__ = [
    "METHOD_LABELS",
    "METHOD_STYLE",
    "STYLE",
    "bin_average",
    "density_points",
    "errorbar",
    "figure",
    "figure_legend",
    "inset",
    "legend_outside",
    "method_errorbar",
    "residual_panel",
    "save",
    "shade",
    "theory_steps",
]

STYLE = Path(__file__).with_name("kinetic.mplstyle")
plt.style.use(STYLE)


METHOD_STYLE: dict[str, dict[str, Any]] = {
    "md": {"marker": "o", "color": "black"},
    "dsmc": {"marker": "s", "color": "tab:blue"},
    "dsmc_homogeneous": {"marker": "v", "color": "tab:cyan"},
    "cloning": {"marker": "^", "color": "tab:red"},
    "direct": {"marker": "D", "color": "tab:purple"},
    "markov": {"marker": "v", "color": "tab:orange"},
    "theory": {"color": "tab:green", "linestyle": "-"},
    "theory_alt": {"color": "tab:gray", "linestyle": "--"},
}
"""One symbol and colour per method, the same in every figure of every document (MD,
DSMC, its one-cell homogeneous variant, cloning, direct and Markov-chain sampling; theory
as lines, a second theory dashed)."""

METHOD_LABELS = {
    "md": "MD",
    "dsmc": "DSMC",
    "dsmc_homogeneous": "homogeneous DSMC",
    "cloning": "cloning",
    "direct": "direct sampling",
    "markov": "Markov chain",
    "theory": "theory",
    "theory_alt": "theory",
}


def shade(color, index: int, count: int):
    """Member ``index`` of ``count`` runs of one method told apart by lightness: the
    method's ``color`` darkened for the first, lightened for the last (itself when alone)."""
    from matplotlib.colors import to_rgb

    base = np.asarray(to_rgb(color))
    if count < 2:
        return tuple(base)
    where = index / (count - 1) - 0.5  # -0.5 (darkest) ... +0.5 (lightest)
    target = np.ones(3) if where > 0 else np.zeros(3)
    return tuple(base + 1.1 * abs(where) * (target - base))


def figure(nrows: int = 1, ncols: int = 1, **kwargs):
    """A figure in the shared style; keyword arguments go to ``plt.subplots``."""
    return plt.subplots(nrows, ncols, **kwargs)


def inset(ax, bounds=(0.55, 0.55, 0.4, 0.4), **kwargs):
    """An inset axes at ``bounds`` (x0, y0, width, height in axes fraction)."""
    child = ax.inset_axes(bounds, **kwargs)
    child.tick_params(labelsize=6)
    return child


def errorbar(ax, x, y, yerr, *, label=None, marker="o", **kwargs):
    """Simulation points: open markers (unless ``mfc`` says otherwise, e.g. to tell two
    runs of one method apart) with their standard errors."""
    kwargs.setdefault("mfc", "none")
    return ax.errorbar(x, y, yerr=yerr, fmt=marker, label=label, elinewidth=0.7, **kwargs)


def density_points(ax, x, density, error, *, x_max, every, **kwargs):
    """A histogrammed density as error-bar points: bins up to ``x_max`` with a positive
    value, one in ``every`` of them (so the markers stay apart)."""
    shown = (x <= x_max) & (density > 0)
    shown[shown] &= np.arange(shown.sum()) % every == 0
    return errorbar(ax, x[shown], density[shown], error[shown], **kwargs)


def save(fig, pdf_path: str | os.PathLike) -> None:
    """Save ``fig`` as PDF at ``pdf_path`` and as a PNG twin beside it, then close it."""
    pdf_path = Path(pdf_path)
    pdf_path.parent.mkdir(parents=True, exist_ok=True)
    # fixed metadata keeps the PDF bytes reproducible
    fig.savefig(pdf_path, metadata={"CreationDate": None, "Creator": "kinetic"})
    fig.savefig(pdf_path.with_suffix(".png"))
    plt.close(fig)


def legend_outside(ax, *, ncols: int = 1, **kwargs):
    """The legend of ``ax`` to the right of the axes, off the data, at the style's size."""
    kwargs.setdefault("loc", "upper left")
    kwargs.setdefault("bbox_to_anchor", (1.02, 1.0))
    kwargs.setdefault("borderaxespad", 0.0)
    return ax.legend(ncols=ncols, **kwargs)


def figure_legend(fig, *, ncols: int = 3, handles=None, **kwargs):
    """One legend for every axes of ``fig`` (each label once), above the panels; or of
    ``handles`` (artists made for the legend alone), in the same place."""
    if handles is not None:
        handles = {handle.get_label(): handle for handle in handles}
        labels = list(handles)
    else:
        handles, labels = {}, []
        for ax in fig.axes:
            for handle, label in zip(*ax.get_legend_handles_labels(), strict=True):
                if label not in handles:
                    handles[label] = handle
                    labels.append(label)
    # just above the highest panel (and its title), not at the figure's top edge, which
    # leaves the default top margin empty between legend and panels
    top = max(ax.get_position().y1 for ax in fig.axes)
    titled = any(ax.get_title() for ax in fig.axes if ax.get_position().y1 == top)
    kwargs.setdefault("loc", "lower center")
    kwargs.setdefault("bbox_to_anchor", (0.5, top + (0.05 if titled else 0.01)))
    return fig.legend([handles[label] for label in labels], labels, ncols=ncols, **kwargs)


def method_errorbar(ax, method: str, x, y, yerr, *, label=None, **kwargs):
    """Simulation points of ``method`` (a key of METHOD_STYLE) with their standard errors,
    in the method's marker and colour; ``label`` defaults to the method's name."""
    style = {**METHOD_STYLE[method], **kwargs}
    marker = style.pop("marker", "o")
    label = METHOD_LABELS[method] if label is None else label
    return errorbar(ax, x, y, yerr, label=label, marker=marker, **style)


def bin_average(function: Callable[[np.ndarray], np.ndarray], edges, points: int = 12):
    """The mean of ``function`` over each bin [edges[i], edges[i+1]] (Gauss-Legendre with
    ``points`` nodes per bin): the quantity a histogram estimates, to compare like with
    like near steep fronts and contacts."""
    edges = np.asarray(edges, dtype=float)
    nodes, weights = np.polynomial.legendre.leggauss(points)
    left, right = edges[:-1, None], edges[1:, None]
    x = 0.5 * (right - left) * nodes[None, :] + 0.5 * (right + left)
    return 0.5 * (function(x) * weights[None, :]).sum(axis=1)


def theory_steps(ax, edges, values, *, method: str = "theory", label=None, **kwargs):
    """Bin-averaged theory drawn as steps over the histogram's bins."""
    style = {k: v for k, v in METHOD_STYLE[method].items() if k != "marker"}
    style.update(kwargs)
    label = METHOD_LABELS[method] if label is None else label
    return ax.stairs(values, edges, label=label, baseline=None, **style)


def residual_panel(
    ax, x, data, error, theory, *, method: str = "md", label=None, theory_error=None, **kwargs
):
    """Residuals data/theory - 1 with their errors, beside a zero line; points where the
    theory vanishes are skipped. ``theory_error``: the reference's own standard error
    (another simulation's), propagated with the data's."""
    data, error, theory = (np.asarray(a, dtype=float) for a in (data, error, theory))
    ok = theory != 0
    spread = error[ok] / np.abs(theory[ok])
    if theory_error is not None:
        reference = np.asarray(theory_error, dtype=float)[ok]
        spread = np.hypot(spread, data[ok] * reference / theory[ok] ** 2)
    ax.axhline(0.0, color="0.6", linewidth=0.6, zorder=0)
    ax.set_ylabel("data/theory − 1")
    return method_errorbar(
        ax,
        method,
        np.asarray(x)[ok],
        data[ok] / theory[ok] - 1.0,
        spread,
        label=label,
        **kwargs,
    )
