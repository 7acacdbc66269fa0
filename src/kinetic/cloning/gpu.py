"""The ``cuda`` backend of the cloning Monte Carlo: the discrete-time cloning algorithm,
one GPU thread per clone, many realizations per launch.

The tilted dynamics is the same as the CPU engine's (``kinetic.cloning.kernels``), in its
discrete-time form (Giardinà, Kurchan, Peliti, PRL 96, 120603 (2006); Lecomte, Tailleur,
J. Stat. Mech. P03004 (2007)):

1. *Advance*: every clone, one thread, runs the untilted collision process of its tagged
   particle exactly over a control interval Δ: candidates at its own rate
   K1|v| + 1/√2 (hard spheres: channels A and B of the CPU engine) or 1 (Maxwell
   molecules), exponential waiting times, the acceptance test and the post-collision
   velocity of the CPU engine's proposal functions (the same source, compiled for the
   GPU by ``kinetic.gpu.device_function``). It counts its collisions K_i.
2. *Weigh*: w_i = e^{-λ (K_i - K*)}, shifted by the largest log-weight (K* = min K_i for
   λ >= 0, max K_i for λ < 0), so that w_i <= 1; their float64 sum gives μ, and their
   fixed-point values q_i = round(2³² w_i) an exact int64 scan Q_i (inclusive, in index
   order) for the selection.
3. *Select*: systematic resampling keeps N_c clones: slot j goes to the clone i with
   Q_{i-1} <= (u + j) Q/N_c < Q_i (one uniform u per realization and interval). Clone i
   computes its own slots, [g(Q_{i-1}), g(Q_i)) with g(E) = ceil(N_c E/Q - u), and copies
   itself there: no search, and since the integer scan is monotone the slots tile
   [0, N_c) exactly. μ(λ) accumulates ln(Σw/N_c) - λK*, i.e. ln<e^{-λK}>, and the
   population after selection (distributed as the eigenfunction f̃(v, λ) of visco2008
   Eq. 28) gives the snapshot moments, rate and velocity histogram.

The intervals run one of two ways, chosen by N_c alone: up to ``RESIDENT_MAX_POPULATION``
clones, ``_resident`` runs all the intervals of a block of the run in one thread block per
realization (the phases separated by block barriers); above, three launches per interval
(``_advance``, ``_weigh`` whose last block of a realization closes the interval,
``_select``; four before revision 2a3fd50) over N_c/BLOCK thread blocks per realization.
Both draw the same random numbers and make the same integer selections.
Both read each realization's interval, count of intervals, λ and histogram flag from a
plan array, so that several points (λ) of one population share their launches
(``run_points``, behind ``kinetic.cloning.simulate_points``): a point's numbers are those
it gets alone, while the GPU holds many more threads than one point has clones. On the
launched path a realization's population alternates between two buffers on its own
count of intervals, and each interval's launches cover only the realizations that run
it.

For any Δ the product of the mean weights is an unbiased estimate of the tilted
partition function; its logarithm is biased by about -Var(w)/(2 N_c <w>²) per interval,
which grows with Δ and the tilt: ``kinetic.cloning.simulate`` picks Δ from λ so that
the weights' relative variance stays below ``CONTROL_WEIGHT_VARIANCE``. For Maxwell
molecules K_i is Poisson(Δ) whatever the velocity, so μ = e^{-λ} - 1, T = 1, a2 = 0 for
every Δ (the test of the GPU path).

Output: the CPU engine's per-block sums (``kernels.BLOCK_FIELDS``), so that the
estimators, the dataset and the figures do not know which backend ran:
``net_compensations`` holds N_c ln<w> summed over the block's intervals (μ = its sum over
N_c t, as the compensation count is for the CPU engine), the integrals hold the snapshot
sums times Δ, ``collision_events`` = ``elastic_collisions`` = ΣK_i (collisions of the
untilted clones), ``proposals`` = ``candidates``, ``max_speed`` the largest speed after a
selection.

Determinism: the float sums are folded in a fixed order (a tree in each thread block, then
strided sums and a tree in one block), the scan is integer, and the histogram counts, K*
and the max speed go through atomics (one per thread block, in shared memory for the
histogram) whose results do not depend on the order: the same seed gives the same
numbers on the same GPU model.
Clone i of realization r draws from ``thread_state(row r, i)``; the selection uniforms from
row r itself.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np
from numba.core.errors import NumbaPerformanceWarning

from kinetic.backends import simulated
from kinetic.cloning import kernels
from kinetic.cloning.arguments import MAX_CUDA_HISTOGRAM_BINS
from kinetic.gpu import (
    BLOCK,
    block_exclusive_scan,
    block_inclusive_scan,
    block_reduce_extreme,
    block_reduce_sum,
    cuda,
    device_function,
    device_inline,
    grid,
    kernel,
    kernel_within,
    last_block,
    to_device,
    warm,
)
from kinetic.rng import (
    thread_state,
    xoshiro_exponential,
    xoshiro_normal_pair,
    xoshiro_uniform,
)

__all__ = ["run", "run_points"]

_proposal_2d = device_function(kernels._hard_sphere_proposal_2d)
_proposal_3d = device_function(kernels._hard_sphere_proposal_3d)
_maxwell = device_function(kernels._maxwell_collision)
_tabulated_rate = device_function(kernels._tabulated_rate)
_thread_state = device_function(thread_state)
_exponential = device_function(xoshiro_exponential)
_normal_pair = device_function(xoshiro_normal_pair)
_uniform = device_function(xoshiro_uniform)

_HARD_SPHERES = kernels.HARD_SPHERES
_RATE_B = 1.0 / math.sqrt(2.0)  # channel B's rate (r(0), visco2008 Eq. 36)
_NO_MIN = np.int64(2**62)
_FIXED_POINT = 2.0**32  # q_i = round(2³² w_i): N_c 2³² < 2⁶³ up to N_c = 2 × 10⁹
_ZERO = np.int64(0)

_FIELD = {name: k for k, name in enumerate(kernels.BLOCK_FIELDS)}
_ELAPSED = _FIELD["elapsed_time"]
_NET = _FIELD["net_compensations"]
_COLLISIONS = _FIELD["elastic_collisions"]
_CANDIDATES = _FIELD["candidates"]
_SNAPSHOT = (_FIELD["integral_v2"], _FIELD["integral_v4"], _FIELD["integral_rate"])
_MAX_SPEED = _FIELD["max_speed"]
# columns of the per-thread-block partial sums
_P_COLLISIONS, _P_CANDIDATES, _P_WEIGHT, _P_V2, _P_V4, _P_RATE = range(6)


@kernel
def _seed(states, velocity, rows):
    """Clone i of realization r: its stream from row r, its velocity from the bath."""
    i = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    r = cuda.blockIdx.y
    n = states.shape[1]
    if i >= n:
        return
    s0, s1, s2, s3 = _thread_state(rows[r, 0], rows[r, 1], rows[r, 2], rows[r, 3], i)
    d = velocity.shape[1]
    k = 0
    while k < d:
        z0, z1, s0, s1, s2, s3 = _normal_pair(s0, s1, s2, s3)
        velocity[r, k, i] = z0
        if k + 1 < d:
            velocity[r, k + 1, i] = z1
        k += 2
    states[r, i, 0] = s0
    states[r, i, 1] = s1
    states[r, i, 2] = s2
    states[r, i, 3] = s3


@device_inline
def _advance_clone(velocity, states, r, i, code, interval, rate_a):
    """One control interval of the untilted process for clone i of realization r: its
    velocity and stream advance in place; returns (collisions, candidates)."""
    d = velocity.shape[1]
    collisions = 0
    candidates = 0
    s0 = states[r, i, 0]
    s1 = states[r, i, 1]
    s2 = states[r, i, 2]
    s3 = states[r, i, 3]
    waiting = False
    held = 0.0
    if code == _HARD_SPHERES:
        vx = velocity[r, 0, i]
        vy = velocity[r, 1, i]
        vz = velocity[r, 2, i] if d == 3 else 0.0
        t = 0.0
        while True:
            speed = math.sqrt(vx * vx + vy * vy + vz * vz)
            rate = rate_a * speed + _RATE_B
            e, s0, s1, s2, s3 = _exponential(s0, s1, s2, s3)
            t += e / rate
            if not t <= interval:  # a NaN rate ends the interval, not the lease
                break
            candidates += 1
            w, s0, s1, s2, s3 = _uniform(s0, s1, s2, s3)
            use_a = w * rate < rate_a * speed
            if d == 2:
                ok, vx, vy, s0, s1, s2, s3, waiting, held = _proposal_2d(
                    vx, vy, speed, use_a, s0, s1, s2, s3, waiting, held
                )
            else:
                ok, vx, vy, vz, s0, s1, s2, s3, waiting, held = _proposal_3d(
                    vx, vy, vz, speed, use_a, s0, s1, s2, s3, waiting, held
                )
            if ok:
                collisions += 1
        velocity[r, 0, i] = vx
        velocity[r, 1, i] = vy
        if d == 3:
            velocity[r, 2, i] = vz
    else:
        members = velocity[r]
        t = 0.0
        while True:
            e, s0, s1, s2, s3 = _exponential(s0, s1, s2, s3)
            t += e
            if not t <= interval:  # a NaN rate ends the interval, not the lease
                break
            candidates += 1
            collisions += 1
            _, s0, s1, s2, s3, waiting, held = _maxwell(members, i, s0, s1, s2, s3, waiting, held)
    states[r, i, 0] = s0
    states[r, i, 1] = s1
    states[r, i, 2] = s2
    states[r, i, 3] = s3
    return collisions, candidates


@device_inline
def _buffers(first, second, step):
    """(source, target) of interval ``step``: the population starts a block in ``first``
    and alternates between the two buffers."""
    if step % 2 == 0:
        return first, second
    return second, first


@kernel
def _advance(first, second, states, counts, extremes, partials, run, plan, order, step):
    """One control interval of the untilted process for every clone (thread (i, r)) of the
    realizations that run interval ``step`` (``plan[r]``: Δ, intervals, λ, record): the
    launch's rows are the first of ``order``, the realizations by their intervals in the
    block, most first, and the host launches as many rows as run the interval."""
    shared = cuda.shared.array(BLOCK, np.float64)
    shared_counts = cuda.shared.array(BLOCK, np.int64)
    i = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    r = order[cuda.blockIdx.y]
    code, rate_a = run
    source, _ = _buffers(first, second, step)
    n = states.shape[1]
    collisions = 0
    candidates = 0
    if i < n:
        collisions, candidates = _advance_clone(source, states, r, i, code, plan[r, 0], rate_a)
        counts[r, i] = collisions
    low = block_reduce_extreme(shared_counts, collisions if i < n else _NO_MIN, False)
    high = block_reduce_extreme(shared_counts, collisions if i < n else -1, True)
    total = block_reduce_sum(shared, float(collisions))
    tried = block_reduce_sum(shared, float(candidates))
    if cuda.threadIdx.x == 0:
        b = cuda.blockIdx.x
        partials[r, b, _P_COLLISIONS] = total
        partials[r, b, _P_CANDIDATES] = tried
        cuda.atomic.min(extremes, (r, 0), low)
        cuda.atomic.max(extremes, (r, 1), high)


@kernel
def _weigh(
    counts, extremes, cumulative, block_sums, partials, controls, out, done, plan, order, step
):
    """w_i = e^{-λ(K_i - K*)} <= 1: its sum per thread block (for μ), and the inclusive
    scan of q_i = round(2³² w_i) inside each thread block (exact int64), the block's
    total in ``block_sums``. The last block of realization r to finish
    (``kinetic.gpu.last_block``, its ticket ``done[r]``) then closes the interval
    (``_close``) with its threads, as a launch of one block a realization did before
    revision 2a3fd50 (``_close_interval``): the same folds, the same numbers."""
    shared = cuda.shared.array(BLOCK, np.float64)
    shared_q = cuda.shared.array(BLOCK, np.int64)
    last = cuda.shared.array(1, np.int64)
    t = cuda.threadIdx.x
    i = cuda.blockIdx.x * cuda.blockDim.x + t
    r = order[cuda.blockIdx.y]
    lam = plan[r, 2]
    n = counts.shape[1]
    shift = extremes[r, 0] if lam >= 0.0 else extremes[r, 1]
    weight = 0.0
    if i < n:
        weight = math.exp(-lam * (counts[r, i] - shift))
    total = block_reduce_sum(shared, weight)
    if t == 0:
        partials[r, cuda.blockIdx.x, _P_WEIGHT] = total
    prefix, block_total = block_inclusive_scan(
        shared_q, np.int64(weight * _FIXED_POINT + 0.5), _ZERO
    )
    if i < n:
        cumulative[r, i] = prefix
    if t == 0:
        block_sums[r, cuda.blockIdx.x] = block_total
    if not last_block(done, r, last):
        return
    _close(shared, shared_q, block_sums, extremes, controls, partials, out, plan, r, step)


@device_inline
def _fold(shared, partials, r, column):
    """Σ_b partials[r, b, column] in a fixed order (strided per thread, then a tree)."""
    total = 0.0
    for b in range(cuda.threadIdx.x, partials.shape[1], BLOCK):
        total += partials[r, b, column]
    return block_reduce_sum(shared, total)


@device_inline
def _selection_uniform(controls, r):
    """The next selection uniform of realization r, from its control stream
    ``controls[r, :4]`` (a multiple of 2⁻⁵³: exact as float64 and as 2⁵³ u in uint64)."""
    s0 = controls[r, 0]
    s1 = controls[r, 1]
    s2 = controls[r, 2]
    s3 = controls[r, 3]
    u, s0, s1, s2, s3 = _uniform(s0, s1, s2, s3)
    controls[r, 0] = s0
    controls[r, 1] = s1
    controls[r, 2] = s2
    controls[r, 3] = s3
    return float(np.uint64(u * 2.0**53)) * 2.0**-53


@device_inline
def _close(shared, shared_q, block_sums, extremes, controls, partials, out, plan, r, step):
    """By every thread of one block, for realization r: the block offsets of the integer scan, the
    interval's collision and candidate counts, ln<w> into ``net_compensations``, the
    next selection uniform, and the previous selection's snapshot sums times Δ (from the
    block's second interval on: the last one's are folded by ``_fold_snapshot``).
    ``extremes[r]`` holds (K min, K max, N_c, Q); K min and max are reset for the next
    interval."""
    interval = plan[r, 0]
    lam = plan[r, 2]
    previous = interval if step > 0 else 0.0
    total_q = block_exclusive_scan(shared_q, block_sums[r], block_sums.shape[1], _ZERO)
    weight = _fold(shared, partials, r, _P_WEIGHT)
    collisions = _fold(shared, partials, r, _P_COLLISIONS)
    candidates = _fold(shared, partials, r, _P_CANDIDATES)
    if previous > 0.0:
        _add_snapshot(shared, partials, out, r, previous)
    if cuda.threadIdx.x != 0:
        return
    n_clones = extremes[r, 2]
    shift = extremes[r, 0] if lam >= 0.0 else extremes[r, 1]
    out[r, _ELAPSED] += interval
    out[r, _NET] += n_clones * (math.log(weight / n_clones) - lam * shift)
    out[r, _COLLISIONS] += collisions
    out[r, _CANDIDATES] += candidates
    extremes[r, 0] = _NO_MIN
    extremes[r, 1] = -1
    extremes[r, 3] = total_q
    controls[r, 4] = np.uint64(_selection_uniform(controls, r) * 2.0**53)  # exactly


@device_inline
def _slots_below(cumulative, offsets, r, i, n, total, u):
    """g(Q_i) = ceil(N_c Q_i/Q - u) in [0, N_c]: the slots whose target lies below the
    inclusive cumulative weight of clone i (0 for i = -1, N_c for the last clone)."""
    if i < 0:
        return 0
    if i == n - 1:
        return n
    return _slot(cumulative[r, i] + offsets[r, i // BLOCK], n, total, u)


@kernel
def _select(
    first, second, cumulative, offsets, extremes, controls, partials, observers, plan, order, step
):
    """Clone i copies itself into its slots [g(Q_{i-1}), g(Q_i)) of the other buffer; then
    the snapshot sums (each clone counted once per copy) and, if ``plan[r, 3]``, the
    histogram of the new population."""
    shared = cuda.shared.array(BLOCK, np.float64)
    counts = cuda.shared.array(MAX_CUDA_HISTOGRAM_BINS, np.int64)
    table, table_step, histogram, half_width, block_max = observers
    t = cuda.threadIdx.x
    i = cuda.blockIdx.x * cuda.blockDim.x + t
    r = order[cuda.blockIdx.y]
    source, target = _buffers(first, second, step)
    record = plan[r, 3] != 0.0
    n = cumulative.shape[1]
    d = source.shape[1]
    bins = histogram.shape[1]
    if record:
        for b in range(t, bins, BLOCK):
            counts[b] = 0
        cuda.syncthreads()
    v2 = 0.0
    v4 = 0.0
    rate = 0.0
    speed = 0.0
    if i < n:
        total = float(extremes[r, 3])
        u = float(controls[r, 4]) * 2.0**-53
        first = _slots_below(cumulative, offsets, r, i - 1, n, total, u)
        last = _slots_below(cumulative, offsets, r, i, n, total, u)
        copies = last - first
        if copies > 0:
            for k in range(d):
                value = source[r, k, i]
                v2 += value * value
                for j in range(first, last):
                    target[r, k, j] = value
                if record:
                    b = math.floor((value + half_width) * bins / (2.0 * half_width))
                    if 0 <= b < bins:
                        cuda.atomic.add(counts, b, copies)
            speed = math.sqrt(v2)
            rate = copies * _tabulated_rate(speed, table, table_step)
            v4 = copies * v2 * v2
            v2 = copies * v2
    total = block_reduce_sum(shared, v2)
    if t == 0:
        partials[r, cuda.blockIdx.x, _P_V2] = total
    total = block_reduce_sum(shared, v4)
    if t == 0:
        partials[r, cuda.blockIdx.x, _P_V4] = total
    total = block_reduce_sum(shared, rate)
    if t == 0:
        partials[r, cuda.blockIdx.x, _P_RATE] = total
    fastest = block_reduce_extreme(shared, speed, True)
    if t == 0:
        cuda.atomic.max(block_max, r, fastest)
    if record:
        cuda.syncthreads()
        for b in range(t, bins, BLOCK):
            if counts[b] != 0:
                cuda.atomic.add(histogram, (r, b), counts[b])


@device_inline
def _add_snapshot(shared, partials, out, r, interval):
    """The selection's snapshot sums of realization r, times Δ, into ``out[r]``."""
    v2 = _fold(shared, partials, r, _P_V2)
    v4 = _fold(shared, partials, r, _P_V4)
    rate = _fold(shared, partials, r, _P_RATE)
    if cuda.threadIdx.x == 0:
        out[r, _SNAPSHOT[0]] += interval * v2
        out[r, _SNAPSHOT[1]] += interval * v4
        out[r, _SNAPSHOT[2]] += interval * rate


