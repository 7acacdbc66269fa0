"""Table I's scaled cumulants of one joined visco2008 MD run (rule visco2008_cumulants_md)."""

from kinetic import io
from kinetic.analysis import collision_statistics
from kinetic.workflow_support import start, write_output

log = start(snakemake)
data = io.read_dataset(snakemake.input.data)
cumulants = collision_statistics.cumulant_dataset(
    data,
    snakemake.params.table_windows,
    extrapolation_windows=snakemake.params.extrapolation_windows,
)
write_output(snakemake, cumulants, int(data.attrs["seed"]))
for window in cumulants["window"].values:
    values = cumulants["scaled_cumulant"].sel(window=window).values
    errors = cumulants["scaled_cumulant_sem"].sel(window=window).values
    log.info("t = %g: <N^p>_c/t = %s +- %s", window, values.round(4), errors.round(4))
log.info(
    "t -> inf (fit in 1/t over t = %s): %s +- %s",
    cumulants.attrs["extrapolation_windows"],
    cumulants["extrapolated_cumulant"].values.round(4),
    cumulants["extrapolated_cumulant_sem"].values.round(4),
)
