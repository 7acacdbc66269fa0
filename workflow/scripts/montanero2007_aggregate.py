"""Join the batches of one montanero2007 run (rule montanero2007_aggregate_run)."""

from kinetic.studies.montanero2007 import join_run
from kinetic.workflow_support import start, write_output

log = start(snakemake)
run = join_run(snakemake.input.batches)
write_output(snakemake, run, int(run.attrs["seed"]))
log.info(
    "%s: %d realizations from %d batches",
    snakemake.wildcards.run,
    run.sizes["realization"],
    len(snakemake.input.batches),
)
