"""visco2008 Fig. 5: μ(λ) of hard disks, cloning Monte Carlo against the Gaussian (Eq. 43)
and first-Sonine (Eqs. 47-49, ends at its fold) closures, the Poisson(ω/√2) generating
function (Eq. 38) and the deterministic solution of Eq. (28); inset: zoom near λ = 0."""

from kinetic import io, plotting
from kinetic.cloning.figures import draw_series, finite, scan_series
from kinetic.workflow_support import start

start(snakemake)
series = scan_series(snakemake.input.scan, "hard_disks", "mu")
closures = io.read_dataset(snakemake.input.closures)
reference = io.read_dataset(snakemake.input.reference)
lam = closures["lam"].values


def curves(axis):
    axis.plot(lam, closures["mu_gaussian"], "-", label="Gaussian (Eq. 43)")
    axis.plot(*finite(lam, closures["mu_sonine"].values), "--", label="Sonine (Eqs. 47-49)")
    axis.plot(lam, closures["mu_poisson_slow"], ":", label=r"Poisson($\omega/\sqrt{2}$)")
    axis.plot(
        reference["lam"], reference["mu"], "-", color="0.6", lw=0.7, label="Eq. (28), quadrature"
    )


fig, ax = plotting.figure()
curves(ax)
draw_series(ax, series)
ax.set_xlabel(r"$\lambda$")
ax.set_ylabel(r"$\mu(\lambda)$")
ax.set_xlim(lam.min(), lam.max())
ax.legend(loc="center right", bbox_to_anchor=(1.0, 0.3), fontsize=5.5)

inner = plotting.inset(ax, (0.47, 0.52, 0.5, 0.45))
curves(inner)
draw_series(inner, series, label="")
inner.set_xlim(0.4, 1.6)
inner.set_ylim(-0.72, -0.33)
plotting.save(fig, snakemake.output.pdf)
