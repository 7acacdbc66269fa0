"""Fronts of the homogeneous DSMC engine: validate, run the kernels in chunks, return datasets.

Two kinds of runs:

``simulate_homogeneous`` (montanero2007; HCS; extreme cases)
    N particles of a spatially homogeneous gas of inelastic hard spheres (or Maxwell
    molecules / very hard particles), d = 2 or 3, stepped with time step δt: Bird's
    collision stage, then the heat-flux force of montanero2007 Eq. (3.2) (ε = ε x̂) by
    the paper's Euler step (4.1) or its exact integration, then the thermostat (4.2)
    that restores zero momentum and the initial energy (``splitting="lie"``, the
    paper's order), or half force steps before and after the collisions
    (``splitting="strang"``). Which δt each needs: the force integrator does not
    matter at ε* <= 0.05 (Euler and exact agree); the Lie splitting biases κ'/κ0 by
    about +0.3 δt/τ at α = 1, the Strang splitting is unbiased within 1-2 % up to
    δt = 0.4 τ (tests/physics/test_dsmc_force_splitting.py). With zero field the thermostat
    only rescales: the run is the homogeneous cooling state (HCS) in scaled variables
    and, since the collision dynamics is invariant under v -> v/s, t -> s^p t, the same
    run also gives the freely cooling gas (``log_temperature_free``, ``time_free``:
    Haff's law) without ever letting the temperature underflow.
    Units: montanero2007 Section 4 — T0 = 1, time in τ = λ/v0, ε* = λ ε, velocities
    reported as c = V/v0.

``simulate_free_flights`` (visco2008 Figs 1, 12)
    An equilibrium gas run in continuous time (exact exponential event times), with
    histograms of every particle's free-flight times and free paths. Units: visco2008 —
    T0 = 1, time in 1/ω, length in the mean free path l = <v>/ω.

Lower-level API (for studies that sample velocities themselves, e.g. the montanero2007
study's own observers): ``HomogeneousSettings`` (validated parameters), ``new_gas``
(state of one realization), ``advance_gas`` (n steps, optional built-in sampling into
a ``Samples``), ``realization_streams``. Example::

    settings = HomogeneousSettings(n_particles=20000, restitution=0.5, time_step=0.01,
                                   reduced_field=0.025, force_step="exact")
    for stream in realization_streams(seed, 0, 10):
        gas = new_gas(settings, stream)
        for window in range(300):
            advance_gas(gas, 10)                    # 10 steps of 0.01 τ
            c = gas.reduced_velocities()            # (N, d) copy, c = V/v0, x first
            ...                                     # observe c (zero mean, <c²> = d/2)
        cpu, collisions = gas.cpu_seconds, gas.collisions

The montanero2007 observables from ``simulate_homogeneous`` directly (same names as
kinetic.analysis.montanero2007.MOMENTS): κ'(t) from ``heat_flux`` = <c² c_x> (window
averages per realization); b'_k by Eq. (3.10) from ``moments.sel(moment="full_k")`` and
by Eq. (3.12) from ``"marginal_k"``; g(V_x) and its odd part from ``cx_counts`` on
``cx_edges`` (symmetric, n_cx_bins even so that 0 is an edge, as ``histogram_edges``)
with ``histogram_observations`` particle observations; β1(c_x²) of Eq. (4.6) from
``cx_weights`` (sums of c_x (3/2 - c_x²) per bin) and ``cx_outside_weights``; the HCS
a2 from ``a2`` at zero field; ζ from ``cooling_rate``.

Timing hooks: every dataset holds per realization ``cpu_seconds`` (process time),
``collisions``, ``candidates`` and ``steps``; a ``HomogeneousGas`` accumulates
``cpu_seconds`` over its ``advance_gas`` calls.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from kinetic import gas as units
from kinetic import io
from kinetic.dsmc import kernels
from kinetic.progress import Progress, logger
from kinetic.rng import stream_states

__all__ = [
    "FORCE_STEPS",
    "MAX_COLLISIONS_PER_STEP",
    "MAX_FIELD_STEP",
    "MAX_REDUCED_FIELD",
    "MOMENT_NAMES",
    "SELECTIONS",
    "HomogeneousGas",
    "HomogeneousSettings",
    "Samples",
    "advance_gas",
    "new_gas",
    "realization_streams",
    "simulate_free_flights",
    "simulate_homogeneous",
]

MOMENT_NAMES = (
    "cx",
    "c2",
    "cx2",
    "c4",
    "c2cx",
    "full_1",
    "full_2",
    "full_3",
    "marginal_1",
    "marginal_2",
    "marginal_3",
    "c6",
    "cx4",
    "cxcy",
)
"""Snapshot averages of ``kernels.accumulate_moments`` (c = V/v0): <c_x>, <c²>, <c_x²>,
<c⁴>, <c² c_x>, <c_x L_k^(d/2)(c²)> (k = 1..3, Eq. 3.10), <c_x L_k^(1/2)(c_x²)>
(k = 1..3, Eq. 3.12), <c⁶>, <c_x⁴>, <c_x c_y>. Same names as
kinetic.analysis.montanero2007.MOMENTS for the entries both have."""

FORCE_STEPS = ("euler", "exact")
SPLITTINGS = ("lie", "strang")
SELECTIONS = ("ntc", "poisson")

MAX_COLLISIONS_PER_STEP = 0.5
"""Largest mean number of collisions per particle in one time step (δt ν <= 0.5)."""

MAX_REDUCED_FIELD = 1.0
"""Largest ε* accepted (linear response needs ε* << 1; the paper uses 0.025)."""

LINEAR_RESPONSE_FIELD = 0.1
"""Above this ε* a warning is logged: see tests/physics/test_dsmc_extreme_cases.py."""

MAX_FIELD_STEP = 0.1
"""Largest ε* δt/τ: the relative change of V_x in one force step is ε* (δt/τ) c_x / 2."""

_KERNEL_ID = {
    "hard_spheres": kernels.HARD_SPHERES,
    "maxwell": kernels.MAXWELL,
    "very_hard": kernels.VERY_HARD,
}


# ------------------------------------------------------------------------ validation


def _integer(name: str, value: Any, minimum: int, maximum: int | None = None) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    if value < minimum or (maximum is not None and value > maximum):
        allowed = f">= {minimum}" if maximum is None else f"in [{minimum}, {maximum}]"
        raise ValueError(f"{name} = {value} is not allowed: must be {allowed}")
    return int(value)


def _real(
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


def _choice(name: str, value: Any, choices: Sequence[str]) -> str:
    if value not in choices:
        raise ValueError(f"{name} = {value!r} is not allowed: must be one of {', '.join(choices)}")
    return value


def _multiple(name: str, value: float, unit_name: str, unit: float) -> int:
    """``value / unit`` as an integer >= 1, or an error naming both."""
    ratio = value / unit
    count = round(ratio)
    if count < 1 or abs(ratio - count) > 1e-9 * max(1.0, ratio):
        raise ValueError(
            f"{name} = {value!r} must be a whole multiple (>= 1) of {unit_name} = {unit!r}"
        )
    return int(count)


# ------------------------------------------------------------- homogeneous gas: state


@dataclass(frozen=True)
class HomogeneousSettings:
    """Validated parameters of one homogeneous DSMC run (montanero2007 units).

    n_particles: N >= 2. restitution: α in (0, 1]. time_step: δt in τ, with at most
    MAX_COLLISIONS_PER_STEP collisions per particle per step on average.
    dimension: 2 or 3. kernel: "hard_spheres", "maxwell" or "very_hard".
    reduced_field: ε* in [0, MAX_REDUCED_FIELD], with ε* δt/τ <= MAX_FIELD_STEP.
    force_step: "euler" (Eq. 4.1) or "exact" (V -> V/(1 + ε V_x δt/2)).
    selection: "ntc" (no-time-counter) or "poisson" (exact event times).
    splitting: "lie" (the paper's: collisions, then force and thermostat; O(δt) bias)
    or "strang" (half a force step before and after the collisions; O(δt²) bias, twice
    the force work per step).
    """

    n_particles: int
    restitution: float
    time_step: float
    dimension: int = 3
    kernel: str = "hard_spheres"
    reduced_field: float = 0.0
    force_step: str = "euler"
    selection: str = "ntc"
    splitting: str = "lie"

    def __post_init__(self) -> None:
        _integer("dimension", self.dimension, 2, 3)
        _choice("kernel", self.kernel, units.KERNELS)
        _integer("n_particles", self.n_particles, 2)
        _real("restitution", self.restitution, 0.0, 1.0, low_open=True)
        _real("reduced_field", self.reduced_field, 0.0, MAX_REDUCED_FIELD)
        _choice("force_step", self.force_step, FORCE_STEPS)
        _choice("selection", self.selection, SELECTIONS)
        _choice("splitting", self.splitting, SPLITTINGS)
        limit = MAX_COLLISIONS_PER_STEP / self.collision_frequency
        if isinstance(self.time_step, bool) or not isinstance(
            self.time_step, int | float | np.integer | np.floating
        ):
            raise TypeError(f"time_step must be a real number, got {self.time_step!r}")
        if not (math.isfinite(self.time_step) and 0.0 < self.time_step <= limit):
            raise ValueError(
                f"time_step = {self.time_step!r} τ is not allowed: must be in (0, {limit:.4g}] τ "
                f"(at most {MAX_COLLISIONS_PER_STEP} collisions per particle per step; the "
                f"collision time is {1.0 / self.collision_frequency:.4g} τ)"
            )
        if self.reduced_field * self.time_step > MAX_FIELD_STEP:
            raise ValueError(
                f"reduced_field * time_step = {self.reduced_field!r} x {self.time_step!r} τ is "
                f"too large a force step: must be <= {MAX_FIELD_STEP} (reduce time_step to "
                f"<= {MAX_FIELD_STEP / self.reduced_field:.4g} τ)"
            )
        for name in ("n_particles", "dimension"):
            object.__setattr__(self, name, int(getattr(self, name)))
        for name in ("restitution", "time_step", "reduced_field"):
            object.__setattr__(self, name, float(getattr(self, name)))

    # derived quantities, internal units (m = σ = T0 = 1, density such that λ = 1)
    @property
    def density(self) -> float:
        """Number density n with λ = 1."""
        return 1.0 / (math.sqrt(2.0) * units.cross_section(self.dimension))

    @property
    def tau(self) -> float:
        """τ = λ/v0 in internal time units (λ = 1, v0 = √2)."""
        return units.montanero_time_unit(self.dimension, self.density)

    @property
    def collision_frequency(self) -> float:
        """Equilibrium collisions per particle per τ at T0 (2/√π for hard spheres)."""
        omega = units.equilibrium_collision_frequency(self.kernel, self.dimension, self.density)
        return omega * self.tau

    @property
    def pair_coefficient(self) -> float:
        return units.candidate_coefficient(
            self.kernel, self.dimension, self.density, self.n_particles
        )

    @property
    def half_field_step(self) -> float:
        """a = ε δt/2 (internal units, ε = ε*/λ = ε*)."""
        return 0.5 * self.reduced_field * self.time_step * self.tau

    @property
    def target_energy(self) -> float:
        """K0 = d T0/2 per particle."""
        return 0.5 * self.dimension

    def parameters_init(self) -> dict[str, Any]:
        """The constructor's keyword arguments."""
        return {
            "n_particles": self.n_particles,
            "restitution": self.restitution,
            "time_step": self.time_step,
            "dimension": self.dimension,
            "kernel": self.kernel,
            "reduced_field": self.reduced_field,
            "force_step": self.force_step,
            "selection": self.selection,
            "splitting": self.splitting,
        }

    def parameters(self) -> dict[str, Any]:
        """The constructor's arguments as dataset attributes (the time step named with
        its unit)."""
        parameters = self.parameters_init()
        parameters["time_step_tau"] = parameters.pop("time_step")
        return parameters


@dataclass
class Samples:
    """Accumulators of the built-in observers (filled by ``advance_gas``).

    moment_sums: (1 + len(MOMENT_NAMES),) [0] = snapshots, [1:] = sums of snapshot
    averages. cx_counts: (n_cx_bins + 2,) int64 over the edges ``cx_edges`` with [0]
    below and [-1] above; speed_counts: (n_speed_bins + 1,) int64 of |c| from 0 with
    [-1] above. Snapshots are taken every ``stride`` steps; histograms only when
    ``histogram`` is set.
    """

    stride: int = 10
    cx_max: float = 5.0
    n_cx_bins: int = 200
    speed_max: float = 6.0
    n_speed_bins: int = 120
    histogram: bool = False
    moment_sums: np.ndarray = field(init=False, repr=False)
    cx_counts: np.ndarray = field(init=False, repr=False)
    cx_weights: np.ndarray = field(init=False, repr=False)
    speed_counts: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        _integer("sample_stride", self.stride, 1)
        _real("cx_max", self.cx_max, 0.0, 1e3, low_open=True)
        if (
            isinstance(self.n_cx_bins, bool)
            or not isinstance(self.n_cx_bins, int | np.integer)
            or self.n_cx_bins < 2
            or self.n_cx_bins % 2
        ):
            raise ValueError(f"n_cx_bins = {self.n_cx_bins!r} must be an even integer >= 2")
        _real("speed_max", self.speed_max, 0.0, 1e3, low_open=True)
        _integer("n_speed_bins", self.n_speed_bins, 1)
        self.moment_sums = np.zeros(1 + len(MOMENT_NAMES))
        self.cx_counts = np.zeros(self.n_cx_bins + 2, dtype=np.int64)
        self.cx_weights = np.zeros(self.n_cx_bins + 2)
        self.speed_counts = np.zeros(self.n_speed_bins + 1, dtype=np.int64)

    @property
    def cx_edges(self) -> np.ndarray:
        return np.linspace(-self.cx_max, self.cx_max, self.n_cx_bins + 1)

    @property
    def speed_edges(self) -> np.ndarray:
        return np.linspace(0.0, self.speed_max, self.n_speed_bins + 1)

    def reset_moments(self) -> None:
        self.moment_sums[:] = 0.0


@dataclass
class HomogeneousGas:
    """State of one realization (all arrays; mutated in place by ``advance_gas``).

    velocity: (d, N) float64 peculiar velocities, struct of arrays (row k = component k;
    internal units T0 = 1, so c = V/√2). rng: (4,) uint64 xoshiro256+ state.
    bounds: (d + 2,) speed bounds; carry: (1,) NTC fraction; tally: (4,) int64
    candidates, collisions, bound raises, stale-bound detections (always 0 here);
    clock: (5,) internal time, ln(T_free/T0), free-cooling time, steps, Σ ζ δt.
    """

    settings: HomogeneousSettings
    velocity: np.ndarray
    rng: np.ndarray
    bounds: np.ndarray
    carry: np.ndarray
    tally: np.ndarray
    clock: np.ndarray
    cpu_seconds: float = 0.0

    @property
    def time(self) -> float:
        """Elapsed time in τ."""
        return self.clock[0] / self.settings.tau

    @property
    def steps(self) -> int:
        return int(self.clock[3])

    @property
    def collisions(self) -> int:
        return int(self.tally[kernels.TALLY_ACCEPTED])

    @property
    def candidates(self) -> int:
        return int(self.tally[kernels.TALLY_CANDIDATES])

    @property
    def log_temperature_free(self) -> float:
        """ln(T/T0) of the freely cooling gas this zero-field run represents."""
        return float(self.clock[1])

    @property
    def time_free(self) -> float:
        """Elapsed time of that freely cooling gas, in τ(T0)."""
        return self.clock[2] / self.settings.tau

    def reduced_velocities(self) -> np.ndarray:
        """(N, d) view of c = V/v0 (a copy scaled by 1/v0; x is column 0)."""
        return (self.velocity / units.thermal_speed(1.0)).T


def realization_streams(seed: int, first: int, count: int) -> np.ndarray:
    """xoshiro256+ states of realizations ``first..first+count-1`` of a run with ``seed``.

    Row k of ``stream_states(seed, ·)`` belongs to realization k, so batching the
    realizations into jobs does not change any of them.
    """
    _integer("seed", seed, 0)
    _integer("first_realization", first, 0)
    _integer("n_realizations", count, 1)
    return stream_states(seed, first + count)[first:].copy()


def new_gas(
    settings: HomogeneousSettings, stream: np.ndarray, velocity: np.ndarray | None = None
) -> HomogeneousGas:
    """Initial state: a Maxwellian drawn from ``stream`` (copied), or ``velocity``.

    A given ``velocity`` ((d, N), finite, not all equal) is shifted to zero momentum and
    rescaled to T = T0 = 1 (as the thermostat would), so only its shape matters: e.g. a
    Maxwellian plus one particle far in the tail (a velocity outlier).
    """
    d, n = settings.dimension, settings.n_particles
    rng = np.array(stream, dtype=np.uint64).reshape(4).copy()
    if velocity is None:
        v = np.empty((d, n))
        kernels.maxwellian(v, rng, 1.0)
    else:
        v = np.ascontiguousarray(velocity, dtype=np.float64).copy()
        if v.shape != (d, n):
            raise ValueError(
                f"velocity has shape {v.shape}, expected (dimension, n_particles) = {(d, n)}"
            )
        if not np.all(np.isfinite(v)):
            bad = np.argwhere(~np.isfinite(v))[0]
            raise ValueError(
                f"velocity[{bad[0]}, {bad[1]}] = {float(v[tuple(bad)])!r} is not finite"
            )
        v -= v.mean(axis=1, keepdims=True)
        energy = 0.5 * np.sum(v * v) / n
        if not energy > 0.0:
            raise ValueError("velocity has no thermal motion (all particles equal)")
        v *= math.sqrt(settings.target_energy / energy)
    bounds = np.empty(d + 2)
    kernels.speed_bounds(v, 0, n, bounds)
    return HomogeneousGas(
        settings=settings,
        velocity=v,
        rng=rng,
        bounds=bounds,
        carry=np.zeros(1),
        tally=np.zeros(4, dtype=np.int64),
        clock=np.zeros(5),
    )


_STATUS_MESSAGES = {
    kernels.STATUS_FORCE_BLOW_UP: (
        "the exact force step diverged: a particle had 1 + ε V_x δt/2 <= 0, i.e. "
        "c_x <= {limit:.3g}, and would reach infinite speed within one step"
    ),
    kernels.STATUS_EULER_STEP_TOO_LARGE: (
        "the Euler force step is not small: a particle had |ε V_x δt/2| > "
        f"{kernels.EULER_LIMIT}, i.e. |c_x| > {{euler:.3g}}"
    ),
    kernels.STATUS_NONFINITE: "the kinetic energy became non-finite or zero",
}


def advance_gas(gas: HomogeneousGas, n_steps: int, samples: Samples | None = None) -> None:
    """Advance ``gas`` by ``n_steps`` steps, sampling into ``samples`` if given.

    Raises RuntimeError (naming the step, the time and the remedy) if a force step
    diverges; the gas is then left in the failed state.
    """
    _integer("n_steps", n_steps, 0)
    s = gas.settings
    if samples is None:
        samples = _NO_SAMPLES
        stride = 2**62
        histogram = False
    else:
        stride = samples.stride
        histogram = samples.histogram
    inverse_v0 = 1.0 / units.thermal_speed(1.0)
    start = time.process_time()
    status = kernels.advance(
        gas.velocity,
        gas.rng,
        _KERNEL_ID[s.kernel],
        s.restitution,
        s.pair_coefficient,
        s.time_step * s.tau,
        n_steps,
        s.selection == "poisson",
        s.half_field_step,
        s.force_step == "exact",
        s.splitting == "strang",
        s.target_energy,
        float(units.rate_exponent(s.kernel)),
        gas.bounds,
        gas.carry,
        gas.tally,
        gas.clock,
        stride,
        inverse_v0,
        samples.moment_sums,
        histogram,
        -samples.cx_max,
        2.0 * samples.cx_max / samples.n_cx_bins,
        samples.cx_counts,
        samples.cx_weights,
        samples.speed_max / samples.n_speed_bins,
        samples.speed_counts,
    )
    gas.cpu_seconds += time.process_time() - start
    if status != kernels.STATUS_OK:
        per_unit = s.reduced_field * s.time_step / 2.0  # ε δt/2 times v0 per unit c_x
        message = _STATUS_MESSAGES[status].format(
            limit=-1.0 / per_unit if per_unit else -math.inf,
            euler=kernels.EULER_LIMIT / per_unit if per_unit else math.inf,
        )
        raise RuntimeError(
            f"step {gas.steps + 1} (t = {gas.time:.6g} τ) of the run with "
            f"{s.parameters()}: {message}; reduce time_step or reduced_field"
        )
    if gas.tally[kernels.TALLY_EXCEEDED]:
        raise RuntimeError(
            "internal error: the collision bound was exceeded "
            f"{gas.tally[kernels.TALLY_EXCEEDED]} times although it is kept rigorous"
        )


_NO_SAMPLES = Samples()


def _compile_outside_the_timers(settings: HomogeneousSettings, samples: Samples) -> None:
    """One step of a tiny gas with the same argument types, so that the CPU time recorded
    per realization never includes numba compilation (a no-op once cached)."""
    tiny = HomogeneousSettings(**{**settings.parameters_init(), "n_particles": 4})
    gas = new_gas(tiny, np.array([1, 2, 3, 4], dtype=np.uint64))
    probe = Samples(
        stride=1,
        cx_max=samples.cx_max,
        n_cx_bins=samples.n_cx_bins,
        speed_max=samples.speed_max,
        n_speed_bins=samples.n_speed_bins,
        histogram=True,
    )
    advance_gas(gas, 1, probe)


# ----------------------------------------------------------- homogeneous gas: front


def simulate_homogeneous(
    *,
    n_particles: int,
    restitution: float,
    duration: float,
    time_step: float,
    sample_interval: float,
    seed: int,
    n_realizations: int = 1,
    first_realization: int = 0,
    dimension: int = 3,
    kernel: str = "hard_spheres",
    reduced_field: float = 0.0,
    force_step: str = "euler",
    selection: str = "ntc",
    splitting: str = "lie",
    sample_stride: int = 10,
    histogram_start: float | None = None,
    cx_max: float = 5.0,
    n_cx_bins: int = 200,
    speed_max: float = 6.0,
    n_speed_bins: int = 120,
    label: str | None = None,
):
    """Run independent realizations of the homogeneous (forced, thermostatted) gas.

    Parameters (times in τ = λ/v0, see the module docstring)
    ----------
    n_particles, restitution, time_step, dimension, kernel, reduced_field, force_step,
    selection, splitting
        As in ``HomogeneousSettings``. Above ε* = 0.1 a warning is logged: the forced
        state is then far from linear response, with a power-law tail of c_x towards -x
        (|c_x|^-5.5 at ε* = 0.2) in which high moments do not exist.
    duration
        Run length, a whole multiple of ``sample_interval``. Start: a Maxwellian at T0.
    sample_interval
        Length of the windows over which the moments are averaged (the time resolution
        of the output), a whole multiple of ``time_step``.
    sample_stride
        Snapshots are taken every ``sample_stride`` steps (<= steps per window).
    histogram_start
        The c_x and |c| histograms accumulate the snapshots after this time (default:
        half the duration), in [0, duration).
    cx_max, n_cx_bins, speed_max, n_speed_bins
        Histogram ranges (c_x on [-cx_max, cx_max], n_cx_bins even; |c| on [0, speed_max]).
    seed, n_realizations, first_realization
        Realization k uses row k of ``stream_states(seed, ·)``.
    label
        Name of the run in progress lines.

    Returns
    -------
    xarray.Dataset with dimensions realization, time (window centres), moment, cx,
    cx_edge, speed, speed_edge:
    ``moments`` (realization, time, moment) window averages of MOMENT_NAMES;
    ``a2`` = 4<c⁴>/(d(d+2)) - 1 and ``heat_flux`` = <c² c_x> = q_x/(n T v0) (realization,
    time); ``thermostat_rate`` = -d ln T/dt of the energy the thermostat restores (1/τ);
    ``cooling_rate`` (1/τ): at zero field the HCS cooling rate ζ(T0) of Eq. (2.14),
    without time-step error (Haff's law holds within each step);
    ``log_temperature_free``, ``time_free`` (window ends; the freely cooling gas);
    ``collisions_per_particle`` (cumulative, window ends); histograms ``cx_counts``,
    ``cx_weights`` (sums of c_x (3/2 - c_x²) per bin, for β1 of Eq. 4.6), ``cx_outside``
    and ``cx_outside_weights`` (below, above), ``speed_counts``, ``speed_overflow`` and
    ``histogram_observations`` (particles x snapshots); per realization ``collisions``,
    ``candidates``, ``bound_raises``, ``steps``, ``cpu_seconds``.
    """
    settings = HomogeneousSettings(
        n_particles=n_particles,
        restitution=restitution,
        time_step=time_step,
        dimension=dimension,
        kernel=kernel,
        reduced_field=reduced_field,
        force_step=force_step,
        selection=selection,
        splitting=splitting,
    )
    duration = _real("duration", duration, 0.0, 1e12, low_open=True, unit=" τ")
    sample_interval = _real(
        "sample_interval", sample_interval, 0.0, duration, low_open=True, unit=" τ"
    )
    steps_per_window = _multiple("sample_interval", sample_interval, "time_step", time_step)
    n_windows = _multiple("duration", duration, "sample_interval", sample_interval)
    _integer("sample_stride", sample_stride, 1, steps_per_window)
    if histogram_start is None:
        histogram_start = 0.5 * duration
    histogram_start = _real(
        "histogram_start", histogram_start, 0.0, duration, high_open=True, unit=" τ"
    )
    streams = realization_streams(seed, first_realization, n_realizations)
    samples = Samples(
        stride=sample_stride,
        cx_max=cx_max,
        n_cx_bins=n_cx_bins,
        speed_max=speed_max,
        n_speed_bins=n_speed_bins,
    )

    d = settings.dimension
    shape = (n_realizations, n_windows)
    moments = np.full((*shape, len(MOMENT_NAMES)), np.nan)
    snapshots = np.zeros(shape, dtype=np.int64)
    log_temperature = np.zeros(shape)
    cooling_sum = np.zeros(shape)
    time_free = np.zeros(shape)
    collisions_per_particle = np.zeros(shape)
    cx_counts = np.zeros((n_realizations, n_cx_bins), dtype=np.int64)
    cx_weights = np.zeros((n_realizations, n_cx_bins))
    cx_outside_weights = np.zeros((n_realizations, 2))
    cx_outside = np.zeros((n_realizations, 2), dtype=np.int64)
    speed_counts = np.zeros((n_realizations, n_speed_bins), dtype=np.int64)
    speed_overflow = np.zeros(n_realizations, dtype=np.int64)
    observations = np.zeros(n_realizations, dtype=np.int64)
    totals = {
        key: np.zeros(n_realizations, dtype=np.int64)
        for key in ("collisions", "candidates", "bound_raises", "steps")
    }
    cpu_seconds = np.zeros(n_realizations)

    label = label or (
        f"dsmc d={d} {settings.kernel} alpha={settings.restitution:g} "
        f"eps*={settings.reduced_field:g} N={settings.n_particles}"
    )
    if settings.reduced_field > LINEAR_RESPONSE_FIELD:
        logger.warning(
            "reduced_field = %g is beyond linear response: the particles moving against "
            "the field run away between collisions and the c_x distribution grows a power-"
            "law tail (|c_x|^-5.5 at 0.2): high moments such as b'_2, b'_3 do not exist",
            settings.reduced_field,
        )
    _compile_outside_the_timers(settings, samples)
    progress = Progress(n_realizations * n_windows, label=label, unit="windows")
    first_histogram_window = math.ceil(histogram_start / sample_interval - 1e-9)
    for r in range(n_realizations):
        gas = new_gas(settings, streams[r])
        samples.cx_counts[:] = 0
        samples.cx_weights[:] = 0.0
        samples.speed_counts[:] = 0
        histogram_snapshots = 0
        for w in range(n_windows):
            samples.reset_moments()
            samples.histogram = w >= first_histogram_window
            advance_gas(gas, steps_per_window, samples)
            count = int(samples.moment_sums[0])
            snapshots[r, w] = count
            if count:
                moments[r, w] = samples.moment_sums[1:] / count
            if samples.histogram:
                histogram_snapshots += count
            log_temperature[r, w] = gas.log_temperature_free
            cooling_sum[r, w] = gas.clock[4]
            time_free[r, w] = gas.time_free
            collisions_per_particle[r, w] = 2.0 * gas.collisions / settings.n_particles
            progress.update(1)
        cx_counts[r] = samples.cx_counts[1:-1]
        cx_outside[r] = samples.cx_counts[[0, -1]]
        cx_weights[r] = samples.cx_weights[1:-1]
        cx_outside_weights[r] = samples.cx_weights[[0, -1]]
        speed_counts[r] = samples.speed_counts[:-1]
        speed_overflow[r] = samples.speed_counts[-1]
        observations[r] = histogram_snapshots * settings.n_particles
        totals["collisions"][r] = gas.collisions
        totals["candidates"][r] = gas.candidates
        totals["bound_raises"][r] = gas.tally[kernels.TALLY_RAISED]
        totals["steps"][r] = gas.steps
        cpu_seconds[r] = gas.cpu_seconds

    window_ends = sample_interval * np.arange(1, n_windows + 1)
    previous = np.concatenate([np.zeros((n_realizations, 1)), log_temperature[:, :-1]], axis=1)
    thermostat_rate = (previous - log_temperature) / sample_interval
    previous = np.concatenate([np.zeros((n_realizations, 1)), cooling_sum[:, :-1]], axis=1)
    cooling_rate = (cooling_sum - previous) / sample_interval
    c4 = moments[..., MOMENT_NAMES.index("c4")]
    a2 = 4.0 * c4 / (d * (d + 2)) - 1.0
    heat_flux = moments[..., MOMENT_NAMES.index("c2cx")]
    cx_edges = samples.cx_edges
    speed_edges = samples.speed_edges
    rt = ("realization", "time")
    dataset = io.make_dataset(
        {
            "moments": (
                ("realization", "time", "moment"),
                moments,
                "1",
                "window average of the snapshot moment (c = V/v0)",
            ),
            "snapshots": (rt, snapshots, "1", "snapshots averaged in the window"),
            "a2": (rt, a2, "1", "fourth cumulant a2 = 4<c^4>/(d(d+2)) - 1 (Eq. 2.13)"),
            "heat_flux": (rt, heat_flux, "n T v0", "reduced heat flux q_x/(n T v0) = <c^2 c_x>"),
            "thermostat_rate": (
                rt,
                thermostat_rate,
                "1/tau",
                "thermostat energy-input rate -d ln T/dt (Eq. 3.5's left side)",
            ),
            "cooling_rate": (
                rt,
                cooling_rate,
                "1/tau",
                "free cooling rate zeta at T0 (zero field: the HCS cooling rate, Eq. 2.14)",
            ),
            "log_temperature_free": (
                rt,
                log_temperature,
                "1",
                "ln(T/T0) of the freely cooling gas at the window end",
            ),
            "time_free": (
                rt,
                time_free,
                "tau(T0)",
                "time of the freely cooling gas at the window end",
            ),
            "window_end": ("time", window_ends, "tau", "end of the sampling window"),
            "collisions_per_particle": (
                rt,
                collisions_per_particle,
                "1",
                "cumulative collisions per particle at the window end",
            ),
            "cx_weights": (
                ("realization", "cx"),
                cx_weights,
                "1",
                "sum of c_x (3/2 - c_x^2) per c_x bin (the integrand of Eq. 4.6)",
            ),
            "cx_outside_weights": (
                ("realization", "side"),
                cx_outside_weights,
                "1",
                "sum of c_x (3/2 - c_x^2) below / above the histogram range",
            ),
            "cx_counts": (
                ("realization", "cx"),
                cx_counts,
                "1",
                "histogram of c_x over the steady-state snapshots",
            ),
            "cx_outside": (
                ("realization", "side"),
                cx_outside,
                "1",
                "c_x observations below / above the histogram range",
            ),
            "cx_edges": ("cx_edge", cx_edges, "1", "bin edges of c_x"),
            "speed_counts": (
                ("realization", "speed"),
                speed_counts,
                "1",
                "histogram of |c| over the steady-state snapshots",
            ),
            "speed_overflow": (
                "realization",
                speed_overflow,
                "1",
                "|c| observations beyond the histogram range",
            ),
            "speed_edges": ("speed_edge", speed_edges, "1", "bin edges of |c|"),
            "histogram_observations": (
                "realization",
                observations,
                "1",
                "particle observations behind each histogram",
            ),
            "collisions": ("realization", totals["collisions"], "1", "accepted collisions"),
            "candidates": ("realization", totals["candidates"], "1", "candidate pairs"),
            "bound_raises": (
                "realization",
                totals["bound_raises"],
                "1",
                "raises of the relative-speed bound within collision stages",
            ),
            "steps": ("realization", totals["steps"], "1", "time steps"),
            "cpu_seconds": ("realization", cpu_seconds, "s", "CPU (process) time in the kernels"),
        },
        coords={
            "realization": (
                "realization",
                np.arange(first_realization, first_realization + n_realizations),
                "1",
                "realization index (stream row)",
            ),
            "time": (
                "time",
                window_ends - 0.5 * sample_interval,
                "tau",
                "centre of the sampling window",
            ),
            "moment": ("moment", np.array(MOMENT_NAMES), "1", "snapshot moment name"),
            "cx": ("cx", 0.5 * (cx_edges[1:] + cx_edges[:-1]), "1", "c_x bin centre"),
            "cx_edge": ("cx_edge", cx_edges, "1", "c_x bin edge"),
            "speed": ("speed", 0.5 * (speed_edges[1:] + speed_edges[:-1]), "1", "|c| bin centre"),
            "speed_edge": ("speed_edge", speed_edges, "1", "|c| bin edge"),
            "side": ("side", np.array(["below", "above"]), "1", "side of the histogram range"),
        },
        attrs={
            "engine": "kinetic.dsmc",
            "units": "m = sigma = T0 = 1; time in tau = lambda/v0, lambda = 1/(sqrt(2) S n); "
            "c = V/v0, v0 = sqrt(2 T0/m); eps* = lambda eps",
            "histogram_start_tau": histogram_start,
        },
    )
    parameters = {
        **settings.parameters(),
        "duration_tau": duration,
        "sample_interval_tau": sample_interval,
        "sample_stride": sample_stride,
        "histogram_start_tau": histogram_start,
        "n_realizations": n_realizations,
        "first_realization": first_realization,
    }
    return io.stamp(dataset, parameters=parameters, seed=seed)


# ------------------------------------------------------------------- free flights front


def simulate_free_flights(
    *,
    n_particles: int,
    duration: float,
    seed: int,
    dimension: int = 2,
    kernel: str = "hard_spheres",
    restitution: float = 1.0,
    n_realizations: int = 1,
    first_realization: int = 0,
    max_flight_time: float = 20.0,
    n_time_bins: int = 200,
    max_free_path: float = 20.0,
    n_path_bins: int = 200,
    chunk: float = 5.0,
    label: str | None = None,
):
    """Free-flight times and free paths of an equilibrium gas (visco2008 Figs 1, 12).

    Continuous-time DSMC (exact event times by thinning) of N particles starting from
    a Maxwellian at T0 = 1. Every collision ends a free flight of both partners. The
    flights that start (at a collision) within [0, duration) are recorded, and the run
    goes on to duration + max_flight_time so that each of them is either complete or
    known to be longer than the histogram (then counted in the overflow): no bias
    against long flights. The first interval of each particle does not start at a
    collision and is not recorded. Time in 1/ω (ω: the kernel's equilibrium collision
    frequency at T0), lengths in the mean free path l = <v>/ω.

    Parameters
    ----------
    n_particles
        N >= 2.
    duration
        Recording window per realization in 1/ω (> 0); the run lasts duration +
        max_flight_time, done in chunks of about ``chunk``.
    dimension, kernel, restitution
        As in ``HomogeneousSettings`` (α < 1: a cooling gas, times still in 1/ω(T0)).
    max_flight_time, n_time_bins, max_free_path, n_path_bins
        Uniform histogram bins on [0, max]; longer flights go to the overflow counts.
    seed, n_realizations, first_realization
        Realization k uses row k of ``stream_states(seed, ·)``.

    Returns
    -------
    xarray.Dataset: ``time_counts`` (realization, flight_time), ``path_counts``
    (realization, free_path), overflows, ``flights`` (recorded flights),
    ``time_pdf``/``path_pdf`` (counts / (flights x bin width)), ``unresolved_paths``
    (open flights whose path is unknown; a fraction ~ e^{-max_flight_time/√2} of the
    flights for hard spheres), ``collision_frequency`` (2 collisions/(N duration) in the
    window, in ω), ``cpu_seconds``, ``candidates``, ``collisions``.
    """
    _integer("dimension", dimension, 2, 3)
    _choice("kernel", kernel, units.KERNELS)
    _integer("n_particles", n_particles, 2)
    _real("restitution", restitution, 0.0, 1.0, low_open=True)
    duration = _real("duration", duration, 0.0, 1e12, low_open=True, unit=" /omega")
    chunk = _real("chunk", chunk, 0.0, 1e12, low_open=True, unit=" /omega")
    max_flight_time = _real("max_flight_time", max_flight_time, 0.0, 1e6, low_open=True)
    max_free_path = _real("max_free_path", max_free_path, 0.0, 1e6, low_open=True)
    _integer("n_time_bins", n_time_bins, 1)
    _integer("n_path_bins", n_path_bins, 1)
    streams = realization_streams(seed, first_realization, n_realizations)

    d = dimension
    density = 1.0 / units.equilibrium_collision_frequency(kernel, d, 1.0)  # ω = 1
    free_path_unit = units.mean_speed(d, 1.0)  # l = <v>/ω
    coefficient = units.candidate_coefficient(kernel, d, density, n_particles)
    kernel_id = _KERNEL_ID[kernel]
    time_width = max_flight_time / n_time_bins
    path_width = max_free_path / n_path_bins
    # record the flights that start in [0, duration); run on until every one of them has
    # ended or is known to be longer than max_flight_time
    total_time = duration + max_flight_time
    n_chunks = max(1, math.ceil(total_time / chunk - 1e-9))

    time_counts = np.zeros((n_realizations, n_time_bins + 1), dtype=np.int64)
    path_counts = np.zeros((n_realizations, n_path_bins + 1), dtype=np.int64)
    unresolved = np.zeros(n_realizations, dtype=np.int64)
    collisions_in_window = np.zeros(n_realizations, dtype=np.int64)
    tallies = np.zeros((n_realizations, 4), dtype=np.int64)
    cpu_seconds = np.zeros(n_realizations)
    label = label or f"dsmc free flights d={d} {kernel} N={n_particles}"
    progress = Progress(n_realizations * n_chunks, label=label, unit="chunks")

    def observe(velocity, rng, bounds, begin, length, tally, last_collision, times, paths):
        """Collisions in [begin, begin + length), recording the flights started in the window."""
        kernels.collide_observed(
            velocity, rng, kernel_id, restitution, coefficient, begin, length, bounds, tally,
            last_collision, 0.0, duration, time_width, times, path_width * free_path_unit, paths,
        )  # fmt: skip

    tiny = np.zeros((d, 2))
    tiny[0] = [1.0, -1.0]
    tiny_bounds = np.empty(d + 2)
    kernels.speed_bounds(tiny, 0, 2, tiny_bounds)
    observe(
        tiny, streams[0].copy(), tiny_bounds, 0.0, 1e-3, np.zeros(4, dtype=np.int64),
        np.full(2, -1.0), np.zeros(n_time_bins + 1, dtype=np.int64),
        np.zeros(n_path_bins + 1, dtype=np.int64),
    )  # fmt: skip  # compile outside the timers (a no-op once cached)
    for r in range(n_realizations):
        rng = streams[r].copy()
        velocity = np.empty((d, n_particles))
        kernels.maxwellian(velocity, rng, 1.0)
        bounds = np.empty(d + 2)
        kernels.speed_bounds(velocity, 0, n_particles, bounds)
        last_collision = np.full(n_particles, -1.0)
        run_state = (tallies[r], last_collision, time_counts[r], path_counts[r])
        start = time.process_time()
        for c in range(n_chunks):
            begin = c * total_time / n_chunks
            if begin < duration <= (c + 1) * total_time / n_chunks:
                # split the chunk at the end of the window to count its collisions
                observe(velocity, rng, bounds, begin, duration - begin, *run_state)
                collisions_in_window[r] = tallies[r, kernels.TALLY_ACCEPTED]
                begin, length = duration, (c + 1) * total_time / n_chunks - duration
            else:
                length = total_time / n_chunks
            observe(velocity, rng, bounds, begin, length, *run_state)
            progress.update(1)
        cpu_seconds[r] = time.process_time() - start
        if tallies[r, kernels.TALLY_EXCEEDED]:
            raise RuntimeError("internal error: the collision bound was exceeded")
        # flights started in the window and still open: longer than max_flight_time
        open_flights = (last_collision >= 0.0) & (last_collision < duration)
        time_counts[r, -1] += np.count_nonzero(open_flights)
        open_paths = np.sqrt(np.sum(velocity[:, open_flights] ** 2, axis=0)) * (
            total_time - last_collision[open_flights]
        )
        longer = open_paths >= max_free_path * free_path_unit
        path_counts[r, -1] += np.count_nonzero(longer)
        unresolved[r] = np.count_nonzero(~longer)

    flights = time_counts.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        time_pdf = time_counts[:, :-1] / (flights[:, None] * time_width)
        path_pdf = path_counts[:, :-1] / (flights[:, None] * path_width)
    time_edges = np.linspace(0.0, max_flight_time, n_time_bins + 1)
    path_edges = np.linspace(0.0, max_free_path, n_path_bins + 1)
    dataset = io.make_dataset(
        {
            "time_counts": (
                ("realization", "flight_time"),
                time_counts[:, :-1],
                "1",
                "free flights per flight-time bin",
            ),
            "time_overflow": (
                "realization",
                time_counts[:, -1],
                "1",
                "free flights longer than the histogram range",
            ),
            "path_counts": (
                ("realization", "free_path"),
                path_counts[:, :-1],
                "1",
                "free flights per free-path bin",
            ),
            "path_overflow": (
                "realization",
                path_counts[:, -1],
                "1",
                "free paths longer than the histogram range",
            ),
            "flights": ("realization", flights, "1", "recorded free flights"),
            "time_pdf": (
                ("realization", "flight_time"),
                time_pdf,
                "omega",
                "free-flight time distribution P_FFT",
            ),
            "path_pdf": (
                ("realization", "free_path"),
                path_pdf,
                "1/l",
                "free-path distribution P_FPL",
            ),
            "time_edges": ("flight_time_edge", time_edges, "1/omega", "flight-time bin edges"),
            "path_edges": ("free_path_edge", path_edges, "l", "free-path bin edges"),
            "unresolved_paths": (
                "realization",
                unresolved,
                "1",
                "flights open at the end whose free path is unknown (shorter than "
                "max_free_path, longer than max_flight_time)",
            ),
            "collision_frequency": (
                "realization",
                2.0 * collisions_in_window / (n_particles * duration),
                "omega",
                "measured collisions per particle per unit time in the recording window",
            ),
            "collisions": (
                "realization",
                tallies[:, kernels.TALLY_ACCEPTED],
                "1",
                "accepted collisions",
            ),
            "candidates": (
                "realization",
                tallies[:, kernels.TALLY_CANDIDATES],
                "1",
                "candidate pairs",
            ),
            "cpu_seconds": ("realization", cpu_seconds, "s", "CPU (process) time"),
        },
        coords={
            "realization": (
                "realization",
                np.arange(first_realization, first_realization + n_realizations),
                "1",
                "realization index (stream row)",
            ),
            "flight_time": (
                "flight_time",
                0.5 * (time_edges[1:] + time_edges[:-1]),
                "1/omega",
                "free-flight time (bin centre)",
            ),
            "free_path": (
                "free_path",
                0.5 * (path_edges[1:] + path_edges[:-1]),
                "l",
                "free path (bin centre)",
            ),
            "flight_time_edge": ("flight_time_edge", time_edges, "1/omega", "bin edge"),
            "free_path_edge": ("free_path_edge", path_edges, "l", "bin edge"),
        },
        attrs={
            "engine": "kinetic.dsmc",
            "units": "m = sigma = T0 = 1; time in 1/omega (equilibrium collision frequency "
            "of the kernel at T0); length in l = <v>/omega",
        },
    )
    parameters = {
        "n_particles": n_particles,
        "duration_omega": duration,
        "dimension": d,
        "kernel": kernel,
        "restitution": float(restitution),
        "n_realizations": n_realizations,
        "first_realization": first_realization,
        "max_flight_time": max_flight_time,
        "n_time_bins": n_time_bins,
        "max_free_path": max_free_path,
        "n_path_bins": n_path_bins,
    }
    return io.stamp(dataset, parameters=parameters, seed=seed)
