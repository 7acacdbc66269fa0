"""Numba kernels of the event-driven molecular dynamics of hard disks and spheres.

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

``phase``   (N, 8) float64: columns 0..2 the *false position* x0 = x(t) − v t of the
            current flight (the position at time t is ``x0 + v t`` without touching the
            particle between its events), 3..5 the velocity (z = 0 in d = 2), 6 the time of
            i's earliest predicted pair collision, 7 the time i next leaves its cell (or
            touches a wall).
``ints``    (N, 8) int64: 0 the predicted partner j (−1: none), 1 the number of the
            event at which the prediction was made, 2 the face of the next crossing
            (2 k + 1 upwards along axis k, 2 k downwards), 3 the number of the event at
            which i's velocity last changed (collision or wall bounce; 0 before the first),
            4 i's position in its cell row, 5..7 its cell coordinates (z = 0 in d = 2).
            Lazy invalidation: i's pair prediction is valid iff ``ints[j, 3] <=
            ints[i, 1]`` (j has not changed velocity since; within one event every
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
            events min(phase[i, 6], phase[i, 7]). Bucket b of B = N covers the times
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
from llvmlite import ir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

from kinetic.rng import normal_pair, uniform

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
#: entries copied unconditionally from each cell row by the neighbour scan (≤ row capacity)
GATHER_HEAD = 4


# ----------------------------------------------------------------------------- prefetch


@intrinsic
def prefetch_row(typingctx, array, row):
    """Hint the processor to load the cache line of ``array[row]`` (a C-contiguous 1-D
    array) or the first cache line of row ``row`` (2-D) into every cache level; no effect
    on the program's results. Emits LLVM's ``llvm.prefetch`` (read, high locality, data
    cache)."""
    if not (
        isinstance(array, types.Array) and array.ndim in (1, 2) and isinstance(row, types.Integer)
    ):
        return None

    def codegen(context, builder, signature, args):
        array_type, row_type = signature.args
        view = context.make_array(array_type)(context, builder, args[0])
        index = context.cast(builder, args[1], row_type, types.intp)
        indices = [index] + [context.get_constant(types.intp, 0)] * (array_type.ndim - 1)
        pointer = cgutils.get_item_pointer2(
            context,
            builder,
            view.data,
            cgutils.unpack_tuple(builder, view.shape),
            cgutils.unpack_tuple(builder, view.strides),
            array_type.layout,
            indices,
            wraparound=False,
            boundscheck=False,
        )
        byte_pointer = ir.IntType(8).as_pointer()
        i32 = ir.IntType(32)
        function = cgutils.get_or_insert_function(
            builder.module,
            ir.FunctionType(ir.VoidType(), [byte_pointer, i32, i32, i32]),
            "llvm.prefetch.p0",
        )
        builder.call(function, [builder.bitcast(pointer, byte_pointer), i32(0), i32(3), i32(1)])
        return context.get_dummy_value()

    return types.void(array, row), codegen


# ----------------------------------------------------------------------------- calendar


@njit(cache=True, error_model="numpy", inline="always")
def smaller(a, b):
    """The smaller of two floats as one select instruction (numba compiles the builtin
    ``min`` of two floats to a function call, with its NaN handling)."""
    return a if a < b else b


@njit(cache=True, error_model="numpy", inline="always")
def event_key(phase, i):
    """Time of particle i's next event: its earliest pair collision or crossing."""
    return smaller(phase[i, 6], phase[i, 7])


@njit(cache=True, error_model="numpy", inline="always")
def earlier(time_a, index_a, time_b, index_b):
    """Order of the calendar's entries: by time, equal times by particle (deterministic)."""
    return time_a < time_b or (time_a == time_b and index_a < index_b)


@njit(cache=True, error_model="numpy", inline="always")
def heap_sift_up(heap_time, heap_index, links, position, key, i):
    """Place entry (key, i) at ``position`` of the current-bucket heap or above it.

    Entries are ordered by (time, particle) so that equal times resolve deterministically.
    """
    while position > 0:
        parent = (position - 1) >> 1
        parent_time = heap_time[parent]
        parent_index = heap_index[parent]
        if earlier(parent_time, parent_index, key, i):
            break
        heap_time[position] = parent_time
        heap_index[position] = parent_index
        links[parent_index, L_HEAP] = position
        position = parent
    heap_time[position] = key
    heap_index[position] = i
    links[i, L_HEAP] = position


@njit(cache=True, error_model="numpy", inline="always")
def heap_sift_down(heap_time, heap_index, links, position, size, key, i):
    """Place entry (key, i) at ``position`` of the heap (of ``size`` entries) or below it."""
    while True:
        child = 2 * position + 1
        if child >= size:
            break
        other = child + 1
        if other < size and earlier(
            heap_time[other], heap_index[other], heap_time[child], heap_index[child]
        ):
            child = other
        child_time = heap_time[child]
        child_index = heap_index[child]
        if earlier(key, i, child_time, child_index):
            break
        heap_time[position] = child_time
        heap_index[position] = child_index
        links[child_index, L_HEAP] = position
        position = child
    heap_time[position] = key
    heap_index[position] = i
    links[i, L_HEAP] = position


