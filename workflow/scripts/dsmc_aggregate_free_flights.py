"""Combine the jobs of one visco2008 DSMC run (rule aggregate_visco2008_dsmc)."""

from kinetic import io
from kinetic.batches import read_batches
from kinetic.dsmc.aggregate import combine_free_flights
from kinetic.workflow_support import start

log = start(snakemake)
batches = read_batches(snakemake.input)
combined = combine_free_flights(batches)
combined = io.stamp(
    combined,
    parameters=io.parameters_of(combined),
    seed=int(combined.attrs["seed"]),
    config=snakemake.config,
)
io.write_dataset(combined, snakemake.output[0])
log.info(
    "wrote %s from %d jobs (%d realizations)",
    snakemake.output[0],
    len(batches),
    combined.sizes["realization"],
)
