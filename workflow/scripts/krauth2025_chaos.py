"""krauth2025 §4.1.2, chaos: the same initial state of four disks run by event-disks in
float32 and in float64, and in float64 from positions one unit in the last place away.
The largest position difference against the float64 run grows exponentially until the
sequences of collisions part (vertical lines): against all events (walls included) and
against pair collisions per disk, the lecture's count. chaos_table.csv gives, for the
figure's start and for further random starts, the event and the pair collisions per disk
at which each sequence parts from float64, with their mean and standard error over the
random starts (given only where every start parted within the events compared)."""

import numpy as np
import pandas as pd

from kinetic import io, plotting
from kinetic.analysis.krauth2025 import (
    pair_collisions_per_disk,
    parting_summary,
    parting_table,
)
from kinetic.workflow_support import start, write_caption

log = start(snakemake)
data = io.read_dataset(snakemake.input.chaos)
n_disks = int(data.attrs["n_disks"])
reference = data.sel(precision="float64")
events = data["event"].values
per_disk = pair_collisions_per_disk(reference["event_pair"].values, n_disks)
fig, (by_event, by_pair) = plotting.figure(1, 2, figsize=(6.8, 2.6), sharey=True)
labels = {"float32": "float32", "float64_ulp": "float64, one ulp away"}
for name, label in labels.items():
    run = data.sel(precision=name)
    gap = np.abs(run["positions"] - reference["positions"]).max(("disk", "axis")).values
    gap = np.maximum(gap, 1e-17)
    (line,) = by_event.semilogy(events, gap, "-", lw=0.9, label=label)
    by_pair.semilogy(per_disk, gap, "-", lw=0.9, color=line.get_color())
    differs = np.flatnonzero((run["event_pair"] != reference["event_pair"]).any("member").values)
    if differs.size:
        by_event.axvline(events[differs[0]], color=line.get_color(), ls=":", lw=0.8)
        by_pair.axvline(per_disk[differs[0]], color=line.get_color(), ls=":", lw=0.8)
by_event.set_xlabel("event (pair and wall collisions)")
by_pair.set_xlabel("pair collisions per disk")
by_event.set_ylabel("largest position difference to float64")
plotting.figure_legend(fig, ncols=2)
plotting.save(fig, snakemake.output.pdf)

table = pd.DataFrame(parting_table(data))
summary = parting_summary(table)
for row in summary:
    if row["starts_parted"] < row["starts"]:
        log.warning(
            "%s: %d of %d random starts did not part within %d events; their mean is not "
            "given (raise chaos_events)",
            row["comparison"],
            row["starts"] - row["starts_parted"],
            row["starts"],
            row["events_compared"],
        )
table = pd.concat([table, pd.DataFrame(summary)], ignore_index=True)
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".4g")
log.info("where the precisions part:\n%s", table.to_string(index=False))

first = table[table["start"] == 0].set_index("comparison")
means = table[table["start"] == -1].set_index("comparison")
numbers = {
    "start": data.attrs["start"],
    "starts": int(data.attrs["extra_starts"]),
    "events": int(data.sizes["event"]),
}
for key, comparison in (("f32", "float32 against float64"), ("ulp", "float64_ulp against float64")):
    numbers[f"{key}_event"] = first.loc[comparison, "parting_event"]
    numbers[f"{key}_pairs"] = first.loc[comparison, "pair_collisions_per_disk"]
    parted = means.loc[comparison, "starts_parted"] if comparison in means.index else 0
    numbers[f"{key}_parted"] = int(parted)
    if comparison in means.index:
        for name in ("parting_event", "pair_collisions_per_disk"):
            numbers[f"{key}_{name}"] = means.loc[comparison, name]
            numbers[f"{key}_{name}_sem"] = means.loc[comparison, f"{name}_sem"]
    else:
        for name in ("parting_event", "pair_collisions_per_disk"):
            numbers[f"{key}_{name}"] = numbers[f"{key}_{name}_sem"] = np.nan
write_caption(snakemake.input.template, snakemake.output.caption, **numbers)
