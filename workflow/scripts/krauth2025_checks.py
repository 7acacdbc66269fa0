"""krauth2025 checks (kinetic.analysis.krauth2025.checks) -> checks.csv (rule krauth2025_checks)."""

from kinetic import io
from kinetic.analysis import checks as check
from kinetic.analysis import krauth2025 as analysis
from kinetic.workflow_support import start

log = start(snakemake)
found = analysis.checks(
    io.read_table(snakemake.input.pins),
    io.read_table(snakemake.input.pressure),
    sigmas=snakemake.params.checks["sigmas"],
)
log.info("checks:\n%s", check.table(found).to_string(index=False))
check.write(found, snakemake.output.csv, snakemake.output.md, fail=snakemake.params.fail)
