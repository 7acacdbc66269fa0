"""visco2008 Table I: cumulants <N^p>_c / t of the number of collisions, p = 1, 2, 3
(kinetic.analysis.visco2008.table1, where the columns are described: the first nine are
the original contract, source,rho,t,k1,k2,k3,k1_err,k2_err,k3_err), and its caption with
every number from the table."""

from kinetic import io
from kinetic.analysis import visco2008 as analysis
from kinetic.workflow_support import start, write_caption

log = start(snakemake)
windows = snakemake.params.extrapolation_windows
runs = [io.read_dataset(path) for path in snakemake.input.md]
cumulants = analysis.md_cumulants(runs, snakemake.params.table_windows, windows)
table = analysis.table1(cumulants, io.read_dataset(snakemake.input.closures), windows)
numbers = analysis.table1_caption_numbers(table, windows)
caption = write_caption(snakemake.input.template, snakemake.output.caption, **numbers)
io.write_table(
    table, snakemake.output.csv, snakemake.output.md, float_format=".5f", markdown_note=caption
)
log.info("Table I:\n%s", table.to_string(index=False))
