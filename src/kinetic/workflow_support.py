"""Glue for workflow scripts: logging to the rule's log file, and reading parameters.

Every script in ``workflow/scripts`` starts with::

    from kinetic.workflow_support import start
    log = start(snakemake)

or, for a simulation job whose rule passes the front's arguments as ``params.job``::

    from kinetic.workflow_support import run_job
    log, job, dataset = run_job(snakemake, front)

which sends the ``kinetic`` logger (progress lines with ETA) and uncaught exceptions to
``snakemake.log[0]`` as well as to standard error, and limits numba to the job's threads.
A simulation job (``run_job``, or ``start_simulation`` for a script that calls its front
itself) also makes sure numba's cache holds the compiled kernels of the engines it runs
before it runs them (``kinetic.jit.warm``): the first job after an edit compiles them
under a lock, parallel jobs wait and load.
"""

from __future__ import annotations

import logging
import sys
from typing import Any

__all__ = ["run_job", "start", "start_simulation", "warm_engines", "write_output"]


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
    threads = max(1, int(getattr(snakemake, "threads", 1)))
    try:
        import numba

        numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
    except (ImportError, ValueError):
        pass
    logger.info("rule %s: output %s", snakemake.rule, list(snakemake.output))
    return logger


def warm_engines(log: logging.Logger) -> None:
    """Fill numba's cache with the kernels of every engine package the script has imported
    (``kinetic.jit.warm``), before the job calls any of them."""
    from kinetic import jit
    from kinetic.sources import ENGINES

    for engine in ENGINES:
        if f"kinetic.{engine}" in sys.modules:
            seconds = jit.warm(engine)
            if seconds > 0.0:
                log.info("kinetic.%s kernels in numba's cache after %.1f s", engine, seconds)


def start_simulation(snakemake: Any) -> logging.Logger:
    """``start`` for a simulation job: logging, then the engines' kernels in the cache."""
    log = start(snakemake)
    warm_engines(log)
    return log


def write_output(
    snakemake: Any,
    dataset: Any,
    seed: int | None,
    *,
    output: str | None = None,
    parameters: dict | None = None,
) -> None:
    """Stamp ``dataset`` with provenance and write it atomically: the one path by which a
    workflow script writes netCDF.

    Attributes: the physical ``parameters`` (default: those the engine stored), ``seed``
    (the seed of the random streams behind the data: the job's seed for a simulation, the
    run's for an aggregate of one run, -1 for data without random numbers or combined from
    several runs), ``root_seed`` (the config's seed, from which every job seed derives),
    the workflow ``config``, the package version and the git revision. ``output`` names
    the rule output to write (default: the first).
    """
    from kinetic import io

    dataset = io.stamp(
        dataset,
        parameters=io.parameters_of(dataset) if parameters is None else parameters,
        seed=seed,
        config=snakemake.config,
    )
    dataset = dataset.assign_attrs(root_seed=int(snakemake.config.get("seed", -1)))
    path = snakemake.output[0] if output is None else getattr(snakemake.output, output)
    io.write_dataset(dataset, path)


def run_job(snakemake: Any, front: Any) -> tuple[logging.Logger, dict, Any]:
    """One simulation job: ``front(**params.job)`` written to the rule's output with the
    job's seed, and a log line with its CPU time. Returns the logger, the job's arguments
    and the dataset, for a script that logs more."""
    log = start_simulation(snakemake)
    job = dict(snakemake.params.job)
    dataset = front(**job)
    write_output(snakemake, dataset, job["seed"])
    if "cpu_seconds" in dataset:
        cpu = float(dataset["cpu_seconds"].sum())
        log.info("wrote %s in %.1f CPU s", snakemake.output[0], cpu)
    return log, job, dataset
