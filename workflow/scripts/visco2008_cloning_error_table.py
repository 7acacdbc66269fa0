"""Error-against-CPU-time study (rule visco2008_cloning_error_table) -> table and netCDF."""

import numpy as np

from kinetic import io
from kinetic.analysis import cloning as analysis
from kinetic.workflow_support import start, write_output

log = start(snakemake)
paths = list(snakemake.input.batches)
records = analysis.combine_points([io.read_dataset(path) for path in paths], names=paths)
reference = io.read_dataset(snakemake.input.reference)
exact = {}
for record in records:
    match = np.flatnonzero(np.isclose(reference["lam"].values, record["lam"], atol=1e-9))
    exact[record["lam"]] = float(reference["mu"].values[match[0]])
table = analysis.error_table(records, exact)
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".4g")
write_output(
    snakemake,
    analysis.error_dataset(records, exact),
    None,
    output="nc",
    parameters={"points": len(records)},
)
log.info("error study: %d points", len(records))
