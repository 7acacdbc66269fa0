"""Deterministic solution of visco2008 Eq. 28 on a λ grid (rule
visco2008_theory_cloning_reference)."""

from kinetic.theory.visco2008_exact import reference_dataset
from kinetic.workflow_support import start, write_output

log = start(snakemake)
lambdas = list(snakemake.params.lambdas)
dataset = reference_dataset(lambdas, 2, n_nodes=int(snakemake.params.nodes))
write_output(
    snakemake,
    dataset,
    None,
    parameters={"n_nodes": int(snakemake.params.nodes), "points": len(lambdas)},
)
log.info("solved Eq. 28 at %d values of lambda", len(lambdas))