@njit(cache=True, error_model="numpy", inline="always")
def calendar_place(key, heads, calendar, cursor):
    """Where an event at time ``key`` goes: −1 (``PLACE_HEAP``) into the current bucket's
    heap if it falls in that bucket (or before it, by round-off), else the list of its
    bucket, or the overflow list B beyond the calendar's horizon (``key`` = +inf
    included)."""
    q = (key - calendar[0]) * calendar[1]
    if q < cursor[0] + 1:
        return PLACE_HEAP
    n_buckets = heads.shape[0] - 1
    return int(q) if q < n_buckets else n_buckets


@njit(cache=True, error_model="numpy", inline="always")
def calendar_insert(i, key, links, heads, heap_time, heap_index, calendar, cursor):
    """Schedule particle i's next event at time ``key`` (see ``calendar_place``), in a list
    at its head."""
    bucket = calendar_place(key, heads, calendar, cursor)
    if bucket == PLACE_HEAP:
        size = cursor[1]
        cursor[1] = size + 1
        links[i, L_PLACE] = PLACE_HEAP
        heap_sift_up(heap_time, heap_index, links, size, key, i)
        return
    head = heads[bucket]
    links[i, L_NEXT] = head
    links[i, L_PREV] = -1
    links[i, L_PLACE] = bucket
    if head >= 0:
        links[head, L_PREV] = i
    heads[bucket] = i


@njit(cache=True, error_model="numpy", inline="always")
def calendar_remove(i, links, heads, heap_time, heap_index, cursor):
    """Take particle i's event out of the calendar (out of the heap or its list)."""
    place = links[i, L_PLACE]
    if place == PLACE_HEAP:
        size = cursor[1] - 1
        cursor[1] = size
        position = links[i, L_HEAP]
        if position == size:
            return
        key = heap_time[size]
        moved = heap_index[size]
        parent = (position - 1) >> 1
        if position > 0 and earlier(key, moved, heap_time[parent], heap_index[parent]):
            heap_sift_up(heap_time, heap_index, links, position, key, moved)
        else:
            heap_sift_down(heap_time, heap_index, links, position, size, key, moved)
        return
    following = links[i, L_NEXT]
    previous = links[i, L_PREV]
    if previous >= 0:
        links[previous, L_NEXT] = following
    else:
        heads[place] = following
    if following >= 0:
        links[following, L_PREV] = previous


@njit(cache=True, error_model="numpy", inline="always")
def calendar_reschedule(i, key, links, heads, heap_time, heap_index, calendar, cursor):
    """Move particle i's event to the new time ``key``."""
    calendar_remove(i, links, heads, heap_time, heap_index, cursor)
    calendar_insert(i, key, links, heads, heap_time, heap_index, calendar, cursor)


@njit(cache=True, error_model="numpy")
def calendar_build(phase, links, heads, heap_time, heap_index, calendar, cursor):
    """(Re)build the calendar from every particle's event time ``event_key``.

    The origin is the earliest finite event time, the bucket width ``EVENTS_PER_BUCKET``
    times the mean event time after the origin divided by N (about that many events per
    bucket), so the B buckets reach about B/N · EVENTS_PER_BUCKET mean event times ahead.
    Returns the number of finite event times (0: nothing will ever happen).
    """
    n = phase.shape[0]
    origin = np.inf
    total = 0.0
    finite = 0
    for i in range(n):
        key = event_key(phase, i)
        if key < np.inf:
            finite += 1
            total += key
            if key < origin:
                origin = key
    width = 1.0
    if finite > 0:
        mean_ahead = total / finite - origin
        if mean_ahead > 0.0:
            width = EVENTS_PER_BUCKET * mean_ahead / n
    else:
        origin = 0.0
    calendar[0] = origin
    calendar[1] = 1.0 / width
    cursor[0] = 0
    cursor[1] = 0
    for slot in range(2, cursor.shape[0]):
        cursor[slot] = -1
    for bucket in range(heads.shape[0]):
        heads[bucket] = -1
    for i in range(n):
        calendar_insert(
            i, event_key(phase, i), links, heads, heap_time, heap_index, calendar, cursor
        )
    return finite


@njit(cache=True, error_model="numpy", inline="always")
def prefetch_particle(j, phase, ints, links):
    """Prefetch the rows of particle j (phase, ints and its calendar links)."""
    prefetch_row(phase, j)
    prefetch_row(ints, j)
    prefetch_row(links, j)


