"""montanero2007 Table 1: kappa'/kappa0 and b'_1..3 (Eq. 3.10) against alpha.

Columns: alpha,kappa_ratio,kappa_ratio_err,b1,b1_err,b2,b2_err,b3,b3_err,kappa_ratio_sonine
(kappa_ratio = kappa'/kappa0 from the heat flux, Eq. 3.9 over Eq. 2.47; b'_k from
<c_x L_k^(3/2)(c^2)>, the paper's choice; kappa_ratio_sonine = first Sonine, Eqs. 2.42, 2.46),
then field (the protocol's eps*), bias_field (the partner run's), and for each of
kappa_ratio, b1, b2, b3: <q>_bias(_err), the O(eps*^2) bias at the protocol's field, and
<q>_extrapolated(_err), the limit eps* -> 0 (kinetic.analysis.montanero2007.field_extrapolation).
"""

import pandas as pd

from kinetic import io
from kinetic.analysis import montanero2007 as analysis
from kinetic.analysis.montanero2007 import load_runs
from kinetic.theory import montanero2007 as theory
from kinetic.workflow_support import start

log = start(snakemake)
QUANTITIES = {"kappa_ratio": "kappa_ratio", "b1": "b1_full", "b2": "b2_full", "b3": "b3_full"}
records = []
for row in analysis.rows_with_field_bias(
    load_runs(snakemake.input.runs).values(), load_runs(snakemake.input.partners).values()
):
    record = {"alpha": row["alpha"]}
    for name, key in QUANTITIES.items():
        record[name], record[f"{name}_err"] = row[key], row[f"{key}_err"]
    record["kappa_ratio_sonine"] = float(theory.kappa_prime_ratio(row["alpha"]))
    record["field"], record["bias_field"] = row["field_low"], row["field_high"]
    for name, key in QUANTITIES.items():
        for suffix in ("bias", "bias_err", "extrapolated", "extrapolated_err"):
            record[f"{name}_{suffix}"] = row[f"{key}_{suffix}"]
    records.append(record)
table = pd.DataFrame(records)
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".5f")
log.info("Table 1:\n%s", table.to_string(index=False))
