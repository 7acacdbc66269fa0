"""costantini2010's visual language: one symbol and colour per method in every figure; the
figures drawn from Table 1 (``fig04`` ... ``fig07``) and the convergence study as whole
functions (the data in, the PDF written), so that their scripts only read and call."""

from __future__ import annotations

import xarray as xr

from kinetic import plotting

__all__ = [
    "METHOD_LABELS",
    "METHOD_STYLE",
    "RESOLVED_ERRORS",
    "convergence_figure",
    "correlation_panel",
    "fig04",
    "fig05",
    "fig06",
    "fig07",
    "inverse_n_figure",
    "ratio_figure",
    "real_per_cell",
    "run_label",
    "transport_figure",
    "transport_rows",
]

METHOD_STYLE = plotting.METHOD_STYLE
"""The project's marker and colour of each method (kinetic.plotting.METHOD_STYLE)."""

METHOD_LABELS = plotting.METHOD_LABELS | {"theory": "theory (first Sonine)"}
"""The project's legend text of each method; costantini2010's theory is first Sonine."""


RESOLVED_ERRORS = 2.0
"""C(τ) is drawn while it stands this many standard errors above zero
(:func:`correlation_panel`)."""


def run_label(result: xr.Dataset, per_cell: bool = True) -> str:
    """Legend text of one run aggregate: method, Λ and (``per_cell``) real particles per
    cell."""
    if result.attrs["engine"] == "md":
        return "MD"
    cells = int(result.attrs["cells_per_side"])
    factor = int(result.attrs["fictive_factor"])
    if cells == 1:
        return rf"homogeneous DSMC, $\Lambda={factor}$"
    if not per_cell:
        return rf"DSMC, $\Lambda={factor}$"
    return rf"DSMC, $\Lambda={factor}$, {real_per_cell(result):.2g} real/cell"


def real_per_cell(result: xr.Dataset) -> float:
    """Real particles per cell of an inhomogeneous DSMC run aggregate."""
    return int(result.attrs["n_particles"]) / int(result.attrs["cells_per_side"]) ** 2


