"""The costantini2010 study: which runs, in which units, and which figure uses which.

Every run simulates N real inelastic hard disks at the config's density in the stationary
representation of the homogeneous cooling state (``simulate_cooling_modes`` of
``kinetic.dsmc`` or ``kinetic.edmd``) and records the temperature and the transverse
modes on a fixed grid of rescaled time. Three families:

``grid``
    every (N, α) of the config, by inhomogeneous DSMC (the production Λ and cell side)
    and by MD: C(τ) for each N (Fig 3), ν* and ν̄* against 1/N and α (Figs 4-7, Table 1);
``figures``
    at the figure's (N, α): homogeneous DSMC (one cell) for each of its Λ, inhomogeneous
    DSMC with the production cells and with fine cells (less than one real particle per
    cell when Λ = 1) for each Λ, and MD (Figs 1 and 2);
``convergence``
    α = 1 at the figure's N: DSMC with several cell sides and time steps (the
    systematic errors of the method).

A run is named by a plain string built from its parameters (``n1000-alpha0.8-md``,
``n1000-alpha0.8-f10-cell0.5-step0.05``, ``n1000-alpha0.8-hom-f1-step0.05``): two
families asking for the same run share it, and Snakemake wildcards are looked up in
:func:`runs`, never parsed. Lengths of the config are in mean free paths
λ = 1/(2√2 nσ) and times in mean free times 1/ω_c, ω_c = 2nσ√(πT0/m) (T0 = 1, the
initial temperature); :meth:`Run.engine_arguments` converts them into engine units
(m = σ = T0 = 1) in one place.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from kinetic import batches
from kinetic.studies import Job, backend_arguments, points_job, run_jobs
from kinetic.theory import costantini2010 as theory
from kinetic.theory.costantini2010 import MIN_LAGS, mean_free_path, mean_free_time

__all__ = [
    "FRONTS",
    "METHODS",
    "Run",
    "batch_file",
    "batch_plan",
    "check",
    "convergence_runs",
    "correlation_runs",
    "dsmc_groups",
    "figure_runs",
    "grid_runs",
    "group_files",
    "group_name",
    "group_rule",
    "jobs",
    "mean_free_path",
    "mean_free_time",
    "run_file",
    "runs",
    "single_dsmc_runs",
    "table_runs",
]

METHODS = ("dsmc_homogeneous", "dsmc", "md")

"""Method names of the table: homogeneous DSMC (one cell), inhomogeneous DSMC, MD."""


@dataclass(frozen=True)
class Run:
    """One run: engine and physics parameters (config units: λ, 1/ω_c)."""

    engine: str  # "dsmc" or "md"
    n_particles: int
    restitution: float
    fictive_factor: int = 1
    homogeneous: bool = False
    cell_side: float | None = None  # mean free paths (inhomogeneous DSMC)
    time_step: float | None = None  # mean free times (DSMC)

    @property
    def method(self) -> str:
        if self.engine == "md":
            return "md"
        return "dsmc_homogeneous" if self.homogeneous else "dsmc"

    @property
    def name(self) -> str:
        head = f"n{self.n_particles}-alpha{self.restitution:g}"
        if self.engine == "md":
            return f"{head}-md"
        if self.homogeneous:
            return f"{head}-hom-f{self.fictive_factor}-step{self.time_step:g}"
        return f"{head}-f{self.fictive_factor}-cell{self.cell_side:g}-step{self.time_step:g}"

    def cells_per_side(self, density: float) -> int:
        """M of the M x M collision cells (1 for homogeneous DSMC)."""
        if self.homogeneous:
            return 1
        side = math.sqrt(self.n_particles / density)
        return max(1, round(side / (self.cell_side * mean_free_path(density))))

    def real_particles_per_cell(self, density: float) -> float:
        return self.n_particles / self.cells_per_side(density) ** 2

    def engine_arguments(self, study: Mapping[str, Any]) -> dict[str, Any]:
        """Keyword arguments of ``simulate_cooling_modes`` (engine units), without the
        seed and the realization range."""
        density = study["density"]
        unit = mean_free_time(density)
        interval = study["sample_interval"]
        total = study["transient"] + duration(self, study)
        arguments = {
            "n_particles": self.n_particles,
            "density": density,
            "restitution": self.restitution,
            "drag_rate": drag_rate(self.restitution, study),
            "equilibration": 0.0,
            "sample_interval": interval * unit,
            "n_samples": math.ceil(total / interval),
        }
        if self.engine == "dsmc":
            ratio = interval / self.time_step
            if abs(ratio - round(ratio)) > 1e-9 * ratio:
                raise ValueError(
                    f"costantini2010.sample_interval = {interval} is not a whole multiple of "
                    f"the DSMC time step {self.time_step} (mean free times)"
                )
            arguments |= {
                "fictive_factor": self.fictive_factor,
                "cells_per_side": self.cells_per_side(density),
                "time_step": interval * unit / round(ratio),
                "collision_rule": study["dsmc"]["collision_rule"],
            }
        return arguments


def drag_rate(restitution: float, study: Mapping[str, Any]) -> float:
    """ω0 = ζ(T0)/2 of Eq. 12 in engine units (T_s = T0 = 1 up to the error of a2)."""
    return theory.drag_rate(restitution, study["density"], a2=study["a2"])


def duration(run: Run, study: Mapping[str, Any]) -> float:
    """Sampled length of one realization in mean free times: ``duration`` predicted
    correlation times τ_c (Eq. 9, first Sonine), so every (N, α) gets a similar relative
    error; at least ``min_duration``."""
    tau_c = theory.correlation_time(run.restitution, run.n_particles, study["density"])
    mean_free_times = tau_c * math.sqrt(2.0 * math.pi)  # τ_c is in ℓ/v_s; 1/ω_c = ℓ/(v_s √(2π))
    return max(study["duration"] * mean_free_times, study["min_duration"])


def grid_runs(study: Mapping[str, Any]) -> list[Run]:
    """Inhomogeneous DSMC and MD for every (N, α) of the config."""
    dsmc = study["dsmc"]
    found = []
    for n in study["particles"]:
        for alpha in study["restitutions"]:
            found.append(
                Run(
                    "dsmc",
                    n,
                    alpha,
                    dsmc["fictive_factor"],
                    cell_side=dsmc["cell_side"],
                    time_step=dsmc["time_step"],
                )
            )
            found.append(Run("md", n, alpha))
    return found


def figure_runs(study: Mapping[str, Any]) -> list[Run]:
    """The runs of Figs 1 and 2 at the figure's (N, α)."""
    dsmc, figures = study["dsmc"], study["figures"]
    n, alpha, step = figures["particles"], figures["restitution"], dsmc["time_step"]
    found = [
        Run("dsmc", n, alpha, factor, homogeneous=True, time_step=step)
        for factor in figures["homogeneous_fictive_factors"]
    ]
    for cell_side in (dsmc["cell_side"], figures["fine_cell_side"]):
        found += [
            Run("dsmc", n, alpha, factor, cell_side=cell_side, time_step=step)
            for factor in figures["fictive_factors"]
        ]
    return [*found, Run("md", n, alpha)]


