"""One batch of visco2008 MD realizations (rule edmd_visco2008_batch)."""

from kinetic import io
from kinetic.edmd import simulate
from kinetic.workflow_support import start

log = start(snakemake)
parameters = dict(snakemake.params.simulation)
dataset = simulate(**parameters, config=snakemake.config)
io.write_dataset(dataset, snakemake.output[0])
rate = dataset["collisions"].values[:, -1].sum() / dataset["cpu_time"].values[:, -1].sum()
log.info(
    "wrote %s: %d realizations, %.3g collisions per CPU-second",
    snakemake.output[0],
    parameters["realizations"],
    rate,
)
