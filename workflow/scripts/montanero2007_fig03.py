"""montanero2007 Fig. 3: kappa'/kappa0 against alpha, DSMC and Sonine approximations.

DSMC at the protocol's field (open) and extrapolated to eps* -> 0 from the larger-field
partner runs (filled): the estimate is even in eps*, so its O(eps*^2) bias is removed.
"""

import numpy as np

from kinetic import plotting
from kinetic.analysis import montanero2007 as analysis
from kinetic.analysis.montanero2007 import load_runs
from kinetic.theory import montanero2007 as theory
from kinetic.workflow_support import start, write_caption

log = start(snakemake)
rows = analysis.rows_with_field_bias(
    load_runs(snakemake.input.runs).values(), load_runs(snakemake.input.partners).values()
)
alpha = np.array([row["alpha"] for row in rows])
kappa = np.array([row["kappa_ratio"] for row in rows])
error = np.array([row["kappa_ratio_err"] for row in rows])
limit = np.array([row["kappa_ratio_extrapolated"] for row in rows])
limit_err = np.array([row["kappa_ratio_extrapolated_err"] for row in rows])
bias = np.array([row["kappa_ratio_bias"] for row in rows])
bias_err = np.array([row["kappa_ratio_bias_err"] for row in rows])

grid = np.linspace(min(0.3, alpha.min()), 1.0, 301)
fig, ax = plotting.figure()
ax.plot(
    grid,
    theory.kappa_prime_ratio(grid),
    **plotting.METHOD_STYLE["theory"],
    lw=1,
    label="first Sonine (Eqs. 2.42, 2.46)",
)
ax.plot(
    grid,
    theory.kappa_prime_ratio(grid, approximation="modified"),
    **plotting.METHOD_STYLE["theory_alt"],
    lw=1,
    label="modified first Sonine (Ref. [28])",
)
field, field_high = rows[0]["field_low"], rows[0]["field_high"]
plotting.method_errorbar(
    ax, "dsmc", alpha, kappa, error, label=rf"DSMC, $\varepsilon^* = {field:g}$"
)
plotting.method_errorbar(
    ax,
    "dsmc",
    alpha + 0.008,
    limit,
    limit_err,
    mfc="tab:blue",
    label=r"DSMC, $\varepsilon^* \to 0$",
)
anchor = theory.KAPPA_ELASTIC_HIGHER_SONINE
ax.annotate(
    "", xy=(1.0, anchor), xytext=(1.045, anchor), arrowprops={"arrowstyle": "->", "lw": 0.8}
)
ax.text(1.047, anchor, f"{anchor}", va="center", fontsize=8)
ax.set_xlim(grid[0] - 0.02, 1.12)
ax.set_xlabel(r"$\alpha$")
ax.set_ylabel(r"$\kappa'/\kappa_0$")
plotting.legend_outside(ax)
plotting.save(fig, snakemake.output.pdf)

z_bias = bias / bias_err
elastic = int(np.argmin(abs(alpha - 1.0)))
write_caption(
    snakemake.input.template,
    snakemake.output.caption,
    field=field,
    field_high=field_high,
    max_bias=100 * np.max(np.abs(bias / limit)),
    max_z_bias=np.max(np.abs(z_bias)),
    alpha_max_bias=alpha[int(np.argmax(np.abs(z_bias)))],
    elastic_alpha=alpha[elastic],
    elastic=limit[elastic],
    elastic_err=limit_err[elastic],
    elastic_z=(limit[elastic] - anchor) / limit_err[elastic],
    anchor=anchor,
)
for row in rows:
    log.info(
        "alpha = %.2f: kappa'/kappa0 = %.4f +- %.4f at eps* = %g; bias %+.4f +- %.4f; "
        "eps* -> 0: %.4f +- %.4f (first Sonine %.4f)",
        row["alpha"],
        row["kappa_ratio"],
        row["kappa_ratio_err"],
        field,
        row["kappa_ratio_bias"],
        row["kappa_ratio_bias_err"],
        row["kappa_ratio_extrapolated"],
        row["kappa_ratio_extrapolated_err"],
        theory.kappa_prime_ratio(row["alpha"]),
    )
