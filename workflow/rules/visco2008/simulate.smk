# visco2008 simulations: molecular dynamics (kinetic.edmd, §IV.B), homogeneous DSMC
# (kinetic.dsmc, Figs 1 and 12) and the cloning Monte Carlo (kinetic.cloning, §IV.A).
# Every run is cut into jobs of independent realizations (kinetic.batches: one
# <results>/visco2008/<engine>/<run>/batchNNNN.nc per job); realization k of a run always
# uses stream k of the run's seed, so the data do not depend on the cut and a stopped run
# resumes job by job. One aggregate per run joins its jobs.
import math
import re

from kinetic import batches
from kinetic.studies import visco2008 as visco2008_study
from kinetic.studies import visco2008_cloning as cloning_plan

BATCH = r"batch[0-9]{4}"
"""Wildcard constraint of a batch file's stem (kinetic.batches.batch_name)."""


# ---------------------------------------------------------------- molecular dynamics
def visco2008_md():
    """The config section visco2008.md (validated and filled with defaults)."""
    return config["visco2008"]["md"]


def visco2008_md_jobs():
    """kinetic.batches plan of one MD run (every run has the same)."""
    md = visco2008_md()
    return batches.plan(
        realizations=md["realizations"], realizations_per_job=md["realizations_per_job"]
    )


def visco2008_md_data(run):
    """Aggregated observers of one MD run (all realizations)."""
    return results_file(f"visco2008/md/{run}.nc")


def visco2008_md_cumulants(run):
    """Scaled cumulants <N^p>_c/t with standard errors of one run (Table I input)."""
    return results_file(f"visco2008/md/{run}_cumulants.nc")


def visco2008_md_batch_files(wildcards):
    """Input function: every batch file of the run named by the wildcard."""
    return [
        results_file(f"visco2008/md/{wildcards.run}/{batches.batch_name(job.index)}.nc")
        for job in visco2008_md_jobs()
    ]


def visco2008_md_table_windows(wildcards):
    return visco2008_md()["table_windows"]


def visco2008_md_extrapolation_windows(wildcards):
    return visco2008_md()["extrapolation_windows"]


def visco2008_md_runs():
    """Wildcard constraint: the run names of the config, nothing else."""
    return "|".join(re.escape(run) for run in visco2008_md()["densities"])


rule visco2008_simulate_md:
    input:
        code=job_code("visco2008_simulate_md"),
    output:
        results_file("visco2008/md/{run}/{batch}.nc"),
    log:
        log_file("visco2008/md/{run}/{batch}.log"),
    benchmark:
        log_file("benchmarks/visco2008/md/{run}/{batch}.tsv")
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    threads: 1
    wildcard_constraints:
        run=visco2008_md_runs(),
        batch=BATCH,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/simulate.py"


rule visco2008_aggregate_md:
    input:
        batches=visco2008_md_batch_files,
        code=script_code("visco2008_aggregate_md"),
    output:
        data=results_file("visco2008/md/{run}.nc"),
        cumulants=results_file("visco2008/md/{run}_cumulants.nc"),
    log:
        log_file("visco2008/md/{run}_aggregate.log"),
    params:
        table_windows=visco2008_md_table_windows,
        extrapolation_windows=visco2008_md_extrapolation_windows,
    wildcard_constraints:
        run=visco2008_md_runs(),
    script:
        "../../scripts/visco2008_aggregate_md.py"


# ---------------------------------------------------------------- homogeneous DSMC
VISCO2008_DSMC_RUNS = ["free_flight_times", "maxwell_free_paths"]
"""Runs of config visco2008.dsmc (the {run} wildcard takes exactly these config keys)."""


def visco2008_dsmc_run(run):
    """Config section of one visco2008 DSMC run."""
    return config["visco2008"]["dsmc"][run]


def visco2008_dsmc_jobs(run):
    """kinetic.batches plan of one DSMC run."""
    settings = visco2008_dsmc_run(run)
    return batches.plan(
        realizations=settings["realizations"],
        realizations_per_job=settings["realizations_per_job"],
    )


def visco2008_dsmc_data(run):
    """Aggregated free-flight densities of one DSMC run."""
    return results_file(f"visco2008/dsmc/{run}.nc")


