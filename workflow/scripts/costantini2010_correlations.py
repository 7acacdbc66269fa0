"""One costantini2010 run's correlations (rule costantini2010_correlations): its jobs joined,
then C(tau), the tail fit, nu*, nu_bar*, zeta* and T(tau)."""

from kinetic import io
from kinetic.analysis.costantini2010 import analyse_run
from kinetic.workflow_support import start, write_output

log = start(snakemake)
run = io.read_run(snakemake.input.batches)
result = analyse_run(run, **snakemake.params.analysis)
result = result.assign_attrs(parameters_json=run.attrs["parameters_json"])
write_output(snakemake, result, int(run.attrs["seed"]))
log.info(
    "%s: tau_c = %.4g +- %.2g, nu* = %.4g +- %.2g, nu_bar* = %.4g +- %.2g, T_s = %.4f",
    snakemake.wildcards.run,
    float(result.tau_c),
    float(result.tau_c_err),
    float(result.nu_star),
    float(result.nu_star_err),
    float(result.nu_bar_star),
    float(result.nu_bar_star_err),
    float(result.temperature_s),
)
