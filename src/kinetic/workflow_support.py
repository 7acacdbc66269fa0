"""Glue for workflow scripts: logging to the rule's log file, writing netCDF with its
provenance (``write_output``) and rendering captions (``write_caption``).

Every script in ``workflow/scripts`` starts with::

    from kinetic.workflow_support import start
    log = start(snakemake)

or, for a simulation job (``workflow/scripts/simulate.py``, whose rule passes a
``kinetic.studies.Job``'s front, arguments and provenance as ``params``)::

    from kinetic.workflow_support import run_job
    run_job(snakemake)

which sends the ``kinetic`` logger (progress lines with ETA) and uncaught exceptions to
``snakemake.log[0]`` as well as to standard error, and limits numba to the job's threads.
A simulation job also makes sure numba's cache holds the compiled kernels it runs before
it runs them (``kinetic.jit.warm``, :func:`warm_engines`): the first job after an edit
compiles them under a lock, parallel jobs wait and load.
"""

from __future__ import annotations

import logging
import os
import sys
from pathlib import Path
from typing import Any

__all__ = ["run_job", "start", "warm_engines", "write_caption", "write_output"]


def start(snakemake: Any) -> logging.Logger:
    """Configure logging for one Snakemake job and return the ``kinetic`` logger."""
    logger = logging.getLogger("kinetic")
    logger.setLevel(logging.INFO)
    logger.handlers.clear()
    formatter = logging.Formatter("%(asctime)s %(message)s", "%H:%M:%S")
    handlers: list[logging.Handler] = [logging.StreamHandler(sys.stderr)]
    if len(snakemake.log) > 0:
        handlers.append(logging.FileHandler(snakemake.log[0], mode="w"))
    for handler in handlers:
        handler.setFormatter(formatter)
        logger.addHandler(handler)

    def log_uncaught(kind, value, traceback):
        logger.error("job failed", exc_info=(kind, value, traceback))

    sys.excepthook = log_uncaught
    # the job's threads cap numba's thread pool; numba reads the variable when an engine
    # first imports it, so a job that joins, analyses or plots never loads numba (0.6 CPU-s
    # a job, a tenth of a ci build)
    threads = max(1, int(getattr(snakemake, "threads", 1)))
    available = int(os.environ.get("NUMBA_NUM_THREADS", os.cpu_count() or 1))
    os.environ["NUMBA_NUM_THREADS"] = str(min(threads, available))
    if "numba" in sys.modules:  # already loaded: its pool exists
        import numba

        numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
    logger.info("rule %s: output %s", snakemake.rule, list(snakemake.output))
    return logger


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


def write_output(
    snakemake: Any,
    dataset: Any,
    seed: int | None,
    *,
    output: str | int | None = None,
    parameters: dict | None = None,
) -> None:
    """Stamp ``dataset`` with provenance and write it atomically: the one path by which a
    workflow script writes netCDF.

    Attributes: the physical ``parameters`` (default: those the engine stored), ``seed``
    (the seed of the random streams behind the data: the job's seed for a simulation, the
    run's for an aggregate of one run, -1 for data without random numbers or combined from
    several runs), ``root_seed`` (the config's seed, from which every job seed derives),
    the workflow ``config``, the package version and the git revision. ``output`` names
    the rule output to write, or gives its index (default: the first).
    """
    from kinetic import io

    dataset = io.stamp(
        dataset,
        parameters=io.parameters_of(dataset) if parameters is None else parameters,
        seed=seed,
        config=snakemake.config,
    )
    dataset = dataset.assign_attrs(root_seed=int(snakemake.config.get("seed", -1)))
    if output is None or isinstance(output, int):
        path = snakemake.output[output or 0]
    else:
        path = getattr(snakemake.output, output)
    io.write_dataset(dataset, path)


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


def write_caption(template: str | os.PathLike, path: str | os.PathLike, **values) -> str:
    """Render a caption template (reStructuredText with ``str.format`` fields such as
    ``{z_k2:.1f}``) with numbers taken from the data files, and write it to ``path``
    (the report reads it there). Returns the text."""
    text = Path(template).read_text(encoding="utf-8").format(**values)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return text
