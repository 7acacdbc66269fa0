"""Join the batches of one visco2008 MD run (rule visco2008_aggregate_md)."""

from kinetic import io
from kinetic.workflow_support import start, write_output

log = start(snakemake)
data = io.read_run(snakemake.input.batches)
write_output(snakemake, data, int(data.attrs["seed"]))
log.info("%s: %d realizations", snakemake.output[0], data.sizes["realization"])
