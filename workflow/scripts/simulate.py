"""One simulation job (every <document>_simulate_<what> rule): the job's front
(params.front, from kinetic.studies) called with its arguments (params.job) and written
with its provenance (params.parameters beside the front's own) and the job's seed."""

from kinetic.simulation_job import run_job

run_job(snakemake)
