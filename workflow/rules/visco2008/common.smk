# visco2008: the helpers of its rules (paths, input functions, params), included before
# its rule files, which hold only rules and the targets they register.

import math
import re

from kinetic import batches
from kinetic.studies import visco2008 as visco2008_study
from kinetic.studies import visco2008_cloning as cloning_plan

# ---------------------------------------------------------------- for the theory rules

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
        "large_deviations": {
            "rate_max": theory["rate_max"],
            "points": theory["rate_points"],
        },
        "free_flights": {
            "time_max": theory["time_max"],
            "points": theory["time_points"],
        },
        "free_paths": {"path_max": theory["path_max"], "points": theory["path_points"]},
        # Table I's theory rows, Eq. (28)'s at the MD rows' windows too
        "closures": {
            "lambda_min": theory["lambda_min"],
            "lambda_max": theory["lambda_max"],
            "points": theory["lambda_points"],
            "windows": config["visco2008"]["md"]["table_windows"],
        },
        # π(n) at the MD's counting windows (Fig. 9): the windows are the MD's, by design
        "finite_time": {
            "windows": config["visco2008"]["md"]["ldf_windows"],
            "rate_max": theory["rate_max"],
        },
    }
    return grids[wildcards.family]


def visco2008_cloning_reference_grid(wildcards):
    """Keyword arguments of kinetic.theory.tabulate.visco2008_cloning_reference: a regular
    λ grid over the scan plus every λ of the scan and of the error study (so exact values
    are looked up, not interpolated), and the quadrature's nodes."""
    cloning = config["visco2008"]["cloning"]
    return {
        "lambdas": cloning_plan.reference_lambdas(cloning),
        "n_nodes": int(cloning["reference_nodes"]),
    }


def visco2008_cloning_reference_parameters(wildcards):
    """The provenance stamped on the reference file: the nodes and the number of λ."""
    grid = visco2008_cloning_reference_grid(wildcards)
    return {"n_nodes": grid["n_nodes"], "points": len(grid["lambdas"])}


# ---------------------------------------------------------------- for the simulation rules


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
        results_file(
            f"visco2008/dsmc/{wildcards.run}/{batches.batch_name(job.index)}.nc"
        )
        for job in visco2008_dsmc_jobs(wildcards.run)
    ]


# ---------------------------------------------------------------- cloning Monte Carlo
# One job per batch of runs of a (kernel, λ, N_c) point; paths name points by tokens built
# from the config (lam+1.000, N1000), which the helpers look up in the config, never parse.
def visco2008_cloning():
    """The config section visco2008.cloning."""
    return config["visco2008"]["cloning"]


def visco2008_cloning_batch_files(study):
    """Every batch file of one study ('scan' or 'error_vs_time')."""
    return [
        results_file(
            f"visco2008/cloning/{study}/{kernel}/{point}/{size}/{batches.batch_name(batch)}.nc"
        )
        for kernel, point, size, batch in cloning_plan.batch_keys(
            visco2008_cloning(), study, config["backend"]
        )
    ]


def visco2008_cloning_single_sizes():
    """Wildcard constraint of the per-point cloning rule: the populations whose points run
    one job per batch (every one on the cpu; on cuda those above the resident kernel's).
    """
    sizes = cloning_plan.single_sizes(visco2008_cloning(), config["backend"])
    return "|".join(sizes) if sizes else "(?!)"


def visco2008_cloning_groups():
    """(study, kernel, λ tokens, N tokens) of every grouped-points rule (cuda only)."""
    return cloning_plan.groups(visco2008_cloning(), config["backend"])


def visco2008_cloning_scan_batches(wildcards):
    return visco2008_cloning_batch_files("scan")


def visco2008_cloning_kernel_batches(wildcards):
    """The scan's batch files of one kernel (wildcards.kernel): a figure of one kernel
    waits for its own points only (Fig. 4 for 4 of the ci config's 16 cloning jobs)."""
    return [
        path
        for path in visco2008_cloning_batch_files("scan")
        if path.startswith(results_file(f"visco2008/cloning/scan/{wildcards.kernel}/"))
    ]


def visco2008_cloning_kernel_scan(kernel):
    """The scan of one kernel, joined and extrapolated like cloning.nc."""
    return results_file(f"visco2008/cloning/scan/{kernel}.nc")


def visco2008_cloning_error_batches(wildcards):
    return visco2008_cloning_batch_files("error_vs_time")


# ---------------------------------------------------------------- for the analysis rules
def visco2008_md_figure_data(wildcards):
    """Aggregated MD observers of the run drawn in Fig. 9 (config key md.figure_run)."""
    return visco2008_md_data(visco2008_md()["figure_run"])


def visco2008_md_all_data(wildcards):
    """Aggregated MD observers of every run (error-against-run-time study)."""
    return [visco2008_md_data(run) for run in visco2008_md()["densities"]]


def visco2008_fig01_dsmc(wildcards):
    """DSMC free-flight-time densities drawn as squares in Fig. 1 (variables time_pdf,
    time_pdf_sem on flight_time): the hard-disk run."""
    return [visco2008_dsmc_data("free_flight_times")]


def visco2008_md_ldf_windows(wildcards):
    return visco2008_md()["ldf_windows"]


def visco2008_md_ldf_min_count(wildcards):
    return visco2008_md()["ldf_min_count"]


def visco2008_md_error_window(wildcards):
    return visco2008_md()["error_window"]


def visco2008_table1_md(wildcards):
    """Table I's MD runs, one joined file each."""
    return [visco2008_md_data(run) for run in visco2008_md()["densities"]]
