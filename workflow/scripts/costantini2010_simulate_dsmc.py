"""One job of a costantini2010 run with the DSMC engine (rule costantini2010_simulate_dsmc):
realizations of the cooling gas -> netCDF."""

from kinetic.dsmc import simulate_cooling_modes
from kinetic.workflow_support import run_job

run_job(snakemake, simulate_cooling_modes)
