"""The simulation jobs a config asks for, their estimated cost, and the budget check.

``python -m kinetic.plan --configfile config/paper.yaml`` prints, per document and in
total, the number of simulation jobs, their CPU-hours, the longest job, the memory asked
per job and the wall time on P = 2, 64 and 1024 cores (greedy longest-first scheduling
of the estimated job times; the aggregation and figure jobs, seconds to minutes each,
are not counted).

The jobs are the studies' (``kinetic.studies.jobs``), the same records the simulation
rules take their ``params`` from: every simulation rule asks SLURM for the ``runtime`` and
``mem_mb`` of its output's job (:func:`jobs_by_output`, through kinetic.cost), and before
any job the workflow refuses a config with a job above the ``limits`` section
(:func:`check_limits`) and prints the total (:func:`summary_line`). A workflow test
compares this list with the jobs of a Snakemake dry run.
"""

from __future__ import annotations

import argparse
import heapq
import sys
from collections.abc import Iterable, Mapping
from dataclasses import replace
from pathlib import Path
from typing import Any

from kinetic import cost, studies
from kinetic.backends import BACKENDS
from kinetic.config import load_configs, results_root
from kinetic.studies import Job

__all__ = [
    "CORES",
    "JOB_TABLE_COLUMNS",
    "BudgetError",
    "Job",
    "benchmark_overruns",
    "check_limits",
    "job_table",
    "jobs_by_output",
    "main",
    "plan_jobs",
    "resource_hints",
    "summary_line",
    "summary_rows",
    "summary_table",
    "wall_seconds",
]

CORES = (2, 64, 1024)
"""Core counts of the wall-time columns."""

DEFAULT_LIMITS = {"max_job_cpu_hours": 12.0, "max_job_memory_gb": 16.0, "max_total_cpu_hours": 1e5}
"""Defaults of the config section ``limits`` (workflow/schemas/limits.schema.yaml)."""


class BudgetError(ValueError):
    """A config whose jobs exceed the limits of its ``limits`` section."""


def plan_jobs(config: Mapping[str, Any]) -> list[Job]:
    """Every simulation job of a validated (defaults filled) config, in plan order
    (``kinetic.studies.jobs``), with its output under the config's results root and its
    benchmark file under the root's ``logs/``."""
    root = results_root(config)
    return [
        replace(
            job,
            output=f"{root}/{job.output}",
            outputs=tuple(f"{root}/{path}" for path in job.outputs),
            benchmark=f"{root}/logs/{job.benchmark}" if job.benchmark else None,
        )
        for job in studies.jobs(config)
    ]


def jobs_by_output(config: Mapping[str, Any]) -> dict[str, Job]:
    """:func:`plan_jobs` keyed by each file a job writes."""
    return {path: job for job in plan_jobs(config) for path in job.files}


# ------------------------------------------------------------------ limits
def check_limits(jobs: Iterable[Job], limits: Mapping[str, Any] | None = None) -> None:
    """Raise BudgetError naming every job (up to five) above a limit, with its estimate.

    ``limits``: ``max_job_cpu_hours`` (estimated CPU time of one job),
    ``max_job_memory_gb`` (memory a job would ask for, margin included),
    ``max_total_cpu_hours`` (estimated CPU time of all jobs).
    """
    limits = {**DEFAULT_LIMITS, **(limits or {})}
    jobs = list(jobs)
    problems = []
    for job in jobs:
        estimate = job.estimate
        if not estimate.cpu_hours <= limits["max_job_cpu_hours"]:
            problems.append(
                f"{job.output}: estimated {estimate.cpu_hours:.3g} CPU-hours "
                f"({estimate.work}) > limits.max_job_cpu_hours = {limits['max_job_cpu_hours']:g}"
            )
        requested = cost.mem_mb(estimate) / 1000.0
        if not requested <= limits["max_job_memory_gb"]:
            problems.append(
                f"{job.output}: would ask for {requested:.3g} GB of memory (estimated peak "
                f"{estimate.peak_mb / 1000.0:.3g} GB, x{cost.MEMORY_SAFETY:g} margin on the "
                f"particles) > limits.max_job_memory_gb = {limits['max_job_memory_gb']:g}"
            )
    total = sum(job.estimate.cpu_hours for job in jobs)
    if not total <= limits["max_total_cpu_hours"]:
        problems.append(
            f"the config's {len(jobs)} simulation jobs: estimated {total:.3g} CPU-hours in all "
            f"> limits.max_total_cpu_hours = {limits['max_total_cpu_hours']:g}"
        )
    if problems:
        shown = problems[:5] + ([f"... and {len(problems) - 5} more"] if len(problems) > 5 else [])
        raise BudgetError(
            "refused before any job, the estimated cost exceeds the config's limits "
            "(kinetic.cost; lower the statistics, split the jobs, e.g. fewer realizations "
            "per job, or raise the limit):\n  " + "\n  ".join(shown)
        )


