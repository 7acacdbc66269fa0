# Event-driven molecular dynamics (kinetic.edmd): the equilibrium hard-disk runs of
# visco2008 §IV.B, in resumable batches of independent seeded realizations (one netCDF per
# batch), then one aggregate per run. Realization k of a run always uses row k of the run's
# stream states, so the results do not depend on the batch size.

import math
import re


def visco2008_md():
    """The config section visco2008.md (validated and filled with defaults)."""
    return config["visco2008"]["md"]


def _check_visco2008_md():
    """Cross-key consistency of visco2008.md, checked before any job starts."""
    md = visco2008_md()
    windows = md["windows"]
    problems = []
    if any(b <= a for a, b in zip(windows, windows[1:])):
        problems.append(f"windows {windows} must be strictly increasing")
    if windows[-1] > md["duration"]:
        problems.append(f"the longest window {windows[-1]} exceeds duration {md['duration']}")
    for key in ("table_windows", "ldf_windows", "extrapolation_windows"):
        missing = [t for t in md[key] if t not in windows]
        if missing:
            problems.append(f"{key} {missing} are not among windows {windows}")
    if md["error_window"] not in windows:
        problems.append(f"error_window {md['error_window']} is not among windows {windows}")
    checkpoints = md["checkpoints"]
    if any(b <= a for a, b in zip(checkpoints, checkpoints[1:])):
        problems.append(f"checkpoints {checkpoints} must be strictly increasing")
    if checkpoints[-1] != md["duration"]:
        problems.append(f"the last checkpoint {checkpoints[-1]} must equal duration {md['duration']}")
    if md["figure_run"] not in md["densities"]:
        problems.append(f"figure_run {md['figure_run']!r} is not a key of densities {sorted(md['densities'])}")
    if problems:
        raise WorkflowError("config section visco2008.md: " + "; ".join(problems))


_check_visco2008_md()


def visco2008_md_batch_count():
    md = visco2008_md()
    return math.ceil(md["realizations"] / md["batch_size"])


def visco2008_md_data(run):
    """Aggregated observers of one MD run (all realizations)."""
    return f"results/visco2008/md/{run}.nc"


def visco2008_md_cumulants(run):
    """Scaled cumulants <N^p>_c/t with standard errors of one run (Table I input)."""
    return f"results/visco2008/md/{run}_cumulants.nc"


def visco2008_md_batch_files(wildcards):
    """Input function: every batch file of the run named by the wildcard."""
    return [
        f"results/visco2008/md/{wildcards.run}/batch{batch:03d}.nc"
        for batch in range(visco2008_md_batch_count())
    ]


def visco2008_md_batch_parameters(wildcards):
    """Keyword arguments of kinetic.edmd.simulate for one batch."""
    md = visco2008_md()
    batch = int(wildcards.batch)
    first = batch * md["batch_size"]
    return {
        "n_particles": md["n_particles"],
        "density": md["densities"][wildcards.run],
        "seed": job_seed(f"visco2008/md/{wildcards.run}"),
        "realizations": min(md["batch_size"], md["realizations"] - first),
        "first_realization": first,
        "equilibration": md["equilibration"],
        "duration": md["duration"],
        "windows": md["windows"],
        "checkpoints": md["checkpoints"],
        "flight_time_max": md["flight_time_max"],
        "flight_time_bins": md["flight_time_bins"],
        "free_path_max": md["free_path_max"],
        "free_path_bins": md["free_path_bins"],
        "cell_occupancy": md["cell_occupancy"],
        "label": f"visco2008 md {wildcards.run} batch {batch}",
    }


def visco2008_md_table_windows(wildcards):
    return visco2008_md()["table_windows"]


def visco2008_md_extrapolation_windows(wildcards):
    return visco2008_md()["extrapolation_windows"]


def edmd_sources(wildcards):
    return engine_sources("edmd")


def visco2008_md_run_pattern():
    """Wildcard constraint: the run names of the config, nothing else."""
    return "|".join(re.escape(run) for run in visco2008_md()["densities"])


rule edmd_visco2008_batch:
    input:
        sources=edmd_sources,
        warm=numba_warm("edmd"),
    output:
        "results/visco2008/md/{run}/batch{batch}.nc",
    log:
        "logs/visco2008/md/{run}/batch{batch}.log",
    benchmark:
        "logs/benchmarks/visco2008/md/{run}/batch{batch}.tsv"
    params:
        simulation=visco2008_md_batch_parameters,
    threads: 1
    wildcard_constraints:
        run=visco2008_md_run_pattern(),
        batch=r"\d{3}",
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../scripts/edmd_visco2008_batch.py"


rule edmd_visco2008_aggregate:
    input:
        batches=visco2008_md_batch_files,
        sources=package_files("analysis"),
    output:
        data="results/visco2008/md/{run}.nc",
        cumulants="results/visco2008/md/{run}_cumulants.nc",
    log:
        "logs/visco2008/md/{run}_aggregate.log",
    params:
        table_windows=visco2008_md_table_windows,
        extrapolation_windows=visco2008_md_extrapolation_windows,
    wildcard_constraints:
        run=visco2008_md_run_pattern(),
    script:
        "../scripts/edmd_visco2008_aggregate.py"


# Table I of visco2008 reads one cumulant file per MD run.
VISCO2008_TABLE1_MD.extend(visco2008_md_cumulants(run) for run in visco2008_md()["densities"])
