"""Argument checks of the event-driven MD, without the engine: numpy only.

The fronts call them before any work, and the workflow calls them while it reads the
config (no compiled kernel is loaded for that):

- ``check_system``: every argument of ``HardSphereSystem`` (``HardSphereSystem.validated``);
- ``check_simulate``: every argument of ``kinetic.edmd.simulate``;
- ``cell_grid``: the cell-list grid of a box, refused when a periodic axis holds fewer
  than three cells;
- ``packing_fraction`` and the limits the checks use.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np

from kinetic import validate
from kinetic.seeds import checked_stream, stream_states

__all__ = [
    "CLOSE_PACKING",
    "DEFAULT_CELL_OCCUPANCY",
    "GATHER_HEAD",
    "PREFETCH_MIN_PARTICLES",
    "RANDOM_INSERTION_LIMIT",
    "SystemArguments",
    "cell_grid",
    "check_simulate",
    "check_system",
    "packing_fraction",
]

#: packing fraction above which random sequential insertion is refused (jamming of RSA is
#: 0.547 in d = 2 and 0.38 in d = 3); pass explicit positions beyond
RANDOM_INSERTION_LIMIT = {2: 0.45, 3: 0.30}
#: close packing: no configuration exists beyond
CLOSE_PACKING = {2: math.pi / (2 * math.sqrt(3)), 3: math.pi / (3 * math.sqrt(2))}
#: default mean number of particles per cell by dimension (tuned with
#: ``python -m kinetic.bench edmd``: fewer cells cost crossings, more particles per cell cost
#: pair tests; 27 neighbour cells in d = 3 against 9 in d = 2)
DEFAULT_CELL_OCCUPANCY = {2: 2.0, 3: 0.7}


#: systems of at least that many particles prefetch the rows and cells of the coming
#: events (their rows outgrow the L2 cache; for smaller ones the prefetch is pure overhead;
#: see kernels.prefetch_ahead), from the second size on also the rows of the neighbour
#: scans' candidates (2D, ρσ² = 1e-2, speeds of levels 2/1/0 in one process relative to
#: level 1: N = 2e4 0.87/1/0.96, N = 3e4 1.2/1/0.8, N = 1e5 1.5/1/0.67)
PREFETCH_MIN_PARTICLES = (10_000, 30_000)


#: entries copied unconditionally from each cell row by the neighbour scan (≤ row capacity)
GATHER_HEAD = 4


def packing_fraction(density: float, dimension: int, diameter: float = 1.0) -> float:
    """Fraction of space covered: ρ π σ²/4 in d = 2, ρ π σ³/6 in d = 3."""
    if dimension == 2:
        return density * math.pi * diameter**2 / 4.0
    return density * math.pi * diameter**3 / 6.0


def cell_grid(
    box: Sequence[float],
    diameter: float,
    density: float,
    dimension: int,
    occupancy: float,
    walls: Sequence[bool],
) -> np.ndarray:
    """Cells per side: width ≈ (occupancy/ρ)^{1/d} (the mean free path scale at low
    density, since l ∝ 1/(ρσ^{d−1})), never below σ, at least 3 on periodic axes."""
    target = (occupancy / density) ** (1.0 / dimension)
    counts = np.ones(3, dtype=np.int64)
    for axis in range(dimension):
        length = box[axis]
        width = max(target, diameter * (1.0 + 1e-9))
        n = max(int(length / width), 1)
        # the cell width L/n must stay ≥ σ (with margin for round-off)
        while n > 1 and length / n < diameter * (1.0 + 1e-9):
            n -= 1
        if not walls[axis] and n < 3 and length / 3 >= diameter * (1.0 + 1e-9):
            n = 3
        if not walls[axis] and n < 3:
            raise ValueError(
                f"periodic box side {length} holds {n} cell(s) of width ≥ σ = {diameter}; "
                f"a periodic axis needs at least 3 (side ≥ {3 * diameter * (1 + 1e-9)})"
            )
        counts[axis] = n
    return counts


def _number(name, value):
    """``value`` as a float if it is a real number (not a bool, not a string)."""
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise TypeError(f"{name} must be a number, got {value!r}")
    return float(value)


def _finite_positive(name, value):
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise TypeError(f"{name} must be a number, got {value!r}")
    if not math.isfinite(value) or value <= 0:
        raise ValueError(f"{name} must be finite and > 0, got {value}")
    return float(value)


class SystemArguments(NamedTuple):
    """The constructor's arguments after ``HardSphereSystem.validated``: box side lengths
    from the density, walls per axis, the random stream, cell settings, and the packing
    fraction ``eta`` of the accessible volume."""

    n_particles: Any
    dimension: Any
    density: Any
    box: Any
    diameter: Any
    walls: Any
    restitution: Any
    contact_time: Any
    collapse_time: Any
    collapse_streak: Any
    rescale_every: Any
    temperature: Any
    positions: Any
    velocities: Any
    stream: Any
    cell_occupancy: Any
    cell_capacity: Any
    sort_every: Any
    prefetch: Any
    eta: Any


def check_system(
    *,
    n_particles: int,
    dimension: int = 2,
    density: float | None = None,
    box: Sequence[float] | None = None,
    diameter: float = 1.0,
    walls: bool | Sequence[bool] = False,
    restitution: float = 1.0,
    contact_time: float = 0.0,
    collapse_time: float | None = None,
    collapse_streak: int = 64,
    rescale_every: int = 0,
    temperature: float = 1.0,
    positions=None,
    velocities=None,
    seed: int | None = None,
    stream: np.ndarray | None = None,
    cell_occupancy: float | None = None,
    cell_capacity: int | None = None,
    sort_every: int = 0,
    prefetch: int | None = None,
) -> SystemArguments:
    """Check every argument of ``HardSphereSystem`` (same names and defaults) and return
    them normalized (box from the density, walls per axis, the random stream, the
    packing fraction ``eta``, ...), allocating nothing: fronts call it to refuse bad
    input before any work. Raises ``TypeError``/``ValueError`` naming the argument."""
    if isinstance(n_particles, bool) or not isinstance(n_particles, int | np.integer):
        raise TypeError(f"n_particles must be an integer, got {n_particles!r}")
    if n_particles < 2:
        raise ValueError(f"n_particles must be >= 2, got {n_particles}")
    # positions, velocities, event calendar and cells: about 450 B a particle (kinetic.cost)
    validate.fits_in_memory(f"n_particles = {n_particles}", 450.0 * n_particles)
    integral = isinstance(dimension, int | np.integer) and not isinstance(dimension, bool)
    if not integral or dimension not in (2, 3):
        raise ValueError(f"dimension must be 2 or 3, got {dimension!r}")
    dimension = int(dimension)
    diameter = _finite_positive("diameter", diameter)
    # far from overflow: velocities of T = 1e308 squared to inf
    temperature = validate.real("temperature", temperature, 1e-100, 1e100)
    if cell_occupancy is None and dimension in DEFAULT_CELL_OCCUPANCY:
        cell_occupancy = DEFAULT_CELL_OCCUPANCY[dimension]
    cell_occupancy = _finite_positive("cell_occupancy", cell_occupancy)
    if isinstance(sort_every, bool) or not isinstance(sort_every, int | np.integer):
        raise TypeError(f"sort_every must be an integer, got {sort_every!r}")
    if sort_every < 0:
        raise ValueError(f"sort_every must be >= 0 (0: never), got {sort_every}")
    if prefetch is None:
        prefetch = sum(n_particles >= size for size in PREFETCH_MIN_PARTICLES)
    if isinstance(prefetch, bool) or not isinstance(prefetch, int | np.integer):
        raise TypeError(f"prefetch must be an integer, got {prefetch!r}")
    if prefetch not in (0, 1, 2):
        raise ValueError(f"prefetch must be 0, 1 or 2, got {prefetch!r}")
    restitution = _number("restitution", restitution)
    if not (math.isfinite(restitution) and 0.0 < restitution <= 1.0):
        raise ValueError(f"restitution must be in (0, 1], got {restitution}")
    contact_time = _number("contact_time", contact_time)
    if not (math.isfinite(contact_time) and contact_time >= 0.0):
        raise ValueError(f"contact_time must be finite and >= 0, got {contact_time}")
    for name, value in (("collapse_streak", collapse_streak), ("rescale_every", rescale_every)):
        if isinstance(value, bool) or not isinstance(value, int | np.integer):
            raise TypeError(f"{name} must be an integer, got {value!r}")
    if collapse_time is None:
        collapse_time = 1e-7 * diameter / math.sqrt(temperature)
    collapse_time = _number("collapse_time", collapse_time)
    if not (math.isfinite(collapse_time) and collapse_time >= 0.0):
        raise ValueError(f"collapse_time must be finite and >= 0, got {collapse_time}")
    if int(collapse_streak) < 1:
        raise ValueError(f"collapse_streak must be >= 1, got {collapse_streak}")
    if cell_capacity is not None and not (GATHER_HEAD <= int(cell_capacity) <= 2**20):
        raise ValueError(f"cell_capacity must be in [{GATHER_HEAD}, 2**20], got {cell_capacity}")
    if int(rescale_every) < 0:
        raise ValueError(f"rescale_every must be >= 0, got {rescale_every}")
    if (density is None) == (box is None):
        raise ValueError("give exactly one of density (cubic box) or box (side lengths)")
    if density is not None:
        density = _finite_positive("density", density)
        side = (n_particles / density) ** (1.0 / dimension)
        box = [side] * dimension
    else:
        box = [_finite_positive("box side", float(x)) for x in np.ravel(box)]
        if len(box) != dimension:
            raise ValueError(f"box needs {dimension} side lengths, got {len(box)}")
        density = n_particles / math.prod(box)
    if isinstance(walls, bool | np.bool_):
        walls = [bool(walls)] * dimension
    flags = list(np.ravel(walls)) if not isinstance(walls, str) else [walls]
    if not all(isinstance(w, bool | np.bool_) for w in flags):
        raise TypeError(f"walls must be a bool or one bool per axis, got {walls!r}")
    walls = [bool(w) for w in flags]
    if len(walls) != dimension:
        raise ValueError(f"walls needs {dimension} flags, got {len(walls)}")
    # accessible volume: centres stay σ/2 away from walls
    accessible = math.prod(box[a] - (diameter if walls[a] else 0.0) for a in range(dimension))
    if any(box[a] - (diameter if walls[a] else 0.0) <= 0 for a in range(dimension)):
        raise ValueError(f"box {box} is narrower than one diameter {diameter} between walls")
    eta = packing_fraction(n_particles / accessible, dimension, diameter)
    if eta >= CLOSE_PACKING[dimension]:
        raise ValueError(
            f"{n_particles} particles of diameter {diameter} cannot fit in box {box}: "
            f"packing fraction {eta:.4g} >= close packing {CLOSE_PACKING[dimension]:.4g}"
        )
    if positions is None and eta > RANDOM_INSERTION_LIMIT[dimension]:
        raise ValueError(
            f"packing fraction {eta:.4g} is above {RANDOM_INSERTION_LIMIT[dimension]} "
            f"where random insertion is refused in d = {dimension}; pass positions"
        )
    if stream is None:
        if seed is None and (positions is None or velocities is None):
            raise ValueError("a seed (or stream) is needed for random initial conditions")
        stream = stream_states(0 if seed is None else seed, 1)[0]
    stream = checked_stream(stream)

    return SystemArguments(
        n_particles,
        dimension,
        density,
        box,
        diameter,
        walls,
        restitution,
        contact_time,
        collapse_time,
        collapse_streak,
        rescale_every,
        temperature,
        positions,
        velocities,
        stream,
        cell_occupancy,
        cell_capacity,
        sort_every,
        prefetch,
        eta,
    )


def _sequence(name, values, *, minimum=0.0, strictly_increasing=False):
    try:
        array = np.asarray(values, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a sequence of numbers, got {values!r}") from None
    if array.size == 0:
        raise ValueError(f"{name} must not be empty")
    if not np.all(np.isfinite(array)) or np.any(array <= minimum):
        raise ValueError(f"{name} must be finite and > {minimum}, got {list(array)}")
    if strictly_increasing and np.any(np.diff(array) <= 0):
        raise ValueError(f"{name} must be strictly increasing, got {list(array)}")
    return array


def check_simulate(
    *,
    n_particles: int,
    density: float,
    seed: int,
    realizations: int,
    first_realization: int = 0,
    dimension: int = 2,
    equilibration: float = 10.0,
    duration: float,
    windows: Sequence[float] = (1.0, 2.0, 5.0, 10.0, 20.0, 50.0),
    checkpoints: Sequence[float] | None = None,
    flight_time_max: float = 20.0,
    flight_time_bins: int = 200,
    free_path_max: float = 20.0,
    free_path_bins: int = 200,
    cell_occupancy: float | None = None,
    label: str | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Check every argument of ``kinetic.edmd.simulate`` (same names and defaults) before
    any work: raises ``TypeError``/``ValueError`` naming the argument; returns the windows
    and checkpoints as arrays. The workflow calls it when it reads the config, so a bad
    config is refused before any job."""
    validate.seed(seed)
    for name, value in (
        ("realizations", realizations),
        ("first_realization", first_realization),
        ("flight_time_bins", flight_time_bins),
        ("free_path_bins", free_path_bins),
    ):
        if isinstance(value, bool) or not isinstance(value, int | np.integer):
            raise TypeError(f"{name} must be an integer, got {value!r}")
    if realizations < 1:
        raise ValueError(f"realizations must be >= 1, got {realizations}")
    validate.realizations(first_realization, realizations, count_name="realizations")
    validate.integer("flight_time_bins", flight_time_bins, 1, validate.MAX_BINS)
    validate.integer("free_path_bins", free_path_bins, 1, validate.MAX_BINS)
    if dimension not in (2, 3):
        raise ValueError(f"dimension must be 2 or 3, got {dimension!r}")
    density = _finite_positive("density", density)
    for name, value in (
        ("equilibration", equilibration),
        ("duration", duration),
        ("flight_time_max", flight_time_max),
        ("free_path_max", free_path_max),
    ):  # a string reached math.isfinite, whose message named no argument
        if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
            raise TypeError(f"{name} must be a real number, got {value!r}")
    if not (math.isfinite(equilibration) and equilibration >= 1.0):
        raise ValueError(f"equilibration must be >= 1 collision per particle, got {equilibration}")
    if not (math.isfinite(duration) and duration > 0):
        raise ValueError(f"duration must be finite and > 0 mean free times, got {duration}")
    for name, value in (("flight_time_max", flight_time_max), ("free_path_max", free_path_max)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be finite and > 0, got {value}")
    windows = _sequence("windows", windows, strictly_increasing=True)
    if windows[-1] > duration:
        raise ValueError(f"the longest window {windows[-1]} exceeds duration {duration}")
    checkpoints = _sequence(
        "checkpoints", [duration] if checkpoints is None else checkpoints, strictly_increasing=True
    )
    if not math.isclose(checkpoints[-1], duration, rel_tol=1e-12):
        raise ValueError(f"the last checkpoint {checkpoints[-1]} must equal duration {duration}")
    # N, the packing fraction and the cells: the system's own checks, nothing built
    arguments = check_system(
        n_particles=n_particles,
        density=density,
        dimension=dimension,
        seed=0,
        cell_occupancy=cell_occupancy,
    )
    cell_grid(
        arguments.box,
        arguments.diameter,
        arguments.density,
        dimension,
        arguments.cell_occupancy,
        arguments.walls,
    )
    return windows, checkpoints
