# visco2008 simulations: molecular dynamics (kinetic.edmd, §IV.B), homogeneous DSMC
# (kinetic.dsmc, Figs 1 and 12) and the cloning Monte Carlo (kinetic.cloning, §IV.A).
# Every run is cut into jobs of independent realizations (kinetic.batches: one
# <results>/visco2008/<engine>/<run>/batchNNNN.nc per job); realization k of a run always
# uses stream k of the run's seed, so the data do not depend on the cut and a stopped run
# resumes job by job. One aggregate per run joins its jobs.


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
        data=results_file("visco2008/md/{run}.nc"),
        cumulants=results_file("visco2008/md/{run}_cumulants.nc"),
    log:
        log_file("visco2008/md/{run}_aggregate.log"),
    wildcard_constraints:
        run=visco2008_md_runs(),
    params:
        table_windows=visco2008_md_table_windows,
        extrapolation_windows=visco2008_md_extrapolation_windows,
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
    params:
        front=job_param("visco2008_simulate_cloning", "front"),
        job=job_param("visco2008_simulate_cloning", "arguments"),
        parameters=job_param("visco2008_simulate_cloning", "parameters"),
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
