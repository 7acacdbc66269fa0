"""krauth2025 §4.2.1, equal probability of velocities: event-disks conserve the energy, so
the 2N velocity components live on the sphere Σ v² = R², and a long run visits it
uniformly. The time-weighted density of one component, u = v_a/R, from the four-disk MD
runs (mean and standard error over realizations) against the sphere's marginal
∝ (1 − u²)^(N − 3/2) and the Maxwell Gaussian √(N/π) e^(−N u²) it tends to at large N,
both averaged over the bins; residuals against the sphere; χ²/dof of each curve."""

from kinetic import io, plotting
from kinetic.analysis.checks import sum_of_squares_p_value
from kinetic.analysis.statistics import chi2_per_dof, mean_and_sem
from kinetic.theory import krauth2025 as theory
from kinetic.workflow_support import start, write_caption

log = start(snakemake)
md = io.read_dataset(snakemake.input.md)
n = int(md.attrs["n_disks"])
edges = md["velocity_edges"].values
u = md["u"].values
density, error = mean_and_sem(md["velocity_density"].values, axis=0)
curves = {
    "sphere": plotting.bin_average(lambda x: theory.sphere_velocity_marginal(x, n), edges),
    "maxwell": plotting.bin_average(lambda x: theory.maxwell_velocity_marginal(x, n), edges),
}
chi2 = {}
for name, curve in curves.items():
    chi2[name], dof = chi2_per_dof(density, error, curve)

fig, (top, bottom) = plotting.figure(
    2, 1, sharex=True, figsize=(3.4, 3.6), gridspec_kw={"height_ratios": [2.2, 1]}
)
plotting.method_errorbar(top, "md", u, density, error, label=f"event-disks, N = {n}")
plotting.theory_steps(top, edges, curves["sphere"], label=r"sphere: $(1-u^2)^{N-3/2}$")
plotting.theory_steps(
    top, edges, curves["maxwell"], method="theory_alt", label=r"Maxwell: $e^{-N u^2}$"
)
top.set_ylabel(r"density of $u = v_a/R$")
top.set_ylim(0.0, None)
plotting.residual_panel(bottom, u, density, error, curves["sphere"], label="_nolegend_")
bottom.set_xlabel(r"$u = v_a/R$")
bottom.set_ylabel("MD/sphere − 1")
plotting.figure_legend(fig, ncols=1)
plotting.save(fig, snakemake.output.pdf)
write_caption(
    snakemake.input.template,
    snakemake.output.caption,
    n=n,
    realizations=int(md.sizes["realization"]),
    chi2_sphere=chi2["sphere"],
    chi2_maxwell=chi2["maxwell"],
    dof=dof,
    # the errors come from the realizations: Σ z² of Student's t, not χ²_dof
    p_sphere=sum_of_squares_p_value(chi2["sphere"] * dof, dof, md.sizes["realization"] - 1),
    centre_ratio=float(
        theory.sphere_velocity_marginal(0.0, n) / theory.maxwell_velocity_marginal(0.0, n)
    ),
)
log.info("chi2/dof over %d bins: sphere %.3f, Maxwell %.1f", dof, chi2["sphere"], chi2["maxwell"])
