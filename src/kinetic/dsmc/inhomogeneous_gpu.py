"""CUDA backend of the inhomogeneous DSMC engine (costantini2010):
``simulate_cooling_modes(backend="cuda")``.

All realizations of a call advance together on one GPU: realization r is row r of
``(R, 2, N_sim)`` arrays (each row a struct of arrays, double-buffered by swapping two
device arrays) and of ``(R, M², ·)`` per-cell arrays; every kernel covers
all realizations. The realizations may belong to several runs that share N, density, Λ,
cells, time step and rule (``inhomogeneous.SHARED_SETTINGS``; ``run_points``, behind
``simulate_cooling_modes_points``: the runs of several α): what depends on α (the drag's
free flight and growth, (1 + α)/2, the energy lost) is a row parameter (``rows``), and the
runs, longest first, keep step together; a run that is done sits in the last rows, which
every kernel then leaves out (the first ``count`` rows are advanced and observed).

One step is five phases, each written once as a device function of one
realization, particle or cell (``_centre_row``, ``_stream_particle``, ``_scan_row``,
``_scatter_particle``, ``_collide_in_cell``), run either by one cooperative launch for all
the steps between two samples (``_advance_together``: the phases in turn, each a loop of
the whole grid, with a grid-wide barrier between them; the default where the GPU allows
it, ``TOGETHER``) or by one launch per phase (the realization is the grid's y index):

1. ``_centre`` (one block per realization): the centre-of-mass velocity u of the
   previous step, Σ_c of the cells' Σw (``moments[:, :, :2]``) by a fixed tree over the
   cells (strided sums, then ``kinetic.gpu.block_reduce_sum``), divided by N_sim; and
   the cell counts zeroed. As on the CPU, u is the velocity before the previous step's
   collisions (which conserve momentum) and is removed in the streaming of this step.
2. ``_stream`` (threads over particles): ``kernels._streamed``, the CPU engine's free
   flight with drag and periodic wrap and the particle's cell, and w -> (w - u) e^{ω0 Δτ}
   in place; each particle adds one to its cell's count (an integer atomic).
3. ``_scan`` (one block per realization): the exclusive prefix sum of the counts over
   the cells in index order (``kinetic.gpu.block_exclusive_scan``, exact in integers):
   ``cell_start``, the cells' ranges.
4. ``_scatter`` (threads over particles): each particle takes a slot of its cell's range
   by an integer atomic on the cell's fill pointer and writes its index there
   (``order``). The slots a cell's particles get depend on the order in which the
   atomics land, which the GPU does not fix.
5. ``_collide`` (a group of ``CELL_THREADS`` threads per cell: a warp on a GPU): the
   group ranks its cell's slice of ``order`` by particle index (each index compared with
   every other: the slice's sorted order is then exactly a stable counting sort's,
   whatever order the atomics landed in), copies its particles into the other buffer in
   that order, folds the cell's moments (``kernels._accumulated``: Σw, Σ|w|², two largest
   |w|², a fixed tree over the group) and its first thread runs
   ``kernels._collide_cell``, the CPU engine's per-cell collision code ("paper" or
   "majorant" rule, Λ, restitution, recollision tally), with the cell's own xoshiro256+
   stream (``kinetic.rng.thread_state`` of the realization's row after its initial
   state, and the cell index), its carried fraction and its tallies.

Cost of the sort: a cell of n particles takes ⌈n/32⌉² rounds of 32 comparisons a thread,
the warp's threads side by side. Until revision 5836ea7 one thread per cell sorted its
slice by insertion, which the atomics' order made a chain of about n²/4 dependent memory
accesses: at costantini2010's 60 particles a cell that phase took 1.54 of the step's
1.72 ms on an H100 (bench cuda ``inhomogeneous_bound``, 3 × 10⁶ particles), 5.4 × 10⁻¹⁰
s a particle against 0.6 × 10⁻¹⁰ for the streaming.

Sampled steps add two launches: ``_observe`` (per-block sums of the 8 particle sums of
``kernels.observe``, a fixed tree per block) and ``_finish`` (one block per realization:
the blocks summed in index order by one thread, ``kernels._observables`` for the row, and
the energy lost in collisions since the previous sample, summed over the cells by a fixed
tree and reset).

Determinism: the same call gives the same numbers twice (on one GPU model), on either
path. Every float sum has a fixed order (above: per realization, whatever the grid); the
only atomics are integer counts and fill pointers, and the per-cell sort removes the order
they land in. A realization's numbers do not depend
on the other realizations of the batch (the number of blocks over particles depends on
N_sim only). Not bit-identical with the CPU engine, which draws every cell's collisions
from one stream per realization: the two agree statistically
(tests/gpu/test_dsmc_inhomogeneous_cuda.py). The initial states are the CPU engine's
(``initial_particles`` of each realization's stream row).
"""

