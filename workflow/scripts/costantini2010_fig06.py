"""costantini2010 Fig. 6: nu* and nu_bar* against alpha at every N and for 1/N -> 0, with
the first-Sonine curves (rule costantini2010_fig06)."""

from kinetic import io
from kinetic.plotting import costantini2010 as figures
from kinetic.workflow_support import start

log = start(snakemake)
table = io.read_table(snakemake.input.table)
figures.fig06(table, snakemake.params.study, snakemake.output.pdf)
_, limit, _, _ = figures.transport_rows(table, snakemake.params.study)
for row in limit.itertuples():
    log.info(
        "%s alpha=%g: nu* = %.4f +- %.4f, nu_bar* = %.4f +- %.4f, ratio %.4f +- %.4f",
        row.method,
        row.alpha,
        row.nu_star,
        row.nu_star_err,
        row.nu_bar_star,
        row.nu_bar_star_err,
        row.ratio,
        row.ratio_err,
    )
