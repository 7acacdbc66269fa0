"""Studies: from a document's config section to the simulation jobs it needs.

Every document's study module (``kinetic.studies.<document>``) has ``check(config)``, which
refuses what the schema cannot judge before any job, and ``jobs(config)``, the list of its
simulation jobs as :class:`Job` records: the rule that runs it, the file it
writes (relative to the results root), the engine front and its keyword arguments (the
job's seed included), the provenance to stamp beside the front's own parameters, and
the cost estimate. The workflow and ``kinetic.plan`` read the same list (:func:`jobs`):
the rules take their ``params`` and ``resources`` from it, the plan its costs, and the
one simulate script (``workflow/scripts/simulate.py``) calls ``front(**arguments)``.

The modules are read while Snakemake parses the workflow: numpy at most, no numba, no
xarray at import.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from kinetic import DOCUMENTS

if TYPE_CHECKING:  # the cost model is loaded where a study plans its jobs, not on import
    from kinetic.cost import Estimate

__all__ = [
    "DOCUMENTS",
    "Job",
    "backend_arguments",
    "benchmark_file",
    "check",
    "front",
    "jobs",
    "points_job",
    "run_jobs",
]


@dataclass(frozen=True)
class Job:
    """One simulation job (see the module docstring).

    ``front`` names the function that runs it as ``module:function``; ``engines`` the
    engine packages whose compiled kernels it runs (their sources are the job's code
    inputs, and ``kinetic.jit.warm`` fills their cache before the front runs);
    ``parameters`` are stamped beside the ones the front stores (the run a batch belongs
    to, say)."""

    document: str
    rule: str
    output: str
    front: str
    arguments: Mapping[str, Any]
    estimate: Estimate
    engines: tuple[str, ...]
    parameters: Mapping[str, Any] = field(default_factory=dict)
    benchmark: str | None = None
    outputs: tuple[str, ...] = ()
    """Every file the job writes, ``output`` first, where it writes several (the front
    then returns a dataset for each, in this order); empty for a job of one output."""

    @property
    def files(self) -> tuple[str, ...]:
        """The files the job writes: ``outputs``, or ``output`` alone."""
        return self.outputs or (self.output,)

    @property
    def seed(self) -> int:
        """The seed of the job's random streams (of its first point, for a job of several
        points)."""
        if "points" in self.arguments:
            return int(self.arguments["points"][0]["seed"])
        return int(self.arguments["seed"])

    @property
    def gpus(self) -> int:
        """GPUs the job asks the scheduler for: 1 for a ``backend='cuda'`` job, else 0."""
        points = self.arguments.get("points", [self.arguments])
        return 1 if any(point.get("backend") == "cuda" for point in points) else 0


def backend_arguments(config: Mapping[str, Any]) -> dict[str, str]:
    """``{'backend': 'cuda'}`` where the config asks for the GPU backend, else nothing: the
    keyword a front with a ``cuda`` backend gets. A ``cpu`` job's arguments (its Snakemake
    params) stay what they were before the backends existed, so no result reruns."""
    return {"backend": "cuda"} if config.get("backend", "cpu") == "cuda" else {}


def benchmark_file(output: str) -> str:
    """The Snakemake benchmark file of the job writing ``output`` (relative to the results
    root's logs/): ``benchmarks/<output without .nc>.tsv``."""
    return f"benchmarks/{output.removesuffix('.nc')}.tsv"


def run_jobs(
    *,
    document: str,
    rule: str,
    run: str,
    front: str,
    engines: tuple[str, ...],
    cut,
    arguments,
    estimate,
    parameters: Mapping[str, Any] | None = None,
) -> list[Job]:
    """The jobs of one run of independent realizations: ``run`` names its folder under the
    results root (``visco2008/md/rho1e-3``), ``cut`` is its ``kinetic.batches.plan``, and
    job k writes ``<run>/batchNNNN.nc`` with the front's ``arguments(job, batch name)`` (the
    seed and the realization range included) and the cost ``estimate(job)``."""
    from kinetic.batches import batch_name

    found = []
    for job in cut:
        batch = batch_name(job.index)
        output = f"{run}/{batch}.nc"
        found.append(
            Job(
                document=document,
                rule=rule,
                output=output,
                front=front,
                arguments=arguments(job, batch),
                estimate=estimate(job),
                engines=engines,
                parameters=dict(parameters or {}),
                benchmark=benchmark_file(output),
            )
        )
    return found


def points_job(
    *,
    document: str,
    rule: str,
    group: str,
    outputs,
    front: str,
    points,
    label: str,
    estimate: Estimate,
    engines: tuple[str, ...],
) -> Job:
    """One job of several points in the same launches (a ``cuda`` front's ``*_points``):
    ``outputs`` are the points' files in order, the front gets ``points`` (each a front's
    keyword arguments, its seed included) and ``label``; ``group`` names the job under the
    results root's logs/ (``costantini2010/dsmc/grid/n1000``: its Snakemake benchmark file
    is ``benchmarks/<group>.tsv``)."""
    outputs = tuple(outputs)
    return Job(
        document=document,
        rule=rule,
        output=outputs[0],
        outputs=outputs,
        front=front,
        arguments={"points": list(points), "label": label},
        estimate=estimate,
        engines=engines,
        benchmark=f"benchmarks/{group}.tsv",
    )


def front(name: str):
    """The function named ``module:function`` (a job's ``front``)."""
    module, _, function = name.partition(":")
    return getattr(importlib.import_module(module), function)


def check(config: Mapping[str, Any]) -> None:
    """Every study's ``check(config)``: what the schema cannot judge (keys that contradict
    each other, a box that cannot hold its particles, arguments an engine's front would
    refuse), a ValueError naming the key before any job."""
    for document in DOCUMENTS:
        importlib.import_module(f"kinetic.studies.{document}").check(config)


def jobs(config: Mapping[str, Any]) -> list[Job]:
    """Every simulation job of a validated and checked config (:func:`check`), document by
    document, in plan order (paths relative to the results root)."""
    found = []
    for document in DOCUMENTS:
        module = importlib.import_module(f"kinetic.studies.{document}")
        found += module.jobs(config)
    return found