def correlation_panel(
    ax, results, density: float, log=None, per_cell: bool = True, limit: bool = True
) -> float:
    """C(τ) of several runs of one (N, α) on a log scale, each method in its style (the
    runs of one method at several Λ told apart by lightness, darkest the smallest Λ), with
    the first-Sonine prediction A e^{-τ/τ_c} (Eq. 9). Each run is drawn up to its first lag
    where C(τ) is less than :data:`RESOLVED_ERRORS` standard errors above zero: beyond it
    the points are noise about zero, which a log axis would show only where it happens to
    be positive (a false plateau). The DSMC labels give the real particles per cell unless
    ``per_cell`` is false (a figure whose panels differ only in that number says it in
    their titles, and lists DSMC once). The y axis ends at half the lowest point drawn
    (its error bar included), not where the theory line does, unless ``limit`` is false
    (panels sharing their y axis: the caller sets it from the returned lowest point)."""
    import numpy as np

    from kinetic.analysis.costantini2010 import method_of
    from kinetic.theory import costantini2010 as theory

    lowest = np.inf  # the y axis ends below the lowest point drawn, not the theory's
    factors: dict[str, list[int]] = {}
    for result in results:
        factor = int(result.attrs.get("fictive_factor", 1))
        factors.setdefault(method_of(result), []).append(factor)
    for result in results:
        method = method_of(result)
        style = METHOD_STYLE[method]
        own = sorted(set(factors[method]))
        factor = int(result.attrs.get("fictive_factor", 1))
        color = plotting.shade(style["color"], own.index(factor), len(own))
        correlation = result.correlation.values
        error = result.correlation_sem.values
        unresolved = np.flatnonzero(~(correlation > RESOLVED_ERRORS * error))
        end = unresolved[0] if unresolved.size else correlation.size
        keep = np.arange(end)[:: max(1, end // 25)]
        if keep.size:
            lowest = min(lowest, float(np.min(correlation[keep] - error[keep])))
        ax.errorbar(
            result.lag.values[keep],
            correlation[keep],
            yerr=error[keep],
            fmt=style["marker"],
            mfc="none",
            ms=3,
            elinewidth=0.6,
            color=color,
            label=run_label(result, per_cell),
        )
        if log is not None:
            log.info(
                "%s: tau_c = %.4f +- %.4f l/v_s, A = %.4f +- %.4f; C(tau) drawn to %.3g "
                "l/v_s (%d of %d lags resolved)",
                run_label(result),
                float(result.tau_c),
                float(result.tau_c_err),
                float(result.amplitude),
                float(result.amplitude_err),
                float(result.lag.values[max(end - 1, 0)]),
                end,
                correlation.size,
            )
    first = results[0]
    alpha, n = float(first.attrs["restitution"]), int(first.attrs["n_particles"])
    lag = np.linspace(0.0, float(first.lag.max()), 200)
    prediction = theory.correlation_amplitude(alpha, n, density) * np.exp(
        -lag / theory.correlation_time(alpha, n, density)
    )
    ax.plot(lag, prediction, color=METHOD_STYLE["theory"]["color"], lw=1, label="Eq. 9")
    ax.set_yscale("log")
    if limit and np.isfinite(lowest) and lowest > 0:
        ax.set_ylim(bottom=0.5 * lowest)
    ax.set_xlabel(r"$\tau\, v_s/\ell$")
    ax.set_ylabel(r"$C(\tau)$")
    return lowest


def transport_rows(table, study):
    """Table 1's measured rows of Figs 4-7: MD and the production DSMC (Λ of the config),
    split into finite N and the 1/N -> 0 rows; with the restitutions (largest first) and
    the sizes."""
    measured = table[table.method.isin(["md", "dsmc"])]
    production = study["dsmc"]["fictive_factor"]
    measured = measured[(measured.method == "md") | (measured.fictive_factor == production)]
    finite = measured[measured.n_particles.notna()]
    limit = measured[measured.n_particles.isna()]
    alphas = sorted(finite.alpha.unique(), reverse=True)
    sizes = sorted(int(n) for n in finite.n_particles.unique())
    return finite, limit, alphas, sizes


def fit_band(fit, inverse_n):
    """Standard error of a fitted line a + b/N at ``inverse_n`` (1/N) from the fit's
    errors and ``covariance`` of a and b (``statistics.line_error``); None for a table
    without the covariance."""
    import numpy as np

    from kinetic.analysis.statistics import line_error

    covariance = getattr(fit, "covariance", np.nan)
    if not np.isfinite(covariance):
        return None
    return line_error(inverse_n, fit.intercept_err, fit.slope_err, covariance)


def inverse_n_figure(table, fits, amplitudes, study, quantity, symbol):
    """Figs 4 (ν*) and 5 (ν̄*): ``quantity`` against 1/N, one panel per α, with the 1/N
    fits of ``fits`` extrapolated to 1/N -> 0 (shaded: their standard error,
    :func:`fit_band`), the first-Sonine value, and for ν̄* also
    the values from the measured C(0) (``amplitudes``)."""
    import numpy as np

    from kinetic.theory import costantini2010 as theory

    finite, _, alphas, _ = transport_rows(table, study)
    production = study["dsmc"]["fictive_factor"]
    theory_color = METHOD_STYLE["theory"]["color"]
    fig, axes = plotting.figure(1, len(alphas), figsize=(2.4 * len(alphas), 2.6), squeeze=False)
    for ax, alpha in zip(axes[0], alphas, strict=True):
        goodness = []  # each fit's χ², written in its panel (the legend is the figure's)
        for method in ("dsmc", "md"):
            rows = finite[(finite.method == method) & (finite.alpha == alpha)]
            if rows.empty:
                continue
            style = METHOD_STYLE[method]
            x = 1000.0 / rows.n_particles.to_numpy(float)
            plotting.errorbar(
                ax,
                x,
                rows[quantity],
                rows[f"{quantity}_err"],
                marker=style["marker"],
                color=style["color"],
                label=METHOD_LABELS[method],
            )
            fit = fits[
                (fits.method == method) & (fits.alpha == alpha) & (fits.quantity == quantity)
            ]
            if not fit.empty:
                fit = fit.iloc[0]
                line = np.linspace(0.0, x.max() * 1.05, 50)  # 10³/N
                # the fit is a + b/N: b/N = b x/1000 on this axis
                fitted = fit.intercept + fit.slope * line / 1000.0
                ax.plot(line, fitted, color=style["color"], lw=0.7)
                band = fit_band(fit, line / 1000.0)
                if band is not None:  # the line's standard error, from the fit's covariance
                    ax.fill_between(
                        line, fitted - band, fitted + band, color=style["color"], alpha=0.15, lw=0
                    )
                plotting.errorbar(
                    ax,
                    [0.0],
                    [fit.intercept],
                    [fit.intercept_err],
                    marker=style["marker"],
                    color=style["color"],
                    mfc=style["color"],
                    label=rf"{METHOD_LABELS[method]}, $1/N\to 0$",
                )
                if not np.isnan(fit.chi2):
                    goodness.append(
                        rf"{METHOD_LABELS[method]} $\chi^2$ = {fit.chi2:.2g}/{int(fit.dof)}"
                    )
        if quantity == "nu_bar_star":  # the other amplitude: ν̄* from the measured C(0)
            for method in ("dsmc", "md"):
                other = amplitudes[(amplitudes.method == method) & (amplitudes.alpha == alpha)]
                if method == "dsmc":
                    other = other[other.fictive_factor == production]
                ax.errorbar(  # a little right of the fitted-amplitude points they shadow
                    1000.0 / other.n_particles + 0.03,
                    other.nu_bar_star_c0,
                    other.nu_bar_star_c0_err,
                    fmt=METHOD_STYLE[method]["marker"],
                    color=METHOD_STYLE[method]["color"],
                    alpha=0.3,
                    ms=3,
                    label=f"{METHOD_LABELS[method]}, from C(0)",
                )
        ax.axhline(
            getattr(theory, quantity if quantity == "nu_star" else "nu_bar_star_white")(alpha),
            color=theory_color,
            lw=0.8,
            label="first Sonine",
        )
        ax.set_title(rf"$\alpha = {alpha:g}$", fontsize=8)
        ax.set_xlabel(r"$10^3/N$")
        ax.set_xlim(left=-0.05)
        if goodness:
            ax.text(0.03, 0.03, "\n".join(goodness), transform=ax.transAxes, fontsize=6)
    axes[0][0].set_ylabel(symbol)
    plotting.figure_legend(fig)
    return fig


def _alpha_grid(alphas):
    import numpy as np

    return np.linspace(min(0.5, min(alphas)), 1.0, 101)


def transport_figure(table, study):
    """Fig 6: ν* and ν̄* against α at every N and for 1/N -> 0, with the first-Sonine
    curves and the converged elastic ν*."""
    from kinetic.theory import costantini2010 as theory

    finite, limit, alphas, sizes = transport_rows(table, study)
    grid = _alpha_grid(alphas)
    theory_color = METHOD_STYLE["theory"]["color"]
    fig, axes = plotting.figure(1, 2, figsize=(6.0, 2.6))
    fig.subplots_adjust(wspace=0.3)  # the right panel's label clear of the left's ticks
    for ax, quantity, symbol, curve in (
        (axes[0], "nu_star", r"$\nu^*$", theory.nu_star),
        (axes[1], "nu_bar_star", r"$\bar\nu^*$", theory.nu_bar_star_white),
    ):
        for method in ("dsmc", "md"):
            style = METHOD_STYLE[method]
            for k, n in enumerate(sizes):
                rows = finite[(finite.method == method) & (finite.n_particles == n)]
                plotting.errorbar(
                    ax,
                    rows.alpha + (0.004 * k if method == "md" else -0.004 * k),
                    rows[quantity],
                    rows[f"{quantity}_err"],
                    marker=style["marker"],
                    color=style["color"],
                    alpha=0.35 + 0.65 * (k + 1) / len(sizes),
                    ms=3,
                    label=f"{METHOD_LABELS[method]}, N = {n}",
                )
            rows = limit[limit.method == method]
            ax.errorbar(
                rows.alpha + 0.004 * len(sizes) * (1 if method == "md" else -1),
                rows[quantity],
                rows[f"{quantity}_err"],
                fmt=style["marker"],
                color=style["color"],
                ms=4,
                label=rf"{METHOD_LABELS[method]}, $1/N\to 0$",
            )
        ax.plot(grid, curve(grid), color=theory_color, lw=1, label="first Sonine")
        ax.plot(
            [1.0],
            [theory.nu_star_elastic()],
            "*",
            color=theory_color,
            ms=6,
            label="elastic, converged",
        )
        ax.set_xlabel(r"$\alpha$")
        ax.set_ylabel(symbol)
    plotting.figure_legend(fig)
    return fig


def ratio_figure(table, study):
    """Fig 7: ν̄*/ν* against α for 1/N -> 0 (filled) and the largest N (open), MD and
    DSMC on either side of each α, with the white-noise and the coloured-noise
    predictions."""
    import pandas as pd

    from kinetic.theory import costantini2010 as theory

    finite, limit, alphas, sizes = transport_rows(table, study)
    grid = _alpha_grid(alphas)
    theory_color = METHOD_STYLE["theory"]["color"]
    fig, ax = plotting.figure()
    ax.plot(grid, theory.fdr_ratio_white(grid), color=theory_color, lw=1, label="white noise")
    for n, dash in zip(sizes, ("--", "-.", ":", (0, (1, 3)), (0, (5, 1))), strict=False):
        ax.plot(
            grid,
            theory.fdr_ratio_coloured(grid, n, study["density"]),
            color=theory_color,
            ls=dash,
            lw=0.8,
            label=f"coloured noise, N = {n}",
        )
    for method in ("dsmc", "md"):
        style = METHOD_STYLE[method]
        side = 1 if method == "md" else -1  # the methods apart at each α, and the two rows
        for rows, label, size, fill, shift in (
            (limit[limit.method == method], rf"{METHOD_LABELS[method]}, $1/N\to 0$", 4, True, 1),
            (
                finite[(finite.method == method) & (finite.n_particles == sizes[-1])],
                f"{METHOD_LABELS[method]}, N = {sizes[-1]}",
                3,
                False,
                3,
            ),
        ):
            plotting.errorbar(  # filled: extrapolated, as in Figs 4-6
                ax,
                rows.alpha + side * 0.004 * shift,
                rows.ratio,
                rows.ratio_err,
                marker=style["marker"],
                color=style["color"],
                mfc=style["color"] if fill else "none",
                ms=size,
                label=label,
            )
    ax.axhline(1.0, color="0.6", lw=0.5)
    shown = pd.concat([limit, finite])
    top = max(
        float((shown.ratio + shown.ratio_err).max()), float(theory.fdr_ratio_white(grid).max())
    )
    ax.set_ylim(0.8, 1.15 * top)  # the coloured-noise curves of small N may leave the frame
    ax.set_xlabel(r"$\alpha$")
    ax.set_ylabel(r"$\bar\nu^*/\nu^*$")
    plotting.legend_outside(ax)
    return fig


def fig04(table, fits, amplitudes, study, pdf) -> None:
    """Fig. 4: ν* against 1/N per α with the 1/N fits of Table 1 (``inverse_n_figure``),
    saved at ``pdf``."""
    plotting.save(inverse_n_figure(table, fits, amplitudes, study, "nu_star", r"$\nu^*$"), pdf)


def fig05(table, fits, amplitudes, study, pdf) -> None:
    """Fig. 5: ν̄* against 1/N per α with the 1/N fits of Table 1 (``inverse_n_figure``),
    saved at ``pdf``."""
    figure = inverse_n_figure(table, fits, amplitudes, study, "nu_bar_star", r"$\bar\nu^*$")
    plotting.save(figure, pdf)


def fig06(table, study, pdf) -> None:
    """Fig. 6 (``transport_figure``), saved at ``pdf``."""
    plotting.save(transport_figure(table, study), pdf)


def fig07(table, study, pdf) -> None:
    """Fig. 7 (``ratio_figure``), saved at ``pdf``."""
    plotting.save(ratio_figure(table, study), pdf)


def convergence_figure(table, study, pdf) -> None:
    """DSMC's systematic errors at α = 1: ν* against the squared collision cell side (at the
    production time step) and against the squared time step (at the production cells),
    as measured and with the paper rule's collision excess and the cells' collisional
    transfer removed (``nu_star_corrected``, filled markers), beside the first-Sonine and
    converged elastic values; ``table`` is
    ``kinetic.analysis.costantini2010.convergence_table``'s. Saved at ``pdf``."""
    from kinetic.theory import costantini2010 as theory

    production_step = study["dsmc"]["time_step"]
    production_cells = table.loc[
        (table.cell_side - study["dsmc"]["cell_side"]).abs().idxmin(), "cell_side"
    ]
    fig, axes = plotting.figure(1, 2, figsize=(6.0, 2.6), sharey=True)
    style = METHOD_STYLE["dsmc"]
    for ax, column, fixed, fixed_value, label in (
        (axes[0], "cell_side", "time_step", production_step, r"cell side / $\lambda$"),
        (axes[1], "time_step", "cell_side", production_cells, r"$\Delta\tau\ \omega_c$"),
    ):
        rows = table[(table[fixed] - fixed_value).abs() < 1e-6 * fixed_value].sort_values(column)
        measured = f"DSMC, N = {rows.n_particles.iloc[0]}"
        for name, fill, series in (
            ("nu_star", "none", measured),
            ("nu_star_corrected", style["color"], "rule's excess and cells' transfer removed"),
        ):
            plotting.errorbar(
                ax,
                rows[column] ** 2,
                rows[name],
                rows[f"{name}_err"],
                marker=style["marker"],
                color=style["color"],
                mfc=fill,
                label=series,
            )
        ax.axhline(
            theory.nu_star(1.0),
            color=METHOD_STYLE["theory"]["color"],
            lw=0.8,
            label="first Sonine",
        )
        ax.axhline(
            theory.nu_star_elastic(),
            color=METHOD_STYLE["theory"]["color"],
            lw=0.8,
            ls="--",
            label="converged Sonine",
        )
        ax.set_xlabel(f"({label})$^2$")
    axes[0].set_ylabel(r"$\nu^*$ ($\alpha = 1$)")
    plotting.figure_legend(fig)
    plotting.save(fig, pdf)
