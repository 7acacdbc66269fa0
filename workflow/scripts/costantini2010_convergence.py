"""costantini2010: DSMC's systematic errors at alpha = 1 -- nu* against the collision cell
side (at the production time step) and against the time step (at the production cells)."""

from kinetic import io
from kinetic.analysis import costantini2010 as analysis
from kinetic.plotting import costantini2010 as figures
from kinetic.workflow_support import start

log = start(snakemake)
study = snakemake.params.study
results = [io.read_dataset(path) for path in snakemake.input.runs]
table = analysis.convergence_table(results, study["density"])
figures.convergence_figure(table, study, snakemake.output.pdf)
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".4g")
log.info("%s", table.to_string())
