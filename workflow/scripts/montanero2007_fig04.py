"""montanero2007 Fig. 4: Sonine coefficients b'_1, b'_2, b'_3 against alpha (Eq. 3.10).

Top: the three coefficients at the protocol's field (open) and extrapolated to
eps* -> 0 (filled). Bottom: b'_2 and b'_3 at weak dissipation (alpha >= ZOOM_FROM), where
both are small, on their own scale; the caption quotes them at alpha = 0.9.
"""

import numpy as np

from kinetic import plotting
from kinetic.analysis import montanero2007 as analysis
from kinetic.analysis.montanero2007 import load_runs
from kinetic.theory import montanero2007 as theory
from kinetic.workflow_support import start, write_caption

log = start(snakemake)
rows = analysis.rows_with_field_bias(
    load_runs(snakemake.input.runs).values(), load_runs(snakemake.input.partners).values()
)
alpha = np.array([row["alpha"] for row in rows])
field = rows[0]["field_low"]


def column(key):
    return np.array([row[key] for row in rows])


ZOOM_FROM = 0.7
zoom = alpha >= ZOOM_FROM - 1e-9
fig, (top, bottom) = plotting.figure(nrows=2, figsize=(4.5, 5.0))
for k, marker, color in zip(range(1, 4), "os^", ("C0", "C1", "C2"), strict=True):
    key = f"b{k}_full"
    everything = np.ones_like(zoom)
    panels = ((top, everything), (bottom, zoom)) if k > 1 else ((top, everything),)
    for ax, shown in panels:
        plotting.errorbar(
            ax,
            alpha[shown],
            column(key)[shown],
            column(f"{key}_err")[shown],
            marker=marker,
            color=color,
            label=rf"$b'_{k}$, $\varepsilon^* = {field:g}$",
        )
        plotting.errorbar(
            ax,
            alpha[shown] + 0.008,
            column(f"{key}_extrapolated")[shown],
            column(f"{key}_extrapolated_err")[shown],
            marker=marker,
            color=color,
            mfc=color,
            label=rf"$b'_{k}$, $\varepsilon^* \to 0$",
        )
        ax.plot(alpha[shown], column(key)[shown], "-", lw=0.5, color=color)
grid = np.linspace(alpha.min(), 1.0, 201)
top.plot(
    grid,
    theory.sonine_b1_from_kappa_prime_ratio(theory.kappa_prime_ratio(grid)),
    **(plotting.METHOD_STYLE["theory"] | {"color": "black", "linestyle": "--"}),
    lw=0.8,
    label="$b'_1$, first Sonine",
)
for ax in (top, bottom):
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_ylabel(r"$b'_k$")
top.set_xlabel(r"$\alpha$")
bottom.set_xlabel(r"$\alpha$ (weak dissipation)")
plotting.figure_legend(fig, ncols=3)
plotting.save(fig, snakemake.output.pdf)

b2, b2_err = column("b2_full_extrapolated"), column("b2_full_extrapolated_err")
b3, b3_err = column("b3_full_extrapolated"), column("b3_full_extrapolated_err")
ratio, ratio_err = np.array([analysis.extrapolated_b3_over_b2(row) for row in rows]).T
at = int(np.argmin(abs(alpha - 0.9)))
strongest = int(np.argmin(alpha))
write_caption(
    snakemake.input.template,
    snakemake.output.caption,
    field=field,
    field_high=rows[0]["field_high"],
    zoom_from=ZOOM_FROM,
    alpha=alpha[at],
    b2=column("b2_full")[at],
    b2_err=column("b2_full_err")[at],
    b3=column("b3_full")[at],
    b3_err=column("b3_full_err")[at],
    b2_limit=b2[at],
    b2_limit_err=b2_err[at],
    b3_limit=b3[at],
    b3_limit_err=b3_err[at],
    z2=b2[at] / b2_err[at],
    z3=b3[at] / b3_err[at],
    alpha_strong=alpha[strongest],
    ratio_strong=ratio[strongest],
    ratio_strong_err=ratio_err[strongest],
    b3_max_z_bias=np.max(np.abs(column("b3_full_bias") / column("b3_full_bias_err"))),
)
for row, r, e in zip(rows, ratio, ratio_err, strict=True):
    log.info(
        "alpha = %.2f: "
        + ", ".join(f"b'_{k} = %.4f +- %.4f (eps* -> 0: %.4f +- %.4f)" for k in (1, 2, 3))
        + "; b'_3/b'_2 (eps* -> 0) = %.3f +- %.3f",
        row["alpha"],
        *(
            row[f"b{k}_full{s}"]
            for k in (1, 2, 3)
            for s in ("", "_err", "_extrapolated", "_extrapolated_err")
        ),
        r,
        e,
    )
