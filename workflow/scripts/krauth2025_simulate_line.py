"""One washing-line sample of krauth2025 §4.4.1 (rule krauth2025_simulate_line): the pin
density by naive-pin or direct-pin, with standard errors across
realizations (the exact
density beside it comes from rule krauth2025_theory_line)."""

from kinetic.samplers import sample_line
from kinetic.workflow_support import run_job

log, job, data = run_job(snakemake, sample_line)
log.info(
    "%d configurations (%d started)",
    job["samples"] * job["realizations"],
    int(data.started.sum()),
)
