"""Planned cost, requested resources and measured benchmark of every simulation job, for
the report (rule workflow_jobs)."""

import csv

from kinetic import plan
from kinetic.workflow_support import start

log = start(snakemake)
rows = plan.job_table(".", plan.plan_jobs(snakemake.config))
with open(snakemake.output[0], "w", newline="") as handle:
    writer = csv.DictWriter(handle, fieldnames=plan.JOB_TABLE_COLUMNS)
    writer.writeheader()
    writer.writerows(rows)
log.info("wrote %s: %d jobs", snakemake.output[0], len(rows))
