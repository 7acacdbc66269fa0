"""visco2008 Table I: cumulants <N^p>_c / t of the number of collisions, p = 1, 2, 3.

Columns: source,rho,t,k1,k2,k3,k1_err,k2_err,k3_err. MD rows carry the density, the
window length t (mean free times) and standard errors; theory rows leave them empty.
"""

import numpy as np
import pandas as pd

from kinetic import io
from kinetic.workflow_support import start

log = start(snakemake)
COLUMNS = ["source", "rho", "t", "k1", "k2", "k3", "k1_err", "k2_err", "k3_err"]

rows = []
for path in snakemake.input.md:
    md = io.read_dataset(path)
    for window in md["window"].values:
        values = md["scaled_cumulant"].sel(window=window).sel(order=[1, 2, 3]).values
        errors = md["scaled_cumulant_sem"].sel(window=window).sel(order=[1, 2, 3]).values
        rows.append(["MD", float(md.attrs["density"]), float(window), *values, *errors])

closures = io.read_dataset(snakemake.input.closures)
for source, variable in [
    ("Poisson", "cumulant_poisson"),
    ("Gaussian", "cumulant_gaussian"),
    ("Sonine", "cumulant_sonine"),
]:
    rows.append([source, np.nan, np.nan, *closures[variable].values, np.nan, np.nan, np.nan])

table = pd.DataFrame(rows, columns=COLUMNS)
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".5f")
log.info("Table I:\n%s", table.to_string(index=False))
