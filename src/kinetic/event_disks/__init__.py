"""event-disks (krauth2025 §4.1 and §4.4.3): a few hard disks in a box with walls, by the
lecture's naive event-driven MD (kernels in ``kinetic.event_disks.kernels``). An engine of
its own, apart from ``kinetic.edmd``: an edit of one reruns none of the other's jobs.

- ``simulate_box``: independent realizations (direct-disks start, Gaussian velocities
  scaled to Σ v² = 2N, i.e. k_B T = 1 with m = 1) run for a fixed time; returns the
  y-density by Eq. (4.3) and from stroboscopic snapshots, the wall hits per face with
  Σ|v⊥| and Σ 1/|v⊥|, the pair collisions with Σ|Δv⊥| and Σ 1/|Δv⊥|, and the time-weighted
  density of one velocity component over R (§4.2.1: uniform on the sphere Σv² = R²), per
  realization;
- ``chaos``: the same initial state run in float32 and float64 (and in float64 from a
  state one unit in the last place away), event by event (§4.1.2), from the classic start
  of Krauth's four-disk program or a random one, and the event sequences of further
  random starts (where the precisions part, with a spread);
- ``initial_state``: the start of realization r of a seed;
- ``warmup``: compile (or load from numba's cache) the kernels for float64 and float32.
"""

from __future__ import annotations

import math
import time

import numpy as np
import xarray as xr

from kinetic import io, validate
from kinetic.event_disks import kernels
from kinetic.progress import Progress
from kinetic.rng import stream_states
from kinetic.samplers import disk_configuration
from kinetic.theory.krauth2025 import (
    CLASSIC_START,
    check_classic_start,
    check_snapshots,
    snapshot_count,
)

__all__ = ["CLASSIC_START", "chaos", "initial_state", "simulate_box", "warmup"]


def initial_state(n_disks: int, sigma: float, box, seed: int, realization: int):
    """Positions (direct-disks, stream ``realization`` of ``seed``) and velocities
    (Gaussian from the same seed, scaled to Σ v² = 2N) of one realization."""
    state = stream_states(seed, 1, realization)[0]
    positions = disk_configuration(n_disks, sigma, box, state=state)
    rng = np.random.default_rng([int(seed), int(realization)])
    velocities = rng.standard_normal((n_disks, 2))
    velocities *= math.sqrt(2 * n_disks / np.sum(velocities**2))
    return positions, velocities


def _positive(name: str, value: float) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise TypeError(f"{name} must be a number, got {value!r}")
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name} must be finite and > 0, got {value!r}")
    return float(value)


