"""costantini2010: DSMC's systematic errors at alpha = 1 -- nu* against the collision cell
side (at the production time step) and against the time step (at the production cells)."""

import pandas as pd

from kinetic import io, plotting
from kinetic.plotting.costantini2010 import METHOD_STYLE
from kinetic.studies.costantini2010 import mean_free_path, mean_free_time
from kinetic.theory import costantini2010 as theory
from kinetic.workflow_support import start

log = start(snakemake)
study = snakemake.params.study
density = study["density"]
records = []
for path in snakemake.input.runs:
    result = io.read_dataset(path)
    side = (float(result.attrs["n_particles"]) / density) ** 0.5
    records.append(
        {
            "n_particles": int(result.attrs["n_particles"]),
            "fictive_factor": int(result.attrs["fictive_factor"]),
            "cell_side": side / int(result.attrs["cells_per_side"]) / mean_free_path(density),
            "time_step": float(result.attrs["time_step"]) / mean_free_time(density),
            "tau_c": float(result.tau_c),
            "tau_c_err": float(result.tau_c_err),
            "nu_star": float(result.nu_star),
            "nu_star_err": float(result.nu_star_err),
            "temperature_s": float(result.temperature_s),
        }
    )
table = pd.DataFrame(records).drop_duplicates(["cell_side", "time_step"])
production_step = study["dsmc"]["time_step"]
production_cells = table.loc[
    (table.cell_side - study["dsmc"]["cell_side"]).abs().idxmin(), "cell_side"
]
fig, axes = plotting.figure(1, 2, figsize=(6.0, 2.6), sharey=True)
style = METHOD_STYLE["dsmc"]
for ax, column, fixed, fixed_value, label in (
    (axes[0], "cell_side", "time_step", production_step, r"cell side / $\lambda$"),
    (axes[1], "time_step", "cell_side", production_cells, r"$\Delta\tau\ \omega_c$"),
):
    rows = table[(table[fixed] - fixed_value).abs() < 1e-6 * fixed_value].sort_values(column)
    plotting.errorbar(
        ax,
        rows[column] ** 2,
        rows.nu_star,
        rows.nu_star_err,
        marker=style["marker"],
        color=style["color"],
        label=f"DSMC, N = {rows.n_particles.iloc[0]}",
    )
    ax.axhline(
        theory.nu_star(1.0), color=METHOD_STYLE["theory"]["color"], lw=0.8, label="first Sonine"
    )
    ax.axhline(
        theory.nu_star_elastic(),
        color=METHOD_STYLE["theory"]["color"],
        lw=0.8,
        ls="--",
        label="converged Sonine",
    )
    ax.set_xlabel(f"({label})$^2$")
axes[0].set_ylabel(r"$\nu^*$ ($\alpha = 1$)")
plotting.figure_legend(fig)
plotting.save(fig, snakemake.output.pdf)
io.write_table(table, snakemake.output.csv)
log.info("%s", table.to_string())
