"""One job of a costantini2010 run with the MD engine (rule costantini2010_simulate_md):
realizations of the cooling gas -> netCDF."""

from kinetic.edmd import simulate_cooling_modes
from kinetic.workflow_support import run_job

run_job(snakemake, simulate_cooling_modes)
