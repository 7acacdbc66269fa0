"""One batch of visco2008 MD realizations (rule visco2008_simulate_md)."""

from kinetic.edmd import simulate
from kinetic.workflow_support import start_simulation, write_output

log = start_simulation(snakemake)
parameters = dict(snakemake.params.simulation)
dataset = simulate(**parameters)
write_output(snakemake, dataset, parameters["seed"])
rate = dataset["collisions"].values[:, -1].sum() / dataset["cpu_time"].values[:, -1].sum()
log.info(
    "wrote %s: %d realizations, %.3g collisions per CPU-second",
    snakemake.output[0],
    parameters["realizations"],
    rate,
)
