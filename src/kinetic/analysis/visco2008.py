"""visco2008's Table I (``table1``, ``table1_caption_numbers``) and its claims checked on
the built tables (``checks``, rule visco2008_checks).

``table1`` builds the rows of Table I from the MD runs' scaled cumulants and the closures:
the MD rows per density and window, their 1/t extrapolation, the Poisson, Gaussian and
Sonine rows and the Boltzmann equation's own (``Eq. (28)``), the document's printed row
beside ours with z-scores, the density whose rows the document's MD rows match best (the
smallest sum of squared z-scores), and the
MD rows carried to ρ → 0 by a line through the two lowest densities (``dilute``: at
paper.yaml's statistics the ρσ² = 10⁻³ rows sit 3-4 errors below the printed ones, the
line's value within one).

The checks:

``checks`` reads Table I (``table1.csv``: the MD cumulants, their 1/t extrapolation, the
closures' rows and the document's printed rows), the cloning scan (``cloning.csv``) and
the deterministic solution of Eq. 28 on the scan's λ values (``cloning/reference.nc``):

1. the document's MD rows of Table I: our k2 and k3 on the line through the two lowest
   densities at ρ → 0 (``dilute``; the document does not say which density its rows
   come from) equal the printed values, and the rows of the density they match best
   (``paper_row_density``) are reported beside them; with one density, that density's
   rows are judged;
2. the collision count is not Poissonian, and the first-Sonine closure describes it:
   k2(t → ∞) at the lowest density equals the Sonine closure's k2 and exceeds the
   Gaussian closure's (reported beside them: k2(t → ∞) against Eq. (28)'s own k2,
   1.14090, 0.0031 above Sonine's; the document makes no claim about it);
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

__all__ = ["TABLE1_COLUMNS", "checks", "md_cumulants", "table1", "table1_caption_numbers"]

EXACT_SOURCE = "Eq. (28)"
"""Table I's theory row of the Boltzmann equation's own cumulants (Eq. (28) solved)."""


def window_source(window: float) -> str:
    """The source of Table I's row of Eq. (28) at a finite window t (beside the MD row)."""
    return f"{EXACT_SOURCE}, t = {float(window):g}"


TABLE1_COLUMNS = ["source", "rho", "t", "k1", "k2", "k3", "k1_err", "k2_err", "k3_err"]
"""The first columns of table1.csv (the original contract: keep the names and order)."""


def _z(value, error, reference):
    return (value - reference) / error if error > 0 else np.nan


def _row(source, rho, t, values, errors, kind, paper, closures):
    record = dict(zip(TABLE1_COLUMNS, [source, rho, t, *values, *errors], strict=True))
    record["kind"] = kind
    for p in range(3):
        record[f"paper_k{p + 1}"] = paper[p] if paper is not None else np.nan
    for p in (1, 2):
        record[f"z_k{p + 1}"] = _z(values[p], errors[p], paper[p]) if paper is not None else np.nan
    # the closures' values are t -> ∞ limits: a row at a finite window is not compared
    # (its z against them was -60 to -89 at t = 10)
    comparable = kind != "theory" and not math.isfinite(t)
    for name in ("Gaussian", "Sonine"):
        for p in (1, 2):
            record[f"z_{name.lower()}_k{p + 1}"] = (
                _z(values[p], errors[p], closures[name][p]) if comparable else np.nan
            )
    record["k1_exact"] = 1
    return record


def md_cumulants(runs, table_windows, extrapolation_windows):
    """Table I's input from joined MD runs: per run, ⟨N^p⟩_c/t and its standard error at
    ``table_windows`` and the t -> ∞ values of the 1/t fit over ``extrapolation_windows``
    (``kinetic.analysis.collision_statistics.cumulant_dataset``)."""
    from kinetic.analysis.collision_statistics import cumulant_dataset

    return [
        cumulant_dataset(run, table_windows, extrapolation_windows=extrapolation_windows)
        for run in runs
    ]


