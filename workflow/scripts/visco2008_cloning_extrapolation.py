"""The 1/N_c -> 0 extrapolation of the hard-disk cloning estimates: μ, T and a2 against
1/N_c at a few λ, with the weighted straight-line fits shaded by their standard error
(from the fit's covariance of intercept and slope), their intercepts (open symbols at
1/N_c = 0) and the deterministic solution of Eq. (28) (stars)."""

import numpy as np

from kinetic import io, plotting
from kinetic.analysis.statistics import line_error
from kinetic.workflow_support import start

start(snakemake)
ds = io.read_dataset(snakemake.input.scan)
reference = io.read_dataset(snakemake.input.reference)
kernel = ds["point_kernel"].values.astype(str)
limit_kernel = ds["limit_kernel"].values.astype(str)
observables = [
    ("mu", r"$\mu$", "mu"),
    ("temperature", r"$T/T_0$", "temperature"),
    ("a2", r"$a_2$", "a2"),
]
fitted = [
    k
    for k in np.flatnonzero(limit_kernel == "hard_disks")
    if np.isfinite(ds["limit_mu_slope"].values[k])
]
wanted = [-1.5, 1.0, 2.0]
limits = sorted(
    {min(fitted, key=lambda k, w=w: abs(ds["limit_lambda"].values[k] - w)) for w in wanted},
    key=lambda k: ds["limit_lambda"].values[k],
)

fig, axes = plotting.figure(len(observables), len(limits), figsize=(2.3 * len(limits), 5.2))
axes = np.atleast_2d(axes)
for column, k in enumerate(limits):
    lam = float(ds["limit_lambda"].values[k])
    points = np.flatnonzero((kernel == "hard_disks") & (ds["point_lambda"].values == lam))
    inverse = 1.0 / ds["point_population"].values[points]
    exact_row = int(np.argmin(np.abs(reference["lam"].values - lam)))
    for row, (name, label, reference_name) in enumerate(observables):
        ax = axes[row, column]
        values = ds[f"point_{name}"].values[points]
        errors = ds[f"point_{name}_err"].values[points]
        plotting.errorbar(ax, inverse, values, errors, marker="o")
        intercept = float(ds[f"limit_{name}"].values[k])
        slope = float(ds[f"limit_{name}_slope"].values[k])
        intercept_err = float(ds[f"limit_{name}_err"].values[k])
        if np.isfinite(intercept):
            grid = np.linspace(0.0, inverse.max() * 1.05, 20)
            line = intercept + slope * grid
            (drawn,) = ax.plot(grid, line, "-", lw=0.8)
            band = line_error(
                grid,
                intercept_err,
                float(ds[f"limit_{name}_slope_err"].values[k]),
                float(ds[f"limit_{name}_covariance"].values[k]),
            )
            ax.fill_between(
                grid, line - band, line + band, color=drawn.get_color(), alpha=0.15, lw=0
            )
            plotting.errorbar(ax, [0.0], [intercept], [intercept_err], marker="s")
        exact = float(reference[reference_name].values[exact_row])
        if np.isfinite(exact):
            ax.plot([0.0], [exact], "*", color="0.3", ms=5)
        ax.set_xlim(-0.05 * inverse.max(), inverse.max() * 1.08)
        ax.tick_params(labelsize=6)
        if column == 0:
            ax.set_ylabel(label)
        if row == 0:
            ax.set_title(rf"hard disks, $\lambda={lam:g}$", fontsize=7)
        if row == len(observables) - 1:
            ax.set_xlabel(r"$1/N_c$")
fig.tight_layout()
plotting.save(fig, snakemake.output.pdf)
