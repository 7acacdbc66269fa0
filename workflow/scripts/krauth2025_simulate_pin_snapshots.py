"""Direct-pin configurations for krauth2025 Fig. 4.10 (rule krauth2025_simulate_pin_snapshots)."""

from kinetic.samplers import pin_snapshots
from kinetic.workflow_support import run_job

log, job, data = run_job(snakemake, pin_snapshots)
log.info("%d configurations", job["count"])