@njit(cache=True, error_model="numpy", inline="always")
def prefetch_scan(j, stage, phase, ints, members, occupancy, last_collision, grid):
    """Prefetch for particle j's coming event, stage 2 or 1 (see ``prefetch_ahead``).

    Stage 2: the cell rows and occupancies its scan will visit and, for a pair event, the
    partner's rows and both ``last_collision`` entries. Stage 1: the rows of the particles
    listed in those cells (the candidates of the scan) and, for a crossing, the row of the
    member its cell removal moves. The cells of a pair event are all neighbours; those of
    a crossing its own cell, the destination and the layer beyond the destination
    (candidates: that layer only). Cells are taken without periodic wrapping (a hint: the
    rare misses at the box edges cost nothing else)."""
    n_cells = members.shape[0]
    dim = grid[I_DIM]
    layer = grid[0] * grid[1]
    flat = cell_flat(ints[j, 5], ints[j, 6], ints[j, 7], grid)
    lo0, hi0, lo1, hi1 = -1, 1, -1, 1
    lo2, hi2 = (-1, 1) if dim == 3 else (0, 0)
    if phase[j, 7] <= phase[j, 6]:
        code = ints[j, 2]
        step = 1 if (code & 1) == 1 else -1
        stride = 1 if code >> 1 == 0 else (grid[0] if code >> 1 == 1 else layer)
        if stage == 2:
            # the own and the destination cell (removal and insertion)
            for cell in (flat, flat + step * stride):
                if 0 <= cell < n_cells:
                    prefetch_row(members, cell)
                    prefetch_row(occupancy, cell)
        elif occupancy[flat] > 0:
            prefetch_row(ints, members[flat, occupancy[flat] - 1])
        # then the layer beyond the destination
        if code >> 1 == 0:
            lo0, hi0 = 2 * step, 2 * step
        elif code >> 1 == 1:
            lo1, hi1 = 2 * step, 2 * step
        else:
            lo2, hi2 = 2 * step, 2 * step
    elif stage == 2:
        partner = ints[j, 0]
        if partner >= 0:
            prefetch_row(phase, partner)
            prefetch_row(ints, partner)
            prefetch_row(last_collision, partner)
            prefetch_row(last_collision, j)
    for o2 in range(lo2, hi2 + 1):
        for o1 in range(lo1, hi1 + 1):
            for o0 in range(lo0, hi0 + 1):
                cell = flat + o0 + o1 * grid[0] + o2 * layer
                if cell < 0 or cell >= n_cells:
                    continue
                if stage == 2:
                    prefetch_row(members, cell)
                    prefetch_row(occupancy, cell)
                else:
                    for q in range(occupancy[cell]):
                        prefetch_row(phase, members[cell, q])


@njit(cache=True, error_model="numpy", inline="always")
def prefetch_step(phase, ints, members, occupancy, last_collision, grid, links, cursor):
    """One step of stages 2 and 1 of the prefetch pipeline (``prefetch_ahead``): the next
    particle of each stage's list. Called once per event, so that the prefetches are spread
    over the events rather than issued in a burst at each bucket opening (4 % faster at
    N = 1e5 and ρσ² = 1e-2, 12 % at 1e-3)."""
    j = cursor[C_STAGE2]
    if j >= 0:
        prefetch_scan(j, 2, phase, ints, members, occupancy, last_collision, grid)
        cursor[C_STAGE2] = links[j, L_NEXT]
    j = cursor[C_STAGE1]
    if j >= 0:
        prefetch_scan(j, 1, phase, ints, members, occupancy, last_collision, grid)
        cursor[C_STAGE1] = links[j, L_NEXT]


@njit(cache=True, error_model="numpy", inline="always")
def prefetch_ahead(
    current, phase, ints, members, occupancy, last_collision, grid, links, heads, cursor
):
    """Prefetch, in stages, what the events of the coming buckets will read, on opening
    bucket ``current``. Stage 3: the rows (``phase``, ``ints``, ``links``) of the
    particles of bucket + 3; stage 2 (``prefetch_scan``): for those of bucket + 2, the
    cells their scans will visit and a pair event's partner; stage 1 (at level
    ``grid[I_PREFETCH]`` = 2): for those of bucket + 1, the candidates of their scans
    (many prefetches, worth it only when most of them would miss the L3 cache). Each stage
    reads only what an earlier stage prefetched.

    Stages 2 and 1 walk their lists one particle per event (``prefetch_step``,
    ``cursor[C_STAGE2]``, ``cursor[C_STAGE1]``, the latter −1 below level 2); what a
    bucket's events left over is done here, before the stages move on to the next lists.
    Stage 3 walks the lists of buckets + 3 … + 2 + R (R = ``PREFETCH_WALKS``) side by
    side, one particle per list and opening (``cursor[C_WALKS + b % R]`` is the particle
    reached in bucket b's list): each step reads a ``links`` row prefetched one opening
    earlier, and the R steps are independent, where walking one list is a chain of
    dependent misses. A list still
    unfinished at + 3 (longer than R) is walked to its end then. Lists change meanwhile
    (a walk may miss new entries or stray into another list, or into the heap's stale
    links): only the hints suffer, every index read is a particle or −1, and walks are
    bounded by ``WALK_LIMIT``.
    """
    n_buckets = heads.shape[0] - 1
    for stage, slot in ((1, C_STAGE1), (2, C_STAGE2)):
        j = cursor[slot]
        for _ in range(WALK_LIMIT):
            if j < 0:
                break
            prefetch_scan(j, stage, phase, ints, members, occupancy, last_collision, grid)
            j = links[j, L_NEXT]
    candidates = grid[I_PREFETCH] == 2
    cursor[C_STAGE1] = heads[current + 1] if candidates and current + 1 < n_buckets else -1
    cursor[C_STAGE2] = heads[current + 2] if current + 2 < n_buckets else -1
    for offset in range(3, 3 + PREFETCH_WALKS):
        bucket = current + offset
        slot = C_WALKS + bucket % PREFETCH_WALKS
        if offset == 2 + PREFETCH_WALKS:
            # a new walk: the list head
            j = heads[bucket] if bucket < n_buckets else -1
            if j >= 0:
                prefetch_particle(j, phase, ints, links)
            cursor[slot] = j
            continue
        j = cursor[slot]
        if j >= 0:
            j = links[j, L_NEXT]
        if offset > 3:
            if j >= 0:
                prefetch_particle(j, phase, ints, links)
                cursor[slot] = j
            # else: the walk ended; cursor[slot] keeps the list's last particle (its
            # successor is −1) or −1
        else:
            for _ in range(WALK_LIMIT):
                if j < 0:
                    break
                prefetch_particle(j, phase, ints, links)
                j = links[j, L_NEXT]
            cursor[slot] = -1


