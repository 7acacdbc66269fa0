"""Setting up and maintaining the state outside the event loop: random placement without
overlaps, cell lists, predictions and the calendar for every particle, rebasing the
clock, Maxwellian velocities, the smallest pair distance."""

from __future__ import annotations

import numpy as np

from kinetic.edmd.calendar import calendar_build
from kinetic.edmd.cells import cell_insert, predict
from kinetic.edmd.events import rescale_velocities, temperature
from kinetic.edmd.layout import (
    CELL,
    G_L,
    G_SIGMA,
    G_SIGMA2,
    G_W,
    I_DIM,
    I_N,
    I_WALL,
    T_CELL,
    T_PAIR,
    X0,
    V,
    cell_flat,
)
from kinetic.jit import kernel, refcount_free
from kinetic.rng import normal_pair, uniform

# ----------------------------------------------------------------------------- set-up


@kernel
def place_random(phase, ints, members, occupancy, geometry, grid, state, max_attempts):
    """Random sequential insertion of N non-overlapping particles at time 0.

    Positions uniform in the box ([σ/2, L − σ/2] along wall axes); each trial is checked
    against the particles already placed in the neighbour cells. Fills the false positions
    (= positions at t = 0), the cells and the cell rows. Returns the number of particles
    placed (< N if one needed more than ``max_attempts`` trials), −1 if a cell row is full.
    """
    n = phase.shape[0]
    dim = grid[I_DIM]
    sigma = geometry[G_SIGMA]
    sigma2 = geometry[G_SIGMA2]
    for flat in range(occupancy.shape[0]):
        occupancy[flat] = 0
    for i in range(n):
        placed = False
        for _attempt in range(max_attempts):
            for k in range(3):
                if k >= dim:
                    phase[i, X0 + k] = 0.0
                    ints[i, CELL + k] = 0
                    continue
                length = geometry[G_L + k]
                if grid[I_WALL + k]:
                    x = 0.5 * sigma + (length - sigma) * uniform(state)
                else:
                    x = length * uniform(state)
                phase[i, X0 + k] = x
                c = int(x / geometry[G_W + k])
                if c >= grid[I_N + k]:
                    c = grid[I_N + k] - 1
                ints[i, CELL + k] = c
            for k in range(3, 6):
                phase[i, X0 + k] = 0.0
            if not overlaps_neighbours(i, phase, ints, members, occupancy, geometry, grid, sigma2):
                flat = cell_flat(ints[i, CELL], ints[i, CELL + 1], ints[i, CELL + 2], grid)
                if not cell_insert(i, flat, members, occupancy, ints):
                    return -1  # a cell is full: the caller grows the capacity and retries
                placed = True
                break
        if not placed:
            return i
    return n


@kernel
def overlaps_neighbours(i, phase, ints, members, occupancy, geometry, grid, sigma2):
    """True if particle i (at t = 0) overlaps a particle listed in its neighbour cells."""
    dim = grid[I_DIM]
    lo2, hi2 = (-1, 1) if dim == 3 else (0, 0)
    for o2 in range(lo2, hi2 + 1):
        for o1 in range(-1, 2):
            for o0 in range(-1, 2):
                ks = (ints[i, CELL] + o0, ints[i, CELL + 1] + o1, ints[i, CELL + 2] + o2)
                shift0 = 0.0
                shift1 = 0.0
                shift2 = 0.0
                k0 = ks[0]
                k1 = ks[1]
                k2 = ks[2]
                skip = False
                if k0 < 0 or k0 >= grid[0]:
                    if grid[I_WALL]:
                        skip = True
                    elif k0 < 0:
                        k0 += grid[0]
                        shift0 = -geometry[G_L]
                    else:
                        k0 -= grid[0]
                        shift0 = geometry[G_L]
                if k1 < 0 or k1 >= grid[1]:
                    if grid[I_WALL + 1]:
                        skip = True
                    elif k1 < 0:
                        k1 += grid[1]
                        shift1 = -geometry[G_L + 1]
                    else:
                        k1 -= grid[1]
                        shift1 = geometry[G_L + 1]
                if k2 < 0 or k2 >= grid[2]:
                    if grid[I_WALL + 2]:
                        skip = True
                    elif k2 < 0:
                        k2 += grid[2]
                        shift2 = -geometry[G_L + 2]
                    else:
                        k2 -= grid[2]
                        shift2 = geometry[G_L + 2]
                if skip:
                    continue
                flat = cell_flat(k0, k1, k2, grid)
                for q in range(occupancy[flat]):
                    j = members[flat, q]
                    dx = phase[j, X0] + shift0 - phase[i, X0]
                    dy = phase[j, X0 + 1] + shift1 - phase[i, X0 + 1]
                    dz = phase[j, X0 + 2] + shift2 - phase[i, X0 + 2]
                    if dx * dx + dy * dy + dz * dz < sigma2:
                        return True
    return False


