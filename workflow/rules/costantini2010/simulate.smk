# costantini2010: runs of the cooling gas in the stationary representation, by inhomogeneous
# DSMC (kinetic.dsmc.simulate_cooling_modes) and MD (kinetic.edmd.simulate_cooling_modes).
# Every run is cut into jobs of realizations (kinetic.batches); one aggregate per run joins
# them and computes C(tau), the tail fit, nu*, nu_bar*, zeta* and T(tau)
# (kinetic.analysis.costantini2010). Run names are the keys of
# kinetic.studies.costantini2010.runs(config): wildcards are looked up, never parsed.
from kinetic.studies import costantini2010 as costantini2010_study

COSTANTINI2010_PACKAGES = {"dsmc": "dsmc", "md": "edmd"}
"""Package of each engine wildcard."""

def costantini2010_runs():
    """Every run of the study by name."""
    return costantini2010_study.runs(config["costantini2010"])


def costantini2010_run(wildcards):
    """The run named by the {run} wildcard, checked against the {engine} wildcard."""
    run = costantini2010_runs().get(wildcards.run)
    if run is None or run.engine != wildcards.engine:
        raise WorkflowError(f"the config asks for no costantini2010 {wildcards.engine} run {wildcards.run!r}")
    return run


def costantini2010_batch_files(wildcards):
    """Input of the aggregate: every job's file of the run."""
    run = costantini2010_run(wildcards)
    return [
        results_file(costantini2010_study.batch_file(run, job))
        for job in costantini2010_study.batch_plan(config["costantini2010"])
    ]


def costantini2010_analysis(wildcards):
    """Settings of kinetic.analysis.costantini2010.analyse_run, in engine time units where
    the analysis wants them (the transient)."""
    study = config["costantini2010"]
    return {
        "transient": study["transient"] * costantini2010_study.mean_free_time(study["density"]),
        "max_lag": study["max_lag"],
        "blocks_per_realization": study["blocks_per_realization"],
        "fit_start": study["fit_start"],
        "fit_stop": study["fit_stop"],
    }


rule costantini2010_simulate_dsmc:
    input:
        code=job_code("costantini2010_simulate_dsmc"),
    output:
        results_file("costantini2010/{engine}/{run}/batch{batch}.nc"),
    log:
        log_file("costantini2010/{engine}/{run}/batch{batch}.log"),
    benchmark:
        log_file("benchmarks/costantini2010/{engine}/{run}/batch{batch}.tsv")
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    wildcard_constraints:
        engine="dsmc",
        run="[^/]+",
        batch="[0-9]{4}",
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
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    wildcard_constraints:
        engine="md",
        run="[^/]+",
        batch="[0-9]{4}",
    script:
        "../../scripts/simulate.py"


rule costantini2010_aggregate_run:
    input:
        batches=costantini2010_batch_files,
        code=script_code("costantini2010_aggregate"),
    output:
        results_file("costantini2010/{engine}/{run}.nc"),
    log:
        log_file("costantini2010/{engine}/{run}.log"),
    params:
        analysis=costantini2010_analysis,
    wildcard_constraints:
        engine="dsmc|md",
        run="[^/]+",
    script:
        "../../scripts/costantini2010_aggregate.py"
