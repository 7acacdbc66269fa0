"""costantini2010 Figs. 4-7 from Table 1: nu* and nu_bar* against 1/N with the linear
extrapolations (Figs 4, 5), both against alpha with theory (Fig 6), and nu_bar*/nu* against
alpha with the white- and coloured-noise predictions (Fig 7)."""

import numpy as np
import pandas as pd

from kinetic import io, plotting
from kinetic.plotting.costantini2010 import METHOD_LABELS, METHOD_STYLE
from kinetic.theory import costantini2010 as theory
from kinetic.workflow_support import start

log = start(snakemake)
study = snakemake.params.study
table = io.read_table(snakemake.input.table)
fits = io.read_table(snakemake.input.fits)
amplitudes = io.read_table(snakemake.input.amplitudes)
measured = table[table.method.isin(["md", "dsmc"])]
production = study["dsmc"]["fictive_factor"]
measured = measured[(measured.method == "md") | (measured.fictive_factor == production)]
finite = measured[measured.n_particles.notna()]
limit = measured[measured.n_particles.isna()]
alphas = sorted(finite.alpha.unique(), reverse=True)
theory_color = METHOD_STYLE["theory"]["color"]


def versus_inverse_n(quantity, symbol, path):
    """nu* or nu_bar* against 1/N, one panel per alpha, with the fitted lines."""
    fig, axes = plotting.figure(1, len(alphas), figsize=(2.4 * len(alphas), 2.6), squeeze=False)
    for ax, alpha in zip(axes[0], alphas, strict=True):
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
                line = np.linspace(0.0, x.max() * 1.05, 50)
                chi2 = "" if np.isnan(fit.chi2) else rf", $\chi^2$={fit.chi2:.2g}/{int(fit.dof)}"
                ax.plot(line, fit.intercept + fit.slope * line, color=style["color"], lw=0.7)
                plotting.errorbar(
                    ax,
                    [0.0],
                    [fit.intercept],
                    [fit.intercept_err],
                    marker=style["marker"],
                    color=style["color"],
                    label=rf"$1/N\to 0${chi2}",
                )
        if quantity == "nu_bar_star":  # the other amplitude: ν̄* from the measured C(0)
            for method in ("dsmc", "md"):
                other = amplitudes[(amplitudes.method == method) & (amplitudes.alpha == alpha)]
                if method == "dsmc":
                    other = other[other.fictive_factor == production]
                ax.errorbar(
                    1000.0 / other.n_particles,
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
    axes[0][0].set_ylabel(symbol)
    plotting.figure_legend(fig)
    plotting.save(fig, path)


versus_inverse_n("nu_star", r"$\nu^*$", snakemake.output.fig04)
versus_inverse_n("nu_bar_star", r"$\bar\nu^*$", snakemake.output.fig05)

grid = np.linspace(min(0.5, min(alphas)), 1.0, 101)
sizes = sorted(int(n) for n in finite.n_particles.unique())
fig, axes = plotting.figure(1, 2, figsize=(6.0, 2.6))
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
                label=f"{METHOD_LABELS[method]}, N = {n}" if k in (0, len(sizes) - 1) else None,
            )
        rows = limit[limit.method == method]
        ax.errorbar(
            rows.alpha,
            rows[quantity],
            rows[f"{quantity}_err"],
            fmt=style["marker"],
            color=style["color"],
            ms=4,
            label=rf"{METHOD_LABELS[method]}, $1/N\to 0$",
        )
    ax.plot(grid, curve(grid), color=theory_color, lw=1, label="first Sonine")
    ax.plot(
        [1.0], [theory.nu_star_elastic()], "*", color=theory_color, ms=6, label="elastic, converged"
    )
    ax.set_xlabel(r"$\alpha$")
    ax.set_ylabel(symbol)
plotting.figure_legend(fig)
plotting.save(fig, snakemake.output.fig06)

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
    for rows, label, size in (
        (limit[limit.method == method], rf"{METHOD_LABELS[method]}, $1/N\to 0$", 4),
        (
            finite[(finite.method == method) & (finite.n_particles == sizes[-1])],
            f"{METHOD_LABELS[method]}, N = {sizes[-1]}",
            3,
        ),
    ):
        plotting.errorbar(
            ax,
            rows.alpha,
            rows.ratio,
            rows.ratio_err,
            marker=style["marker"],
            color=style["color"],
            ms=size,
            label=label,
        )
ax.axhline(1.0, color="0.6", lw=0.5)
shown = pd.concat([limit, finite])
top = max(float((shown.ratio + shown.ratio_err).max()), float(theory.fdr_ratio_white(grid).max()))
ax.set_ylim(0.8, 1.15 * top)  # the coloured-noise curves of small N may leave the frame
ax.set_xlabel(r"$\alpha$")
ax.set_ylabel(r"$\bar\nu^*/\nu^*$")
plotting.legend_outside(ax)
plotting.save(fig, snakemake.output.fig07)
for _, row in limit.iterrows():
    log.info(
        "%s alpha=%g: nu* = %.4f +- %.4f, nu_bar* = %.4f +- %.4f, ratio %.4f +- %.4f",
        row.method,
        row.alpha,
        row.nu_star,
        row.nu_star_err,
        row.nu_bar_star,
        row.nu_bar_star_err,
        row.ratio,
        row.ratio_err,
    )
