"""visco2008's cloning study: names of its points and the parameters of each job.

The workflow splits the realizations of every (kernel, λ, N_c) point into jobs
(``kinetic.batches``). Paths name points by tokens built from the config (``lam+1.000``,
``N1000``); the rules map a token back to its value by lookup in the config, never by
parsing it. Realization k of a point uses row k of the point's stream states, so results
do not depend on the batching. Imports no engine: the workflow reads it while parsing.

Config section ``visco2008.cloning`` (schema: workflow/schemas/visco2008.cloning.schema.yaml)::

    kernels: {hard_disks: {lambdas: [...], populations: [...]}, maxwell: {...}}
    collisions_per_realization, realizations, realizations_per_job, n_blocks, transient,
    transient_kept_collisions, histogram_bins, histogram_half_width
    error_vs_time: {lambdas, populations, collisions_per_realization, realizations, n_blocks}
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from kinetic import batches, cost

__all__ = [
    "GROUPED_MAX_POPULATION",
    "KERNEL_SETTINGS",
    "batch_keys",
    "group_rule",
    "grouped",
    "groups",
    "job_parameters",
    "jobs",
    "lambda_token",
    "point_seed_key",
    "population_token",
    "reference_lambdas",
    "single_sizes",
    "study_points",
]

KERNEL_SETTINGS = {
    "hard_disks": {"kernel": "hard_spheres", "dimension": 2, "slowest_rate": 1 / math.sqrt(2)},
    "maxwell": {"kernel": "maxwell", "dimension": 2, "slowest_rate": 1.0},
}
"""Config kernel names (also the ``kernel`` column of cloning.csv) -> front arguments."""


def lambda_token(lam: float) -> str:
    """Path token of a tilt: ``lam+1.000``, ``lam-0.250``."""
    return f"lam{float(lam):+.3f}"


def population_token(population: int) -> str:
    """Path token of a population size: ``N1000``."""
    return f"N{int(population)}"


def study_points(section: Mapping[str, Any], study: str) -> list[tuple[str, float, int]]:
    """(kernel, λ, N_c) of every point of ``study`` ('scan' or 'error_vs_time')."""
    if study == "scan":
        return [
            (kernel, float(lam), int(n))
            for kernel, grid in section["kernels"].items()
            for lam in grid["lambdas"]
            for n in grid["populations"]
        ]
    if study == "error_vs_time":
        grid = section["error_vs_time"]
        return [
            ("hard_disks", float(lam), int(n))
            for lam in grid["lambdas"]
            for n in grid["populations"]
        ]
    raise ValueError(f"unknown cloning study {study!r}; expected 'scan' or 'error_vs_time'")


def _study_settings(section: Mapping[str, Any], study: str) -> dict[str, Any]:
    keys = ("collisions_per_realization", "realizations", "n_blocks")
    settings = {key: section[key] for key in keys}
    settings["realizations_per_job"] = section["realizations_per_job"]
    if study == "error_vs_time":  # one job per point
        settings.update({key: section["error_vs_time"][key] for key in keys})
        settings["realizations_per_job"] = settings["realizations"]
    return settings


def jobs(section: Mapping[str, Any], study: str, backend: str = "cpu") -> list[batches.Job]:
    """The jobs of every point of ``study`` (every point has the same plan). With the
    ``cuda`` backend a point is one job: the GPU runs all its realizations in one launch."""
    settings = _study_settings(section, study)
    realizations = int(settings["realizations"])
    per_job = realizations if backend == "cuda" else int(settings["realizations_per_job"])
    return batches.plan(realizations=realizations, realizations_per_job=per_job)


GROUPED_MAX_POPULATION = cost.CLONING_GPU_GROUPED_MAX_POPULATION
"""With the ``cuda`` backend, the points of a (study, kernel, N_c) with N_c up to this share
one job and the GPU's launches (``kinetic.cloning.simulate_points``): as one thread block
of the resident kernel each up to ``kinetic.cloning.gpu.RESIDENT_MAX_POPULATION`` clones,
as rows of the three launches of an interval above (``kinetic.cost`` holds the limit and
says why)."""


def grouped(backend: str, population: int) -> bool:
    """Whether a point of ``population`` clones runs in its (study, kernel, N_c) group's
    job: the ``cuda`` backend and at most ``GROUPED_MAX_POPULATION`` clones."""
    return backend == "cuda" and int(population) <= GROUPED_MAX_POPULATION


def group_rule(study: str, kernel: str) -> str:
    """The Snakemake rule of the grouped jobs of ``study`` and ``kernel``
    (``visco2008_simulate_cloning_<study>_<kernel>``, one job per N_c)."""
    return f"visco2008_simulate_cloning_{study}_{kernel}"


def groups(section: Mapping[str, Any], backend: str) -> list[tuple[str, str, list[str], list[str]]]:
    """(study, kernel, λ tokens, N tokens) of every group rule the config needs: the
    grouped populations of each study and kernel, and their tilts."""
    found = {}  # (study, kernel) -> ({λ token: None}, {N token: None}): ordered sets
    for study in ("scan", "error_vs_time"):
        for kernel, lam, population in study_points(section, study):
            if grouped(backend, population):
                lams, sizes = found.setdefault((study, kernel), ({}, {}))
                lams[lambda_token(lam)] = sizes[population_token(population)] = None
    return [(study, kernel, [*lams], [*sizes]) for (study, kernel), (lams, sizes) in found.items()]


def single_sizes(section: Mapping[str, Any], backend: str) -> list[str]:
    """N tokens of the points that run one job per batch (every point on the ``cpu``)."""
    sizes = []
    for study in ("scan", "error_vs_time"):
        for _, _, population in study_points(section, study):
            token = population_token(population)
            if not grouped(backend, population) and token not in sizes:
                sizes.append(token)
    return sizes


def batch_keys(
    section: Mapping[str, Any], study: str, backend: str = "cpu"
) -> list[tuple[str, str, str, int]]:
    """(kernel, λ token, N token, job index) of every job of ``study``."""
    return [
        (kernel, lambda_token(lam), population_token(n), job.index)
        for kernel, lam, n in study_points(section, study)
        for job in jobs(section, study, backend)
    ]


def point_seed_key(study: str, kernel: str, lam_token: str, n_token: str) -> str:
    """Key from which a point's seed derives (the batch is not part of it)."""
    return f"visco2008/cloning/{study}/{kernel}/{lam_token}/{n_token}"


