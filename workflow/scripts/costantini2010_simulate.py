"""One job of a costantini2010 run: realizations of the cooling gas -> netCDF."""

import importlib

from kinetic.workflow_support import start, write_output

log = start(snakemake)
job = dict(snakemake.params.job)
package = {"dsmc": "kinetic.dsmc", "md": "kinetic.edmd"}[snakemake.wildcards.engine]
dataset = importlib.import_module(package).simulate_cooling_modes(**job)
write_output(snakemake, dataset, job["seed"])
log.info(
    "wrote %s: %d collisions in %.1f CPU s",
    snakemake.output[0],
    int(dataset.collisions.sum()),
    float(dataset.cpu_seconds.sum()),
)
