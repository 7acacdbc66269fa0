"""costantini2010 Fig. 5: nu_bar_star against 1/N per alpha, with the 1/N fits of Table 1
extrapolated to 1/N -> 0 (rule costantini2010_fig05)."""

from kinetic import io
from kinetic.plotting import costantini2010 as figures
from kinetic.workflow_support import start

start(snakemake)
figures.fig05(
    io.read_table(snakemake.input.table),
    io.read_table(snakemake.input.fits),
    io.read_table(snakemake.input.amplitudes),
    snakemake.params.study,
    snakemake.output.pdf,
)