def convergence_runs(study: Mapping[str, Any]) -> list[Run]:
    """α = 1 DSMC at the figure's N: each cell side at the production step, each step at
    the production cell side."""
    dsmc, convergence = study["dsmc"], study["convergence"]
    n, factor = study["figures"]["particles"], dsmc["fictive_factor"]
    found = [
        Run("dsmc", n, 1.0, factor, cell_side=side, time_step=dsmc["time_step"])
        for side in convergence["cell_sides"]
    ]
    found += [
        Run("dsmc", n, 1.0, factor, cell_side=dsmc["cell_side"], time_step=step)
        for step in convergence["time_steps"]
    ]
    return found


def correlation_runs(study: Mapping[str, Any]) -> list[Run]:
    """The runs of Fig 2: the figure runs without the fine cells (Fig 1's bad case)."""
    production = study["dsmc"]["cell_side"]
    return [
        run
        for run in figure_runs(study)
        if run.homogeneous or run.engine == "md" or run.cell_side == production
    ]


def table_runs(study: Mapping[str, Any]) -> list[Run]:
    """The runs of Table 1: the grid and those of Fig 2 (one run per method, α, N, Λ)."""
    found = {run.name: run for run in grid_runs(study)}
    for run in correlation_runs(study):
        found.setdefault(run.name, run)
    return list(found.values())