def simulate_box(
    *,
    n_disks: int,
    sigma: float,
    box=(1.0, 1.0),
    duration: float,
    snapshot_interval: float,
    bins: int,
    realizations: int,
    seed: int,
    velocity_bins: int = 40,
) -> xr.Dataset:
    """Run ``realizations`` independent systems for ``duration`` each (see the module
    docstring). Densities are disk centres per unit length of y on [σ, L_y − σ]."""
    duration = _positive("duration", duration)
    snapshot_interval = _positive("snapshot_interval", snapshot_interval)
    check_snapshots(duration, snapshot_interval)
    bins = validate.integer("bins", bins, 1)
    velocity_bins = validate.integer("velocity_bins", velocity_bins, 2)
    realizations = validate.integer("realizations", realizations, 2)
    box = np.array([float(side) for side in box])
    # validates N, σ and the box, and fails before any run if no start can be drawn
    starts = [initial_state(n_disks, sigma, box, seed, r) for r in range(realizations)]
    lower, upper = sigma, box[1] - sigma
    occupancy = np.zeros((realizations, bins))
    snapshots = np.zeros((realizations, bins))
    walls = np.zeros((realizations, 4, 3))
    pairs = np.zeros((realizations, 3))
    velocity_time = np.zeros((realizations, velocity_bins))
    events = np.zeros(realizations, dtype=np.int64)
    radius2 = np.zeros(realizations)
    cpu = np.zeros(realizations)
    progress = Progress(realizations, label=f"event-disks N={n_disks}", unit="realizations")
    x, v = starts[0]

    def observers(r: int, radius: float) -> kernels.Observers:
        """Realization r's observers, velocities in units of ``radius``."""
        return kernels.Observers(
            occupancy[r],
            snapshots[r],
            float(snapshot_interval),
            float(lower),
            float(upper),
            walls[r],
            pairs[r],
            velocity_time[r],
            float(radius),
        )

    # load the compiled kernel before the clock runs (a run of length 0)
    kernels.observe(x.copy(), v.copy(), float(sigma), box, 0.0, observers(0, 1.0))
    for r, (x, v) in enumerate(starts):
        radius2[r] = np.sum(v**2)
        begin = time.process_time()
        events[r] = kernels.observe(
            x, v, float(sigma), box, float(duration), observers(r, math.sqrt(radius2[r]))
        )
        cpu[r] = time.process_time() - begin
        progress.update(1)
    width = (upper - lower) / bins
    n_snapshots = snapshot_count(duration, snapshot_interval)
    edges = np.linspace(lower, upper, bins + 1)
    data = {
        "density_trajectory": (
            ("realization", "y"),
            occupancy / (duration * width),
            "1/length",
            "y-density by Eq. 4.3 (time spent per bin over T and the bin width)",
        ),
        "density_snapshots": (
            ("realization", "y"),
            snapshots / (n_snapshots * width),
            "1/length",
            "y-density of stroboscopic snapshots",
        ),
        "wall_statistics": (
            ("realization", "face", "statistic"),
            walls,
            "1",
            "wall hits per face: count, sum |v_perp|, sum 1/|v_perp|",
        ),
        "pair_statistics": (
            ("realization", "statistic"),
            pairs,
            "1",
            "pair collisions: count, sum |dv_perp|, sum 1/|dv_perp|",
        ),
        "events": ("realization", events, "1", "events (pair and wall collisions)"),
        "radius_squared": ("realization", radius2, "length^2/time^2", "R^2 = sum of v^2"),
        "cpu_seconds": ("realization", cpu, "s", "CPU time per realization"),
        "bin_edges": ("edge", edges, "length", "bin edges"),
        "velocity_density": (
            ("realization", "u"),
            velocity_time / (duration * 2 * n_disks * (2.0 / velocity_bins)),
            "1",
            "time-weighted density of u = v_a/R, one velocity component over the radius "
            "of the velocity sphere, both components of every disk",
        ),
        "velocity_edges": (
            "velocity_edge",
            np.linspace(-1.0, 1.0, velocity_bins + 1),
            "1",
            "bin edges of u",
        ),
    }
    coords = {
        "y": ("y", 0.5 * (edges[1:] + edges[:-1]), "length", "disk centre y (bin middle)"),
        "realization": ("realization", np.arange(realizations), "1", "independent run"),
        "face": ("face", ["x=0", "x=Lx", "y=0", "y=Ly"], "1", "wall"),
        "statistic": ("statistic", ["count", "sum", "sum_inverse"], "1", "accumulated sum"),
        "edge": ("edge", np.arange(bins + 1), "1", "bin edge index"),
        "u": (
            "u",
            np.linspace(-1.0, 1.0, velocity_bins + 1)[:-1] + 1.0 / velocity_bins,
            "1",
            "v_a/R (bin middle)",
        ),
        "velocity_edge": ("velocity_edge", np.arange(velocity_bins + 1), "1", "edge index"),
    }
    parameters = {
        "n_disks": int(n_disks),
        "sigma": float(sigma),
        "box_x": float(box[0]),
        "box_y": float(box[1]),
        "duration": duration,
        "snapshot_interval": snapshot_interval,
        "bins": bins,
        "realizations": realizations,
        "snapshot_count": n_snapshots,
        "velocity_bins": velocity_bins,
    }
    return io.stamp(io.make_dataset(data, coords), parameters=parameters, seed=seed)


def _classic_start(n_disks: int, sigma: float, box) -> tuple[np.ndarray, np.ndarray]:
    check_classic_start(n_disks, sigma, box)
    return np.array(CLASSIC_START["positions"]), np.array(CLASSIC_START["velocities"])


def _parting_runs(x, v, sigma, box, events: int):
    """The three runs of one start (float64, float32, float64 one ulp away), from the
    start rounded to float32 so that every run begins from exactly the same numbers."""
    x = x.astype(np.float32).astype(np.float64)
    v = v.astype(np.float32).astype(np.float64)
    runs = {
        "float64": (x.copy(), v.copy(), np.float64),
        "float32": (x.astype(np.float32), v.astype(np.float32), np.float32),
        "float64_ulp": (np.nextafter(x, np.inf), v.copy(), np.float64),
    }
    n_disks = x.shape[0]
    times = np.zeros((len(runs), events))
    pairs = np.zeros((len(runs), events, 2), dtype=np.int64)
    positions = np.zeros((len(runs), events, n_disks, 2))
    for index, (xr_, vr, dtype) in enumerate(runs.values()):
        event_time = np.zeros(events, dtype=dtype)
        event_positions = np.zeros((events, n_disks, 2), dtype=dtype)
        kernels.trajectory(
            xr_,
            vr,
            dtype(sigma),
            np.asarray(box, dtype=dtype),
            events,
            event_time,
            pairs[index],
            event_positions,
        )
        times[index] = event_time
        positions[index] = event_positions
    return list(runs), x, v, times, pairs, positions


