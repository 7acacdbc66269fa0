"""The event loop (``advance``) and what it executes: collisions, crossings, wall bounces,
velocity rescalings, and the observers fed by each collision.

Events
------
A *crossing* moves i to the next cell (wrapping x0 by the box length on periodic faces)
and tests i only against the layer of cells that just became adjacent; a *wall* event
reflects the normal velocity; a *collision* is executed if the partner's velocity has not
changed since the prediction, otherwise i's collisions are predicted anew (an *invalid*
event). Round-off overlaps are handled deterministically: an approaching pair found at
distance < σ collides at once, a receding overlapping pair is ignored (it separates).
Collisions with velocity rescaling: the rescaling by s at time t maps every pending event
time t_e to t + (t_e − t)/s, an order-preserving map, so no prediction is redone (the
calendar is rebuilt).

Observers fed by each collision (when ``observing`` is 1)
---------------------------------------------------------
per-particle counts in consecutive windows of several lengths (histograms of the counts),
free-flight times and free paths (histograms + sums), wall hits (count, Σ|v⊥|, Σ1/|v⊥|),
temperature and collision count at requested times.
"""

from __future__ import annotations

import numpy as np

from kinetic.edmd.calendar import (
    calendar_build,
    calendar_next,
    calendar_place,
    calendar_reschedule,
    event_key,
    prefetch_row,
    prefetch_step,
)
from kinetic.edmd.cells import cell_insert, cell_remove, next_crossing, scan_neighbours
from kinetic.edmd.layout import (
    CELL,
    CHANGED_AT,
    COUNT_COLLAPSE_PARTICLE,
    COUNT_COLLAPSE_PARTNER,
    COUNT_COLLISIONS,
    COUNT_CROSSINGS,
    COUNT_EVENTS,
    COUNT_INELASTIC,
    COUNT_INVALID,
    COUNT_PAIR_TESTS,
    COUNT_RESCALES,
    COUNT_STALL,
    COUNT_WALL_HITS,
    FACE,
    G_ALPHA,
    G_COLLAPSE_TIME,
    G_CONTACT,
    G_L,
    I_DIM,
    I_N,
    I_PREFETCH,
    I_RESCALE,
    I_STREAK,
    I_WALL,
    N_CURSOR,
    PARTNER,
    PLACE_HEAP,
    PREDICTED_AT,
    STALL_LIMIT,
    STATUS_CELL_FULL,
    STATUS_COLLAPSE,
    STATUS_COLLISIONS,
    STATUS_EVENT_LIMIT,
    STATUS_NO_EVENTS,
    STATUS_STALLED,
    STATUS_TIME,
    T_CELL,
    T_PAIR,
    X0,
    V,
    cell_flat,
)
from kinetic.jit import inline, kernel, refcount_free

WINDOW_SLACK = 1e-9
"""Relative distance within which a counting window's end counts as the run's stop (the
ends are sums of window lengths; a window of 20 mean free times in a run of 20 ended
5.7e-13 beyond it with one seed and was dropped)."""

# ----------------------------------------------------------------------------- observers


@kernel
def temperature(phase, dim):
    """Kinetic temperature Σ v² / (d N) (m = 1)."""
    total = 0.0
    n = phase.shape[0]
    for i in range(n):
        for k in range(dim):
            total += phase[i, V + k] * phase[i, V + k]
    return total / (dim * n)


@kernel
def flush_windows(w, window_count, window_histogram, window_overflow):
    """Close window length w for every particle: histogram the counts, reset them."""
    n = window_count.shape[0]
    top = window_histogram.shape[1]
    for i in range(n):
        c = window_count[i, w]
        if c < top:
            window_histogram[w, c] += 1
        else:
            window_overflow[w] += 1
        window_count[i, w] = 0


@inline
def observe_flight(
    i, t, speed, last_collision, flight_histogram, path_histogram, bin_widths, flight_sums
):
    """Record the free flight of i that ends at time t (if it began with a collision).

    ``bin_widths`` = [flight-time bin, free-path bin]; ``flight_sums`` = [number of
    flights, Σ time, Σ time², Σ path, Σ path², flights beyond the time histogram, beyond
    the path histogram].
    """
    start = last_collision[i]
    if start == -np.inf:
        return
    duration = t - start
    path = speed * duration
    flight_sums[0] += 1.0
    flight_sums[1] += duration
    flight_sums[2] += duration * duration
    flight_sums[3] += path
    flight_sums[4] += path * path
    b = int(duration / bin_widths[0])
    if b < flight_histogram.shape[0]:
        flight_histogram[b] += 1
    else:
        flight_sums[5] += 1.0
    b = int(path / bin_widths[1])
    if b < path_histogram.shape[0]:
        path_histogram[b] += 1
    else:
        flight_sums[6] += 1.0


# ----------------------------------------------------------------------------- events