@kernel
def _fold_snapshot(partials, out, plan):
    """One thread block per realization: the block's last selection's snapshot sums."""
    shared = cuda.shared.array(BLOCK, np.float64)
    r = cuda.blockIdx.x
    if np.int64(plan[r, 1]) > 0:
        _add_snapshot(shared, partials, out, r, plan[r, 0])


@kernel
def _settle(first, second, plan):
    """The population of a realization that ran an odd number of intervals this block,
    from ``second`` back to ``first`` (thread (i, r))."""
    i = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    r = cuda.blockIdx.y
    if np.int64(plan[r, 1]) % 2 == 0 or i >= first.shape[2]:
        return
    for k in range(first.shape[1]):
        first[r, k, i] = second[r, k, i]


RESIDENT_MAX_POPULATION = 5_000
"""Largest population run by ``_resident`` (one thread block per realization for the
whole of a block of the run); larger ones run ``_advance``/``_weigh``/``_select``, three
launches per control interval over many thread blocks (four before 2a3fd50, when these
timings were made: the interval's close had a launch of its own). Timed on an H100
(bench cuda ``cloning_speed``, revision 2984f74; hard disks, λ = 1, 32 realizations): the
resident kernel took 0.100 ms an interval at N_c = 10³ against the launches' 0.371 ms,
and 1.04 ms at 10⁴ against 0.651 ms, since its 128 threads run a realization's clones one
after the other (``kinetic.cost.CLONING_GPU_RESIDENT_*``: 6.1 µs a clone and 7.2 µs an
event in one thread). The two cross at about 3300 clones for Δ = 1 and 6100 for
Δ = 0.137 (λ = -1): 5000 between them."""

