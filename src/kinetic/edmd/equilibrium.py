"""Front of the event-driven MD: independent equilibrium realizations -> one Dataset.

``simulate`` runs the protocol of visco2008 §IV.B: N hard disks (or spheres) in a periodic
box at number density ρ, each realization from its own random stream (row ``k`` of
``kinetic.rng.stream_states(seed, ...)`` for realization number ``k``, so results do not
depend on how realizations are batched), an equilibration of a few collisions per particle
during which the mean free time τ_eq is measured, then a production run of ``duration``
mean free times observed without storing history:

- per-particle collision counts in consecutive windows of the lengths ``windows`` (in units
  of τ_eq), histogrammed, cumulatively at each of the production lengths ``checkpoints``;
- free-flight times and free paths (histograms with fixed bins in units of the Enskog mean
  free time and mean free path of the initial temperature; the analysis rescales them to the
  measured ones, see ``kinetic.analysis.collision_statistics``);
- collision counts, temperature and process CPU time at each checkpoint.

Units: m = 1, σ = 1 (``diameter``), T0 = 1 (``temperature``); simulation time in
σ√(m/T0). Only the ``cpu_time`` variable is not reproducible (it is measured).
"""

from __future__ import annotations

import logging
import math
import time
from collections.abc import Sequence

import numpy as np

from kinetic import io, rng
from kinetic.edmd.arguments import DEFAULT_CELL_OCCUPANCY, check_simulate, packing_fraction
from kinetic.edmd.observers import Observers
from kinetic.edmd.system import HardSphereSystem, enskog_collision_frequency
from kinetic.gas import mean_speed
from kinetic.progress import Progress

__all__ = ["count_bins_for", "simulate"]

logger = logging.getLogger("kinetic")


def count_bins_for(longest_window: float) -> int:
    """Histogram size for the counts in windows up to ``longest_window`` mean free times:
    far beyond any count that occurs (the large-deviation tails decay like e^{-t π(n)})."""
    return int(3.0 * longest_window + 12.0 * math.sqrt(longest_window) + 40.0)


