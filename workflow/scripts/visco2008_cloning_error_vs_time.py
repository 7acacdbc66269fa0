"""Error of the cloning μ(λ) against CPU time: statistical error of both estimators
for each population size (lines) and the finite-N_c bias against the deterministic
solution of Eq. (28) (dotted levels). Error bars and the thin lines' bands: the standard
error of each standard error, SE/√(2(n − 1)) for n realizations; the bias's band: its
standard error (the final run's; Eq. (28) is exact)."""

import numpy as np

from kinetic import io, plotting
from kinetic.analysis.cloning import BIAS_RESOLVED_SIGMAS
from kinetic.analysis.statistics import error_of_sem
from kinetic.workflow_support import start

start(snakemake)
ds = io.read_dataset(snakemake.input.curves)
lams = sorted(set(ds["point_lambda"].values.tolist()), reverse=True)

fig, axes = plotting.figure(1, len(lams), figsize=(3.4 * len(lams), 2.8), sharey=True)
axes = np.atleast_1d(axes)
for ax, lam in zip(axes, lams, strict=True):
    for k in np.flatnonzero(ds["point_lambda"].values == lam):
        n_c = int(ds["point_population"].values[k])
        cpu = ds["cpu_seconds"].values[k]
        error = ds["mu_rate_err"].values[k]
        spread = error_of_sem(error, ds["point_realizations"].values[k])
        (line,) = ax.loglog(cpu, error, "-", lw=0.8)
        plotting.errorbar(
            ax, cpu, error, spread, color=line.get_color(), ms=2, label=rf"$N_c={n_c}$"
        )
        compensation = ds["mu_err"].values[k]
        compensation_spread = error_of_sem(compensation, ds["point_realizations"].values[k])
        ax.loglog(cpu, compensation, "-", lw=0.6, color=line.get_color())
        ax.fill_between(
            cpu,
            compensation - compensation_spread,
            compensation + compensation_spread,
            color=line.get_color(),
            alpha=0.15,
            lw=0,
        )
        bias = abs(float(ds["mu_rate"].values[k] - ds["mu_exact"].values[k]))
        bias_err = float(ds["mu_rate_final_err"].values[k])
        if bias > BIAS_RESOLVED_SIGMAS * bias_err:  # resolved
            ax.axhline(bias, ls=":", lw=0.8, color=line.get_color())
            ax.axhspan(bias - bias_err, bias + bias_err, color=line.get_color(), alpha=0.1, lw=0)
    ax.set_title(rf"$\lambda={lam:g}$")
    ax.set_xlabel("CPU time (s)")
axes[0].set_ylabel(r"error of $\mu$")
handles, labels = axes[-1].get_legend_handles_labels()
fig.legend(
    handles,
    labels,
    loc="upper center",
    ncol=min(len(labels), 5),
    bbox_to_anchor=(0.5, 1.12),
)
fig.text(
    0.5,
    -0.06,
    r"points: $(e^{-\lambda}-1)\langle r\rangle$ estimator; thin lines: "
    r"compensation count; dotted: $|\mu(N_c)-\mu|$ against Eq. (28) where > "
    f"{BIAS_RESOLVED_SIGMAS:g} s.e.",
    ha="center",
)
plotting.save(fig, snakemake.output.pdf)
