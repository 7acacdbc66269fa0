"""The visco2008 study: its simulation jobs.

- molecular dynamics (``kinetic.edmd.simulate``, §IV.B): one run per density of the config's
  ``md.densities``, each cut into batches of realizations;
- homogeneous DSMC (``kinetic.dsmc.simulate_free_flights``, Figs 1 and 12): one run per
  entry of ``dsmc``;
- the cloning Monte Carlo (``kinetic.cloning.simulate``, §IV.A): one run per point
  (kernel, λ, N_c) of the scan and of the error study (``kinetic.studies.visco2008_cloning``).

Realization k of a run always uses stream k of the run's seed, so the data do not depend on
the cut into jobs.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from kinetic.studies import Job, backend_arguments, points_job, run_jobs
from kinetic.studies import visco2008_cloning as cloning_plan

__all__ = [
    "check",
    "cloning_jobs",
    "dsmc_arguments",
    "dsmc_jobs",
    "jobs",
    "md_arguments",
    "md_jobs",
]


def check(config: Mapping[str, Any]) -> None:
    """Before any job: the cloning section's jobs by the cloning front's own checks
    (:func:`check_cloning`), then the MD section: every run's first job by the MD front's
    own checks (``kinetic.edmd.arguments.check_simulate``, numpy only), then what only the
    config knows (the windows the table and figures use, the figure's run)."""
    from kinetic.edmd.arguments import check_simulate

    check_cloning(config)
    md = config.get("visco2008", {}).get("md")
    if not md:
        return
    windows = md["windows"]
    problems = []
    for job in md_jobs(config):
        if job.arguments["first_realization"] == 0:
            try:
                check_simulate(**job.arguments)
            except (TypeError, ValueError) as error:
                problems.append(f"run {job.output.split('/')[2]}: {error}")
    for key in ("table_windows", "ldf_windows", "extrapolation_windows"):
        missing = [t for t in md[key] if t not in windows]
        if missing:
            problems.append(f"{key} {missing} are not among windows {windows}")
    if md["error_window"] not in windows:
        problems.append(f"error_window {md['error_window']} is not among windows {windows}")
    short = [t for t in md["checkpoints"] if t < md["error_window"]]
    if short:
        problems.append(
            f"checkpoints {short} are shorter than error_window {md['error_window']}: the "
            "error-against-CPU study would have no count window there (NaN)"
        )
    if md["figure_run"] not in md["densities"]:
        problems.append(
            f"figure_run {md['figure_run']!r} is not a key of densities {sorted(md['densities'])}"
        )
    if problems:
        raise ValueError("config section visco2008.md: " + "; ".join(problems))


def check_cloning(config: Mapping[str, Any]) -> None:
    """Every cloning job's arguments (each point of a grouped ``cuda`` job) by the front's
    own checks (``kinetic.cloning.arguments.validate_parameters``, numpy only): a value it
    refuses (a histogram too fine for the GPU, a transient too short at large λ) stops the
    parse instead of the jobs."""
    import inspect

    from kinetic.cloning.arguments import validate_parameters

    accepted = set(inspect.signature(validate_parameters).parameters)
    problems = []
    for job in cloning_jobs(config):
        for arguments in job.arguments.get("points", [job.arguments]):
            try:
                validate_parameters(**{k: v for k, v in arguments.items() if k in accepted})
            except (TypeError, ValueError) as error:
                problems.append(f"job {job.output}: {error}")
    if problems:
        more = f" (and {len(problems) - 1} more jobs)" if len(problems) > 1 else ""
        raise ValueError(f"config section visco2008.cloning: {problems[0]}{more}")


def md_arguments(md: Mapping[str, Any], run: str) -> dict[str, Any]:
    """Keyword arguments of ``kinetic.edmd.simulate`` shared by every job of MD run
    ``run`` (without the seed, the realization range and the label)."""
    return {
        "n_particles": md["n_particles"],
        "density": md["densities"][run],
        "equilibration": md["equilibration"],
        "duration": md["duration"],
        "windows": md["windows"],
        "checkpoints": md["checkpoints"],
        "flight_time_max": md["flight_time_max"],
        "flight_time_bins": md["flight_time_bins"],
        "free_path_max": md["free_path_max"],
        "free_path_bins": md["free_path_bins"],
        "cell_occupancy": md["cell_occupancy"],
    }


def md_jobs(config: Mapping[str, Any]) -> list[Job]:
    """The MD jobs (every density's run cut into batches)."""
    from kinetic import batches, cost
    from kinetic.seeds import derive_seed

    md = config.get("visco2008", {}).get("md")
    if not md:
        return []
    cut = batches.plan(
        realizations=md["realizations"], realizations_per_job=md["realizations_per_job"]
    )
    found = []
    for run, density in md["densities"].items():
        seed = derive_seed(config["seed"], f"visco2008/md/{run}")
        found += run_jobs(
            document="visco2008",
            rule="visco2008_simulate_md",
            run=f"visco2008/md/{run}",
            front="kinetic.edmd:simulate",
            engines=("edmd",),
            cut=cut,
            arguments=lambda job, batch, run=run, seed=seed: (
                md_arguments(md, run)
                | {
                    "seed": seed,
                    "realizations": job.n_realizations,
                    "first_realization": job.first_realization,
                    "label": f"visco2008 md {run} {batch}",
                }
            ),
            estimate=lambda job, density=density: cost.edmd_periodic(
                n_particles=md["n_particles"],
                density=density,
                realizations=job.n_realizations,
                equilibration=md["equilibration"],
                duration=md["duration"],
            ),
        )
    return found


def dsmc_arguments(settings: Mapping[str, Any]) -> dict[str, Any]:
    """Keyword arguments of ``kinetic.dsmc.simulate_free_flights`` shared by every job of a
    DSMC run (without the seed, the realization range and the label)."""
    return {
        "kernel": settings["kernel"],
        "dimension": settings["dimension"],
        "n_particles": settings["n_particles"],
        "duration": settings["duration"],
        "max_flight_time": settings["max_flight_time"],
        "n_time_bins": settings["time_bins"],
        "max_free_path": settings["max_free_path"],
        "n_path_bins": settings["path_bins"],
    }


def dsmc_jobs(config: Mapping[str, Any]) -> list[Job]:
    """The DSMC jobs of Figs 1 and 12 (every run cut into batches)."""
    from kinetic import batches, cost
    from kinetic.seeds import derive_seed

    found = []
    for run, settings in config.get("visco2008", {}).get("dsmc", {}).items():
        seed = derive_seed(config["seed"], f"visco2008/dsmc/{run}")
        found += run_jobs(
            document="visco2008",
            rule="visco2008_simulate_dsmc",
            run=f"visco2008/dsmc/{run}",
            front="kinetic.dsmc:simulate_free_flights",
            engines=("dsmc",),
            cut=batches.plan(
                realizations=settings["realizations"],
                realizations_per_job=settings["realizations_per_job"],
            ),
            arguments=lambda job, batch, run=run, seed=seed, settings=settings: (
                dsmc_arguments(settings)
                | {
                    "seed": seed,
                    "first_realization": job.first_realization,
                    "n_realizations": job.n_realizations,
                    "label": f"visco2008 dsmc {run} {batch}",
                }
            ),
            estimate=lambda job, settings=settings: cost.dsmc_free_flights(
                n_particles=settings["n_particles"],
                duration=settings["duration"],
                n_realizations=job.n_realizations,
                kernel=settings["kernel"],
            ),
        )
    return found


def cloning_jobs(config: Mapping[str, Any]) -> list[Job]:
    """The cloning jobs of the scan and of the error study: every point cut into batches;
    with the ``cuda`` backend the points of a study, kernel and population (up to
    ``visco2008_cloning.GROUPED_MAX_POPULATION`` clones) share one job
    (``visco2008_cloning.grouped``)."""
    from kinetic import cost
    from kinetic.batches import batch_name
    from kinetic.seeds import derive_seed

    section = config.get("visco2008", {}).get("cloning")
    if not section:
        return []
    backend = config.get("backend", "cpu")
    found = []
    grouped = {}
    for study in ("scan", "error_vs_time"):
        for kernel, lam, population in cloning_plan.study_points(section, study):
            point = cloning_plan.lambda_token(lam)
            size = cloning_plan.population_token(population)
            seed = derive_seed(
                config["seed"], cloning_plan.point_seed_key(study, kernel, point, size)
            )

            def arguments(
                job, batch, study=study, kernel=kernel, point=point, size=size, seed=seed
            ):
                parameters = cloning_plan.job_parameters(
                    section, study, kernel, point, size, job.index, seed, backend
                )
                label = {"label": f"cloning {kernel} {point} {size} {batch}"}
                return parameters | backend_arguments(config) | label

            cut = cloning_plan.jobs(section, study, backend)
            if cloning_plan.grouped(backend, population):
                job = cut[0]  # the cuda plan: the point is one job
                batch = batch_name(job.index)
                grouped.setdefault((study, kernel, size), []).append(arguments(job, batch))
                continue
            found += run_jobs(
                document="visco2008",
                rule="visco2008_simulate_cloning",
                run=f"visco2008/cloning/{study}/{kernel}/{point}/{size}",
                front="kinetic.cloning:simulate",
                engines=("cloning",),
                cut=cut,
                arguments=arguments,
                estimate=lambda job, arguments=arguments: cost.cloning_batch(
                    **{k: v for k, v in arguments(job, "").items() if k != "label"}
                ),
            )
    for (study, kernel, size), points in grouped.items():
        outputs = [
            f"visco2008/cloning/{study}/{kernel}/"
            f"{cloning_plan.lambda_token(point['lam'])}/{size}/{batch_name(0)}.nc"
            for point in points
        ]
        stripped = [{k: v for k, v in point.items() if k != "label"} for point in points]
        found.append(
            points_job(
                document="visco2008",
                rule=cloning_plan.group_rule(study, kernel),
                group=f"visco2008/cloning/{study}/{kernel}/{size}",
                outputs=outputs,
                front="kinetic.cloning:simulate_points",
                points=stripped,
                label=f"cloning {study} {kernel} {size} ({len(points)} points)",
                estimate=cost.cloning_points(stripped),
                engines=("cloning",),
            )
        )
    return found


def jobs(config: Mapping[str, Any]) -> list[Job]:
    """Every visco2008 simulation job (``kinetic.studies``): MD, DSMC, cloning."""
    return md_jobs(config) + dsmc_jobs(config) + cloning_jobs(config)
