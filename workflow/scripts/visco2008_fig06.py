"""visco2008 Fig. 6 (kinetic.plotting.visco2008_cloning.fig06; rule visco2008_fig06)."""

from kinetic import io
from kinetic.plotting import visco2008_cloning as figures
from kinetic.workflow_support import start, write_caption

start(snakemake)
numbers = figures.fig06(
    snakemake.input.scan,
    io.read_dataset(snakemake.input.closures),
    io.read_dataset(snakemake.input.reference),
    snakemake.output.pdf,
)
write_caption(snakemake.input.template, snakemake.output.caption, **numbers)
