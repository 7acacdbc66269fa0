"""visco2008 Fig. 4: μ(λ) of Maxwell molecules, cloning Monte Carlo against the Poisson
generating function e^{-λ} - 1; inset μ + 1 on a log scale."""

import numpy as np

from kinetic import io, plotting
from kinetic.plotting.visco2008_cloning import draw_series, scan_series
from kinetic.workflow_support import start

start(snakemake)
series = scan_series(snakemake.input.scan, "maxwell", "mu")
closures = io.read_dataset(snakemake.input.closures)
lam = closures["lam"].values

fig, ax = plotting.figure()
ax.plot(lam, closures["mu_poisson"], "-", label=r"Poisson: $e^{-\lambda}-1$")
draw_series(ax, series)
ax.set_xlabel(r"$\lambda$")
ax.set_ylabel(r"$\mu(\lambda)$")
ax.set_xlim(lam.min(), lam.max())
plotting.legend_outside(ax)

inner = plotting.inset(ax, (0.42, 0.18, 0.5, 0.42))
inner.semilogy(lam, closures["mu_poisson"] + 1.0, "-")
draw_series(inner, series, label="", scale=lambda _, v, e: (v + 1.0, e))
inner.set_xlabel(r"$\lambda$", fontsize=7)
inner.set_ylabel(r"$\mu+1$", fontsize=7)
inner.set_xlim(lam.min(), lam.max())
inner.set_ylim(0.5 * np.exp(-lam.max()), 2.0 * np.exp(-lam.min()))
plotting.save(fig, snakemake.output.pdf)
