"""visco2008 Fig. 12: free paths of Maxwell molecules (d = 2), continuous-time DSMC against
(D3) (drawn from x = 0, where it is π/2; bin averages for the residuals) and (D4)."""

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
dsmc = io.read_dataset(snakemake.input.dsmc)
curves = io.read_dataset(snakemake.input.curves)
parameters = io.parameters_of(dsmc)
if parameters["kernel"] != "maxwell" or parameters["dimension"] != 2:
    raise ValueError(f"Fig. 12 needs Maxwell molecules in d = 2, got {parameters}")
grid = curves["path"].values
histogram = Histogram(
    "DSMC",
    dsmc["path_edges"].values,
    dsmc["path_pdf"].values,
    dsmc["path_pdf_sem"].values,
    method="dsmc",
    style={"markersize": 2.5},
)
asymptotic = np.where(grid >= 1.0, curves["maxwell_asymptotic"].values, np.nan)
fig, numbers = comparison_figure(
    [histogram],
    lambda edges: collision_statistics.bin_averaged_density(
        grid, curves["maxwell_survival"].values, edges
    ),
    [
        Curve("Eq. (D3)", grid, curves["maxwell"].values, plotting.METHOD_STYLE["theory"]),
        Curve("large-$x$ form, Eq. (D4)", grid, asymptotic, plotting.METHOD_STYLE["theory_alt"]),
    ],
    linear_max=3.0,
    xlabel=r"$x$  (mean free paths $l = \langle v\rangle/\omega$)",
    ylabel=r"$P_{\rm FPL}(x)$",
    reference_label="Eq. (D3)",
)
plotting.save(fig, snakemake.output.pdf)
write_caption(
    snakemake.input.template,
    snakemake.output.caption,
    chi2=numbers["DSMC"]["chi2"],
    dof=numbers["DSMC"]["dof"],
    max_error=100 * RESIDUAL_MAX_RELATIVE_ERROR,
    p0=float(curves["maxwell"].values[0]),
    realizations=int(dsmc.sizes.get("realization", parameters.get("realizations", 0))),
)
