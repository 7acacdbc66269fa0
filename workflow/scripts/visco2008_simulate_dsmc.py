"""One job of a visco2008 DSMC run: realizations -> netCDF (rule visco2008_simulate_dsmc)."""

from kinetic.dsmc import simulate_free_flights
from kinetic.workflow_support import run_job

log, job, dataset = run_job(snakemake, simulate_free_flights)
log.info(
    "wrote %s: %d flights in %.1f CPU s",
    snakemake.output[0],
    int(dataset.flights.sum()),
    float(dataset.cpu_seconds.sum()),
)
