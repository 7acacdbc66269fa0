"""costantini2010's visual language: one symbol and colour per method in every figure."""

from __future__ import annotations

import xarray as xr

from kinetic import plotting

__all__ = ["METHOD_LABELS", "METHOD_STYLE", "correlation_panel", "run_label"]

METHOD_STYLE = plotting.METHOD_STYLE
"""The project's marker and colour of each method (kinetic.plotting.METHOD_STYLE)."""

METHOD_LABELS = plotting.METHOD_LABELS | {"theory": "theory (first Sonine)"}
"""The project's legend text of each method; costantini2010's theory is first Sonine."""


def run_label(result: xr.Dataset) -> str:
    """Legend text of one run aggregate: method, Λ and real particles per cell."""
    if result.attrs["engine"] == "md":
        return "MD"
    cells = int(result.attrs["cells_per_side"])
    factor = int(result.attrs["fictive_factor"])
    if cells == 1:
        return rf"homogeneous DSMC, $\Lambda={factor}$"
    per_cell = int(result.attrs["n_particles"]) / cells**2
    return rf"DSMC, $\Lambda={factor}$, {per_cell:.2g} real/cell"


def correlation_panel(ax, results, density: float, log=None) -> None:
    """C(τ) of several runs of one (N, α) on a log scale, each method in its style (DSMC
    runs shaded by Λ), with the first-Sonine prediction A e^{-τ/τ_c} (Eq. 9)."""
    import numpy as np

    from kinetic.analysis.costantini2010 import method_of
    from kinetic.theory import costantini2010 as theory

    factors = sorted({int(r.attrs.get("fictive_factor", 1)) for r in results})
    for result in results:
        method = method_of(result)
        style = METHOD_STYLE[method]
        color = style["color"]
        if method == "dsmc" and len(factors) > 1:
            shade = factors.index(int(result.attrs["fictive_factor"])) / (len(factors) - 1)
            color = (0.1, 0.3 + 0.3 * shade, 0.9 - 0.5 * shade)
        keep = np.flatnonzero(result.correlation.values > 0)
        step = max(1, keep.size // 25)
        keep = keep[::step]
        ax.errorbar(
            result.lag.values[keep],
            result.correlation.values[keep],
            yerr=result.correlation_sem.values[keep],
            fmt=style["marker"],
            mfc="none",
            ms=3,
            elinewidth=0.6,
            color=color,
            label=run_label(result),
        )
        if log is not None:
            log.info(
                "%s: tau_c = %.4f +- %.4f l/v_s, A = %.4f +- %.4f",
                run_label(result),
                float(result.tau_c),
                float(result.tau_c_err),
                float(result.amplitude),
                float(result.amplitude_err),
            )
    first = results[0]
    alpha, n = float(first.attrs["restitution"]), int(first.attrs["n_particles"])
    lag = np.linspace(0.0, float(first.lag.max()), 200)
    prediction = theory.correlation_amplitude(alpha, n, density) * np.exp(
        -lag / theory.correlation_time(alpha, n, density)
    )
    ax.plot(lag, prediction, color=METHOD_STYLE["theory"]["color"], lw=1, label="Eq. 9")
    ax.set_yscale("log")
    ax.set_xlabel(r"$\tau\, v_s/\ell$")
    ax.set_ylabel(r"$C(\tau)$")
