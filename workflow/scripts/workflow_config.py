"""The config of the build, defaults filled in, for the report (rule workflow_config)."""

import yaml

from kinetic.workflow_support import start

log = start(snakemake)
with open(snakemake.output[0], "w") as handle:
    yaml.safe_dump(dict(snakemake.params.config), handle, sort_keys=False)
log.info("wrote %s", snakemake.output[0])
