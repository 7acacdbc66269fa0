"""visco2008 Fig. 12: free paths of Maxwell molecules (d = 2), DSMC against D3 and D4."""

import numpy as np

from kinetic import io, plotting
from kinetic.workflow_support import start

start(snakemake)
dsmc = io.read_dataset(snakemake.input.dsmc)
curves = io.read_dataset(snakemake.input.curves)
parameters = io.parameters_of(dsmc)
if parameters["kernel"] != "maxwell" or parameters["dimension"] != 2:
    raise ValueError(f"Fig. 12 needs Maxwell molecules in d = 2, got {parameters}")

x, pdf, sem = dsmc["free_path"].values, dsmc["path_pdf"].values, dsmc["path_pdf_sem"].values
edges = dsmc["path_edges"].values
path, d3 = curves["path"].values, curves["maxwell"].values
# the DSMC points are bin averages: compare them with bin averages of (D3)
inside = edges[-1] <= path[-1]
fine = edges[:-1, None] + np.diff(edges)[:, None] * (np.arange(16) + 0.5) / 16
d3_bins = np.interp(fine, path, d3).mean(axis=1) if inside else np.interp(x, path, d3)
shown = pdf > 0

fig, ax = plotting.figure()
ax.semilogy(path, d3, "-", color="C0", label="Eq. (D3)", zorder=1)
ax.semilogy(
    path, curves["maxwell_asymptotic"], "--", color="C1", label="large-$x$ form, Eq. (D4)", zorder=1
)
plotting.errorbar(
    ax, x[shown], pdf[shown], sem[shown], label="DSMC", markersize=3, color="C2", zorder=2
)
ax.set_xlim(0, float(min(edges[-1], path.max())))
ax.set_ylim(max(0.3 * pdf[shown].min(), 1e-8), 3)
ax.set_xlabel(r"$x$  (mean free paths $l = \langle v\rangle/\omega$)")
ax.set_ylabel(r"$P_{\rm FPL}(x)$")
ax.legend(loc="lower left")

residual = plotting.inset(ax, bounds=(0.56, 0.6, 0.4, 0.33))
plotting.errorbar(
    residual,
    x[shown],
    pdf[shown] / d3_bins[shown] - 1,
    sem[shown] / d3_bins[shown],
    markersize=2,
    color="C2",
)
residual.axhline(0.0, color="C0", linewidth=0.8)
residual.set_ylim(-0.1, 0.1)
residual.set_xlabel(r"$x$", fontsize=6, labelpad=1)
residual.set_title("DSMC / (D3) - 1", fontsize=6, pad=2)
plotting.save(fig, snakemake.output.pdf)
