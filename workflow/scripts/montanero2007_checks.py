"""montanero2007 checks of the paper's claims and of the engine
(kinetic.analysis.montanero2007.checks); fails loudly (after logging the table) if one
fails."""

import pandas as pd

from kinetic import io
from kinetic.analysis import montanero2007 as analysis
from kinetic.studies.montanero2007 import load_runs
from kinetic.workflow_support import start

log = start(snakemake)
rows = [analysis.summary_row(ds) for ds in load_runs(snakemake.input.runs).values()]
table = pd.DataFrame(analysis.checks(rows, snakemake.params.section["checks"]))
log.info("checks:\n%s", table.to_string(index=False))
failed = table[table["passed"] == "NO"]
if len(failed):
    raise RuntimeError(f"{len(failed)} montanero2007 check(s) failed:\n{failed.to_string()}")
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".6g")