from __future__ import annotations

import time
import warnings

import numpy as np
from numba.core.errors import NumbaPerformanceWarning

from kinetic import rng
from kinetic.backends import simulated
from kinetic.dsmc import inhomogeneous_kernels as kernels
from kinetic.dsmc.gpu import THREADS, _block_sums, blocks_per_realization
from kinetic.dsmc.inhomogeneous import CoolingModesSettings, initial_particles
from kinetic.fourier import mode_terms
from kinetic.gpu import (
    BLOCK,
    block_exclusive_scan,
    block_reduce_sum,
    cuda,
    device_function,
    device_inline,
    device_zeros,
    first_pair,
    grid,
    kernel,
    next_pair,
    synchronize,
    to_device,
    warm,
)
from kinetic.progress import logger

__all__ = ["N_SUMS", "run_points"]

N_SUMS = 8
"""Particle sums of an observation: Σw_x, Σw_y, the four mode terms, Σw_x², Σw_y²."""

# per-cell tallies
_CANDIDATES, _COLLISIONS, _REPEATED, _EXCEEDED = 0, 1, 2, 3
_N_TALLIES = 4

# per-row parameters (``rows[r]``): the ones that depend on α, so that the runs of several
# α share a batch
_SHIFT, _GROWTH, _HALF, _LOSS = 0, 1, 2, 3
"""Columns of ``rows``: the free flight's (e^{ω0 Δτ} - 1)/ω0, the drag's growth e^{ω0
Δτ}, the collision's (1 + α)/2, and the energy lost per unit of ``lost``, (1 - α²)/4."""
_N_ROW_PARAMETERS = 4

_SPREAD_BLOCKS = 1 if simulated() else 2048
"""Most thread blocks per realization of the streaming and the scatter, which reduce no
floats (their grid may change without changing a number): a single realization of 3 x
10⁶ particles fills the GPU. The observer keeps the homogeneous engine's
``blocks_per_realization`` (its partial sums need a grid that depends on N_sim only)."""

CELL_THREADS = BLOCK if simulated() else 32
"""Threads that share a cell in the collision phase: a warp on a GPU (its barrier is
``cuda.syncwarp``); the whole block under the simulator, which has no warp barrier."""

_CELLS_PER_BLOCK = BLOCK // CELL_THREADS
"""Cells a thread block works on at once, one per group of ``CELL_THREADS``."""

_NO_KEY = np.int64(2**62)
"""A sort key above every particle index: the empty slots of a group's last round."""


def _cell_barrier():
    """Barrier of the threads that share a cell (``CELL_THREADS``), with the ordering of
    their shared and global memory."""
    if CELL_THREADS == BLOCK:
        cuda.syncthreads()
    else:
        cuda.syncwarp()


_cell_barrier = device_inline(_cell_barrier)

_collide_cell = device_function(kernels._collide_cell)
_accumulated = device_function(kernels._accumulated)
_streamed = device_function(kernels._streamed)
_observables = device_function(kernels._observables)
_thread_state = device_function(rng.thread_state)


@kernel
def _seed(keys, states):
    """``states[r, c] = thread_state(keys[r], c)``: one stream per cell."""
    c = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    r = cuda.blockIdx.y
    if c >= states.shape[1]:
        return
    s0, s1, s2, s3 = _thread_state(keys[r, 0], keys[r, 1], keys[r, 2], keys[r, 3], c)
    states[r, c, 0] = s0
    states[r, c, 1] = s1
    states[r, c, 2] = s2
    states[r, c, 3] = s3


# ------------------------------------------------------------- the phases of a step
# Each phase is written once, as an inline device function of one realization (block
# phases: every thread of the block calls it) or of one particle or cell; the launched
# kernels and the cooperative kernel (_advance_together) are loops over them.


def _centre_row(moments, u, cell_start, inverse_n, shared, r):
    """Block phase: ``u[r]`` = Σ_c moments[r, c, :2] / N_sim (fixed tree), and
    ``cell_start[r]`` zeroed (the counts of the coming sort)."""
    t = cuda.threadIdx.x
    n_cells = moments.shape[1]
    sum0 = 0.0
    sum1 = 0.0
    for c in range(t, n_cells, BLOCK):
        sum0 += moments[r, c, 0]
        sum1 += moments[r, c, 1]
    for c in range(t, n_cells + 1, BLOCK):
        cell_start[r, c] = 0
    sum0 = block_reduce_sum(shared, sum0)
    sum1 = block_reduce_sum(shared, sum1)
    if t == 0:
        u[r, 0] = sum0 * inverse_n
        u[r, 1] = sum1 * inverse_n


_centre_row = device_inline(_centre_row)


