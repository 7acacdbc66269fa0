"""Direct-pin configurations for krauth2025 Fig. 4.10 (rule krauth2025_snapshots)."""

from kinetic import io
from kinetic.samplers import pin_snapshots
from kinetic.workflow_support import start

log = start(snakemake)
job = dict(snakemake.params.job)
data = pin_snapshots(**job)
data = io.stamp(data, parameters=io.parameters_of(data), seed=job["seed"], config=snakemake.config)
io.write_dataset(data, snakemake.output[0])
log.info("wrote %s: %d configurations", snakemake.output[0], job["count"])