_RESIDENT_MAX_THREADS = 1024
"""Most threads of a ``_resident`` block: its shared trees are this long (16 KB), whatever
the launch uses."""

RESIDENT_THREADS = BLOCK if simulated() else 256
"""Threads of one realization's block in ``_resident`` (a power of two, at most
``_RESIDENT_MAX_THREADS``; read at each launch, so the bench can compare counts with one
compiled kernel). 256 on a GPU: the H100 run of revision 5836ea7 (``cloning_speed``,
``resident_threads``; the kernel had 144 registers a thread, so at most 384 threads a
block and one block of 256 a multiprocessor against two of 128) timed 256 faster than
128 on every shape it ran: 32 realizations of 10³ clones (Δ = 1) 0.143 s against 0.221,
of 10⁴ clones 0.131 s against 0.212, and the grouped job's shape (41 λ × 32 realizations
of 10³ clones, 1312 blocks in 10 waves instead of 5) 0.91 s against 1.09. The
populations and counts do not depend on it (the scan is exact), μ and the sums only in
the last bits (another summation tree)."""


@device_inline
def _slot(position, n, total, u):
    """g(E) = ceil(N_c E/Q - u), clamped to [0, N_c]: the first slot at or above the
    cumulative fixed-point weight E (``_slots_below`` too). Neighbouring clones compute
    their shared boundary each at its own call site, and the slots tile the population
    only if both round alike: the product comes before the division, so no multiply
    feeds the subtraction and NVVM cannot fuse one site into an FMA and not the other."""
    g = math.ceil((n * float(position)) / total - u)
    return min(n, max(0, g))