@njit(cache=True, error_model="numpy", inline="always")
def calendar_next(
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
):
    """The particle whose event comes next (the top of the current bucket's heap), −1 if
    no event is finite. Moves on to the next non-empty bucket when the heap is empty,
    pouring its list into the heap; past the last bucket every event waits in the overflow
    list, and the calendar is rebuilt from there.

    On opening a bucket, large systems (``grid[I_PREFETCH]``) prefetch what the events of
    the next three buckets will read (``prefetch_ahead``).
    """
    n_buckets = heads.shape[0] - 1
    while cursor[1] == 0:
        current = cursor[0] + 1
        if current >= n_buckets:
            if calendar_build(phase, links, heads, heap_time, heap_index, calendar, cursor) == 0:
                return -1
            continue
        cursor[0] = current
        j = heads[current]
        heads[current] = -1
        while j >= 0:
            following = links[j, L_NEXT]
            size = cursor[1]
            cursor[1] = size + 1
            links[j, L_PLACE] = PLACE_HEAP
            heap_sift_up(heap_time, heap_index, links, size, event_key(phase, j), j)
            j = following
        if grid[I_PREFETCH] > 0 and cursor.shape[0] >= N_CURSOR:
            prefetch_ahead(
                current,
                phase,
                ints,
                members,
                occupancy,
                last_collision,
                grid,
                links,
                heads,
                cursor,
            )
    return heap_index[0]


# ----------------------------------------------------------------------------- geometry


@njit(cache=True, error_model="numpy", inline="always")
def cell_flat(cx, cy, cz, grid):
    """Flat index of cell (cx, cy, cz): x fastest."""
    return (cz * grid[1] + cy) * grid[0] + cx


@njit(cache=True, error_model="numpy", inline="always")
def cell_insert(i, flat, members, occupancy, ints):
    """Append particle i to cell ``flat``; False (nothing changed) if the cell is full.

    ``members`` (n_cells, C) int32 lists the particles of each cell in its first
    ``occupancy[flat]`` entries; ``ints[i, 4]`` is i's position there.
    """
    count = occupancy[flat]
    if count >= members.shape[1]:
        return False
    members[flat, count] = i
    ints[i, 4] = count
    occupancy[flat] = count + 1
    return True


@njit(cache=True, error_model="numpy", inline="always")
def cell_remove(i, flat, members, occupancy, ints):
    """Remove particle i from cell ``flat`` (the cell's last member takes its place)."""
    last = occupancy[flat] - 1
    position = ints[i, 4]
    moved = members[flat, last]
    members[flat, position] = moved
    ints[moved, 4] = position
    occupancy[flat] = last


@njit(cache=True, error_model="numpy", inline="always")
def pair_time(xi, yi, zi, ui, vi, wi, phase, j, sx, sy, sz, t, sigma2, dim):
    """Absolute time of the next contact of i (position (xi, yi, zi) at time t, velocity
    (ui, vi, wi)) with the image of j shifted by (sx, sy, sz); +inf if they never touch.

    Uses the cancellation-free root (|r|² − σ²)/(−b + √disc); an approaching pair that
    already overlaps by round-off collides at once (returns t).
    """
    dx = phase[j, 0] + phase[j, 3] * t + sx - xi
    dy = phase[j, 1] + phase[j, 4] * t + sy - yi
    du = phase[j, 3] - ui
    dv = phase[j, 4] - vi
    b = dx * du + dy * dv
    r2 = dx * dx + dy * dy
    g2 = du * du + dv * dv
    if dim == 3:
        dz = phase[j, 2] + phase[j, 5] * t + sz - zi
        dw = phase[j, 5] - wi
        b += dz * dw
        r2 += dz * dz
        g2 += dw * dw
    c = r2 - sigma2
    disc = b * b - g2 * c
    # one branch on min(disc, −b) > 0, i.e. disc > 0 (impact parameter below σ) and b < 0
    # (approaching): rarely true, so well predicted; a separate test of b < 0, a coin flip,
    # would cost a branch misprediction every other pair
    if smaller(disc, -b) > 0.0:
        dt = c / (np.sqrt(disc) - b)
        if dt < 0.0:
            dt = 0.0
        return t + dt
    return np.inf