def visco2008_dsmc_batch_files(wildcards):
    """Input function of the aggregate: every batch file of the run."""
    return [
        results_file(f"visco2008/dsmc/{wildcards.run}/{batches.batch_name(job.index)}.nc")
        for job in visco2008_dsmc_jobs(wildcards.run)
    ]


rule visco2008_simulate_dsmc:
    input:
        code=job_code("visco2008_simulate_dsmc"),
    output:
        results_file("visco2008/dsmc/{run}/{batch}.nc"),
    log:
        log_file("visco2008/dsmc/{run}/{batch}.log"),
    benchmark:
        log_file("benchmarks/visco2008/dsmc/{run}/{batch}.tsv")
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    threads: 1
    wildcard_constraints:
        run="|".join(VISCO2008_DSMC_RUNS),
        batch=BATCH,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/simulate.py"


rule visco2008_aggregate_dsmc:
    input:
        batches=visco2008_dsmc_batch_files,
        code=script_code("visco2008_aggregate_dsmc"),
    output:
        results_file("visco2008/dsmc/{run}.nc"),
    log:
        log_file("visco2008/dsmc/{run}.log"),
    wildcard_constraints:
        run="|".join(VISCO2008_DSMC_RUNS),
    script:
        "../../scripts/visco2008_aggregate_dsmc.py"


# ---------------------------------------------------------------- cloning Monte Carlo
# One job per batch of runs of a (kernel, λ, N_c) point; paths name points by tokens built
# from the config (lam+1.000, N1000), which the helpers look up in the config, never parse.
def visco2008_cloning():
    """The config section visco2008.cloning."""
    return config["visco2008"]["cloning"]


def visco2008_cloning_batch_files(study):
    """Every batch file of one study ('scan' or 'error_vs_time')."""
    return [
        results_file(f"visco2008/cloning/{study}/{kernel}/{point}/{size}/{batches.batch_name(batch)}.nc")
        for kernel, point, size, batch in cloning_plan.batch_keys(visco2008_cloning(), study)
    ]


def visco2008_cloning_scan_batches(wildcards):
    return visco2008_cloning_batch_files("scan")


def visco2008_cloning_error_batches(wildcards):
    return visco2008_cloning_batch_files("error_vs_time")


rule visco2008_simulate_cloning:
    input:
        # the engine and the collision rate it scales time by (kinetic.cloning.rates)
        code=job_code("visco2008_simulate_cloning"),
    output:
        results_file("visco2008/cloning/{study}/{kernel}/{point}/{size}/{batch}.nc"),
    log:
        log_file("visco2008/cloning/{study}/{kernel}/{point}/{size}/{batch}.log"),
    benchmark:
        log_file("benchmarks/visco2008/cloning/{study}/{kernel}/{point}/{size}/{batch}.tsv")
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    threads: 1
    wildcard_constraints:
        study="scan|error_vs_time",
        kernel="|".join(cloning_plan.KERNEL_SETTINGS),
        point=r"lam[+-][0-9]+\.[0-9]{3}",
        size=r"N[0-9]+",
        batch=BATCH,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/simulate.py"


rule visco2008_aggregate_cloning:
    input:
        batches=visco2008_cloning_scan_batches,
        code=script_code("visco2008_aggregate_cloning"),
    output:
        csv=results_file("visco2008/cloning.csv"),
        md=results_file("visco2008/cloning.md"),
        nc=results_file("visco2008/cloning.nc"),
    log:
        log_file("visco2008/cloning_aggregate.log"),
    script:
        "../../scripts/visco2008_aggregate_cloning.py"


rule visco2008_aggregate_cloning_error:
    input:
        batches=visco2008_cloning_error_batches,
        reference=results_file("visco2008/cloning/reference.nc"),
        code=script_code("visco2008_aggregate_cloning_error"),
    output:
        csv=results_file("visco2008/cloning_error_vs_time.csv"),
        md=results_file("visco2008/cloning_error_vs_time.md"),
        nc=results_file("visco2008/cloning/error_vs_time.nc"),
    log:
        log_file("visco2008/cloning_error_vs_time_aggregate.log"),
    script:
        "../../scripts/visco2008_aggregate_cloning_error.py"