def runs(study: Mapping[str, Any]) -> dict[str, Run]:
    """Every run of the study by name (runs asked for by several families appear once)."""
    found: dict[str, Run] = {}
    for run in grid_runs(study) + figure_runs(study) + convergence_runs(study):
        found.setdefault(run.name, run)
    return found


def run_file(run: Run) -> str:
    """The aggregate of one run (its jobs joined and analysed), under the results root."""
    return f"costantini2010/{run.engine}/{run.name}.nc"


def batch_file(run: Run, job: batches.Job) -> str:
    """The dataset written by one job of a run, under the results root."""
    return f"costantini2010/{run.engine}/{run.name}/{batches.batch_name(job.index)}.nc"


def batch_plan(study: Mapping[str, Any], run: Run, backend: str = "cpu") -> list[batches.Job]:
    """The cut of a run into jobs of realizations: ``realizations_per_job`` at a time, or,
    for a DSMC run on the ``cuda`` backend, every realization in one job (one launch
    advances them all)."""
    per_job = study["realizations_per_job"]
    if backend == "cuda" and run.engine == "dsmc":
        per_job = study["realizations"]
    return batches.plan(realizations=study["realizations"], realizations_per_job=per_job)


FRONTS = {
    "dsmc": ("kinetic.dsmc:simulate_cooling_modes", "dsmc"),
    "md": ("kinetic.edmd:simulate_cooling_modes", "edmd"),
}
"""Per engine key of a run: the front that runs it and its engine package."""


def dsmc_groups(study: Mapping[str, Any], backend: str) -> dict[str, list[Run]]:
    """With the ``cuda`` backend, the grid's DSMC runs of one N (every α of the config:
    the same particles, cells and step) share one job and the GPU's launches
    (``kinetic.dsmc.simulate_cooling_modes_points``): {group name (``n1000``): its runs in
    the config's α order}. None on the cpu, where every run is cut into its own jobs."""
    if backend != "cuda":
        return {}
    groups: dict[str, list[Run]] = {}
    for run in grid_runs(study):
        if run.engine == "dsmc":
            groups.setdefault(f"n{run.n_particles}", []).append(run)
    return groups


def group_rule(group: str) -> str:
    """The Snakemake rule of a group of :func:`dsmc_groups`
    (``costantini2010_simulate_dsmc_grid_n1000``: one job, a file per run)."""
    return f"costantini2010_simulate_dsmc_grid_{group}"


def group_name(group: str) -> str:
    """The path of a group's job under the results root's logs/, without its suffix: its
    log (``.log``) and, under ``benchmarks/``, its Snakemake benchmark file (``.tsv``)."""
    return f"costantini2010/dsmc/grid/{group}"


def group_files(study: Mapping[str, Any], group: list[Run]) -> list[str]:
    """The files a group's job writes (under the results root): each run's one batch."""
    return [batch_file(run, batch_plan(study, run, "cuda")[0]) for run in group]


def single_dsmc_runs(study: Mapping[str, Any], backend: str) -> list[str]:
    """Names of the DSMC runs cut into jobs of their own (every one on the cpu)."""
    grouped = {run.name for group in dsmc_groups(study, backend).values() for run in group}
    return [
        name for name, run in runs(study).items() if run.engine == "dsmc" and name not in grouped
    ]


