"""One batch of realizations of one montanero2007 run (rule montanero2007_simulate_dsmc)."""

from kinetic import io
from kinetic.studies.montanero2007 import simulate_batch
from kinetic.workflow_support import start_simulation, write_output

log = start_simulation(snakemake)
run = dict(snakemake.params.run)
batch = dict(snakemake.params.batch)
name = snakemake.wildcards.run
dataset = simulate_batch(
    run,
    seed=int(snakemake.params.seed),
    first=batch["first"],
    count=batch["count"],
    label=f"montanero2007 {name} {snakemake.wildcards.batch}",
)
write_output(
    snakemake,
    dataset,
    int(snakemake.params.seed),
    parameters={
        **io.parameters_of(dataset),
        "run": name,
        "family": run["family"],
        "setting": run.get("setting", ""),
    },
)
log.info("wrote %s (%.1f CPU s)", snakemake.output[0], float(dataset["cpu_seconds"].sum()))