@kernel
def build_cells(phase, ints, members, occupancy, geometry, grid, t):
    """Assign every particle (position x0 + v t) to its cell and rebuild the cell lists.

    Returns the index of the first particle outside the box, −1 if all are inside, −2 if a
    cell row is full (the caller grows the capacity and retries).
    """
    n = phase.shape[0]
    dim = grid[I_DIM]
    for flat in range(occupancy.shape[0]):
        occupancy[flat] = 0
    for i in range(n):
        for k in range(3):
            if k >= dim:
                ints[i, CELL + k] = 0
                continue
            x = phase[i, X0 + k] + phase[i, V + k] * t
            length = geometry[G_L + k]
            if x < 0.0 or x > length:
                return i
            c = int(x / geometry[G_W + k])
            if c >= grid[I_N + k]:
                c = grid[I_N + k] - 1
            ints[i, CELL + k] = c
        if not cell_insert(
            i,
            cell_flat(ints[i, CELL], ints[i, CELL + 1], ints[i, CELL + 2], grid),
            members,
            occupancy,
            ints,
        ):
            return -2
    return -1


@kernel
def relink_cells(ints, members, occupancy, grid):
    """Rebuild the cell rows from the cell coordinates ``cell`` (kept as they are: a
    particle sitting on a face by round-off stays in the cell its crossings put it in).
    Returns False if a row is full (the caller grows the capacity and retries)."""
    for flat in range(occupancy.shape[0]):
        occupancy[flat] = 0
    for i in range(ints.shape[0]):
        if not cell_insert(
            i,
            cell_flat(ints[i, CELL], ints[i, CELL + 1], ints[i, CELL + 2], grid),
            members,
            occupancy,
            ints,
        ):
            return False
    return True


@refcount_free
def _rebuild(phase, calendar):
    """``calendar_build`` on the arrays of a ``layout.Calendar``."""
    calendar_build(
        phase,
        calendar.links,
        calendar.heads,
        calendar.heap_time,
        calendar.heap_index,
        calendar.calendar,
        calendar.cursor,
    )


@refcount_free
def predict_all(t, state, calendar):
    """Predict every particle's events from time t and rebuild the calendar (``state`` a
    ``layout.State``, ``calendar`` a ``layout.Calendar``)."""
    phase = state.phase
    n = phase.shape[0]
    for i in range(n):
        predict(
            i,
            t,
            phase,
            state.ints,
            state.members,
            state.occupancy,
            state.geometry,
            state.grid,
            state.counters,
            state.scratch,
            state.images,
        )
    _rebuild(phase, calendar)


