"""visco2008 Fig. 10: P_FFT(t) from MD at both densities against Eq. 9 and the
Gaussian-weighted P_FFT^W (A1) with its large-time form (A8); residuals against the bin
averages of Eq. 9, with P^W/P_FFT - 1 (A1 over Eq. 9, both bin-averaged) beside them."""

import numpy as np

from kinetic import io, plotting
from kinetic.analysis import collision_statistics
from kinetic.plotting.visco2008 import (
    RESIDUAL_MAX_RELATIVE_ERROR,
    Curve,
    Histogram,
    comparison_figure,
)
from kinetic.workflow_support import start, write_caption

start(snakemake)
curves = io.read_dataset(snakemake.input.curves)
grid = curves["time"].values
runs = sorted(
    (io.read_dataset(path) for path in snakemake.input.md), key=lambda d: d.attrs["density"]
)
histograms = []
for number, md in enumerate(runs):
    t_md, pdf_md, sem_md = collision_statistics.flight_time_pdf(md)
    histograms.append(
        Histogram(
            rf"MD, $\rho\sigma^2 = {md.attrs['density']:g}$",
            collision_statistics.bin_edges(t_md),
            pdf_md,
            sem_md,
            style={"markersize": 2.0, "mfc": "black"} if number == 0 else {"markersize": 3.2},
        )
    )


def hard_spheres(edges):
    return collision_statistics.bin_averaged_density(
        grid, curves["hard_spheres_survival"].values, edges
    )


def weighted(edges):
    return collision_statistics.bin_averaged_density(
        grid, curves["weighted_survival"].values, edges
    )


# P^W/P - 1 on the bins of the low-density run, the ratio the document quotes (≈ 1.3 at
# large t), as a line in the residual panels
edges = histograms[0].edges
edges = edges[edges <= grid[-1]]
ratio = weighted(edges) / hard_spheres(edges) - 1
centres = 0.5 * (edges[1:] + edges[:-1])
asymptotic = np.where(grid >= 1.0, curves["weighted_asymptotic"].values, np.nan)
fig, numbers = comparison_figure(
    histograms,
    hard_spheres,
    [
        Curve("Eq. (9)", grid, curves["hard_spheres"].values, plotting.METHOD_STYLE["theory"]),
        Curve(
            r"$P^W_{\rm FFT}$ (A1)",
            grid,
            curves["weighted"].values,
            plotting.METHOD_STYLE["theory_alt"],
        ),
        Curve("(A8)", grid, asymptotic, {"color": "tab:gray", "linestyle": ":"}),
    ],
    extra_residuals=[
        Curve(
            r"$P^W_{\rm FFT}/P_{\rm FFT} - 1$",
            centres,
            ratio,
            {**plotting.METHOD_STYLE["theory_alt"], "linewidth": 1.0},
        )
    ],
    linear_max=3.0,
    xlabel=r"$t$  (mean free times, $\omega = 1$)",
    ylabel=r"$P_{\rm FFT}(t)$",
    reference_label="Eq. (9)",
)
plotting.save(fig, snakemake.output.pdf)
values = list(numbers.values())
t_ratio = 10.0
write_caption(
    snakemake.input.template,
    snakemake.output.caption,
    rho_low=runs[0].attrs["density"],
    rho_high=runs[-1].attrs["density"],
    chi2_low=values[0]["chi2"],
    dof_low=values[0]["dof"],
    chi2_high=values[1]["chi2"],
    dof_high=values[1]["dof"],
    max_error=100 * RESIDUAL_MAX_RELATIVE_ERROR,
    t_ratio=t_ratio,
    ratio=float(np.interp(t_ratio, centres, ratio)) + 1.0,
)
