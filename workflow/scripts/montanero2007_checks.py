"""montanero2007 checks of the paper's claims and of the engine
(kinetic.analysis.montanero2007.checks) -> checks.csv; a failed check stops the build
when the config's fail_on_checks lists montanero2007."""

from kinetic.analysis import checks as check
from kinetic.analysis import montanero2007 as analysis
from kinetic.analysis.montanero2007 import load_runs
from kinetic.workflow_support import start

log = start(snakemake)
rows = [analysis.summary_row(ds) for ds in load_runs(snakemake.input.runs).values()]
found = analysis.checks(rows, snakemake.params.checks)
log.info("checks:\n%s", check.table(found).to_string(index=False))
check.write(found, snakemake.output.csv, snakemake.output.md, fail=snakemake.params.fail)
