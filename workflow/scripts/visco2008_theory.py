"""Tabulate one family of visco2008 theory curves (rule visco2008_theory)."""

from kinetic import io
from kinetic.theory import tabulate
from kinetic.workflow_support import start

log = start(snakemake)
family = snakemake.wildcards.family
grid = dict(snakemake.params.grid)
curves = getattr(tabulate, f"visco2008_{family}")(**grid)
curves = io.stamp(curves, parameters=grid, seed=None, config=snakemake.config)
io.write_dataset(curves, snakemake.output[0])
log.info("wrote %s", snakemake.output[0])