@kernel
def rescale_velocities(t, target_temperature, phase, dim):
    """Thermostat: scale every velocity by s = sqrt(T_target / T) at time t.

    Positions are continuous (x0 ← x0 + v t (1 − s)); every pending event time maps to
    t + (t_e − t)/s, an order-preserving map, so no prediction is redone (the caller
    rebuilds the calendar, whose buckets do change, and maps the last collision times the
    same way, so that a flight's time and path stay those of the scaled motion). Returns s.
    """
    n = phase.shape[0]
    current = temperature(phase, dim)
    if current <= 0.0:
        return 1.0
    s = np.sqrt(target_temperature / current)
    inverse = 1.0 / s
    for i in range(n):
        for k in range(3):
            phase[i, X0 + k] += phase[i, V + k] * t * (1.0 - s)
            phase[i, V + k] *= s
        if phase[i, T_PAIR] < np.inf:
            phase[i, T_PAIR] = t + (phase[i, T_PAIR] - t) * inverse
        if phase[i, T_CELL] < np.inf:
            phase[i, T_CELL] = t + (phase[i, T_CELL] - t) * inverse
    return s


@inline
def collide(i, j, t, phase, geometry, grid, last_collision):
    """Execute the collision of i and j at time t: new velocities, continuous positions.

    Returns (normal relative speed before the collision, restitution used). The normal is
    taken between the minimum images (contact distance σ < L/2).
    """
    dim = grid[I_DIM]
    alpha = geometry[G_ALPHA]
    contact = geometry[G_CONTACT]
    if (alpha < 1.0 and contact > 0.0) and (
        t - last_collision[i] < contact or t - last_collision[j] < contact
    ):
        alpha = 1.0
    dr0 = 0.0
    dr1 = 0.0
    dr2 = 0.0
    norm2 = 0.0
    for k in range(dim):
        d = (phase[j, X0 + k] + phase[j, V + k] * t) - (phase[i, X0 + k] + phase[i, V + k] * t)
        if not grid[I_WALL + k]:
            length = geometry[G_L + k]
            d -= length * np.round(d / length)
        if k == 0:
            dr0 = d
        elif k == 1:
            dr1 = d
        else:
            dr2 = d
        norm2 += d * d
    inv = 1.0 / np.sqrt(norm2)
    n0 = dr0 * inv
    n1 = dr1 * inv
    n2 = dr2 * inv
    gn = (phase[j, V] - phase[i, V]) * n0 + (phase[j, V + 1] - phase[i, V + 1]) * n1
    if dim == 3:
        gn += (phase[j, V + 2] - phase[i, V + 2]) * n2
    # gn < 0: approaching. Δv_i = (1+α)/2 gn n, Δv_j = −Δv_i
    factor = 0.5 * (1.0 + alpha) * gn
    for k in range(dim):
        nk = n0 if k == 0 else (n1 if k == 1 else n2)
        delta = factor * nk
        phase[i, V + k] += delta
        phase[i, X0 + k] -= delta * t
        phase[j, V + k] -= delta
        phase[j, X0 + k] += delta * t
    return gn, alpha


