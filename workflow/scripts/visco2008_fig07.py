"""visco2008 Fig. 7 (kinetic.plotting.visco2008_cloning.fig07; rule visco2008_fig07)."""

from kinetic import io
from kinetic.plotting import visco2008_cloning as figures
from kinetic.workflow_support import start

start(snakemake)
figures.fig07(
    snakemake.input.scan,
    io.read_dataset(snakemake.input.closures),
    io.read_dataset(snakemake.input.reference),
    snakemake.output.pdf,
)
