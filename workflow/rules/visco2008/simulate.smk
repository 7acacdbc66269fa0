# visco2008 simulations: molecular dynamics (kinetic.edmd, §IV.B), homogeneous DSMC
# (kinetic.dsmc, Figs 1 and 12) and the cloning Monte Carlo (kinetic.cloning, §IV.A).
# Every run is cut into jobs of independent realizations (kinetic.batches: one
# <results>/visco2008/<engine>/<run>/batchNNNN.nc per job); realization k of a run always
# uses stream k of the run's seed, so the data do not depend on the cut and a stopped run
# resumes job by job. One aggregate per run joins its jobs and computes nothing else; the
# analyses of the joined runs are in figures.smk.


rule visco2008_simulate_md:
    input:
        code=job_code("visco2008_simulate_md"),
    output:
        results_file("visco2008/md/{run}/{batch}.nc"),
    log:
        log_file("visco2008/md/{run}/{batch}.log"),
    benchmark:
        log_file("benchmarks/visco2008/md/{run}/{batch}.tsv")
    wildcard_constraints:
        run=visco2008_md_runs(),
        batch=BATCH,
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("visco2008_simulate_md", "front"),
        job=job_param("visco2008_simulate_md", "arguments"),
        parameters=job_param("visco2008_simulate_md", "parameters"),
    script:
        "../../scripts/simulate.py"


rule visco2008_aggregate_md:
    input:
        batches=visco2008_md_batch_files,
        code=script_code("visco2008_aggregate_md"),
    output:
        results_file("visco2008/md/{run}.nc"),
    log:
        log_file("visco2008/md/{run}_aggregate.log"),
    wildcard_constraints:
        run=visco2008_md_runs(),
    script:
        "../../scripts/visco2008_aggregate_md.py"


rule visco2008_simulate_dsmc:
    input:
        code=job_code("visco2008_simulate_dsmc"),
    output:
        results_file("visco2008/dsmc/{run}/{batch}.nc"),
    log:
        log_file("visco2008/dsmc/{run}/{batch}.log"),
    benchmark:
        log_file("benchmarks/visco2008/dsmc/{run}/{batch}.tsv")
    wildcard_constraints:
        run="|".join(VISCO2008_DSMC_RUNS),
        batch=BATCH,
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("visco2008_simulate_dsmc", "front"),
        job=job_param("visco2008_simulate_dsmc", "arguments"),
        parameters=job_param("visco2008_simulate_dsmc", "parameters"),
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


rule visco2008_simulate_cloning:
    input:
        # the engine and the collision rate it scales time by (kinetic.cloning.rates)
        code=job_code("visco2008_simulate_cloning"),
    output:
        results_file("visco2008/cloning/{study}/{kernel}/{point}/{size}/{batch}.nc"),
    log:
        log_file("visco2008/cloning/{study}/{kernel}/{point}/{size}/{batch}.log"),
    benchmark:
        log_file(
            "benchmarks/visco2008/cloning/{study}/{kernel}/{point}/{size}/{batch}.tsv"
        )
    wildcard_constraints:
        study="scan|error_vs_time",
        kernel="|".join(cloning_plan.KERNEL_SETTINGS),
        point=r"lam[+-][0-9]+\.[0-9]{3}",
        size=r"N[0-9]+",
        batch=BATCH,
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
        gpu=planned_gpus,
    params:
        front=job_param("visco2008_simulate_cloning", "front"),
        job=job_param("visco2008_simulate_cloning", "arguments"),
        parameters=job_param("visco2008_simulate_cloning", "parameters"),
    script:
        "../../scripts/simulate.py"
