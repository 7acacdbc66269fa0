"""Progress lines with an ETA for long runs.

Kernels run in chunks; after each chunk the front calls ``Progress.update`` and a line
such as ``[edmd rho=0.01] 42.0% 4.2e+06/1.0e+07 collisions  elapsed 12s  ETA 17s`` is
logged at most every ``interval`` seconds (and always at the end). Lines go to the
``kinetic`` logger, which Snakemake scripts route to the rule's log file.
"""

from __future__ import annotations

import logging
import time

__all__ = ["Progress", "format_seconds"]

logger = logging.getLogger("kinetic")


def format_seconds(seconds: float) -> str:
    """``75`` -> ``'1m15s'``; ``3725`` -> ``'1h02m'``."""
    seconds = max(0.0, float(seconds))
    if seconds < 60:
        return f"{seconds:.0f}s"
    if seconds < 3600:
        return f"{int(seconds // 60)}m{int(seconds % 60):02d}s"
    return f"{int(seconds // 3600)}h{int(seconds % 3600 // 60):02d}m"


class Progress:
    """Periodic progress lines with elapsed time and ETA.

    Parameters
    ----------
    total
        Amount of work (collisions, steps, realizations...), > 0.
    label
        Prefix naming the run.
    unit
        Name of one unit of work.
    interval
        Minimum seconds between two lines.
    """

    def __init__(self, total: float, *, label: str, unit: str = "steps", interval: float = 10.0):
        if not total > 0:
            raise ValueError(f"total must be > 0, got {total}")
        self.total = float(total)
        self.label = label
        self.unit = unit
        self.interval = interval
        self.done = 0.0
        self.start = time.perf_counter()
        self._last = -float("inf")
        self._finished = False

    def update(self, amount: float) -> None:
        """Record ``amount`` more units of work and log a line if one is due."""
        self.done += amount
        now = time.perf_counter()
        finished = self.done >= self.total
        if finished and self._finished:
            return  # the 100% line is logged once, however often the front reports after it
        if now - self._last >= self.interval or finished:
            self._last = now
            self._finished = finished
            elapsed = now - self.start
            fraction = min(self.done / self.total, 1.0)
            eta = elapsed * (1.0 - fraction) / fraction if fraction > 0 else float("inf")
            logger.info(
                "[%s] %5.1f%% %.3g/%.3g %s  elapsed %s  ETA %s",
                self.label,
                100.0 * fraction,
                self.done,
                self.total,
                self.unit,
                format_seconds(elapsed),
                format_seconds(eta) if fraction > 0 else "?",
            )
