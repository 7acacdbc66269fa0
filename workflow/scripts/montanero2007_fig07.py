"""montanero2007 Fig. 7: beta_1(c_x^2)/b'_1 (Eq. 4.6), the share of b'_1 below |c_x|."""

import numpy as np

from kinetic import plotting
from kinetic.analysis import montanero2007 as analysis
from kinetic.studies.montanero2007 import load_runs
from kinetic.workflow_support import start

log = start(snakemake)
runs = list(load_runs(snakemake.input.runs).values())
fig, ax = plotting.figure()
for ds in runs:
    summary = analysis.steady_summary_of(ds)
    curves = analysis.distributions_of(ds, summary)
    x, ratio, error = curves["beta_cx2"], curves["beta_ratio"], curves["beta_ratio_err"]
    alpha = summary["parameters"]["restitution"]
    line = ax.plot(x, ratio, "-", lw=0.9, label=rf"$\alpha = {alpha:g}$")[0]
    ax.fill_between(x, ratio - error, ratio + error, color=line.get_color(), alpha=0.25, lw=0)
    share = np.interp(6.0, x, ratio)
    share_err = np.interp(6.0, x, error)
    log.info(
        "alpha = %g: particles with c_x^2 <= 6 carry %.1f +- %.1f %% of b'_1",
        alpha,
        100 * share,
        100 * share_err,
    )
ax.axhline(1.0, color="0.6", lw=0.5)
ax.axvline(6.0, color="0.6", lw=0.5, ls=":")
ax.set_xlim(0.0, 2.0 * snakemake.params.figures["phi_cx2_max"])
ax.set_xlabel(r"$c_x^2$")
ax.set_ylabel(r"$\beta_1(c_x^2)/b'_1$")
ax.legend(loc="lower right", fontsize=6)
plotting.save(fig, snakemake.output.pdf)
