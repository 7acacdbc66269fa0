"""montanero2007 Fig. 7: beta_1(c_x^2)/b'_1 (Eq. 4.6), the share of b'_1 below |c_x|.

The caption sets the share at c_x^2 = 6 beside the document's 87 % (alpha = 1) and 66 %
(alpha = 0.3): at the protocol's field, extrapolated to eps* -> 0 from the larger-field
partner runs of those two alphas (the share is a ratio of two quantities even in eps*),
and for the truncated Sonine series phi_1 and phi_3 with the measured b'_k.
"""

import numpy as np

from kinetic import plotting
from kinetic.analysis import montanero2007 as analysis
from kinetic.analysis.montanero2007 import load_runs
from kinetic.theory import montanero2007 as theory
from kinetic.theory.montanero2007 import FIG07_QUOTED_SHARES as PAPER
from kinetic.workflow_support import start, write_caption

CX2 = 6.0

log = start(snakemake)


def share_row(ds):
    """Summary row of one run with the share at c_x^2 = 6 and its slope there."""
    summary = analysis.steady_summary_of(ds)
    curves = analysis.distributions_of(ds, summary)
    x, ratio, error = curves["beta_cx2"], curves["beta_ratio"], curves["beta_ratio_err"]
    row = analysis.summary_row(ds, summary)
    row["share"] = float(np.interp(CX2, x, ratio))
    row["share_err"] = float(np.interp(CX2, x, error))
    row["slope"] = float(np.interp(CX2, x, np.gradient(ratio, x)))
    return row, (x, ratio, error)


partners = {}
for ds in load_runs(snakemake.input.partners).values():
    row, _ = share_row(ds)
    partners[row["alpha"]] = row

fig, ax = plotting.figure()
values = {}
for ds in load_runs(snakemake.input.runs).values():
    row, (x, ratio, error) = share_row(ds)
    alpha = row["alpha"]
    line = ax.plot(x, ratio, "-", lw=0.9, label=rf"$\alpha = {alpha:g}$")[0]
    ax.fill_between(x, ratio - error, ratio + error, color=line.get_color(), alpha=0.25, lw=0)
    b = [row[f"b{k}_full"] for k in (1, 2, 3)]
    values[alpha] = {
        "share": 100 * row["share"],
        "share_err": 100 * row["share_err"],
        "sonine3": 100 * theory.beta1_share(CX2, b),
        "slope": 100 * row["slope"],
    }
    log.info(
        "alpha = %g: c_x^2 <= 6 carries %.1f +- %.1f %% of b'_1 at eps* = %g; phi_3 with the "
        "measured b'_k: %.1f %%; slope %.1f %% per unit c_x^2",
        alpha,
        *(values[alpha][key] for key in ("share", "share_err")),
        row["reduced_field"],
        *(values[alpha][key] for key in ("sonine3", "slope")),
    )
    if alpha in partners:  # the caption's alphas: eps* -> 0
        limit = analysis.field_extrapolation(row, partners[alpha], keys=("share",))
        values[alpha]["limit"] = 100 * limit["share_extrapolated"]
        values[alpha]["limit_err"] = 100 * limit["share_extrapolated_err"]
        log.info(
            "alpha = %g: %.1f +- %.1f %% for eps* -> 0",
            alpha,
            values[alpha]["limit"],
            values[alpha]["limit_err"],
        )
ax.plot(
    np.linspace(0, 2 * snakemake.params.cx2_max, 201),
    [theory.beta1_share(v) for v in np.linspace(0, 2 * snakemake.params.cx2_max, 201)],
    **plotting.METHOD_STYLE["theory_alt"],
    lw=0.8,
    label=r"first Sonine $\varphi_1$",
)
ax.axhline(1.0, color="0.6", lw=0.5)
ax.axvline(CX2, color="0.6", lw=0.5, ls=":")
ax.set_xlim(0.0, 2.0 * snakemake.params.cx2_max)
ax.set_xlabel(r"$c_x^2$")
ax.set_ylabel(r"$\beta_1(c_x^2)/b'_1$")
ax.legend(loc="lower right")
plotting.save(fig, snakemake.output.pdf)

numbers = {"field": row["reduced_field"], "sonine1": 100 * theory.beta1_share(CX2)}
for alpha, key in ((1.0, "elastic"), (0.3, "strong")):
    numbers[f"{key}_paper"] = 100 * PAPER[alpha]
    for name, value in values[alpha].items():
        numbers[f"{key}_{name}"] = value
    numbers[f"{key}_z"] = (values[alpha]["limit"] - numbers[f"{key}_paper"]) / values[alpha][
        "limit_err"
    ]
    # a two-digit percentage stands for the interval [paper - 0.5, paper + 0.5)
    gap = abs(values[alpha]["limit"] - numbers[f"{key}_paper"]) - 0.5
    numbers[f"{key}_z_round"] = max(gap, 0.0) / values[alpha]["limit_err"]
    numbers[f"{key}_reach"] = (
        CX2 + (numbers[f"{key}_paper"] - values[alpha]["share"]) / values[alpha]["slope"]
    )
write_caption(snakemake.input.template, snakemake.output.caption, **numbers)
