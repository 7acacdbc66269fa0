"""event-disks: the naive event-driven MD of krauth2025 (Algs. 4.1-4.3) for a few hard
disks of radius σ in the box [0, L0] × [0, L1] with walls.

Every event recomputes all N(N − 1)/2 pair times (Alg. 4.2) and N wall times, moves every
disk to the earliest one and executes it (Alg. 4.3 for a pair): O(N²) per event, which
is what the lecture's program does and what makes it an independent check of
``kinetic.edmd`` (cell lists, calendar, lazy positions) on small systems.

Two kernels:

- ``trajectory``: the first events from a state, in the precision of the arrays it is
  given (float32 or float64: every constant is derived from the inputs, so a float32 run
  stays float32), returning each event's time and pair and the positions after it; the
  chaos of krauth2025 §4.1.2 compares runs at two precisions;
- ``observe``: a long float64 run that feeds observers without storing the history:
  the y-density by Eq. (4.3) (for each straight flight the time spent in each bin of y,
  which is Σ 1/|v_y| over the crossings of a strip, divided by T), the y-density of
  stroboscopic snapshots every Δt, the wall hits per face with Σ|v⊥| and Σ 1/|v⊥|
  (pressure estimators 4.9 and 4.10) and the pair collisions with Σ|Δv⊥| and Σ 1/|Δv⊥|
  (Eq. 4.14).

Faces are numbered 2k + (1 if the wall is at L_k, 0 if at 0). Disks must start legal
(inside [σ, L_k − σ], no overlap); the front (``kinetic.event_disks``) checks that.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from kinetic.jit import inline, kernel

__all__ = ["observe", "trajectory"]


@inline
def _next_event(x, v, sigma, box):
    """(dt, k, l) of the earliest event from now: a pair (k, l) or a wall (k, −1 − face).

    Pair times by Alg. 4.2 (Υ > 0 and Δx·Δv < 0); wall times by time of flight to the
    plane at σ from the wall. Arithmetic in the arrays' precision."""
    n = x.shape[0]
    zero = sigma - sigma
    four = (sigma + sigma) / sigma * (sigma + sigma) / sigma  # 4 in the input precision
    best = zero
    best_k = -1
    best_l = -1
    found = False
    for k in range(n):
        for axis in range(2):
            speed = v[k, axis]
            if speed > zero:
                dt = (box[axis] - sigma - x[k, axis]) / speed
                face = 2 * axis + 1
            elif speed < zero:
                dt = (sigma - x[k, axis]) / speed
                face = 2 * axis
            else:
                continue
            if not found or dt < best:
                best, best_k, best_l, found = dt, k, -1 - face, True
        for m in range(k + 1, n):
            dx0 = x[k, 0] - x[m, 0]
            dx1 = x[k, 1] - x[m, 1]
            dv0 = v[k, 0] - v[m, 0]
            dv1 = v[k, 1] - v[m, 1]
            xv = dx0 * dv0 + dx1 * dv1
            vv = dv0 * dv0 + dv1 * dv1
            upsilon = xv * xv - vv * (dx0 * dx0 + dx1 * dx1 - four * sigma * sigma)
            if upsilon > zero and xv < zero:
                dt = -(xv + np.sqrt(upsilon)) / vv
                if not found or dt < best:
                    best, best_k, best_l, found = dt, k, m, True
    if best < zero:  # round-off: an event due now
        best = zero
    return best, best_k, best_l


@inline
def _execute(x, v, k, l):
    """Alg. 4.3 for a pair (k, l ≥ 0), a wall reflection for l = −1 − face. Returns the
    normal speed of the event: |v⊥| of the disk at a wall, |Δv·ê⊥| for a pair."""
    if l < 0:
        axis = (-1 - l) >> 1
        speed = v[k, axis]
        v[k, axis] = -speed
        return abs(speed)
    dx0 = x[k, 0] - x[l, 0]
    dx1 = x[k, 1] - x[l, 1]
    norm = np.sqrt(dx0 * dx0 + dx1 * dx1)
    e0 = dx0 / norm
    e1 = dx1 / norm
    dv_e = (v[k, 0] - v[l, 0]) * e0 + (v[k, 1] - v[l, 1]) * e1
    v[k, 0] -= e0 * dv_e
    v[k, 1] -= e1 * dv_e
    v[l, 0] += e0 * dv_e
    v[l, 1] += e1 * dv_e
    return abs(dv_e)


@inline
def _advance(x, v, dt):
    """Every disk moves straight for dt (no temporary array)."""
    for m in range(x.shape[0]):
        x[m, 0] += v[m, 0] * dt
        x[m, 1] += v[m, 1] * dt


