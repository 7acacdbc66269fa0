"""montanero2007 checks of the paper's claims and of the engine; fails loudly (after logging
the table) if one fails.

Statistical checks pass within `sigmas` standard errors, widened to Student's t for the
number of realizations behind each error (analysis.tolerance_factor).
1. kappa'/kappa0 at alpha = 1 agrees with 1.025218 (Ref. [37]);
2. the two routes to b'_k (Eqs. 3.10 and 3.12) agree (paired differences);
3. linear response: the larger field of field_check gives the same kappa' as the scan;
4. the HCS a2 (zero field) agrees with Eq. (2.16) for alpha >= a2_alpha_min within
   a2_relative_tolerance |a2| + a2_absolute_floor + sigmas errors;
5. the thermostat holds momentum and energy: |<c_x>|, |<c^2> - 3/2| <= thermostat_tolerance.
Informative rows (passed empty): the HCS cooling rate against Eq. (2.14).
"""

import numpy as np
import pandas as pd

from kinetic import io
from kinetic.analysis import montanero2007 as analysis
from kinetic.studies.montanero2007 import load_runs
from kinetic.theory import montanero2007 as theory
from kinetic.workflow_support import start

log = start(snakemake)
tolerances = snakemake.params.section["checks"]
sigmas = tolerances["sigmas"]
rows = [analysis.summary_row(ds) for ds in load_runs(snakemake.input.runs).values()]
checks = []


def check(name, row, quantity, measured, error, expected, tolerance, passed=None):
    checks.append(
        {
            "check": name,
            "run": row["run"],
            "alpha": row["alpha"],
            "quantity": quantity,
            "measured": measured,
            "error": error,
            "expected": expected,
            "relative_deviation": (measured - expected) / expected if expected else float("nan"),
            "tolerance": tolerance,
            "passed": "" if passed is None else ("yes" if passed else "NO"),
        }
    )


scan = {row["alpha"]: row for row in rows if row["family"] == "scan"}
if 1.0 in scan:
    row = scan[1.0]
    tolerance = analysis.tolerance_factor(sigmas, row["realizations"] - 1) * row["kappa_ratio_err"]
    deviation = abs(row["kappa_ratio"] - theory.KAPPA_ELASTIC_HIGHER_SONINE)
    check(
        "elastic kappa",
        row,
        "kappa'/kappa0",
        row["kappa_ratio"],
        row["kappa_ratio_err"],
        theory.KAPPA_ELASTIC_HIGHER_SONINE,
        tolerance,
        deviation <= tolerance,
    )
for row in scan.values():
    for k in (1, 2, 3):
        difference = row[f"b{k}_route_difference"]
        error = row[f"b{k}_route_difference_err"]
        tolerance = analysis.tolerance_factor(sigmas, row["realizations"] - 1) * error
        check(
            "two routes",
            row,
            f"b'_{k} (3.10) - b'_{k} (3.12)",
            difference,
            error,
            0.0,
            tolerance,
            abs(difference) <= tolerance,
        )
for row in rows:
    if row["family"] == "field":
        base = scan[row["alpha"]]
        error = float(np.hypot(row["kappa_ratio_err"], base["kappa_ratio_err"]))
        difference = row["kappa_ratio"] - base["kappa_ratio"]
        dof = min(row["realizations"], base["realizations"]) - 1
        tolerance = analysis.tolerance_factor(sigmas, dof) * error
        check(
            "linear response",
            row,
            f"kappa'/kappa0(eps*={row['reduced_field']:g}) - (eps*={base['reduced_field']:g})",
            difference,
            error,
            0.0,
            tolerance,
            abs(difference) <= tolerance,
        )
for row in rows:
    if row["family"] != "hcs":
        continue
    expected = float(theory.hcs_a2(row["alpha"]))
    tolerance = (
        tolerances["a2_relative_tolerance"] * abs(expected)
        + tolerances["a2_absolute_floor"]
        + analysis.tolerance_factor(sigmas, row["realizations"] - 1) * row["a2_err"]
    )
    passed = abs(row["a2"] - expected) <= tolerance
    check(
        "HCS a2 (Eq. 2.16)",
        row,
        "a2",
        row["a2"],
        row["a2_err"],
        expected,
        tolerance,
        passed if row["alpha"] >= tolerances["a2_alpha_min"] else None,
    )
    zeta = float(theory.reduced_cooling_rate(row["alpha"], a2=row["a2"]) * theory.nu0_tau())
    check(
        "HCS cooling rate (Eq. 2.14)",
        row,
        "zeta tau",
        row["thermostat_rate"],
        row["thermostat_rate_err"],
        zeta,
        float("nan"),
    )
for row in rows:
    limit = tolerances["thermostat_tolerance"]
    check(
        "thermostat momentum",
        row,
        "max |<c_x>|",
        row["max_abs_cx"],
        0.0,
        0.0,
        limit,
        row["max_abs_cx"] <= limit,
    )
    check(
        "thermostat energy",
        row,
        "max |<c^2> - 3/2|",
        row["max_abs_energy_error"],
        0.0,
        0.0,
        limit,
        row["max_abs_energy_error"] <= limit,
    )

table = pd.DataFrame(checks)
log.info("checks:\n%s", table.to_string(index=False))
failed = table[table["passed"] == "NO"]
if len(failed):
    raise RuntimeError(f"{len(failed)} montanero2007 check(s) failed:\n{failed.to_string()}")
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".6g")
