"""costantini2010 Fig. 4: nu_star against 1/N per alpha, with the 1/N fits of Table 1
extrapolated to 1/N -> 0 (rule costantini2010_fig04)."""

from kinetic import io, plotting
from kinetic.plotting.costantini2010 import inverse_n_figure
from kinetic.workflow_support import start

start(snakemake)
fig = inverse_n_figure(
    io.read_table(snakemake.input.table),
    io.read_table(snakemake.input.fits),
    io.read_table(snakemake.input.amplitudes),
    snakemake.params.study,
    "nu_star",
    r"$\nu^*$",
)
plotting.save(fig, snakemake.output.pdf)