def simulate(
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
):
    """Equilibrium MD realizations with collision-count, free-flight and free-path observers.

    Parameters (keyword-only)
    -------------------------
    n_particles : N ≥ 2.
    density : ρσ^d > 0 (packing fraction below 0.45 in d = 2, 0.30 in d = 3).
    seed : root seed of the realization streams (integer ≥ 0).
    realizations : number of independent realizations in this call (≥ 1), numbered
        ``first_realization`` ... ``first_realization + realizations − 1``.
    dimension : 2 or 3.
    equilibration : collisions per particle before observing (≥ 1; the mean free time
        measured during it is kept as ``equilibration_mean_free_time``).
        ``windows``, ``duration`` and ``checkpoints`` are in Enskog's mean free time
        1/ω_E, the same simulated time in every realization. (Until 2026-12-01 each
        realization used the mean free time it measured while equilibrating, 1.4 % apart
        at 10 collisions a particle: the windows of the realizations differed by that
        much, and their pooled count histograms were wider than any one's, k2 +0.0098 at
        t = 50.)
    duration : production length in mean free times (≥ the longest window).
    windows : window lengths t in mean free times (each > 0, ≤ duration).
    checkpoints : increasing production lengths (mean free times, last one = duration) at
        which the cumulative count histograms, collisions and CPU time are saved (default:
        only ``duration``).
    flight_time_max, flight_time_bins : range (Enskog mean free times) and number of bins
        of the free-flight-time histogram; free_path_max, free_path_bins likewise in Enskog
        mean free paths l = ⟨v⟩/ω.
    cell_occupancy : mean particles per cell (speed only; default by dimension).
    label : prefix of the progress lines.

    Returns an ``xarray.Dataset`` (dims realization, checkpoint, window, count, flight_time,
    free_path), every variable with units and long_name, parameters and seed stamped.
    """
    # ------------------------------------------------------------------ validation
    # the parameters are the only locals yet: check them all with the same names
    windows, checkpoints = check_simulate(**locals())

    # ------------------------------------------------------------------ set-up
    from kinetic.edmd import warmup

    warmup()
    omega_enskog = enskog_collision_frequency(density, dimension)
    tau_enskog = 1.0 / omega_enskog
    path_enskog = mean_speed(dimension, 1.0) * tau_enskog
    flight_width = flight_time_max * tau_enskog / flight_time_bins
    path_width = free_path_max * path_enskog / free_path_bins
    count_bins = count_bins_for(windows[-1])
    states = rng.stream_states(seed, realizations, first_realization)
    label = label or f"edmd N={n_particles} rho={density:g}"
    n_checkpoints = checkpoints.size
    n_windows = windows.size
    shape_rc = (realizations, n_checkpoints)
    out = {
        "window_histogram": np.zeros((*shape_rc, n_windows, count_bins), dtype=np.int64),
        "window_overflow": np.zeros((*shape_rc, n_windows), dtype=np.int64),
        "collisions": np.zeros(shape_rc, dtype=np.int64),
        "production_time": np.zeros(shape_rc),
        "temperature": np.zeros(shape_rc),
        "cpu_time": np.zeros(shape_rc),
        "window_time": np.zeros((realizations, n_windows)),
        "equilibration_mean_free_time": np.zeros(realizations),
        "flight_time_histogram": np.zeros((realizations, flight_time_bins), dtype=np.int64),
        "free_path_histogram": np.zeros((realizations, free_path_bins), dtype=np.int64),
        "flight_sums": np.zeros((realizations, 7)),
        "crossings": np.zeros(realizations, dtype=np.int64),
        "pair_tests": np.zeros(realizations, dtype=np.int64),
        "invalid_events": np.zeros(realizations, dtype=np.int64),
    }
    expected_collisions = realizations * (equilibration + duration) * n_particles / 2.0
    progress = Progress(expected_collisions, label=label, unit="collisions")

    # ------------------------------------------------------------------ realizations
    for r in range(realizations):
        cpu_start = time.process_time()
        system = HardSphereSystem(
            n_particles=n_particles,
            density=density,
            dimension=dimension,
            stream=states[r],
            cell_occupancy=cell_occupancy,
        )
        equilibration_collisions = max(1, round(equilibration * n_particles / 2.0))
        system.run(collisions=equilibration_collisions)
        progress.update(equilibration_collisions)
        out["equilibration_mean_free_time"][r] = (
            system.time * n_particles / (2.0 * system.collisions)
        )
        out["window_time"][r] = windows * tau_enskog
        observers = Observers.create(
            n_particles,
            window_lengths=windows * tau_enskog,
            count_bins=count_bins,
            flight_bin_width=flight_width,
            flight_bins=flight_time_bins,
            path_bin_width=path_width,
            path_bins=free_path_bins,
        )
        observers.start(system)
        start_time = system.time
        start_collisions = system.collisions
        start_counters = system.counters()
        done = start_collisions
        chunk = duration * tau_enskog / 50.0
        for c, checkpoint in enumerate(checkpoints):
            target = start_time + checkpoint * tau_enskog
            while system.time < target:
                system.run(until=min(target, system.time + chunk), observers=observers)
                progress.update(system.collisions - done)
                done = system.collisions
            out["window_histogram"][r, c] = observers.window_histogram
            out["window_overflow"][r, c] = observers.window_overflow
            out["collisions"][r, c] = system.collisions - start_collisions
            out["production_time"][r, c] = system.time - start_time
            out["temperature"][r, c] = system.kinetic_temperature()
            out["cpu_time"][r, c] = time.process_time() - cpu_start
        out["flight_time_histogram"][r] = observers.flight_histogram
        out["free_path_histogram"][r] = observers.path_histogram
        out["flight_sums"][r] = observers.flight_sums
        counters = system.counters()
        for key in ("crossings", "pair_tests", "invalid_events"):
            out[key][r] = counters[key] - start_counters[key]
        if observers.window_overflow.any():
            logger.warning(
                "[%s] realization %d: %d counts beyond the histogram",
                label,
                first_realization + r,
                int(observers.window_overflow.sum()),
            )

    # ------------------------------------------------------------------ dataset
    sums = out["flight_sums"]
    length_unit = "sigma"
    time_unit = "sigma*sqrt(m/T0)"
    data_vars = {
        "window_histogram": (
            ("realization", "checkpoint", "window", "count"),
            out["window_histogram"],
            "1",
            "number of (particle, window) pairs with that many collisions, "
            "complete windows up to the checkpoint",
        ),
        "window_overflow": (
            ("realization", "checkpoint", "window"),
            out["window_overflow"],
            "1",
            "particle-windows with more collisions than the histogram holds",
        ),
        "collisions": (
            ("realization", "checkpoint"),
            out["collisions"],
            "1",
            "pair collisions in the production run up to the checkpoint",
        ),
        "production_time": (
            ("realization", "checkpoint"),
            out["production_time"],
            time_unit,
            "production time simulated up to the checkpoint",
        ),
        "temperature": (
            ("realization", "checkpoint"),
            out["temperature"],
            "T0",
            "kinetic temperature sum(v^2)/(d N) at the checkpoint",
        ),
        "cpu_time": (
            ("realization", "checkpoint"),
            out["cpu_time"],
            "s",
            "process CPU time of the realization up to the checkpoint, equilibration "
            "included (measured: the one non-reproducible variable)",
        ),
        "window_time": (
            ("realization", "window"),
            out["window_time"],
            time_unit,
            "window length in simulation time (window / Enskog collision frequency)",
        ),
        "equilibration_mean_free_time": (
            "realization",
            out["equilibration_mean_free_time"],
            time_unit,
            "mean free time measured during the equilibration, N t / (2 collisions)",
        ),
        "flight_time_histogram": (
            ("realization", "flight_time"),
            out["flight_time_histogram"],
            "1",
            "free flights (between two collisions of a particle) per flight-time bin",
        ),
        "free_path_histogram": (
            ("realization", "free_path"),
            out["free_path_histogram"],
            "1",
            "free flights per free-path bin",
        ),
        "flight_count": ("realization", sums[:, 0], "1", "free flights observed"),
        "flight_time_sum": ("realization", sums[:, 1], time_unit, "sum of free-flight times"),
        "flight_time_sum_squares": (
            "realization",
            sums[:, 2],
            f"({time_unit})^2",
            "sum of squared free-flight times",
        ),
        "free_path_sum": ("realization", sums[:, 3], length_unit, "sum of free paths"),
        "free_path_sum_squares": (
            "realization",
            sums[:, 4],
            f"{length_unit}^2",
            "sum of squared free paths",
        ),
        "flight_time_overflow": (
            "realization",
            sums[:, 5],
            "1",
            "free flights longer than the histogram range",
        ),
        "free_path_overflow": (
            "realization",
            sums[:, 6],
            "1",
            "free paths longer than the histogram range",
        ),
        "crossings": ("realization", out["crossings"], "1", "cell crossings in the production run"),
        "pair_tests": (
            "realization",
            out["pair_tests"],
            "1",
            "pair collision predictions in the production run",
        ),
        "invalid_events": (
            "realization",
            out["invalid_events"],
            "1",
            "popped predictions invalidated by the partner's collision",
        ),
    }
    coords = {
        "realization": (
            "realization",
            np.arange(first_realization, first_realization + realizations),
            "1",
            "realization number (row of the seed's stream states)",
        ),
        "checkpoint": (
            "checkpoint",
            checkpoints,
            "equilibration mean free times",
            "production length at which the cumulative observers are saved",
        ),
        "window": ("window", windows, "equilibration mean free times", "counting window length t"),
        "count": ("count", np.arange(count_bins), "1", "collisions of a particle in a window"),
        "flight_time": (
            "flight_time",
            (np.arange(flight_time_bins) + 0.5) * flight_width,
            time_unit,
            "centre of the free-flight-time bin",
        ),
        "free_path": (
            "free_path",
            (np.arange(free_path_bins) + 0.5) * path_width,
            length_unit,
            "centre of the free-path bin",
        ),
    }
    parameters = {
        "engine": "edmd",
        "n_particles": int(n_particles),
        "density": float(density),
        "dimension": int(dimension),
        "packing_fraction": packing_fraction(density, dimension),
        "restitution": 1.0,
        "boundary": "periodic",
        "temperature": 1.0,
        "diameter": 1.0,
        "equilibration": float(equilibration),
        "duration": float(duration),
        "first_realization": int(first_realization),
        "realizations": int(realizations),
        "flight_time_bin_width": flight_width,
        "free_path_bin_width": path_width,
        "enskog_collision_frequency": omega_enskog,
        "cell_occupancy": float(cell_occupancy or DEFAULT_CELL_OCCUPANCY[dimension]),
    }
    dataset = io.make_dataset(data_vars, coords)
    return io.stamp(dataset, parameters=parameters, seed=int(seed))
