"""One job of a costantini2010 run: realizations of the cooling gas -> netCDF."""

from kinetic.dsmc import simulate_cooling_modes as dsmc_cooling_modes
from kinetic.edmd import simulate_cooling_modes as md_cooling_modes
from kinetic.workflow_support import start, write_output

ENGINES = {"dsmc": dsmc_cooling_modes, "md": md_cooling_modes}

log = start(snakemake)
job = dict(snakemake.params.job)
dataset = ENGINES[snakemake.wildcards.engine](**job)
write_output(snakemake, dataset, job["seed"])
log.info(
    "wrote %s: %d collisions in %.1f CPU s",
    snakemake.output[0],
    int(dataset.collisions.sum()),
    float(dataset.cpu_seconds.sum()),
)
