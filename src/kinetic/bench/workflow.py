"""What Snakemake itself costs (``python -m kinetic.bench workflow``).

Two measurements of the workflow, each in a fresh temporary working directory (nothing
built yet, numba's cache as it is):

- the dry run of the default config (``snakemake all -n``): wall time of a separate
  process, median of three;
- a whole build (``--quick``: the ``ci`` config, else the default config) run inside this
  process, so that the CPU time of the main Snakemake process (``RUSAGE_SELF``: parsing,
  the DAG, scheduling, input functions) is told apart from that of its jobs
  (``RUSAGE_CHILDREN``: every job script and what it starts). The jobs' own benchmark
  files give the CPU time per document.

The main process's share of the build's CPU time is the overhead that the jobs cannot
use on a machine with as many cores as jobs.
"""

from __future__ import annotations

import contextlib
import csv
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from kinetic.config import load_configs, results_root

__all__ = ["run"]

REPOSITORY = Path(__file__).resolve().parents[3]
SNAKEFILE = REPOSITORY / "Snakefile"


def _cpu(usage) -> float:
    return usage.ru_utime + usage.ru_stime


def _dry_run_seconds(repeats: int = 3) -> dict[str, Any]:
    walls = []
    for _ in range(repeats):
        with tempfile.TemporaryDirectory() as workdir:
            start = time.perf_counter()
            command = [sys.executable, "-m", "snakemake", "all", "-n", "--quiet", "all"]
            command += ["--snakefile", str(SNAKEFILE), "--directory", workdir]
            command += ["--configfile", str(REPOSITORY / "config" / "config.yaml")]
            subprocess.run(
                command,
                check=True,
                capture_output=True,
            )
            walls.append(time.perf_counter() - start)
    return {
        "config": "config/config.yaml",
        "median_seconds": statistics.median(walls),
        "seconds": walls,
    }


def _benchmark_cpu(benchmarks: Path) -> dict[str, float]:
    """CPU seconds of the jobs with a ``benchmark:`` file, per document (the first folder
    under ``benchmarks``, the results root's logs/benchmarks)."""
    per_document: dict[str, float] = {}
    for path in sorted(benchmarks.rglob("*.tsv")):
        document = path.relative_to(benchmarks).parts[0]
        with path.open() as handle:
            for row in csv.DictReader(handle, delimiter="\t"):
                with contextlib.suppress(KeyError, ValueError):
                    per_document[document] = per_document.get(document, 0.0) + float(
                        row["cpu_time"]
                    )
    return per_document


def _build(config: str, cores: int) -> dict[str, Any]:
    from snakemake.cli import main as snakemake_main

    with tempfile.TemporaryDirectory() as workdir:
        self_before = _cpu(resource.getrusage(resource.RUSAGE_SELF))
        children_before = _cpu(resource.getrusage(resource.RUSAGE_CHILDREN))
        start = time.perf_counter()
        argv = ["all", "--snakefile", str(SNAKEFILE), "--directory", workdir]
        argv += ["--cores", str(cores), "--quiet", "all", "--configfile", config]
        cwd = os.getcwd()
        try:
            snakemake_main(argv)
        except SystemExit as done:
            if done.code not in (0, None):
                raise RuntimeError(f"the {config} build failed ({done.code})") from None
        finally:
            os.chdir(cwd)
        wall = time.perf_counter() - start
        main_cpu = _cpu(resource.getrusage(resource.RUSAGE_SELF)) - self_before
        jobs_cpu = _cpu(resource.getrusage(resource.RUSAGE_CHILDREN)) - children_before
        root = results_root(load_configs([config]))
        benchmarked = _benchmark_cpu(Path(workdir, root, "logs", "benchmarks"))
    return {
        "config": config,
        "cores": cores,
        "wall_seconds": wall,
        "main_process_cpu_seconds": main_cpu,
        "jobs_cpu_seconds": jobs_cpu,
        "main_process_share": main_cpu / (main_cpu + jobs_cpu),
        "benchmarked_jobs_cpu_seconds_per_document": benchmarked,
    }


def run(quick: bool = False) -> dict[str, Any]:
    config = str(REPOSITORY / "config" / ("ci.yaml" if quick else "config.yaml"))
    return {
        "dry_run": _dry_run_seconds(),
        "build": _build(config, cores=os.cpu_count() or 1),
    }
