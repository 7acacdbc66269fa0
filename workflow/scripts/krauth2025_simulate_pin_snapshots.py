"""Direct-pin configurations for krauth2025 Fig. 4.10 (rule krauth2025_simulate_pin_snapshots)."""

from kinetic.samplers import pin_snapshots
from kinetic.workflow_support import start, write_output

log = start(snakemake)
job = dict(snakemake.params.job)
data = pin_snapshots(**job)
write_output(snakemake, data, job["seed"])
log.info("wrote %s: %d configurations", snakemake.output[0], job["count"])
