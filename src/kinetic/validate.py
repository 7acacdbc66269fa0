"""Argument checks shared by the engines' fronts: each raises before any work, naming the
argument, its value and what is allowed (``TypeError`` for a wrong type, ``ValueError``
for a value out of range)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = ["choice", "integer", "multiple", "real", "seed"]


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
