"""Pins on a ring, krauth2025 Fig. 4.13 (rule krauth2025_simulate_ring): the pair density
from independent Markov chains, with standard errors across chains (the exact density
beside it comes from rule krauth2025_theory_ring)."""

from kinetic.samplers import sample_ring
from kinetic.workflow_support import run_job

log, job, data = run_job(snakemake, sample_ring)
log.info("%d chains, acceptance %.3f", job["realizations"], float(data.acceptance.mean()))
