"""visco2008 Fig. 4 (kinetic.plotting.visco2008_cloning.fig04; rule visco2008_fig04)."""

from kinetic import io
from kinetic.plotting import visco2008_cloning as figures
from kinetic.workflow_support import start

start(snakemake)
figures.fig04(
    snakemake.input.scan,
    io.read_dataset(snakemake.input.closures),
    snakemake.output.pdf,
)