def _stream_particle(position, velocity, cell_of, cell_start, u, rows, arguments, r, i):
    """Particle phase: the free flight with drag of particle i (``kernels._streamed``, in
    place), its velocity (w - u) e^{ω0 Δτ} (in place), its cell, and one more in the
    cell's count (an integer atomic on ``cell_start[r, c]``); ``arguments`` is (box side,
    cells per unit length, cells per side), ``rows[r]`` the row's drag (``_SHIFT``,
    ``_GROWTH``)."""
    box_side, inverse_cell, m = arguments
    shift = rows[r, _SHIFT]
    growth = rows[r, _GROWTH]
    w0 = velocity[r, 0, i] - u[r, 0]
    w1 = velocity[r, 1, i] - u[r, 1]
    x, y, c = _streamed(
        position[r, 0, i], position[r, 1, i], w0, w1, shift, box_side, inverse_cell, m
    )
    position[r, 0, i] = x
    position[r, 1, i] = y
    velocity[r, 0, i] = w0 * growth
    velocity[r, 1, i] = w1 * growth
    cell_of[r, i] = c
    cuda.atomic.add(cell_start, (r, c), 1)


_stream_particle = device_inline(_stream_particle)


def _scan_row(cell_start, fill, shared, r):
    """Block phase: ``cell_start[r]`` = exclusive prefix sums of the counts
    (``cell_start[r, M²]`` = N_sim), and the fill pointers ``fill[r] = cell_start[r, :M²]``."""
    n_cells = fill.shape[1]
    total = block_exclusive_scan(shared, cell_start[r], n_cells, np.int64(0))
    if cuda.threadIdx.x == 0:
        cell_start[r, n_cells] = total
    for c in range(cuda.threadIdx.x, n_cells, BLOCK):
        fill[r, c] = cell_start[r, c]


_scan_row = device_inline(_scan_row)


def _scatter_particle(cell_of, fill, order, r, i):
    """Particle phase: particle i takes a slot of its cell's range (integer atomic on the
    cell's fill pointer) and writes its index there."""
    p = cuda.atomic.add(fill, (r, cell_of[r, i]), 1)
    order[r, p] = i


_scatter_particle = device_inline(_scatter_particle)


def _collide_in_cell(source, target, order, cell_start, cells, rows, step, r, c, keys, sums):
    """Cell phase of cell c, by the ``CELL_THREADS`` threads of a group (every one calls
    it with the same r and c; ``keys`` (CELL_THREADS,) int64 and ``sums``
    (CELL_THREADS, 5) float64 are the group's shared scratch):

    1. each particle of the cell's slice of ``order`` gets its rank among the slice's
       particle indices (the group compares it with every index of the slice, a round of
       ``CELL_THREADS`` indices at a time through ``keys``): the slice sorted by index,
       the CPU's stable counting-sort order, whatever order the scatter's atomics landed
       in;
    2. each thread copies its particles from the ``source`` buffers (position, velocity,
       labels) into slot ``first + rank`` of the ``target`` buffers (the loads of the
       group's particles in flight together);
    3. thread k accumulates the cell's moments over slots k, k + CELL_THREADS, ... of the
       sorted cell (``kernels._accumulated``: Σw, Σ|w|², two largest |w|²) and the group
       folds them by a fixed tree (the sums' rounding then differs from the CPU's one
       loop; the two largest are exact);
    4. its first thread runs ``kernels._collide_cell``, the CPU engine's per-cell
       collisions, with the cell's stream, carry, tallies and lost energy.

    ``cells`` is (moments, carry, states, tally, lost); ``step`` is (rule, density per
    count, pair coefficient, time step), ``rows[r, _HALF]`` the row's (1 + α)/2. The
    slice of ``order`` is left as the scatter wrote it (no later phase reads it)."""
    moments, carry, states, tally, lost = cells
    rule, density_per_count, pair_coefficient, time_step = step
    _, velocity_to, labels_to = target
    lane = cuda.threadIdx.x % CELL_THREADS
    first = cell_start[r, c]
    count = cell_start[r, c + 1] - first
    for base in range(0, count, CELL_THREADS):
        key = order[r, first + base + lane] if base + lane < count else _NO_KEY
        rank = 0
        for other in range(0, count, CELL_THREADS):
            _cell_barrier()  # the group has compared with the previous round's keys
            keys[lane] = order[r, first + other + lane] if other + lane < count else _NO_KEY
            _cell_barrier()
            for k in range(min(CELL_THREADS, count - other)):
                if keys[k] < key:
                    rank += 1
        if key != _NO_KEY:
            x, y, wx, wy, ident, partner = _particle(source, r, key)
            _copy_particle(target, r, first + rank, x, y, wx, wy, ident, partner)
    _cell_barrier()  # the group's copies visible to the group
    m0 = 0.0
    m1 = 0.0
    m2 = 0.0
    m3 = 0.0
    m4 = 0.0
    for p in range(first + lane, first + count, CELL_THREADS):
        m0, m1, m2, m3, m4 = _accumulated(
            m0, m1, m2, m3, m4, velocity_to[r, 0, p], velocity_to[r, 1, p]
        )
    sums[lane, 0] = m0
    sums[lane, 1] = m1
    sums[lane, 2] = m2
    sums[lane, 3] = m3
    sums[lane, 4] = m4
    stride = CELL_THREADS // 2
    while stride > 0:
        _cell_barrier()
        if lane < stride:
            for f in range(3):
                sums[lane, f] += sums[lane + stride, f]
            a3 = sums[lane, 3]
            b3 = sums[lane + stride, 3]
            sums[lane, 4] = max(min(a3, b3), max(sums[lane, 4], sums[lane + stride, 4]))
            sums[lane, 3] = max(a3, b3)
        stride //= 2
    if lane != 0:
        return
    cell_moments = moments[r]
    for f in range(5):
        cell_moments[c, f] = sums[0, f]
    if count < 2:
        return
    state = states[r, c]
    counts = tally[r, c]
    candidates, collisions, repeated, exceeded, hh, s0, s1, s2, s3 = _collide_cell(
        velocity_to[r],
        labels_to[r, 0],
        labels_to[r, 1],
        first,
        first + count,
        cell_moments,
        c,
        carry[r],
        rule,
        rows[r, _HALF],
        density_per_count,
        pair_coefficient,
        time_step,
        counts[_CANDIDATES],
        counts[_COLLISIONS],
        counts[_REPEATED],
        counts[_EXCEEDED],
        lost[r, c],
        state[0],
        state[1],
        state[2],
        state[3],
    )
    counts[_CANDIDATES] = candidates
    counts[_COLLISIONS] = collisions
    counts[_REPEATED] = repeated
    counts[_EXCEEDED] = exceeded
    lost[r, c] = hh
    state[0] = s0
    state[1] = s1
    state[2] = s2
    state[3] = s3


