"""visco2008's claims checked on the built tables (rule visco2008_checks).

``checks`` reads Table I (``table1.csv``: the MD cumulants, their 1/t extrapolation, the
closures' rows and the document's printed rows), the cloning scan (``cloning.csv``) and
the deterministic solution of Eq. 28 on the scan's λ values (``cloning/reference.nc``):

1. the document's MD rows of Table I: our k2 and k3 at the density whose rows they match
   (``paper_row_density``) equal the printed values;
2. the collision count is not Poissonian, and the first-Sonine closure describes it:
   k2(t → ∞) at the lowest density equals the Sonine closure's k2 and exceeds the
   Gaussian closure's;
3. Maxwell molecules: μ(λ) = e^{−λ} − 1 exactly, at every λ and population of the scan;
4. hard disks: μ, T and a2 of the populations extrapolated to 1/N_c → 0 equal the
   solution of Eq. 28, wherever the quadrature converged (λ = 0, exact by construction,
   aside).
"""

from __future__ import annotations

import math

import numpy as np

from kinetic.analysis import checks as check
from kinetic.analysis.checks import Check

__all__ = ["checks"]


def checks(table1, cloning, reference, sigmas: float = check.SIGMAS) -> list[Check]:
    """The checks above; ``table1`` and ``cloning`` are the DataFrames of the tables,
    ``reference`` the dataset of Eq. 28 (variables mu, temperature, a2 over lam)."""
    found = []
    md = table1[(table1["kind"] == "md") & (table1["paper_row_density"] == 1)]
    for row in md.itertuples():
        for order in (2, 3):
            printed = getattr(row, f"paper_k{order}")
            if math.isnan(printed):
                continue
            found.append(
                check.agrees(
                    f"Table I, MD row t = {row.t:g}: k{order} equals the printed "
                    f"{printed:g} (rho sigma^2 = {row.rho:g})",
                    getattr(row, f"k{order}"),
                    getattr(row, f"k{order}_err"),
                    printed,
                    sigmas,
                )
            )
    closures = table1[table1["kind"] == "theory"].set_index("source")
    extrapolated = table1[table1["kind"] == "extrapolated"]
    if len(extrapolated):
        row = extrapolated.loc[extrapolated["rho"].idxmin()]
        where = f"rho sigma^2 = {row['rho']:g}"
        found.append(
            check.agrees(
                f"k2(t -> inf) equals the first-Sonine closure ({where})",
                row["k2"],
                row["k2_err"],
                closures.loc["Sonine", "k2"],
                sigmas,
            )
        )
        found.append(
            check.exceeds(
                f"k2(t -> inf) exceeds the Gaussian closure: not Gaussian ({where})",
                row["k2"],
                row["k2_err"],
                closures.loc["Gaussian", "k2"],
                sigmas,
            )
        )
    for row in cloning[cloning["kernel"] == "maxwell"].itertuples():
        if row.mu_err == 0:  # lambda = 0: mu = 0 by construction
            continue
        population = "1/N_c -> 0" if math.isnan(row.n_c) else f"N_c = {row.n_c:g}"
        found.append(
            check.agrees(
                f"Maxwell molecules: mu = exp(-lambda) - 1 at lambda = {row.lam:g}, {population}",
                row.mu,
                row.mu_err,
                math.expm1(-row.lam),
                sigmas,
            )
        )
    lams = np.asarray(reference["lam"].values, dtype=float)
    disks = cloning[(cloning["kernel"] == "hard_disks") & cloning["n_c"].isna()]
    for row in disks.itertuples():
        (matches,) = np.nonzero(np.isclose(lams, row.lam, rtol=0.0, atol=1e-9))
        if row.mu_err == 0 or not matches.size:
            continue
        for name, variable in (("mu", "mu"), ("T", "temperature"), ("a2", "a2")):
            exact = float(reference[variable].values[matches[0]])
            if not math.isfinite(exact):
                continue
            found.append(
                check.agrees(
                    f"hard disks, 1/N_c -> 0: {name} equals Eq. (28) at lambda = {row.lam:g}",
                    getattr(row, name),
                    getattr(row, f"{name}_err"),
                    exact,
                    sigmas,
                )
            )
    return found