def benchmark_overruns(directory: str | Path, jobs: Iterable[Job]) -> tuple[int, list[str]]:
    """Compare the jobs' requests with what their Snakemake ``benchmark:`` files measured.

    Returns ``(checked, problems)``: the number of jobs of ``jobs`` that have a benchmark
    file under ``directory``, and one sentence per job whose measured CPU time (column
    ``cpu_time``) exceeds its ``runtime`` request before the rounding up to minutes
    (``kinetic.cost.requested_seconds``) or whose peak memory
    (``max_rss``, MB) exceeds its ``mem_mb`` request. CPU time, not wall time: on a
    cluster every job has its core to itself and the two agree, while on a shared machine
    the wall time also counts the waits for a core, which no estimate can know (the wall
    time stands in where a job ended before Snakemake sampled its CPU time). Snakemake 9
    samples every 0.5 s for the first 15 s, then every 30 s, and keeps the last sample: a
    job's ``cpu_time`` can fall up to 30 s short of what it used (a job of 15-45 s
    reports about 15 s: 26 of the default build's 252; of 274 paper.yaml jobs, 49
    reported 0.44-0.9 of their engines' own CPU time, those of 30-60 s the most), so the
    check is blind to an overrun smaller than that; the requests are at least 2 minutes,
    so only a job that runs longer than that can hide one.
    """
    import csv

    checked, problems = 0, []
    for job in jobs:
        path = Path(directory) / job.benchmark if job.benchmark else None
        if path is None or not path.is_file():
            continue
        with path.open(newline="") as handle:
            rows = list(csv.DictReader(handle, delimiter="\t"))
        if not rows:
            continue
        checked += 1
        cpu = [float(row["cpu_time"]) for row in rows if row.get("cpu_time", "NA") != "NA"]
        seconds = max(cpu) if cpu else max(float(row["s"]) for row in rows)
        memory = max(float(row["max_rss"]) for row in rows if row["max_rss"] != "NA")
        # the request before its rounding to whole minutes (at least 2): overhead + margin
        runtime = cost.requested_seconds(job.estimate)
        requested = cost.mem_mb(job.estimate)
        if seconds > runtime:
            problems.append(
                f"{job.output}: ran {seconds:.1f} CPU-s, estimate x margin {runtime:.1f} s"
            )
        if memory > requested:
            problems.append(f"{job.output}: peak {memory:.0f} MB, asked for {requested} MB")
    return checked, problems


JOB_TABLE_COLUMNS = (
    "document",
    "rule",
    "output",
    "work",
    "estimated_cpu_s",
    "runtime_min",
    "mem_mb",
    "measured_s",
    "measured_cpu_s",
    "measured_max_rss_mb",
    "outputs",
)
"""Columns of :func:`job_table`: ``output`` is the job's first file, ``outputs`` every file
it writes (several for a job of several points in the same GPU launches), space-separated."""


