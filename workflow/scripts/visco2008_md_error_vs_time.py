"""Standard error of the MD cumulants ⟨N²⟩_c/t and ⟨N³⟩_c/t at one window t against the
CPU time spent (several production lengths, read from the cumulative checkpoints)."""

import numpy as np
import pandas as pd

from kinetic import io, plotting
from kinetic.analysis import collision_statistics
from kinetic.analysis.statistics import error_of_sem
from kinetic.workflow_support import start

log = start(snakemake)
window = float(snakemake.params.window)
rows = []
fig, ax = plotting.figure()
for index, path in enumerate(snakemake.input.md):
    md = io.read_dataset(path)
    study = collision_statistics.error_against_cpu_time(md, window)
    density = float(md.attrs["density"])
    table = pd.DataFrame(
        {"density": density, "n_particles": int(md.attrs["n_particles"]), "window": window, **study}
    )
    rows.append(table)
    for key, marker, style in (("k2", "o", "-"), ("k3", "s", "--")):
        cpu, sem = study["cpu_time"], study[f"{key}_sem"]
        # statistical error ∝ 1/sqrt(CPU): the guide goes through the longest run
        guide = sem[-1] * np.sqrt(cpu[-1] / cpu)
        (line,) = ax.plot(cpu, guide, style, linewidth=0.6, color=f"C{index}")
        spread = error_of_sem(sem, study["realizations"])
        plotting.errorbar(
            ax,
            cpu,
            sem,
            spread,
            marker=marker,
            color=line.get_color(),
            markersize=3,
            label=rf"$k_{key[1]}$, $\rho\sigma^2 = {density:g}$",
        )
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("CPU time, all realizations (s)")
ax.set_ylabel(rf"standard error of $\langle\mathcal{{N}}^p\rangle_c/t$ at $t = {window:g}$")
plotting.legend_outside(ax)
plotting.save(fig, snakemake.output.pdf)
table = pd.concat(rows, ignore_index=True)
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".5g")
log.info("error against CPU time:\n%s", table.to_string(index=False))
