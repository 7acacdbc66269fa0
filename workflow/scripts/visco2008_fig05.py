"""visco2008 Fig. 5: μ(λ) of hard disks, cloning Monte Carlo against the Gaussian (Eq. 43)
and first-Sonine (Eqs. 47-49, ends at its fold) closures, the Poisson(ω/√2) generating
function (Eq. 38) and the deterministic solution of Eq. (28); inset: zoom near λ = 0.
Open triangles are finite-population values (one N_c usable): their 1/N_c bias can put
them below the exact bound μ >= -ω/√2; the caption counts them from the scan file."""

import numpy as np

from kinetic import io, plotting
from kinetic.plotting.visco2008_cloning import data_limits, draw_series, finite, scan_series
from kinetic.workflow_support import start, write_caption

start(snakemake)
series = scan_series(snakemake.input.scan, "hard_disks", "mu")
closures = io.read_dataset(snakemake.input.closures)
reference = io.read_dataset(snakemake.input.reference)
lam = closures["lam"].values
BOUND = -1.0 / np.sqrt(2.0)


def curves(axis):
    axis.plot(
        lam, closures["mu_gaussian"], **plotting.METHOD_STYLE["theory"], label="Gaussian (Eq. 43)"
    )
    axis.plot(
        *finite(lam, closures["mu_sonine"].values),
        color="tab:green",
        linestyle="--",
        label="Sonine (Eqs. 47-49)",
    )
    axis.plot(
        lam,
        closures["mu_poisson_slow"],
        **plotting.METHOD_STYLE["theory_alt"],
        label=r"Poisson($\omega/\sqrt{2}$)",
    )
    axis.plot(
        reference["lam"], reference["mu"], "-", color="0.3", lw=0.7, label="Eq. (28), quadrature"
    )


fig, ax = plotting.figure(figsize=(3.4, 3.6))
curves(ax)
drawn = draw_series(ax, series)
ax.axhline(BOUND, color="0.7", lw=0.5, ls=":", zorder=0)
ax.set_xlabel(r"$\lambda$")
ax.set_ylabel(r"$\mu(\lambda)$")
ax.set_xlim(lam.min() - 0.2, lam.max() + 0.2)
ax.set_ylim(*data_limits(drawn, include=closures["mu_gaussian"].values))
fig.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2)

inner = plotting.inset(ax, (0.47, 0.52, 0.5, 0.45))
curves(inner)
draw_series(inner, series, label="")
inner.set_xlim(0.4, 1.6)
inner.set_ylim(-0.72, -0.33)
plotting.save(fig, snakemake.output.pdf)

single_lam, single_mu, single_err = drawn["single"]
below = single_mu < BOUND
write_caption(
    snakemake.input.template,
    snakemake.output.caption,
    population=series.single_population,
    n_single=int(single_lam.size),
    n_below=int(below.sum()),
    lambdas_below=", ".join(f"{x:g}" for x in single_lam[below]) or "none",
    n_limit=int(drawn["limit"][0].size),
)
