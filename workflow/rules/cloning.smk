# Cloning Monte Carlo of visco2008 §IV.A: one job per batch of runs of a (kernel, λ, N_c)
# point, then aggregates: results/visco2008/cloning.csv|md|nc (every point plus the
# 1/N_c -> 0 extrapolation), the deterministic solution of Eq. 28 drawn beside the data,
# and the error-against-CPU-time study. Paths name points by tokens built from the config
# (lam+1.000, N1000), which the helpers look up in the config, never parse.
from kinetic.cloning import plan as cloning_plan

CLONING = config["visco2008"]["cloning"]


def cloning_batch_path(study, kernel, point, size, batch):
    """netCDF of one batch job."""
    return f"results/visco2008/cloning/{study}/{kernel}/{point}/{size}/batch{batch}.nc"


def cloning_batches(study):
    """Every batch file of one study ('scan' or 'error_vs_time')."""
    return [cloning_batch_path(study, *key) for key in cloning_plan.batch_keys(CLONING, study)]


def cloning_scan_batches(wildcards):
    return cloning_batches("scan")


def cloning_error_batches(wildcards):
    return cloning_batches("error_vs_time")


def cloning_run_parameters(wildcards):
    """Keyword arguments of kinetic.cloning.simulate for the batch named by the wildcards."""
    key = cloning_plan.point_seed_key(
        wildcards.study, wildcards.kernel, wildcards.point, wildcards.size
    )
    return cloning_plan.run_parameters(
        CLONING,
        wildcards.study,
        wildcards.kernel,
        wildcards.point,
        wildcards.size,
        int(wildcards.batch),
        job_seed(key),
    )


def cloning_reference_lambdas(wildcards):
    """λ grid of the deterministic solution: a regular grid over the scan plus every
    λ of the scan and of the error study (so exact values are looked up, not interpolated)."""
    return cloning_plan.reference_lambdas(CLONING)


# what a batch's numbers depend on (aggregation and plotting code are not part of it)
CLONING_SIMULATION_SOURCES = package_files(
    "cloning/__init__",
    "cloning/kernels",
    "cloning/simulate",
    "cloning/estimators",
    "cloning/rates",
    "theory/visco2008",
    "rng",
    "io",
)


wildcard_constraints:
    study="scan|error_vs_time",
    kernel="|".join(cloning_plan.KERNEL_SETTINGS),
    point=r"lam[+-][0-9]+\.[0-9]{3}",
    size=r"N[0-9]+",
    batch=r"[0-9]+",


rule cloning_batch:
    input:
        sources=CLONING_SIMULATION_SOURCES,
        # ancient: the compiled cache must exist, but its age does not rerun batches
        warm=ancient(numba_warm("cloning")),
    output:
        "results/visco2008/cloning/{study}/{kernel}/{point}/{size}/batch{batch}.nc",
    log:
        "logs/visco2008/cloning/{study}/{kernel}/{point}/{size}/batch{batch}.log",
    benchmark:
        "logs/benchmarks/visco2008/cloning/{study}/{kernel}/{point}/{size}/batch{batch}.tsv"
    params:
        run=cloning_run_parameters,
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../scripts/cloning_batch.py"


rule cloning_aggregate:
    input:
        batches=cloning_scan_batches,
        code=package_files("cloning/aggregate"),
    output:
        csv="results/visco2008/cloning.csv",
        md="results/visco2008/cloning.md",
        nc="results/visco2008/cloning.nc",
    log:
        "logs/visco2008/cloning_aggregate.log",
    script:
        "../scripts/cloning_aggregate.py"


rule cloning_reference:
    input:
        package_files("theory/visco2008_exact"),
    output:
        "results/visco2008/cloning/reference.nc",
    log:
        "logs/visco2008/cloning_reference.log",
    benchmark:
        "logs/benchmarks/visco2008/cloning_reference.tsv"
    params:
        lambdas=cloning_reference_lambdas,
        nodes=CLONING["reference_nodes"],
    threads: 1
    script:
        "../scripts/cloning_reference.py"


rule cloning_error_aggregate:
    input:
        batches=cloning_error_batches,
        reference="results/visco2008/cloning/reference.nc",
        code=package_files("cloning/aggregate"),
    output:
        csv="results/visco2008/cloning_error_vs_time.csv",
        md="results/visco2008/cloning_error_vs_time.md",
        nc="results/visco2008/cloning/error_vs_time.nc",
    log:
        "logs/visco2008/cloning_error_aggregate.log",
    script:
        "../scripts/cloning_error_aggregate.py"