@njit(cache=True, error_model="numpy", inline="always")
def scan_neighbours(
    i,
    t,
    fixed_axis,
    fixed_offset,
    phase,
    ints,
    members,
    occupancy,
    geometry,
    grid,
    best_t,
    best_j,
    scratch,
    images,
):
    """Earliest collision of i with the particles of its neighbour cells.

    All 3^d cells around i's cell when ``fixed_axis`` < 0, otherwise only the layer whose
    offset along ``fixed_axis`` is ``fixed_offset`` (the cells that became adjacent after a
    crossing). Periodic axes wrap with the image shift ±L; cells beyond a wall are skipped.
    Returns (best_t, best_j, number of pair tests).

    Two passes: the candidates are first gathered from the cell rows into ``scratch``
    ((N + C,) int64, entry = 32 j + cell ordinal), with i's position relative to each visited
    cell's image in ``images`` ((27, 3) float64); then one loop tests them all. Gathering
    copies whole rows of C entries (no per-cell data-dependent branch) and the tests are
    independent of each other, so the processor overlaps them.
    """
    dim = grid[I_DIM]
    sigma2 = geometry[G_SIGMA2]
    lo0, hi0 = -1, 1
    lo1, hi1 = -1, 1
    lo2, hi2 = (-1, 1) if dim == 3 else (0, 0)
    if fixed_axis == 0:
        lo0 = fixed_offset
        hi0 = fixed_offset
    elif fixed_axis == 1:
        lo1 = fixed_offset
        hi1 = fixed_offset
    elif fixed_axis == 2:
        lo2 = fixed_offset
        hi2 = fixed_offset
    n0 = grid[0]
    n1 = grid[1]
    n2 = grid[2]
    c0 = ints[i, 5 + 0]
    c1 = ints[i, 5 + 1]
    c2 = ints[i, 5 + 2]
    xi = phase[i, 0] + phase[i, 3] * t
    yi = phase[i, 1] + phase[i, 4] * t
    zi = phase[i, 2] + phase[i, 5] * t
    count = 0
    ordinal = 0
    for o2 in range(lo2, hi2 + 1):
        k2 = c2 + o2
        s2 = 0.0
        if k2 < 0:
            if grid[I_WALL + 2]:
                continue
            k2 += n2
            s2 = -geometry[G_L + 2]
        elif k2 >= n2:
            if grid[I_WALL + 2]:
                continue
            k2 -= n2
            s2 = geometry[G_L + 2]
        for o1 in range(lo1, hi1 + 1):
            k1 = c1 + o1
            s1 = 0.0
            if k1 < 0:
                if grid[I_WALL + 1]:
                    continue
                k1 += n1
                s1 = -geometry[G_L + 1]
            elif k1 >= n1:
                if grid[I_WALL + 1]:
                    continue
                k1 -= n1
                s1 = geometry[G_L + 1]
            for o0 in range(lo0, hi0 + 1):
                k0 = c0 + o0
                s0 = 0.0
                if k0 < 0:
                    if grid[I_WALL]:
                        continue
                    k0 += n0
                    s0 = -geometry[G_L]
                elif k0 >= n0:
                    if grid[I_WALL]:
                        continue
                    k0 -= n0
                    s0 = geometry[G_L]
                flat = (k2 * n1 + k1) * n0 + k0
                occupied = occupancy[flat]
                images[ordinal, 0] = xi - s0
                images[ordinal, 1] = yi - s1
                images[ordinal, 2] = zi - s2
                # copy a fixed head of the row (no data-dependent branch: most cells hold
                # at most GATHER_HEAD particles), then the rare rest; entries past the
                # occupied ones are junk that ``count`` never reaches
                for q in range(GATHER_HEAD):
                    scratch[count + q] = (members[flat, q] << 5) | ordinal
                if occupied > GATHER_HEAD:
                    for q in range(GATHER_HEAD, occupied):
                        scratch[count + q] = (members[flat, q] << 5) | ordinal
                count += occupied
                ordinal += 1
    ui = phase[i, 3]
    vi = phase[i, 4]
    wi = phase[i, 5]
    tests = 0
    for q in range(count):
        code = scratch[q]
        j = code >> 5
        if j == i:
            continue
        o = code & 31
        tc = pair_time(
            images[o, 0],
            images[o, 1],
            images[o, 2],
            ui,
            vi,
            wi,
            phase,
            j,
            0.0,
            0.0,
            0.0,
            t,
            sigma2,
            dim,
        )
        tests += 1
        if tc < best_t:
            best_t = tc
            best_j = j
    return best_t, best_j, tests


@njit(cache=True, error_model="numpy", inline="always")
def next_crossing(i, phase, ints, geometry, grid):
    """Time and face code (2k + 1 upwards, 2k downwards) at which i leaves its cell or
    touches a wall. A wall face is the plane at σ/2 from the wall. Written with selects
    rather than branches: the direction of motion is a coin flip for the branch predictor."""
    dim = grid[I_DIM]
    best = np.inf
    code = -1
    half_sigma = 0.5 * geometry[G_SIGMA]
    for k in range(dim):
        velocity = phase[i, 3 + k]
        c = ints[i, 5 + k]
        width = geometry[G_W + k]
        upper = (c + 1) * width
        lower = c * width
        if grid[I_WALL + k]:
            if c == grid[I_N + k] - 1:
                upper = geometry[G_L + k] - half_sigma
            if c == 0:
                lower = half_sigma
        upwards = velocity > 0.0
        boundary = upper if upwards else lower
        tc = (boundary - phase[i, k]) / velocity
        tc = tc if velocity != 0.0 else np.inf
        face = 2 * k + (1 if upwards else 0)
        earlier = tc < best
        code = face if earlier else code
        best = tc if earlier else best
    return best, code


