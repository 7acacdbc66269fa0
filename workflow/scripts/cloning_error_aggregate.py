"""Error-against-CPU-time study (rule cloning_error_aggregate) -> table and netCDF."""

import numpy as np

from kinetic import io
from kinetic.cloning import aggregate
from kinetic.workflow_support import start

log = start(snakemake)
paths = list(snakemake.input.batches)
records = aggregate.combine_points([io.read_dataset(path) for path in paths], names=paths)
reference = io.read_dataset(snakemake.input.reference)
exact = {}
for record in records:
    match = np.flatnonzero(np.isclose(reference["lam"].values, record["lam"], atol=1e-9))
    exact[record["lam"]] = float(reference["mu"].values[match[0]])
table = aggregate.error_table(records, exact)
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".4g")
dataset = io.stamp(
    aggregate.error_dataset(records, exact),
    parameters={"points": len(records)},
    seed=snakemake.config["seed"],
    config=snakemake.config,
)
io.write_dataset(dataset, snakemake.output.nc)
log.info("error study: %d points", len(records))
