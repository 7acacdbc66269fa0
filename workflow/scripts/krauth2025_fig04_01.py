"""krauth2025 Fig. 4.1: Newtonian evolution of four disks in a square box with walls, by
event-disks (Alg. 4.1): the configuration at t = 0 and right after each of the first
events; the disks of the event are filled."""

import numpy as np
from matplotlib.patches import Circle, Rectangle

from kinetic import io, plotting
from kinetic.workflow_support import start

start(snakemake)
data = io.read_dataset(snakemake.input.chaos).sel(precision="float64")
sigma = float(data.attrs["sigma"])
box = (float(data.attrs["box_x"]), float(data.attrs["box_y"]))
panels = int(snakemake.params.panels)
columns = 4
rows = -(-(panels + 1) // columns)
fig, axes = plotting.figure(rows, columns, figsize=(6.4, 1.7 * rows))
positions = [data["initial_positions"].values, *data["positions"].values[:panels]]
times = [0.0, *data["event_time"].values[:panels]]
pairs = [(-1, -1), *(tuple(p) for p in data["event_pair"].values[:panels])]
for index, ax in enumerate(np.ravel(axes)):
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_aspect("equal")
    for spine in ax.spines.values():
        spine.set_visible(False)
    if index >= len(positions):
        ax.axis("off")
        continue
    ax.add_patch(Rectangle((0, 0), *box, fill=False, lw=1.0))
    for disk, (x, y) in enumerate(positions[index]):
        involved = disk in pairs[index]
        ax.add_patch(Circle((x, y), sigma, fc="0.6" if involved else "white", ec="k", lw=0.6))
    ax.set_xlim(-0.02, box[0] + 0.02)
    ax.set_ylim(-0.02, box[1] + 0.02)
    label = "start" if index == 0 else ("wall" if pairs[index][1] < 0 else "pair")
    ax.set_title(f"t = {times[index]:.3f} ({label})", fontsize=7)
plotting.save(fig, snakemake.output.pdf)
