"""montanero2007 Fig. 4: Sonine coefficients b'_1, b'_2, b'_3 against alpha (Eq. 3.10)."""

import numpy as np

from kinetic import plotting
from kinetic.analysis import montanero2007 as analysis
from kinetic.studies.montanero2007 import load_runs
from kinetic.theory import montanero2007 as theory
from kinetic.workflow_support import start

log = start(snakemake)
rows = [analysis.summary_row(ds) for ds in load_runs(snakemake.input.runs).values()]
rows.sort(key=lambda row: row["alpha"])
alpha = np.array([row["alpha"] for row in rows])

fig, ax = plotting.figure()
for k, marker in zip(range(1, 4), "os^", strict=True):
    value = np.array([row[f"b{k}_full"] for row in rows])
    error = np.array([row[f"b{k}_full_err"] for row in rows])
    container = plotting.errorbar(ax, alpha, value, error, marker=marker, label=f"$b'_{k}$")
    ax.plot(alpha, value, "-", lw=0.5, color=container[0].get_color())
grid = np.linspace(alpha.min(), 1.0, 201)
ax.plot(
    grid,
    theory.sonine_b1_from_kappa_prime_ratio(theory.kappa_prime_ratio(grid)),
    ":",
    color="k",
    lw=0.8,
    label="$b'_1$, first Sonine",
)
ax.axhline(0.0, color="0.6", lw=0.5)
ax.set_xlabel(r"$\alpha$")
ax.set_ylabel(r"$b'_k$")
ax.legend(fontsize=6)
plotting.save(fig, snakemake.output.pdf)
