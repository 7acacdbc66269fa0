"""visco2008 Fig. 8: a2(λ), the kurtosis coefficient of the hard-disk eigenfunction,
cloning Monte Carlo against the first-Sonine closure (valid for small a2, ends at its
fold) and the deterministic solution of Eq. (28)."""

import numpy as np

from kinetic import io, plotting
from kinetic.plotting.visco2008_cloning import data_limits, draw_series, finite, scan_series
from kinetic.workflow_support import start, write_caption

start(snakemake)
series = scan_series(snakemake.input.scan, "hard_disks", "a2")
closures = io.read_dataset(snakemake.input.closures)
reference = io.read_dataset(snakemake.input.reference)
lam = closures["lam"].values

fig, ax = plotting.figure()
ax.plot(
    *finite(lam, closures["a2_sonine"].values),
    "--",
    color="tab:green",
    label="Sonine (Eqs. 47-49)",
)
ax.plot(
    *finite(reference["lam"].values, reference["a2"].values),
    "-",
    color="0.3",
    lw=0.7,
    label="Eq. (28), quadrature",
)
ax.axhline(0.0, color="0.8", lw=0.5)
# every usable point is drawn (runs whose population collapsed onto a few clones are
# not estimates of a2 and are left out by scan_series); the axes follow the points
drawn = draw_series(ax, series)
shown_lam = np.concatenate([drawn["limit"][0], drawn["single"][0]])
ax.set_xlim(lam.min() - 0.1, float(shown_lam.max()) + 0.2)
ax.set_ylim(*data_limits(drawn, include=[-0.1, 1.2]))
ax.set_xlabel(r"$\lambda$")
ax.set_ylabel(r"$a_2(\lambda)$")
ax.legend(loc="upper left")
plotting.save(fig, snakemake.output.pdf)
write_caption(
    snakemake.input.template,
    snakemake.output.caption,
    population=series.single_population,
    n_single=int(drawn["single"][0].size),
    n_limit=int(drawn["limit"][0].size),
    lambdas_single=", ".join(f"{x:g}" for x in drawn["single"][0]) or "none",
)