@refcount_free
def advance(run, state, queue, observers):
    """Run the event loop from ``clock[0]`` until ``t_stop`` or ``max_collisions`` more
    collisions (or a failure status), then set ``clock[0]`` and return a status code.

    Arguments are the named tuples of ``kinetic.edmd.layout``: ``run`` (``Run``: limits
    and settings of this call), ``state`` (``State``), ``queue`` (``Calendar``) and
    ``observers`` (``ObserverBuffers``). Observers: ``window_*`` (W window lengths,
    zero-size arrays disable them),
    ``flight_*``/``path_histogram`` (only when ``observing``), ``wall_statistics`` (2d, 3)
    [hits, Σ|v⊥|, Σ 1/|v⊥|] per face 2k + upwards, ``sample_*`` temperature and collision
    count at the increasing times ``sample_times`` (``sample_cursor[0]`` = next one), and
    ``record_*`` a ring buffer of the last collisions (time, pair of labels ``label[i]``,
    normal relative speed).
    """
    t_stop, max_collisions, max_events, target_temperature, observing = run
    (
        clock,
        phase,
        ints,
        members,
        occupancy,
        last_collision,
        streak,
        label,
        scratch,
        images,
        geometry,
        grid,
        counters,
    ) = state
    links, heads, heap_time, heap_index, calendar, cursor = queue
    (
        window_length,
        window_end,
        window_count,
        window_histogram,
        window_overflow,
        flight_histogram,
        path_histogram,
        bin_widths,
        flight_sums,
        wall_statistics,
        sample_times,
        sample_temperature,
        sample_collisions,
        sample_cursor,
        record_time,
        record_pair,
        record_normal_speed,
    ) = observers
    dim = grid[I_DIM]
    pipeline = grid[I_PREFETCH] > 0 and cursor.shape[0] >= N_CURSOR
    streak_limit = grid[I_STREAK]
    rescale_every = grid[I_RESCALE]
    collapse_time = geometry[G_COLLAPSE_TIME]
    n_windows = window_length.shape[0]
    n_samples = sample_times.shape[0]
    n_records = record_time.shape[0]
    t = clock[0]
    collisions_done = 0
    events_done = 0
    next_window = np.inf
    longest_window = 0.0
    for w in range(n_windows):
        if window_end[w] < next_window:
            next_window = window_end[w]
        longest_window = max(longest_window, window_length[w])
    # a window that ends at the stop (a checkpoint its lengths divide) is closed even when
    # the round-off of its end's sums left it a few ulps beyond: kept or lost by chance
    window_stop = t_stop + WINDOW_SLACK * (abs(t_stop) + longest_window)
    while True:
        i = calendar_next(
            phase,
            ints,
            members,
            occupancy,
            last_collision,
            grid,
            links,
            heads,
            heap_time,
            heap_index,
            calendar,
            cursor,
        )
        if i < 0:
            clock[0] = t_stop
            return STATUS_NO_EVENTS
        if pipeline:
            prefetch_step(phase, ints, members, occupancy, last_collision, grid, links, cursor)
        t_event = heap_time[0]
        # scheduled observations that come before the event
        while next_window < t_event and next_window <= window_stop:
            next_window = np.inf
            for w in range(n_windows):
                if window_end[w] < t_event and window_end[w] <= window_stop:
                    flush_windows(w, window_count, window_histogram, window_overflow)
                    window_end[w] += window_length[w]
                if window_end[w] < next_window:
                    next_window = window_end[w]
        while (
            sample_cursor[0] < n_samples
            and sample_times[sample_cursor[0]] < t_event
            and sample_times[sample_cursor[0]] <= t_stop
        ):
            sample_temperature[sample_cursor[0]] = temperature(phase, dim)
            sample_collisions[sample_cursor[0]] = counters[COUNT_COLLISIONS]
            sample_cursor[0] += 1
        if t_event > t_stop:
            clock[0] = t_stop
            return STATUS_TIME
        if events_done >= max_events:
            clock[0] = t
            return STATUS_EVENT_LIMIT
        events_done += 1
        event_number = counters[COUNT_EVENTS] + 1
        counters[COUNT_EVENTS] = event_number
        if t_event == t:
            counters[COUNT_STALL] += 1
            if counters[COUNT_STALL] > STALL_LIMIT:
                counters[COUNT_COLLAPSE_PARTICLE] = i
                counters[COUNT_COLLAPSE_PARTNER] = ints[i, PARTNER]
                clock[0] = t
                return STATUS_STALLED
        else:
            counters[COUNT_STALL] = 0
        t_previous = t
        t = t_event

        # After the event, the predictions of up to two particles are redone by the one
        # (inlined) copy of the neighbour scan below: ``axis`` < 0 scans all neighbour
        # cells and replaces the prediction, ``axis`` = k scans the layer of cells that
        # became adjacent along k and keeps the earlier prediction.
        second = -1
        axis = -1
        offset = 0
        new_crossing = True
        collided = False
        if phase[i, T_CELL] <= phase[i, T_PAIR]:
            # ---------------------------------------------------------- crossing or wall
            code = ints[i, FACE]
            k = code >> 1
            upwards = (code & 1) == 1
            c = ints[i, CELL + k]
            at_wall = False
            if grid[I_WALL + k] != 0:
                at_wall = c == grid[I_N + k] - 1 if upwards else c == 0
            if at_wall:
                velocity = phase[i, V + k]
                speed = abs(velocity)
                wall_statistics[code, 0] += 1.0
                wall_statistics[code, 1] += speed
                wall_statistics[code, 2] += 1.0 / speed
                phase[i, X0 + k] += 2.0 * velocity * t
                phase[i, V + k] = -velocity
                ints[i, CHANGED_AT] = event_number
                counters[COUNT_WALL_HITS] += 1
            else:
                # arithmetic rather than a branch on the direction (a coin flip)
                offset = 1 if upwards else -1
                c += offset
                wrap = 0.0
                if c == grid[I_N + k]:
                    c = 0
                    wrap = -geometry[G_L + k]
                elif c < 0:
                    c = grid[I_N + k] - 1
                    wrap = geometry[G_L + k]
                old = cell_flat(ints[i, CELL], ints[i, CELL + 1], ints[i, CELL + 2], grid)
                new = old + (c - ints[i, CELL + k]) * (
                    1 if k == 0 else (grid[0] if k == 1 else grid[0] * grid[1])
                )
                if occupancy[new] >= members.shape[1]:
                    # the destination row is full: stop before changing anything; the
                    # caller grows the rows and resumes with this very event
                    counters[COUNT_EVENTS] -= 1
                    clock[0] = t_previous
                    return STATUS_CELL_FULL
                cell_remove(i, old, members, occupancy, ints)
                phase[i, X0 + k] += wrap
                ints[i, CELL + k] = c
                cell_insert(i, new, members, occupancy, ints)
                counters[COUNT_CROSSINGS] += 1
                axis = k
        else:
            j = ints[i, PARTNER]
            if ints[j, CHANGED_AT] > ints[i, PREDICTED_AT]:
                # ------------------------------------------------------ stale prediction
                counters[COUNT_INVALID] += 1
                new_crossing = False
            else:
                # ---------------------------------------------------------- pair collision
                collided = True
                second = j
                speed_i = np.sqrt(phase[i, V] ** 2 + phase[i, V + 1] ** 2 + phase[i, V + 2] ** 2)
                speed_j = np.sqrt(phase[j, V] ** 2 + phase[j, V + 1] ** 2 + phase[j, V + 2] ** 2)
                gn, alpha_used = collide(i, j, t, phase, geometry, grid, last_collision)
                if alpha_used < 1.0:
                    counters[COUNT_INELASTIC] += 1
                ints[i, CHANGED_AT] = event_number
                ints[j, CHANGED_AT] = event_number
                if observing:
                    observe_flight(
                        i,
                        t,
                        speed_i,
                        last_collision,
                        flight_histogram,
                        path_histogram,
                        bin_widths,
                        flight_sums,
                    )
                    observe_flight(
                        j,
                        t,
                        speed_j,
                        last_collision,
                        flight_histogram,
                        path_histogram,
                        bin_widths,
                        flight_sums,
                    )
                    for w in range(n_windows):
                        window_count[i, w] += 1
                        window_count[j, w] += 1
                # inelastic collapse detector: streaks of collisions closer than
                # collapse_time
                if streak_limit > 0:
                    streak[i] = streak[i] + 1 if t - last_collision[i] < collapse_time else 0
                    streak[j] = streak[j] + 1 if t - last_collision[j] < collapse_time else 0
                last_collision[i] = t
                last_collision[j] = t
                if n_records > 0:
                    record_slot = counters[COUNT_COLLISIONS] % n_records
                    record_time[record_slot] = t
                    record_pair[record_slot, 0] = label[i]
                    record_pair[record_slot, 1] = label[j]
                    record_normal_speed[record_slot] = -gn
                counters[COUNT_COLLISIONS] += 1
                collisions_done += 1

        # -------------------------------------------------------------- re-predictions
        for q in range(2 if second >= 0 else 1):
            p = i if q == 0 else second
            if new_crossing:
                tc, new_code = next_crossing(p, phase, ints, geometry, grid)
                # never schedule in the past (round-off right after a crossing)
                phase[p, T_CELL] = tc if tc > t else t
                ints[p, FACE] = new_code
                if pipeline:
                    # the list head that the rescheduling below reads, if the crossing
                    # stays the next event (mostly): the scan hides the miss
                    bucket = calendar_place(
                        phase[p, T_CELL] if axis < 0 else event_key(phase, p),
                        heads,
                        calendar,
                        cursor,
                    )
                    if bucket != PLACE_HEAP:
                        prefetch_row(heads, bucket)
            best_t, best_j, tests = scan_neighbours(
                p,
                t,
                axis,
                offset,
                phase,
                ints,
                members,
                occupancy,
                geometry,
                grid,
                np.inf,
                -1,
                scratch,
                images,
            )
            counters[COUNT_PAIR_TESTS] += tests
            if axis < 0 or best_t < phase[p, T_PAIR]:
                phase[p, T_PAIR] = best_t
                ints[p, PARTNER] = best_j
                ints[p, PREDICTED_AT] = event_number
            calendar_reschedule(
                p, event_key(phase, p), links, heads, heap_time, heap_index, calendar, cursor
            )

        if collided:
            if streak_limit > 0 and (streak[i] > streak_limit or streak[j] > streak_limit):
                counters[COUNT_COLLAPSE_PARTICLE] = i
                counters[COUNT_COLLAPSE_PARTNER] = j
                clock[0] = t
                return STATUS_COLLAPSE
            if rescale_every > 0 and counters[COUNT_COLLISIONS] % rescale_every == 0:
                scale = rescale_velocities(t, target_temperature, phase, dim)
                for m in range(phase.shape[0]):
                    if np.isfinite(last_collision[m]):
                        last_collision[m] = t + (last_collision[m] - t) / scale
                calendar_build(phase, links, heads, heap_time, heap_index, calendar, cursor)
                counters[COUNT_RESCALES] += 1
            if collisions_done >= max_collisions:
                clock[0] = t
                return STATUS_COLLISIONS