_collide_in_cell = device_inline(_collide_in_cell)


def _particle(source, r, i):
    """Particle i of realization r of the ``source`` buffers: ``(x, y, w_x, w_y, ident,
    partner)``."""
    position, velocity, labels = source
    return (
        position[r, 0, i],
        position[r, 1, i],
        velocity[r, 0, i],
        velocity[r, 1, i],
        labels[r, 0, i],
        labels[r, 1, i],
    )


_particle = device_inline(_particle)


def _copy_particle(target, r, p, x, y, wx, wy, ident, partner):
    """Slot p of realization r of the ``target`` buffers (position, velocity, labels)."""
    position_to, velocity_to, labels_to = target
    position_to[r, 0, p] = x
    position_to[r, 1, p] = y
    velocity_to[r, 0, p] = wx
    velocity_to[r, 1, p] = wy
    labels_to[r, 0, p] = ident
    labels_to[r, 1, p] = partner


_copy_particle = device_inline(_copy_particle)


# ------------------------------------------------------------ one launch per phase


@kernel
def _centre(moments, u, cell_start, inverse_n):
    """One block per realization: ``_centre_row``."""
    shared = cuda.shared.array(BLOCK, np.float64)
    _centre_row(moments, u, cell_start, inverse_n, shared, cuda.blockIdx.x)


@kernel
def _stream(position, velocity, cell_of, cell_start, u, rows, arguments):
    """Threads over the particles of realization ``blockIdx.y``: ``_stream_particle``."""
    r = cuda.blockIdx.y
    n = position.shape[2]
    for i in range(cuda.blockIdx.x * THREADS + cuda.threadIdx.x, n, cuda.gridDim.x * THREADS):
        _stream_particle(position, velocity, cell_of, cell_start, u, rows, arguments, r, i)


@kernel
def _scan(cell_start, fill):
    """One block per realization: ``_scan_row``."""
    shared = cuda.shared.array(BLOCK, np.int64)
    _scan_row(cell_start, fill, shared, cuda.blockIdx.x)


@kernel
def _scatter(cell_of, fill, order):
    """Threads over the particles of realization ``blockIdx.y``: ``_scatter_particle``."""
    r = cuda.blockIdx.y
    n = cell_of.shape[1]
    for i in range(cuda.blockIdx.x * THREADS + cuda.threadIdx.x, n, cuda.gridDim.x * THREADS):
        _scatter_particle(cell_of, fill, order, r, i)


