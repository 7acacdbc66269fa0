"""Front of the inhomogeneous DSMC engine (costantini2010): ``simulate_cooling_modes``.

N real inelastic hard disks (d = 2, m = σ = 1) in a periodic square box of side
L = √(N/n), simulated by Λ N fictive particles in M x M equal square collision cells, in
the stationary representation of the homogeneous cooling state: between collisions
dr/dτ = w and dw/dτ = +ω0 w, so that the temperature relaxes to T_s with ζ(T_s) = 2 ω0
instead of cooling. The step (streaming with drag, counting sort by cell, collisions,
centre-of-mass removal) and the two collision rules ("paper": the Appendix's fixed
number ½ N_c ω_c(T_c) Δτ of collisions per cell and step; "majorant": Bird's scheme
with a rigorous relative-speed majorant) are described in
:mod:`kinetic.dsmc.inhomogeneous_kernels`. M = 1 is the paper's "homogeneous DSMC"
(same engine, positions kept so that the modes can be measured).

Units: m = σ = 1, initial temperature T0 = 1, time in σ √(m/T0). The collision frequency
is ω_c(T) = 2 n σ √(πT/m), the mean free path λ = 1/(2√2 n σ).

The dataset follows the "cooling modes" contract shared with the event-driven MD
engine (same variable names); the DSMC adds per realization ``candidates``,
``particle_steps`` and ``repeated_collisions`` (collisions whose two partners' previous
collisions were with each other: the molecular-chaos diagnostic, to plot against the
real particles per cell N/M²).

Sampling point: a step is a Lie splitting, streaming with the drag (T x e^{2ω0Δτ}) and
then the collisions, and the kernels observe after the collisions, the step's lowest T.
The dataset reports the velocities half a drag later (w x e^{ω0Δτ/2}: ``temperature`` and
``mode_norm`` x e^{ω0Δτ}, the modes x e^{ω0Δτ/2}; positions stay where they were
observed, a shift of the modes' phases by k w Δτ/2), which is where Strang's splitting
(half a drag, the collisions, half a drag) samples the same trajectory: T there is the
step's time average to O(Δτ²) in every regime, and the dissipation over T that ζ* is
measured from is 2 sinh(ω0Δτ)/Δτ = 2ω0(1 + (ω0Δτ)²/6), against (e^{2ω0Δτ} - 1)/Δτ =
2ω0(1 + ω0Δτ) over the lowest T. What first-order error is left is the collisions':
- the majorant rule, where a cell makes many collisions a step, cools the gas through
  the step as the Boltzmann equation does, and T_s is right to O(Δτ²) (one cell of
  4000 simulated particles: flat within ± 0.0006 from Δτ = 0.1 to 0.0125 mean free
  times, where the lowest T rises by 0.0080);
- where a cell makes about one collision a step or fewer (the documents' cells of half
  a mean free path), the collisions act on the step's heated state, and T_s is about
  2ω0Δτ low (one cell of N = 100 at Λ = 1: T rises by 0.0016 ± 0.0005 from Δτ = 0.0125
  to 0.003125 mean free times, 2ω0 δ(Δτ) = 0.0017; the lowest T by 0.0025);
- the paper's rule draws a step's collisions at the rate of its heated T, so T_s(Δτ) =
  T_s(0) e^{-ω0Δτ} at the reported point (``test_costantini2010_time_step``).
``CoolingModesGas.observables`` is the kernels' observer (after the collisions).

Lower level (tests, studies that read the particles): ``CoolingModesSettings``
(validated engine parameters), ``new_cooling_gas`` (one realization's state) and the
``CoolingModesGas`` methods ``advance``, ``observables``, ``positions``,
``velocities``.
"""

from __future__ import annotations

import inspect
import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from kinetic import backends, io
from kinetic.dsmc import inhomogeneous_kernels as kernels
from kinetic.dsmc.state import realization_streams
from kinetic.gas import cell_changing_fraction
from kinetic.progress import Progress, logger
from kinetic.seeds import checked_stream
from kinetic.validate import choice, fits_in_memory, integer, real

__all__ = [
    "COLLISION_RULES",
    "HEATING_HEADROOM",
    "MAX_COLLISIONS_PER_STEP",
    "MAX_DRAG_PER_STEP",
    "SHARED_SETTINGS",
    "CoolingModesGas",
    "CoolingModesSettings",
    "check_heating",
    "initial_particles",
    "largest_temperature",
    "new_cooling_gas",
    "simulate_cooling_modes",
    "simulate_cooling_modes_points",
    "slack_per_cell",
]

COLLISION_RULES = ("paper", "majorant")
_RULE_ID = {"paper": kernels.RULE_PAPER, "majorant": kernels.RULE_MAJORANT}

MAX_COLLISIONS_PER_STEP = 0.1
"""Largest ω_c(T0) Δτ: mean collisions per particle per step at the initial temperature."""

MAX_DRAG_PER_STEP = 0.1
"""Largest ω0 Δτ: the drag's relative velocity change over one step."""

CLOSE_PACKING_DENSITY = 2.0 / math.sqrt(3.0)
"""Largest n σ² of disks (hexagonal close packing, packing fraction π/(2√3)): the DSMC's
particles are points, so it ran a gas of n σ² = 5 that no arrangement of disks can hold;
the EDMD refuses the same densities (``kinetic.edmd.arguments.CLOSE_PACKING``)."""

