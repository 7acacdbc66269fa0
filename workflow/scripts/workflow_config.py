"""The config of the build, defaults filled in, for the report (rule workflow_config)."""

import yaml

from kinetic import io
from kinetic.workflow_support import start

log = start(snakemake)
text = yaml.safe_dump(dict(snakemake.params.config), sort_keys=False)
io.write_text(snakemake.output[0], text)
log.info("wrote %s", snakemake.output[0])
