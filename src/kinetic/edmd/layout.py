"""Memory layout of the event-driven MD state: the columns of its rows, the entries of its
parameter vectors, counters and status codes (shared by every EDMD kernel module).

Arrays only: no Python objects, no I/O, no allocation inside the event loop. The Python
front (``kinetic.edmd.system.HardSphereSystem``) allocates the state and calls
``advance`` in chunks.

Units: mass m = 1; lengths in the units of the box and diameter (σ = 1 in the project);
times in the units those and the velocities imply.

State (N particles, every array preallocated, row/index i = memory slot of a particle)
--------------------------------------------------------------------------------------
Everything an event of particle i touches lives in two 64-byte rows (two cache lines), so
that a large system pays two cache misses per event rather than one per array. Systems
can be re-sorted in memory along the Z-order curve of the cells now and then (``label``
keeps each slot's particle identity; ``HardSphereSystem(sort_every=...)``).

``phase``   (N, 8) float64, columns named below: X0..X0 + 2 the *false position* x0 =
            x(t) − v t of the current flight (the position at time t is ``x0 + v t``
            without touching the particle between its events), V..V + 2 the velocity (z = 0
            in d = 2), T_PAIR the time of i's earliest predicted pair collision, T_CELL the
            time i next leaves its cell (or touches a wall).
``ints``    (N, 8) int64: PARTNER the predicted partner j (−1: none), PREDICTED_AT the
            number of the event at which the prediction was made, FACE the face of the next
            crossing (2 k + 1 upwards along axis k, 2 k downwards), CHANGED_AT the number of
            the event at which i's velocity last changed (collision or wall bounce; 0 before
            the first), ROW_SLOT i's position in its cell row, CELL..CELL + 2 its cell
            coordinates (z = 0 in d = 2).
            Lazy invalidation: i's pair prediction is valid iff ``ints[j, CHANGED_AT] <=
            ints[i, PREDICTED_AT]`` (j has not changed velocity since; within one event every
            velocity change precedes every prediction). Event numbers, unlike counts of
            j's changes, need nothing of j's row when the prediction is made (a cache miss
            per prediction in large systems).
``members`` (n_cells, C) int32, ``occupancy`` (n_cells,) int32: the particles of each
            cell are ``members[c, :occupancy[c]]``; rows have a fixed capacity C (16 by
            default: one cache line), grown by the front when a crossing finds its
            destination full (``STATUS_CELL_FULL``).
``links`` (N, 4) int32, ``heads`` (B + 1,) int32, ``heap_time`` (N,) float64,
``heap_index`` (N,) int32, ``calendar`` float64 [origin, 1/width], ``cursor`` int64
            [current bucket, heap size, then the prefetch pipeline's list positions (see
            ``prefetch_ahead``; ``N_CURSOR`` entries in all, 2 disable the pipeline)]:
            the event calendar (Paul 2007, J. Comput. Phys. 221, 615), the queue of the N
            events min(phase[i, T_PAIR], phase[i, T_CELL]). Bucket b of B = N covers the times
            origin + [b, b + 1) · width (width ≈ EVENTS_PER_BUCKET mean intervals between
            events) in an unsorted doubly linked list (``heads[b]`` the first particle,
            ``links[i]`` = next, previous, bucket of i, heap position); list B is the
            overflow beyond the horizon. The current bucket is poured into a binary heap
            ordered by (time, particle), whose top is the next event; when the last bucket
            is done every event is in the overflow list and the calendar is rebuilt from
            there (also after a velocity rescaling, a rebase of the clock and a
            re-sorting). Every particle is in exactly one place: the heap or one list.
            Large systems prefetch the memory of the events one to three buckets ahead
            (``prefetch_ahead``).
``last_collision`` (N,) float64: time of i's last pair collision (−inf before the first).
``streak``  (N,) int32: consecutive pair collisions of i separated by less than the
            collapse time (inelastic collapse detector).

Parameters
----------
``geometry`` float64 [L0, L1, L2, w0, w1, w2, σ, σ², α, contact_time, collapse_time]:
            box lengths, cell widths (L_k / n_k, each ≥ σ), diameter, restitution, the
            contact duration of the TC model (pairs in which a particle collided less than
            that time before collide elastically; 0 disables it) and the collapse time.
``grid``    int64 [n0, n1, n2, d, wall0, wall1, wall2, collapse_streak, rescale_every,
            prefetch]: cells per side (n2 = 1 in d = 2), dimension, hard wall (1) or
            periodic (0) per axis, the streak length that declares inelastic collapse, the
            number of collisions between two velocity rescalings (0: no thermostat), and
            the prefetch level (0 none, 1 rows and cells, 2 also the scans' candidates).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from kinetic.edmd.arguments import GATHER_HEAD  # noqa: F401  (defined with the checks)
from kinetic.jit import inline


class Run(NamedTuple):
    """What one call of ``advance`` may do: stop at time ``t_stop`` (on the clock that
    ``clock[0]`` reads), after ``max_collisions`` collisions or ``max_events`` events;
    the thermostat's ``target_temperature``; ``observing`` (1: feed the flight and path
    histograms)."""

    t_stop: float
    max_collisions: int
    max_events: int
    target_temperature: float
    observing: int


class State(NamedTuple):
    """The particles and cells (see the module docstring for each array), with the
    parameter vectors ``geometry`` and ``grid`` and the ``counters``."""

    clock: np.ndarray
    phase: np.ndarray
    ints: np.ndarray
    members: np.ndarray
    occupancy: np.ndarray
    last_collision: np.ndarray
    streak: np.ndarray
    label: np.ndarray
    scratch: np.ndarray
    images: np.ndarray
    geometry: np.ndarray
    grid: np.ndarray
    counters: np.ndarray


class Calendar(NamedTuple):
    """The event calendar: bucket lists, the heap of the current bucket, its origin and
    width, the cursor (and prefetch pipeline)."""

    links: np.ndarray
    heads: np.ndarray
    heap_time: np.ndarray
    heap_index: np.ndarray
    calendar: np.ndarray
    cursor: np.ndarray


class ObserverBuffers(NamedTuple):
    """What the observers fill during ``advance`` (``kinetic.edmd.observers.Observers``):
    counting windows, flight and path histograms, wall statistics, timed samples and
    the ring buffer of the last collisions."""

    window_length: np.ndarray
    window_end: np.ndarray
    window_count: np.ndarray
    window_histogram: np.ndarray
    window_overflow: np.ndarray
    flight_histogram: np.ndarray
    path_histogram: np.ndarray
    bin_widths: np.ndarray
    flight_sums: np.ndarray
    wall_statistics: np.ndarray
    sample_times: np.ndarray
    sample_temperature: np.ndarray
    sample_collisions: np.ndarray
    sample_cursor: np.ndarray
    record_time: np.ndarray
    record_pair: np.ndarray
    record_normal_speed: np.ndarray


# columns of ``phase`` (float64)
X0 = 0  # false position x0 = x(t) − v t: columns X0, X0 + 1, X0 + 2
V = 3  # velocity: columns V, V + 1, V + 2 (z = 0 in d = 2)
T_PAIR = 6  # time of the earliest predicted pair collision
T_CELL = 7  # time the particle next leaves its cell (or touches a wall)

# columns of ``ints`` (int64)
PARTNER = 0  # predicted partner (−1: none)
PREDICTED_AT = 1  # number of the event at which the pair prediction was made
FACE = 2  # face of the next crossing (2 k + 1 upwards along axis k, 2 k downwards)
CHANGED_AT = 3  # number of the event at which the velocity last changed
ROW_SLOT = 4  # position in its cell row
CELL = 5  # cell coordinates: columns CELL, CELL + 1, CELL + 2 (z = 0 in d = 2)

# status codes returned by ``advance``
STATUS_TIME = 0  # reached the requested time
STATUS_COLLISIONS = 1  # executed the requested number of collisions
STATUS_COLLAPSE = 2  # inelastic collapse: a particle's collision streak exceeded the limit
STATUS_STALLED = 3  # the clock did not advance for too many consecutive events
STATUS_EVENT_LIMIT = 4  # more events than allowed in one call
STATUS_NO_EVENTS = 5  # every particle is at rest: nothing will ever happen
STATUS_CELL_FULL = 6  # a crossing found its destination cell row full (grow and resume)

# indices into ``counters`` (int64)
COUNT_COLLISIONS = 0
COUNT_CROSSINGS = 1
COUNT_WALL_HITS = 2
COUNT_INVALID = 3
COUNT_PAIR_TESTS = 4
COUNT_EVENTS = 5
COUNT_RESCALES = 6
COUNT_COLLAPSE_PARTICLE = 7  # particle that triggered the collapse report
COUNT_COLLAPSE_PARTNER = 8
COUNT_STALL = 9  # consecutive events at the same time (internal)
COUNT_INELASTIC = 10  # collisions executed with α < 1
N_COUNTERS = 11

# indices into ``geometry``
G_L = 0
G_W = 3
G_SIGMA = 6
G_SIGMA2 = 7
G_ALPHA = 8
G_CONTACT = 9
G_COLLAPSE_TIME = 10
N_GEOMETRY = 11

# indices into ``grid``
I_N = 0
I_DIM = 3
I_WALL = 4
I_STREAK = 7
I_RESCALE = 8
I_PREFETCH = 9  # 0: no prefetching, 1: rows and cells of coming events, 2: and candidates
N_GRID = 10

STALL_LIMIT = 100_000
# columns of ``links`` (the event calendar's per-particle entries)
L_NEXT = 0  # next particle in the same bucket list (−1: last)
L_PREV = 1  # previous particle in the same bucket list (−1: first)
L_PLACE = 2  # bucket of the particle's event (B: overflow list; PLACE_HEAP: current heap)
L_HEAP = 3  # position in the current bucket's heap
PLACE_HEAP = -1
#: mean number of events per calendar bucket (sets the bucket width)
EVENTS_PER_BUCKET = 4.0
#: bucket lists walked side by side by the prefetch pipeline (``prefetch_ahead``)
PREFETCH_WALKS = 6
#: most particles the prefetch pipeline follows in one go along a list
WALK_LIMIT = 64
# entries of ``cursor``: the calendar's, then the prefetch pipeline's
C_BUCKET = 0  # current bucket
C_HEAP = 1  # heap size
C_STAGE2 = 2  # next particle of stage 2 (−1: none)
C_STAGE1 = 3  # next particle of stage 1
C_WALKS = 4  # PREFETCH_WALKS list walks of stage 3
N_CURSOR = C_WALKS + PREFETCH_WALKS


# ---------------------------------------------------------------- index helpers
@inline
def smaller(a, b):
    """The smaller of two floats as one select instruction (numba compiles the builtin
    ``min`` of two floats to a function call, with its NaN handling)."""
    return a if a < b else b


@inline
def cell_flat(cx, cy, cz, grid):
    """Flat index of cell (cx, cy, cz): x fastest."""
    return (cz * grid[1] + cy) * grid[0] + cx
