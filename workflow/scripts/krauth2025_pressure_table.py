"""krauth2025 §4.4.3 in numbers (rule krauth2025_pressure_table): the pressure of four
disks in a box by the wall-rift (Eq. 4.9a) and kinematic (Eq. 4.10a, times β) EDMD
estimators on the x and y walls, and the thermodynamic value βP = contact density (the
projected density at the wall over the wall length, from the MD's Eq. 4.3 density and from
direct-disks); then the averages of Eqs. (4.13a/b) over wall collisions and (4.14a/b) over
pair collisions against their finite-N values; then βP from the rate of wall hits n̂
(4.9b) times the finite-N flux average (4.9c, = β times 4.10c) and times its N → ∞ limit
(4.9d, = β times 4.10d corrected): at N = 4 the two differ by Γ(N+1/2)/(Γ(N)√N) = 0.969,
and the z-scores say which the measured pressure follows. Each measured row: mean and standard error
across independent realizations (runs or chains for the samplers); ``z`` = (value − reference) /
standard error, with the reference's own standard error (direct-disks realizations) combined.
(4.14a) is compared with its corrected value; the printed one is listed."""

import math

import numpy as np
import pandas as pd

from kinetic import io
from kinetic.analysis.krauth2025 import (
    contact_pressure,
    rate_pressures,
    wall_hit_rate,
    wall_pressures,
)
from kinetic.analysis.statistics import mean_and_sem
from kinetic.theory import krauth2025 as theory
from kinetic.workflow_support import start

start(snakemake)
md = io.read_dataset(snakemake.input.md)
n = int(md.attrs["n_disks"])
walls = md["wall_statistics"].values  # (realization, face, [count, sum, sum_inverse])
pairs = md["pair_statistics"].values
radius = float(np.sqrt(md["radius_squared"].values).mean())
rift_x, kinematic_x = wall_pressures(md, "x")
rift_y, kinematic_y = wall_pressures(md, "y")
thermodynamic, thermodynamic_sem = mean_and_sem(
    contact_pressure(io.read_dataset(snakemake.input.direct))
)
wall_exact = theory.wall_speed_averages(n, radius)
pair_exact = theory.pair_speed_averages(n, radius)
rows = []


def row(quantity, equation, values, reference, source, reference_sem=0.0, printed=math.nan):
    value, sem = mean_and_sem(values)
    rows.append(
        {
            "quantity": quantity,
            "equation": equation,
            "value": value,
            "sem": sem,
            "reference": reference,
            "reference_sem": reference_sem,
            "reference_source": source,
            "z": (
                (value - reference) / math.hypot(sem, reference_sem)
                if math.isfinite(reference)
                else math.nan
            ),
            "printed_value": printed,
        }
    )


contact = "contact density from direct-disks"
row("beta P_x, wall rift", "4.9a", rift_x, thermodynamic, contact, thermodynamic_sem)
row("beta P_y, wall rift", "4.9a", rift_y, thermodynamic, contact, thermodynamic_sem)
row(
    "beta P_x, kinematic",
    "4.10a",
    kinematic_x,
    thermodynamic,
    contact,
    thermodynamic_sem,
)
row(
    "beta P_y, kinematic",
    "4.10a",
    kinematic_y,
    thermodynamic,
    contact,
    thermodynamic_sem,
)
row(
    "beta P, contact density (MD, Eq. 4.3)",
    "4.8",
    contact_pressure(md),
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
for faces in ("x", "y"):
    finite, limit = rate_pressures(md, faces)
    row(
        f"wall-hit rate n_{faces} per unit wall length and time",
        "4.9b",
        wall_hit_rate(md, faces),
        math.nan,
        "",
    )
    row(
        f"beta P_{faces}, wall-hit rate, finite N",
        "4.9c = beta x 4.10c",
        finite,
        thermodynamic,
        contact,
        thermodynamic_sem,
    )
    row(
        f"beta P_{faces}, wall-hit rate, N -> inf",
        "4.9d = beta x 4.10d (corrected)",
        limit,
        thermodynamic,
        contact,
        thermodynamic_sem,
    )
factor = theory.rate_pressure_factors(n, radius)["finite_over_limit"]
row(
    "Gamma(N+1/2)/(Gamma(N) sqrt N), finite N over limit",
    "4.9c / 4.9d",
    [factor, factor],
    math.nan,
    "exact",
)
table = pd.DataFrame(rows)
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".5g")
