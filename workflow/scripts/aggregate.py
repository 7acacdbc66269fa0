"""Join the batches of one run, computing nothing else (rules visco2008_aggregate_md and
montanero2007_aggregate_dsmc): kinetic.io.read_run checks that they are one run's, each
realization once."""

from kinetic import io
from kinetic.workflow_support import start, write_output

log = start(snakemake)
run = io.read_run(snakemake.input.batches)
write_output(snakemake, run, int(run.attrs["seed"]))
log.info(
    "%s: %d realizations from %d batches",
    snakemake.output[0],
    run.sizes["realization"],
    len(snakemake.input.batches),
)