MAX_CHAOS_EVENTS = 10**6
"""Most events of a ``chaos`` run (its arrays grow with them; 10¹⁰ asked for 224 GiB)."""


def chaos(
    *,
    n_disks: int,
    sigma: float,
    box=(1.0, 1.0),
    events: int,
    seed: int,
    start: str = "random",
    extra_starts: int = 0,
) -> xr.Dataset:
    """One initial state run for ``events`` events in float64, in float32, and in float64
    from positions moved by one unit in the last place; ``start`` is "classic"
    (:data:`CLASSIC_START`) or "random" (realization 0 of ``seed``). ``extra_starts``
    random starts (realizations 1, 2, ... of ``seed``) add their event sequences
    (``start_event_pair``) for the statistics of where the precisions part."""
    # the run keeps every event's positions in each precision (10^6 events: about 22 MiB);
    # the precisions part after about 60 pair collisions
    events = validate.integer("events", events, 1, MAX_CHAOS_EVENTS)
    extra_starts = validate.integer("extra_starts", extra_starts, 0)
    if start == "classic":
        x, v = _classic_start(n_disks, sigma, box)
    elif start == "random":
        x, v = initial_state(n_disks, sigma, box, seed, 0)
    else:
        raise ValueError(f"start must be 'classic' or 'random', got {start!r}")
    names, x, v, times, pairs, positions = _parting_runs(x, v, sigma, box, events)
    start_pairs = [pairs]
    for realization in range(1, extra_starts + 1):
        xs, vs = initial_state(n_disks, sigma, box, seed, realization)
        start_pairs.append(_parting_runs(xs, vs, sigma, box, events)[4])
    data = {
        "event_time": (("precision", "event"), times, "time", "time of the event"),
        "event_pair": (
            ("precision", "event", "member"),
            pairs,
            "1",
            "disks of the event (second member -1 - face for a wall)",
        ),
        "positions": (
            ("precision", "event", "disk", "axis"),
            positions,
            "length",
            "positions right after the event",
        ),
        "initial_positions": (("disk", "axis"), x, "length", "common initial positions"),
        "initial_velocities": (
            ("disk", "axis"),
            v,
            "length/time",
            "common initial velocities",
        ),
        "start_event_pair": (
            ("start", "precision", "event", "member"),
            np.array(start_pairs),
            "1",
            "event_pair of every start (start 0: the one above; then random starts)",
        ),
    }
    coords = {
        "precision": ("precision", names, "1", "arithmetic of the run"),
        "start": ("start", np.arange(extra_starts + 1), "1", "initial state"),
        "event": ("event", np.arange(1, events + 1), "1", "event number"),
        "member": ("member", [0, 1], "1", "first or second member"),
        "disk": ("disk", np.arange(n_disks), "1", "disk"),
        "axis": ("axis", ["x", "y"], "1", "coordinate"),
    }
    parameters = {
        "n_disks": int(n_disks),
        "sigma": float(sigma),
        "events": events,
        "start": start,
        "extra_starts": extra_starts,
    }
    parameters.update({"box_x": float(box[0]), "box_y": float(box[1])})
    return io.stamp(io.make_dataset(data, coords), parameters=parameters, seed=seed)


def warmup() -> None:
    """Compile the kernels for float64 and float32 arrays (numba cache=True: later processes
    load the machine code), without the direct-disks start (compiled by
    ``kinetic.samplers``)."""
    for dtype in (np.float64, np.float32):
        x = np.array([[0.3, 0.3], [0.7, 0.7]], dtype=dtype)
        v = np.array([[1.0, 0.5], [-0.5, -1.0]], dtype=dtype)
        pairs = np.zeros((3, 2), dtype=np.int64)
        kernels.trajectory(
            x,
            v,
            dtype(0.1),
            np.ones(2, dtype=dtype),
            3,
            np.zeros(3, dtype=dtype),
            pairs,
            np.zeros((3, 2, 2), dtype=dtype),
        )
    x = np.array([[0.3, 0.3], [0.7, 0.7]])
    v = np.array([[1.0, 0.5], [-0.5, -1.0]])
    observers = kernels.Observers(
        np.zeros(4), np.zeros(4), 0.5, 0.1, 0.9, np.zeros((4, 3)), np.zeros(3), np.zeros(4), 1.0
    )
    kernels.observe(x, v, 0.1, np.ones(2), 2.0, observers)