HEATING_HEADROOM = 1.1
"""How far above MAX_COLLISIONS_PER_STEP a run's step may go at the largest temperature
its drag heats it to (``largest_temperature``): that temperature comes from Eq. 12, whose
ζ* differs by up to 1 % between the two a2 closures, and a gas of N particles settles
about 1/N above it, so that a run that holds T near T0 at a step on the T0 limit passes,
while a drag that heats the gas to T_s > 1.21 T0 (or an elastic gas with drag, which heats
without end) is refused."""

SHARED_SETTINGS = (
    "n_particles",
    "density",
    "fictive_factor",
    "cells_per_side",
    "time_step",
    "collision_rule",
)
"""Settings that runs sharing GPU launches (``simulate_cooling_modes_points``) must share:
the batch's array shapes, its cells and its step; restitution and drag rate may differ."""

_ROUNDING = 1.0 + 1e-12
"""A step given in mean free times lands on a limit up to rounding: the limit is allowed."""

MAX_SIMULATED_PARTICLES = 50_000_000
"""Largest Λ N (memory: 48 bytes a slot and 88 a particle, with 1.3-3 slots a particle at
four or more simulated particles a cell and 1 + 5/mean below, ``slack_per_cell``)."""

MAX_CELLS_PER_SIDE = 10_000

MAX_LAYOUT_BYTES = 16 * 2**30
"""Largest memory of one realization's arrays (``CELL_BYTES`` a cell, ``PARTICLE_BYTES`` a
simulated particle): 10⁴ cells a side of 100 particles passed validation and would have
allocated about 25 GB."""

CELL_BYTES = 256
"""A cell's memory: its start, count, carry and moments (64 bytes) and at least 4 free slots
of 48 bytes (``slack_per_cell``)."""

PARTICLE_BYTES = 232
"""A simulated particle's memory: 88 bytes and up to 3 slots of 48."""

CHUNK_PARTICLE_STEPS = 50_000_000
"""Particle steps per kernel call between two progress lines (about half a second)."""

MODES = ("wy_kx", "wx_ky")
_TIME_UNIT = "sigma*sqrt(m/T0)"


_CPU_SECONDS = {
    "cpu": "CPU (process) time of the realization in the kernels",
    "cuda": "wall time of the GPU run (all realizations together) per realization",
}


def _whole_steps(name: str, value: float, time_step: float, minimum: int) -> int:
    """``value / time_step`` as an integer >= minimum, or an error naming both."""
    ratio = value / time_step
    count = round(ratio)
    if count < minimum or abs(ratio - count) > 1e-9 * max(1.0, ratio):
        raise ValueError(
            f"{name} = {value!r} must be a whole multiple (>= {minimum}) of "
            f"time_step = {time_step!r} (it is {ratio:.6g} time steps)"
        )
    return int(count)


