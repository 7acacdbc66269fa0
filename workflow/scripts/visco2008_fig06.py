"""visco2008 Fig. 6: hard-disk μ(λ) divided by the Poisson(ω/√2) generating function
(e^{-λ} - 1)/√2, which Eq. (38) predicts to dominate at large λ. The exact bound
μ >= -1/√2 gives the ratio 1/(1 - e^{-λ}) when μ sits at that edge."""

import numpy as np

from kinetic import io, plotting
from kinetic.cloning.figures import draw_series, finite, scan_series
from kinetic.workflow_support import start

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
ratio_curve(ax, lam, closures["mu_gaussian"].values, "-", label="Gaussian (Eq. 43)")
ratio_curve(ax, lam, closures["mu_sonine"].values, "--", label="Sonine (Eqs. 47-49)")
ax.axhline(1.0, ls=":", label=r"Poisson($\omega/\sqrt{2}$), Eq. (38)")
ratio_curve(
    ax,
    reference["lam"].values,
    reference["mu"].values,
    "-",
    color="0.6",
    lw=0.7,
    label="Eq. (28), quadrature",
)
grid = lam[lam >= LAMBDA_MIN]
ax.plot(grid, 1.0 / -np.expm1(-grid), "-.", lw=0.8, label=r"$\mu=-\omega/\sqrt{2}$")


def scaled(lam, value, error):
    keep = lam >= LAMBDA_MIN
    return np.where(keep, value / poisson(lam), np.nan), np.abs(error / poisson(lam))


draw_series(ax, series, scale=scaled)
ax.set_xlim(LAMBDA_MIN, lam.max())
ax.set_ylim(0.95, 1.4)
ax.set_xlabel(r"$\lambda$")
ax.set_ylabel(r"$\mu(\lambda)\,/\,[(e^{-\lambda}-1)\,\omega/\sqrt{2}]$")
ax.legend(loc="upper right", fontsize=5.5)
plotting.save(fig, snakemake.output.pdf)
