"""One batch of cloning Monte Carlo runs (rule cloning_batch) -> netCDF."""

from kinetic import io
from kinetic.cloning import simulate
from kinetic.workflow_support import start

log = start(snakemake)
parameters = dict(snakemake.params.run)
dataset = simulate(
    **parameters,
    label=f"cloning {snakemake.wildcards.kernel} "
    f"{snakemake.wildcards.point} {snakemake.wildcards.size} "
    f"batch {snakemake.wildcards.batch}",
)
dataset = io.stamp(
    dataset, parameters=io.parameters_of(dataset), seed=parameters["seed"], config=snakemake.config
)
io.write_dataset(dataset, snakemake.output[0])
log.info(
    "mu = %.6f +- %.6f, T = %.5f +- %.5f, a2 = %.5f +- %.5f",
    float(dataset.mu),
    float(dataset.mu_err),
    float(dataset.temperature),
    float(dataset.temperature_err),
    float(dataset.a2),
    float(dataset.a2_err),
)
