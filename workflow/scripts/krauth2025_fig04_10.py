"""krauth2025 Fig. 4.10: N clothes-pins of width 2σ on a washing line of length L, a few
independent direct-pin configurations (Alg. 4.7), one per row."""

from matplotlib.patches import Rectangle

from kinetic import io, plotting
from kinetic.workflow_support import start

start(snakemake)
data = io.read_dataset(snakemake.input.snapshots)
length, sigma = float(data.attrs["length"]), float(data.attrs["sigma"])
positions = data["position"].values

fig, ax = plotting.figure(figsize=(3.4, 0.35 * len(positions) + 0.5))
for row, configuration in enumerate(positions):
    y = len(positions) - 1 - row
    ax.plot([0, length], [y, y], color="0.5", lw=0.6)  # the line
    for x in configuration:
        ax.add_patch(Rectangle((x - sigma, y - 0.3), 2 * sigma, 0.6, fc="0.8", ec="k", lw=0.4))
for post in (0.0, length):
    ax.plot([post, post], [-0.6, len(positions) - 0.4], color="k", lw=1.5)
ax.set_xlim(-0.5, length + 0.5)
ax.set_ylim(-0.8, len(positions) - 0.2)
ax.set_yticks([])
ax.set_xlabel("$x$")
ax.set_title(f"$N = {positions.shape[1]}$ pins, $2\\sigma = {2 * sigma:g}$, $L = {length:g}$")
plotting.save(fig, snakemake.output.pdf)
