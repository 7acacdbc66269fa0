"""Pool the scan's batches (rule visco2008_cloning_table) -> cloning.csv|md|nc, or one
kernel's (rule visco2008_cloning_kernel_table) -> cloning/scan/<kernel>.nc."""

from kinetic import io
from kinetic.analysis import cloning as analysis
from kinetic.workflow_support import start, write_output

log = start(snakemake)
paths = list(snakemake.input.batches)
records = analysis.combine_points([io.read_dataset(path) for path in paths], names=paths)
limits = analysis.extrapolate_points(records)
if hasattr(snakemake.output, "csv"):  # the whole scan (not one kernel)
    io.write_table(analysis.scan_table(records, limits), snakemake.output.csv, snakemake.output.md)
write_output(
    snakemake,
    analysis.scan_dataset(records, limits),
    None,
    output="nc",
    parameters={"points": len(records)},
)
for record in records:
    if record["collapsed"]:
        log.info(
            "%s lam=%g N=%d: diversity collapse (%d distinct velocities), T and a2 left empty",
            record["kernel"],
            record["lam"],
            record["population"],
            record["distinct_min"],
        )
log.info("wrote %d points and %d extrapolations", len(records), len(limits))