@dataclass(frozen=True)
class CoolingModesSettings:
    """Validated engine parameters of one inhomogeneous DSMC run (module units).

    n_particles: N >= 2 real particles. density: n σ² in (0, 2/√3) (below close packing).
    restitution: α in (0, 1].
    drag_rate: ω0 >= 0. fictive_factor: Λ >= 1 (Λ N simulated particles).
    cells_per_side: M >= 1. time_step: Δτ > 0 with ω_c(T0) Δτ <= 0.1 and ω0 Δτ <= 0.1.
    collision_rule: "paper" or "majorant".
    """

    n_particles: int
    density: float
    restitution: float
    drag_rate: float
    fictive_factor: int
    cells_per_side: int
    time_step: float
    collision_rule: str

    def __post_init__(self) -> None:
        integer("n_particles", self.n_particles, 2)
        real("density", self.density, 0.0, math.inf, low_open=True, high_open=True)
        if self.density >= CLOSE_PACKING_DENSITY:
            raise ValueError(
                f"density = {self.density!r} is at or beyond the close packing of disks: "
                f"n sigma^2 must be < 2/sqrt(3) = {CLOSE_PACKING_DENSITY:.6g} (the Boltzmann "
                "DSMC is meant for n sigma^2 << 1)"
            )
        real("restitution", self.restitution, 0.0, 1.0, low_open=True)
        real("drag_rate", self.drag_rate, 0.0, math.inf, high_open=True)
        integer("fictive_factor", self.fictive_factor, 1)
        integer("cells_per_side", self.cells_per_side, 1, MAX_CELLS_PER_SIDE)
        choice("collision_rule", self.collision_rule, COLLISION_RULES)
        real("time_step", self.time_step, 0.0, math.inf, low_open=True, high_open=True)
        for name in ("n_particles", "fictive_factor", "cells_per_side"):
            object.__setattr__(self, name, int(getattr(self, name)))
        for name in ("density", "restitution", "drag_rate", "time_step"):
            object.__setattr__(self, name, float(getattr(self, name)))
        if self.n_simulated > MAX_SIMULATED_PARTICLES:
            raise ValueError(
                f"n_particles x fictive_factor = {self.n_particles} x {self.fictive_factor} = "
                f"{self.n_simulated} simulated particles is too many: must be <= "
                f"{MAX_SIMULATED_PARTICLES}"
            )
        cells = self.cells_per_side**2
        memory = CELL_BYTES * cells + PARTICLE_BYTES * self.n_simulated
        if memory > MAX_LAYOUT_BYTES:
            room = (MAX_LAYOUT_BYTES - PARTICLE_BYTES * self.n_simulated) // CELL_BYTES
            raise ValueError(
                f"cells_per_side = {self.cells_per_side} gives {cells} cells for "
                f"{self.n_simulated} simulated particles: about {memory / 2**30:.3g} GiB a "
                f"realization, more than {MAX_LAYOUT_BYTES / 2**30:g} GiB; use cells_per_side "
                f"<= {math.isqrt(max(1, room))}"
            )
        collisions = self.collision_frequency * self.time_step
        if collisions > MAX_COLLISIONS_PER_STEP * _ROUNDING:
            raise ValueError(
                f"time_step = {self.time_step!r} is too large: omega_c(T0) * time_step = "
                f"{self.collision_frequency:.6g} x {self.time_step!r} = {collisions:.4g} "
                f"collisions per particle per step, must be <= {MAX_COLLISIONS_PER_STEP} "
                f"(omega_c = 2 n sigma sqrt(pi T0/m) at density = {self.density!r}; use "
                f"time_step <= {MAX_COLLISIONS_PER_STEP / self.collision_frequency:.6g})"
            )
        drag = self.drag_rate * self.time_step
        if drag > MAX_DRAG_PER_STEP * _ROUNDING:
            raise ValueError(
                f"time_step = {self.time_step!r} is too large for drag_rate = "
                f"{self.drag_rate!r}: drag_rate * time_step = {drag:.4g} must be <= "
                f"{MAX_DRAG_PER_STEP} (use time_step <= "
                f"{MAX_DRAG_PER_STEP / self.drag_rate:.6g})"
            )

    @property
    def n_simulated(self) -> int:
        """N_sim = Λ N."""
        return self.n_particles * self.fictive_factor

    @property
    def box_side(self) -> float:
        """L = √(N/n)."""
        return math.sqrt(self.n_particles / self.density)

    @property
    def wavenumber(self) -> float:
        """k = 2π/L."""
        return 2.0 * math.pi / self.box_side

    @property
    def cell_side(self) -> float:
        return self.box_side / self.cells_per_side

    @property
    def real_particles_per_cell(self) -> float:
        """N/M²."""
        return self.n_particles / self.cells_per_side**2

    @property
    def collision_frequency(self) -> float:
        """ω_c(T0) = 2 n σ √(π T0/m)."""
        return 2.0 * self.density * math.sqrt(math.pi)

    @property
    def mean_free_path(self) -> float:
        """λ = 1/(2√2 n σ)."""
        return 1.0 / (2.0 * math.sqrt(2.0) * self.density)

    @property
    def changing_fraction(self) -> float:
        """The fraction of the particles expected to change cell a step at T0
        (``kinetic.gas.cell_changing_fraction``; 0 in one cell)."""
        return cell_changing_fraction(2, self.time_step, self.box_side, self.cells_per_side)

    @property
    def density_per_count(self) -> float:
        """1/(Λ A_c): a cell holding ``count`` simulated particles has real density
        count/(Λ A_c)."""
        return 1.0 / (self.fictive_factor * self.cell_side**2)

    @property
    def pair_coefficient(self) -> float:
        """Collision rate per pair of a cell per unit relative speed (rule "majorant"):
        S/(Λ A_c) x N_sim/(N_sim - 1), S = 2σ, so that each particle collides on average
        at exactly 2 n σ √(πT/m) (see :mod:`kinetic.dsmc.inhomogeneous_kernels`)."""
        n_sim = self.n_simulated
        return kernels.CROSS_SECTION * self.density_per_count * n_sim / (n_sim - 1.0)

    def step(self) -> kernels.Step:
        """The kernels' step settings."""
        return kernels.Step(
            rule=_RULE_ID[self.collision_rule],
            restitution=float(self.restitution),
            box_side=float(self.box_side),
            cells_per_side=int(self.cells_per_side),
            density_per_count=float(self.density_per_count),
            pair_coefficient=float(self.pair_coefficient),
            time_step=float(self.time_step),
            drag_rate=float(self.drag_rate),
        )

    def parameters(self) -> dict[str, Any]:
        return {
            "n_particles": self.n_particles,
            "density": self.density,
            "restitution": self.restitution,
            "drag_rate": self.drag_rate,
            "fictive_factor": self.fictive_factor,
            "cells_per_side": self.cells_per_side,
            "time_step": self.time_step,
            "collision_rule": self.collision_rule,
        }


def largest_temperature(settings: CoolingModesSettings, duration: float) -> float:
    """The largest mean temperature (units of T0) of a run of this length
    (``kinetic.theory.costantini2010.heated_temperature``: Eq. 12's balance; an elastic gas
    with drag heats as e^(2ω0 τ))."""
    from kinetic.theory.costantini2010 import heated_temperature

    return heated_temperature(settings.restitution, settings.density, settings.drag_rate, duration)


def check_heating(settings: CoolingModesSettings, duration: float) -> None:
    """Refuse a run whose drag heats the gas until its step makes more than
    HEATING_HEADROOM x MAX_COLLISIONS_PER_STEP collisions per particle (the step is
    checked at T0 by ``CoolingModesSettings``; ω_c grows as √T)."""
    temperature = largest_temperature(settings, duration)
    collisions = settings.collision_frequency * math.sqrt(temperature) * settings.time_step
    limit = HEATING_HEADROOM * MAX_COLLISIONS_PER_STEP
    if collisions > limit * _ROUNDING:
        raise ValueError(
            f"drag_rate = {settings.drag_rate!r} heats the gas at restitution = "
            f"{settings.restitution!r} to T = {temperature:.4g} T0 within the run "
            f"({duration!r} time units; Eq. 12's steady T_s = (2 drag_rate/zeta(T0))^2), "
            f"where time_step = {settings.time_step!r} makes {collisions:.4g} collisions per "
            f"particle per step: must be <= {limit:.4g}. Use drag_rate = zeta(T0)/2 "
            "(kinetic.theory.costantini2010.drag_rate) to hold T near T0, a shorter run, "
            f"or time_step <= {limit / (settings.collision_frequency * math.sqrt(temperature)):.6g}"
        )


