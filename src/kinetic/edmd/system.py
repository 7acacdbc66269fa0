"""A system of hard disks (d = 2) or spheres (d = 3) advanced by event-driven MD.

``HardSphereSystem`` owns the preallocated state arrays of ``kinetic.edmd.layout`` and
validates everything before any work; ``run`` advances it in chunks. Units: m = 1, the
diameter and box in the same length unit, the temperature sets the velocity unit.

    system = HardSphereSystem(n_particles=1000, density=0.01, seed=1)
    system.run(until=100.0)
    system.positions(), system.velocities(), system.counters()
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from kinetic import validate
from kinetic.edmd import kernels as k
from kinetic.edmd.arguments import (  # noqa: F401  (re-exported)
    CLOSE_PACKING,
    DEFAULT_CELL_OCCUPANCY,
    PREFETCH_MIN_PARTICLES,
    RANDOM_INSERTION_LIMIT,
    SystemArguments,
    cell_grid,
    check_system,
    packing_fraction,
)
from kinetic.edmd.observers import Observers

__all__ = [
    "HardSphereSystem",
    "InelasticCollapseError",
    "cell_grid",
    "enskog_collision_frequency",
    "packing_fraction",
]


class InelasticCollapseError(RuntimeError):
    """Inelastic collapse: a particle collided more than ``collapse_streak`` times in a row
    with less than ``collapse_time`` between collisions (or the clock stalled).

    Attributes ``time``, ``collisions``, ``particles`` (the pair of the last collision) and
    ``system`` (the stopped system, its state valid up to ``time``).
    """

    def __init__(self, message, *, time, collisions, particles, system):
        super().__init__(message)
        self.time = time
        self.collisions = collisions
        self.particles = particles
        self.system = system


def contact_value(density: float, dimension: int, diameter: float = 1.0) -> float:
    """Pair correlation at contact χ: Henderson (d = 2) (1 − 7η/16)/(1 − η)², Carnahan–
    Starling (d = 3) (1 − η/2)/(1 − η)³."""
    eta = packing_fraction(density, dimension, diameter)
    if dimension == 2:
        return (1.0 - 7.0 * eta / 16.0) / (1.0 - eta) ** 2
    return (1.0 - eta / 2.0) / (1.0 - eta) ** 3


def enskog_collision_frequency(
    density: float, dimension: int, temperature: float = 1.0, diameter: float = 1.0
) -> float:
    """Collisions per particle per unit time, ω = χ ρ σ^{d−1} ⟨g⟩ Ω_d/... in closed form:
    d = 2: 2√π ρσ√T χ; d = 3: 4√π ρσ²√T χ (m = 1)."""
    chi = contact_value(density, dimension, diameter)
    if dimension == 2:
        return 2.0 * math.sqrt(math.pi) * density * diameter * math.sqrt(temperature) * chi
    return 4.0 * math.sqrt(math.pi) * density * diameter**2 * math.sqrt(temperature) * chi


class HardSphereSystem:
    """N hard disks/spheres in a box, periodic or with hard walls, restitution α.

    Parameters (keyword-only)
    -------------------------
    n_particles : int ≥ 2
    dimension : 2 or 3
    density : number density N/V (ρσ^d); give either ``density`` (square/cubic box) or
        ``box`` (side lengths, d values).
    diameter : σ > 0 (default 1).
    walls : bool or sequence of d bools: hard walls along each axis (default periodic).
        Centres stay in [σ/2, L − σ/2] along wall axes.
    restitution : α in (0, 1] (1: elastic).
    contact_time : TC model of Luding and McNamara: a collision in which either particle
        collided less than ``contact_time`` before is elastic (0: off). Avoids inelastic
        collapse at the price of a slight change of the dissipation.
    collapse_time, collapse_streak : inelastic collapse is reported (InelasticCollapseError)
        when a particle has more than ``collapse_streak`` consecutive collisions separated by
        less than ``collapse_time`` (default 1e-7 σ/√T).
    rescale_every : thermostat: every that many collisions all velocities are rescaled to
        ``temperature`` (0: off; the stationary representation of the cooling state).
    temperature : T of the initial velocities (exact: Σv² = d N T, zero total momentum).
    positions, velocities : optional (N, d) initial state (validated: inside the box, no
        overlap, finite); otherwise random sequential insertion and Maxwellian velocities.
    seed : integer seed, or ``stream``: one row of ``kinetic.rng.stream_states``.
    cell_occupancy : mean particles per cell (> 0) sets the cell width (see ``cell_grid``);
        default ``DEFAULT_CELL_OCCUPANCY[dimension]``.
    cell_capacity : initial slots per cell row (default from the occupancy); rows double
        whenever one overflows, so this only matters for speed (and tests).
    sort_every : re-sort the particles in memory along the Z-order curve of their cells
        every that many collisions (``sort_particles``; 0, the default: never). With the
        prefetch pipeline it no longer pays: every 2 N collisions cost 8 % at N = 1e5 and
        11 % at 5e4 (2D, ρσ² = 1e-2; 5 % at 1e-3, 2 % in 3D), measured in one process.
        The dynamics stay the same, but runs split at the re-sorts, and each kernel call
        rebases the clock: round-off then differs from a run without re-sorting.
    prefetch : 0 none, 1 the rows and cells of the coming events, 2 also the neighbour
        scans' candidates (see ``kernels.prefetch_ahead``); default by N
        (``PREFETCH_MIN_PARTICLES``). Hints only: the dynamics do not depend on it.
    """

    validated = staticmethod(check_system)

    def __init__(
        self,
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
    ):
        # ----------------------------------------------------------- validation
        # the parameters are the only locals yet besides self: check them all by name
        arguments = self.validated(**{k: v for k, v in locals().items() if k != "self"})
        (
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
        ) = arguments

        self.n_particles = int(n_particles)
        self.dimension = int(dimension)
        self.box = np.array(box, dtype=float)
        self.walls = np.array(walls, dtype=bool)
        self.diameter = diameter
        self.density = float(density)
        self.restitution = restitution
        self.temperature = temperature
        self.stream = stream

        # ----------------------------------------------------------- state arrays
        n = self.n_particles
        counts = cell_grid(box, diameter, self.density, dimension, cell_occupancy, walls)
        length3 = np.ones(3)
        length3[:dimension] = box
        self.grid = np.zeros(k.N_GRID, dtype=np.int64)
        self.grid[0:3] = counts
        self.grid[k.I_DIM] = dimension
        self.grid[k.I_WALL : k.I_WALL + dimension] = walls
        self.grid[k.I_STREAK] = int(collapse_streak)
        self.grid[k.I_RESCALE] = int(rescale_every)
        self.grid[k.I_PREFETCH] = prefetch
        self.geometry = np.zeros(k.N_GEOMETRY)
        self.geometry[k.G_L : k.G_L + 3] = length3
        self.geometry[k.G_W : k.G_W + 3] = length3 / counts
        self.geometry[k.G_SIGMA] = diameter
        self.geometry[k.G_SIGMA2] = diameter * diameter
        self.geometry[k.G_ALPHA] = restitution
        self.geometry[k.G_CONTACT] = contact_time
        self.geometry[k.G_COLLAPSE_TIME] = collapse_time
        self.phase = _aligned_zeros((n, 8))
        # event data of each particle: see the layout in kinetic.edmd.layout
        self.ints = _aligned_zeros((n, 8), np.int64)
        self.n_cells = int(np.prod(counts))
        self.occupancy = np.zeros(self.n_cells, dtype=np.int32)
        if cell_capacity is None:
            # 16 int32 slots: one cache line per row; P(a cell holds more) < 1e-9 at the
            # default occupancies (a full row is grown by ``run``)
            cell_capacity = 16
            while cell_capacity < cell_occupancy + 7.0 * math.sqrt(cell_occupancy):
                cell_capacity *= 2
        self._allocate_rows(cell_capacity)
        # event calendar: see kinetic.edmd.calendar (N buckets + the overflow list)
        self.links = _aligned_zeros((n, 4), np.int32)
        self.heads = np.full(n + 1, -1, dtype=np.int32)
        self.heap_time = np.full(n, np.inf)
        self.heap_index = np.zeros(n, dtype=np.int32)
        self.calendar = np.array([0.0, 1.0])
        # current bucket, heap size, list positions of the prefetch pipeline
        self.cursor = np.full(k.N_CURSOR, -1, dtype=np.int64)
        self.cursor[:2] = 0
        self.last_collision = np.full(n, -np.inf)
        self.streak = np.zeros(n, dtype=np.int32)
        self.label = np.arange(n, dtype=np.int64)  # original particle number of slot i
        self.images = np.zeros((27, 3))  # position of a particle relative to cell images
        self.sort_every = int(sort_every)
        self._since_sort = 0
        self.counters_array = np.zeros(k.N_COUNTERS, dtype=np.int64)
        self.clock = np.zeros(1)
        self.time_origin = 0.0
        self._idle_observers = Observers.create(n)

        # ----------------------------------------------------------- initial state
        if positions is None:
            initial_stream = self.stream.copy()
            while True:
                placed = k.place_random(
                    self.phase,
                    self.ints,
                    self.members,
                    self.occupancy,
                    self.geometry,
                    self.grid,
                    self.stream,
                    10_000,
                )
                if placed >= 0:
                    break
                # a cell row overflowed: grow the rows and redo the same placement
                self.stream[:] = initial_stream
                self._allocate_rows(2 * self.members.shape[1])
            if placed < n:
                raise ValueError(
                    f"random insertion placed only {placed} of {n} particles (packing "
                    f"fraction {eta:.3g}); lower the density or pass positions"
                )
        else:
            self._set_positions(positions)
        if velocities is None:
            k.draw_velocities(self.phase, dimension, self.stream)
            v = self.phase[:, 3 : 3 + dimension]
            if not self.walls.any():
                v -= v.mean(axis=0)
            v *= math.sqrt(dimension * n * temperature / np.sum(v * v))
        else:
            v = np.asarray(velocities, dtype=float)
            if v.shape != (n, dimension) or not np.all(np.isfinite(v)):
                raise ValueError(f"velocities must be a finite ({n}, {dimension}) array")
            if not np.any(v):
                raise ValueError("velocities are all zero: no particle would ever move")
            self.phase[:, 3 : 3 + dimension] = v
        self._predict_all(0.0)
        if self.sort_every > 0:
            self.sort_particles()

    # --------------------------------------------------------------- set-up helpers
    def _set_positions(self, positions) -> None:
        n, d = self.n_particles, self.dimension
        x = np.asarray(positions, dtype=float)
        if x.shape != (n, d) or not np.all(np.isfinite(x)):
            raise ValueError(f"positions must be a finite ({n}, {d}) array, got shape {x.shape}")
        half = 0.5 * self.diameter
        for axis in range(d):
            lo, hi = (half, self.box[axis] - half) if self.walls[axis] else (0.0, self.box[axis])
            bad = np.flatnonzero(
                (x[:, axis] < lo) | (x[:, axis] > hi if self.walls[axis] else x[:, axis] >= hi)
            )
            if bad.size:
                raise ValueError(
                    f"particle {bad[0]} at {x[bad[0]]} is outside the box along axis {axis} "
                    f"(allowed [{lo}, {hi}]{']' if self.walls[axis] else ')'})"
                )
        self.phase[:, :d] = x
        while True:
            outside = k.build_cells(
                self.phase,
                self.ints,
                self.members,
                self.occupancy,
                self.geometry,
                self.grid,
                0.0,
            )
            if outside != -2:
                break
            self._allocate_rows(2 * self.members.shape[1])
        if outside >= 0:
            raise ValueError(f"particle {outside} lies outside the box")
        distance = self.min_distance()
        if distance < self.diameter * (1.0 - 1e-12):
            raise ValueError(
                f"initial configuration overlaps: closest centres {distance:.6g} apart, "
                f"diameter {self.diameter}"
            )

    # --------------------------------------------------------------- running
    def run(
        self,
        *,
        until: float | None = None,
        collisions: int | None = None,
        observers: Observers | None = None,
        max_events: int | None = None,
        scale: float = 1.0,
    ) -> int:
        """Advance to simulation time ``until`` and/or by ``collisions`` collisions,
        whichever comes first. Returns the kernel status (``kernels.STATUS_*``).

        ``scale``: then multiply every velocity by it, as :meth:`scale_velocities` after
        the run (the same numbers), in the pass that rebases the clock at ``until``: one
        calendar rebuild instead of two (the cooling gas of ``kinetic.edmd.cooling``
        scales after every segment).

        With ``sort_every`` > 0 the particles are re-sorted in memory by cell every that
        many collisions (see ``sort_particles``) between kernel calls. Use a single
        ``Observers`` object per system: its times are kept on the system's clock.

        Raises ``InelasticCollapseError`` on collapse or a stalled clock and
        ``RuntimeError`` if the event budget ``max_events`` (per kernel call) is exhausted.
        """
        if until is None and collisions is None:
            raise ValueError("give until (a time) and/or collisions (a count)")
        if until is not None and (
            isinstance(until, bool) or not isinstance(until, int | float | np.integer | np.floating)
        ):
            raise TypeError(f"until must be a real number (a time), got {until!r}")
        if until is not None and not (math.isfinite(until) and until >= self.time):
            raise ValueError(
                f"until must be finite and >= the current time {self.time}, got {until}"
            )
        if collisions is not None:
            collisions = validate.integer("collisions", collisions, 1)
        if max_events is not None:
            max_events = validate.integer("max_events", max_events, 1)
        scale = float(scale)
        if not (math.isfinite(scale) and scale > 0.0):
            raise ValueError(f"scale must be finite and > 0, got {scale}")
        observers = observers if observers is not None else self._idle_observers
        if observers.window_count.shape[0] != self.n_particles:
            raise ValueError("observers were created for a different number of particles")
        big = np.iinfo(np.int64).max
        remaining = big if collisions is None else int(collisions)
        # a count-limited run must not spin on crossings in a gas that stopped colliding
        # (e.g. after strong inelastic cooling): a kernel call gets a budget of events
        # (about 60 crossings a collision at ρσ² = 1e-4, 600 at 1e-6), and the default one
        # is renewed while the call before it collided at all
        renew = max_events is None and collisions is not None
        if max_events is None:
            max_events = big if collisions is None else 1000 * remaining + 100 * self.n_particles
        while True:
            chunk = remaining
            if self.sort_every > 0:
                chunk = min(chunk, max(self.sort_every - self._since_sort, 1))
            t_stop = np.inf if until is None else until - self.time_origin
            before = self.collisions
            status = k.advance(
                k.Run(t_stop, chunk, max_events, self.temperature, int(observers.observing)),
                self._state(),
                self._calendar_arrays(),
                observers.kernel_arguments(),
            )
            self._rebase(observers, scale if status == k.STATUS_TIME else 1.0)
            if status == k.STATUS_CELL_FULL:
                self._allocate_rows(2 * self.members.shape[1])
                self._relink()
                status = k.STATUS_COLLISIONS  # nothing wrong: continue
            done = self.collisions - before
            self._since_sort += done
            if remaining != big:
                remaining -= done
            if status == k.STATUS_EVENT_LIMIT and renew and done > 0:
                status = k.STATUS_COLLISIONS  # a dilute gas, still colliding: go on
            self._check(status, max_events)
            if self.sort_every > 0 and self._since_sort >= self.sort_every:
                self.sort_particles(observers)
            if status != k.STATUS_COLLISIONS or remaining <= 0:
                if scale != 1.0 and status != k.STATUS_TIME:  # not scaled by the rebase
                    self.scale_velocities(scale)
                return int(status)

    def _check(self, status: int, max_events: int) -> None:
        if status in (k.STATUS_COLLAPSE, k.STATUS_STALLED):
            slots = (
                int(self.counters_array[k.COUNT_COLLAPSE_PARTICLE]),
                int(self.counters_array[k.COUNT_COLLAPSE_PARTNER]),
            )
            pair = tuple(int(self.label[s]) if s >= 0 else -1 for s in slots)
            if status == k.STATUS_COLLAPSE:
                what = (
                    f"inelastic collapse at time {self.time:.10g} after {self.collisions} "
                    f"collisions: particle {pair[0]} (last partner {pair[1]}) collided more "
                    f"than {self.grid[k.I_STREAK]} times in a row less than "
                    f"{self.geometry[k.G_COLLAPSE_TIME]:.3g} apart"
                )
            else:
                what = (
                    f"stalled clock at time {self.time:.10g} after {self.collisions} "
                    f"collisions: more than {k.STALL_LIMIT} events at one time, the last of "
                    f"particle {pair[0]} and {pair[1]} (inelastic collapse or a degenerate "
                    "configuration)"
                )
            raise InelasticCollapseError(
                f"{what} (restitution {self.restitution}); contact_time > 0 (TC model) "
                "avoids a collapse",
                time=self.time,
                collisions=self.collisions,
                particles=pair,
                system=self,
            )
        if status == k.STATUS_EVENT_LIMIT:
            raise RuntimeError(
                f"event budget of {max_events} events exhausted at time {self.time} after "
                f"{self.collisions} collisions: the particles (almost) stopped colliding, "
                "or max_events is too small for the crossings between collisions"
            )

    def _allocate_rows(self, capacity: int) -> None:
        """(Re)allocate the cell rows with ``capacity`` slots each (and the scan scratch)."""
        self.members = np.zeros((self.n_cells, int(capacity)), dtype=np.int32)
        self.scratch = np.zeros(self.n_particles + int(capacity), dtype=np.int64)

    def _state(self) -> k.State:
        """The particles, cells, parameters and counters as the event loop takes them."""
        return k.State(
            self.clock,
            self.phase,
            self.ints,
            self.members,
            self.occupancy,
            self.last_collision,
            self.streak,
            self.label,
            self.scratch,
            self.images,
            self.geometry,
            self.grid,
            self.counters_array,
        )

    def _calendar_arrays(self) -> k.Calendar:
        """The event calendar's arrays in the order the kernels take them."""
        return k.Calendar(
            self.links,
            self.heads,
            self.heap_time,
            self.heap_index,
            self.calendar,
            self.cursor,
        )

    def _relink(self) -> None:
        """Refill the cell rows from the cell coordinates, growing them if needed."""
        while not k.relink_cells(self.ints, self.members, self.occupancy, self.grid):
            self._allocate_rows(2 * self.members.shape[1])

    def _predict_all(self, t: float) -> None:
        """Predict every event from kernel time t (pair tests not counted)."""
        tests = int(self.counters_array[k.COUNT_PAIR_TESTS])
        k.predict_all(t, self._state(), self._calendar_arrays())
        self.counters_array[k.COUNT_PAIR_TESTS] = tests

    def sort_particles(self, observers: Observers | None = None) -> None:
        """Renumber the memory slots along the Z-order (Morton) curve of the particles'
        cells, so that particles close in space are close in memory.

        A pure permutation: every state row moves with its particle, the predicted partners
        are renumbered and the calendar rebuilt, so the dynamics (the collision sequence)
        is unchanged. Particle identities are kept in ``label`` (read-outs are in label
        order); the per-particle arrays of ``observers`` are permuted along.
        """
        n = self.n_particles
        order = np.argsort(morton_code(self.ints[:, 5:8]), kind="stable")
        new_slot = np.empty(n, dtype=np.int64)
        new_slot[order] = np.arange(n)
        for array in (self.phase, self.ints, self.last_collision, self.streak, self.label):
            array[:] = array[order]
        partner = self.ints[:, 0]
        partner[:] = np.where(partner >= 0, new_slot[partner], -1)
        for obs in {
            id(self._idle_observers): self._idle_observers,
            id(observers): observers,
        }.values():
            if obs is not None and obs.window_count.shape[0] == n:
                obs.window_count[:] = obs.window_count[order]
        self._relink()
        k.calendar_build(self.phase, *self._calendar_arrays())
        self._since_sort = 0

    def _rebase(self, observers: Observers, factor: float = 1.0) -> None:
        """Move the time origin to the clock (``k.rebase``), then multiply every velocity
        by ``factor`` (as :meth:`scale_velocities`, in the same pass)."""
        t = float(self.clock[0])
        if t == 0.0 or not math.isfinite(t):
            if factor != 1.0:
                self.scale_velocities(factor)
            return
        k.rebase(
            t,
            factor,
            self.dimension,
            self._state(),
            self._calendar_arrays(),
            observers.kernel_arguments(),
        )
        self.time_origin += t
        self.clock[0] = 0.0

    def scale_velocities(self, factor: float) -> None:
        """Multiply every velocity by ``factor`` (> 0) at the current time.

        Hard-core dynamics only changes its time scale: positions stay continuous and every
        pending event time t_e maps to t + (t_e − t)/factor (no prediction is redone; the
        calendar is rebuilt). Used by the stationary representation of the cooling state
        (``kinetic.edmd.cooling``), where the factor is prescribed, not a target temperature.
        """
        factor = float(factor)
        if not (math.isfinite(factor) and factor > 0.0):
            raise ValueError(f"factor must be finite and > 0, got {factor}")
        t = float(self.clock[0])
        current = k.temperature(self.phase, self.dimension)
        if current <= 0.0:
            return
        k.rescale_velocities(t, factor * factor * current, self.phase, self.dimension)
        finite = np.isfinite(self.last_collision)
        self.last_collision[finite] = t + (self.last_collision[finite] - t) / factor
        k.calendar_build(self.phase, *self._calendar_arrays())

    def remove_drift(self) -> np.ndarray:
        """Subtract the centre-of-mass velocity from every particle (periodic boxes) and
        predict every event anew; returns the velocity removed.

        A uniform shift leaves every pair's relative motion unchanged but moves the cell
        crossings, hence the full prediction. In the stationary representation of the
        cooling state the drag amplifies round-off momentum exponentially; the front calls
        this whenever the drift exceeds round-off by a few orders.
        """
        if self.walls.any():
            raise ValueError("remove_drift needs a periodic box (walls do not conserve momentum)")
        d = self.dimension
        t = float(self.clock[0])
        drift = self.phase[:, 3 : 3 + d].mean(axis=0)
        self.phase[:, :d] += drift * t  # positions stay continuous at t
        self.phase[:, 3 : 3 + d] -= drift
        self._predict_all(t)
        return drift

    # --------------------------------------------------------------- read-out
    @property
    def time(self) -> float:
        """Current simulation time."""
        return self.time_origin + float(self.clock[0])

    @property
    def collisions(self) -> int:
        return int(self.counters_array[k.COUNT_COLLISIONS])

    def counters(self) -> dict[str, int]:
        """Event counts since creation."""
        c = self.counters_array
        return {
            "collisions": int(c[k.COUNT_COLLISIONS]),
            "crossings": int(c[k.COUNT_CROSSINGS]),
            "wall_hits": int(c[k.COUNT_WALL_HITS]),
            "invalid_events": int(c[k.COUNT_INVALID]),
            "pair_tests": int(c[k.COUNT_PAIR_TESTS]),
            "events": int(c[k.COUNT_EVENTS]),
            "rescalings": int(c[k.COUNT_RESCALES]),
            "inelastic_collisions": int(c[k.COUNT_INELASTIC]),
        }

    def positions(self) -> np.ndarray:
        """(N, d) positions at the current time (inside the box up to round-off)."""
        d = self.dimension
        t = float(self.clock[0])
        out = np.empty((self.n_particles, d))
        out[self.label] = self.phase[:, :d] + self.phase[:, 3 : 3 + d] * t
        return out

    def velocities(self) -> np.ndarray:
        """(N, d) velocities (a copy, in label order)."""
        out = np.empty((self.n_particles, self.dimension))
        out[self.label] = self.phase[:, 3 : 3 + self.dimension]
        return out

    def kinetic_temperature(self) -> float:
        """Σ v² / (d N)."""
        return float(k.temperature(self.phase, self.dimension))

    def min_distance(self) -> float:
        """Smallest centre distance (periodic images included) at the current time."""
        return float(
            k.min_pair_distance(
                self.phase,
                self.ints,
                self.members,
                self.occupancy,
                self.geometry,
                self.grid,
                float(self.clock[0]),
            )
        )

    @property
    def cells_per_side(self) -> np.ndarray:
        return self.grid[: self.dimension].copy()


def morton_code(cells: np.ndarray) -> np.ndarray:
    """Z-order index of integer cell coordinates (M, 3) (bits of the three axes interleaved,
    x lowest; coordinates below 2^21)."""
    code = np.zeros(cells.shape[0], dtype=np.int64)
    for bit in range(21):
        for axis in range(3):
            code |= ((cells[:, axis].astype(np.int64) >> bit) & 1) << (3 * bit + axis)
    return code


def _aligned_zeros(shape, dtype=np.float64, alignment: int = 64) -> np.ndarray:
    """Zeroed array whose data starts on an ``alignment``-byte boundary (a particle row of
    64 bytes is then one cache line)."""
    count = int(np.prod(shape))
    size = np.dtype(dtype).itemsize
    raw = np.zeros(count + alignment // size, dtype=dtype)
    offset = (-raw.ctypes.data % alignment) // size
    return raw[offset : offset + count].reshape(shape)