def table1(md_runs, closures, extrapolation_windows):
    """Table I as a DataFrame, the columns of table1.csv: source,rho,t,k1,k2,k3,k1_err,
    k2_err,k3_err (the original contract), then kind (md | extrapolated | dilute | theory),
    paper_k1..3 (the document's printed row; empty where it has none), z_k2, z_k3 (ours
    minus printed, over our standard error), z_gaussian_k2..z_sonine_k3 (ours against the
    Gaussian and Sonine closures), k1_exact (1: k1 = 1 holds by construction, not as a
    measurement), paper_row_density (1 on the MD rows at the density whose rows the
    document's MD rows match best), note. MD rows carry the density, the window length t
    (mean free times) and standard errors; extrapolated rows (t = inf) the 1/t fit over
    several windows; dilute rows (rho = 0) the line in ρ through the MD rows of the two
    lowest densities at each t, at ρ = 0 (errors propagated from both; two densities
    cannot test the line itself); theory rows leave rho, t and the errors empty, but for
    Eq. (28)'s at the MD windows (``closures``' ``cumulant_exact_window``, when present),
    which carry their t.

    ``md_runs``: the MD cumulant datasets (``scaled_cumulant`` and its ``_sem`` over window
    and order, the ``density`` attribute, optionally ``extrapolated_cumulant``);
    ``closures``: the theory dataset with ``cumulant_poisson``, ``cumulant_gaussian``,
    ``cumulant_sonine`` and ``cumulant_exact``."""
    import pandas as pd

    from kinetic.theory.visco2008 import TABLE_I_DOCUMENT

    theory = {
        "Poisson": closures["cumulant_poisson"].values,
        "Gaussian": closures["cumulant_gaussian"].values,
        "Sonine": closures["cumulant_sonine"].values,
        EXACT_SOURCE: closures["cumulant_exact"].values,
    }
    rows = []
    for md in md_runs:
        density = float(md.attrs["density"])
        for window in md["window"].values:
            values = md["scaled_cumulant"].sel(window=window).sel(order=[1, 2, 3]).values
            errors = md["scaled_cumulant_sem"].sel(window=window).sel(order=[1, 2, 3]).values
            paper = TABLE_I_DOCUMENT.get(f"MD t={window:g}")
            rows.append(_row("MD", density, float(window), values, errors, "md", paper, theory))
        if "extrapolated_cumulant" in md:
            rows.append(
                _row(
                    "MD",
                    density,
                    np.inf,
                    md["extrapolated_cumulant"].values,
                    md["extrapolated_cumulant_sem"].values,
                    "extrapolated",
                    None,
                    theory,
                )
            )
    rows += _dilute_rows([row for row in rows if row["kind"] == "md"], theory)
    for source, values in theory.items():
        rows.append(
            _row(
                source,
                np.nan,
                np.nan,
                values,
                [np.nan] * 3,
                "theory",
                TABLE_I_DOCUMENT.get(source),  # the document prints no Eq. (28) row
                theory,
            )
        )
    if "cumulant_exact_window" in closures:  # Eq. (28) at the MD rows' windows
        for window in closures["window"].values:
            values = closures["cumulant_exact_window"].sel(window=window).values
            rows.append(
                _row(
                    window_source(window),
                    np.nan,
                    float(window),
                    values,
                    [np.nan] * 3,
                    "theory",
                    None,
                    theory,
                )
            )
    table = pd.DataFrame(rows)
    # which density the document's MD rows come from: the smallest sum of squared z-scores
    # (the rows the caption quotes first and the checks report beside the rho -> 0 line
    # they judge; with one density, the rows they judge). The choice is never close: in
    # the default build of dd25787 the sums are 23 at 1e-3 and 2265 at 1e-2 (z_k2 = -42.7
    # at t = 10)
    md_rows = table[(table["kind"] == "md") & table["paper_k2"].notna()]
    chi2 = (md_rows["z_k2"] ** 2 + md_rows["z_k3"] ** 2).groupby(md_rows["rho"]).sum()
    paper_density = float(chi2.idxmin())
    table["paper_row_density"] = ((table["kind"] == "md") & (table["rho"] == paper_density)).astype(
        int
    )
    notes = {
        "md": "k1 = 1 by construction (t in measured mean free times), not a measurement",
        "extrapolated": "fit k(t) = k(inf) + c/t per realization over t = {}".format(
            ", ".join(f"{w:g}" for w in extrapolation_windows)
        ),
        "dilute": "line in rho through the two lowest densities' rows, at rho = 0",
        "theory": "k1 = 1 by construction (omega = 1)",
    }
    table["note"] = table["kind"].map(notes)
    table.loc[table["paper_row_density"] == 1, "note"] += "; density of the document's MD rows"
    return table


