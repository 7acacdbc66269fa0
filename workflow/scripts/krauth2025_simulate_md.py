"""event-disks runs of krauth2025 (rule krauth2025_simulate_md): independent realizations of N
disks in a box with walls -> y-densities, wall and pair collision statistics."""

from kinetic.edmd.disks import simulate_box
from kinetic.workflow_support import run_job

log, job, data = run_job(snakemake, simulate_box)
log.info("%d events", int(data.events.sum()))