@kernel
def _collide(source, target, order, cell_start, cells, rows, step):
    """A group of ``CELL_THREADS`` threads per cell c of realization ``blockIdx.y``
    (``_CELLS_PER_BLOCK`` cells a block): ``_collide_in_cell``."""
    keys = cuda.shared.array((_CELLS_PER_BLOCK, CELL_THREADS), np.int64)
    sums = cuda.shared.array((_CELLS_PER_BLOCK, CELL_THREADS, 5), np.float64)
    group = cuda.threadIdx.x // CELL_THREADS
    c = cuda.blockIdx.x * _CELLS_PER_BLOCK + group
    if c < cell_start.shape[1] - 1:
        r = cuda.blockIdx.y
        _collide_in_cell(
            source, target, order, cell_start, cells, rows, step, r, c, keys[group], sums[group]
        )


# ----------------------------------------------------- every phase in one launch


def _step_together(source, target, work, cells, u, rows, stream, step, inverse_n, count, shared):
    """One step of ``_advance_together`` from the ``source`` buffers to the ``target``
    ones (inlined once for each direction, so that neither the buffers nor their shapes
    are chosen at run time: the kernel's arrays stay its parameters)."""
    cell_of, order, cell_start, fill = work
    sums, counts, keys, cell_sums = shared
    grid_group = cuda.cg.this_grid()
    group = cuda.threadIdx.x // CELL_THREADS
    block = cuda.blockIdx.x
    blocks = cuda.gridDim.x
    thread = block * BLOCK + cuda.threadIdx.x
    threads = blocks * BLOCK
    n = cell_of.shape[1]
    n_cells = fill.shape[1]
    for r in range(block, count, blocks):
        _centre_row(cells[0], u, cell_start, inverse_n, sums, r)
    grid_group.sync()
    r, i, dr, di = first_pair(thread, n, threads)  # k = r n + i, no division a step
    while r < count:
        _stream_particle(source[0], source[1], cell_of, cell_start, u, rows, stream, r, i)
        r, i = next_pair(r, i, dr, di, n)
    grid_group.sync()
    for r in range(block, count, blocks):
        _scan_row(cell_start, fill, counts, r)
    grid_group.sync()
    r, i, dr, di = first_pair(thread, n, threads)
    while r < count:
        _scatter_particle(cell_of, fill, order, r, i)
        r, i = next_pair(r, i, dr, di, n)
    grid_group.sync()
    worker = block * _CELLS_PER_BLOCK + group  # a group of CELL_THREADS per cell
    r, c, dr, dc = first_pair(worker, n_cells, blocks * _CELLS_PER_BLOCK)
    while r < count:
        _collide_in_cell(
            source,
            target,
            order,
            cell_start,
            cells,
            rows,
            step,
            r,
            c,
            keys[group],
            cell_sums[group],
        )
        r, c = next_pair(r, c, dr, dc, n_cells)
    grid_group.sync()


_step_together = device_inline(_step_together)


@kernel
def _advance_together(first, second, work, cells, u, rows, stream, step, inverse_n, plan):
    """``plan`` = (steps, rows) whole steps of the first ``rows`` realizations in one
    cooperative launch: the five phases of a step in order, each a loop of the grid over
    its realizations, particles or cells, separated by grid-wide barriers
    (``cuda.cg.this_grid().sync()``: every block resident at once). Step s reads the
    ``first`` buffers and writes the ``second`` when s is even, the other way round when
    odd. ``work`` is (cell_of, order, cell_start, fill). The phases are the launched
    kernels' own functions, so the numbers are theirs bit for bit."""
    shared = (
        cuda.shared.array(BLOCK, np.float64),
        cuda.shared.array(BLOCK, np.int64),
        cuda.shared.array((_CELLS_PER_BLOCK, CELL_THREADS), np.int64),
        cuda.shared.array((_CELLS_PER_BLOCK, CELL_THREADS, 5), np.float64),
    )
    n_steps, count = plan
    for s in range(n_steps):
        if s % 2 == 0:
            _step_together(
                first, second, work, cells, u, rows, stream, step, inverse_n, count, shared
            )
        else:
            _step_together(
                second, first, work, cells, u, rows, stream, step, inverse_n, count, shared
            )


@kernel
def _observe(position, velocity, partials, wavenumber):
    """Per-block sums ``partials[r, b]`` of Σw_x, Σw_y, Σw_y cos(kx), Σw_y sin(kx),
    Σw_x cos(ky), Σw_x sin(ky), Σw_x², Σw_y² (each thread a fixed strided set of
    particles, then a fixed tree); the Fourier factors are the CPU observer's
    (``kinetic.fourier.mode_terms``)."""
    shared = cuda.shared.array((THREADS, N_SUMS), np.float64)
    sums = cuda.local.array(N_SUMS, np.float64)
    r = cuda.blockIdx.y
    b = cuda.blockIdx.x
    n = position.shape[2]
    turns = wavenumber / (2.0 * np.pi)  # k x in turns: x / L
    for f in range(N_SUMS):
        sums[f] = 0.0
    for i in range(b * THREADS + cuda.threadIdx.x, n, cuda.gridDim.x * THREADS):
        wx = velocity[r, 0, i]
        wy = velocity[r, 1, i]
        terms = mode_terms(turns * position[r, 0, i], turns * position[r, 1, i], wx, wy)
        sums[0] += wx
        sums[1] += wy
        sums[2] += terms[0]
        sums[3] += terms[1]
        sums[4] += terms[2]
        sums[5] += terms[3]
        sums[6] += wx * wx
        sums[7] += wy * wy
    _block_sums(shared, sums, partials[r, b])


