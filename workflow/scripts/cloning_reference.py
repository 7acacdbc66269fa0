"""Deterministic solution of visco2008 Eq. 28 on a λ grid (rule cloning_reference)."""

from kinetic import io
from kinetic.theory.visco2008_exact import reference_dataset
from kinetic.workflow_support import start

log = start(snakemake)
lambdas = list(snakemake.params.lambdas)
dataset = reference_dataset(lambdas, 2, n_nodes=int(snakemake.params.nodes))
dataset = io.stamp(
    dataset,
    parameters={"n_nodes": int(snakemake.params.nodes), "points": len(lambdas)},
    seed=None,
    config=snakemake.config,
)
io.write_dataset(dataset, snakemake.output[0])
log.info("solved Eq. 28 at %d values of lambda", len(lambdas))
