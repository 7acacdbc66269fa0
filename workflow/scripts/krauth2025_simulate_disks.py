"""direct-disks or markov-disks for krauth2025's equal-probability check (rule
krauth2025_simulate_disks): the projected density of N disks in the box along y."""

from kinetic.samplers import sample_disks
from kinetic.workflow_support import run_job

run_job(snakemake, sample_disks)
