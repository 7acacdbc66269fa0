# visco2008 theory: the curves of the paper's equations on the config's grids (one netCDF
# per family under <results>/visco2008/theory/) and the deterministic solution of Eq. 28
# drawn beside the cloning data. Figures read these files; they compute no theory.
from kinetic.studies import visco2008_cloning as cloning_plan

VISCO2008_THEORY_FAMILIES = [
    "large_deviations",
    "free_flights",
    "free_paths",
    "closures",
    "finite_time",
]


def visco2008_theory(family):
    """Path of one family of visco2008 theory curves (an input of figure rules)."""
    if family not in VISCO2008_THEORY_FAMILIES:
        raise ValueError(f"unknown visco2008 theory family {family!r}")
    return results_file(f"visco2008/theory/{family}.nc")


def visco2008_theory_grid(wildcards):
    """Keyword arguments of kinetic.theory.tabulate.visco2008_<family> from the config."""
    theory = config["visco2008"]["theory"]
    grids = {
        "large_deviations": {"rate_max": theory["rate_max"], "points": theory["rate_points"]},
        "free_flights": {"time_max": theory["time_max"], "points": theory["time_points"]},
        "free_paths": {"path_max": theory["path_max"], "points": theory["path_points"]},
        "closures": {
            "lambda_min": theory["lambda_min"],
            "lambda_max": theory["lambda_max"],
            "points": theory["lambda_points"],
        },
        # π(n) at the MD's counting windows (Fig. 9): the windows are the MD's, by design
        "finite_time": {
            "windows": config["visco2008"]["md"]["ldf_windows"],
            "rate_max": theory["rate_max"],
        },
    }
    return grids[wildcards.family]


rule visco2008_theory:
    input:
        code=script_code("visco2008_theory"),
    output:
        results_file("visco2008/theory/{family}.nc"),
    log:
        log_file("visco2008/theory/{family}.log"),
    params:
        grid=visco2008_theory_grid,
    wildcard_constraints:
        family="|".join(VISCO2008_THEORY_FAMILIES),
    script:
        "../../scripts/visco2008_theory.py"


def visco2008_cloning_reference_lambdas(wildcards):
    """λ grid of the deterministic solution: a regular grid over the scan plus every
    λ of the scan and of the error study (so exact values are looked up, not interpolated)."""
    return cloning_plan.reference_lambdas(config["visco2008"]["cloning"])


def visco2008_cloning_reference_nodes(wildcards):
    return config["visco2008"]["cloning"]["reference_nodes"]


rule visco2008_theory_cloning_reference:
    input:
        code=script_code("visco2008_theory_cloning_reference"),
    output:
        results_file("visco2008/cloning/reference.nc"),
    log:
        log_file("visco2008/cloning_reference.log"),
    benchmark:
        log_file("benchmarks/visco2008/cloning_reference.tsv")
    params:
        lambdas=visco2008_cloning_reference_lambdas,
        nodes=visco2008_cloning_reference_nodes,
    threads: 1
    script:
        "../../scripts/visco2008_theory_cloning_reference.py"
