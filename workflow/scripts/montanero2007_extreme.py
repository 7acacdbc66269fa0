"""montanero2007 extreme cases: fields up to eps* = 0.2 and strong dissipation.

Left: kappa'/kappa0 against eps*^2 with the fit kappa0 (1 - C eps*^2) over every field
but the largest (kappa' is even in eps); the departure of the largest field from it is
shown, not hidden.
Right: the O(eps*^2) signatures, <c_x^2> - 1/2 and b'_1 (Eq. 3.10) - b'_1 (Eq. 3.12).
Table extreme.csv: every run with its deviation from the linear-response value, and the
strong-dissipation runs against the Sonine approximations and Eq. (2.16).
"""

import numpy as np
import pandas as pd

from kinetic import io, plotting
from kinetic.analysis import montanero2007 as analysis
from kinetic.analysis.montanero2007 import load_runs
from kinetic.theory import montanero2007 as theory
from kinetic.workflow_support import start

log = start(snakemake)
rows = [analysis.summary_row(ds) for ds in load_runs(snakemake.input.runs).values()]
field_rows = [row for row in rows if row["family"] in ("scan", "extreme")]
by_alpha = {}
for row in field_rows:
    by_alpha.setdefault(row["alpha"], []).append(row)
scan_alphas = {row["alpha"] for row in rows if row["family"] == "scan"}

fig, (left, right) = plotting.figure(1, 2, figsize=(6.8, 2.6))


def measured_and_theory(row, alpha):
    """The columns every table row carries: the run's diagnostics and the theory values."""
    return {
        "anisotropy": row["anisotropy"],
        "anisotropy_err": row["anisotropy_err"],
        "b1_route_difference": row["b1_route_difference"],
        "b1_route_difference_err": row["b1_route_difference_err"],
        "a2": row["a2"],
        "a2_err": row["a2_err"],
        "kappa_ratio_sonine": float(theory.kappa_prime_ratio(alpha)),
        "kappa_ratio_modified_sonine": float(
            theory.kappa_prime_ratio(alpha, approximation="modified")
        ),
        "a2_eq_2_16": float(theory.hcs_a2(alpha)),
    }


table = []
for alpha in sorted(scan_alphas, reverse=True):
    chosen = sorted(by_alpha[alpha], key=lambda row: row["reduced_field"])
    fields = np.array([row["reduced_field"] for row in chosen])
    kappa = np.array([row["kappa_ratio"] for row in chosen])
    error = np.array([row["kappa_ratio_err"] for row in chosen])
    # fit every field but the largest (at least the two smallest)
    fit_max = np.sort(fields)[max(1, len(fields) - 2)]
    k0, k0_err, c, c_err = analysis.linear_response_fit(fields, kappa, error, fit_max)
    container = plotting.errorbar(left, fields**2, kappa, error, label=rf"$\alpha = {alpha:g}$")
    color = container[0].get_color()
    grid = np.linspace(0.0, fields.max() ** 2 * 1.05, 50)
    left.plot(grid, k0 * (1 - c * grid), "--", color=color, lw=0.7)
    # the eps* -> 0 limit with the fit's standard error
    left.errorbar([0.0], [k0], yerr=[k0_err], fmt="*", color=color, elinewidth=0.7)
    anisotropy = np.array([row["anisotropy"] for row in chosen])
    anisotropy_err = np.array([row["anisotropy_err"] for row in chosen])
    plotting.errorbar(
        right,
        fields,
        anisotropy,
        anisotropy_err,
        marker="o",
        color=color,
        label=rf"$\langle c_x^2\rangle - 1/2$, $\alpha={alpha:g}$",
    )
    difference = np.array([row["b1_route_difference"] for row in chosen])
    difference_err = np.array([row["b1_route_difference_err"] for row in chosen])
    plotting.errorbar(
        right,
        fields,
        difference,
        difference_err,
        marker="s",
        color=color,
        label=rf"$b'_1$(3.10) $-$ $b'_1$(3.12), $\alpha={alpha:g}$",
    )
    log.info(
        "alpha = %g: linear response kappa'/kappa0 = %.4f +- %.4f, C = %.3g +- %.3g",
        alpha,
        k0,
        k0_err,
        c,
        c_err,
    )
    departures = analysis.departure_from_linear_response(fields, kappa, error, fit_max)
    for row, deviation, deviation_err in zip(
        chosen, departures["departure"], departures["departure_err"], strict=True
    ):
        table.append(
            {
                "case": "field",
                "alpha": alpha,
                "reduced_field": row["reduced_field"],
                "kappa_ratio": row["kappa_ratio"],
                "kappa_ratio_err": row["kappa_ratio_err"],
                "linear_response_kappa_ratio": k0,
                "linear_response_kappa_ratio_err": k0_err,
                "relative_departure": deviation,
                "relative_departure_err": deviation_err,
                **measured_and_theory(row, alpha),
            }
        )
for row in rows:
    if row["family"] == "extreme" and row["alpha"] not in scan_alphas:
        alpha = row["alpha"]
        table.append(
            {
                "case": "strong dissipation",
                "alpha": alpha,
                "reduced_field": row["reduced_field"],
                "kappa_ratio": row["kappa_ratio"],
                "kappa_ratio_err": row["kappa_ratio_err"],
                **measured_and_theory(row, alpha),
            }
        )
left.set_xlabel(r"$\varepsilon^{*2}$")
left.set_ylabel(r"$\kappa'/\kappa_0$")
plotting.figure_legend(
    fig,
    ncols=3,
    title=r"dashed: $\kappa_0(1 - C\varepsilon^{*2})$, all but the largest field",
)
right.axhline(0.0, color="0.6", lw=0.5)
right.set_xlabel(r"$\varepsilon^*$")
right.set_ylabel("nonlinear signatures")
fig.subplots_adjust(wspace=0.4)
plotting.save(fig, snakemake.output.pdf)
frame = pd.DataFrame(table)
io.write_table(frame, snakemake.output.csv, snakemake.output.md, float_format=".4g")
log.info("extreme cases:\n%s", frame.to_string(index=False))
