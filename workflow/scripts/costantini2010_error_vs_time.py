"""costantini2010: error of nu* and nu_bar* against CPU time, DSMC and MD at one (N, alpha).

Each point uses the first 1/k of every realization's blocks (k = 1, 2, ...): its CPU time is
that fraction of the run's, its error the jackknife error over those blocks, with the
error of that error, SE/√(2(n − 1)) for n blocks. The dashed lines are a/sqrt(t) through
the full runs' points."""

import numpy as np
import pandas as pd

from kinetic import io, plotting
from kinetic.analysis.costantini2010 import method_of
from kinetic.analysis.statistics import error_of_sem
from kinetic.plotting.costantini2010 import METHOD_LABELS, METHOD_STYLE
from kinetic.workflow_support import start

log = start(snakemake)
records = []
fig, axes = plotting.figure(1, 2, figsize=(6.0, 2.6), sharey=False)
fig.subplots_adjust(wspace=0.35)  # the right panel's label clear of the left's ticks
for path in snakemake.input.runs:
    result = io.read_dataset(path)
    method = method_of(result)
    style = METHOD_STYLE[method]
    cpu = result.error_cpu_seconds.values
    for ax, name, symbol in (
        (axes[0], "nu_star", r"$\nu^*$"),
        (axes[1], "nu_bar_star", r"$\bar\nu^*$"),
    ):
        error = result[f"error_{name}"].values
        blocks = np.rint(result.subset.values * float(result.blocks))  # jackknife samples
        plotting.errorbar(
            ax,
            cpu,
            error,
            error_of_sem(error, blocks),
            marker=style["marker"],
            color=style["color"],
            label=METHOD_LABELS[method],
        )
        ax.set_xscale("log")
        ax.set_yscale("log")
        line = np.geomspace(cpu.min() / 2, cpu.max() * 4, 20)
        ax.loglog(line, error[0] * np.sqrt(cpu[0] / line), "--", color=style["color"], lw=0.6)
        ax.set_xlabel("CPU time (s)")
        ax.set_ylabel(f"standard error of {symbol}")
    for k in range(cpu.size):
        records.append(
            {
                "method": method,
                "alpha": float(result.attrs["restitution"]),
                "n_particles": int(result.attrs["n_particles"]),
                "cpu_seconds": float(cpu[k]),
                "nu_star_err": float(result.error_nu_star[k]),
                "nu_bar_star_err": float(result.error_nu_bar_star[k]),
            }
        )
    seconds_for_1pc = float(cpu[0] * (result.error_nu_star[0] / (0.01 * result.nu_star)) ** 2)
    log.info("%s: CPU seconds for a 1 %% error on nu*: %.3g", method, seconds_for_1pc)
plotting.figure_legend(fig)
plotting.save(fig, snakemake.output.pdf)
io.write_table(pd.DataFrame(records), snakemake.output.csv, snakemake.output.md, float_format=".4g")