def slack_per_cell(mean: float, changing: float = 0.0) -> int:
    """Free slots a layout gives each cell beyond its particles (``Cells``), for ``mean``
    simulated particles a cell of which the fraction ``changing`` is expected to change
    cell a step.

    Where the steps move the particles one by one, min(5 √mean, mean) + 4: a cell's
    count drifts from the one it was laid out with by about √(2 mean) (two Poisson
    counts), and the layout is redone when any cell runs out of room; at 62 particles a
    cell and 484 cells, 36 free slots ran out every 38 steps, 52 not in 3000 (5 √62 + 4 =
    44), and more room costs time (16.0 instead of 12.2 ns a particle-step with 66).
    Where they will sort (``changing`` above 0.8 ``RESORT_FRACTION``), mean + 4, so that
    the slots hold two packed copies of the particles (S >= 2 N_sim): the sorts alternate
    between the two ends of the slots."""
    if changing > 0.8 * kernels.RESORT_FRACTION:
        return math.ceil(mean) + 4
    return math.ceil(min(5.0 * math.sqrt(mean), mean)) + 4


@dataclass
class CoolingModesGas:
    """State of one realization (arrays mutated in place by ``advance``).

    position, velocity: (2, S) float64 and labels: (2, S) int64 by slot, cell c's
    particles in slots start[c]..start[c] + count[c] - 1 (layout in
    :mod:`kinetic.dsmc.inhomogeneous_kernels`); start (M² + 1,), count (M²,) int64;
    carry: (M²,) float64; cell_moments (M², 5) float64; mode_terms: (4, N_sim) float64 work
    array of the observer; moving_position, moving_velocity (2, N_sim) float64,
    moving_labels (2, N_sim) int64, moving_cell (N_sim,) int64: the buffer of the
    particles that change cell; fill (M²,) int64: a sort's work array; rng: (4,) uint64
    stream; tally: (TALLY_SIZE,) int64; energy: (1,) float64 energy lost since it was
    last reset (sum over simulated particles).
    """

    settings: CoolingModesSettings
    position: np.ndarray
    velocity: np.ndarray
    labels: np.ndarray
    start: np.ndarray
    count: np.ndarray
    carry: np.ndarray
    cell_moments: np.ndarray
    mode_terms: np.ndarray
    moving_position: np.ndarray
    moving_velocity: np.ndarray
    moving_labels: np.ndarray
    moving_cell: np.ndarray
    fill: np.ndarray
    rng: np.ndarray
    tally: np.ndarray
    energy: np.ndarray
    cpu_seconds: float = 0.0

    @property
    def steps(self) -> int:
        return int(self.tally[kernels.TALLY_STEPS])

    @property
    def time(self) -> float:
        return self.steps * self.settings.time_step

    @property
    def collisions(self) -> int:
        return int(self.tally[kernels.TALLY_COLLISIONS])

    def slots(self) -> np.ndarray:
        """(N_sim,) int64 slots of the particles, cell after cell."""
        counts = self.count
        first = np.repeat(self.start[:-1] - np.cumsum(counts) + counts, counts)
        return first + np.arange(counts.sum())

    def positions(self) -> np.ndarray:
        """(N_sim, 2) copy of the positions in [0, L)², cell after cell."""
        return self.position[:, self.slots()].T.copy()

    def velocities(self) -> np.ndarray:
        """(N_sim, 2) copy of the velocities w (same order as ``positions``)."""
        return self.velocity[:, self.slots()].T.copy()

    def identities(self) -> np.ndarray:
        """(N_sim,) int64 number of each particle in the initial state (same order)."""
        return self.labels[0, self.slots()].copy()

    def arrays(self) -> kernels.Gas:
        """The realization's arrays as the kernels take them (views, not copies)."""
        return kernels.Gas(
            self.position, self.velocity, self.labels, self.rng, self.tally, self.energy
        )

    def cells(self) -> kernels.Cells:
        """The per-cell arrays as the kernels take them (views, not copies)."""
        return kernels.Cells(
            self.start,
            self.count,
            self.carry,
            self.cell_moments,
            self.mode_terms,
            self.moving_position,
            self.moving_velocity,
            self.moving_labels,
            self.moving_cell,
            self.fill,
        )

    def advance(self, n_steps: int) -> None:
        """``n_steps`` steps of length ``settings.time_step`` (CPU time accumulated)."""
        integer("n_steps", n_steps, 0)
        s = self.settings
        start = time.process_time()
        kernels.advance(self.arrays(), self.cells(), s.step(), n_steps)
        self.cpu_seconds += time.process_time() - start
        self._check()

    def run_samples(self, steps_first: int, stride: int, observables, dissipated) -> None:
        """``kernels.run_samples`` on this gas (rows of ``observables``, ``dissipated``)."""
        s = self.settings
        start = time.process_time()
        kernels.run_samples(
            self.arrays(),
            self.cells(),
            s.step(),
            int(steps_first),
            int(stride),
            float(s.wavenumber),
            observables,
            dissipated,
        )
        self.cpu_seconds += time.process_time() - start
        self._check()

    def observables(self) -> dict[str, Any]:
        """The kernel's observer on the current state: ``temperature``, ``mode`` (complex
        (2,): wy_kx, wx_ky), ``mode_norm`` (2,), ``momentum`` (2,) = Σ w/(N_sim √T)."""
        out = np.zeros(kernels.N_OBSERVABLES)
        kernels.observe(
            self.position,
            self.velocity,
            self.start,
            self.count,
            self.settings.wavenumber,
            self.mode_terms,
            out,
        )
        return {
            "temperature": out[0],
            "mode": np.array([out[1] + 1j * out[2], out[3] + 1j * out[4]]),
            "mode_norm": out[5:7].copy(),
            "momentum": out[7:9].copy(),
        }

    def _check(self) -> None:
        if self.tally[kernels.TALLY_EXCEEDED]:
            raise RuntimeError(
                "internal error: the relative-speed bound of a cell was exceeded "
                f"{self.tally[kernels.TALLY_EXCEEDED]} times although it is kept rigorous"
            )