def jobs(config: Mapping[str, Any]) -> list[Job]:
    """The simulation jobs of the config's costantini2010 section (``kinetic.studies``):
    every run of :func:`runs`, cut by :func:`batch_plan` into batches of realizations, but
    with the ``cuda`` backend one job for each group of :func:`dsmc_groups`."""
    from kinetic import cost
    from kinetic.seeds import derive_seed

    study = config.get("costantini2010")
    if not study:
        return []
    found = []
    backend = config.get("backend", "cpu")
    groups = dsmc_groups(study, backend)
    grouped = {run.name for group in groups.values() for run in group}
    points: dict[str, dict[str, Any]] = {}  # run name -> its group job's point
    for run in runs(study).values():
        shared = run.engine_arguments(study)
        gpu = backend_arguments(config) if run.engine == "dsmc" else {}
        front, engine = FRONTS[run.engine]
        seed = derive_seed(config["seed"], f"costantini2010/{run.engine}/{run.name}")
        if run.name in grouped:
            (job,) = batch_plan(study, run, backend)
            points[run.name] = (
                shared
                | {
                    "seed": seed,
                    "first_realization": job.first_realization,
                    "n_realizations": job.n_realizations,
                }
                | gpu
            )
            continue
        found += run_jobs(
            document="costantini2010",
            rule=f"costantini2010_simulate_{run.engine}",
            run=run_file(run).removesuffix(".nc"),
            front=front,
            engines=(engine,),
            cut=batch_plan(study, run, backend),
            arguments=lambda job, batch, run=run, shared=shared, seed=seed, gpu=gpu: (
                shared
                | {
                    "seed": seed,
                    "first_realization": job.first_realization,
                    "n_realizations": job.n_realizations,
                    "label": f"costantini2010 {run.engine} {run.name} {batch}",
                }
                | gpu
            ),
            estimate=lambda job, run=run, shared=shared, gpu=gpu: cost.cooling_modes(
                engine=run.engine, n_realizations=job.n_realizations, **shared, **gpu
            ),
        )
    for name, group in groups.items():
        group_points = [points[run.name] for run in group]
        found.append(
            points_job(
                document="costantini2010",
                rule=group_rule(name),
                group=group_name(name),
                outputs=group_files(study, group),
                front="kinetic.dsmc:simulate_cooling_modes_points",
                points=group_points,
                label=f"costantini2010 dsmc grid {name} ({len(group)} runs)",
                estimate=cost.cooling_modes_points(group_points),
                engines=("dsmc",),
            )
        )
    return found


def check(config: Mapping[str, Any]) -> None:
    """Stop before any job on what the schema cannot judge: keys that contradict each
    other (a tail fit starting beyond the longest lag of C, blocks too short for the
    correlation's lags, an error-against-CPU study at an N or α the grid does not run),
    an (N, α) at or beyond the shear instability (L >= L_c, where τ_c diverges), a sample
    interval that the DSMC steps do not divide."""
    study = config.get("costantini2010")
    if not study:
        return
    try:
        _check(study)
    except ValueError as error:
        raise ValueError(f"config section costantini2010: {error}") from None


def _check(study: Mapping[str, Any]) -> None:
    if study["fit_start"] >= study["max_lag"]:
        raise ValueError(
            f"fit_start = {study['fit_start']} l/v_s starts the tail fit of C at or beyond "
            f"its longest lag max_lag = {study['max_lag']} l/v_s"
        )
    blocks = study["blocks_per_realization"]
    for name, run in runs(study).items():
        theory.check_stable(run.n_particles, study["density"], run.restitution)
        run.engine_arguments(study)
        samples = duration(run, study) / study["sample_interval"]
        if samples // blocks < 2 * MIN_LAGS:
            raise ValueError(
                f"run {name}: blocks_per_realization = {blocks} cuts its {samples:.0f} "
                f"steady samples into blocks of {samples // blocks:.0f}, and C needs "
                f"{2 * MIN_LAGS} a block ({MIN_LAGS} lags): lower blocks_per_realization or "
                "lengthen duration or min_duration"
            )
    figure_n, alpha = study["figures"]["particles"], study["error_restitution"]
    if figure_n not in study["particles"] or alpha not in study["restitutions"]:
        raise ValueError(
            f"the error-against-CPU study runs at figures.particles = {figure_n} and "
            f"error_restitution = {alpha}, which must be among particles "
            f"{study['particles']} and restitutions {study['restitutions']} (its figure "
            "and table would be empty)"
        )
