"""visco2008 Fig. 2: free-path density P_FPL(x), MD against Eq. 14; inset Eq. 16 tail."""

from kinetic import io, plotting
from kinetic.analysis import collision_statistics
from kinetic.workflow_support import start

start(snakemake)
md = io.read_dataset(snakemake.input.md)
curves = io.read_dataset(snakemake.input.curves)
x_md, pdf_md, sem_md = collision_statistics.free_path_pdf(md)
x = curves["path"].values
density = md.attrs["density"]

fig, ax = plotting.figure()
inset = plotting.inset(ax)
for axis, x_max, every in ((ax, 4.0, 2), (inset, float(x_md.max()), 5)):
    plotting.density_points(
        axis,
        x_md,
        pdf_md,
        sem_md,
        x_max=x_max,
        every=every,
        markersize=3,
        label=rf"MD, $\rho\sigma^2 = {density:g}$",
    )
    axis.plot(x, curves["hard_spheres"], "-", color="k", label="Eq. (14)")
    axis.set_xlim(0, x_max)
inset.plot(x, curves["hard_spheres_tail"], "--", color="C3", label="Eq. (16)")
inset.set_yscale("log")
inset.set_ylim(max(1e-6, 0.3 * float(pdf_md[pdf_md > 0].min())), 3)
ax.set_ylim(0, 1.25)
ax.set_xlabel(r"$x$  (mean free paths $l = \langle v\rangle/\omega$)")
ax.set_ylabel(r"$P_{\rm FPL}(x)$")
ax.legend(loc="center right", bbox_to_anchor=(1.0, 0.27), fontsize=6)
plotting.save(fig, snakemake.output.pdf)
