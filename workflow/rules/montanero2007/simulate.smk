# montanero2007 simulations: DSMC of the heat-flux-forced granular gas (kinetic.dsmc).
#
#   <results>/montanero2007/runs/<run>/batchNNNN.nc   one job: realizations of one run
#   <results>/montanero2007/runs/<run>.nc              the run's batches joined (what figures read)
#
# Run names come from kinetic.studies.montanero2007.run_plan(config["montanero2007"]).
import functools

from kinetic import batches
from kinetic.studies.montanero2007 import run_plan


@functools.cache
def montanero2007_runs():
    """{run name: parameters} of the config's plan (the protocol merged with each family's
    overrides), computed once."""
    return run_plan(config["montanero2007"])


def montanero2007_jobs(name):
    """kinetic.batches plan of one run."""
    run = montanero2007_runs()[name]
    return batches.plan(
        realizations=int(run["realizations"]),
        realizations_per_job=int(run["realizations_per_job"]),
    )


def montanero2007_batch_files(name):
    """The batch files of one run (all its realizations)."""
    return [
        results_file(f"montanero2007/runs/{name}/{batches.batch_name(job.index)}.nc")
        for job in montanero2007_jobs(name)
    ]


def montanero2007_run_file(name):
    """One run, its batches joined (rule montanero2007_aggregate_run)."""
    return results_file(f"montanero2007/runs/{name}.nc")


def montanero2007_run_batches(wildcards):
    return montanero2007_batch_files(wildcards.run)


def montanero2007_run_names():
    """Wildcard constraint: the run names of the plan, nothing else."""
    return "|".join(sorted(montanero2007_runs()))


rule montanero2007_simulate_dsmc:
    input:
        code=job_code("montanero2007_simulate_dsmc"),
    output:
        results_file("montanero2007/runs/{run}/{batch}.nc"),
    log:
        log_file("montanero2007/runs/{run}/{batch}.log"),
    benchmark:
        log_file("benchmarks/montanero2007/runs/{run}/{batch}.tsv")
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    threads: 1
    wildcard_constraints:
        run=montanero2007_run_names(),
        batch=r"batch[0-9]{4}",
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/simulate.py"


rule montanero2007_aggregate_run:
    input:
        batches=montanero2007_run_batches,
        code=script_code("montanero2007_aggregate"),
    output:
        results_file("montanero2007/runs/{run}.nc"),
    log:
        log_file("montanero2007/runs/{run}.log"),
    wildcard_constraints:
        run=montanero2007_run_names(),
    script:
        "../../scripts/montanero2007_aggregate.py"
