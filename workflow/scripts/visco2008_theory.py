"""Tabulate one family of visco2008 theory (rules visco2008_theory and
visco2008_theory_cloning_reference): kinetic.theory.tabulate.visco2008_<family> on the
config's grid."""

from kinetic.theory import tabulate
from kinetic.workflow_support import start, write_output

log = start(snakemake)
family = snakemake.params.family
grid = dict(snakemake.params.grid)
curves = getattr(tabulate, f"visco2008_{family}")(**grid)
write_output(snakemake, curves, None, parameters=dict(snakemake.params.parameters))
log.info("wrote %s (%s)", snakemake.output[0], family)
