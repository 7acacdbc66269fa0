"""montanero2007 Fig. 1: kappa'(t)/kappa0 against t/tau at one alpha and two fields."""

import numpy as np

from kinetic import plotting
from kinetic.analysis import montanero2007 as analysis
from kinetic.analysis.montanero2007 import load_runs
from kinetic.workflow_support import start

log = start(snakemake)
runs = sorted(
    load_runs(snakemake.input.runs).values(),
    key=lambda ds: analysis.run_parameters(ds)["reduced_field"],
)
fig, ax = plotting.figure()
styles = ["-", "--", "-.", ":"]
for ds, style in zip(runs, styles, strict=False):
    p = analysis.run_parameters(ds)
    series = analysis.time_series_of(ds)
    t, k, e = series["time"], series["kappa_ratio"], series["kappa_ratio_err"]
    line = ax.plot(t, k, style, label=rf"$\varepsilon^* = {p['reduced_field']:g}$")[0]
    ax.fill_between(t, k - e, k + e, color=line.get_color(), alpha=0.25, lw=0)
    log.info("eps* = %g: %d realizations", p["reduced_field"], ds.sizes["realization"])
steady = analysis.steady_summary_of(runs[0])
value, error = steady["kappa_ratio"], steady["kappa_ratio_err"]
ax.axhline(
    value,
    ls=":",
    color="k",
    lw=0.8,
    label=rf"steady, $\varepsilon^*={runs[0].attrs['reduced_field']:g}$: "
    rf"{value:.3f} $\pm$ {error:.3f}",
)
ax.axhspan(value - error, value + error, color="k", alpha=0.12, lw=0)  # its standard error
ax.axvspan(steady["parameters"]["steady_from_tau"], float(np.max(t)), color="0.92", zorder=0)
alpha = analysis.run_parameters(runs[0])["restitution"]
ax.set_title(
    rf"$\alpha = {alpha:g}$ (bands: $\pm 1$ standard error; shaded: time average)", fontsize=7
)
ax.set_xlabel(r"$t/\tau$")
ax.set_ylabel(r"$\kappa'(t)/\kappa_0$")
ax.set_xlim(0, float(np.max(t)))
ax.legend(loc="lower right")
plotting.save(fig, snakemake.output.pdf)
log.info("steady kappa'/kappa0 = %.4f +- %.4f", value, error)