RESIDENT_REGISTERS = 128
"""Registers a thread of ``_resident`` may use (``kinetic.gpu.kernel_within``). Left to
itself ptxas gave it 144 (the H100 run of 5836ea7) to 157 (nvJitLink 13.5, sm_90), so a
multiprocessor held one block of 256 threads (65 536 registers); at 128 it spills nothing
(tests/gpu/test_kernels_compile.py links it so) and holds two. In paper.yaml's grouped
jobs of 10³ and 3 × 10³ clones (41 λ × 32 realizations a block each) the blocks wait
for a multiprocessor: ``kinetic.cost`` plans 111 and 106 s of their 115 and 110 s so.
Not yet timed on a GPU; the plan still counts one block a multiprocessor
(``cost.CLONING_GPU_RESIDENT_BLOCKS``)."""


@kernel_within(RESIDENT_REGISTERS)
def _resident(first, second, states, counts, controls, out, observers, run, plan):
    """The control intervals of a block of the run for every clone of realization
    r = blockIdx.x, in one thread block of ``RESIDENT_THREADS`` threads (a power of two up
    to ``_RESIDENT_MAX_THREADS``, read from the launch): advance (clones t, t + threads,
    ...), weigh and
    scan (thread t the contiguous chunk t of the clones), select, the snapshot sums, with
    block barriers between the phases instead of launches. ``plan[r]`` is the
    realization's (interval Δ, number of intervals, λ, record the histogram: 0 or 1), so
    that the realizations of several points (λ) share the launch. The same random
    numbers, collision counts, integer scan and selections as the four-launch path, so the
    same populations; μ and the snapshot sums differ from it in the last bits only (other
    summation order). The population starts and ends in ``first`` (``second`` is
    scratch)."""
    shared = cuda.shared.array(_RESIDENT_MAX_THREADS, np.float64)
    shared_q = cuda.shared.array(_RESIDENT_MAX_THREADS, np.int64)
    counts_shared = cuda.shared.array(MAX_CUDA_HISTOGRAM_BINS, np.int64)
    selection = cuda.shared.array(1, np.float64)
    table, table_step, histogram, half_width = observers
    code, rate_a = run
    t = cuda.threadIdx.x
    threads = cuda.blockDim.x
    r = cuda.blockIdx.x
    interval = plan[r, 0]
    steps = np.int64(plan[r, 1])
    lam = plan[r, 2]
    record = plan[r, 3] != 0.0
    n = states.shape[1]
    d = first.shape[1]
    bins = histogram.shape[1]
    chunk = (n + threads - 1) // threads
    start = min(t * chunk, n)
    stop = min(start + chunk, n)
    if record:
        for b in range(t, bins, threads):
            counts_shared[b] = 0
    cuda.syncthreads()
    for step in range(steps):
        source, target = _buffers(first, second, step)
        collisions = 0
        candidates = 0
        low = _NO_MIN
        high = np.int64(-1)
        for i in range(t, n, threads):
            k, c = _advance_clone(source, states, r, i, code, interval, rate_a)
            counts[r, i] = k
            collisions += k
            candidates += c
            low = min(low, k)
            high = max(high, k)
        low = block_reduce_extreme(shared_q, low, False, threads)
        high = block_reduce_extreme(shared_q, high, True, threads)
        total_collisions = block_reduce_sum(shared, float(collisions), threads)
        total_candidates = block_reduce_sum(shared, float(candidates), threads)
        shift = low if lam >= 0.0 else high
        weights = 0.0
        chunk_q = _ZERO
        for k in range(start, stop):
            w = math.exp(-lam * (counts[r, k] - shift))
            weights += w
            chunk_q += np.int64(w * _FIXED_POINT + 0.5)
        weight = block_reduce_sum(shared, weights, threads)
        prefix, total_q = block_inclusive_scan(shared_q, chunk_q, _ZERO, threads)
        if t == 0:
            out[r, _ELAPSED] += interval
            out[r, _NET] += n * (math.log(weight / n) - lam * shift)
            out[r, _COLLISIONS] += total_collisions
            out[r, _CANDIDATES] += total_candidates
            selection[0] = _selection_uniform(controls, r)
        cuda.syncthreads()
        u = selection[0]
        total = float(total_q)
        running = prefix - chunk_q
        v2_sum = 0.0
        v4_sum = 0.0
        rate_sum = 0.0
        fastest = 0.0
        for k in range(start, stop):
            q = np.int64(math.exp(-lam * (counts[r, k] - shift)) * _FIXED_POINT + 0.5)
            low_slot = 0 if k == 0 else _slot(running, n, total, u)
            running += q
            high_slot = n if k == n - 1 else _slot(running, n, total, u)
            copies = high_slot - low_slot
            if copies > 0:
                v2 = 0.0
                for dim in range(d):
                    value = source[r, dim, k]
                    v2 += value * value
                    for j in range(low_slot, high_slot):
                        target[r, dim, j] = value
                    if record:
                        b = math.floor((value + half_width) * bins / (2.0 * half_width))
                        if 0 <= b < bins:
                            cuda.atomic.add(counts_shared, b, copies)
                speed = math.sqrt(v2)
                fastest = max(fastest, speed)
                rate_sum += copies * _tabulated_rate(speed, table, table_step)
                v4_sum += copies * v2 * v2
                v2_sum += copies * v2
        v2_sum = block_reduce_sum(shared, v2_sum, threads)
        v4_sum = block_reduce_sum(shared, v4_sum, threads)
        rate_sum = block_reduce_sum(shared, rate_sum, threads)
        fastest = block_reduce_extreme(shared, fastest, True, threads)
        if t == 0:
            out[r, _SNAPSHOT[0]] += interval * v2_sum
            out[r, _SNAPSHOT[1]] += interval * v4_sum
            out[r, _SNAPSHOT[2]] += interval * rate_sum
            out[r, _MAX_SPEED] = max(out[r, _MAX_SPEED], fastest)
        cuda.syncthreads()
    if record:
        for b in range(t, bins, threads):
            histogram[r, b] += counts_shared[b]
    if steps % 2:  # the population ended in ``second``: back to ``first``
        for dim in range(d):
            for i in range(t, n, threads):
                first[r, dim, i] = second[r, dim, i]


