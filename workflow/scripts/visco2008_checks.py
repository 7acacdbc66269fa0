"""visco2008 checks (kinetic.analysis.visco2008.checks) -> checks.csv (rule visco2008_checks)."""

from kinetic import io
from kinetic.analysis import checks as check
from kinetic.analysis import visco2008 as analysis
from kinetic.workflow_support import start

log = start(snakemake)
cloning = io.read_table(snakemake.input.cloning).rename(columns={"lambda": "lam"})
found = analysis.checks(
    io.read_table(snakemake.input.table),
    cloning,
    io.read_dataset(snakemake.input.reference),
    sigmas=snakemake.params.checks["sigmas"],
    md_dof=snakemake.params.md_dof,
    cloning_dof=snakemake.params.cloning_dof,
)
log.info("checks:\n%s", check.table(found).to_string(index=False))
check.write(found, snakemake.output.csv, snakemake.output.md, fail=snakemake.params.fail)
