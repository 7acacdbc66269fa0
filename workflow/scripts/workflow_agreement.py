"""Checks passed, failed and reported per document (rule workflow_agreement) -> CSV and the
reStructuredText table the report's front page includes."""

from pathlib import Path

from kinetic import io
from kinetic.analysis import checks as check
from kinetic.workflow_support import start

log = start(snakemake)
tables = {Path(path).parent.name: io.read_table(path) for path in snakemake.input.tables}
frame = check.overview(tables)
io.write_table(frame, snakemake.output.csv)
io.write_text(snakemake.output.rst, check.overview_rst(frame))
log.info("checks per document:\n%s", frame.to_string(index=False))