@njit(cache=True, error_model="numpy", inline="always")
def predict(
    i,
    t,
    phase,
    ints,
    members,
    occupancy,
    geometry,
    grid,
    counters,
    scratch,
    images,
):
    """Predict i's next collision (all neighbour cells) and next crossing from time t."""
    best_t, best_j, tests = scan_neighbours(
        i, t, -1, 0, phase, ints, members, occupancy, geometry, grid, np.inf, -1, scratch, images
    )
    counters[COUNT_PAIR_TESTS] += tests
    phase[i, 6] = best_t
    ints[i, 0] = best_j
    ints[i, 1] = counters[COUNT_EVENTS]
    tc, code = next_crossing(i, phase, ints, geometry, grid)
    # never schedule in the past (round-off right after a crossing)
    phase[i, 7] = tc if tc > t else t
    ints[i, 2] = code


# ----------------------------------------------------------------------------- observers


@njit(cache=True, error_model="numpy")
def temperature(phase, dim):
    """Kinetic temperature Σ v² / (d N) (m = 1)."""
    total = 0.0
    n = phase.shape[0]
    for i in range(n):
        for k in range(dim):
            total += phase[i, 3 + k] * phase[i, 3 + k]
    return total / (dim * n)


@njit(cache=True, error_model="numpy")
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


@njit(cache=True, error_model="numpy", inline="always")
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


@njit(cache=True, error_model="numpy")
def rescale_velocities(t, target_temperature, phase, dim):
    """Thermostat: scale every velocity by s = sqrt(T_target / T) at time t.

    Positions are continuous (x0 ← x0 + v t (1 − s)); every pending event time maps to
    t + (t_e − t)/s, an order-preserving map, so no prediction is redone (the caller
    rebuilds the calendar, whose buckets do change).
    """
    n = phase.shape[0]
    current = temperature(phase, dim)
    if current <= 0.0:
        return
    s = np.sqrt(target_temperature / current)
    inverse = 1.0 / s
    for i in range(n):
        for k in range(3):
            phase[i, k] += phase[i, 3 + k] * t * (1.0 - s)
            phase[i, 3 + k] *= s
        if phase[i, 6] < np.inf:
            phase[i, 6] = t + (phase[i, 6] - t) * inverse
        if phase[i, 7] < np.inf:
            phase[i, 7] = t + (phase[i, 7] - t) * inverse


@njit(cache=True, error_model="numpy", inline="always")
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
        d = (phase[j, k] + phase[j, 3 + k] * t) - (phase[i, k] + phase[i, 3 + k] * t)
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
    gn = (phase[j, 3] - phase[i, 3]) * n0 + (phase[j, 4] - phase[i, 4]) * n1
    if dim == 3:
        gn += (phase[j, 5] - phase[i, 5]) * n2
    # gn < 0: approaching. Δv_i = (1+α)/2 gn n, Δv_j = −Δv_i
    factor = 0.5 * (1.0 + alpha) * gn
    for k in range(dim):
        nk = n0 if k == 0 else (n1 if k == 1 else n2)
        delta = factor * nk
        phase[i, 3 + k] += delta
        phase[i, k] -= delta * t
        phase[j, 3 + k] -= delta
        phase[j, k] += delta * t
    return gn, alpha


