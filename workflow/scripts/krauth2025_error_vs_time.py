"""krauth2025 error against CPU time, for every method of the document (rule
krauth2025_error_vs_time), from the runs the figures use: for each method a headline
quantity is measured once per independent realization (a run or a chain); the standard
error of the first k realizations is drawn against their summed CPU time (points), with the
1/√(CPU time) law through the full run (line). The table gives, per method, the total CPU
time, the standard error, the error at one CPU-second (σ √t) and the CPU time a relative
error of 0.1 % would take, so a user can pick the cheapest method and run length. All the
methods are unbiased here (no time step, exact event times): the error is statistical."""

import math

import numpy as np
import pandas as pd
from matplotlib import colormaps

from kinetic import io, plotting
from kinetic.analysis.krauth2025 import contact_pressure, wall_pressures
from kinetic.analysis.statistics import (
    cpu_for_error,
    error_against_cpu,
    error_of_sem,
    mean_and_sem,
)
from kinetic.workflow_support import start

start(snakemake)


def middle(data, name, axis):
    """Per-realization mean of a histogrammed density over the middle fifth of its range."""
    centres = data[axis].values
    span = data["bin_edges"].values[[0, -1]]
    inside = np.abs(centres - span.mean()) < 0.1 * (span[1] - span[0])
    counts = data["counts"].values[:, inside]
    width = float(data["bin_edges"][1] - data["bin_edges"][0])
    return counts.mean(axis=1) / (per_sample(data) * width)


def per_sample(data):
    attrs = data.attrs
    if "sweeps" in attrs:  # ring chains: every pin is a sample
        return int(attrs["sweeps"]) * int(attrs["n_pins"])
    return int(attrs["samples"])


series = []
for path in snakemake.input.lines:
    data = io.read_dataset(path)
    method = f"{data.attrs['method']}-pin, L = {float(data.attrs['length']):g}"
    series.append(
        (method, "bulk pin density", middle(data, "density", "x"), data["cpu_seconds"].values)
    )
ring = io.read_dataset(snakemake.input.ring)
series.append(
    (
        "ring Markov chain",
        "pair density, middle fifth",
        middle(ring, "pair_density", "r"),
        ring["cpu_seconds"].values,
    )
)
for name in ("direct", "markov"):
    data = io.read_dataset(getattr(snakemake.input, name))
    series.append(
        (
            f"{name}-disks",
            "beta P (contact density)",
            contact_pressure(data),
            data["cpu_seconds"].values,
        )
    )
md = io.read_dataset(snakemake.input.md)
rift, kinematic = wall_pressures(md, "all")  # square box: P_x = P_y, all four walls
cpu_md = md["cpu_seconds"].values
series += [
    ("event-disks, wall rift (4.9a)", "beta P", rift, cpu_md),
    ("event-disks, kinematic (4.10a)", "beta P", kinematic, cpu_md),
    ("event-disks, contact density (Eq. 4.3)", "beta P", contact_pressure(md), cpu_md),
]

rows = []
fig, ax = plotting.figure(figsize=(6.4, 3.4))
colours = colormaps["tab10"].colors
for index, (method, quantity, values, cpu) in enumerate(series):
    groups = values.size
    spent = np.cumsum(cpu)
    curve = error_against_cpu(
        range(2, groups + 1),
        lambda m, values=values: mean_and_sem(values[:m]),
        lambda m, spent=spent: spent[m - 1],
    )
    errors, times = curve.error, curve.cpu_seconds
    mean = values.mean()
    relative = errors / abs(mean)
    colour = colours[index % len(colours)]
    spread = error_of_sem(relative, np.asarray(curve.part))  # n groups behind each error
    plotting.errorbar(
        ax, times, relative, spread, marker="os^v"[index % 4], ms=2.5, color=colour, label=method
    )
    ax.set_xscale("log")
    ax.set_yscale("log")
    merit = relative[-1] * math.sqrt(times[-1])
    line = np.geomspace(times[0], times[-1] * 10, 20)
    ax.loglog(line, merit / np.sqrt(line), "-", lw=0.6, color=colour)
    rows.append(
        {
            "method": method,
            "quantity": quantity,
            "value": mean,
            "groups": groups,
            "cpu_seconds": float(times[-1]),
            "sem": errors[-1],
            "relative_error_at_1_cpu_second": merit,
            "cpu_seconds_for_0.1_percent": cpu_for_error(times[-1], relative[-1], 1e-3),
        }
    )
ax.set_xlabel("CPU time (s)")
ax.set_ylabel("relative standard error")
plotting.legend_outside(ax)
plotting.save(fig, snakemake.output.pdf)
io.write_table(pd.DataFrame(rows), snakemake.output.csv, snakemake.output.md, float_format=".4g")