@kernel
def _finish(partials, n_blocks, lost, rows, n, observables, dissipated, sample):
    """One block per realization: ``observables[r, sample]`` (``kernels._observables`` of
    the block sums, folded in index order) and ``dissipated[r, sample]`` = rows[r, _LOSS]
    Σ_c lost[r, c] / N_sim (a fixed tree over the cells), the cells' ``lost`` reset."""
    shared = cuda.shared.array(BLOCK, np.float64)
    r = cuda.blockIdx.x
    t = cuda.threadIdx.x
    total = 0.0
    for c in range(t, lost.shape[1], BLOCK):
        total += lost[r, c]
        lost[r, c] = 0.0
    total = block_reduce_sum(shared, total)
    if t != 0:
        return
    dissipated[r, sample] = rows[r, _LOSS] * total / n
    px = 0.0
    py = 0.0
    re_y = 0.0
    im_y = 0.0
    re_x = 0.0
    im_x = 0.0
    sum_xx = 0.0
    sum_yy = 0.0
    for b in range(n_blocks):
        px += partials[r, b, 0]
        py += partials[r, b, 1]
        re_y += partials[r, b, 2]
        im_y += partials[r, b, 3]
        re_x += partials[r, b, 4]
        im_x += partials[r, b, 5]
        sum_xx += partials[r, b, 6]
        sum_yy += partials[r, b, 7]
    _observables(n, px, py, re_y, im_y, re_x, im_x, sum_xx, sum_yy, observables[r, sample])


# ------------------------------------------------------------------------------ host


TOGETHER = True
"""Run the steps between two samples in one cooperative launch (``_advance_together``)
where the GPU allows it; False: five launches a step (``python -m kinetic.bench cuda``
times both). The numbers are the same either way."""


def _cooperative_blocks(batch) -> int:
    """Thread blocks of ``_advance_together``'s grid for ``batch``: as many as the GPU
    keeps resident at once, and no more than its largest phase has work for; one under the
    simulator (whose grid barrier is a block barrier). 0 where the kernel cannot be
    compiled or launched cooperatively (a toolkit without libcudadevrt, say): the batch
    then launches each phase (the same numbers)."""
    if simulated():
        return 1
    needed = grid(batch.count * max(batch.n, batch.n_cells * CELL_THREADS))
    try:
        _advance_together[1, BLOCK](*batch.together_arguments(0, 0))  # compiles; does nothing
        resident = min(
            compiled.max_cooperative_grid_blocks(BLOCK)
            for compiled in _advance_together.overloads.values()
        )
    except Exception as error:  # any failure leaves the launched path
        logger.warning("one launch per phase: no cooperative launch on this GPU (%s)", error)
        return 0
    return max(1, min(resident, needed))


def _row_parameters(settings) -> list[float]:
    """``rows[r]`` of a realization of ``settings`` (``_SHIFT``, ``_GROWTH``, ``_HALF``,
    ``_LOSS``)."""
    s = settings
    row = [0.0] * _N_ROW_PARAMETERS
    rate = s.drag_rate
    row[_SHIFT] = float(np.expm1(rate * s.time_step) / rate) if rate != 0.0 else s.time_step
    row[_GROWTH] = float(np.exp(rate * s.time_step))
    row[_HALF] = 0.5 * (1.0 + s.step().restitution)
    row[_LOSS] = 0.25 * (1.0 - s.restitution * s.restitution)
    return row


