"""visco2008 Table I: cumulants <N^p>_c / t of the number of collisions, p = 1, 2, 3.

Columns (the first nine are the original contract): source,rho,t,k1,k2,k3,k1_err,k2_err,
k3_err, then kind (md | extrapolated | theory), paper_k1..3 (the document's printed row;
empty where it has none), z_k2, z_k3 (ours minus printed, over our standard error),
z_gaussian_k2..z_sonine_k3 (ours against the Gaussian and Sonine closures), k1_exact
(1: k1 = 1 holds by construction, not as a measurement), paper_row_density (1 on the MD
rows at the density whose rows the document's MD rows match best, by their z-scores),
note. MD rows carry the density, the window length t (mean free times) and standard
errors; extrapolated rows (t = inf) the 1/t fit over several windows; theory rows leave
rho, t and the errors empty.
"""

import numpy as np
import pandas as pd

from kinetic import io, plotting
from kinetic.theory.visco2008 import TABLE_I_DOCUMENT
from kinetic.workflow_support import start

log = start(snakemake)
COLUMNS = ["source", "rho", "t", "k1", "k2", "k3", "k1_err", "k2_err", "k3_err"]

closures = io.read_dataset(snakemake.input.closures)
theory = {
    "Poisson": closures["cumulant_poisson"].values,
    "Gaussian": closures["cumulant_gaussian"].values,
    "Sonine": closures["cumulant_sonine"].values,
}


def z(value, error, reference):
    return (value - reference) / error if error > 0 else np.nan


def row(source, rho, t, values, errors, kind, paper):
    record = dict(zip(COLUMNS, [source, rho, t, *values, *errors], strict=True))
    record["kind"] = kind
    for p in range(3):
        record[f"paper_k{p + 1}"] = paper[p] if paper is not None else np.nan
    for p in (1, 2):
        record[f"z_k{p + 1}"] = z(values[p], errors[p], paper[p]) if paper is not None else np.nan
    for name in ("Gaussian", "Sonine"):
        for p in (1, 2):
            record[f"z_{name.lower()}_k{p + 1}"] = (
                z(values[p], errors[p], theory[name][p]) if kind != "theory" else np.nan
            )
    record["k1_exact"] = 1
    return record


rows = []
for path in snakemake.input.md:
    md = io.read_dataset(path)
    density = float(md.attrs["density"])
    for window in md["window"].values:
        values = md["scaled_cumulant"].sel(window=window).sel(order=[1, 2, 3]).values
        errors = md["scaled_cumulant_sem"].sel(window=window).sel(order=[1, 2, 3]).values
        paper = TABLE_I_DOCUMENT.get(f"MD t={window:g}")
        rows.append(row("MD", density, float(window), values, errors, "md", paper))
    if "extrapolated_cumulant" in md:
        rows.append(
            row(
                "MD",
                density,
                np.inf,
                md["extrapolated_cumulant"].values,
                md["extrapolated_cumulant_sem"].values,
                "extrapolated",
                None,
            )
        )
for source, values in theory.items():
    rows.append(
        row(source, np.nan, np.nan, values, [np.nan] * 3, "theory", TABLE_I_DOCUMENT[source])
    )

table = pd.DataFrame(rows)
# which density the document's MD rows come from: the smallest sum of squared z-scores
md_rows = table[(table["kind"] == "md") & table["paper_k2"].notna()]
chi2 = (md_rows["z_k2"] ** 2 + md_rows["z_k3"] ** 2).groupby(md_rows["rho"]).sum()
paper_density = float(chi2.idxmin())
table["paper_row_density"] = ((table["kind"] == "md") & (table["rho"] == paper_density)).astype(int)
notes = {
    "md": "k1 = 1 by construction (t in measured mean free times), not a measurement",
    "extrapolated": "fit k(t) = k(inf) + c/t per realization over t = {}".format(
        ", ".join(f"{w:g}" for w in snakemake.params.extrapolation_windows)
    ),
    "theory": "k1 = 1 by construction (omega = 1)",
}
table["note"] = table["kind"].map(notes)
table.loc[table["paper_row_density"] == 1, "note"] += "; density of the document's MD rows"
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".5f")

# caption: every number from the table just written; "doc" is the density of the
# document's MD rows, "other" the other one
numbers = {}
densities = sorted(table["rho"].dropna().unique(), key=lambda rho: rho != paper_density)
for density, tag in zip(densities, ("doc", "other"), strict=False):
    numbers[f"rho_{tag}"] = density
    for kind_row in table[(table["rho"] == density)].itertuples():
        key = "inf" if kind_row.kind == "extrapolated" else f"{kind_row.t:g}"
        for p in (2, 3):
            for column in (f"k{p}", f"k{p}_err", f"z_k{p}", f"z_gaussian_k{p}", f"z_sonine_k{p}"):
                numbers[f"{column}_{tag}_{key}"] = getattr(kind_row, column)
for key in ("10", "50", "inf"):
    difference = numbers[f"k2_other_{key}"] - numbers[f"k2_doc_{key}"]
    error = np.hypot(numbers[f"k2_err_other_{key}"], numbers[f"k2_err_doc_{key}"])
    numbers[f"dk2_{key}"], numbers[f"dk2_err_{key}"] = difference, error
    numbers[f"dz_{key}"] = difference / error
numbers["windows"] = ", ".join(f"{w:g}" for w in snakemake.params.extrapolation_windows)
caption = plotting.write_caption(snakemake.input.template, snakemake.output.caption, **numbers)
with open(snakemake.output.md, "a", encoding="utf-8") as markdown:
    markdown.write("\n" + caption)
log.info("Table I:\n%s", table.to_string(index=False))
