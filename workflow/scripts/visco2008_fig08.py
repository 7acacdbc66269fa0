"""visco2008 Fig. 8: a2(λ), the kurtosis coefficient of the hard-disk eigenfunction,
cloning Monte Carlo against the first-Sonine closure (valid for small a2, ends at its
fold) and the deterministic solution of Eq. (28)."""

from kinetic import io, plotting
from kinetic.cloning.figures import draw_series, finite, scan_series
from kinetic.workflow_support import start

start(snakemake)
series = scan_series(snakemake.input.scan, "hard_disks", "a2")
closures = io.read_dataset(snakemake.input.closures)
reference = io.read_dataset(snakemake.input.reference)
lam = closures["lam"].values

fig, ax = plotting.figure()
ax.plot(*finite(lam, closures["a2_sonine"].values), "--", label="Sonine (Eqs. 47-49)")
ax.plot(
    *finite(reference["lam"].values, reference["a2"].values),
    "-",
    color="0.6",
    lw=0.7,
    label="Eq. (28), quadrature",
)
ax.axhline(0.0, color="0.8", lw=0.5)
LAMBDA_MAX = 2.6  # beyond, a2 grows past 3 (and the population collapses soon after)
draw_series(ax, series, lam_max=LAMBDA_MAX)
ax.set_xlim(lam.min(), LAMBDA_MAX)
ax.set_ylim(-0.1, 1.2)
ax.set_xlabel(r"$\lambda$")
ax.set_ylabel(r"$a_2(\lambda)$")
ax.legend(loc="upper left", fontsize=6)
plotting.save(fig, snakemake.output.pdf)