class _Batch:
    """Device state of the realizations of one or several runs that share
    ``SHARED_SETTINGS``
    (``points``: (settings, streams) pairs, row after row), and the launches of a step.
    ``advance`` and ``observe`` act on the first ``count`` rows: a run that ends before
    the others sits in the last rows and idles once it is done."""

    def __init__(self, points, n_samples: int):
        settings = points[0][0]  # the front checked that the runs share SHARED_SETTINGS
        n = settings.n_simulated
        n_cells = settings.cells_per_side**2
        count = sum(streams.shape[0] for _, streams in points)
        position = np.empty((count, 2, n))
        velocity = np.empty((count, 2, n))
        labels = np.empty((count, 2, n), dtype=np.int64)
        keys = np.empty((count, 4), dtype=np.uint64)
        rows = np.empty((count, _N_ROW_PARAMETERS))
        r = 0
        for own, streams in points:
            for stream in streams:
                # the CPU engine's initial state
                position[r], velocity[r], labels[r], keys[r] = initial_particles(own, stream)
                rows[r] = _row_parameters(own)
                r += 1
        self.settings = settings
        self.count = count
        self.n = n
        self.n_cells = n_cells
        self.n_blocks = blocks_per_realization(n)
        self.spread_blocks = min(grid(n, THREADS), _SPREAD_BLOCKS)
        spare = (
            device_zeros((count, 2, n)),
            device_zeros((count, 2, n)),
            device_zeros((count, 2, n), np.int64),
        )
        self.buffers = ((to_device(position), to_device(velocity), to_device(labels)), spare)
        self.rows = to_device(rows)
        self.cell_of = device_zeros((count, n), np.int64)
        self.order = device_zeros((count, n), np.int64)
        self.cell_start = device_zeros((count, n_cells + 1), np.int64)
        self.fill = device_zeros((count, n_cells), np.int64)
        self.moments = device_zeros((count, n_cells, 5))
        self.carry = device_zeros((count, n_cells))
        self.states = device_zeros((count, n_cells, 4), np.uint64)
        _seed[(grid(n_cells), count), BLOCK](to_device(keys), self.states)
        self.tally = device_zeros((count, n_cells, _N_TALLIES), np.int64)
        self.lost = device_zeros((count, n_cells))
        self.u = device_zeros((count, 2))
        self.partials = device_zeros((count, self.n_blocks, N_SUMS))
        self.observables = device_zeros((count, n_samples, kernels.N_OBSERVABLES))
        self.dissipated = device_zeros((count, n_samples))
        s = settings
        m = s.cells_per_side
        self.stream_arguments = (float(s.box_side), float(m / s.box_side), int(m))
        step = s.step()
        self.collide_arguments = (
            int(step.rule),
            float(step.density_per_count),
            float(step.pair_coefficient),
            float(step.time_step),
        )
        self.cells = (self.moments, self.carry, self.states, self.tally, self.lost)
        self.together = _cooperative_blocks(self) if TOGETHER else 0

    def advance(self, n_steps: int, count: int) -> None:
        """Advance the first ``count`` realizations by ``n_steps`` steps: one cooperative
        launch (``_advance_together``) where the GPU runs it, else five launches a step."""
        if n_steps <= 0 or count <= 0:
            return
        if self.together:
            _advance_together[self.together, BLOCK](*self.together_arguments(n_steps, count))
            if n_steps % 2:
                self.buffers = self.buffers[::-1]
            return
        for _ in range(n_steps):
            self.launched_step(count)

    def launched_step(self, count: int, run=None) -> None:
        """One step of the first ``count`` realizations as five launches (``_centre``,
        ``_stream``, ``_scan``, ``_scatter``, ``_collide``), then the buffers swapped.
        ``run(name, launch)`` makes each launch (``launch()``; the bench times them one by
        one); by default they are launched in turn."""
        source, target = self.buffers
        position, velocity, _labels = source
        particles = (self.spread_blocks, count)
        cell_grid = (grid(self.n_cells, _CELLS_PER_BLOCK), count)
        phases = (
            (
                "centre",
                lambda: _centre[count, BLOCK](self.moments, self.u, self.cell_start, 1.0 / self.n),
            ),
            (
                "stream",
                lambda: _stream[particles, THREADS](
                    position,
                    velocity,
                    self.cell_of,
                    self.cell_start,
                    self.u,
                    self.rows,
                    self.stream_arguments,
                ),
            ),
            ("scan", lambda: _scan[count, BLOCK](self.cell_start, self.fill)),
            ("scatter", lambda: _scatter[particles, THREADS](self.cell_of, self.fill, self.order)),
            (
                "collide",
                lambda: _collide[cell_grid, BLOCK](
                    source,
                    target,
                    self.order,
                    self.cell_start,
                    self.cells,
                    self.rows,
                    self.collide_arguments,
                ),
            ),
        )
        for name, launch in phases:
            if run is None:
                launch()
            else:
                run(name, launch)
        self.buffers = (target, source)

    def together_arguments(self, n_steps: int, count: int) -> tuple:
        """The arguments of ``_advance_together`` for ``n_steps`` steps of the first
        ``count`` realizations."""
        first, second = self.buffers
        work = (self.cell_of, self.order, self.cell_start, self.fill)
        return (
            first,
            second,
            work,
            self.cells,
            self.u,
            self.rows,
            self.stream_arguments,
            self.collide_arguments,
            1.0 / self.n,
            (int(n_steps), int(count)),
        )

    def observe(self, sample: int, count: int) -> None:
        """Row ``sample`` of the first ``count`` realizations' observables and of the
        energy they lost since the last one."""
        if count <= 0:
            return
        position, velocity, _labels = self.buffers[0]
        _observe[(self.n_blocks, count), THREADS](
            position, velocity, self.partials, float(self.settings.wavenumber)
        )
        _finish[count, BLOCK](
            self.partials,
            self.n_blocks,
            self.lost,
            self.rows,
            self.n,
            self.observables,
            self.dissipated,
            sample,
        )

    def reset_lost(self) -> None:
        self.lost.copy_to_device(np.zeros((self.count, self.n_cells)))


