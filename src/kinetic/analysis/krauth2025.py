"""Pressure of hard disks in a box with walls from the krauth2025 runs (§4.4.3).

Per independent realization (an MD run, a sampler's run or chain), from the datasets of
``kinetic.event_disks`` and ``kinetic.samplers.sample_disks``:

- ``wall_pressures``: βP by the wall rift, Eq. (4.9a), (1/(2 L τ)) Σ 2/|v⊥| over the hits
  of the chosen walls of total length 2L, and by the kinematic estimator, Eq. (4.10a)
  times β = 2N/R² (m = 1), (β/(2 L τ)) Σ 2|v⊥|;
- ``rate_pressures``: βP from the rate of wall hits alone, n̂ (4.9b), times the finite-N
  flux average 2⟨1/|v⊥|⟩ (4.9c) or its N → ∞ limit (4.9d), both with R of the realization;
- ``contact_pressure``: the thermodynamic βP_y = contact density, the projected density
  η(y) at the wall (extrapolated from the first bins, ``theory.krauth2025.wall_value``)
  over the wall length L_x.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pandas as pd
import xarray as xr

from kinetic.analysis import checks as check
from kinetic.analysis.checks import Check
from kinetic.analysis.statistics import mean_and_sem, ratio_and_sem
from kinetic.theory import krauth2025 as theory
from kinetic.theory.krauth2025 import rate_pressure_factors, wall_value

__all__ = [
    "FACES",
    "checks",
    "contact_pressure",
    "pair_collisions_per_disk",
    "parting_summary",
    "parting_table",
    "pin_contact_density",
    "pins_table",
    "pressure_table",
    "rate_pressures",
    "wall_hit_rate",
    "wall_pressures",
]

#: polynomial terms and bins of the pin density's extrapolation to a post: near a post the
#: density is a steep polynomial of degree N - 1, and 5 terms over 8 bins of 0.1 leave a
#: bias of -0.0016 of 3.0 for 15 pins on L = 20 (exact bin averages), half an error bar
PIN_CONTACT_TERMS, PIN_CONTACT_BINS = 5, 8

#: faces of ``wall_statistics``: the x walls (length L_y each), the y walls (L_x each)
FACES = {"x": [0, 1], "y": [2, 3], "all": [0, 1, 2, 3]}


def wall_pressures(md: xr.Dataset, faces: str) -> tuple[np.ndarray, np.ndarray]:
    """(wall rift, kinematic) βP per realization from the hits on ``faces`` ('x', 'y' or
    'all': in a square box P_x = P_y, so all four walls estimate the same pressure)."""
    box_x, box_y = float(md.attrs["box_x"]), float(md.attrs["box_y"])
    wall_length = {"x": 2 * box_y, "y": 2 * box_x, "all": 2 * (box_x + box_y)}[faces]
    hits = md["wall_statistics"].values[:, FACES[faces], :].sum(axis=1)
    norm = 2 / (wall_length * float(md.attrs["duration"]))
    beta = 2 * int(md.attrs["n_disks"]) / md["radius_squared"].values
    return hits[:, 2] * norm, beta * hits[:, 1] * norm


def wall_hit_rate(md: xr.Dataset, faces: str) -> np.ndarray:
    """n̂ of Eq. (4.9b) per realization: hits on ``faces`` per unit wall length and time."""
    box_x, box_y = float(md.attrs["box_x"]), float(md.attrs["box_y"])
    wall_length = {"x": 2 * box_y, "y": 2 * box_x, "all": 2 * (box_x + box_y)}[faces]
    hits = md["wall_statistics"].values[:, FACES[faces], 0].sum(axis=1)
    return hits / (wall_length * float(md.attrs["duration"]))


def rate_pressures(md: xr.Dataset, faces: str) -> tuple[np.ndarray, np.ndarray]:
    """(finite N, N → ∞) βP per realization from the wall-hit rate: Eqs. (4.9c), (4.9d)."""
    n = int(md.attrs["n_disks"])
    rate = wall_hit_rate(md, faces)
    radii = np.sqrt(md["radius_squared"].values)
    factors = [rate_pressure_factors(n, radius) for radius in radii]
    finite = np.array([f["finite"] for f in factors]) * rate
    limit = np.array([f["limit"] for f in factors]) * rate
    return finite, limit


def contact_pressure(data: xr.Dataset) -> np.ndarray:
    """βP = η(σ)/L_x per realization (MD: its Eq. 4.3 density; a sampler: its counts),
    the contact density the mean of the two y walls' (equal by symmetry: a √2 smaller
    error than one wall's)."""
    edges = data["bin_edges"].values
    if "density_trajectory" in data:
        densities = data["density_trajectory"].values
    else:
        width = float(edges[1] - edges[0])
        densities = data["counts"].values / (int(data.attrs["samples"]) * width)
    from_top = edges[-1] - edges[::-1]  # distances from the upper wall, increasing
    contact = [
        0.5 * (wall_value(edges, row) + wall_value(from_top, row[::-1])) for row in densities
    ]
    return np.array(contact) / float(data.attrs["box_x"])


