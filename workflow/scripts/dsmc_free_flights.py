"""One job of a visco2008 DSMC run: realizations -> netCDF (rule simulate_visco2008_dsmc)."""

from kinetic import io
from kinetic.dsmc import simulate_free_flights
from kinetic.workflow_support import start

log = start(snakemake)
job = dict(snakemake.params.job)
dataset = simulate_free_flights(**job)
dataset = io.stamp(
    dataset, parameters=io.parameters_of(dataset), seed=job["seed"], config=snakemake.config
)
io.write_dataset(dataset, snakemake.output[0])
log.info(
    "wrote %s: %d flights in %.1f CPU s",
    snakemake.output[0],
    int(dataset.flights.sum()),
    float(dataset.cpu_seconds.sum()),
)
