"""costantini2010 Fig. 7: nu_bar*/nu* against alpha with the white- and coloured-noise
predictions (rule costantini2010_fig07)."""

from kinetic import io, plotting
from kinetic.plotting.costantini2010 import ratio_figure
from kinetic.workflow_support import start

start(snakemake)
fig = ratio_figure(io.read_table(snakemake.input.table), snakemake.params.study)
plotting.save(fig, snakemake.output.pdf)
