"""Combine the jobs of one visco2008 DSMC run (rule visco2008_aggregate_dsmc)."""

from kinetic.analysis.collision_statistics import combine_free_flights
from kinetic.batches import read_batches
from kinetic.workflow_support import start, write_output

log = start(snakemake)
batches = read_batches(snakemake.input.batches)
combined = combine_free_flights(batches)
write_output(snakemake, combined, int(combined.attrs["seed"]))
log.info(
    "wrote %s from %d jobs (%d realizations)",
    snakemake.output[0],
    len(batches),
    combined.sizes["realization"],
)