def run_points(points, warm, first_steps, stride, progress=None):
    """Run the realizations of several runs together on the GPU.

    ``points`` are (settings, streams, n_samples, out) of runs that share
    ``inhomogeneous.SHARED_SETTINGS`` (one
    row of ``streams`` a realization); restitution, drag, streams and ``n_samples`` may
    differ. Every run follows the CPU front's schedule: ``warm`` steps, then
    ``first_steps`` before the first sample and ``stride`` before each later one, so the
    runs keep step together until the shorter ones are done (they sit in the last rows of
    the batch and idle from then on). Fills each ``out`` (numpy arrays): ``observables``
    (R, n_samples, N_OBSERVABLES), ``dissipated`` (R, n_samples), ``collisions``,
    ``candidates``, ``particle_steps``, ``repeated_collisions`` and ``cpu_seconds`` (R,),
    the last the wall time of the whole batch (launches and the GPU, compilation
    excluded) divided by its number of realizations. A run's numbers are those it gives
    alone. ``progress`` (a ``Progress`` over realizations x steps) is updated after every
    sample.
    """
    by_length = sorted(points, key=lambda point: -point[2])  # stable: the longest first
    settings = by_length[0][0]
    longest = by_length[0][2]
    _compile_outside_the_timer(settings)
    batch = _Batch([(s, streams) for s, streams, _, _ in by_length], longest)
    ends = np.cumsum([streams.shape[0] for _, streams, _, _ in by_length])
    lengths = np.array([n_samples for _, _, n_samples, _ in by_length])

    def active(sample: int) -> int:
        """Rows of the runs that take ``sample``: a prefix, the runs sorted by length."""
        taking = lengths > sample
        return int(ends[taking][-1]) if taking.any() else 0

    synchronize()
    start = time.perf_counter()
    batch.advance(warm, batch.count)
    if progress is not None and warm:
        progress.update(batch.count * warm)
    batch.reset_lost()
    for sample in range(longest):
        count = active(sample)
        steps = first_steps if sample == 0 else stride
        batch.advance(steps, count)
        batch.observe(sample, count)
        if progress is not None and steps:
            progress.update(count * steps)
    observables = batch.observables.copy_to_host()
    dissipated = batch.dissipated.copy_to_host()
    tally = batch.tally.copy_to_host().sum(axis=1)
    synchronize()
    elapsed = time.perf_counter() - start
    if tally[:, _EXCEEDED].any():
        raise RuntimeError(
            "internal error: the relative-speed bound of a cell was exceeded "
            f"{tally[:, _EXCEEDED].sum()} times although it is kept rigorous"
        )
    first = 0
    for (_, _, n_samples, out), last in zip(by_length, ends, strict=True):
        rows = slice(first, last)
        out["observables"][:] = observables[rows, :n_samples]
        out["dissipated"][:] = dissipated[rows, :n_samples]
        out["collisions"][:] = tally[rows, _COLLISIONS]
        out["candidates"][:] = tally[rows, _CANDIDATES]
        out["repeated_collisions"][:] = tally[rows, _REPEATED]
        out["particle_steps"][:] = (warm + first_steps + (n_samples - 1) * stride) * batch.n
        out["cpu_seconds"][:] = elapsed / batch.count
        first = last


def _compile_outside_the_timer(settings) -> None:
    """Two steps and a sample of a tiny batch with the same argument types, so that the
    timed run does not include numba-cuda's compilation, which goes to the cache once
    (``kinetic.gpu.warm``; skipped under the simulator)."""
    if simulated():
        return
    tiny = CoolingModesSettings(
        **{**settings.parameters(), "n_particles": 4, "fictive_factor": 1, "cells_per_side": 1}
    )

    def compile_kernels():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NumbaPerformanceWarning)  # grids of one block
            batch = _Batch([(tiny, np.array([[1, 2, 3, 4]], dtype=np.uint64))], 1)
            batch.advance(2, 1)
            batch.observe(0, 1)
            synchronize()

    warm("cuda_dsmc_inhomogeneous", "dsmc", compile_kernels)