def job_table(directory: str | Path, jobs: Iterable[Job]) -> list[dict[str, Any]]:
    """One row per job (:data:`JOB_TABLE_COLUMNS`): the estimate and the requests, and,
    where the job's benchmark file exists under ``directory``, what it measured (wall
    seconds, CPU seconds, peak resident memory in MB; empty otherwise)."""
    import csv

    rows = []
    for job in jobs:
        row = {
            "document": job.document,
            "rule": job.rule,
            "output": job.output,
            "work": job.estimate.work,
            "estimated_cpu_s": round(job.estimate.cpu_seconds, 3),
            "runtime_min": cost.runtime_minutes(job.estimate),
            "mem_mb": cost.mem_mb(job.estimate),
            "measured_s": "",
            "measured_cpu_s": "",
            "measured_max_rss_mb": "",
            "outputs": " ".join(job.files),
        }
        path = Path(directory) / job.benchmark if job.benchmark else None
        if path is not None and path.is_file():
            with path.open(newline="") as handle:
                measured = list(csv.DictReader(handle, delimiter="\t"))
            if measured:
                row["measured_s"] = measured[-1]["s"]
                row["measured_cpu_s"] = measured[-1]["cpu_time"]
                row["measured_max_rss_mb"] = measured[-1]["max_rss"]
        rows.append(row)
    return rows


RESOURCE_OF_STATE = {"TIMEOUT": "runtime", "OUT_OF_MEMORY": "mem_mb"}
"""SLURM job states that mean a job outgrew its request, and the resource to raise."""


def resource_hints(log_text: str) -> str:
    """Sentences telling which resource to raise for every job of a Snakemake log that
    SLURM killed for its time (TIMEOUT) or memory (OUT_OF_MEMORY); empty if none."""
    import re

    hints = []
    for block in re.split(r"\n(?=Error in rule )", log_text):
        rule = re.match(r"Error in rule (\w+):", block)
        state = re.search(r"SLURM status is: '(TIMEOUT|OUT_OF_MEMORY)'", block)
        if not (rule and state):
            continue
        resource = RESOURCE_OF_STATE[state.group(1)]
        output = re.search(r"^\s+output: ([^,\n]+)", block, flags=re.MULTILINE)
        logs = re.search(r"^\s+log: ([^\n]+)", block, flags=re.MULTILINE)
        hints.append(
            f"rule {rule.group(1)} ({output.group(1) if output else 'job'}) was killed by "
            f"SLURM ({state.group(1)}): raise its {resource}, e.g. --set-resources "
            f"{rule.group(1)}:{resource}=<value> (every retry doubles it; kinetic.cost has "
            f"the estimate){'; log: ' + logs.group(1) if logs else ''}"
        )
    return "\n".join(hints)


# ------------------------------------------------------------------ summaries
def wall_seconds(seconds: Iterable[float], cores: int) -> float:
    """Makespan of independent jobs on ``cores`` cores, longest job first to the least
    loaded core (within 4/3 of the optimum)."""
    loads = [0.0] * min(cores, max(1, len(durations := sorted(seconds, reverse=True))))
    heapq.heapify(loads)
    for duration in durations:
        heapq.heappush(loads, heapq.heappop(loads) + duration)
    return max(loads) if durations else 0.0


def summary_rows(jobs: Iterable[Job], cores: Iterable[int] = CORES) -> list[dict[str, Any]]:
    """One row per document and a 'total' row: jobs, cpu_hours, longest_job_hours,
    mem_mb (largest request), and wall_hours_P for each P of ``cores``."""
    jobs = list(jobs)
    cores = list(cores)
    groups: dict[str, list[Job]] = {}
    for job in jobs:
        groups.setdefault(job.document, []).append(job)
    groups["total"] = jobs
    rows = []
    for document, members in groups.items():
        seconds = [job.estimate.job_seconds for job in members]
        row = {
            "document": document,
            "jobs": len(members),
            "cpu_hours": sum(job.estimate.cpu_seconds for job in members) / 3600.0,
            "gpu_hours": sum(job.estimate.cpu_seconds for job in members if job.estimate.gpus)
            / 3600.0,
            "longest_job_hours": max(seconds, default=0.0) / 3600.0,
            "mem_mb": max((cost.mem_mb(job.estimate) for job in members), default=0),
        }
        for count in cores:
            row[f"wall_hours_{count}"] = wall_seconds(seconds, count) / 3600.0
        rows.append(row)
    return rows


