"""costantini2010 Table 1: tau_c, amplitude, nu*, nu_bar*, their ratio and zeta* per
(method, alpha, N, Lambda), the 1/N -> 0 rows and the first-Sonine theory; the 1/N fits;
the tail amplitudes against C(0). Rule costantini2010_table1 tabulates every run of Table 1;
costantini2010_transport_table the grid runs only (transport/), what Figs 4-7 draw."""

import pandas as pd

from kinetic import io
from kinetic.analysis import costantini2010 as analysis
from kinetic.workflow_support import start

log = start(snakemake)
study = snakemake.params.study
results = [io.read_dataset(path) for path in snakemake.input.runs]
rows = [analysis.summary_row(result) for result in results]
extrapolated, fits = analysis.extrapolated_rows(rows)
rows += extrapolated
rows += analysis.theory_rows(study["restitutions"], study["particles"], study["density"])
table = pd.DataFrame(rows, columns=analysis.TABLE_COLUMNS)
order = {method: k for k, method in enumerate(("theory", "md", "dsmc", "dsmc_homogeneous"))}
table = table.sort_values(
    by=["method", "alpha", "fictive_factor", "n_particles"],
    key=lambda column: column.map(order) if column.name == "method" else column,
    ascending=[True, False, True, True],
    na_position="last",
)
for column in ("n_particles", "fictive_factor"):  # integers, empty where they do not apply
    table[column] = [None if pd.isna(value) else int(value) for value in table[column]]
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".4g")
io.write_table(
    pd.DataFrame(fits), snakemake.output.fits, snakemake.output.fits_md, float_format=".4g"
)
amplitudes = pd.DataFrame(
    [analysis.amplitude_row(result) for result in results], columns=analysis.AMPLITUDE_COLUMNS
)
io.write_table(
    amplitudes, snakemake.output.amplitudes, snakemake.output.amplitudes_md, float_format=".4g"
)
for fit in fits:
    log.info(
        "%s alpha=%g Lambda=%s %s(1/N -> 0) = %.4f +- %.4f, chi2 = %.3g (dof %d)",
        fit["method"],
        fit["alpha"],
        fit["fictive_factor"],
        fit["quantity"],
        fit["intercept"],
        fit["intercept_err"],
        fit["chi2"],
        fit["dof"],
    )
