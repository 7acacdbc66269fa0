"""krauth2025 Figs. 4.5/4.6 and the equal-probability check: projected density η(y) of
four disks in a box, from event-disks trajectories (Eq. 4.3: time spent per bin, i.e.
Σ 1/|v_y| over the crossings of a strip, over T) and from their stroboscopic snapshots,
against direct-disks (Alg. 4.4) and markov-disks (Alg. 4.5); standard errors across
independent realizations. It is not flat: the walls attract the disks."""

from kinetic import io, plotting
from kinetic.analysis.statistics import mean_and_sem
from kinetic.workflow_support import start

start(snakemake)
md = io.read_dataset(snakemake.input.md)
series = [
    ("density_trajectory", md, "MD, Eq. (4.3)", ("md", {})),
    ("density_snapshots", md, "MD, snapshots", ("md", {"marker": "s", "mfc": "black"})),
    ("density", io.read_dataset(snakemake.input.direct), "direct-disks", ("direct", {})),
    ("density", io.read_dataset(snakemake.input.markov), "markov-disks", ("markov", {})),
]
fig, ax = plotting.figure()
for offset, (name, data, label, (method, style)) in enumerate(series):
    if "realization" in data[name].dims:
        values, error = mean_and_sem(data[name].values)  # over the realizations
    else:
        values, error = data[name].values, data[f"{name}_sem"].values
    y = data["y"].values
    every = max(1, y.size // 18)
    shown = slice(offset % every, None, every)
    plotting.method_errorbar(
        ax, method, y[shown], values[shown], error[shown], ms=2.5, label=label, **style
    )
ax.set_xlabel("$y$")
ax.set_ylabel(r"projected density $\eta(y)$")
ax.set_title(
    f"$N = {int(md.attrs['n_disks'])}$ disks of radius $\\sigma = {float(md.attrs['sigma']):g}$",
    fontsize=8,
)
plotting.legend_outside(ax)
plotting.save(fig, snakemake.output.pdf)
