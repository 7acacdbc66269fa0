"""krauth2025 §4.4.1 in numbers (rule krauth2025_pins_table): for each washing-line sample,
the pin density in the bins at the posts and in the middle fifth of the line, their ratio
("the density there is 4 times larger than in the bulk") and naive-pin's acceptance, each
with its standard error across realizations, beside the exact values (Eqs. 4.6, 4.7 averaged
over the same bins; ``post_over_centre_exact`` is Eq. 4.7 at the post over its value at
the centre, the lecture's "4 times"). Acceptance columns are naive-pin's only.

The 1-D check of the wall-rift pressure (§4.4.3): removing a slab at a wall eliminates the
configurations with a pin touching it, so βP is the pin density at contact, here
extrapolated to the post from the first bins of each realization
(``analysis.krauth2025.pin_contact_density``), against the exact βP = N/(L − 2Nσ) of N
pins of width 2σ between hard walls (columns beta_p_*); beta_p_extrapolation_bias is the
same fit applied to the exact bin averages minus the exact βP, the part of the difference
that is the method's, not the sampling's."""

import math

import numpy as np
import pandas as pd

from kinetic import io
from kinetic.analysis.krauth2025 import pin_contact_density as contact_density
from kinetic.analysis.statistics import mean_and_sem
from kinetic.workflow_support import start

start(snakemake)

rows = []
theory = {float(ds.attrs["length"]): ds for ds in map(io.read_dataset, snakemake.input.theory)}
for path in snakemake.input.lines:
    run = io.read_dataset(path)
    length, samples = float(run.attrs["length"]), int(run.attrs["samples"])
    x = run["x"].values
    width = float(run["bin_edges"][1] - run["bin_edges"][0])
    per_realization = run["counts"].values / (samples * width)
    walls = [0, x.size - 1]
    middle = np.abs(x - 0.5 * length) < 0.1 * length
    wall_r = per_realization[:, walls].mean(axis=1)
    bulk_r = per_realization[:, middle].mean(axis=1)
    wall, wall_sem = mean_and_sem(wall_r)
    bulk, bulk_sem = mean_and_sem(bulk_r)
    ratio = wall / bulk
    n_realizations = wall_r.size
    covariance = np.cov(wall_r, bulk_r)[0, 1] / n_realizations
    ratio_sem = abs(ratio) * math.sqrt(
        (wall_sem / wall) ** 2 + (bulk_sem / bulk) ** 2 - 2 * covariance / (wall * bulk)
    )
    exact = theory[length]["density_exact"].values
    naive = run.attrs["method"] == "naive"
    acceptance, acceptance_sem = mean_and_sem(samples / run["started"].values)
    curve = theory[length]["density_curve"].values
    at_post = curve[0] / np.interp(0.5 * length, theory[length]["x_curve"].values, curve)
    edges = run["bin_edges"].values
    contact_r = np.array([contact_density(edges, row) for row in per_realization])
    contact, contact_sem = mean_and_sem(contact_r)
    n_pins, sigma = int(run.attrs["n_pins"]), float(run.attrs["sigma"])
    beta_p_exact = n_pins / (length - 2 * n_pins * sigma)
    rows.append(
        {
            "method": run.attrs["method"],
            "n_pins": int(run.attrs["n_pins"]),
            "length": length,
            "bin_width": width,
            "configurations": samples * n_realizations,
            "wall_density": wall,
            "wall_density_sem": wall_sem,
            "wall_density_exact": exact[walls].mean(),
            "bulk_density": bulk,
            "bulk_density_sem": bulk_sem,
            "bulk_density_exact": exact[middle].mean(),
            "wall_over_bulk": ratio,
            "wall_over_bulk_sem": ratio_sem,
            "wall_over_bulk_exact": exact[walls].mean() / exact[middle].mean(),
            "post_over_centre_exact": at_post,
            "acceptance": acceptance if naive else math.nan,
            "acceptance_sem": acceptance_sem if naive else math.nan,
            "acceptance_exact": float(theory[length]["acceptance_exact"]) if naive else math.nan,
            "cpu_seconds": float(run["cpu_seconds"].sum()),
            "beta_p_wall_rift": contact,
            "beta_p_wall_rift_sem": contact_sem,
            "beta_p_exact": beta_p_exact,
            "beta_p_z": (contact - beta_p_exact) / contact_sem,
            "beta_p_extrapolation_bias": contact_density(edges, exact) - beta_p_exact,
        }
    )
io.write_table(pd.DataFrame(rows), snakemake.output.csv, snakemake.output.md, float_format=".5g")
