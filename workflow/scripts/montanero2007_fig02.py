"""montanero2007 Fig. 2: b'_k(t), k = 1..3, by Eq. (3.10) and by Eq. (3.12)."""

from matplotlib.lines import Line2D

from kinetic import plotting
from kinetic.analysis import montanero2007 as analysis
from kinetic.analysis.montanero2007 import load_runs
from kinetic.workflow_support import start

log = start(snakemake)
runs = list(load_runs(snakemake.input.runs).values())
fig, axes = plotting.figure(
    len(runs), 1, sharex=True, figsize=(3.4, 2.0 * len(runs) + 0.4), squeeze=False
)
colors = ["C0", "C1", "C2"]
for ax, ds in zip(axes[:, 0], runs, strict=True):
    series = analysis.time_series_of(ds)
    steady = analysis.steady_summary_of(ds)
    t = series["time"]
    for k in range(analysis.N_SONINE):
        for route, style in (("full", "-"), ("marginal", "--")):
            value = series[f"b_{route}"][:, k]
            error = series[f"b_{route}_err"][:, k]
            ax.plot(t, value, style, color=colors[k], lw=0.9)
            ax.fill_between(t, value - error, value + error, color=colors[k], alpha=0.15, lw=0)
        steady_value, steady_error = steady["b_full"][k], steady["b_full_err"][k]
        ax.axhline(steady_value, ls=":", color=colors[k], lw=0.8)
        ax.axhspan(
            steady_value - steady_error,
            steady_value + steady_error,
            color=colors[k],
            alpha=0.12,
            lw=0,
        )
        log.info(
            "alpha = %g: b'_%d = %.4f +- %.4f (full), %.4f +- %.4f (marginal)",
            steady["parameters"]["restitution"],
            k + 1,
            steady["b_full"][k],
            steady["b_full_err"][k],
            steady["b_marginal"][k],
            steady["b_marginal_err"][k],
        )
    ax.set_ylabel(r"$b'_k(t)$")
    # above the panel, not on it (inside, a label hid b'_1 and b'_3 at t/tau ~ 50)
    ax.set_title(rf"$\alpha = {steady['parameters']['restitution']:g}$", fontsize=8, pad=2)
handles = [Line2D([], [], color=colors[k], label=f"$b'_{k + 1}$") for k in range(3)]
handles += [
    Line2D([], [], color="0.4", ls="-", label=r"from $\langle c_x L_k^{(3/2)}(c^2)\rangle$"),
    Line2D([], [], color="0.4", ls="--", label=r"from $\langle c_x L_k^{(1/2)}(c_x^2)\rangle$"),
]
plotting.figure_legend(fig, handles=handles)  # just above the panels
axes[-1, 0].set_xlabel(r"$t/\tau$")
axes[-1, 0].set_xlim(0, float(t.max()))
plotting.save(fig, snakemake.output.pdf)
