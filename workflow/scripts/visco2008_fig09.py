"""visco2008 Fig. 9 (kinetic.plotting.visco2008.fig09; rule visco2008_fig09)."""

from kinetic import io
from kinetic.plotting import visco2008 as figures
from kinetic.workflow_support import start, write_caption

start(snakemake)
numbers = figures.fig09(
    io.read_dataset(snakemake.input.md),
    io.read_dataset(snakemake.input.finite),
    io.read_dataset(snakemake.input.curves),
    snakemake.params.windows,
    snakemake.params.min_count,
    snakemake.output.pdf,
)
write_caption(snakemake.input.template, snakemake.output.caption, **numbers)
