"""costantini2010: the document's claims checked against the measured numbers (checks.csv;
a failed check stops the build when the config's fail_on_checks lists costantini2010)."""

from kinetic import io
from kinetic.analysis import checks as check
from kinetic.analysis import costantini2010 as analysis
from kinetic.workflow_support import start

log = start(snakemake)
results = [io.read_dataset(path) for path in snakemake.input.runs]
extrapolated, fits = analysis.extrapolated_rows([analysis.summary_row(r) for r in results])
sigmas = snakemake.params.checks["sigmas"]
found = analysis.checks(results, snakemake.params.study, sigmas=sigmas)
found += analysis.elastic_checks(extrapolated, fits, sigmas=sigmas)
log.info("checks:\n%s", check.table(found).to_string(index=False))
check.write(found, snakemake.output.csv, snakemake.output.md, fail=snakemake.params.fail)
