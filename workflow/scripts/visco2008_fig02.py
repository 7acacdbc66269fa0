"""visco2008 Fig. 2 (kinetic.plotting.visco2008.fig02; rule visco2008_fig02)."""

from kinetic import io
from kinetic.plotting import visco2008 as figures
from kinetic.workflow_support import start, write_caption

start(snakemake)
numbers = figures.fig02(
    io.read_dataset(snakemake.input.curves),
    [io.read_dataset(path) for path in snakemake.input.md],
    snakemake.output.pdf,
)
write_caption(snakemake.input.template, snakemake.output.caption, **numbers)
