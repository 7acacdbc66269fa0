"""Tabulate one family of visco2008 theory curves (rule visco2008_theory)."""

from kinetic.theory import tabulate
from kinetic.workflow_support import start, write_output

log = start(snakemake)
family = snakemake.wildcards.family
grid = dict(snakemake.params.grid)
curves = getattr(tabulate, f"visco2008_{family}")(**grid)
write_output(snakemake, curves, None, parameters=grid)
log.info("wrote %s", snakemake.output[0])
