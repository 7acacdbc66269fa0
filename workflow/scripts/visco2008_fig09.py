"""visco2008 Fig. 9: π(n) of the number of collisions from MD at t = 10 and 50, each against
the same finite-t estimator applied to the Gaussian closure (Eq. 43, saddle-point order) and
to the exact Poisson(t) count, with the t -> ∞ curves for reference.

Bins of P(N) seen fewer than ``min_count`` times are dropped (they sit at the histogram's
floor). The caption quotes χ²/dof of the data against each finite-t curve (pooled counting
errors), computed here from the MD and theory files.
"""

import numpy as np

from kinetic import io, plotting
from kinetic.analysis import collision_statistics
from kinetic.workflow_support import start, write_caption

log = start(snakemake)
md = io.read_dataset(snakemake.input.md)
finite = io.read_dataset(snakemake.input.finite)
asymptotic = io.read_dataset(snakemake.input.curves)
min_count = int(snakemake.params.min_count)
windows = list(snakemake.params.windows)
density = md.attrs["density"]


fig, axes = plotting.figure(1, len(windows), figsize=(3.4 * len(windows), 2.8), sharey=True)
axes = np.atleast_1d(axes)
numbers = {"min_count": min_count, "density": density}
for axis, window, tag in zip(axes, windows, "ab", strict=False):
    estimate = collision_statistics.count_ldf_estimate(md, window, min_count=min_count)
    curves = finite.sel(window=window)
    theory_rate = curves["rate"].values
    axis.plot(
        asymptotic["rate"],
        asymptotic["gaussian"],
        ":",
        color="0.55",
        lw=0.9,
        label=r"Gaussian, $t\to\infty$",
    )
    axis.plot(
        asymptotic["rate"],
        asymptotic["poisson"],
        ":",
        color="0.8",
        lw=0.9,
        label=r"Poisson(1), $t\to\infty$",
    )
    axis.plot(
        theory_rate,
        curves["gaussian"],
        **plotting.METHOD_STYLE["theory"],
        label=f"Gaussian closure, $t = {window:g}$",
    )
    axis.plot(
        theory_rate,
        curves["poisson"],
        **plotting.METHOD_STYLE["theory_alt"],
        label=f"Poisson(1), $t = {window:g}$",
    )
    plotting.method_errorbar(
        axis,
        "md",
        estimate["rate"],
        estimate["ldf"],
        estimate["error"],
        markersize=3,
        label=rf"MD, $\rho\sigma^2 = {density:g}$",
        zorder=3,
    )
    for name in ("gaussian", "poisson"):
        numbers[f"chi2_{name}_{tag}"] = collision_statistics.ldf_chi2_per_dof(
            estimate["rate"],
            estimate["ldf"],
            estimate["error"],
            theory_rate,
            curves[name].values,
        )
    numbers[f"t_{tag}"] = window
    numbers[f"bins_{tag}"] = int(estimate["rate"].size)
    numbers[f"dropped_{tag}"] = estimate["dropped"]
    numbers[f"floor_{tag}"] = float(np.log(1.0 / estimate["total"]) / estimate["t"])
    # every kept point is inside the axes: the range follows the data
    low = min(-1.0, float((estimate["ldf"] - estimate["error"]).min()) - 0.05)
    axis.set_ylim(low, 0.05)
    axis.set_xlim(-0.08, min(3.0, float(asymptotic["rate"].max())))
    axis.set_xlabel(r"$n = \mathcal{N}/t$  ($\omega = 1$)")
    axis.set_title(f"({tag})  $t = {window:g}$")
    log.info("window %s: %s", window, {k: v for k, v in numbers.items() if k.endswith(tag)})
axes[0].set_ylabel(r"$\pi_t(n)$")
handles, labels = axes[0].get_legend_handles_labels()
labels = [label.replace(f"$t = {windows[0]:g}$", "finite $t$") for label in labels]
fig.legend(handles, labels, loc="lower center", ncol=3, bbox_to_anchor=(0.5, 0.0))
fig.subplots_adjust(bottom=0.33, wspace=0.1)
plotting.save(fig, snakemake.output.pdf)
write_caption(snakemake.input.template, snakemake.output.caption, **numbers)
