"""visco2008 Fig. 12 (kinetic.plotting.visco2008.fig12; rule visco2008_fig12)."""

from kinetic import io
from kinetic.plotting import visco2008 as figures
from kinetic.workflow_support import start, write_caption

start(snakemake)
numbers = figures.fig12(
    io.read_dataset(snakemake.input.dsmc),
    io.read_dataset(snakemake.input.curves),
    snakemake.output.pdf,
)
write_caption(snakemake.input.template, snakemake.output.caption, **numbers)
