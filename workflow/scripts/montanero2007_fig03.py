"""montanero2007 Fig. 3: kappa'/kappa0 against alpha, DSMC and Sonine approximations."""

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
kappa = np.array([row["kappa_ratio"] for row in rows])
error = np.array([row["kappa_ratio_err"] for row in rows])

grid = np.linspace(min(0.3, alpha.min()), 1.0, 301)
fig, ax = plotting.figure()
ax.plot(
    grid,
    theory.kappa_prime_ratio(grid),
    "-",
    color="k",
    lw=1,
    label="first Sonine (Eqs. 2.42, 2.46)",
)
ax.plot(
    grid,
    theory.kappa_prime_ratio(grid, approximation="modified"),
    "--",
    color="C3",
    lw=1,
    label="modified first Sonine (Ref. [28])",
)
plotting.errorbar(ax, alpha, kappa, error, label="DSMC (this work)", color="C0")
anchor = theory.KAPPA_ELASTIC_HIGHER_SONINE
ax.annotate(
    "", xy=(1.0, anchor), xytext=(1.045, anchor), arrowprops={"arrowstyle": "->", "lw": 0.8}
)
ax.text(1.047, anchor, f"{anchor}", va="center", fontsize=5)
ax.set_xlim(grid[0] - 0.02, 1.1)
ax.set_xlabel(r"$\alpha$")
ax.set_ylabel(r"$\kappa'/\kappa_0$")
ax.legend(loc="upper right", fontsize=6)
plotting.save(fig, snakemake.output.pdf)
for a, k, e in zip(alpha, kappa, error, strict=True):
    log.info(
        "alpha = %.2f: kappa'/kappa0 = %.4f +- %.4f (first Sonine %.4f, modified %.4f)",
        a,
        k,
        e,
        theory.kappa_prime_ratio(a),
        theory.kappa_prime_ratio(a, approximation="modified"),
    )