def _dilute_rows(md_rows, theory) -> list[dict]:
    """The MD rows at ρ = 0 by a line through the two lowest densities, one per t: k(0) =
    k(a) - a (k(b) - k(a))/(b - a); the two densities' runs are independent."""
    from kinetic.theory.visco2008 import TABLE_I_DOCUMENT

    densities = sorted({row["rho"] for row in md_rows})
    if len(densities) < 2:
        return []
    low, high = densities[:2]
    lever = low / (high - low)
    found = []
    for window in sorted({row["t"] for row in md_rows}):
        a, b = (
            next(r for r in md_rows if r["rho"] == rho and r["t"] == window) for rho in (low, high)
        )
        values = [a[f"k{p}"] - lever * (b[f"k{p}"] - a[f"k{p}"]) for p in (1, 2, 3)]
        errors = [
            math.hypot((1 + lever) * a[f"k{p}_err"], lever * b[f"k{p}_err"]) for p in (1, 2, 3)
        ]
        paper = TABLE_I_DOCUMENT.get(f"MD t={window:g}")
        found.append(_row("MD", 0.0, window, values, errors, "dilute", paper, theory))
    return found


def table1_caption_numbers(table, extrapolation_windows) -> dict:
    """Every number the caption of Table I quotes, from the table: per density ("doc", the
    density of the document's MD rows, and "other") and window (10, 50, inf) the cumulants,
    their errors and z-scores, and the difference of k2 between the densities."""
    paper_density = float(table.loc[table["paper_row_density"] == 1, "rho"].iloc[0])
    numbers = {}
    densities = sorted(
        table.loc[table["kind"] == "md", "rho"].unique(), key=lambda rho: rho != paper_density
    )
    for density, tag in zip(densities, ("doc", "other"), strict=False):
        numbers[f"rho_{tag}"] = density
        for kind_row in table[(table["rho"] == density)].itertuples():
            key = "inf" if kind_row.kind == "extrapolated" else f"{kind_row.t:g}"
            for p in (2, 3):
                for column in (
                    f"k{p}",
                    f"k{p}_err",
                    f"z_k{p}",
                    f"z_gaussian_k{p}",
                    f"z_sonine_k{p}",
                ):
                    numbers[f"{column}_{tag}_{key}"] = getattr(kind_row, column)
    for key in ("10", "50", "inf"):
        difference = numbers[f"k2_other_{key}"] - numbers[f"k2_doc_{key}"]
        error = np.hypot(numbers[f"k2_err_other_{key}"], numbers[f"k2_err_doc_{key}"])
        numbers[f"dk2_{key}"], numbers[f"dk2_err_{key}"] = difference, error
        numbers[f"dz_{key}"] = difference / error
    for row in table[table["kind"] == "dilute"].itertuples():
        for column in ("k2", "k2_err", "z_k2", "k3", "k3_err", "z_k3"):
            numbers[f"{column}_dilute_{row.t:g}"] = getattr(row, column)
    numbers["windows"] = ", ".join(f"{w:g}" for w in extrapolation_windows)
    return numbers


def _printed_md_rows(rows, band: float | None) -> list[Check]:
    """Table I's MD ``rows`` against the document's printed k2 and k3: agreement within
    ``band`` standard errors, or reported beside them (``band`` None)."""
    found = []
    for row in rows.itertuples():
        if row.kind == "dilute":
            where = "rho sigma^2 -> 0, the line through the two lowest densities"
        else:
            where = f"rho sigma^2 = {row.rho:g}"
        for order in (2, 3):
            printed = getattr(row, f"paper_k{order}")
            if math.isnan(printed):
                continue
            value, error = getattr(row, f"k{order}"), getattr(row, f"k{order}_err")
            if band is None:
                claim = f"k{order} against the printed {printed:g}, simulated density ({where})"
                made = check.reported(
                    f"Table I, MD row t = {row.t:g}: {claim}", value, error, printed
                )
            else:
                claim = f"k{order} equals the printed {printed:g} ({where})"
                made = check.agrees(
                    f"Table I, MD row t = {row.t:g}: {claim}", value, error, printed, band
                )
            found.append(made)
    return found


