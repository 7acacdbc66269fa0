"""krauth2025 §4.1.2, chaos: the same initial state of four disks run by event-disks in
float32 and in float64, and in float64 from positions one unit in the last place away.
The largest position difference against the float64 run grows exponentially with the
number of events until the sequences of collisions part (vertical lines)."""

import numpy as np

from kinetic import io, plotting
from kinetic.workflow_support import start

start(snakemake)
data = io.read_dataset(snakemake.input.chaos)
reference = data.sel(precision="float64")
fig, ax = plotting.figure()
for name, label in (("float32", "float32"), ("float64_ulp", "float64, one ulp away")):
    run = data.sel(precision=name)
    gap = np.abs(run["positions"] - reference["positions"]).max(("disk", "axis")).values
    events = data["event"].values
    (line,) = ax.semilogy(events, np.maximum(gap, 1e-17), "-", lw=0.9, label=label)
    differs = np.flatnonzero((run["event_pair"] != reference["event_pair"]).any("member").values)
    if differs.size:
        ax.axvline(events[differs[0]], color=line.get_color(), ls=":", lw=0.8)
ax.set_xlabel("event")
ax.set_ylabel("largest position difference to float64")
ax.legend(fontsize=6, loc="lower right")
plotting.save(fig, snakemake.output.pdf)
