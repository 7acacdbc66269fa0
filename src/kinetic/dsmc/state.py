"""The homogeneous DSMC gas: validated settings, the state of one realization, stepping.

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
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from kinetic import gas as units
from kinetic import validate
from kinetic.dsmc import kernels
from kinetic.dsmc.arguments import check_settings, collision_frequency
from kinetic.rng import stream_states
from kinetic.seeds import checked_stream

__all__ = [
    "MOMENT_NAMES",
    "HomogeneousGas",
    "HomogeneousSettings",
    "Samples",
    "advance_gas",
    "new_gas",
    "realization_streams",
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

_KERNEL_ID = {
    "hard_spheres": kernels.HARD_SPHERES,
    "maxwell": kernels.MAXWELL,
    "very_hard": kernels.VERY_HARD,
}


# ------------------------------------------------------------- homogeneous gas: state


@dataclass(frozen=True)
class HomogeneousSettings:
    """Validated parameters of one homogeneous DSMC run (montanero2007 units).

    n_particles: N >= 2. restitution: α in (0, 1]. time_step: δt in τ, with at most
    ``arguments.MAX_COLLISIONS_PER_STEP`` collisions per particle per step on average.
    dimension: 2 or 3. kernel: "hard_spheres", "maxwell" or "very_hard".
    reduced_field: ε* in [0, ``arguments.MAX_REDUCED_FIELD``], with ε* δt/τ <=
    ``arguments.MAX_FIELD_STEP``.
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
        check_settings(
            n_particles=self.n_particles,
            restitution=self.restitution,
            time_step=self.time_step,
            dimension=self.dimension,
            kernel=self.kernel,
            reduced_field=self.reduced_field,
            force_step=self.force_step,
            selection=self.selection,
            splitting=self.splitting,
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
        return collision_frequency(self.kernel, self.dimension)

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
        validate.integer("sample_stride", self.stride, 1)
        validate.real("cx_max", self.cx_max, 0.0, 1e3, low_open=True)
        if (
            isinstance(self.n_cx_bins, bool)
            or not isinstance(self.n_cx_bins, int | np.integer)
            or self.n_cx_bins < 2
            or self.n_cx_bins % 2
            or self.n_cx_bins > validate.MAX_BINS
        ):
            raise ValueError(
                f"n_cx_bins = {self.n_cx_bins!r} must be an even integer in [2, "
                f"{validate.MAX_BINS}]"
            )
        validate.real("speed_max", self.speed_max, 0.0, 1e3, low_open=True)
        validate.integer("n_speed_bins", self.n_speed_bins, 1, validate.MAX_BINS)
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
    validate.seed(seed)
    first, count = validate.realizations(first, count, count_name="n_realizations")
    return stream_states(seed, count, first)


def maxwellian_starts(dimension: int, n_particles: int, streams: np.ndarray):
    """The Maxwellian starts of a batch of realizations (one row of ``streams`` each), as
    ``new_gas`` draws them one at a time, the same numbers: ``(velocity, states, tops)``,
    the velocities (R, d, N), the streams after the draws (R, 4) and each realization's
    largest speed (R,). One compiled call that releases the GIL
    (``kernels.maxwellian_batch``)."""
    streams = np.ascontiguousarray(streams, dtype=np.uint64)
    velocity = np.empty((streams.shape[0], dimension, n_particles))
    states = streams.copy()
    tops = np.empty(streams.shape[0])
    kernels.maxwellian_batch(velocity, states, tops)
    return velocity, states, tops


def new_gas(
    settings: HomogeneousSettings, stream: np.ndarray, velocity: np.ndarray | None = None
) -> HomogeneousGas:
    """Initial state: a Maxwellian drawn from ``stream`` (copied), or ``velocity``.

    A given ``velocity`` ((d, N), finite, not all equal) is shifted to zero momentum and
    rescaled to T = T0 = 1 (as the thermostat would), so only its shape matters: e.g. a
    Maxwellian plus one particle far in the tail (a velocity outlier).
    """
    d, n = settings.dimension, settings.n_particles
    rng = checked_stream(stream)
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
    validate.integer("n_steps", n_steps, 0)
    s = gas.settings
    if samples is None:
        samples = _NO_SAMPLES
        stride = 2**62
        histogram = False
    else:
        stride = samples.stride
        histogram = samples.histogram
    inverse_v0 = 1.0 / units.thermal_speed(1.0)
    collisions = kernels.Collisions(
        kernel=_KERNEL_ID[s.kernel],
        restitution=float(s.restitution),
        pair_coefficient=float(s.pair_coefficient),
        duration=float(s.time_step * s.tau),
        poisson=s.selection == "poisson",
        bounds=gas.bounds,
        carry=gas.carry,
        tally=gas.tally,
    )
    forcing = kernels.Forcing(
        half_field_step=float(s.half_field_step),
        exact=s.force_step == "exact",
        strang=s.splitting == "strang",
        target_energy=float(s.target_energy),
        rate_exponent=float(units.rate_exponent(s.kernel)),
    )
    sampling = kernels.Sampling(
        stride=int(stride),
        inverse_v0=inverse_v0,
        moment_sums=samples.moment_sums,
        histogram=bool(histogram),
        cx_low=-float(samples.cx_max),
        cx_width=2.0 * samples.cx_max / samples.n_cx_bins,
        cx_counts=samples.cx_counts,
        cx_weights=samples.cx_weights,
        speed_width=samples.speed_max / samples.n_speed_bins,
        speed_counts=samples.speed_counts,
    )
    start = time.process_time()
    status = kernels.advance(
        gas.velocity, gas.rng, collisions, forcing, sampling, gas.clock, n_steps
    )
    gas.cpu_seconds += time.process_time() - start
    if status != kernels.STATUS_OK:
        # a = ε δt/2 (ε δt/4 for Strang's half steps) times v0 per unit c_x
        per_unit = s.reduced_field * s.time_step / (4.0 if s.splitting == "strang" else 2.0)
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
