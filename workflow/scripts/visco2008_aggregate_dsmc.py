"""Combine the jobs of one visco2008 DSMC run (rule visco2008_aggregate_dsmc): the
free-flight densities over every realization (kinetic.analysis.collision_statistics
.combine_free_flights, which checks through kinetic.batches.combine that the batches are
one run's, each realization once, and names the offending files)."""

from kinetic import io
from kinetic.analysis.collision_statistics import combine_free_flights
from kinetic.workflow_support import start, write_output

log = start(snakemake)
paths = list(snakemake.input.batches)
batches = [io.read_dataset(path) for path in paths]
combined = combine_free_flights(batches, names=paths)
write_output(snakemake, combined, int(combined.attrs["seed"]))
log.info(
    "wrote %s from %d jobs (%d realizations)",
    snakemake.output[0],
    len(batches),
    combined.sizes["realization"],
)
