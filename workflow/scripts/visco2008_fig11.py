"""visco2008 Fig. 11: free-flight-time densities of three collision kernels (d = 2)."""

from kinetic import io, plotting
from kinetic.workflow_support import start

start(snakemake)
curves = io.read_dataset(snakemake.input.curves)
t = curves["time"]

fig, ax = plotting.figure()
ax.semilogy(t, curves["very_hard_particles"], "--", color="C1", label="very hard particles (B4)")
ax.semilogy(t, curves["hard_spheres"], "-", color="C2", label="hard spheres (Eq. 9)")
ax.semilogy(t, curves["maxwell"], ":", color="C3", label="Maxwell molecules")
ax.set_xlim(0, min(15.0, float(t.max())))
ax.set_ylim(1e-6, 2)
ax.set_xlabel(r"$t$  (mean free times, $\omega = 1$)")
ax.set_ylabel(r"$P_{\rm FFT}(t)$")
ax.legend(loc="lower left")
plotting.save(fig, snakemake.output.pdf)