def initial_particles(settings: CoolingModesSettings, stream: np.ndarray):
    """The initial state drawn from ``stream`` (copied): uniform positions, Gaussian
    velocities with zero momentum and Σ|w|² = 2 N_sim T0 exactly. Returns ``(position,
    velocity, labels, rng)``: (2, N_sim) float64, float64, int64 (particle i in column
    i) and the (4,) uint64 stream after the draws (the CUDA backend starts from these)."""
    n = settings.n_simulated
    rng = checked_stream(stream)
    position = np.zeros((2, n))
    velocity = np.zeros((2, n))
    labels = np.zeros((2, n), dtype=np.int64)
    kernels.initial_state(position, velocity, labels, rng, settings.box_side)
    return position, velocity, labels, rng


def _one_block(length: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Zeroed (2, length) float64, float64 and int64 arrays, rows of one page-aligned
    block. The slots' three arrays allocated apart ran their steps 10-35 % slower, by
    where the allocator put them (one process, the same trajectory: 10.9-13.4 ns a
    particle-step, against 8.0-8.8 for one block whatever the offset between rows)."""
    page = 4096
    raw = np.zeros(6 * length * 8 + page, dtype=np.uint8)
    first = -raw.ctypes.data % page
    block = raw[first : first + 6 * length * 8]
    rows = block.view(np.float64).reshape(6, length)
    return rows[0:2], rows[2:4], block.view(np.int64).reshape(6, length)[4:6]


def new_cooling_gas(settings: CoolingModesSettings, stream: np.ndarray) -> CoolingModesGas:
    """Initial state drawn from ``stream`` (``initial_particles``), laid out in its cells."""
    n = settings.n_simulated
    n_cells = settings.cells_per_side**2
    slack = slack_per_cell(n / n_cells, settings.changing_fraction)
    position, velocity, labels = _one_block(n + n_cells * slack)
    moving_position, moving_velocity, moving_labels = _one_block(n)
    moving_position[:], moving_velocity[:], moving_labels[:], rng = initial_particles(
        settings, stream
    )
    gas = CoolingModesGas(
        settings=settings,
        position=position,
        velocity=velocity,
        labels=labels,
        start=np.zeros(n_cells + 1, dtype=np.int64),
        count=np.zeros(n_cells, dtype=np.int64),
        carry=np.zeros(n_cells),
        cell_moments=np.zeros((n_cells, 5)),
        mode_terms=np.zeros((4, n)),
        moving_position=moving_position,
        moving_velocity=moving_velocity,
        moving_labels=moving_labels,
        moving_cell=np.zeros(n, dtype=np.int64),
        fill=np.zeros(n_cells, dtype=np.int64),
        rng=rng,
        tally=np.zeros(kernels.TALLY_SIZE, dtype=np.int64),
        energy=np.zeros(1),
    )
    kernels.lay_out_initial(gas.arrays(), gas.cells(), settings.step())
    return gas


def _compile_outside_the_timers(settings: CoolingModesSettings) -> None:
    """A tiny gas with the same argument types (a no-op once numba's cache is warm)."""
    tiny = CoolingModesSettings(
        **{**settings.parameters(), "n_particles": 4, "fictive_factor": 1, "cells_per_side": 1}
    )
    gas = new_cooling_gas(tiny, np.array([1, 2, 3, 4], dtype=np.uint64))
    gas.advance(1)
    gas.run_samples(1, 1, np.zeros((1, kernels.N_OBSERVABLES)), np.zeros(1))


def simulate_cooling_modes(
    *,
    n_particles: int,
    density: float,
    restitution: float,
    drag_rate: float,
    equilibration: float,
    sample_interval: float,
    n_samples: int,
    seed: int,
    fictive_factor: int,
    cells_per_side: int,
    time_step: float,
    collision_rule: str,
    n_realizations: int = 1,
    first_realization: int = 0,
    label: str | None = None,
    backend: str = "cpu",
):
    """Transverse modes of the homogeneous cooling state by inhomogeneous DSMC (costantini2010).

    Parameters (units of the module docstring)
    ----------
    n_particles
        N >= 2 real particles; box side L = √(N/density).
    density
        n σ² > 0.
    restitution
        α in (0, 1].
    drag_rate
        ω0 >= 0 (1/time): dw/dτ = ω0 w between collisions; ω0 = ζ(T0)/2 keeps T_s = T0.
    equilibration, sample_interval
        τ before the first sample (>= 0) and between samples (> 0), both whole multiples
        of ``time_step``.
    n_samples
        Samples at τ_j = equilibration + j sample_interval, j = 0..n_samples-1.
    fictive_factor
        Λ >= 1: Λ N simulated particles, each colliding at the rate of the real density
        (a cell of area A_c holding ``count`` of them has real density count/(Λ A_c)).
    cells_per_side
        M >= 1: M x M equal square collision cells (M = 1: "homogeneous DSMC"). With
        Λ = 1 and fewer than one real particle per cell a warning is logged.
    time_step
        Δτ > 0 with ω_c(T0) Δτ <= 0.1 (ω_c = 2 n σ √(πT0/m)) and ω0 Δτ <= 0.1, and
        ω_c(T) Δτ <= 0.11 at the largest temperature T the drag heats the gas to within
        the run (``largest_temperature``: Eq. 12's balance; an elastic gas with drag heats
        as e^(2ω0τ)).
    collision_rule
        "paper" (½ N_c ω_c(T_c) Δτ collisions per cell and step) or "majorant" (Bird's
        scheme with a rigorous majorant; exact mean collision rate at any M).
    seed, n_realizations, first_realization
        Realization k uses row k of ``kinetic.rng.stream_states(seed, ·)``.
    label
        Prefix of the progress lines.
    backend
        ``"cpu"`` (numba, one realization after the other) or ``"cuda"`` (numba-cuda, all
        realizations of the call together on one GPU: :mod:`kinetic.dsmc.inhomogeneous_gpu`,
        one thread per cell running the CPU engine's per-cell collision code with a
        stream of its own; statistically equivalent, not bit-identical). A ``cuda`` run on
        a machine without a GPU stops before any work
        (``kinetic.backends.BackendUnavailable``).

    Returns
    -------
    xarray.Dataset (the "cooling modes" contract): coords ``realization``, ``time``
    (τ_j), ``mode`` ("wy_kx", "wx_ky"), ``axis`` ("x", "y"); ``temperature``
    (realization, time); ``mode_real``, ``mode_imag``, ``mode_norm`` (realization,
    time, mode) summed over all Λ N simulated particles; ``dissipated_energy``
    (realization, time) per simulated particle over the interval of length
    sample_interval ending at τ_j (NaN for the first sample when equilibration <
    sample_interval: that interval is not inside the run); ``momentum`` (realization,
    time, axis) Σ w/(N_sim √T); per realization ``collisions``, ``candidates``,
    ``particle_steps``, ``repeated_collisions``, ``cpu_seconds`` (cuda: the batch's wall
    time divided by the realizations). Attributes ``backend`` and ``device``.
    """
    run = _Run(dict(locals()))
    device = backends.require(backend)  # before any work: no GPU, no run
    run.warn()
    progress = Progress(max(1, run.particle_steps), label=run.label, unit="steps")
    if backend == "cuda":
        from kinetic.dsmc import inhomogeneous_gpu

        inhomogeneous_gpu.run_points([run.gpu_point()], *run.schedule, progress)
    else:
        _compile_outside_the_timers(run.settings)
        _run_cpu(run, progress)
    if run.particle_steps == 0:
        progress.update(1)
    return run.dataset(device)


_ARGUMENTS = inspect.signature(simulate_cooling_modes).parameters
"""The keyword arguments of ``simulate_cooling_modes`` (a ``_Run`` reads these)."""


def simulate_cooling_modes_points(points, *, label: str | None = None):
    """Several runs of the ``cuda`` backend in the same GPU launches (``points``: the
    keyword arguments of ``simulate_cooling_modes`` each, with ``backend='cuda'``). The
    runs share N, density, Λ, cells, time step, collision rule, equilibration and sample
    interval (``SHARED_SETTINGS``: the batch's arrays, cells and schedule); restitution,
    drag rate, number of samples, seed and realizations may differ, so that the runs of
    several α fill one GPU together (a point's ``label`` is not used: ``label`` names the
    batch's progress lines). Every point is validated before any work; returns the list
    of datasets ``simulate_cooling_modes`` would return for the points one at a time: the
    same numbers, bit for bit (a realization does not depend on the others of its batch),
    ``cpu_seconds`` aside (the wall time of the whole batch per realization)."""
    runs = [_Run({**point, "label": None}) for point in points]
    if not runs:
        raise ValueError("simulate_cooling_modes_points needs at least one point")
    for key in ("backend", "equilibration", "sample_interval", *SHARED_SETTINGS):
        values = {run.p[key] for run in runs}
        if len(values) > 1:
            raise ValueError(f"the points of one launch must share {key}, got {sorted(values)}")
    if runs[0].p["backend"] != "cuda":
        raise ValueError(
            "simulate_cooling_modes_points runs the cuda backend only; use "
            "simulate_cooling_modes on the cpu"
        )
    backends.check_realizations("cuda", sum(run.p["n_realizations"] for run in runs))
    device = backends.require("cuda")  # before any work
    for run in runs:
        run.warn()
    text = label or f"dsmc cooling modes {len(runs)} runs N={runs[0].settings.n_particles}"
    total = sum(run.particle_steps for run in runs)
    progress = Progress(max(1, total), label=text, unit="steps")
    from kinetic.dsmc import inhomogeneous_gpu

    inhomogeneous_gpu.run_points([run.gpu_point() for run in runs], *runs[0].schedule, progress)
    if total == 0:
        progress.update(1)
    return [run.dataset(device) for run in runs]


class _Run:
    """One validated call of ``simulate_cooling_modes`` (``p``: its keyword arguments):
    the settings, the schedule of steps, the realizations' streams, the arrays the engine
    fills, and the dataset made of them."""

    def __init__(self, p):
        unknown = sorted(set(p) - set(_ARGUMENTS))
        missing = sorted(
            name
            for name, argument in _ARGUMENTS.items()
            if argument.default is inspect.Parameter.empty and name not in p
        )
        if unknown or missing:
            raise TypeError(
                f"simulate_cooling_modes arguments: unknown {unknown}, missing {missing}"
            )
        defaults = {
            name: argument.default
            for name, argument in _ARGUMENTS.items()
            if argument.default is not inspect.Parameter.empty
        }
        p = defaults | dict(p)
        backend = p["backend"]
        backends.check(backend)
        backends.check_realizations(backend, p["n_realizations"])
        settings = CoolingModesSettings(
            **{key: p[key] for key in CoolingModesSettings.__dataclass_fields__}
        )
        equilibration = real("equilibration", p["equilibration"], 0.0, math.inf, high_open=True)
        sample_interval = real(
            "sample_interval", p["sample_interval"], 0.0, math.inf, low_open=True, high_open=True
        )
        n_samples = integer("n_samples", p["n_samples"], 1)
        steps_before = _whole_steps("equilibration", equilibration, settings.time_step, 0)
        stride = _whole_steps("sample_interval", sample_interval, settings.time_step, 1)
        n_realizations = p["n_realizations"]
        self.streams = realization_streams(p["seed"], p["first_realization"], n_realizations)
        label = p["label"]
        if label is not None and not isinstance(label, str):
            raise TypeError(f"label must be a string or None, got {label!r}")
        p |= {
            "equilibration": equilibration,
            "sample_interval": sample_interval,
            "n_samples": n_samples,
        }
        self.p = p
        self.settings = settings
        # steps before the first sample's dissipation interval, and within it
        check_heating(settings, equilibration + (n_samples - 1) * sample_interval)
        if steps_before >= stride:
            warm, first_steps = steps_before - stride, stride
        else:
            warm, first_steps = steps_before, 0
        self.schedule = (warm, first_steps, stride)
        self.particle_steps = n_realizations * (steps_before + (n_samples - 1) * stride)
        """Realizations x steps: the progress lines' unit of work."""
        shape = (n_realizations, n_samples)
        # the samples' arrays (the layout of the particles is bounded by MAX_LAYOUT_BYTES)
        fits_in_memory(
            f"n_realizations = {n_realizations} x n_samples = {n_samples}",
            8.0 * n_realizations * n_samples * (kernels.N_OBSERVABLES + 4),
        )
        self.observables = np.zeros((*shape, kernels.N_OBSERVABLES))
        self.dissipated = np.zeros(shape)
        self.totals = {
            key: np.zeros(n_realizations, dtype=np.int64)
            for key in ("collisions", "candidates", "particle_steps", "repeated_collisions")
        }
        self.cpu_seconds = np.zeros(n_realizations)
        self.label = label or (
            f"dsmc cooling modes {settings.collision_rule} N={settings.n_particles} "
            f"alpha={settings.restitution:g} Lambda={settings.fictive_factor} "
            f"M={settings.cells_per_side}"
        )

    def warn(self) -> None:
        """The warnings of a run whose cells hold less than one real particle, or whose box
        is beyond the shear instability."""
        from kinetic.theory.costantini2010 import warn_if_unstable

        settings = self.settings
        warn_if_unstable(settings.n_particles, settings.density, settings.restitution)
        if settings.fictive_factor == 1 and settings.real_particles_per_cell < 1.0:
            logger.warning(
                "inhomogeneous DSMC with fictive_factor = 1 and %.3g real particles per cell "
                "(N/M² = %d/%d²): fewer than one collision partner per cell, expect strong "
                "recollisions (molecular chaos fails)",
                settings.real_particles_per_cell,
                settings.n_particles,
                settings.cells_per_side,
            )

    def gpu_point(self) -> tuple:
        """(settings, streams, n_samples, out) of ``inhomogeneous_gpu.run_points``."""
        out = {
            "observables": self.observables,
            "dissipated": self.dissipated,
            "cpu_seconds": self.cpu_seconds,
        }
        return self.settings, self.streams, self.p["n_samples"], out | self.totals

    def dataset(self, device: str):
        """The run's dataset (the "cooling modes" contract) from its filled arrays."""
        p, settings = self.p, self.settings
        if self.schedule[1] == 0:
            self.dissipated[:, 0] = np.nan  # the first interval is not inside the run
        observables, dissipated, totals = self.observables, self.dissipated, self.totals
        n_samples, equilibration = p["n_samples"], p["equilibration"]
        sample_interval = p["sample_interval"]
        first_realization, n_realizations = p["first_realization"], p["n_realizations"]
        times = equilibration + sample_interval * np.arange(n_samples)
        # the kernels observe after a step's collisions; the dataset holds the velocities
        # half a drag later (the module docstring's "Sampling point")
        half = math.exp(0.5 * settings.drag_rate * settings.time_step)
        mode_real = np.stack([observables[..., 1], observables[..., 3]], axis=-1) * half
        mode_imag = np.stack([observables[..., 2], observables[..., 4]], axis=-1) * half
        mode_norm = observables[..., 5:7] * half**2
        dataset = io.make_dataset(
            {
                "temperature": (
                    ("realization", "time"),
                    observables[..., 0] * half**2,
                    "T0",
                    "granular temperature sum |w - u|^2 / (2 N_sim) of the rescaled velocities "
                    "half a step's drag after the step's collisions (their value times "
                    "exp(drag_rate time_step))",
                ),
                "mode_real": (
                    ("realization", "time", "mode"),
                    mode_real,
                    "sqrt(T0/m)",
                    "real part of the transverse mode at k = 2 pi/L, summed over all "
                    "simulated particles (velocities as in temperature)",
                ),
                "mode_imag": (
                    ("realization", "time", "mode"),
                    mode_imag,
                    "sqrt(T0/m)",
                    "imaginary part of the transverse mode at k = 2 pi/L, summed over all "
                    "simulated particles (velocities as in temperature)",
                ),
                "mode_norm": (
                    ("realization", "time", "mode"),
                    mode_norm,
                    "T0/m",
                    "normaliser of the mode: sum of w_y^2 (wy_kx) or w_x^2 (wx_ky) "
                    "(velocities as in temperature)",
                ),
                "dissipated_energy": (
                    ("realization", "time"),
                    dissipated,
                    "T0",
                    "energy lost in collisions per simulated particle during the sample "
                    "interval ending at this time (NaN if that interval starts before 0)",
                ),
                "momentum": (
                    ("realization", "time", "axis"),
                    observables[..., 7:9],
                    "1",
                    "total momentum sum w / (N_sim sqrt(T))",
                ),
                "collisions": ("realization", totals["collisions"], "1", "collisions executed"),
                "candidates": (
                    "realization",
                    totals["candidates"],
                    "1",
                    "candidate pairs tested (collisions / candidates = acceptance)",
                ),
                "particle_steps": (
                    "realization",
                    totals["particle_steps"],
                    "1",
                    "simulated particles times time steps",
                ),
                "repeated_collisions": (
                    "realization",
                    totals["repeated_collisions"],
                    "1",
                    "collisions whose two partners' previous collisions were with each other",
                ),
                "cpu_seconds": (
                    "realization",
                    self.cpu_seconds,
                    "s",
                    _CPU_SECONDS[p["backend"]],
                ),
            },
            coords={
                "realization": (
                    "realization",
                    np.arange(first_realization, first_realization + n_realizations),
                    "1",
                    "realization number (stream row)",
                ),
                "time": ("time", times, _TIME_UNIT, "rescaled time tau of the sample"),
                "mode": (
                    "mode",
                    np.array(MODES),
                    "1",
                    "transverse mode: velocity component_wavevector",
                ),
                "axis": ("axis", np.array(["x", "y"]), "1", "Cartesian axis"),
            },
            attrs={
                "units": "m = sigma = T0 = 1; time in sigma sqrt(m/T0); w the rescaled velocities",
                "backend": p["backend"],
                "device": device,
            },
        )
        parameters = {
            **settings.parameters(),
            "equilibration": equilibration,
            "sample_interval": sample_interval,
            "n_samples": n_samples,
            "seed": p["seed"],
            "n_realizations": n_realizations,
            "first_realization": first_realization,
            "engine": "dsmc",
            "box_side": settings.box_side,
            "wavenumber": settings.wavenumber,
            "simulated_particles": settings.n_simulated,
            "cell_side": settings.cell_side,
            "real_particles_per_cell": settings.real_particles_per_cell,
            "collisions_per_particle_per_step_at_T0": settings.collision_frequency
            * settings.time_step,
        }
        return io.stamp(dataset, parameters=parameters, seed=p["seed"])


def _run_cpu(run: _Run, progress: Progress) -> None:
    """The CPU backend: the realizations one after the other, into the run's arrays."""
    settings, (warm, first_steps, stride) = run.settings, run.schedule
    n_samples = run.p["n_samples"]
    chunk_steps = max(1, CHUNK_PARTICLE_STEPS // settings.n_simulated)
    samples_per_chunk = max(1, chunk_steps // stride)
    observables, dissipated, totals = run.observables, run.dissipated, run.totals
    for r in range(run.streams.shape[0]):
        gas = new_cooling_gas(settings, run.streams[r])
        done = 0
        while done < warm:
            steps = min(chunk_steps, warm - done)
            gas.advance(steps)
            done += steps
            progress.update(steps)
        gas.energy[0] = 0.0
        sample = 0
        while sample < n_samples:
            stop = min(n_samples, sample + samples_per_chunk)
            steps_first = first_steps if sample == 0 else stride
            gas.run_samples(
                steps_first, stride, observables[r, sample:stop], dissipated[r, sample:stop]
            )
            progress.update(steps_first + (stop - sample - 1) * stride)
            sample = stop
        totals["collisions"][r] = gas.collisions
        totals["candidates"][r] = gas.tally[kernels.TALLY_CANDIDATES]
        totals["particle_steps"][r] = gas.tally[kernels.TALLY_PARTICLE_STEPS]
        totals["repeated_collisions"][r] = gas.tally[kernels.TALLY_REPEATED]
        run.cpu_seconds[r] = gas.cpu_seconds