def _resident_threads() -> int:
    """``RESIDENT_THREADS``, checked (a power of two, at most ``_RESIDENT_MAX_THREADS``)."""
    threads = int(RESIDENT_THREADS)
    if threads < 1 or threads & (threads - 1) or threads > _RESIDENT_MAX_THREADS:
        raise ValueError(
            f"RESIDENT_THREADS must be a power of two up to {_RESIDENT_MAX_THREADS}, got {threads}"
        )
    return threads


def run(p, durations, n_transient, rows, progress):
    """Run every realization of ``rows`` (one ``stream_states`` row each) at once.

    ``p`` are the validated parameters of ``kinetic.cloning.simulate``, ``durations`` the
    block durations (the first ``n_transient`` discarded); each block is cut into whole
    control intervals of at most ``p["control_interval"]``. Returns ``(blocks, histograms,
    distinct, seconds)`` shaped as the CPU engine's: per-block sums (realization, block,
    field), velocity-component densities, distinct final velocities per realization and
    the wall time per realization (the run's wall time shared equally).
    """
    return run_points([(p, durations, n_transient, rows)], progress)[0]


def run_points(points, progress):
    """``run`` for several points at once: ``points`` is a list of ``(p, durations,
    n_transient, rows)`` of one kernel, dimension, population and histogram (the λ, the
    control interval, the transient and the rows may differ). Every realization of every
    point shares the same launches: up to ``RESIDENT_MAX_POPULATION`` clones as one thread
    block of ``_resident``, above as the rows of the three launches per interval. A point's
    numbers are those it gets alone. Returns ``run``'s tuple for each point; the wall time
    is shared equally among all the realizations."""
    if not simulated():
        warm("cuda_cloning", "cloning", _compile_kernels)
    started = time.perf_counter()
    resident = points[0][0]["population"] <= RESIDENT_MAX_POPULATION
    results = _run_together(points, progress, resident)
    realizations = sum(point[3].shape[0] for point in points)
    seconds = (time.perf_counter() - started) / realizations
    out = []
    for (_, _, _, rows), (blocks, densities, final) in zip(points, results, strict=True):
        count = rows.shape[0]
        distinct = np.array([np.unique(final[r, 0]).size for r in range(count)], dtype=float)
        out.append((blocks, densities, distinct, np.full(count, seconds)))
    return out