def event_rate_factor(lam: float) -> float:
    """c_λ of ``kernels.compensation_parameters`` (1 for λ >= 0, 2e^{-λ} - 1 below), in
    plain Python: the workflow plans jobs at every parse without loading the kernels."""
    return 1.0 if lam >= 0.0 else 2.0 * math.exp(-lam) - 1.0


def job_parameters(
    section: Mapping[str, Any],
    study: str,
    kernel: str,
    lam_token: str,
    n_token: str,
    batch: int,
    seed: int,
    backend: str = "cpu",
) -> dict[str, Any]:
    """Keyword arguments of ``kinetic.cloning.simulate`` for one batch job (of the job plan
    of ``backend``).

    The measured time is ``collisions_per_realization / (N_c c_λ)`` mean free times
    (c_λ = 1 for λ >= 0, 2e^{-λ} - 1 below: about ``collisions_per_realization`` collision
    events a realization), and the transient is the longer of ``transient`` and the time in
    which a member keeps ``transient_kept_collisions`` collisions at the slowest rate
    (e^{λ}/r_min per one).
    """
    by_token = {
        (k, lambda_token(lam), population_token(n)): (lam, n)
        for k, lam, n in study_points(section, study)
    }
    try:
        lam, population = by_token[(kernel, lam_token, n_token)]
    except KeyError:
        raise ValueError(
            f"no cloning point {kernel}/{lam_token}/{n_token} in study {study!r} of the config"
        ) from None
    settings = _study_settings(section, study)
    plan = jobs(section, study, backend)
    if not 0 <= int(batch) < len(plan):
        raise ValueError(f"batch {batch} outside 0..{len(plan) - 1}")
    job = plan[int(batch)]
    rate_factor = event_rate_factor(lam)
    duration = settings["collisions_per_realization"] / (population * rate_factor)
    kernel_settings = KERNEL_SETTINGS[kernel]
    renewal = section["transient_kept_collisions"] * math.exp(lam) / kernel_settings["slowest_rate"]
    return {
        "kernel": kernel_settings["kernel"],
        "dimension": kernel_settings["dimension"],
        "lam": lam,
        "population": population,
        "duration": duration,
        "transient": max(float(section["transient"]), renewal),
        "n_blocks": int(settings["n_blocks"]),
        "n_realizations": job.n_realizations,
        "first_realization": job.first_realization,
        "seed": int(seed),
        "histogram_bins": int(section["histogram_bins"]),
        "histogram_half_width": float(section["histogram_half_width"]),
    }


def reference_lambdas(section: Mapping[str, Any]) -> list[float]:
    """λ grid of the deterministic solution of Eq. 28: ``reference_points`` values over
    the scan's range, plus every λ of the scan and of the error study (sorted, unique)."""
    scanned = [lam for _, lam, _ in study_points(section, "scan")]
    studied = [lam for _, lam, _ in study_points(section, "error_vs_time")]
    low, high = min(scanned + studied), max(scanned + studied)
    grid = np.linspace(low, high, int(section["reference_points"]))
    return sorted({round(float(x), 12) for x in [*grid, *scanned, *studied]})
