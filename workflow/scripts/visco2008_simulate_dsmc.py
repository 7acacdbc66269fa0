"""One job of a visco2008 DSMC run: realizations -> netCDF (rule visco2008_simulate_dsmc)."""

from kinetic.dsmc import simulate_free_flights
from kinetic.workflow_support import start, write_output

log = start(snakemake)
job = dict(snakemake.params.job)
dataset = simulate_free_flights(**job)
write_output(snakemake, dataset, job["seed"])
log.info(
    "wrote %s: %d flights in %.1f CPU s",
    snakemake.output[0],
    int(dataset.flights.sum()),
    float(dataset.cpu_seconds.sum()),
)