def _compile_kernels() -> None:
    """Both paths on 4 clones of two realizations and two blocks: every kernel, with the
    production types. With one realization and one block the views of ``blocks`` and
    ``out`` were contiguous ('C' layout) where a production run's are strided ('A'): each
    kernel then compiled a second time inside the run's timer and outside ``warm``'s lock
    (numba issue 4807)."""
    tiny = {
        "population": 4,
        "dimension": 2,
        "lam": 0.5,
        "kernel": "hard_spheres",
        "histogram_bins": 8,
        "histogram_half_width": 6.0,
        "control_interval": 1.0,
    }
    rows = np.array([[1, 2, 3, 4], [5, 6, 7, 8]], dtype=np.uint64)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NumbaPerformanceWarning)  # grids of one block
        for resident in (True, False):
            _run(tiny, np.array([1.0, 1.0]), 0, rows, None, resident=resident)


class _Clones:
    """Device state of the realizations ``rows`` of N_c clones: the population (two
    buffers), the clones' streams, collision counts, the selection streams, the histogram
    and the per-block sums of ``n_blocks`` blocks."""

    def __init__(self, p, rows, n_blocks):
        from kinetic.cloning.rates import TABLE_STEP, rate_table

        count, n, d = rows.shape[0], p["population"], p["dimension"]
        self.count, self.n, self.d = count, n, d
        self.velocity = [cuda.device_array((count, d, n)), cuda.device_array((count, d, n))]
        self.states = cuda.device_array((count, n, 4), dtype=np.uint64)
        _seed[(grid(n), count), BLOCK](self.states, self.velocity[0], to_device(rows))
        self.controls = to_device(np.concatenate([rows, np.zeros((count, 1), np.uint64)], axis=1))
        self.counts = cuda.device_array((count, n), dtype=np.int64)
        self.histogram = to_device(np.zeros((count, p["histogram_bins"]), dtype=np.int64))
        self.blocks = to_device(np.zeros((count, n_blocks, len(kernels.BLOCK_FIELDS))))
        self.table = to_device(rate_table(p["kernel"], d))
        self.table_step = TABLE_STEP
        self.code = kernels.HARD_SPHERES if p["kernel"] == "hard_spheres" else kernels.MAXWELL
        self.rate_a = kernels.channel_a_rate(d)

    def results(self, points, snapshots, sizes):
        """For each point (``points``: its parameters and block durations, in the order of
        the rows, ``sizes`` realizations each): the blocks' sums, the velocity densities
        over its ``snapshots`` selections and the final velocities (one copy from the GPU
        for all the points)."""
        sums = self.blocks.copy_to_host()
        sums[:, :, _FIELD["collision_events"]] = sums[:, :, _COLLISIONS]
        sums[:, :, _FIELD["proposals"]] = sums[:, :, _CANDIDATES]
        histogram = self.histogram.copy_to_host()
        final = self.velocity[0].copy_to_host()
        first = np.concatenate([[0], np.cumsum(sizes)])
        out = []
        for j, (p, durations) in enumerate(points):
            rows = slice(first[j], first[j + 1])
            bin_width = 2.0 * p["histogram_half_width"] / p["histogram_bins"]
            scale = max(snapshots[j], 1) * self.d * self.n * bin_width
            out.append((sums[rows, : len(durations)], histogram[rows] / scale, final[rows]))
        return out