def pressure_table(md: xr.Dataset, direct: xr.Dataset) -> pd.DataFrame:
    """§4.4.3 in numbers, one row per quantity: βP of the four disks by the wall-rift
    (Eq. 4.9a) and kinematic (Eq. 4.10a, times β) estimators on the x and y walls and by the
    contact density of the MD's Eq. (4.3) density, against the thermodynamic βP (the contact
    density of direct-disks ``direct``); the averages of Eqs. (4.13a/b) over wall collisions
    and (4.14a/b) over pair collisions against their finite-N values ((4.14a) corrected, the
    printed value listed); the wall-hit rate n̂ (4.9b) and βP from it times the finite-N
    flux average (4.9c) and times its N → ∞ limit (4.9d), which differ by
    Γ(N+1/2)/(Γ(N)√N) (0.969 at N = 4).

    Columns: quantity, equation, value, sem (mean and standard error across the
    realizations of ``md``), reference, reference_sem, reference_source, z = (value −
    reference)/hypot(sem, reference_sem) (NaN without a reference), printed_value, dof
    (the degrees of freedom of z's error: Welch–Satterthwaite of the two, those of ``md``
    against an exact reference)."""
    n = int(md.attrs["n_disks"])
    walls = md["wall_statistics"].values  # (realization, face, [count, sum, sum_inverse])
    pairs = md["pair_statistics"].values
    radius = float(np.sqrt(md["radius_squared"].values).mean())
    thermodynamic = mean_and_sem(contact_pressure(direct))
    contact = ("contact density from direct-disks", *thermodynamic)
    # the densities are of y (contacts at the y walls): βP_y; P_x = P_y in a square box only
    square = math.isclose(float(md.attrs["box_x"]), float(md.attrs["box_y"]))
    contact_x = (
        contact if square else ("none: P_x differs from P_y in a box not square", math.nan, 0.0)
    )
    dofs = (md.sizes["realization"] - 1, direct.sizes["realization"] - 1)
    none = ("", math.nan, 0.0)
    wall_exact = theory.wall_speed_averages(n, radius)
    pair_exact = theory.pair_speed_averages(n, radius)
    rows = []

    def row(quantity, equation, values, reference, printed=math.nan):
        value, sem = mean_and_sem(values)
        source, expected, expected_sem = reference
        rows.append(
            {
                "quantity": quantity,
                "equation": equation,
                "value": value,
                "sem": sem,
                "reference": expected,
                "reference_sem": expected_sem,
                "reference_source": source,
                "z": (
                    (value - expected) / math.hypot(sem, expected_sem)
                    if math.isfinite(expected)
                    else math.nan
                ),
                "printed_value": printed,
                "dof": (
                    check.welch_dof((sem, expected_sem), dofs)
                    if sem > 0 or expected_sem > 0
                    else math.nan
                ),
            }
        )

    rift_x, kinematic_x = wall_pressures(md, "x")
    rift_y, kinematic_y = wall_pressures(md, "y")
    row("beta P_x, wall rift", "4.9a", rift_x, contact_x)
    row("beta P_y, wall rift", "4.9a", rift_y, contact)
    row("beta P_x, kinematic", "4.10a", kinematic_x, contact_x)
    row("beta P_y, kinematic", "4.10a", kinematic_y, contact)
    row("beta P, contact density (MD, Eq. 4.3)", "4.8", contact_pressure(md), contact)
    row(
        "mean of 1/v_perp over wall collisions",
        "4.13a",
        walls[:, :, 2].sum(1) / walls[:, :, 0].sum(1),
        ("Eq. 4.13a", wall_exact["inverse"], 0.0),
    )
    row(
        "mean of v_perp over wall collisions",
        "4.13b",
        walls[:, :, 1].sum(1) / walls[:, :, 0].sum(1),
        ("Eq. 4.13b", wall_exact["mean"], 0.0),
    )
    row(
        "mean of 1/dv_perp over pair collisions",
        "4.14a",
        pairs[:, 2] / pairs[:, 0],
        (
            "Eq. 4.14a corrected (sqrt(pi/2) for the printed sqrt(2 pi))",
            pair_exact["inverse"],
            0.0,
        ),
        printed=pair_exact["inverse_printed"],
    )
    row(
        "mean of dv_perp over pair collisions",
        "4.14b",
        pairs[:, 1] / pairs[:, 0],
        ("Eq. 4.14b", pair_exact["mean"], 0.0),
    )
    for faces, reference in (("x", contact_x), ("y", contact)):
        finite, limit = rate_pressures(md, faces)
        row(
            f"wall-hit rate n_{faces} per unit wall length and time",
            "4.9b",
            wall_hit_rate(md, faces),
            none,
        )
        row(f"beta P_{faces}, wall-hit rate, finite N", "4.9c = beta x 4.10c", finite, reference)
        row(
            f"beta P_{faces}, wall-hit rate, N -> inf",
            "4.9d = beta x 4.10d (corrected)",
            limit,
            reference,
        )
    factor = rate_pressure_factors(n, radius)["finite_over_limit"]
    row(
        "Gamma(N+1/2)/(Gamma(N) sqrt N), finite N over limit",
        "4.9c / 4.9d",
        [factor, factor],
        ("exact", math.nan, 0.0),
    )
    return pd.DataFrame(rows)


