"""One initial state of event-disks in float64, float32 and float64 one ulp away (rule
krauth2025_simulate_chaos), event by event: krauth2025 Fig. 4.1 and section 4.1.2."""

from kinetic.edmd.disks import chaos
from kinetic.workflow_support import run_job

log, job, data = run_job(snakemake, chaos)
log.info("%d events per precision", job["events"])
