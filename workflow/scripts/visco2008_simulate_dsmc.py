"""One job of a visco2008 DSMC run: realizations -> netCDF (rule visco2008_simulate_dsmc)."""

from kinetic.dsmc import simulate_free_flights
from kinetic.workflow_support import run_job

log, job, dataset = run_job(snakemake, simulate_free_flights)
log.info("%d flights", int(dataset.flights.sum()))
