"""Shared figure style and helpers; rendering is headless (Agg).

Usage in a figure script::

    from kinetic import plotting
    fig, ax = plotting.figure()
    ...
    plotting.save(fig, "results/visco2008/fig03.pdf")   # writes the .png twin too
"""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")

import matplotlib.pyplot as plt

__all__ = ["STYLE", "density_points", "errorbar", "figure", "inset", "save"]

STYLE = Path(__file__).with_name("kinetic.mplstyle")
plt.style.use(STYLE)


def figure(nrows: int = 1, ncols: int = 1, **kwargs):
    """A figure in the shared style; keyword arguments go to ``plt.subplots``."""
    return plt.subplots(nrows, ncols, **kwargs)


def inset(ax, bounds=(0.55, 0.55, 0.4, 0.4), **kwargs):
    """An inset axes at ``bounds`` (x0, y0, width, height in axes fraction)."""
    child = ax.inset_axes(bounds, **kwargs)
    child.tick_params(labelsize=6)
    return child


def errorbar(ax, x, y, yerr, *, label=None, marker="o", **kwargs):
    """Simulation points: open markers with their standard errors."""
    return ax.errorbar(
        x, y, yerr=yerr, fmt=marker, mfc="none", label=label, elinewidth=0.7, **kwargs
    )


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
