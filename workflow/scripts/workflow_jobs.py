"""Planned cost, requested resources and measured benchmark of every simulation job, for
the report (rule workflow_jobs)."""

import pandas as pd

from kinetic import io, plan
from kinetic.workflow_support import start

log = start(snakemake)
rows = plan.job_table(".", plan.plan_jobs(snakemake.params.config))
table = pd.DataFrame(rows, columns=plan.JOB_TABLE_COLUMNS)
io.write_table(table, snakemake.output[0])
log.info("wrote %s: %d jobs", snakemake.output[0], len(rows))
