"""visco2008 Fig. 9: π(n) of the number of collisions from MD at t = 10 and 50, against the
Gaussian closure (Legendre transform of Eq. 43) and Poisson(1)."""

from kinetic import io, plotting
from kinetic.analysis import collision_statistics
from kinetic.workflow_support import start

start(snakemake)
md = io.read_dataset(snakemake.input.md)
curves = io.read_dataset(snakemake.input.curves)
n = curves["rate"]

fig, ax = plotting.figure()
for window, marker in zip(snakemake.params.windows, "osD^v", strict=False):
    rate, ldf, error = collision_statistics.count_large_deviation(md, window)
    plotting.errorbar(
        ax, rate, ldf, error, marker=marker, markersize=3, label=rf"MD, $t = {window:g}$"
    )
ax.plot(n, curves["gaussian"], "-", color="k", label="Gaussian closure (Eq. 43)")
ax.plot(n, curves["poisson"], "--", color="C3", label="Poisson(1)")
ax.set_xlim(0, min(3.0, float(n.max())))
ax.set_ylim(-1.0, 0.05)
ax.set_xlabel(r"$n = \mathcal{N}/t$  ($\omega = 1$)")
ax.set_ylabel(r"$\pi(n)$")
ax.legend(loc="lower center", fontsize=6)
plotting.save(fig, snakemake.output.pdf)
