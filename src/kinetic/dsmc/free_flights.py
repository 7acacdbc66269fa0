"""Front of the continuous-time DSMC engine with free-flight observers.

``simulate_free_flights`` (visco2008 Figs 1, 12)
    An equilibrium gas run in continuous time (exact exponential event times), with
    histograms of every particle's free-flight times and free paths. Units: visco2008 —
    T0 = 1, time in 1/ω, length in the mean free path l = <v>/ω.
"""

from __future__ import annotations

import math
import time

import numpy as np

from kinetic import gas as units
from kinetic import io, validate
from kinetic.dsmc import kernels
from kinetic.dsmc.state import _KERNEL_ID, realization_streams
from kinetic.progress import Progress

__all__ = ["simulate_free_flights"]

_NO_CARRY = np.zeros(1)
"""``Collisions.carry`` of the Poisson clock, which carries nothing."""

MAX_CHUNKS = 10**6
"""Most chunks (kernel calls, each a few microseconds of Python) of one realization."""


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
    validate.integer("dimension", dimension, 2, 3)
    validate.choice("kernel", kernel, units.KERNELS)
    validate.integer("n_particles", n_particles, 2)
    validate.real("restitution", restitution, 0.0, 1.0, low_open=True)
    duration = validate.real("duration", duration, 0.0, 1e12, low_open=True, unit=" /omega")
    chunk = validate.real("chunk", chunk, 0.0, 1e12, low_open=True, unit=" /omega")
    max_flight_time = validate.real("max_flight_time", max_flight_time, 0.0, 1e6, low_open=True)
    max_free_path = validate.real("max_free_path", max_free_path, 0.0, 1e6, low_open=True)
    validate.integer("n_time_bins", n_time_bins, 1, validate.MAX_BINS)
    validate.integer("n_path_bins", n_path_bins, 1, validate.MAX_BINS)
    streams = realization_streams(seed, first_realization, n_realizations)
    validate.fits_in_memory(  # the gas and its flight records, ~100 B a particle
        f"n_particles = {n_particles}", 100.0 * n_particles
    )

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
    if n_chunks > MAX_CHUNKS:  # a kernel call each: chunk = 1e-9 asked for 2e9 of them
        raise ValueError(
            f"chunk = {chunk!r} cuts duration + max_flight_time = {total_time:g} into "
            f"{n_chunks} kernel calls, more than {MAX_CHUNKS}: use chunk >= "
            f"{total_time / MAX_CHUNKS:.3g}"
        )

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
        collisions = kernels.Collisions(
            kernel=kernel_id,
            restitution=float(restitution),
            pair_coefficient=float(coefficient),
            duration=float(length),
            poisson=True,
            bounds=bounds,
            carry=_NO_CARRY,
            tally=tally,
        )
        flights = kernels.Flights(
            last_collision=last_collision,
            record_start=0.0,
            record_end=float(duration),
            time_bin_width=float(time_width),
            time_counts=times,
            path_bin_width=float(path_width * free_path_unit),
            path_counts=paths,
        )
        kernels.collide_observed(velocity, rng, collisions, float(begin), flights)

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