def pin_contact_density(edges, density) -> float:
    """Pin density at contact with the posts (both posts averaged) from a histogram of pin
    centres on ``edges`` between them: the wall-rift βP of the washing line, whose exact
    value is N/(L − 2Nσ)."""
    edges, density = np.asarray(edges, dtype=float), np.asarray(density, dtype=float)
    mirrored = edges[-1] - edges[::-1]
    left = wall_value(edges, density, PIN_CONTACT_TERMS, PIN_CONTACT_BINS)
    right = wall_value(mirrored, density[::-1], PIN_CONTACT_TERMS, PIN_CONTACT_BINS)
    return 0.5 * (left + right)


def pair_collisions_per_disk(event_pair, n_disks: int) -> np.ndarray:
    """Pair collisions per disk after each event of one sequence (event_pair: (events, 2),
    second member negative for a wall): each pair collision counts for two disks."""
    pair = np.asarray(event_pair)[:, 1] >= 0
    return 2.0 * np.cumsum(pair) / n_disks


def parting_table(chaos: xr.Dataset) -> list[dict]:
    """Where the collision sequences of float32 and of a one-ulp start part from float64,
    for every start of a ``kinetic.event_disks.chaos`` dataset: the first event whose pair
    differs, and the pair collisions per disk of the float64 sequence before it (NaN when
    the sequences agree over all events: the run was too short to see them part)."""
    n_disks = int(chaos.attrs["n_disks"])
    pairs = chaos["start_event_pair"]
    rows = []
    for start in chaos["start"].values:
        reference = pairs.sel(start=start, precision="float64").values
        per_disk = pair_collisions_per_disk(reference, n_disks)
        for other in ("float32", "float64_ulp"):
            differs = np.flatnonzero(
                (pairs.sel(start=start, precision=other).values != reference).any(axis=1)
            )
            parted = differs.size > 0
            index = int(differs[0]) if parted else -1
            rows.append(
                {
                    "start": int(start),
                    "start_kind": chaos.attrs["start"] if start == 0 else "random",
                    "comparison": f"{other} against float64",
                    "parting_event": index + 1 if parted else math.nan,
                    "pair_collisions_per_disk": (per_disk[index - 1] if index > 0 else 0.0)
                    if parted
                    else math.nan,
                    "events_compared": int(reference.shape[0]),
                }
            )
    return rows


