"""visco2008 Fig. 6: hard-disk μ(λ) divided by the Poisson(ω/√2) generating function
(e^{-λ} - 1)/√2, which Eq. (38) predicts to dominate at large λ. The exact bound
μ >= -1/√2 gives the ratio 1/(1 - e^{-λ}) when μ sits at that edge."""

import numpy as np

from kinetic import io, plotting
from kinetic.plotting.visco2008_cloning import data_limits, draw_series, finite, scan_series
from kinetic.workflow_support import start, write_caption

start(snakemake)
LAMBDA_MIN = 0.5  # the ratio is shown where e^{-λ} is small, as in the document
series = scan_series(snakemake.input.scan, "hard_disks", "mu")
closures = io.read_dataset(snakemake.input.closures)
reference = io.read_dataset(snakemake.input.reference)


def poisson(lam):
    return np.expm1(-np.asarray(lam)) / np.sqrt(2.0)


def ratio_curve(axis, lam, mu, style, **kwargs):
    lam, mu = finite(lam, mu)
    keep = lam >= LAMBDA_MIN
    axis.plot(lam[keep], mu[keep] / poisson(lam[keep]), style, **kwargs)


lam = closures["lam"].values
fig, ax = plotting.figure()
ratio_curve(
    ax, lam, closures["mu_gaussian"].values, "-", color="tab:green", label="Gaussian (Eq. 43)"
)
ratio_curve(
    ax, lam, closures["mu_sonine"].values, "--", color="tab:green", label="Sonine (Eqs. 47-49)"
)
ax.axhline(
    1.0, **plotting.METHOD_STYLE["theory_alt"], label=r"Poisson($\omega/\sqrt{2}$), Eq. (38)"
)
ratio_curve(
    ax,
    reference["lam"].values,
    reference["mu"].values,
    "-",
    color="0.3",
    lw=0.7,
    label="Eq. (28), quadrature",
)
grid = lam[lam >= LAMBDA_MIN]
ax.plot(grid, 1.0 / -np.expm1(-grid), "-.", color="0.5", lw=0.8, label=r"$\mu=-\omega/\sqrt{2}$")


def scaled(lam, value, error):
    keep = lam >= LAMBDA_MIN
    return np.where(keep, value / poisson(lam), np.nan), np.where(
        keep, np.abs(error / poisson(lam)), np.nan
    )


drawn = draw_series(ax, series, scale=scaled)
ax.set_xlim(LAMBDA_MIN - 0.1, lam.max() + 0.2)
low, high = data_limits(drawn, include=[0.95, 1.4])  # every point inside the axes
ax.set_ylim(low, high)
ax.set_xlabel(r"$\lambda$")
ax.set_ylabel(r"$\mu(\lambda)\,/\,[(e^{-\lambda}-1)\,\omega/\sqrt{2}]$")
fig.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2)
plotting.save(fig, snakemake.output.pdf)
single_lam, single_ratio, _ = drawn["single"]
write_caption(
    snakemake.input.template,
    snakemake.output.caption,
    population=series.single_population,
    n_single=int(single_lam.size),
    n_limit=int(drawn["limit"][0].size),
    lambdas_single=", ".join(f"{x:g}" for x in single_lam) or "none",
    n_above_bound=int(np.sum(single_ratio > 1.0 / -np.expm1(-single_lam))),
)
