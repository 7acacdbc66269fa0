"""montanero2007 Figs. 5 and 6: phi(c_x^2) (Eq. 4.3) and its truncated Sonine series (4.5).

The caption gives, per alpha, chi^2 per point of the drawn DSMC points against phi_1, phi_2
and phi_3 (the points' standard errors; the measured b'_k's own errors left out): how much
each further Sonine term helps.
"""

import numpy as np

from kinetic import plotting
from kinetic.analysis import montanero2007 as analysis
from kinetic.analysis.montanero2007 import load_runs
from kinetic.workflow_support import start, write_caption

log = start(snakemake)
rebin, cx2_max = snakemake.params.rebin, snakemake.params.cx2_max
runs = list(load_runs(snakemake.input.runs).values())
fits = []  # per alpha: chi^2 per point against phi_1..3
fig, axes = plotting.figure(
    len(runs), 1, sharex=True, figsize=(3.4, 1.8 * len(runs) + 0.5), squeeze=False
)
for ax, ds in zip(axes[:, 0], runs, strict=True):
    summary = analysis.steady_summary_of(ds)
    curves = analysis.distributions_of(ds, summary, rebin_factor=rebin)
    x = curves["phi_cx2"]
    shown = x <= cx2_max
    plotting.method_errorbar(
        ax,
        "dsmc",
        x[shown],
        curves["phi"][shown],
        curves["phi_err"][shown],
        markersize=2.5,
        label=r"DSMC $\varphi$",
    )
    dense = np.linspace(0.0, cx2_max, 400)
    alpha = summary["parameters"]["restitution"]
    points = shown & (curves["phi_err"] > 0)
    chi2 = []
    for p, style in zip(range(1, 4), [":", "-.", "--"], strict=True):
        ax.plot(
            dense,
            analysis.theory.phi_sonine(dense, summary["b_full"][:p]),
            style,
            label=rf"$\varphi_{p}$",
        )
        residual = curves["phi"][points] - analysis.theory.phi_sonine(
            x[points], summary["b_full"][:p]
        )
        chi2.append(float(np.mean((residual / curves["phi_err"][points]) ** 2)))
    fits.append((alpha, chi2, int(points.sum())))
    log.info(
        "alpha = %g: chi^2 per point against phi_1, phi_2, phi_3: %.2f, %.2f, %.2f (%d points)",
        alpha,
        *chi2,
        points.sum(),
    )
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.text(0.97, 0.92, rf"$\alpha = {alpha:g}$", transform=ax.transAxes, ha="right", va="top")
    ax.set_ylabel(r"$\varphi(c_x^2)$")
    log.info("alpha = %g: b' = %s", alpha, np.array2string(summary["b_full"], precision=4))
plotting.figure_legend(fig, ncols=3)
axes[-1, 0].set_xlabel(r"$c_x^2$")
axes[-1, 0].set_xlim(0.0, cx2_max)
plotting.save(fig, snakemake.output.pdf)
write_caption(
    snakemake.input.template,
    snakemake.output.caption,
    cx2_max=cx2_max,
    fits="; ".join(
        f"α = {alpha:g}: {chi2[0]:.2f}, {chi2[1]:.2f}, {chi2[2]:.2f} ({n} points)"
        for alpha, chi2, n in fits
    ),
)