def _hours(value: float) -> str:
    if value < 1.0:
        return f"{value * 60:.3g} min"
    return f"{value:.3g} h"


def summary_table(jobs: Iterable[Job], cores: Iterable[int] = CORES) -> str:
    """Markdown table of :func:`summary_rows` (with a GPU-hours column where some jobs run
    on a GPU)."""
    cores = list(cores)
    rows = summary_rows(jobs, cores)
    gpu = any(row["gpu_hours"] for row in rows)
    header = ["document", "jobs", "CPU-hours"] + (["of it on a GPU"] if gpu else [])
    header += ["longest job", "mem_mb per job"] + [f"wall, {count} cores" for count in cores]
    lines = ["| " + " | ".join(header) + " |", "|" + " --- |" * len(header)]
    for row in rows:
        cells = [row["document"], str(row["jobs"]), f"{row['cpu_hours']:.3g}"]
        cells += [_hours(row["gpu_hours"])] if gpu else []
        cells += [_hours(row["longest_job_hours"]), str(row["mem_mb"])]
        cells += [_hours(row[f"wall_hours_{count}"]) for count in cores]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def summary_line(jobs: Iterable[Job]) -> str:
    """One line: the estimated total of the config's simulation jobs."""
    (total,) = [row for row in summary_rows(jobs) if row["document"] == "total"]
    walls = ", ".join(f"{_hours(total[f'wall_hours_{p}'])} on {p}" for p in CORES)
    gpu = (
        f" ({_hours(total['gpu_hours'])} of it on one GPU, backend cuda)"
        if total["gpu_hours"]
        else ""
    )
    return (
        f"estimated cost of the config's {total['jobs']} simulation jobs (kinetic.plan): "
        f"{total['cpu_hours']:.3g} CPU-hours{gpu}, longest job "
        f"{_hours(total['longest_job_hours'])}, at most {total['mem_mb']} MB per job; "
        f"wall {walls} cores"
    )


# ------------------------------------------------------------------ command line
def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m kinetic.plan",
        description="Estimated cost of the simulation jobs of a workflow config.",
    )
    parser.add_argument(
        "--configfile",
        nargs="+",
        default=["config/config.yaml"],
        help="config file(s), merged in order as snakemake does (default: config/config.yaml)",
    )
    parser.add_argument(
        "--backend",
        choices=BACKENDS,
        help="run the GPU-capable engines on this backend (the config's 'backend' key, "
        "as snakemake's --config backend=cuda would set it)",
    )
    parser.add_argument("--jobs", action="store_true", help="also list every job")
    arguments = parser.parse_args(argv)
    config = load_configs(arguments.configfile)
    if arguments.backend:
        config["backend"] = arguments.backend
    try:
        studies.check(config)
    except ValueError as error:
        print(error, file=sys.stderr)
        return 1
    jobs = plan_jobs(config)
    print(summary_table(jobs))
    if arguments.jobs:
        for job in jobs:
            print(
                f"{job.output}\t{job.estimate.cpu_seconds:.1f} CPU-s\t{job.estimate.work}\t"
                f"runtime={cost.runtime_minutes(job.estimate)} mem_mb={cost.mem_mb(job.estimate)}"
            )
    try:
        check_limits(jobs, config.get("limits"))
    except BudgetError as error:
        print(error, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
