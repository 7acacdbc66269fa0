"""montanero2007 error of kappa' against CPU time: statistics, time-step and N biases.

Figure: top, kappa'/kappa0 against the time step for the paper's Lie splitting (Euler
and exact force steps) and the Strang splitting, with the bias model; bottom, total
relative error sqrt(I/C + (|b| + 2 db)^2) against CPU time C for each setting (curves:
the model of analysis.error_budget; points: the runs themselves, with the error of that
error).
Tables: error_vs_time.csv (one row per run), error_targets.csv (cheapest setting for
each target error). The O(eps*^2) field bias is not part of this budget (extreme.csv).
"""

import numpy as np
import pandas as pd
from matplotlib import colormaps

from kinetic import io, plotting
from kinetic.analysis import montanero2007 as analysis
from kinetic.analysis.montanero2007 import load_runs
from kinetic.analysis.statistics import error_of_sem
from kinetic.workflow_support import start

log = start(snakemake)
n_reference = snakemake.params.n_reference
rows = [analysis.summary_row(ds) for ds in load_runs(snakemake.input.runs).values()]
alphas = sorted({row["alpha"] for row in rows})
MARKERS = {
    ("lie", "euler"): "o",
    ("lie", "exact"): "s",
    ("strang", "euler"): "v",
    ("strang", "exact"): "D",
}


def describe(setting):
    text = (
        f"{setting['splitting']}/{setting['force_step']}, "
        + rf"$\delta t$={setting['time_step']:g}"
    )
    if setting["n_particles"] != n_reference:
        text += f", N={setting['n_particles']}"
    return text


fig, axes = plotting.figure(2, len(alphas), figsize=(3.4 * len(alphas), 5.2), squeeze=False)
all_settings, all_targets = [], []
for column, alpha in enumerate(alphas):
    chosen = [row for row in rows if row["alpha"] == alpha]
    settings, targets, model = analysis.error_budget(
        chosen, n_reference, snakemake.params.target_errors
    )
    log.info(
        "alpha = %g: kappa'/kappa0(dt -> 0, N -> inf) = %.4f; Lie slope %.4f per tau, "
        "curvature %.4f; Strang %.4f per tau^2; chi2/dof %.2f; c_N = %.3g +- %.3g",
        alpha,
        model["k_inf"],
        model["k1"],
        model["k2"],
        model["s2"],
        model["chi2_per_dof"],
        model["c_n"],
        model["c_n_err"],
    )
    all_settings += [{"alpha": alpha, **s} for s in settings]
    all_targets += [{"alpha": alpha, **t} for t in targets]

    top, bottom = axes[0, column], axes[1, column]
    for (splitting, force_step), marker in MARKERS.items():
        own = [
            s
            for s in settings
            if (s["splitting"], s["force_step"]) == (splitting, force_step)
            and s["n_particles"] == n_reference
        ]
        if own:
            plotting.errorbar(
                top,
                [s["time_step"] for s in own],
                [s["kappa_ratio"] for s in own],
                [s["kappa_ratio_err"] for s in own],
                marker=marker,
                label=f"{splitting} splitting, {force_step} force step",
            )
    small = [s for s in settings if s["n_particles"] != n_reference]
    if small:
        plotting.errorbar(
            top,
            [s["time_step"] for s in small],
            [s["kappa_ratio"] for s in small],
            [s["kappa_ratio_err"] for s in small],
            marker="^",
            color="0.5",
            label="N = " + ", ".join(str(s["n_particles"]) for s in small),
        )
    grid = np.geomspace(
        min(s["time_step"] for s in settings) / 2, max(s["time_step"] for s in settings) * 1.2, 100
    )
    top.plot(
        grid,
        model["k0"] + model["k1"] * grid + model["k2"] * grid**2,
        "-",
        color="k",
        lw=0.8,
        label="bias model, Lie",
    )
    if any(s["splitting"] == "strang" for s in settings):
        top.plot(
            grid,
            model["k0"] + model["s2"] * grid**2,
            "--",
            color="k",
            lw=0.8,
            label="bias model, Strang",
        )
    top.axhline(
        model["k_inf"], ls=":", color="k", lw=0.6, label=r"$\delta t \to 0$, $N \to \infty$"
    )
    top.axhspan(
        model["k_inf"] - model["k_inf_err"],
        model["k_inf"] + model["k_inf_err"],
        color="k",
        alpha=0.1,
        lw=0,
    )
    top.set_xscale("log")
    top.set_xlabel(r"$\delta t/\tau$")
    top.set_ylabel(r"$\kappa'/\kappa_0$")
    top.set_title(rf"$\alpha = {alpha:g}$", fontsize=8)

    steps = sorted({s["time_step"] for s in settings})
    palette = dict(
        zip(steps, colormaps["viridis"](np.linspace(0.0, 0.85, len(steps))), strict=True)
    )
    cpu_min = min(s["cpu_seconds"] for s in settings) / 10
    cpu = np.geomspace(cpu_min, cpu_min * 1e6, 200)
    for s in settings:
        bias = abs(s["relative_bias"]) + 2.0 * s["relative_bias_err"]
        small_n = s["n_particles"] != n_reference
        if small_n:
            style, color = ":", "0.5"
        else:
            style = {"lie": "-", "strang": "-."}[s["splitting"]]
            color = palette[s["time_step"]]
        bottom.plot(
            cpu,
            np.sqrt(s["inefficiency"] / cpu + bias**2),
            style,
            color=color,
            lw=0.9 if s["force_step"] == "euler" else 0.6,
            label=describe(s),
        )
        # the run's own total error, with its error: the statistical error's from the
        # realizations (SE/√(2(n − 1))) and the bias's error, propagated through the sum
        stat = s["relative_stat_err"]
        total = np.hypot(stat, bias)
        spread = np.hypot(
            stat * error_of_sem(stat, s["realizations"]), bias * s["relative_bias_err"]
        )
        plotting.errorbar(
            bottom,
            [s["cpu_seconds"]],
            [total],
            [spread / total],
            marker=MARKERS[(s["splitting"], s["force_step"])],
            color=color,
            ms=3,
        )
    bottom.set_xscale("log")
    bottom.set_yscale("log")
    bottom.set_xlabel("CPU time (s, one core)")
    bottom.set_ylabel(r"relative error of $\kappa'$ (stat. $\oplus$ bias)")

plotting.figure_legend(fig, ncols=4)
settings_table = pd.DataFrame(all_settings)
targets_table = pd.DataFrame(all_targets)
plotting.save(fig, snakemake.output.pdf)
io.write_table(settings_table, snakemake.output.csv, snakemake.output.md, float_format=".4g")
io.write_table(
    targets_table, snakemake.output.targets_csv, snakemake.output.targets_md, float_format=".4g"
)
log.info("settings:\n%s", settings_table.to_string(index=False))
log.info("cheapest settings:\n%s", targets_table.to_string(index=False))