def _intervals(p, duration):
    """The whole control intervals of a block of the run: (their length, how many)."""
    steps = max(1, math.ceil(duration / p["control_interval"] - 1e-9))
    return duration / steps, steps


def _run(p, durations, n_transient, rows, progress, resident=None):
    """One point without the compilation step: the blocks' sums, the velocity densities
    and the final velocities; ``resident`` forces a path (default: by the population)."""
    if resident is None:
        resident = p["population"] <= RESIDENT_MAX_POPULATION
    return _run_together([(p, durations, n_transient, rows)], progress, resident)[0]


def _run_together(points, progress, resident):
    """The points' realizations in the same launches, block of the run after block: one
    ``_resident`` launch per block, or (``resident`` false) the three launches of each of
    the block's intervals (``_launched_intervals``). A point whose run has fewer blocks,
    or whose block has fewer intervals, idles through the rest."""
    rows = np.concatenate([point[3] for point in points])
    sizes = [point[3].shape[0] for point in points]
    owner = np.repeat(np.arange(len(points)), sizes)
    n_blocks = max(len(point[1]) for point in points)
    clones = _Clones(points[0][0], rows, n_blocks)
    snapshots = np.zeros(len(points), dtype=np.int64)
    observers = (
        clones.table,
        clones.table_step,
        clones.histogram,
        points[0][0]["histogram_half_width"],
    )
    run = (clones.code, clones.rate_a)
    if not resident:
        advance = _launched_intervals(clones)
    for b in range(n_blocks):
        plan = np.zeros((clones.count, 4))
        simulated_time = 0.0
        for j, (p, durations, n_transient, _) in enumerate(points):
            if b < len(durations):
                interval, steps = _intervals(p, durations[b])
                record = b >= n_transient
                snapshots[j] += steps if record else 0
                plan[owner == j] = (interval, steps, p["lam"], float(record))
                simulated_time += sizes[j] * durations[b]
        if resident:
            _resident[clones.count, _resident_threads()](
                clones.velocity[0],
                clones.velocity[1],
                clones.states,
                clones.counts,
                clones.controls,
                clones.blocks[:, b, :],
                observers,
                run,
                to_device(plan),
            )
        else:
            advance(clones.blocks[:, b, :], observers, run, plan)
        cuda.synchronize()
        if progress is not None:
            progress.update(simulated_time)
    return clones.results([(p, durations) for p, durations, _, _ in points], snapshots, sizes)