def parting_summary(table: pd.DataFrame) -> list[dict]:
    """One row per comparison of ``parting_table``'s random starts: the mean and standard
    error of the parting event and of the pair collisions per disk before it, with the
    number of starts and of those that parted. A start that did not part within the
    events compared is censored (it would part later), so the mean of those that did is
    biased low: the mean and its error are NaN unless every start parted."""
    rows = []
    random = table[table["start_kind"] == "random"]
    for comparison, group in random.groupby("comparison"):
        parted = int(group["parting_event"].notna().sum())
        row = {"start": -1, "start_kind": "random, mean", "comparison": comparison}
        for key in ("parting_event", "pair_collisions_per_disk"):
            values = group[key].values
            complete = parted == len(group) and values.size > 1
            mean, sem = mean_and_sem(values) if complete else (math.nan, math.nan)
            row[key], row[f"{key}_sem"] = float(mean), float(sem)
        row["events_compared"] = int(group["events_compared"].iloc[0])
        row["starts_parted"] = parted
        row["starts"] = len(group)
        rows.append(row)
    return rows


def checks(pins, pressure, sigmas: float = check.SIGMAS) -> list[Check]:
    """krauth2025's claims checked on the built tables (rule krauth2025_checks): per
    washing-line sample (``pins_table.csv``), the pin density at the posts over the bulk
    and naive-pin's acceptance equal their exact values, and βP from the wall rift,
    corrected by the bias its extrapolation has on the exact bin averages, equals
    N/(L − 2Nσ); for the four disks (``pressure_table.csv``), every estimator of βP and
    the finite-N averages of Eqs. 4.13 and 4.14 equal their references, while the
    N → ∞ forms of Eq. 4.9d are reported beside them (at N = 4 they are not expected to
    hold). Every error comes from realizations, so each band is ``sigmas`` widened to
    Student's t for its degrees of freedom (the pins' realizations, the pressure table's
    ``dof``): the normal band made a build of 16 realizations fail one check in 110 by
    chance instead of one in 370, and krauth2025's failed checks stop the build."""
    found = []
    for row in pins.itertuples():
        line = f"{row.method}-pin, {row.n_pins} pins on L = {row.length:g}"
        band = check.tolerance_factor(sigmas, int(row.realizations) - 1)
        found.append(
            check.agrees(
                f"{line}: pin density at the posts over the bulk equals Eq. (4.7)",
                row.wall_over_bulk,
                row.wall_over_bulk_sem,
                row.wall_over_bulk_exact,
                band,
            )
        )
        if not math.isnan(row.acceptance):
            found.append(
                check.agrees(
                    f"{line}: naive-pin acceptance equals Z_N,L/(L - 2 sigma)^N",
                    row.acceptance,
                    row.acceptance_sem,
                    row.acceptance_exact,
                    band,
                )
            )
        found.append(
            check.agrees(
                f"{line}: beta P from the wall rift (less its extrapolation bias "
                f"{row.beta_p_extrapolation_bias:.2g}) equals N/(L - 2 N sigma)",
                row.beta_p_wall_rift - row.beta_p_extrapolation_bias,
                row.beta_p_wall_rift_sem,
                row.beta_p_exact,
                band,
            )
        )
    for row in pressure.itertuples():
        if math.isnan(row.reference):
            continue
        claim = f"four disks: {row.quantity} (Eq. {row.equation}) equals {row.reference_source}"
        error = math.hypot(row.sem, 0.0 if math.isnan(row.reference_sem) else row.reference_sem)
        if "N -> inf" in row.quantity:
            found.append(check.reported(claim, row.value, error, row.reference))
        else:
            band = sigmas if math.isnan(row.dof) else check.tolerance_factor(sigmas, int(row.dof))
            found.append(check.agrees(claim, row.value, error, row.reference, band))
    return found


