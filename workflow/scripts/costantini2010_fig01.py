"""costantini2010 Fig. 1: granular temperature against rescaled time for several cell sizes
and Lambda (bands: the standard error over the realizations), against MD and the expected
T_s; right: the recollision diagnostic with its standard error."""

import numpy as np

from kinetic import io, plotting
from kinetic.analysis.costantini2010 import method_of
from kinetic.plotting.costantini2010 import METHOD_STYLE, run_label
from kinetic.workflow_support import start

log = start(snakemake)
results = [io.read_dataset(path) for path in snakemake.input.runs]
fig, (ax, chaos) = plotting.figure(1, 2, figsize=(7.0, 2.8), width_ratios=[2, 1])
# the inhomogeneous DSMC runs in colours of their own (none of another method's), the
# homogeneous ones in their method's colour, dashed, told apart by lightness and dashes
dsmc_colors = iter(
    ["tab:blue", "tab:orange", "tab:purple", "tab:brown", "tab:pink", "tab:olive"] * 4
)
homogeneous = sorted(
    int(r.attrs["fictive_factor"]) for r in results if method_of(r) == "dsmc_homogeneous"
)
for result in results:
    method = method_of(result)
    color, style = METHOD_STYLE[method]["color"], "-"
    if method == "dsmc":
        color = next(dsmc_colors)
    elif method == "dsmc_homogeneous":
        rank = homogeneous.index(int(result.attrs["fictive_factor"]))
        color = plotting.shade(color, rank, len(homogeneous))
        style = ["--", "-.", ":"][rank % 3]
    ax.plot(result.time, result.temperature, style, color=color, lw=0.8, label=run_label(result))
    ax.fill_between(  # the standard error over the realizations
        result.time,
        result.temperature - result.temperature_sem,
        result.temperature + result.temperature_sem,
        color=color,
        alpha=0.25,
        lw=0,
    )
    log.info(
        "%s: T_s = %.4f +- %.4f, repeated collisions %.4f",
        run_label(result),
        float(result.temperature_s),
        float(result.temperature_s_err),
        float(result.get("repeated_fraction", np.nan)),
    )
    if method != "md":
        per_cell = float(result.attrs["n_particles"]) / float(result.attrs["cells_per_side"]) ** 2
        plotting.errorbar(
            chaos,
            per_cell,
            float(result.repeated_fraction),
            float(result.repeated_fraction_err),
            marker=METHOD_STYLE[method]["marker"],
            color=color,
        )
ax.axhline(1.0, color=METHOD_STYLE["theory"]["color"], lw=0.8, ls=":", label=r"expected $T_s$")
ax.set_xlabel(r"$\tau\, v_0/\ell$")
ax.set_ylabel(r"$T/T_0$")
plotting.figure_legend(fig, ncols=3)
chaos.set_xscale("log")
chaos.set_yscale("log")
chaos.set_xlabel("real particles per cell")
chaos.set_ylabel("fraction of repeated collisions")
plotting.save(fig, snakemake.output.pdf)