def _launched_intervals(clones):
    """Control intervals by three launches each over ``grid(N_c)`` thread blocks per
    realization (``_advance``, ``_weigh`` with ``_close``, ``_select``): returns
    ``advance(out, observers, run, plan)``, which runs the intervals of one block of the
    run (``plan``: each realization's Δ, intervals, λ and record flag) and leaves every
    population in ``clones.velocity[0]``."""
    count, n = clones.count, clones.n
    first, second = clones.velocity
    states, counts, controls = clones.states, clones.counts, clones.controls
    launch = ((grid(n), count), BLOCK)
    extremes = to_device(np.tile(np.array([_NO_MIN, -1, n, 0], dtype=np.int64), (count, 1)))
    cumulative = cuda.device_array((count, n), dtype=np.int64)
    block_sums = cuda.device_array((count, grid(n)), dtype=np.int64)
    partials = to_device(np.zeros((count, grid(n), 6)))
    done = to_device(np.zeros(count, dtype=np.int64))  # ``_weigh``'s tickets
    fold, settle = _fold_snapshot[count, BLOCK], _settle[launch]

    def kernels(rows):
        """The three kernels configured for ``rows`` realizations (configured at each
        launch: the simulator's configured kernels share one launch shape)."""
        over = ((grid(n), rows), BLOCK)
        return _advance[over], _weigh[over], _select[over]

    def advance(out, observers, run, plan):
        table, table_step, histogram, half_width = observers
        observers = (table, table_step, histogram, half_width, out[:, _MAX_SPEED])
        steps = plan[:, 1].astype(np.int64)
        order = np.argsort(-steps, kind="stable")  # the realizations with the most first
        # the realizations that run interval k: the first rows[k] of ``order``
        rows = count - np.searchsorted(np.sort(steps), np.arange(steps.max()), side="right")
        device_plan, device_order = to_device(plan), to_device(order.astype(np.int64))
        for step in range(int(steps.max())):
            launch_advance, weigh, select = kernels(int(rows[step]))
            launch_advance(
                first,
                second,
                states,
                counts,
                extremes,
                partials,
                run,
                device_plan,
                device_order,
                step,
            )
            # closes the interval too, where the previous selection's snapshot is folded
            # (the last one by ``fold``)
            weigh(
                counts,
                extremes,
                cumulative,
                block_sums,
                partials,
                controls,
                out,
                done,
                device_plan,
                device_order,
                step,
            )
            select(
                first,
                second,
                cumulative,
                block_sums,
                extremes,
                controls,
                partials,
                observers,
                device_plan,
                device_order,
                step,
            )
        fold(partials, out, device_plan)
        settle(first, second, device_plan)

    return advance
