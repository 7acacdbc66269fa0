"""costantini2010 Fig. 2: C(tau) on a log scale, homogeneous DSMC against inhomogeneous
DSMC and MD, with the first-Sonine prediction (Eq. 9)."""

from kinetic import io, plotting
from kinetic.plotting.costantini2010 import correlation_panel
from kinetic.workflow_support import start

log = start(snakemake)
study = snakemake.params.study
results = [io.read_dataset(path) for path in snakemake.input.runs]
fig, ax = plotting.figure()
correlation_panel(ax, results, study["density"], log)
plotting.legend_outside(ax)
plotting.save(fig, snakemake.output.pdf)
