"""Glue for workflow scripts: logging to the rule's log file, writing netCDF with its
provenance (``write_output``) and rendering captions (``write_caption``).

Every script in ``workflow/scripts`` starts with::

    from kinetic.workflow_support import start
    log = start(snakemake)

which sends the ``kinetic`` logger (progress lines with ETA) and uncaught exceptions to
``snakemake.log[0]`` as well as to standard error, and limits numba to the job's threads.
The simulation jobs' script runs ``kinetic.simulation_job.run_job`` instead, which starts
the same way. This module imports nothing of the package at its top and only ``io`` and
``sources`` in its functions, so that the rules that join, analyse and plot, whose code
inputs are the package files their script imports (``kinetic.sources.script_sources``), do
not rerun when the studies, the cost model or the engines' argument checks change.
"""

from __future__ import annotations

import contextlib
import logging
import os
import sys
from pathlib import Path
from typing import Any

__all__ = ["output_config", "start", "write_caption", "write_output"]


def start(snakemake: Any) -> logging.Logger:
    """Configure logging for one Snakemake job and return the ``kinetic`` logger."""
    logger = logging.getLogger("kinetic")
    logger.setLevel(logging.INFO)
    for handler in logger.handlers:
        handler.close()
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
    # a job makes outputs from the code its sources hold now, which may have been edited
    # since the build parsed the workflow: its stamps are brought up to date, then every
    # stamp forgets its earlier codes (as onstart does for the build, which a build with
    # --no-hooks skips), so that a return to an earlier code reruns what this job makes
    from kinetic.sources import STAMPS, forget_earlier_codes, refresh_stamps

    scripts = getattr(snakemake, "scriptdir", None)
    if scripts:  # workflow/scripts, two levels below the workflow's directory
        inputs = [str(path) for path in getattr(snakemake, "input", [])]
        refresh_stamps(
            [path for path in inputs if path.endswith(".stamp")], Path(scripts).parents[1]
        )
    with contextlib.suppress(OSError):
        forget_earlier_codes(STAMPS)
    logger.info("rule %s: output %s", snakemake.rule, list(snakemake.output))
    return logger


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
    the workflow ``config`` the file comes from (:func:`output_config`), the package
    version and the git revision. ``output`` names the rule output to write, or gives its
    index (default: the first).
    """
    from kinetic import io

    if output is None or isinstance(output, int):
        path = snakemake.output[output or 0]
    else:
        path = getattr(snakemake.output, output)
    dataset = io.stamp(
        dataset,
        parameters=io.parameters_of(dataset) if parameters is None else parameters,
        seed=seed,
        config=output_config(snakemake.config, path),
    )
    dataset = dataset.assign_attrs(root_seed=int(snakemake.config.get("seed", -1)))
    io.write_dataset(dataset, path)


def output_config(config: dict, path: str | os.PathLike) -> dict:
    """The part of ``config`` that an output at ``path`` comes from: the keys every
    document shares (seed, results, backend, ...) and the section of the document whose
    directory under the results root holds it (``<results>/visco2008/...``: the
    ``visco2008`` section). Another document's section is left out: it did not make the
    file, and it may have changed since without a rerun, so the attribute would misstate
    the file's provenance. A file outside every document's directory gets the whole
    config."""
    try:
        relative = (
            Path(path).resolve().relative_to(Path(config.get("results", "results")).resolve())
        )
    except ValueError:
        return dict(config)
    document = relative.parts[0] if len(relative.parts) > 1 else None
    from kinetic import DOCUMENTS

    if not isinstance(config.get(document), dict):
        return dict(config)
    documents = {key for key in DOCUMENTS if key in config}
    return {key: value for key, value in config.items() if key not in documents - {document}}


def write_caption(template: str | os.PathLike, path: str | os.PathLike, **values) -> str:
    """Render a caption template (reStructuredText with ``str.format`` fields such as
    ``{z_k2:.1f}``) with numbers taken from the data files, and write it to ``path``
    (the report reads it there). Returns the text."""
    text = Path(template).read_text(encoding="utf-8").format(**values)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return text