def checks(
    table1,
    cloning,
    reference,
    sigmas: float = check.SIGMAS,
    md_dof: int | None = None,
    cloning_dof: int | None = None,
) -> list[Check]:
    """The checks above; ``table1`` and ``cloning`` are the DataFrames of the tables,
    ``reference`` the dataset of Eq. 28 (variables mu, temperature, a2 over lam).
    ``md_dof`` and ``cloning_dof``: the degrees of freedom of the MD's and the cloning's
    errors (their realizations less one), which widen ``sigmas`` to Student's t for the
    Table I and the cloning checks (None: the normal band). A 1/N_c -> 0 row combines
    several populations, so its errors have more; the points' own is the conservative
    band."""
    md_band = sigmas if md_dof is None else check.tolerance_factor(sigmas, md_dof)
    cloning_band = sigmas if cloning_dof is None else check.tolerance_factor(sigmas, cloning_dof)
    found = []
    md = table1[(table1["kind"] == "md") & (table1["paper_row_density"] == 1)]
    dilute = table1[table1["kind"] == "dilute"]
    # The printed MD rows are judged at rho -> 0 where the table has that line: at
    # rho sigma^2 = 1e-3, the simulated density they match best, our k2 lies 0.0008-0.0010
    # below them at both windows, a density effect (1e-2 lies lower again, on a line
    # through both), which is 4 errors of the default build (z = -4.27 against a band of
    # 4.29 at dd25787) and 3-4 of paper.yaml's: a verdict there would pass or fail with
    # the seed. The line's values lie within one error of the printed ones; the rows at
    # 1e-3 are reported beside them.
    if len(dilute):
        found += _printed_md_rows(dilute, md_band) + _printed_md_rows(md, None)
    else:
        found += _printed_md_rows(md, md_band)
    closures = table1[table1["kind"] == "theory"].set_index("source")
    for row in md.itertuples():  # MD against the Boltzmann equation at the same window
        source = window_source(row.t)
        if source in closures.index:
            found.append(
                check.reported(
                    f"Table I, MD row t = {row.t:g}: k2 against the Boltzmann equation's "
                    f"at that window, Eq. (28) (rho sigma^2 = {row.rho:g})",
                    row.k2,
                    row.k2_err,
                    closures.loc[source, "k2"],
                )
            )
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
                md_band,
            )
        )
        exact = closures.loc[EXACT_SOURCE, "k2"]
        below = exact - closures.loc["Sonine", "k2"]
        found.append(  # the document compares with Sonine only: reported, no verdict
            check.reported(
                f"k2(t -> inf) against the Boltzmann equation's own k2, Eq. (28) solved "
                f"({where}; the Sonine closure is {below:.4f} below it)",
                row["k2"],
                row["k2_err"],
                exact,
            )
        )
        found.append(
            check.exceeds(
                f"k2(t -> inf) exceeds the Gaussian closure: not Gaussian ({where})",
                row["k2"],
                row["k2_err"],
                closures.loc["Gaussian", "k2"],
                md_band,
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
                cloning_band,
            )
        )
    lams = np.asarray(reference["lam"].values, dtype=float)
    disks = cloning[(cloning["kernel"] == "hard_disks") & cloning["n_c"].isna()]
    for row in disks.itertuples():
        (matches,) = np.nonzero(np.isclose(lams, row.lam, rtol=0.0, atol=1e-9))
        if not matches.size:
            continue
        for name, variable in (("mu", "mu"), ("T", "temperature"), ("a2", "a2")):
            exact = float(reference[variable].values[matches[0]])
            if not math.isfinite(exact) or getattr(row, f"{name}_err") == 0:
                continue  # μ(0) = 0 exactly (no error): T and a2 at λ = 0 are checked
            found.append(
                check.agrees(
                    f"hard disks, 1/N_c -> 0: {name} equals Eq. (28) at lambda = {row.lam:g}",
                    getattr(row, name),
                    getattr(row, f"{name}_err"),
                    exact,
                    cloning_band,
                )
            )
    # a scanned λ without a 1/N_c -> 0 row (fewer than two populations above a collapsed
    # one) is said, not passed over: a seed that collapses one more population would
    # otherwise lose checks without a word
    points = cloning[(cloning["kernel"] == "hard_disks") & cloning["n_c"].notna()]
    for lam in sorted(set(points["lam"]) - set(disks["lam"])):
        (matches,) = np.nonzero(np.isclose(lams, lam, rtol=0.0, atol=1e-9))
        for name, variable in (("mu", "mu"), ("T", "temperature"), ("a2", "a2")):
            exact = float(reference[variable].values[matches[0]]) if matches.size else math.nan
            if math.isfinite(exact):
                found.append(
                    check.reported(
                        f"hard disks, 1/N_c -> 0: {name} at lambda = {lam:g} not judged (fewer "
                        "than two populations above a collapsed one to extrapolate)",
                        math.nan,
                        math.nan,
                        exact,
                    )
                )
    return found
