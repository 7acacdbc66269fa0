"""visco2008 Fig. 1: free-flight-time density P_FFT(t), MD (and DSMC) against Eqs. 9, 11."""

import numpy as np

from kinetic import io, plotting
from kinetic.analysis import collision_statistics
from kinetic.workflow_support import start

start(snakemake)
md = io.read_dataset(snakemake.input.md)
curves = io.read_dataset(snakemake.input.curves)
t_md, pdf_md, sem_md = collision_statistics.flight_time_pdf(md)
dsmc = [io.read_dataset(path) for path in snakemake.input.dsmc]
t = curves["time"].values
asymptotic = np.where(t >= 0.5, curves["hard_spheres_asymptotic"].values, np.nan)
density = md.attrs["density"]

fig, ax = plotting.figure()
inset = plotting.inset(ax)
for axis, t_max, every in ((ax, 4.0, 2), (inset, float(t_md.max()), 5)):
    plotting.density_points(
        axis,
        t_md,
        pdf_md,
        sem_md,
        x_max=t_max,
        every=every,
        markersize=3,
        label=rf"MD, $\rho\sigma^2 = {density:g}$",
    )
    for data in dsmc:
        flight_time = data["flight_time"].values
        plotting.density_points(
            axis,
            flight_time,
            data["time_pdf"].values,
            data["time_pdf_sem"].values,
            x_max=t_max,
            every=max(1, int(np.sum(flight_time <= t_max)) // 25),  # about 25 squares
            marker="s",
            markersize=3,
            label="DSMC",
        )
    axis.plot(t, curves["hard_spheres"], "-", color="k", label="Eq. (9)")
    axis.plot(t, asymptotic, "-.", color="C3", label="Eq. (11)")
    axis.plot(t, curves["maxwell"], "--", color="C2", label=r"$e^{-t}$")
    axis.set_xlim(0, t_max)
inset.set_yscale("log")
inset.set_ylim(max(1e-6, 0.3 * float(pdf_md[pdf_md > 0].min())), 2)
ax.set_ylim(0, 1.1)
ax.set_xlabel(r"$t$  (mean free times, $\omega = 1$)")
ax.set_ylabel(r"$P_{\rm FFT}(t)$")
ax.legend(loc="center right", bbox_to_anchor=(1.0, 0.27), fontsize=6)
plotting.save(fig, snakemake.output.pdf)
