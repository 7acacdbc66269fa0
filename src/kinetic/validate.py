"""Argument checks shared by the engines' fronts: each raises before any work, naming the
argument, its value and what is allowed (``TypeError`` for a wrong type, ``ValueError``
for a value out of range)."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = [
    "MAX_BINS",
    "choice",
    "fits_in_memory",
    "integer",
    "multiple",
    "real",
    "realizations",
    "seed",
]


MAX_BINS = 10**6
"""Most bins of a histogram an engine fills (a count of 10**12 passed the checks and then
asked numpy for terabytes)."""


MEMORY_FRACTION = 0.75
"""Share of the machine's physical memory a run's counted arrays may take (the rest: the
interpreter, numba, xarray, and what the count leaves out)."""


def _physical_memory() -> int | None:
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        return None


def fits_in_memory(what: str, nbytes: float) -> None:
    """Refuse, before any work, a run whose largest arrays (``nbytes``, the caller's count
    of what it allocates) would not fit this machine's physical memory: numpy's
    ``MemoryError`` came after the points run before it in the same call, and named no
    argument. ``what`` names the arguments that set the size."""
    total = _physical_memory()
    if total is not None and nbytes > MEMORY_FRACTION * total:
        raise ValueError(
            f"{what} would need about {nbytes / 2**30:.3g} GiB of arrays, more than "
            f"{MEMORY_FRACTION:.0%} of this machine's {total / 2**30:.3g} GiB of memory"
        )


def integer(name: str, value: Any, minimum: int, maximum: int | None = None) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    if value < minimum or (maximum is not None and value > maximum):
        allowed = f">= {minimum}" if maximum is None else f"in [{minimum}, {maximum}]"
        raise ValueError(f"{name} = {value} is not allowed: must be {allowed}")
    return int(value)


def seed(value: Any) -> int:
    """A random seed: an integer in [0, 2**63 - 1] (``kinetic.seeds.MAX_SEED``, what a
    netCDF attribute holds; a larger one ran, then failed at the write)."""
    from kinetic.seeds import MAX_SEED

    return integer("seed", value, 0, MAX_SEED)


def realizations(
    first: Any, count: Any, *, first_name: str = "first_realization", count_name: str
) -> tuple[int, int]:
    """Realizations ``first .. first + count - 1`` of a run: ``count`` >= 1, ``first`` >= 0
    and the last index at most ``kinetic.seeds.MAX_SEED``, since a dataset's
    ``realization`` coordinate is int64 (an index of 2**64 ran the whole simulation, then
    failed at the write). Returns ``(first, count)`` as Python integers."""
    from kinetic.seeds import MAX_SEED

    count = integer(count_name, count, 1)
    first = integer(first_name, first, 0)
    if first + count - 1 > MAX_SEED:
        raise ValueError(
            f"{first_name} = {first} with {count_name} = {count} is not allowed: the last "
            f"realization's index, {first + count - 1}, must be <= {MAX_SEED} (2**63 - 1, "
            "a dataset's int64 realization coordinate)"
        )
    return first, count


def real(
    name: str,
    value: Any,
    low: float,
    high: float,
    *,
    low_open: bool = False,
    high_open: bool = False,
    unit: str = "",
) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise TypeError(f"{name} must be a real number, got {value!r}")
    value = float(value)
    below = value <= low if low_open else value < low
    above = value >= high if high_open else value > high
    if not math.isfinite(value) or below or above:
        interval = f"{'(' if low_open else '['}{low:g}, {high:g}{')' if high_open else ']'}"
        raise ValueError(f"{name} = {value!r}{unit} is outside the allowed range {interval}{unit}")
    return value


def choice(name: str, value: Any, choices: Sequence[str]) -> str:
    if value not in choices:
        raise ValueError(f"{name} = {value!r} is not allowed: must be one of {', '.join(choices)}")
    return value


def multiple(name: str, value: float, unit_name: str, unit: float) -> int:
    """``value / unit`` as an integer >= 1, or an error naming both."""
    ratio = value / unit
    count = round(ratio)
    if count < 1 or abs(ratio - count) > 1e-9 * max(1.0, ratio):
        raise ValueError(
            f"{name} = {value!r} must be a whole multiple (>= 1) of {unit_name} = {unit!r}"
        )
    return int(count)
