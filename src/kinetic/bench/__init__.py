"""Speed benchmarks: ``python -m kinetic.bench <engine>`` writes results/benchmarks/<engine>.json.

Each engine has a module here with ``run(quick: bool) -> dict``. Shared helpers time a
callable several times after a warm-up call (so numba compile time is excluded) and
report medians, and record the machine the numbers came from.
"""

from __future__ import annotations

import datetime
import json
import os
import platform
import statistics
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from kinetic import __version__
from kinetic.io import git_revision

__all__ = ["machine", "median_rate", "write_report"]


def machine() -> dict[str, Any]:
    """Where the numbers were measured."""
    cpu = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {
        "date": datetime.date.today().isoformat(),
        "cpu": cpu,
        "logical_cpus": os.cpu_count(),
        "load_average_1min": os.getloadavg()[0],
        "python": platform.python_version(),
        "kinetic_version": __version__,
        "git_revision": git_revision(),
    }


def median_rate(work: Callable[[], float], *, repeats: int = 5) -> dict[str, Any]:
    """Run ``work`` once to warm up (compilation), then ``repeats`` times.

    ``work`` returns the amount of work it did (collisions, events...). Returns the
    median rate in work per CPU-second (process time, so a busy neighbour core counts
    less), the median wall-clock rate, and every repeat's numbers.
    """
    work()
    cpu_rates, wall_rates = [], []
    for _ in range(repeats):
        cpu0, wall0 = time.process_time(), time.perf_counter()
        amount = work()
        cpu1, wall1 = time.process_time(), time.perf_counter()
        cpu_rates.append(amount / max(cpu1 - cpu0, 1e-9))
        wall_rates.append(amount / max(wall1 - wall0, 1e-9))
    return {
        "rate_per_cpu_second": statistics.median(cpu_rates),
        "rate_per_wall_second": statistics.median(wall_rates),
        "cpu_rates": cpu_rates,
        "repeats": repeats,
    }


def write_report(engine: str, report: dict[str, Any], directory: str | os.PathLike) -> Path:
    """Write ``<directory>/<engine>.json`` with the machine description added."""
    path = Path(directory) / f"{engine}.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    report = {"engine": engine, "machine": machine(), **report}
    path.write_text(json.dumps(report, indent=2, sort_keys=False) + "\n")
    return path
