"""visco2008 Fig. 1: free-flight-time density P_FFT(t), MD at both densities (and DSMC)
against Eq. 9 (bin averages for the residuals), Eq. 11 and e^{-t}."""

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
survival = curves["hard_spheres_survival"].values

histograms = []
runs = sorted(
    (io.read_dataset(path) for path in snakemake.input.md), key=lambda d: d.attrs["density"]
)
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
for data in (io.read_dataset(path) for path in snakemake.input.dsmc):
    histograms.append(
        Histogram(
            "DSMC",
            np.asarray(data["time_edges"].values)
            if "time_edges" in data
            else collision_statistics.bin_edges(data["flight_time"].values),
            data["time_pdf"].values,
            data["time_pdf_sem"].values,
            method="dsmc",
            style={"markersize": 2.5},
        )
    )

t = grid
asymptotic = np.where(t >= 0.5, curves["hard_spheres_asymptotic"].values, np.nan)
fig, numbers = comparison_figure(
    histograms,
    lambda edges: collision_statistics.bin_averaged_density(grid, survival, edges),
    [
        Curve("Eq. (9)", t, curves["hard_spheres"].values, plotting.METHOD_STYLE["theory"]),
        Curve("Eq. (11)", t, asymptotic, {"color": "tab:green", "linestyle": ":"}),
        Curve(r"$e^{-t}$", t, curves["maxwell"].values, plotting.METHOD_STYLE["theory_alt"]),
    ],
    linear_max=4.0,
    xlabel=r"$t$  (mean free times, $\omega = 1$)",
    ylabel=r"$P_{\rm FFT}(t)$",
    reference_label="Eq. (9)",
)
plotting.save(fig, snakemake.output.pdf)
values = list(numbers.values())
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
)
