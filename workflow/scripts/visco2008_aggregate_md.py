"""Join the batches of one visco2008 MD run (rule visco2008_aggregate_md)."""

from kinetic.batches import combine, read_batches
from kinetic.workflow_support import start, write_output

log = start(snakemake)
data = combine(read_batches(snakemake.input.batches))
write_output(snakemake, data, int(data.attrs["seed"]))
log.info("%s: %d realizations", snakemake.output[0], data.sizes["realization"])
