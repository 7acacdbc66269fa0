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

A job of several points that run one after the other (a front that takes ``finished``,
montanero2007's ``simulate_batches`` on ``cuda``) keeps each point's dataset as it ends,
in a hidden file beside its output (:func:`resume_file`), named by a key of the point,
its stamps and the job's code (:func:`resume_keys`). Snakemake deletes a stopped job's
outputs, not these: the job's rerun loads the points an earlier run of the same job
finished and runs the others. The files go when the outputs are written.
"""

from __future__ import annotations

import hashlib
import inspect
import json
import logging
import sys
from pathlib import Path
from typing import Any

from kinetic.workflow_support import start, write_output

__all__ = ["resume_file", "resume_keys", "run_job", "warm_engines"]

RESUME_KEY = "resume_key"
"""The attribute of a kept point's file that names the job that wrote it (:func:`resume_keys`)."""


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
    if "points" in job and "finished" in inspect.signature(front).parameters:
        result = _run_resumably(snakemake, front, job, log)
    else:
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
    for path in snakemake.output[: len(datasets)]:
        resume_file(path).unlink(missing_ok=True)
    return log, result


def resume_file(output: str | Path) -> Path:
    """Where a job of several points keeps the point of ``output`` once it has finished,
    until the job writes ``output`` (``.<name>.resume.nc`` beside it)."""
    output = Path(output)
    return output.with_name(f".{output.name}.resume.nc")


def resume_keys(snakemake: Any, points: list[dict[str, Any]]) -> list[str]:
    """A digest a point of what its numbers depend on: the job's front, the point's
    arguments, the job's stamps and the contents of the job's inputs (its code, read
    once). A kept point is loaded only by a rerun of the same job with the same code."""
    inputs = hashlib.sha256()
    for path in sorted(str(path) for path in getattr(snakemake, "input", [])):
        inputs.update(path.encode())
        inputs.update(Path(path).read_bytes())
    keys = []
    for point in points:
        described = {
            "front": snakemake.params.front,
            "point": point,
            "parameters": dict(snakemake.params.parameters),
            "inputs": inputs.hexdigest(),
        }
        keys.append(hashlib.sha256(json.dumps(described, sort_keys=True, default=str).encode()))
    return [key.hexdigest() for key in keys]


def _run_resumably(snakemake: Any, front: Any, job: dict[str, Any], log: logging.Logger):
    """``front(**job)`` for a job of several points run one after the other: each point's
    dataset is kept as it ends (:func:`resume_file`), and the points that an earlier,
    stopped run of this job kept are loaded, not run again."""
    from kinetic import io

    points = list(job["points"])
    keys = resume_keys(snakemake, points)
    files = [resume_file(path) for path in snakemake.output[: len(points)]]
    done: dict[int, Any] = {}
    for index, (file, key) in enumerate(zip(files, keys, strict=True)):
        if not file.exists():
            continue
        try:
            kept = io.read_dataset(file)
        except io.CorruptFileError:
            kept = None
        if kept is not None and kept.attrs.pop(RESUME_KEY, None) == key:
            done[index] = kept
            log.info("kept %s: finished by a stopped run of this job", snakemake.output[index])
        else:
            file.unlink()
    remaining = [index for index in range(len(points)) if index not in done]

    def finished(k: int, dataset: Any) -> None:
        index = remaining[k]
        io.write_dataset(dataset.assign_attrs({RESUME_KEY: keys[index]}), files[index])

    if remaining:
        if done:
            log.info("running %d of the job's %d points", len(remaining), len(points))
        ran = front(**{**job, "points": [points[i] for i in remaining]}, finished=finished)
        done.update(zip(remaining, ran, strict=True))
    return [done[index] for index in range(len(points))]