@njit(cache=True, error_model="numpy", _nrt=False)
def advance(
    t_stop,
    max_collisions,
    max_events,
    clock,
    target_temperature,
    observing,
    phase,
    ints,
    members,
    occupancy,
    links,
    heads,
    heap_time,
    heap_index,
    calendar,
    cursor,
    last_collision,
    streak,
    label,
    scratch,
    images,
    geometry,
    grid,
    counters,
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
):
    """Run the event loop from ``clock[0]`` until ``t_stop`` or ``max_collisions`` more
    collisions (or a failure status), then set ``clock[0]`` and return a status code.

    Observers: ``window_*`` (W window lengths, zero-size arrays disable them),
    ``flight_*``/``path_histogram`` (only when ``observing``), ``wall_statistics`` (2d, 3)
    [hits, Σ|v⊥|, Σ 1/|v⊥|] per face 2k + upwards, ``sample_*`` temperature and collision
    count at the increasing times ``sample_times`` (``sample_cursor[0]`` = next one), and
    ``record_*`` a ring buffer of the last collisions (time, pair of labels ``label[i]``,
    normal relative speed).
    """
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
    for w in range(n_windows):
        if window_end[w] < next_window:
            next_window = window_end[w]
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
        while next_window < t_event and next_window <= t_stop:
            next_window = np.inf
            for w in range(n_windows):
                if window_end[w] < t_event and window_end[w] <= t_stop:
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
                counters[COUNT_COLLAPSE_PARTNER] = ints[i, 0]
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
        if phase[i, 7] <= phase[i, 6]:
            # ---------------------------------------------------------- crossing or wall
            code = ints[i, 2]
            k = code >> 1
            upwards = (code & 1) == 1
            c = ints[i, 5 + k]
            at_wall = False
            if grid[I_WALL + k] != 0:
                at_wall = c == grid[I_N + k] - 1 if upwards else c == 0
            if at_wall:
                velocity = phase[i, 3 + k]
                speed = abs(velocity)
                wall_statistics[code, 0] += 1.0
                wall_statistics[code, 1] += speed
                wall_statistics[code, 2] += 1.0 / speed
                phase[i, k] += 2.0 * velocity * t
                phase[i, 3 + k] = -velocity
                ints[i, 3] = event_number
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
                old = cell_flat(ints[i, 5], ints[i, 6], ints[i, 7], grid)
                new = old + (c - ints[i, 5 + k]) * (
                    1 if k == 0 else (grid[0] if k == 1 else grid[0] * grid[1])
                )
                if occupancy[new] >= members.shape[1]:
                    # the destination row is full: stop before changing anything; the
                    # caller grows the rows and resumes with this very event
                    counters[COUNT_EVENTS] -= 1
                    clock[0] = t_previous
                    return STATUS_CELL_FULL
                cell_remove(i, old, members, occupancy, ints)
                phase[i, k] += wrap
                ints[i, 5 + k] = c
                cell_insert(i, new, members, occupancy, ints)
                counters[COUNT_CROSSINGS] += 1
                axis = k
        else:
            j = ints[i, 0]
            if ints[j, 3] > ints[i, 1]:
                # ------------------------------------------------------ stale prediction
                counters[COUNT_INVALID] += 1
                new_crossing = False
            else:
                # ---------------------------------------------------------- pair collision
                collided = True
                second = j
                speed_i = np.sqrt(phase[i, 3] ** 2 + phase[i, 4] ** 2 + phase[i, 5] ** 2)
                speed_j = np.sqrt(phase[j, 3] ** 2 + phase[j, 4] ** 2 + phase[j, 5] ** 2)
                gn, alpha_used = collide(i, j, t, phase, geometry, grid, last_collision)
                if alpha_used < 1.0:
                    counters[COUNT_INELASTIC] += 1
                ints[i, 3] = event_number
                ints[j, 3] = event_number
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
                phase[p, 7] = tc if tc > t else t
                ints[p, 2] = new_code
                if pipeline:
                    # the list head that the rescheduling below reads, if the crossing
                    # stays the next event (mostly): the scan hides the miss
                    bucket = calendar_place(
                        phase[p, 7] if axis < 0 else event_key(phase, p), heads, calendar, cursor
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
            if axis < 0 or best_t < phase[p, 6]:
                phase[p, 6] = best_t
                ints[p, 0] = best_j
                ints[p, 1] = event_number
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
                rescale_velocities(t, target_temperature, phase, dim)
                calendar_build(phase, links, heads, heap_time, heap_index, calendar, cursor)
                counters[COUNT_RESCALES] += 1
            if collisions_done >= max_collisions:
                clock[0] = t
                return STATUS_COLLISIONS


# ----------------------------------------------------------------------------- set-up


@njit(cache=True, error_model="numpy")
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
                    phase[i, k] = 0.0
                    ints[i, 5 + k] = 0
                    continue
                length = geometry[G_L + k]
                if grid[I_WALL + k]:
                    x = 0.5 * sigma + (length - sigma) * uniform(state)
                else:
                    x = length * uniform(state)
                phase[i, k] = x
                c = int(x / geometry[G_W + k])
                if c >= grid[I_N + k]:
                    c = grid[I_N + k] - 1
                ints[i, 5 + k] = c
            for k in range(3, 6):
                phase[i, k] = 0.0
            if not overlaps_neighbours(i, phase, ints, members, occupancy, geometry, grid, sigma2):
                flat = cell_flat(ints[i, 5], ints[i, 6], ints[i, 7], grid)
                if not cell_insert(i, flat, members, occupancy, ints):
                    return -1  # a cell is full: the caller grows the capacity and retries
                placed = True
                break
        if not placed:
            return i
    return n


@njit(cache=True, error_model="numpy")
def overlaps_neighbours(i, phase, ints, members, occupancy, geometry, grid, sigma2):
    """True if particle i (at t = 0) overlaps a particle listed in its neighbour cells."""
    dim = grid[I_DIM]
    lo2, hi2 = (-1, 1) if dim == 3 else (0, 0)
    for o2 in range(lo2, hi2 + 1):
        for o1 in range(-1, 2):
            for o0 in range(-1, 2):
                ks = (ints[i, 5 + 0] + o0, ints[i, 5 + 1] + o1, ints[i, 5 + 2] + o2)
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
                    dx = phase[j, 0] + shift0 - phase[i, 0]
                    dy = phase[j, 1] + shift1 - phase[i, 1]
                    dz = phase[j, 2] + shift2 - phase[i, 2]
                    if dx * dx + dy * dy + dz * dz < sigma2:
                        return True
    return False


@njit(cache=True, error_model="numpy")
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
                ints[i, 5 + k] = 0
                continue
            x = phase[i, k] + phase[i, 3 + k] * t
            length = geometry[G_L + k]
            if x < 0.0 or x > length:
                return i
            c = int(x / geometry[G_W + k])
            if c >= grid[I_N + k]:
                c = grid[I_N + k] - 1
            ints[i, 5 + k] = c
        if not cell_insert(
            i, cell_flat(ints[i, 5], ints[i, 6], ints[i, 7], grid), members, occupancy, ints
        ):
            return -2
    return -1


@njit(cache=True, error_model="numpy")
def relink_cells(ints, members, occupancy, grid):
    """Rebuild the cell rows from the cell coordinates ``cell`` (kept as they are: a
    particle sitting on a face by round-off stays in the cell its crossings put it in).
    Returns False if a row is full (the caller grows the capacity and retries)."""
    for flat in range(occupancy.shape[0]):
        occupancy[flat] = 0
    for i in range(ints.shape[0]):
        if not cell_insert(
            i, cell_flat(ints[i, 5], ints[i, 6], ints[i, 7], grid), members, occupancy, ints
        ):
            return False
    return True


@njit(cache=True, error_model="numpy")
def predict_all(
    t,
    phase,
    ints,
    members,
    occupancy,
    geometry,
    grid,
    links,
    heads,
    heap_time,
    heap_index,
    calendar,
    cursor,
    counters,
    scratch,
    images,
):
    """Predict every particle's events from time t and rebuild the calendar."""
    n = phase.shape[0]
    for i in range(n):
        predict(
            i,
            t,
            phase,
            ints,
            members,
            occupancy,
            geometry,
            grid,
            counters,
            scratch,
            images,
        )
    calendar_build(phase, links, heads, heap_time, heap_index, calendar, cursor)


@njit(cache=True, error_model="numpy")
def rebase(
    t,
    phase,
    links,
    heads,
    heap_time,
    heap_index,
    calendar,
    cursor,
    last_collision,
    window_end,
    sample_times,
    record_time,
):
    """Move the time origin to t (every stored time −= t, x0 += v t), to keep round-off
    small in long runs, and rebuild the calendar on the new clock. Positions and the order
    of events are unchanged."""
    n = phase.shape[0]
    for i in range(n):
        for k in range(3):
            phase[i, k] += phase[i, 3 + k] * t
        phase[i, 6] -= t
        phase[i, 7] -= t
        last_collision[i] -= t
    calendar_build(phase, links, heads, heap_time, heap_index, calendar, cursor)
    for w in range(window_end.shape[0]):
        window_end[w] -= t
    for s in range(sample_times.shape[0]):
        sample_times[s] -= t
    for s in range(record_time.shape[0]):
        record_time[s] -= t


@njit(cache=True, error_model="numpy")
def draw_velocities(phase, dim, state):
    """Independent standard normal velocity components (columns 3 .. 2 + d; others 0)."""
    n = phase.shape[0]
    for i in range(n):
        a, b = normal_pair(state)
        phase[i, 3] = a
        phase[i, 4] = b
        phase[i, 5] = normal_pair(state)[0] if dim == 3 else 0.0


@njit(cache=True, error_model="numpy")
def min_pair_distance(phase, ints, members, occupancy, geometry, grid, t):
    """Smallest centre distance at time t between particles in neighbour cells (periodic
    images included): ≥ σ when nothing overlaps. +inf if no pair is in reach."""
    n = phase.shape[0]
    dim = grid[I_DIM]
    best = np.inf
    lo2, hi2 = (-1, 1) if dim == 3 else (0, 0)
    for i in range(n):
        xi0 = phase[i, 0] + phase[i, 3] * t
        xi1 = phase[i, 1] + phase[i, 4] * t
        xi2 = phase[i, 2] + phase[i, 5] * t
        for o2 in range(lo2, hi2 + 1):
            k2, s2, skip2 = _neighbour(
                ints[i, 5 + 2] + o2, grid[2], grid[I_WALL + 2], geometry[G_L + 2]
            )
            if skip2:
                continue
            for o1 in range(-1, 2):
                k1, s1, skip1 = _neighbour(
                    ints[i, 5 + 1] + o1, grid[1], grid[I_WALL + 1], geometry[G_L + 1]
                )
                if skip1:
                    continue
                for o0 in range(-1, 2):
                    k0, s0, skip0 = _neighbour(
                        ints[i, 5 + 0] + o0, grid[0], grid[I_WALL], geometry[G_L]
                    )
                    if skip0:
                        continue
                    flat = cell_flat(k0, k1, k2, grid)
                    for q in range(occupancy[flat]):
                        j = members[flat, q]
                        if j != i:
                            d0 = phase[j, 0] + phase[j, 3] * t + s0 - xi0
                            d1 = phase[j, 1] + phase[j, 4] * t + s1 - xi1
                            d2 = phase[j, 2] + phase[j, 5] * t + s2 - xi2
                            r2 = d0 * d0 + d1 * d1 + (d2 * d2 if dim == 3 else 0.0)
                            if r2 < best:
                                best = r2
    return np.sqrt(best)


@njit(cache=True, error_model="numpy")
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
