"""Front of the homogeneous DSMC engine: validate, run the kernels in chunks, return a dataset.

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

import inspect

import numpy as np

from kinetic import backends, io, validate
from kinetic.dsmc import kernels
from kinetic.dsmc.arguments import LINEAR_RESPONSE_FIELD, check_windows
from kinetic.dsmc.state import (
    MOMENT_NAMES,
    HomogeneousSettings,
    Samples,
    _compile_outside_the_timers,
    advance_gas,
    new_gas,
    realization_streams,
)
from kinetic.progress import Progress, logger

__all__ = ["simulate_homogeneous", "simulate_homogeneous_points"]


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
    backend: str = "cpu",
    validate_only: bool = False,
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
    backend
        ``"cpu"`` (numba, one realization after the other) or ``"cuda"`` (numba-cuda, all
        realizations of the call together on one GPU: :mod:`kinetic.dsmc.gpu`, collisions
        in random groups of particles re-drawn every step; statistically equivalent, not
        bit-identical). A ``cuda`` run on a machine without a GPU stops before any work
        (``kinetic.backends.BackendUnavailable``).
    validate_only
        Check every argument, and that the backend is usable, and return None without
        any work: a job of several runs checks all of them before running the first
        (``simulate_homogeneous_points``).

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
    ``candidates``, ``bound_raises``, ``steps``, ``cpu_seconds`` (cuda: the batch's wall
    time divided by the realizations). Attributes ``backend``, ``device`` and
    ``collision_groups``: ``whole box`` on the CPU (every pair of the gas a candidate),
    ``sparse`` on ``cuda`` (random groups re-dealt every step, each collided in place:
    :mod:`kinetic.dsmc.gpu`).
    """
    backends.check(backend)
    backends.check_realizations(backend, n_realizations)
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
    windows = check_windows(
        duration=duration,
        sample_interval=sample_interval,
        time_step=time_step,
        sample_stride=sample_stride,
        histogram_start=histogram_start,
    )
    duration, sample_interval, steps_per_window, n_windows = windows[:4]
    histogram_start, first_histogram_window = windows[4:]
    streams = realization_streams(seed, first_realization, n_realizations)
    # the gas (velocities and scratch, ~100 B a particle: kinetic.cost; every realization's
    # at once on cuda) and the per-window results
    gases = n_realizations if backend == "cuda" else 1
    validate.fits_in_memory(
        f"n_particles = {settings.n_particles}, n_realizations = {n_realizations} and "
        f"{n_windows} windows (duration/sample_interval)",
        100.0 * settings.n_particles * gases
        + 8.0 * n_realizations * n_windows * (len(MOMENT_NAMES) + 5),
    )
    samples = Samples(
        stride=sample_stride,
        cx_max=cx_max,
        n_cx_bins=n_cx_bins,
        speed_max=speed_max,
        n_speed_bins=n_speed_bins,
    )
    device = backends.require(backend)  # before any work: no GPU, no run
    if validate_only:
        return None

    d = settings.dimension
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
    lie_bias = LIE_KAPPA_BIAS * settings.time_step
    lie_warned = settings.splitting == "lie" and settings.reduced_field > 0
    if lie_warned and lie_bias > LIE_WARNING_BIAS * (1.0 + 1e-9):
        logger.warning(
            "[%s] the Lie splitting at time_step = %g tau biases kappa'/kappa0 by about "
            "+%.0f %% (+%g dt/tau at alpha = 1, tests/physics/test_dsmc_force_splitting.py); "
            "splitting='strang' is unbiased within 1-2 %% up to 0.4 tau",
            label,
            settings.time_step,
            100 * lie_bias,
            LIE_KAPPA_BIAS,
        )
    progress = Progress(n_realizations * n_windows, label=label, unit="windows")
    out = _empty_results(n_realizations, n_windows, samples)
    run = (settings, samples, streams, n_windows, steps_per_window, first_histogram_window)
    if backend == "cuda":
        from kinetic.dsmc import gpu

        collision_groups = "sparse"
        gpu.run_batch(*run, out, progress)
    else:
        collision_groups = "whole box"
        _compile_outside_the_timers(settings, samples)
        _run_cpu(*run, out, progress)
    moments = out["moments"]
    log_temperature = out["log_temperature"]
    cooling_sum = out["cooling_sum"]
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
            "snapshots": (rt, out["snapshots"], "1", "snapshots averaged in the window"),
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
                out["time_free"],
                "tau(T0)",
                "time of the freely cooling gas at the window end",
            ),
            "window_end": ("time", window_ends, "tau", "end of the sampling window"),
            "collisions_per_particle": (
                rt,
                out["collisions_per_particle"],
                "1",
                "cumulative collisions per particle at the window end",
            ),
            "cx_weights": (
                ("realization", "cx"),
                out["cx_weights"],
                "1",
                "sum of c_x (3/2 - c_x^2) per c_x bin (the integrand of Eq. 4.6)",
            ),
            "cx_outside_weights": (
                ("realization", "side"),
                out["cx_outside_weights"],
                "1",
                "sum of c_x (3/2 - c_x^2) below / above the histogram range",
            ),
            "cx_counts": (
                ("realization", "cx"),
                out["cx_counts"],
                "1",
                "histogram of c_x over the steady-state snapshots",
            ),
            "cx_outside": (
                ("realization", "side"),
                out["cx_outside"],
                "1",
                "c_x observations below / above the histogram range",
            ),
            "cx_edges": ("cx_edge", cx_edges, "1", "bin edges of c_x"),
            "speed_counts": (
                ("realization", "speed"),
                out["speed_counts"],
                "1",
                "histogram of |c| over the steady-state snapshots",
            ),
            "speed_overflow": (
                "realization",
                out["speed_overflow"],
                "1",
                "|c| observations beyond the histogram range",
            ),
            "speed_edges": ("speed_edge", speed_edges, "1", "bin edges of |c|"),
            "histogram_observations": (
                "realization",
                out["observations"],
                "1",
                "particle observations behind each histogram",
            ),
            "collisions": ("realization", out["collisions"], "1", "accepted collisions"),
            "candidates": ("realization", out["candidates"], "1", "candidate pairs"),
            "bound_raises": (
                "realization",
                out["bound_raises"],
                "1",
                "raises of the relative-speed bound within collision stages",
            ),
            "steps": ("realization", out["steps"], "1", "time steps"),
            "cpu_seconds": ("realization", out["cpu_seconds"], "s", _CPU_SECONDS[backend]),
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
                snapshot_times(n_windows, steps_per_window, sample_stride, time_step),
                "tau",
                "mean time of the window's snapshots",
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
            "backend": backend,
            "device": device,
            "collision_groups": collision_groups,
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


