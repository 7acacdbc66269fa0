"""Join the batches of one montanero2007 run (rule montanero2007_aggregate_run)."""

from kinetic import io
from kinetic.workflow_support import start, write_output

log = start(snakemake)
run = io.read_run(snakemake.input.batches)
write_output(snakemake, run, int(run.attrs["seed"]))
log.info(
    "%s: %d realizations from %d batches",
    snakemake.wildcards.run,
    run.sizes["realization"],
    len(snakemake.input.batches),
)
