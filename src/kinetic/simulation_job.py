"""One simulation job of the workflow (``workflow/scripts/simulate.py``, every
``<document>_simulate_<what>`` rule, whose rule passes a ``kinetic.studies.Job``'s front,
arguments and provenance as ``params``)::

    from kinetic.simulation_job import run_job
    run_job(snakemake)

It logs as every workflow script does (``kinetic.workflow_support.start``), makes sure
numba's cache holds the compiled kernels it runs before it runs them (``kinetic.jit.warm``,
:func:`warm_engines`: the first job after an edit compiles them under a lock, parallel jobs
wait and load), and writes through the one provenance writer
(``kinetic.workflow_support.write_output``). It is a module of its own because it imports
the studies: the reading scripts' code inputs do not include them.
"""

from __future__ import annotations

import logging
import sys
from typing import Any

from kinetic.workflow_support import start, write_output

__all__ = ["run_job", "warm_engines"]


def warm_engines(log: logging.Logger, front: Any = None) -> None:
    """Fill numba's cache (``kinetic.jit.warm``), before the job calls any kernel, with the
    kernels of the engine whose function the job's ``front`` is or runs (a study's front
    that imports its engine only when called names that function in its
    ``engine_front``, ``module:function``): those of that function alone where the engine
    lists them (its ``WARMUPS``). Every other engine package the script has imported is
    warmed whole."""
    from kinetic import jit
    from kinetic.sources import ENGINES

    own, name = None, None
    if front is not None:
        target = getattr(front, "engine_front", f"{front.__module__}:{front.__name__}")
        module, _, name = target.partition(":")
        own = module.split(".")[1] if module.count(".") else None
    for engine in ENGINES:
        if engine == own or f"kinetic.{engine}" in sys.modules:
            seconds = jit.warm(engine, name if engine == own else None)
            if seconds > 0.0:
                log.info("kinetic.%s kernels in numba's cache after %.1f s", engine, seconds)


def run_job(snakemake: Any) -> tuple[logging.Logger, Any]:
    """One simulation job: the front named by ``params.front`` (``module:function``, a
    ``kinetic.studies.Job``'s) called with ``params.job``, written to the rule's output with
    the job's seed and ``params.parameters`` stamped beside the front's own parameters,
    and a log line with its CPU time. Numba's cache is filled for the engines the front
    imports before it runs (:func:`warm_engines`). Returns the logger and the dataset."""
    from kinetic import io, studies

    log = start(snakemake)
    front = studies.front(snakemake.params.front)
    warm_engines(log, front)
    job = dict(snakemake.params.job)
    result = front(**job)
    # a job of several points (``points``): a dataset each, written in the rule's order
    datasets = result if isinstance(result, list) else [result]
    seeds = [point["seed"] for point in job.get("points", [job])]
    extra = dict(snakemake.params.parameters)
    for index, (dataset, seed) in enumerate(zip(datasets, seeds, strict=True)):
        parameters = {**io.parameters_of(dataset), **extra} if extra else None
        write_output(snakemake, dataset, seed, output=index, parameters=parameters)
        path = snakemake.output[index]
        if "cpu_seconds" in dataset:
            cpu = float(dataset["cpu_seconds"].sum())
            log.info("wrote %s (%s, %.1f CPU s)", path, snakemake.params.front, cpu)
        else:
            log.info("wrote %s (%s)", path, snakemake.params.front)
    return log, result
