"""visco2008 Fig. 7: T(λ), the variance per component of the hard-disk eigenfunction,
cloning Monte Carlo against the Gaussian (Eq. 43b) and Sonine closures and the
deterministic solution of Eq. (28). Crosses: T of populations that collapsed onto a few
clones at large λ (not estimates of the eigenfunction; they only show T -> 0)."""

from kinetic import io, plotting
from kinetic.plotting.visco2008_cloning import (
    collapsed_points,
    draw_series,
    finite,
    scan_series,
)
from kinetic.workflow_support import start

start(snakemake)
series = scan_series(snakemake.input.scan, "hard_disks", "T")
closures = io.read_dataset(snakemake.input.closures)
reference = io.read_dataset(snakemake.input.reference)
lam = closures["lam"].values

fig, ax = plotting.figure()
ax.plot(lam, closures["temperature_gaussian"], "-", label="Gaussian (Eq. 43)")
ax.plot(*finite(lam, closures["temperature_sonine"].values), "--", label="Sonine")
ax.plot(
    *finite(reference["lam"].values, reference["temperature"].values),
    "-",
    color="0.6",
    lw=0.7,
    label="Eq. (28), quadrature",
)
draw_series(ax, series)
lam_c, value_c, _ = collapsed_points(snakemake.input.scan, "hard_disks", "T")
if lam_c.size:
    ax.plot(
        lam_c,
        value_c,
        "x",
        color="0.5",
        ms=3,
        label=rf"collapsed population, $N_c={series.single_population}$",
    )
ax.set_xlim(lam.min(), lam.max())
ax.set_ylim(0.0, None)
ax.set_xlabel(r"$\lambda$")
ax.set_ylabel(r"$T(\lambda)/T_0$")
plotting.legend_outside(ax)
plotting.save(fig, snakemake.output.pdf)
