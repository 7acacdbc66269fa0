"""visco2008 Fig. 3: large deviation function π(n) of the number of collisions."""

from kinetic import io, plotting
from kinetic.workflow_support import start

start(snakemake)
curves = io.read_dataset(snakemake.input.curves)
n = curves["rate"]

fig, ax = plotting.figure()
ax.plot(n, curves["gaussian"], "-", label="Gaussian closure (Eq. 43)")
ax.plot(n, curves["uncorrelated"], "--", label="uncorrelated flights (Eq. 23)")
ax.plot(n, curves["poisson"], "-.", label="Poisson(1)")
ax.plot(n, curves["poisson_slow"], ":", label=r"Poisson($1/\sqrt{2}$)")
ax.set_xlim(0, float(n.max()))
ax.set_ylim(-1.25, 0.05)
ax.set_xlabel(r"$n = \mathcal{N}/t$  ($\omega = 1$)")
ax.set_ylabel(r"$\pi(n)$")
plotting.legend_outside(ax)
plotting.save(fig, snakemake.output.pdf)
