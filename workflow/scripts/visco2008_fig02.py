"""visco2008 Fig. 2: free-path density P_FPL(x), MD at both densities against Eq. 14 (drawn
from x = 0, where it is finite; bin averages for the residuals) and the exponential of
Eq. 16."""

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
grid = curves["path"].values
survival = curves["hard_spheres_survival"].values
runs = sorted(
    (io.read_dataset(path) for path in snakemake.input.md), key=lambda d: d.attrs["density"]
)
histograms = []
for number, md in enumerate(runs):
    x_md, pdf_md, sem_md = collision_statistics.free_path_pdf(md)
    histograms.append(
        Histogram(
            rf"MD, $\rho\sigma^2 = {md.attrs['density']:g}$",
            collision_statistics.bin_edges(x_md),
            pdf_md,
            sem_md,
            style={"markersize": 2.0, "mfc": "black"} if number == 0 else {"markersize": 3.2},
        )
    )
fig, numbers = comparison_figure(
    histograms,
    lambda edges: collision_statistics.bin_averaged_density(grid, survival, edges),
    [
        Curve("Eq. (14)", grid, curves["hard_spheres"].values, plotting.METHOD_STYLE["theory"]),
        Curve(
            r"Eq. (16), $e^{-x/(\sqrt{2}\,l)}$",
            grid,
            curves["hard_spheres_tail"].values,
            plotting.METHOD_STYLE["theory_alt"],
        ),
    ],
    linear_max=4.0,
    xlabel=r"$x$  (mean free paths $l = \langle v\rangle/\omega$)",
    ylabel=r"$P_{\rm FPL}(x)$",
    reference_label="Eq. (14)",
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
    p0=float(curves["hard_spheres"].values[0]),
)
