# montanero2007 simulations: DSMC of the heat-flux-forced granular gas (kinetic.dsmc).
#
#   <results>/montanero2007/runs/<run>/batchNNNN.nc   one job: realizations of one run
#   <results>/montanero2007/runs/<run>.nc              the run's batches joined (what figures read)
#
# Run names come from kinetic.studies.montanero2007.run_plan(config["montanero2007"]).


rule montanero2007_simulate_dsmc:
    input:
        code=job_code("montanero2007_simulate_dsmc"),
    output:
        results_file("montanero2007/runs/{run}/{batch}.nc"),
    log:
        log_file("montanero2007/runs/{run}/{batch}.log"),
    benchmark:
        log_file("benchmarks/montanero2007/runs/{run}/{batch}.tsv")
    wildcard_constraints:
        run=montanero2007_run_names(),
        batch=r"batch[0-9]{4}",
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
        gpu=planned_gpus,
    params:
        front=job_param("montanero2007_simulate_dsmc", "front"),
        job=job_param("montanero2007_simulate_dsmc", "arguments"),
        parameters=job_param("montanero2007_simulate_dsmc", "parameters"),
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
