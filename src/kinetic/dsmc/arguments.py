"""Argument checks of the homogeneous DSMC, without the engine: numpy only.

``simulate_homogeneous`` calls them before any work, and the workflow calls them on every
montanero2007 run while it reads the config (no compiled kernel is loaded for that), so a
value the front would refuse stops the build before its first job:

- ``check_settings``: the physics of one run (``HomogeneousSettings`` calls it);
- ``check_windows``: the run's clock, its windows and where the histograms start;
- the limits both use.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from kinetic import gas as units
from kinetic import validate

__all__ = [
    "FORCE_STEPS",
    "LINEAR_RESPONSE_FIELD",
    "MAX_COLLISIONS_PER_STEP",
    "MAX_FIELD_STEP",
    "MAX_REDUCED_FIELD",
    "SELECTIONS",
    "SPLITTINGS",
    "Windows",
    "check_settings",
    "check_windows",
    "collision_frequency",
]

FORCE_STEPS = ("euler", "exact")
SPLITTINGS = ("lie", "strang")
SELECTIONS = ("ntc", "poisson")

MAX_COLLISIONS_PER_STEP = 0.5
"""Largest mean number of collisions per particle in one time step (δt ν <= 0.5)."""

MAX_REDUCED_FIELD = 0.2
"""Largest ε* accepted (linear response needs ε* << 1; the paper uses 0.025). Beyond it the
particles moving against the field run away between collisions faster than collisions
stop them, and a run ends with the force step's blow-up: 4 realizations of 20,000 elastic
spheres at δt = 0.1 τ stopped at 7 τ (ε* = 0.25, Euler), 12-22 τ (0.3) and 2-5 τ (0.4,
0.5), and ran 120 τ at 0.2 with either step."""

LINEAR_RESPONSE_FIELD = 0.1
"""Above this ε* a warning is logged (tests/physics/test_dsmc_extreme_cases.py) and the force
step is held to ``MAX_FIELD_STEP``."""

MAX_FIELD_STEP = 0.02
"""Largest ε* δt/τ above ``LINEAR_RESPONSE_FIELD`` (below it, the time step's own limit keeps
ε* δt <= 0.056, and ε* = 0.1 ran 120 τ at δt = 0.4 τ with either force step). Above it the
c_x distribution's tail is a power law (|c_x|^-5.5 at ε* = 0.2), and a step stops the run
once a particle passes |c_x| = 1/(ε* δt) (Euler) or 2/(ε* δt) (exact): at ε* δt = 0.08 an
Euler run of 8 × 10⁴ particles stopped at 90 τ, 0.04 ran 120 τ; 0.02 (the default config's
extreme runs) moves that threshold to |c_x| = 50, about 20 times rarer than at 0.04."""


def collision_frequency(kernel: str, dimension: int) -> float:
    """Equilibrium collisions per particle per τ at T0 (2/√π for hard spheres in d = 3),
    in the units of montanero2007 (λ = 1)."""
    density = 1.0 / (math.sqrt(2.0) * units.cross_section(dimension))
    omega = units.equilibrium_collision_frequency(kernel, dimension, density)
    return omega * units.montanero_time_unit(dimension, density)


def check_settings(
    *,
    n_particles,
    restitution,
    time_step,
    dimension,
    kernel,
    reduced_field,
    force_step,
    selection,
    splitting,
) -> None:
    """Refuse, with a message naming the argument, a run that ``HomogeneousSettings``
    cannot hold: N >= 2, α in (0, 1], d in {2, 3}, a known kernel, ε* in [0,
    MAX_REDUCED_FIELD], the choices, a time step of at most MAX_COLLISIONS_PER_STEP
    collisions per particle and, above LINEAR_RESPONSE_FIELD, a force step
    ε* δt <= MAX_FIELD_STEP."""
    validate.integer("dimension", dimension, 2, 3)
    validate.choice("kernel", kernel, units.KERNELS)
    validate.integer("n_particles", n_particles, 2)
    validate.real("restitution", restitution, 0.0, 1.0, low_open=True)
    validate.real("reduced_field", reduced_field, 0.0, MAX_REDUCED_FIELD)
    validate.choice("force_step", force_step, FORCE_STEPS)
    validate.choice("selection", selection, SELECTIONS)
    validate.choice("splitting", splitting, SPLITTINGS)
    frequency = collision_frequency(kernel, int(dimension))
    limit = MAX_COLLISIONS_PER_STEP / frequency
    if isinstance(time_step, bool) or not isinstance(
        time_step, int | float | np.integer | np.floating
    ):
        raise TypeError(f"time_step must be a real number, got {time_step!r}")
    if not (math.isfinite(time_step) and 0.0 < time_step <= limit):
        raise ValueError(
            f"time_step = {time_step!r} τ is not allowed: must be in (0, {limit:.4g}] τ "
            f"(at most {MAX_COLLISIONS_PER_STEP} collisions per particle per step; the "
            f"collision time is {1.0 / frequency:.4g} τ)"
        )
    # a relative margin: 0.2 x 0.1 is 0.020000000000000004 in floating point
    beyond_linear = reduced_field > LINEAR_RESPONSE_FIELD
    if beyond_linear and reduced_field * time_step > MAX_FIELD_STEP * (1.0 + 1e-9):
        raise ValueError(
            f"reduced_field * time_step = {reduced_field!r} x {time_step!r} τ is "
            f"too large a force step: must be <= {MAX_FIELD_STEP} at reduced_field > "
            f"{LINEAR_RESPONSE_FIELD}, where the c_x tail is a power law (reduce time_step "
            f"to <= {MAX_FIELD_STEP / reduced_field:.4g} τ)"
        )


class Windows(NamedTuple):
    """The run's clock from ``check_windows`` (times in τ)."""

    duration: float
    sample_interval: float
    steps_per_window: int
    n_windows: int
    histogram_start: float
    first_histogram_window: int


def check_windows(*, duration, sample_interval, time_step, sample_stride, histogram_start):
    """The run's clock: ``duration`` and ``sample_interval`` whole multiples of the window
    and of ``time_step``, ``sample_stride`` within a window's steps, and the histograms'
    start (default: half the duration) a time in [0, duration) that leaves at least one
    whole window to histogram (it is rounded up to a window boundary, the ``Windows``'
    ``histogram_start``). Returns a ``Windows``."""
    duration = validate.real("duration", duration, 0.0, 1e12, low_open=True, unit=" τ")
    sample_interval = validate.real(
        "sample_interval", sample_interval, 0.0, duration, low_open=True, unit=" τ"
    )
    steps_per_window = validate.multiple("sample_interval", sample_interval, "time_step", time_step)
    n_windows = validate.multiple("duration", duration, "sample_interval", sample_interval)
    validate.integer("sample_stride", sample_stride, 1, steps_per_window)
    if histogram_start is None:
        histogram_start = 0.5 * duration
    histogram_start = validate.real(
        "histogram_start", histogram_start, 0.0, duration, high_open=True, unit=" τ"
    )
    first_histogram_window = math.ceil(histogram_start / sample_interval - 1e-9)
    if first_histogram_window >= n_windows:
        raise ValueError(
            f"histogram_start = {histogram_start!r} τ, rounded up to a window boundary "
            f"({first_histogram_window * sample_interval:.6g} τ), leaves no window of the "
            f"{duration:g} τ run to histogram: start at or before "
            f"{(n_windows - 1) * sample_interval:.6g} τ"
        )
    return Windows(
        duration,
        sample_interval,
        steps_per_window,
        n_windows,
        first_histogram_window * sample_interval,  # the start used, not the one asked for
        first_histogram_window,
    )
