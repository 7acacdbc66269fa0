"""krauth2025 Fig. 4.11: density of clothes-pins along the washing line, sampled by
direct-pin (Alg. 4.7) and naive-pin (Alg. 4.6) with standard errors, against Eq. (4.7)
averaged over each bin (steps: what a histogram estimates) and at each point (dashed).
Left: the line of the figure, where naive-pin's acceptance (Eq. 4.6) is too small to run;
right: a longer line where both samplers run. The caption gives, per line, Eq. (4.7)'s
density at a post over that at the middle, the acceptance, and each sampler's first bin
against Eq. (4.7)'s average over it.
Every bin is drawn within WALL_ZONE of a post, where the density varies fastest; in the
bulk one bin in ``every`` (the two samplers offset) keeps the markers apart."""

import numpy as np

from kinetic import io, plotting
from kinetic.workflow_support import start, write_caption

start(snakemake)
runs = [io.read_dataset(path) for path in snakemake.input.lines]
theory = {float(ds.attrs["length"]): ds for ds in map(io.read_dataset, snakemake.input.theory)}
lengths = sorted({float(run.attrs["length"]) for run in runs})
style = {"direct": ("direct", "direct-pin"), "naive": ("markov", "naive-pin")}
WALL_ZONE = 2.0  # two pin widths from each post


def caption_line(length, exact, here):
    """One sentence per line length: Eq. (4.7) at a post over the middle, the naive-pin
    acceptance, and each sampler's first bin (by a post) against the bin average."""
    curve, x_curve = exact["density_curve"].values, exact["x_curve"].values
    middle = np.interp(0.5 * (x_curve[0] + x_curve[-1]), x_curve, curve)
    first = float(exact["density_exact"].values[0])
    samples = []
    for run in here:
        value, error = float(run["density"].values[0]), float(run["density_sem"].values[0])
        samples.append(
            f"{style[run.attrs['method']][1]} {value:.3g} ± {error:.2g} "
            f"({(value - first) / error:+.1f} errors)"
        )
    return (
        f"L = {length:g}: at a post Eq. (4.7) is {curve[0] / middle:.2f} times its value at "
        f"the middle of the line, naive-pin's acceptance {float(exact['acceptance_exact']):.2g}; "
        f"first bin {first:.3g} (Eq. 4.7) against {', '.join(samples)}."
    )


lines = []  # the caption's sentence per line length
fig, axes = plotting.figure(1, len(lengths), figsize=(6.4, 2.6), sharey=False)
axes = list(axes) if len(lengths) > 1 else [axes]
for ax, length in zip(axes, lengths, strict=True):
    here = [run for run in runs if float(run.attrs["length"]) == length]
    ax.plot(
        theory[length]["x_curve"],
        theory[length]["density_curve"],
        **plotting.METHOD_STYLE["theory_alt"],
        lw=0.6,
        label="Eq. (4.7)",
    )
    # what a histogram estimates: Eq. (4.7) averaged over each bin (at a post the curve
    # is 3.0, the first bin's average 2.6)
    plotting.theory_steps(
        ax,
        theory[length]["bin_edges"].values,
        theory[length]["density_exact"].values,
        lw=0.8,
        label="Eq. (4.7), bin averages",
    )
    for offset, run in enumerate(here):
        method, label = style[run.attrs["method"]]
        x = run["x"].values
        every = max(1, run.sizes["x"] // 60)
        near_post = (x < x[0] + WALL_ZONE) | (x > x[-1] - WALL_ZONE)
        shown = near_post | (np.arange(x.size) % every == (offset * every // 2) % every)
        plotting.method_errorbar(
            ax,
            method,
            x[shown],
            run["density"].values[shown],
            run["density_sem"].values[shown],
            ms=2.5,
            label=label,
        )
    ax.set_xlabel("$x$")
    ax.set_ylabel(r"density of pins $N\pi(x)$")
    ax.set_title(f"$N = {here[0].attrs['n_pins']}$, $L = {length:g}$", fontsize=8)
    ax.legend(loc="upper center")
    lines.append(caption_line(length, theory[length], here))
plotting.save(fig, snakemake.output.pdf)
write_caption(snakemake.input.template, snakemake.output.caption, lines=" ".join(lines))
