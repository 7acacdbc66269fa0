"""krauth2025 Figs. 4.5/4.6 and the equal-probability check: projected density η(y) of
four disks in a box, from event-disks trajectories (Eq. 4.3: time spent per bin, i.e.
Σ 1/|v_y| over the crossings of a strip, over T) and from their stroboscopic snapshots,
against direct-disks (Alg. 4.4) and markov-disks (Alg. 4.5); standard errors across
independent realizations, each series shifted by a fifth of a bin; below, each against
direct-disks. It is not flat: the walls attract the disks."""

from kinetic import io, plotting
from kinetic.analysis.statistics import mean_and_sem
from kinetic.workflow_support import start

start(snakemake)
md = io.read_dataset(snakemake.input.md)
reference = io.read_dataset(snakemake.input.direct)
series = [
    ("density_trajectory", md, "MD, Eq. (4.3)", ("md", {})),
    ("density_snapshots", md, "MD, snapshots", ("md", {"marker": "s", "mfc": "black"})),
    ("density", reference, "direct-disks", ("direct", {})),
    ("density", io.read_dataset(snakemake.input.markov), "markov-disks", ("markov", {})),
]
fig, (ax, rel) = plotting.figure(2, 1, sharex=True, figsize=(4.2, 3.8), height_ratios=[2, 1])


def mean_and_error(data, name):
    """A series' mean and standard error over its realizations (or as stored)."""
    if "realization" in data[name].dims:
        return mean_and_sem(data[name].values)
    return data[name].values, data[f"{name}_sem"].values


ref_values, ref_error = mean_and_error(reference, "density")
width = float(md["y"].values[1] - md["y"].values[0])
for rank, (name, data, label, (method, style)) in enumerate(series):
    values, error = mean_and_error(data, name)
    # the four agree to their errors (0.2 %): each series shifted by a fifth of a bin, so
    # that none hides another, and below each against direct-disks
    y = data["y"].values + (rank - 1.5) * 0.2 * width
    plotting.method_errorbar(ax, method, y, values, error, ms=2.0, label=label, **style)
    if data is not reference:
        plotting.residual_panel(
            rel,
            y,
            values,
            error,
            ref_values,
            theory_error=ref_error,
            method=method,
            ms=2.0,
            **style,
        )
rel.set_ylabel(r"$\eta/\eta_{\rm direct} - 1$")
rel.set_xlabel("$y$")
ax.set_ylabel(r"projected density $\eta(y)$")
ax.set_title(
    f"$N = {int(md.attrs['n_disks'])}$ disks of radius $\\sigma = {float(md.attrs['sigma']):g}$",
    fontsize=8,
)
plotting.legend_outside(ax)
plotting.save(fig, snakemake.output.pdf)
