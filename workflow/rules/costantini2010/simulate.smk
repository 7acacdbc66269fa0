# costantini2010: runs of the cooling gas in the stationary representation, by inhomogeneous
# DSMC (kinetic.dsmc.simulate_cooling_modes) and MD (kinetic.edmd.simulate_cooling_modes).
# Every run is cut into jobs of realizations (kinetic.batches); rule
# costantini2010_correlations (figures.smk) reads a run's jobs and computes C(tau), the tail
# fit, nu*, nu_bar*, zeta* and T(tau) (kinetic.analysis.costantini2010). Run names are the keys of
# kinetic.studies.costantini2010.runs(config): wildcards are looked up, never parsed.


rule costantini2010_simulate_dsmc:
    input:
        code=job_code("costantini2010_simulate_dsmc"),
    output:
        results_file("costantini2010/{engine}/{run}/batch{batch}.nc"),
    log:
        log_file("costantini2010/{engine}/{run}/batch{batch}.log"),
    benchmark:
        log_file("benchmarks/costantini2010/{engine}/{run}/batch{batch}.tsv")
    wildcard_constraints:
        engine="dsmc",
        run="[^/]+",
        batch="[0-9]{4}",
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("costantini2010_simulate_dsmc", "front"),
        job=job_param("costantini2010_simulate_dsmc", "arguments"),
        parameters=job_param("costantini2010_simulate_dsmc", "parameters"),
    script:
        "../../scripts/simulate.py"


rule costantini2010_simulate_md:
    input:
        code=job_code("costantini2010_simulate_md"),
    output:
        results_file("costantini2010/{engine}/{run}/batch{batch}.nc"),
    log:
        log_file("costantini2010/{engine}/{run}/batch{batch}.log"),
    benchmark:
        log_file("benchmarks/costantini2010/{engine}/{run}/batch{batch}.tsv")
    wildcard_constraints:
        engine="md",
        run="[^/]+",
        batch="[0-9]{4}",
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("costantini2010_simulate_md", "front"),
        job=job_param("costantini2010_simulate_md", "arguments"),
        parameters=job_param("costantini2010_simulate_md", "parameters"),
    script:
        "../../scripts/simulate.py"
