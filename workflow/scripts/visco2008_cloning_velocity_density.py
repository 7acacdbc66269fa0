"""Velocity-component density of the hard-disk cloning population (the eigenfunction
f̃(v, λ) of Eq. 28) at a few λ, against the Gaussian of the measured T(λ)."""

import numpy as np

from kinetic import io, plotting
from kinetic.workflow_support import start

start(snakemake)
ds = io.read_dataset(snakemake.input.scan)
kernel = ds["point_kernel"].values.astype(str)
population = ds["point_population"].values
lam = ds["point_lambda"].values
mine = (kernel == "hard_disks") & (population == population[kernel == "hard_disks"].max())
chosen = [k for k in np.flatnonzero(mine) if ds["point_collapse"].values[k] == 0]
wanted = [-1.5, 0.0, 1.0, 2.0, 3.0]
picked = sorted(
    {min(chosen, key=lambda k, w=w: abs(lam[k] - w)) for w in wanted}, key=lambda k: lam[k]
)
v = ds["velocity"].values

fig, ax = plotting.figure()
for k in picked:
    temperature = float(ds["point_temperature"].values[k])
    line = plotting.errorbar(
        ax,
        v,
        ds["velocity_density"].values[k],
        ds["velocity_density_err"].values[k],
        marker=".",
        label=rf"$\lambda={lam[k]:g}$, $N_c={population[k]}$",
    )
    gauss = np.exp(-0.5 * v**2 / temperature) / np.sqrt(2 * np.pi * temperature)
    ax.plot(v, gauss, "--", lw=0.6, color=line[0].get_color())
ax.set_yscale("log")
ax.set_ylim(1e-5, 3.0)
ax.set_xlim(-4.5, 4.5)
ax.set_xlabel(r"$v_x/\sqrt{T_0/m}$")
ax.set_ylabel(r"$\tilde f(v_x,\lambda)$")
plotting.legend_outside(ax, title="dashed: Gaussian of the same T")
plotting.save(fig, snakemake.output.pdf)
