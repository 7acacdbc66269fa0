"""montanero2007 Table 1: kappa'/kappa0 and b'_1..3 (Eq. 3.10) against alpha.

Columns: alpha,kappa_ratio,kappa_ratio_err,b1,b1_err,b2,b2_err,b3,b3_err,kappa_ratio_sonine
(kappa_ratio = kappa'/kappa0 from the heat flux, Eq. 3.9 over Eq. 2.47; b'_k from
<c_x L_k^(3/2)(c^2)>, the paper's choice; kappa_ratio_sonine = first Sonine, Eqs. 2.42, 2.46).
"""

import pandas as pd

from kinetic import io
from kinetic.analysis import montanero2007 as analysis
from kinetic.studies.montanero2007 import load_runs
from kinetic.theory import montanero2007 as theory
from kinetic.workflow_support import start

log = start(snakemake)
COLUMNS = [
    "alpha",
    "kappa_ratio",
    "kappa_ratio_err",
    "b1",
    "b1_err",
    "b2",
    "b2_err",
    "b3",
    "b3_err",
    "kappa_ratio_sonine",
]
rows = []
for ds in load_runs(snakemake.input.runs).values():
    row = analysis.summary_row(ds)
    rows.append(
        [
            row["alpha"],
            row["kappa_ratio"],
            row["kappa_ratio_err"],
            *(row[f"b{k}_full{suffix}"] for k in (1, 2, 3) for suffix in ("", "_err")),
            float(theory.kappa_prime_ratio(row["alpha"])),
        ]
    )
table = pd.DataFrame(rows, columns=COLUMNS).sort_values("alpha").reset_index(drop=True)
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".5f")
log.info("Table 1:\n%s", table.to_string(index=False))