@kernel
def trajectory(x, v, sigma, box, events, event_time, event_pair, event_positions):
    """Run ``events`` events from time 0 (x, v updated in place, in their precision);
    record each event's time, pair (second member −1 − face for a wall) and positions."""
    t = sigma - sigma
    for e in range(events):
        dt, k, l = _next_event(x, v, sigma, box)
        _advance(x, v, dt)
        t += dt
        _execute(x, v, k, l)
        event_time[e] = t
        event_pair[e, 0] = k
        event_pair[e, 1] = l
        event_positions[e] = x


@inline
def _flight_occupancy(y, vy, dt, histogram, lower, scale):
    """Add to ``histogram`` (bins of width 1/scale from ``lower``) the time a disk moving
    from y with velocity vy for dt spends in each bin."""
    if dt <= 0.0:
        return
    bins = histogram.shape[0]
    if vy == 0.0:
        b = int(np.floor((y - lower) * scale))
        if 0 <= b < bins:
            histogram[b] += dt
        return
    start = y
    end = y + vy * dt
    if end < start:
        start, end = end, start
    speed = abs(vy)
    b = int(np.floor((start - lower) * scale))
    while True:
        if b >= bins:
            break
        edge = lower + (b + 1) / scale
        stop = end if end < edge else edge
        if b >= 0 and stop > start:
            histogram[b] += (stop - start) / speed
        if end <= edge:
            break
        start = edge
        b += 1


class Observers(NamedTuple):
    """What ``observe`` feeds (arrays float64): ``occupancy`` (bins on [lower, upper)), the
    time spent by the disks in each bin of y (Eq. 4.3 times T); ``snapshots``, counts of
    the disks' y at (j + 1/2) × ``snapshot_interval`` < T, j = 0, 1, ...
    (``theory.krauth2025.snapshot_count`` of them); ``wall_statistics``
    (4, 3), per face hits, Σ|v⊥|, Σ 1/|v⊥|; ``pair_statistics`` (3,), collisions, Σ|Δv⊥|,
    Σ 1/|Δv⊥|; ``velocity_time`` (bins on [-1, 1)), the time spent by every velocity
    component v_i,a/``radius`` in each bin (both components of every disk, as velocities
    are constant between events)."""

    occupancy: np.ndarray
    snapshots: np.ndarray
    snapshot_interval: float
    lower: float
    upper: float
    wall_statistics: np.ndarray
    pair_statistics: np.ndarray
    velocity_time: np.ndarray
    radius: float


@kernel
def observe(x, v, sigma, box, duration, observers):
    """Run for ``duration`` from time 0, feeding the :class:`Observers` ``observers``.
    Returns the events done."""
    occupancy = observers.occupancy
    snapshots = observers.snapshots
    snapshot_interval = observers.snapshot_interval
    lower = observers.lower
    upper = observers.upper
    wall_statistics = observers.wall_statistics
    pair_statistics = observers.pair_statistics
    velocity_time = observers.velocity_time
    radius = observers.radius
    n = x.shape[0]
    velocity_bins = velocity_time.shape[0]
    scale = occupancy.shape[0] / (upper - lower)
    t = 0.0
    taken = 0
    next_snapshot = 0.5 * snapshot_interval
    done = 0
    while True:
        dt, k, l = _next_event(x, v, sigma, box)
        if t + dt > duration:
            dt = duration - t
            k = -1
        # stroboscopic snapshots inside the flight, at (j + 1/2) x interval < duration (the
        # last flight takes them all: t + dt may round below the duration)
        end = duration if k < 0 else t + dt
        while next_snapshot <= end and next_snapshot < duration:
            for m in range(n):
                y = x[m, 1] + v[m, 1] * (next_snapshot - t)
                position = (y - lower) * scale
                if 0.0 <= position < snapshots.shape[0]:
                    snapshots[int(position)] += 1.0
            taken += 1
            next_snapshot = (taken + 0.5) * snapshot_interval
        for m in range(n):
            _flight_occupancy(x[m, 1], v[m, 1], dt, occupancy, lower, scale)
            for a in range(2):
                index = int((v[m, a] / radius + 1.0) * 0.5 * velocity_bins)
                velocity_time[min(max(index, 0), velocity_bins - 1)] += dt
        _advance(x, v, dt)
        t += dt
        if k < 0:
            return done
        speed = _execute(x, v, k, l)
        done += 1
        if l < 0:
            face = -1 - l
            wall_statistics[face, 0] += 1.0
            wall_statistics[face, 1] += speed
            wall_statistics[face, 2] += 1.0 / speed
        else:
            pair_statistics[0] += 1.0
            pair_statistics[1] += speed
            pair_statistics[2] += 1.0 / speed
