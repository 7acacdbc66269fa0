"""event-disks runs of krauth2025 (rule krauth2025_simulate_md): independent realizations of N
disks in a box with walls -> y-densities, wall and pair collision statistics."""

from kinetic.edmd.disks import simulate_box
from kinetic.workflow_support import start, write_output

log = start(snakemake)
job = dict(snakemake.params.job)
data = simulate_box(**job)
write_output(snakemake, data, job["seed"])
log.info(
    "wrote %s: %d events in %.1f CPU s",
    snakemake.output[0],
    int(data.events.sum()),
    float(data.cpu_seconds.sum()),
)
