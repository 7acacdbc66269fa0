"""Figures of visco2008 that compare a histogrammed density with theory (Figs 1, 2, 10, 12):
a linear panel near the origin, a logarithmic panel over the whole range, and under each
the residuals data / (bin-averaged theory) - 1, for every run given (e.g. both MD
densities). Reads arrays only; never simulates. Figs 1, 2, 9, 10 and 12 are whole
functions here (``fig01`` ... ``fig12``: the datasets in, the PDF written, the caption's
numbers returned), so that a figure is read in one place; their scripts only read the
files and write the caption.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np

from kinetic import io, plotting
from kinetic.analysis import collision_statistics
from kinetic.analysis.statistics import chi2_per_dof

__all__ = [
    "Curve",
    "Histogram",
    "comparison_figure",
    "fig01",
    "fig02",
    "fig09",
    "fig10",
    "fig12",
]

log = logging.getLogger(__name__)

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


# ---------------------------------------------------------------- the figures


def _md_histograms(runs, density_of):
    """The MD histograms of a figure at two densities (``runs`` sorted by density):
    ``density_of(run)`` -> (bin centres, density, standard error), the lower density in
    small filled markers."""
    histograms = []
    for number, run in enumerate(runs):
        centres, density, sem = density_of(run)
        histograms.append(
            Histogram(
                rf"MD, $\rho\sigma^2 = {run.attrs['density']:g}$",
                collision_statistics.bin_edges(centres),
                density,
                sem,
                style={"markersize": 2.0, "mfc": "black"} if number == 0 else {"markersize": 3.2},
            )
        )
    return histograms


def fig01(curves, md, dsmc, pdf):
    """visco2008 Fig. 1: free-flight-time density P_FFT(t), MD at both densities (and DSMC)
    against Eq. 9 (bin averages for the residuals), Eq. 11 and e^{-t}.

    Drawn from ``curves``, ``md``, ``dsmc`` (the datasets the rule reads) and saved at
    ``pdf``; returns the numbers its caption quotes."""
    grid = curves["time"].values
    survival = curves["hard_spheres_survival"].values

    runs = sorted(md, key=lambda d: d.attrs["density"])
    histograms = _md_histograms(runs, collision_statistics.flight_time_pdf)
    for data in dsmc:
        histograms.append(
            Histogram(
                "DSMC",
                np.asarray(data["time_edges"].values)
                if "time_edges" in data
                else collision_statistics.bin_edges(data["flight_time"].values),
                data["time_pdf"].values,
                data["time_pdf_sem"].values,
                method="dsmc",
                style={"markersize": 2.5},
            )
        )

    t = grid
    asymptotic = np.where(t >= 0.5, curves["hard_spheres_asymptotic"].values, np.nan)
    fig, numbers = comparison_figure(
        histograms,
        lambda edges: collision_statistics.bin_averaged_density(grid, survival, edges),
        [
            Curve("Eq. (9)", t, curves["hard_spheres"].values, plotting.METHOD_STYLE["theory"]),
            Curve("Eq. (11)", t, asymptotic, {"color": "tab:green", "linestyle": ":"}),
            Curve(r"$e^{-t}$", t, curves["maxwell"].values, plotting.METHOD_STYLE["theory_alt"]),
        ],
        linear_max=4.0,
        xlabel=r"$t$  (mean free times, $\omega = 1$)",
        ylabel=r"$P_{\rm FFT}(t)$",
        reference_label="Eq. (9)",
    )
    plotting.save(fig, pdf)
    return _two_densities(runs, numbers)


def _two_densities(runs, numbers):
    """Caption numbers of a figure of MD at two densities against a reference curve: the
    densities (``runs`` sorted by density), the χ² and degrees of freedom of each
    (``numbers`` from ``comparison_figure``, in the same order) and the residual panel's
    error bound in per cent."""
    values = list(numbers.values())
    return dict(
        rho_low=runs[0].attrs["density"],
        rho_high=runs[-1].attrs["density"],
        chi2_low=values[0]["chi2"],
        dof_low=values[0]["dof"],
        chi2_high=values[1]["chi2"],
        dof_high=values[1]["dof"],
        max_error=100 * RESIDUAL_MAX_RELATIVE_ERROR,
    )


def fig02(curves, md, pdf):
    """visco2008 Fig. 2: free-path density P_FPL(x), MD at both densities against Eq. 14 (drawn
    from x = 0, where it is finite; bin averages for the residuals) and the exponential of
    Eq. 16.

    Drawn from ``curves``, ``md`` (the datasets the rule reads) and saved at ``pdf``;
    returns the numbers its caption quotes."""
    grid = curves["path"].values
    survival = curves["hard_spheres_survival"].values
    runs = sorted(md, key=lambda d: d.attrs["density"])
    histograms = _md_histograms(runs, collision_statistics.free_path_pdf)
    fig, numbers = comparison_figure(
        histograms,
        lambda edges: collision_statistics.bin_averaged_density(grid, survival, edges),
        [
            Curve("Eq. (14)", grid, curves["hard_spheres"].values, plotting.METHOD_STYLE["theory"]),
            Curve(
                r"Eq. (16), $e^{-x/(\sqrt{2}\,l)}$",
                grid,
                curves["hard_spheres_tail"].values,
                plotting.METHOD_STYLE["theory_alt"],
            ),
        ],
        linear_max=4.0,
        xlabel=r"$x$  (mean free paths $l = \langle v\rangle/\omega$)",
        ylabel=r"$P_{\rm FPL}(x)$",
        reference_label="Eq. (14)",
    )
    plotting.save(fig, pdf)
    return _two_densities(runs, numbers) | {"p0": float(curves["hard_spheres"].values[0])}


def fig10(curves, md, pdf):
    """visco2008 Fig. 10: P_FFT(t) from MD at both densities against Eq. 9 and the
    Gaussian-weighted P_FFT^W (A1) with its large-time form (A8); residuals against the bin
    averages of Eq. 9, with P^W/P_FFT - 1 (A1 over Eq. 9, both bin-averaged) beside them.

    Drawn from ``curves``, ``md`` (the datasets the rule reads) and saved at ``pdf``;
    returns the numbers its caption quotes."""
    grid = curves["time"].values
    runs = sorted(md, key=lambda d: d.attrs["density"])
    histograms = _md_histograms(runs, collision_statistics.flight_time_pdf)

    def hard_spheres(edges):
        return collision_statistics.bin_averaged_density(
            grid, curves["hard_spheres_survival"].values, edges
        )

    def weighted(edges):
        return collision_statistics.bin_averaged_density(
            grid, curves["weighted_survival"].values, edges
        )

    # P^W/P - 1 on the bins of the low-density run, the ratio the document quotes (≈ 1.3 at
    # large t), as a line in the residual panels
    edges = histograms[0].edges
    edges = edges[edges <= grid[-1]]
    ratio = weighted(edges) / hard_spheres(edges) - 1
    centres = 0.5 * (edges[1:] + edges[:-1])
    asymptotic = np.where(grid >= 1.0, curves["weighted_asymptotic"].values, np.nan)
    fig, numbers = comparison_figure(
        histograms,
        hard_spheres,
        [
            Curve("Eq. (9)", grid, curves["hard_spheres"].values, plotting.METHOD_STYLE["theory"]),
            Curve(
                r"$P^W_{\rm FFT}$ (A1)",
                grid,
                curves["weighted"].values,
                plotting.METHOD_STYLE["theory_alt"],
            ),
            Curve("(A8)", grid, asymptotic, {"color": "tab:gray", "linestyle": ":"}),
        ],
        extra_residuals=[
            Curve(
                r"$P^W_{\rm FFT}/P_{\rm FFT} - 1$",
                centres,
                ratio,
                {**plotting.METHOD_STYLE["theory_alt"], "linewidth": 1.0},
            )
        ],
        linear_max=3.0,
        xlabel=r"$t$  (mean free times, $\omega = 1$)",
        ylabel=r"$P_{\rm FFT}(t)$",
        reference_label="Eq. (9)",
    )
    plotting.save(fig, pdf)
    t_ratio = 10.0
    ratio_at = float(np.interp(t_ratio, centres, ratio)) + 1.0
    return _two_densities(runs, numbers) | {"t_ratio": t_ratio, "ratio": ratio_at}


def fig12(dsmc, curves, pdf):
    """visco2008 Fig. 12: free paths of Maxwell molecules (d = 2), continuous-time DSMC against
    (D3) (drawn from x = 0, where it is π/2; bin averages for the residuals) and (D4).

    Drawn from ``dsmc``, ``curves`` (the datasets the rule reads) and saved at ``pdf``;
    returns the numbers its caption quotes."""
    parameters = io.parameters_of(dsmc)
    if parameters["kernel"] != "maxwell" or parameters["dimension"] != 2:
        raise ValueError(f"Fig. 12 needs Maxwell molecules in d = 2, got {parameters}")
    grid = curves["path"].values
    histogram = Histogram(
        "DSMC",
        dsmc["path_edges"].values,
        dsmc["path_pdf"].values,
        dsmc["path_pdf_sem"].values,
        method="dsmc",
        style={"markersize": 2.5},
    )
    asymptotic = np.where(grid >= 1.0, curves["maxwell_asymptotic"].values, np.nan)
    fig, numbers = comparison_figure(
        [histogram],
        lambda edges: collision_statistics.bin_averaged_density(
            grid, curves["maxwell_survival"].values, edges
        ),
        [
            Curve("Eq. (D3)", grid, curves["maxwell"].values, plotting.METHOD_STYLE["theory"]),
            Curve(
                "large-$x$ form, Eq. (D4)", grid, asymptotic, plotting.METHOD_STYLE["theory_alt"]
            ),
        ],
        linear_max=3.0,
        xlabel=r"$x$  (mean free paths $l = \langle v\rangle/\omega$)",
        ylabel=r"$P_{\rm FPL}(x)$",
        reference_label="Eq. (D3)",
    )
    plotting.save(fig, pdf)
    return dict(
        chi2=numbers["DSMC"]["chi2"],
        dof=numbers["DSMC"]["dof"],
        max_error=100 * RESIDUAL_MAX_RELATIVE_ERROR,
        p0=float(curves["maxwell"].values[0]),
        realizations=int(dsmc.sizes.get("realization", parameters.get("realizations", 0))),
    )


MAX_DRAWN_BINS = 30
"""Fig. 9 draws about this many bins of π_t(n) a panel at most (:func:`fig09`)."""


def fig09(md, finite, asymptotic, windows, min_count, pdf):
    """visco2008 Fig. 9: π(n) of the number of collisions from MD at t = 10 and 50, each against
    the same finite-t estimator applied to the Gaussian closure (Eq. 43, saddle-point order) and
    to the exact Poisson(t) count, with the t -> ∞ curves for reference.

    Bins of P(N) seen fewer than ``min_count`` times are dropped (they sit at the histogram's
    floor). The caption quotes χ²/dof of the data against each finite-t curve (errors over the
    realizations: ``collision_statistics.ERRORS``), computed here from the MD and theory
    files.

    Drawn from ``md``, ``finite``, ``asymptotic``, ``windows``, ``min_count`` (the datasets
    the rule reads) and saved at ``pdf``; returns the numbers its caption quotes."""
    min_count = int(min_count)
    windows = list(windows)
    density = md.attrs["density"]

    fig, axes = plotting.figure(1, len(windows), figsize=(3.4 * len(windows), 2.8), sharey=True)
    axes = np.atleast_1d(axes)
    numbers = {"min_count": min_count, "density": density}
    ratios = []  # counting error over the realizations' error, every bin but the mode
    for axis, window, tag in zip(axes, windows, "ab", strict=False):
        estimate = collision_statistics.count_ldf_estimate(md, window, min_count=min_count)
        counting = collision_statistics.count_ldf_estimate(
            md, window, min_count=min_count, errors="counting"
        )
        spread = estimate["error"] > 0
        ratios.append(counting["error"][spread] / estimate["error"][spread])
        curves = finite.sel(window=window)
        theory_rate = curves["rate"].values
        axis.plot(
            asymptotic["rate"],
            asymptotic["gaussian"],
            ":",
            color="0.55",
            lw=0.9,
            label=r"Gaussian, $t\to\infty$",
        )
        axis.plot(
            asymptotic["rate"],
            asymptotic["poisson"],
            ":",
            color="0.8",
            lw=0.9,
            label=r"Poisson(1), $t\to\infty$",
        )
        axis.plot(
            theory_rate,
            curves["gaussian"],
            **plotting.METHOD_STYLE["theory"],
            label=f"Gaussian closure, $t = {window:g}$",
        )
        axis.plot(
            theory_rate,
            curves["poisson"],
            **plotting.METHOD_STYLE["theory_alt"],
            label=f"Poisson(1), $t = {window:g}$",
        )
        # at most about MAX_DRAWN_BINS markers (69 bins at t = 50 merged into a band that
        # hid the curves), both ends kept; the χ² below takes every bin
        size = estimate["rate"].size
        shown = np.unique(np.r_[np.arange(0, size, max(1, size // MAX_DRAWN_BINS)), size - 1])
        plotting.method_errorbar(
            axis,
            "md",
            estimate["rate"][shown],
            estimate["ldf"][shown],
            estimate["error"][shown],
            markersize=3,
            label=rf"MD, $\rho\sigma^2 = {density:g}$",
            zorder=3,
        )
        numbers[f"shown_{tag}"] = int(shown.size)
        for name in ("gaussian", "poisson"):
            numbers[f"chi2_{name}_{tag}"] = collision_statistics.ldf_chi2_per_dof(
                estimate["rate"],
                estimate["ldf"],
                estimate["error"],
                theory_rate,
                curves[name].values,
            )
        numbers["realizations"] = estimate["realizations"]
        numbers[f"t_{tag}"] = window
        numbers[f"bins_{tag}"] = int(estimate["rate"].size)
        numbers[f"dropped_{tag}"] = estimate["dropped"]
        numbers[f"floor_{tag}"] = float(np.log(1.0 / estimate["total"]) / estimate["t"])
        # every kept point is inside the axes: the range follows the data
        low = min(-1.0, float((estimate["ldf"] - estimate["error"]).min()) - 0.05)
        axis.set_ylim(low, 0.05)
        axis.set_xlim(-0.08, min(3.0, float(asymptotic["rate"].max())))
        axis.set_xlabel(r"$n = \mathcal{N}/t$  ($\omega = 1$)")
        axis.set_title(f"({tag})  $t = {window:g}$")
        log.info("window %s: %s", window, {k: v for k, v in numbers.items() if k.endswith(tag)})
    ratios = np.concatenate(ratios)
    numbers["counting_low"], numbers["counting_median"], numbers["counting_high"] = (
        np.percentile(ratios, [10, 50, 90]) if ratios.size else (np.nan, np.nan, np.nan)
    )
    axes[0].set_ylabel(r"$\pi_t(n)$")
    handles, labels = axes[0].get_legend_handles_labels()
    labels = [label.replace(f"$t = {windows[0]:g}$", "finite $t$") for label in labels]
    fig.legend(handles, labels, loc="lower center", ncol=3, bbox_to_anchor=(0.5, 0.0))
    fig.subplots_adjust(bottom=0.33, wspace=0.1)
    plotting.save(fig, pdf)
    return numbers