def pins_table(lines: Sequence[xr.Dataset], theory_lines: Sequence[xr.Dataset]) -> pd.DataFrame:
    """krauth2025 §4.4.1 in numbers: for each washing-line sample, the pin density in the
    bins at the posts and in the middle fifth of the line, their ratio ("the density
    there is 4 times larger than in the bulk") and naive-pin's acceptance, each with its
    standard error across realizations, beside the exact values (Eqs. 4.6, 4.7 averaged
    over the same bins; ``post_over_centre_exact`` is Eq. 4.7 at the post over its value
    at the centre, the lecture's "4 times"). Acceptance columns are naive-pin's only.

    The 1-D check of the wall-rift pressure (§4.4.3): removing a slab at a wall
    eliminates the configurations with a pin touching it, so βP is the pin density at
    contact, here extrapolated to the post from the first bins of each realization
    (``pin_contact_density``), against the exact βP = N/(L − 2Nσ) of N pins of width 2σ
    between hard walls (columns beta_p_*); beta_p_extrapolation_bias is the same fit
    applied to the exact bin averages minus the exact βP, the part of the difference
    that is the method's, not the sampling's.
    ``realizations`` is the sample's number of realizations (the checks' degrees of
    freedom).

    ``lines`` are the washing-line samples (one dataset per method and length),
    ``theory_lines`` the exact curves of each length (``kinetic.theory.krauth2025``'s
    files)."""
    rows = []
    exact_by_length = {float(ds.attrs["length"]): ds for ds in theory_lines}
    for run in lines:
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
        exact = exact_by_length[length]["density_exact"].values
        naive = run.attrs["method"] == "naive"
        # the pooled ratio: a mean of the realizations' samples/started keeps the ratio
        # bias of one realization, (1 - p)/samples relative
        started = run["started"].values
        acceptance, acceptance_sem = ratio_and_sem(np.full(started.shape, samples), started)
        curve = exact_by_length[length]["density_curve"].values
        at_post = curve[0] / np.interp(
            0.5 * length, exact_by_length[length]["x_curve"].values, curve
        )
        edges = run["bin_edges"].values
        contact_r = np.array([pin_contact_density(edges, row) for row in per_realization])
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
                "acceptance_exact": float(exact_by_length[length]["acceptance_exact"])
                if naive
                else math.nan,
                "cpu_seconds": float(run["cpu_seconds"].sum()),
                "beta_p_wall_rift": contact,
                "beta_p_wall_rift_sem": contact_sem,
                "beta_p_exact": beta_p_exact,
                "beta_p_z": (contact - beta_p_exact) / contact_sem,
                "beta_p_extrapolation_bias": pin_contact_density(edges, exact) - beta_p_exact,
                "realizations": n_realizations,
            }
        )
    return pd.DataFrame(rows)
