"""krauth2025 §4.4.3 in numbers (rule krauth2025_pressure_table): the pressure of four
disks in a box by the wall-rift (Eq. 4.9a) and kinematic (Eq. 4.10a, times β) EDMD
estimators on the x and y walls, and the thermodynamic value βP = contact density (the
projected density at the wall over the wall length, from the MD's Eq. 4.3 density and from
direct-disks); then the averages of Eqs. (4.13a/b) over wall collisions and (4.14a/b) over
pair collisions against their finite-N values. Each measured row: mean and standard error
across independent realizations (batches for direct-disks); ``z`` = (value − reference) /
standard error, with the reference's own standard error (direct-disks batches) combined.
(4.14a) is compared with its corrected value; the printed one is listed."""

import math

import numpy as np
import pandas as pd

from kinetic import io
from kinetic.theory import krauth2025 as theory
from kinetic.workflow_support import start

start(snakemake)
md = io.read_dataset(snakemake.input.md)
direct = io.read_dataset(snakemake.input.direct)
n = int(md.attrs["n_disks"])
duration = float(md.attrs["duration"])
box_x, box_y = float(md.attrs["box_x"]), float(md.attrs["box_y"])
walls = md["wall_statistics"].values  # (realization, face, [count, sum, sum_inverse])
pairs = md["pair_statistics"].values
radius = np.sqrt(md["radius_squared"].values)
beta = 2 * n / radius**2  # k_B T = R²/(2N), m = 1
edges = md["bin_edges"].values


def mean_sem(values):
    values = np.asarray(values, dtype=float)
    return values.mean(), values.std(ddof=1) / math.sqrt(values.size)


def rift(faces, length):
    return walls[:, faces, 2].sum(axis=1) * 2 / (2 * length * duration)


def kinematic(faces, length):
    return beta * walls[:, faces, 1].sum(axis=1) * 2 / (2 * length * duration)


contact_md = [theory.wall_value(edges, row) / box_x for row in md["density_trajectory"].values]
samples = int(direct.attrs["samples"])
width = float(edges[1] - edges[0])
contact_direct = [
    theory.wall_value(direct["bin_edges"].values, row / (samples * width)) / box_x
    for row in direct["counts"].values
]
thermodynamic, thermodynamic_sem = mean_sem(contact_direct)
wall_exact = theory.wall_speed_averages(n, float(radius.mean()))
pair_exact = theory.pair_speed_averages(n, float(radius.mean()))
rows = []


def row(quantity, equation, values, reference, source, reference_sem=0.0, printed=math.nan):
    value, sem = mean_sem(values)
    rows.append(
        {
            "quantity": quantity,
            "equation": equation,
            "value": value,
            "sem": sem,
            "reference": reference,
            "reference_sem": reference_sem,
            "reference_source": source,
            "z": (value - reference) / math.hypot(sem, reference_sem),
            "printed_value": printed,
        }
    )


contact = "contact density from direct-disks"
row("beta P_x, wall rift", "4.9a", rift([0, 1], box_y), thermodynamic, contact, thermodynamic_sem)
row("beta P_y, wall rift", "4.9a", rift([2, 3], box_x), thermodynamic, contact, thermodynamic_sem)
row(
    "beta P_x, kinematic",
    "4.10a",
    kinematic([0, 1], box_y),
    thermodynamic,
    contact,
    thermodynamic_sem,
)
row(
    "beta P_y, kinematic",
    "4.10a",
    kinematic([2, 3], box_x),
    thermodynamic,
    contact,
    thermodynamic_sem,
)
row(
    "beta P, contact density (MD, Eq. 4.3)",
    "4.8",
    contact_md,
    thermodynamic,
    contact,
    thermodynamic_sem,
)
row(
    "mean of 1/v_perp over wall collisions",
    "4.13a",
    walls[:, :, 2].sum(1) / walls[:, :, 0].sum(1),
    wall_exact["inverse"],
    "Eq. 4.13a",
)
row(
    "mean of v_perp over wall collisions",
    "4.13b",
    walls[:, :, 1].sum(1) / walls[:, :, 0].sum(1),
    wall_exact["mean"],
    "Eq. 4.13b",
)
row(
    "mean of 1/dv_perp over pair collisions",
    "4.14a",
    pairs[:, 2] / pairs[:, 0],
    pair_exact["inverse"],
    "Eq. 4.14a corrected (sqrt(pi/2) for the printed sqrt(2 pi))",
    printed=pair_exact["inverse_printed"],
)
row(
    "mean of dv_perp over pair collisions",
    "4.14b",
    pairs[:, 1] / pairs[:, 0],
    pair_exact["mean"],
    "Eq. 4.14b",
)
table = pd.DataFrame(rows)
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".5g")
