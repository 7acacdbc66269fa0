"""costantini2010 Fig. 3: C(tau) for each N at the figure's alpha (DSMC with fixed Lambda and
cell side, and MD), with the first-Sonine prediction (Eq. 9) for each N."""

from kinetic import io, plotting
from kinetic.plotting.costantini2010 import correlation_panel, real_per_cell
from kinetic.workflow_support import start

log = start(snakemake)
study = snakemake.params.study
results = [io.read_dataset(path) for path in snakemake.input.runs]
sizes = sorted({int(result.attrs["n_particles"]) for result in results})
fig, axes = plotting.figure(1, len(sizes), figsize=(2.6 * len(sizes), 2.6), sharey=True)
lowest = []
for ax, n in zip(axes if len(sizes) > 1 else [axes], sizes, strict=True):
    runs = [r for r in results if int(r.attrs["n_particles"]) == n]
    lowest.append(correlation_panel(ax, runs, study["density"], log, per_cell=False, limit=False))
    # the cells are whole numbers per side, so the real particles per cell differ a little
    # between the panels: their titles say it, the legend lists DSMC once
    dsmc = [r for r in runs if r.attrs["engine"] != "md" and int(r.attrs["cells_per_side"]) > 1]
    title = f"N = {n}" + (f", {real_per_cell(dsmc[0]):.2g} real/cell" if dsmc else "")
    ax.set_title(title, fontsize=8)
if 0 < min(lowest) < float("inf"):  # the shared y axis ends below every panel's data
    (axes[0] if len(sizes) > 1 else axes).set_ylim(bottom=0.5 * min(lowest))
plotting.figure_legend(fig)
plotting.save(fig, snakemake.output.pdf)
