# Homogeneous DSMC (kinetic.dsmc): jobs of independent realizations, then one aggregate per
# run. Realization k of a run always uses stream k of the run's seed, so the data do not
# depend on how the realizations are cut into jobs, and a stopped run resumes per job.
import math

# Runs of config visco2008.dsmc (the {run} wildcard takes exactly these config keys).
VISCO2008_DSMC_RUNS = ["free_flight_times", "maxwell_free_paths"]


def visco2008_dsmc_run(run):
    """Config section of one visco2008 DSMC run."""
    return config["visco2008"]["dsmc"][run]


def visco2008_dsmc_jobs(run):
    """Number of jobs (netCDF batches) of one run."""
    settings = visco2008_dsmc_run(run)
    return math.ceil(settings["realizations"] / settings["realizations_per_job"])


def visco2008_dsmc_batches(wildcards):
    """Input function of the aggregate: every batch file of the run."""
    return [
        f"results/visco2008/dsmc/{wildcards.run}/batch{job:04d}.nc"
        for job in range(visco2008_dsmc_jobs(wildcards.run))
    ]


def visco2008_dsmc_job(wildcards):
    """Keyword arguments of kinetic.dsmc.simulate_free_flights for one job."""
    settings = visco2008_dsmc_run(wildcards.run)
    job = int(wildcards.batch)
    if job >= visco2008_dsmc_jobs(wildcards.run):
        raise ValueError(f"run {wildcards.run} has no job {job}")
    first = job * settings["realizations_per_job"]
    return {
        "kernel": settings["kernel"],
        "dimension": settings["dimension"],
        "n_particles": settings["n_particles"],
        "duration": settings["duration"],
        "seed": job_seed(f"visco2008/dsmc/{wildcards.run}"),
        "first_realization": first,
        "n_realizations": min(settings["realizations_per_job"], settings["realizations"] - first),
        "max_flight_time": settings["max_flight_time"],
        "n_time_bins": settings["time_bins"],
        "max_free_path": settings["max_free_path"],
        "n_path_bins": settings["path_bins"],
        "label": f"visco2008 dsmc {wildcards.run} job {job}",
    }


rule simulate_visco2008_dsmc:
    input:
        sources=engine_sources("dsmc"),
        warm=numba_warm("dsmc"),
    output:
        "results/visco2008/dsmc/{run}/batch{batch}.nc",
    log:
        "logs/visco2008/dsmc/{run}/batch{batch}.log",
    benchmark:
        "logs/benchmarks/visco2008/dsmc/{run}/batch{batch}.tsv"
    params:
        job=visco2008_dsmc_job,
    threads: 1
    wildcard_constraints:
        run="|".join(VISCO2008_DSMC_RUNS),
        batch="[0-9]{4}",
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../scripts/dsmc_free_flights.py"


rule aggregate_visco2008_dsmc:
    input:
        visco2008_dsmc_batches,
    output:
        "results/visco2008/dsmc/{run}.nc",
    log:
        "logs/visco2008/dsmc/{run}.log",
    wildcard_constraints:
        run="|".join(VISCO2008_DSMC_RUNS),
    script:
        "../scripts/dsmc_aggregate_free_flights.py"