def snapshot_times(n_windows: int, steps_per_window: int, stride: int, time_step: float):
    """The mean time of each window's snapshots, which both backends take after the steps
    k = stride, 2 stride, ... of the run: the window's centre plus stride δt/2 when the
    stride divides its steps (0.05-0.075 τ in the configs, which the centre left out)."""
    start = np.arange(n_windows, dtype=np.int64) * steps_per_window  # the steps before
    first = (start // stride + 1) * stride  # (a stride <= the window's steps: one or more)
    last = ((start + steps_per_window) // stride) * stride
    return 0.5 * (first + last) * time_step


LIE_KAPPA_BIAS = 0.3
"""The Lie splitting's relative bias of κ'/κ0 per δt/τ at α = 1 (the module docstring)."""

LIE_WARNING_BIAS = 0.03
"""A forced Lie run whose bias (``LIE_KAPPA_BIAS`` δt/τ) exceeds this is warned of: 0.44 τ,
the largest step allowed, gave about 13 % without a word; δt = 0.1 τ (3 %) passes."""


_CPU_SECONDS = {
    "cpu": "CPU (process) time in the kernels",
    "cuda": "wall time of the GPU run (all realizations together) per realization",
}


_FRONT_DEFAULTS = {
    name: parameter.default
    for name, parameter in inspect.signature(simulate_homogeneous).parameters.items()
}
"""``simulate_homogeneous``'s keyword defaults (those a point leaves out)."""


def simulate_homogeneous_points(points, *, label: str | None = None, finished=None):
    """Several runs of ``simulate_homogeneous`` in one process, one after the other
    (``points``: its keyword arguments each): every point is checked before the first
    runs (``validate_only``), and the kernels are compiled or loaded once, so that a job
    of several runs pays one process's startup (on ``cuda``: one CUDA context, and each
    run's Maxwellian starts built in a thread beside the run before it,
    ``gpu.prefetch_starts``). Returns the datasets ``simulate_homogeneous`` returns for
    the points one at a time, the same numbers; ``label`` (if given) prefixes each
    point's progress label. ``finished(k, dataset)`` (if given) is called as point ``k``
    ends, before the next one starts: a job keeps its finished runs when it is stopped
    (``kinetic.simulation_job``)."""
    points = [dict(point) for point in points]
    if not points:
        raise ValueError("simulate_homogeneous_points needs at least one point")
    for point in points:
        simulate_homogeneous(**point, validate_only=True)
    datasets = []
    for k, point in enumerate(points):
        if k + 1 < len(points) and points[k + 1].get("backend") == "cuda":
            _prefetch_starts(points[k + 1])
        if label:
            point["label"] = f"{label} [{k + 1}/{len(points)}] {point.get('label') or ''}".strip()
        datasets.append(simulate_homogeneous(**point))
        if finished is not None:
            finished(k, datasets[-1])
    return datasets


def _prefetch_starts(point) -> None:
    """Have the GPU engine build the Maxwellian starts of ``point`` (a checked
    ``simulate_homogeneous`` call on ``cuda``) beside the run before it
    (``kinetic.dsmc.gpu.prefetch_starts``)."""
    from kinetic.dsmc import gpu

    arguments = _FRONT_DEFAULTS | point
    streams = realization_streams(
        arguments["seed"], arguments["first_realization"], arguments["n_realizations"]
    )
    gpu.prefetch_starts(arguments["dimension"], arguments["n_particles"], streams)


def _empty_results(count: int, n_windows: int, samples: Samples) -> dict[str, np.ndarray]:
    """The arrays a backend fills: per realization and window, and per realization."""
    shape = (count, n_windows)
    results = {
        "moments": np.full((*shape, len(MOMENT_NAMES)), np.nan),
        "snapshots": np.zeros(shape, dtype=np.int64),
        "cx_counts": np.zeros((count, samples.n_cx_bins), dtype=np.int64),
        "cx_weights": np.zeros((count, samples.n_cx_bins)),
        "cx_outside_weights": np.zeros((count, 2)),
        "cx_outside": np.zeros((count, 2), dtype=np.int64),
        "speed_counts": np.zeros((count, samples.n_speed_bins), dtype=np.int64),
        "speed_overflow": np.zeros(count, dtype=np.int64),
        "cpu_seconds": np.zeros(count),
    }
    for key in ("log_temperature", "cooling_sum", "time_free", "collisions_per_particle"):
        results[key] = np.zeros(shape)
    for key in ("observations", "collisions", "candidates", "bound_raises", "steps"):
        results[key] = np.zeros(count, dtype=np.int64)
    return results


def _run_cpu(
    settings: HomogeneousSettings,
    samples: Samples,
    streams: np.ndarray,
    n_windows: int,
    steps_per_window: int,
    first_histogram_window: int,
    out: dict[str, np.ndarray],
    progress: Progress,
) -> None:
    """The CPU backend: the realizations one after the other, into ``out``."""
    for r in range(streams.shape[0]):
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
            out["snapshots"][r, w] = count
            if count:
                out["moments"][r, w] = samples.moment_sums[1:] / count
            if samples.histogram:
                histogram_snapshots += count
            out["log_temperature"][r, w] = gas.log_temperature_free
            out["cooling_sum"][r, w] = gas.clock[4]
            out["time_free"][r, w] = gas.time_free
            out["collisions_per_particle"][r, w] = 2.0 * gas.collisions / settings.n_particles
            progress.update(1)
        out["cx_counts"][r] = samples.cx_counts[1:-1]
        out["cx_outside"][r] = samples.cx_counts[[0, -1]]
        out["cx_weights"][r] = samples.cx_weights[1:-1]
        out["cx_outside_weights"][r] = samples.cx_weights[[0, -1]]
        out["speed_counts"][r] = samples.speed_counts[:-1]
        out["speed_overflow"][r] = samples.speed_counts[-1]
        out["observations"][r] = histogram_snapshots * settings.n_particles
        out["collisions"][r] = gas.collisions
        out["candidates"][r] = gas.candidates
        out["bound_raises"][r] = gas.tally[kernels.TALLY_RAISED]
        out["steps"][r] = gas.steps
        out["cpu_seconds"][r] = gas.cpu_seconds
