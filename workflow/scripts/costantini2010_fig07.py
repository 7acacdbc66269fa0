"""costantini2010 Fig. 7: nu_bar*/nu* against alpha with the white- and coloured-noise
predictions (rule costantini2010_fig07)."""

from kinetic import io
from kinetic.plotting import costantini2010 as figures
from kinetic.workflow_support import start

start(snakemake)
figures.fig07(io.read_table(snakemake.input.table), snakemake.params.study, snakemake.output.pdf)
