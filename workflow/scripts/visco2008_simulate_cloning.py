"""One batch of cloning Monte Carlo realizations (rule visco2008_simulate_cloning) -> netCDF."""

from kinetic.cloning import simulate
from kinetic.workflow_support import start_simulation, write_output

log = start_simulation(snakemake)
parameters = dict(snakemake.params.job)
dataset = simulate(
    **parameters,
    label=f"cloning {snakemake.wildcards.kernel} "
    f"{snakemake.wildcards.point} {snakemake.wildcards.size} "
    f"{snakemake.wildcards.batch}",
)
write_output(snakemake, dataset, parameters["seed"])
log.info(
    "mu = %.6f +- %.6f, T = %.5f +- %.5f, a2 = %.5f +- %.5f",
    float(dataset.mu),
    float(dataset.mu_err),
    float(dataset.temperature),
    float(dataset.temperature_err),
    float(dataset.a2),
    float(dataset.a2_err),
)