@refcount_free
def rebase(t, factor, dim, state, calendar, observers):
    """Move the time origin to t (every stored time −= t, x0 += v t), to keep round-off
    small in long runs, and rebuild the calendar on the new clock. Positions and the order
    of events are unchanged. ``observers`` (a ``layout.ObserverBuffers``): the window ends,
    sample times and record times shift with the clock.

    Unless ``factor`` is 1, every velocity is then multiplied by ``factor`` at the new
    origin before the one rebuild, the numbers of ``HardSphereSystem.scale_velocities``
    called after a rebase (``rescale_velocities`` to factor² times the temperature of the
    ``dim`` components, the last collisions' times divided by ``factor``) without its
    second rebuild."""
    phase = state.phase
    last_collision = state.last_collision
    n = phase.shape[0]
    for i in range(n):
        for k in range(3):
            phase[i, X0 + k] += phase[i, V + k] * t
        phase[i, T_PAIR] -= t
        phase[i, T_CELL] -= t
        last_collision[i] -= t
    if factor != 1.0:
        current = temperature(phase, dim)
        if current > 0.0:
            rescale_velocities(0.0, factor * factor * current, phase, dim)
            for i in range(n):
                if np.isfinite(last_collision[i]):
                    last_collision[i] = last_collision[i] / factor
    _rebuild(phase, calendar)
    window_end = observers.window_end
    sample_times = observers.sample_times
    record_time = observers.record_time
    for w in range(window_end.shape[0]):
        window_end[w] -= t
    for s in range(sample_times.shape[0]):
        sample_times[s] -= t
    for s in range(record_time.shape[0]):
        record_time[s] -= t


@kernel
def draw_velocities(phase, dim, state):
    """Independent standard normal velocity components (columns 3 .. 2 + d; others 0)."""
    n = phase.shape[0]
    for i in range(n):
        a, b = normal_pair(state)
        phase[i, V] = a
        phase[i, V + 1] = b
        phase[i, V + 2] = normal_pair(state)[0] if dim == 3 else 0.0


@kernel
def min_pair_distance(phase, ints, members, occupancy, geometry, grid, t):
    """Smallest centre distance at time t between particles in neighbour cells (periodic
    images included): ≥ σ when nothing overlaps. +inf if no pair is in reach."""
    n = phase.shape[0]
    dim = grid[I_DIM]
    best = np.inf
    lo2, hi2 = (-1, 1) if dim == 3 else (0, 0)
    for i in range(n):
        xi0 = phase[i, X0] + phase[i, V] * t
        xi1 = phase[i, X0 + 1] + phase[i, V + 1] * t
        xi2 = phase[i, X0 + 2] + phase[i, V + 2] * t
        for o2 in range(lo2, hi2 + 1):
            k2, s2, skip2 = _neighbour(
                ints[i, CELL + 2] + o2, grid[2], grid[I_WALL + 2], geometry[G_L + 2]
            )
            if skip2:
                continue
            for o1 in range(-1, 2):
                k1, s1, skip1 = _neighbour(
                    ints[i, CELL + 1] + o1, grid[1], grid[I_WALL + 1], geometry[G_L + 1]
                )
                if skip1:
                    continue
                for o0 in range(-1, 2):
                    k0, s0, skip0 = _neighbour(
                        ints[i, CELL] + o0, grid[0], grid[I_WALL], geometry[G_L]
                    )
                    if skip0:
                        continue
                    flat = cell_flat(k0, k1, k2, grid)
                    for q in range(occupancy[flat]):
                        j = members[flat, q]
                        if j != i:
                            d0 = phase[j, X0] + phase[j, V] * t + s0 - xi0
                            d1 = phase[j, X0 + 1] + phase[j, V + 1] * t + s1 - xi1
                            d2 = phase[j, X0 + 2] + phase[j, V + 2] * t + s2 - xi2
                            r2 = d0 * d0 + d1 * d1 + (d2 * d2 if dim == 3 else 0.0)
                            if r2 < best:
                                best = r2
    return np.sqrt(best)


@kernel
def _neighbour(k, n, wall, length):
    """Wrap cell coordinate k on an axis of n cells: (k mod n, image shift, beyond wall)."""
    if k < 0:
        if wall:
            return 0, 0.0, True
        return k + n, -length, False
    if k >= n:
        if wall:
            return 0, 0.0, True
        return k - n, length, False
    return k, 0.0, False
