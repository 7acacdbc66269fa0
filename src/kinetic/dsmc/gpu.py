"""CUDA backend of the homogeneous DSMC engine: ``simulate_homogeneous(backend="cuda")``.

All realizations of a call advance together, on one GPU: the velocities of realization r
are row r of a ``(R, d, N)`` float64 array (each row the CPU engine's struct of arrays;
``STORAGE`` ``particles`` keeps them as ``(R, N, d)`` instead, the same numbers).
One time step is a short sequence of launches, each covering every realization (the
realization is the grid's y index; the kernels over particles run THREADS x blocks
threads per realization, each looping over the particles with the grid's stride): 2
launches with the Lie splitting, 3 with the Strang splitting, 2 more on a sampled step.

1. **Groups.** Every step the particles of a realization are re-dealt into G = max(1,
   N // GROUP_SIZE) random groups without moving them: the N particles are m columns of
   G rows (particle j G + row in column j; the last column holds the rest), and group g
   takes from each column j the particle of row (g + s_j) mod G
   (``kernels.column_particle``; m or m - 1 particles, GROUP_SIZE = 128 to 2 GROUP_SIZE - 1;
   a gas of fewer than 2 GROUP_SIZE particles is one group, as on the CPU). The shifts
   s_j are a hash of j with the step's key (``kernels.column_shift``), the key
   ``kinetic.rng.thread_state`` of the realization's stream row and the step, so a step's
   groups are a function of (seed, realization, step) only. For a spatially homogeneous
   gas a random group is a collision cell, and one thread per group writes only its own
   particles.
2. **Collisions** (one thread per group): the CPU engine's own collision stage
   (``kernels.collide_members``, ``collide_range``'s loop with the map from a group's
   members to their particles, compiled for the GPU by ``kinetic.gpu.device_function``:
   the same NTC or Poisson clock, majorant, acceptance, collision rule and restitution)
   on its group for one time step, with
   - the pair coefficient of a group of m particles ``pair_coefficient (N - 1)/(m - 1)``:
     a particle meets each of its m - 1 group mates at the rate of the whole-box NTC
     times (N - 1)/(m - 1), so its collision rate is the CPU engine's, whatever m;
   - NTC: the fraction of a candidate (``carry``) is a fresh uniform number each step
     (the group changes every step), so the number of candidates is the expected one
     rounded up or down at random, without bias;
   - its own xoshiro256+ stream (``thread_state`` of the realization's row after its
     Maxwellian start and the group index), kept on the device.
   Each group collides in place (``_collide_sparse``, the ``sparse`` collisions), its
   thread reading and writing only its candidate pairs (at montanero2007's δt = 0.003 τ
   a group of 128 has about 0.2 collisions a step). The majorant is the realization's,
   as in the CPU engine's one box: twice the largest |W| of the stored velocities, found
   by the force pass before (the collisions run on W at the thermostatted rate,
   ``kernels._deferred``), or its image under the thermostat once a snapshot has applied
   it, raised on the fly as on the CPU. The force pass of step 3 is then the step's only
   pass over every particle (48 bytes a Lie step).
3. **Force and thermostat** (``_force``): the force step of every particle
   (``kernels._force_factor``: Euler or exact) with the sums ΣV_k, Σ|V|² and the largest
   |V|² per block; the realization's last block to finish folds the blocks' sums (a
   ticket taken by an integer atomic after a memory fence) and runs
   ``kernels._thermostat_scale`` and the step's clock (``kernels._advance_clock``,
   ``_close``). Until the H100 run of 5836ea7 a kernel of its own (``_finish``) did that,
   one thread summing a realization's 64 blocks in turn: 0.077 ms of a 0.341 ms step
   with its launch. The thermostat V -> scale (V - u) itself is applied by
   the next kernel that reads the velocities (the next force step or snapshot: no pass
   of its own). Lie splitting: once after the collisions; Strang: with half the field
   before and after them.
4. **Observers** on sampled steps (``_observe``): the moments of
   ``kernels._particle_moments`` and, in the histogram windows, the bins of
   ``kernels._histogram_bins``, counted by each thread block in its own histograms in
   shared memory and added to the realization's once a block (where they fit, which the
   configs' few hundred bins do).

Two earlier regroupings are gone. ``feistel`` (a Feistel bijection of the indices and a
copy of the particles in its order every step) was removed after revision 2c14c5a: an
H100 (revision 2984f74, docs/data/cuda-h100-2984f74.json) timed a step of
montanero2007's paper job (50 realizations of 2 × 10⁵) at 1.53 ms against 1.07 ms for
``columns``. ``columns`` (a thread block gathered 14 neighbouring groups into shared
memory, found each group's own majorant, collided them and wrote them back after the
force step, in one launch) was removed after revision cb514dd: an H100 (revision
5836ea7, docs/data/cuda-h100-5836ea7.json, bench cuda ``memory_bound``) timed a Lie step
of those 10⁷ particles at 0.738 ms against 0.341 ms for ``sparse`` (2.16 times slower),
and ``dsmc_speed``'s HCS (N = 2 × 10⁴, 16 realizations, α = 0.9) gave ζ = 0.071302 ±
0.000036, a2 = -0.0162 ± 0.0003 with ``columns`` against 0.071327 ± 0.000037, -0.0158 ±
0.0004 with ``sparse``.

Determinism: the same call gives the same numbers twice (on one GPU model). Float sums
are folded in a fixed order: each thread sums a fixed set of particles (stride THREADS
x blocks), a tree sums the threads of a block (``_block_sums``: the tree of
``kinetic.gpu.block_reduce_sum`` on several fields at once), the same tree sums the
blocks (the force pass's last block; ``_fold_moments``, a thread a moment, the snapshots'
blocks in index order); the number of blocks per realization depends on N only, so a
realization's numbers do not depend on the other realizations of the batch. Histogram
counts are integer atomics. The ``cx_weights`` sums (c_x (3/2 - c_x²) per bin) are
accumulated as integers in units of WEIGHT_UNIT = 2**-20 per observation (rounded to
nearest: an error below 5e-7 per observation) by integer atomics, exact and
order-independent. There are no floating-point atomics.

Not bit-identical with the CPU engine (other grouping, other random numbers, other
summation order): the two agree statistically (tests/gpu/test_dsmc_cuda.py). Units,
outputs and parameters are those of :mod:`kinetic.dsmc.homogeneous`.
"""

from __future__ import annotations

import math
import time
import warnings
from typing import Any

import numpy as np
from numba.core import types
from numba.core.errors import NumbaPerformanceWarning

from kinetic import gas as units
from kinetic import rng
from kinetic.backends import simulated
from kinetic.dsmc import kernels
from kinetic.dsmc.kernels import Collisions
from kinetic.dsmc.state import (
    _KERNEL_ID,
    _STATUS_MESSAGES,
    HomogeneousSettings,
    Samples,
    maxwellian_starts,
)
from kinetic.gpu import (
    BLOCK,
    cuda,
    device_empty,
    device_function,
    device_inline,
    device_zeros,
    grid,
    kernel,
    kernel_variants,
    last_block,
    synchronize,
    to_device,
    warm,
)

__all__ = ["GROUP_SIZE", "WEIGHT_UNIT", "run_batch"]

GROUP_SIZE = 128
"""Fewest particles of a collision group (groups hold GROUP_SIZE to 2 GROUP_SIZE - 1).

Measured on an H100 (N = 2 x 10^4, α = 0.9, δt = 0.1 τ): at ε* = 0.025 (48 realizations,
two seeds) the cooling rate of groups of 32 is 0.16-0.2 % above the CPU engine's (about 5
standard errors; the same at δt = 0.05 τ and 0.025 τ, so not a within-step effect), of
64 0.1 % above, of 128 equal to it within 0.03 %; in the HCS (16 realizations) groups of
32 are 0.17 % above (2 standard errors), groups of 128 agree. κ', a2 and the c_x
histogram agree within their errors for all sizes. Groups of 128 cost no more time on
the GPU (N = 2 x 10^5, 50 realizations: 2.98 against 3.05 ms a step)."""

_SMALL = 8 if simulated() else 32
"""Threads per block of the kernels with one thread per realization (8 under the
simulator, where every thread is a greenlet that runs Python: fewer threads, less
overhead)."""

THREADS = 8 if simulated() else BLOCK
"""Threads per block of the kernels over particles (a power of two: the block sums halve
it). Under the simulator 8: a test's forced run of 6 realizations takes 22 s instead of
29 s with 32."""

MIN_BLOCKS = 1 if simulated() else 64
"""Thread blocks per realization of the kernels over particles (whose threads loop over
the particles with the grid's stride) up to MIN_BLOCKS x THREADS x PARTICLES_PER_THREAD
particles (262,144 on a GPU: montanero2007's and visco2008's N = 2 x 10^5), where a batch
of many realizations fills the GPU; ``blocks_per_realization``."""

PARTICLES_PER_THREAD = 32
"""Particles a thread of those kernels walks through, about, above MIN_BLOCKS blocks."""

MAX_BLOCKS = 1 if simulated() else 1024
"""Most thread blocks per realization of the kernels over particles."""


def blocks_per_realization(n: int) -> int:
    """Thread blocks per realization of the kernels over ``n`` particles: a function of n
    only, so that the order of a realization's sums, hence its numbers, does not depend on
    the other realizations of its batch. MIN_BLOCKS (64) up to 262,144 particles, then
    about PARTICLES_PER_THREAD particles a thread, at most MAX_BLOCKS (1024); never a
    block beyond the particles' ``grid``.

    Until revision b484bd2 every N had at most 64: on an H100 (b66ff5b) one realization of
    2 x 10^7 particles then ran 2.28 x 10^8 collisions/s against 4.93 x 10^8 for 100
    realizations of 2 x 10^5 in one launch (the same particles a step), its force passes'
    64 blocks of 128 threads on 64 of the 132 SMs. Now 1024 blocks (about 153 particles
    a thread); 10 realizations of 2 x 10^6, 640 blocks in all before, get 489 each."""
    return min(
        grid(n, THREADS),
        MAX_BLOCKS,
        max(MIN_BLOCKS, grid(n, THREADS * PARTICLES_PER_THREAD)),
    )


WEIGHT_UNIT = 2.0**-20
"""Resolution of the fixed-point ``cx_weights`` sums (per observation)."""

STORAGE = "components"
"""How a batch keeps its velocities on the device: ``components``, ``(R, d, N)`` (each
component of a realization a contiguous row, the CPU engine's struct of arrays), or
``particles``, ``(R, N, d)`` (a particle's d components side by side). The kernels over
particles are compiled once for each (``_BY_PARTICLE``) and see a realization as a
``(d, N)`` array, ``velocity[r]`` or ``velocity[r].T``; both compute the same numbers,
bit for bit. What differs is the memory a candidate pair touches: its two
particles' 6 components are 6 scattered 32-byte sectors in ``components`` and 2-4 in
``particles`` (a particle's 24 bytes straddle two sectors half the time), while the
passes over every particle read and write the same bytes either way. The collisions of
the bench's Strang step (δt = 0.1 τ) are about two thirds of its time on an H200, at
random-sector rates; ``python -m kinetic.bench cuda --sections dsmc_storage`` times both
storages (not yet run on a GPU)."""

_STORAGE_IS_PARTICLES = {"components": False, "particles": True}
"""Each ``STORAGE`` and its compiled copies' ``_BY_PARTICLE``."""
_STORAGES = tuple(_STORAGE_IS_PARTICLES)

_BY_PARTICLE = False
"""Fixed in each compiled copy of the kernels over particles (``kinetic.gpu.kernel_variants``:
one for each of ``_STORAGES``): whether their velocities come as the ``(R, N, d)`` store,
read through ``velocity[r].T``, else as ``(R, d, N)``. numba prunes the branch on a
constant, so each copy indexes one contiguous layout (C, or F for the transposed rows)
and its loads are global. (A runtime flag, 175d3e0 to 37cb1aa, met both layouts in one
strided type and left every velocity load generic in the PTX, the default's too; a
strided ``(R, d, N)`` view of the store, 8f2b33d, fixed the default's but left the
view's generic.)"""

N_MOMENTS = kernels.N_MOMENTS
_N_FORCE_SUMS = 4
_N_FOLDED = _N_FORCE_SUMS + 1  # the sums and the largest |V|²

# settings of a batch, read by the kernels from two small device arrays
_RESTITUTION, _PAIR_BASE, _DURATION, _TARGET, _RATE_EXPONENT = 0, 1, 2, 3, 4
_INVERSE_V0, _CX_LOW, _INVERSE_CX, _INVERSE_SPEED = 5, 6, 7, 8
_KERNEL, _POISSON, _EXACT, _N_CX, _N_SPEED, _N = 0, 1, 2, 3, 4, 5

# columns of ``thermo[r]``: u (0..2) and scale of the pending thermostat V = scale (W - u),
# the step's ln(scale) so far, and the largest |W| after the last force pass (the
# ``sparse`` majorant: top1 = top2 = it; at the start, of the Maxwellian)
_SCALE, _LOG_SCALE, _TOP, _N_THERMO = 3, 4, 5, 6

_group_members = device_function(kernels.group_size)
_collide_members = device_function(kernels.collide_members)
_force_factor = device_function(kernels._force_factor)
_thermostat_scale = device_function(kernels._thermostat_scale)
_advance_clock = device_function(kernels._advance_clock)
_particle_moments = device_function(kernels._particle_moments)
_histogram_bins = device_function(kernels._histogram_bins)
_uniform = device_function(rng.xoshiro_uniform)
_thread_state = device_function(rng.thread_state)


# ------------------------------------------------------------------------- reductions


def _block_sums(shared, values, out):
    """``out[f]`` = Σ over the T threads of a block of ``values[f]`` (a local array,
    f < shared.shape[1]), by the fixed tree of ``kinetic.gpu.block_reduce_sum`` run on all
    fields at once in ``shared[T, fields]`` (T = shared.shape[0], the block's threads, a
    power of two); every thread must call it, thread 0 writes ``out``."""
    t = cuda.threadIdx.x
    fields = shared.shape[1]
    for f in range(fields):
        shared[t, f] = values[f]
    cuda.syncthreads()
    stride = shared.shape[0] // 2
    while stride > 0:
        if t < stride:
            for f in range(fields):
                shared[t, f] += shared[t + stride, f]
        cuda.syncthreads()
        stride //= 2
    if t == 0:
        for f in range(fields):
            out[f] = shared[0, f]


_block_sums = device_inline(_block_sums)


def _block_max(shared, value, out):
    """``out[0]``, the largest of the block's threads' ``value``, by a tree in
    ``shared[T, 0]`` (as ``_block_sums``); every thread must call it, thread 0 writes
    ``out``."""
    t = cuda.threadIdx.x
    cuda.syncthreads()  # ``shared`` may still be read by a ``_block_sums`` before
    shared[t, 0] = value
    cuda.syncthreads()
    stride = shared.shape[0] // 2
    while stride > 0:
        if t < stride:
            shared[t, 0] = max(shared[t, 0], shared[t + stride, 0])
        cuda.syncthreads()
        stride //= 2
    if t == 0:
        out[0] = shared[0, 0]


_block_max = device_inline(_block_max)


@kernel
def _store_by_particle(components, particles):
    """``particles[r, i, k] = components[r, k, i]``: a batch's starts, drawn as ``(R, d,
    N)``, stored by particle (``STORAGE`` ``particles``) on the device, one thread a
    particle (the host would copy them once more: 0.5 GB at 2 x 10^7 particles)."""
    i = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    r = cuda.blockIdx.y
    if i < particles.shape[1]:
        for k in range(particles.shape[2]):
            particles[r, i, k] = components[r, k, i]


# ------------------------------------------------------------------------- regrouping


def _step_key(keys, r, step):
    """``keys[r, 4]`` = the key of the groups of ``step`` (``kernels.column_shift``): the
    first word of ``thread_state`` of the realization's stream row ``keys[r, :4]`` and
    the step."""
    k0, _, _, _ = _thread_state(keys[r, 0], keys[r, 1], keys[r, 2], keys[r, 3], step)
    keys[r, 4] = k0


_step_key = device_inline(_step_key)


# ------------------------------------------------------------------------- collisions


@kernel
def _seed_groups(group_keys, states, keys):
    """``states[r, g] = thread_state(group_keys[r], g)``: one stream per group; and the
    groups' key of step 0."""
    g = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    r = cuda.blockIdx.y
    if g >= states.shape[1]:
        return
    if g == 0:
        _step_key(keys, r, 0)
    s0, s1, s2, s3 = _thread_state(
        group_keys[r, 0], group_keys[r, 1], group_keys[r, 2], group_keys[r, 3], g
    )
    states[r, g, 0] = s0
    states[r, g, 1] = s1
    states[r, g, 2] = s2
    states[r, g, 3] = s3


def _collide_sparse(
    velocity, states, bounds, carry, tally, reals, flags, keys, layout, thermo, pending
):
    """``sparse``: one time step of collisions in group g of realization r, one thread a
    group, in place: the particles group g takes from the columns ``layout`` in this
    step (``kernels.collide_members``; the shifts of the step's key ``keys[r, 4]``), of
    which the thread reads and writes only its candidate pairs. The majorant is the
    realization's, from the last force pass (``thermo[r, _TOP]``: the largest |W| of the
    stored velocities W, about 0, for both of the two largest speeds), as in the CPU
    engine's one box: with the thermostat ``pending`` (V = scale (W - u)), the collisions
    run on W at scale^p times the rate (``kernels._deferred``), else (applied by a
    snapshot, or the start: scale 1, u 0) on V about the centre -scale u, where
    |V + scale u| = scale |W|. The group's pair coefficient is the settings' times
    (N - 1)/(m - 1) (``reals[_PAIR_BASE]`` / (m - 1)), its stream, carry and tally its own; the
    collisions raise the group's bound where they make a faster particle, as on the CPU."""
    g = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    r = cuda.blockIdx.y
    n_rows = layout[0]
    if g >= n_rows:
        return
    v = velocity[r].T if _BY_PARTICLE else velocity[r]
    d = v.shape[0]
    members = (n_rows, layout[1], layout[2], np.int64(g), keys[r, 4])
    scale = thermo[r, _SCALE]
    row = bounds[r, g]
    if pending:
        stretch = 1.0
        factor = scale ** reals[_RATE_EXPONENT]
        for k in range(d):
            row[k] = 0.0
    else:
        stretch = scale
        factor = 1.0
        for k in range(d):
            row[k] = -scale * thermo[r, k]
    row[d] = stretch * thermo[r, _TOP]
    row[d + 1] = row[d]
    size = _group_members(members)
    state = states[r, g]
    u, s0, s1, s2, s3 = _uniform(state[0], state[1], state[2], state[3])
    state[0] = s0
    state[1] = s1
    state[2] = s2
    state[3] = s3
    carry[r, g, 0] = u
    if row[d] == 0.0:
        return  # all the realization's particles have one velocity: no collision
    collisions = Collisions(
        flags[_KERNEL],
        reals[_RESTITUTION],
        reals[_PAIR_BASE] * factor / (size - 1),
        reals[_DURATION],
        flags[_POISSON] != 0,
        row,
        carry[r, g],
        tally[r, g],
    )
    _collide_members(v, 0, size, members, state, collisions)


# --------------------------------------------------------------- force and thermostat


def _forced(v0, v1, v2, field_step, exact):
    """One particle's force step V -> f V (``kernels._force_factor`` of a V_x, a =
    ``field_step``): ``(status, V_x, V_y, V_z)``."""
    code, f = _force_factor(field_step * v0, exact)
    return code, v0 * f, v1 * f, v2 * f


_forced = device_inline(_forced)


def _force(velocity, partials, status, field_step, exact, thermo, rescale, done, close):
    """Force step V -> f V of every particle (a = ``field_step``; after the pending
    thermostat if ``rescale``), and the per-block sums ``partials[r, b, :4]`` = ΣV_x,
    ΣV_y, ΣV_z, Σ|V|² after it and the largest |V|² in ``partials[r, b, 4]``; a failed
    step raises ``status[r]`` to its STATUS_* code. The last block of realization r to
    finish (its ticket ``done[r]``, an integer atomic after a memory fence) folds the
    blocks' partials, thread t the blocks t, t + THREADS, ... in order, then a fixed tree
    (the same numbers whichever block comes last), closes the thermostat (``_close``,
    with ``close`` = (clock, reals, flags, end_of_step, keys)) and resets the ticket: no
    launch of its own."""
    shared = cuda.shared.array((THREADS, _N_FORCE_SUMS), np.float64)
    folded = cuda.shared.array(_N_FOLDED, np.float64)
    last = cuda.shared.array(1, np.int64)
    r = cuda.blockIdx.y
    b = cuda.blockIdx.x
    t = cuda.threadIdx.x
    v = velocity[r].T if _BY_PARTICLE else velocity[r]
    d = v.shape[0]
    n = v.shape[1]
    sum0 = 0.0
    sum1 = 0.0
    sum2 = 0.0
    total_sq = 0.0
    top = 0.0
    failed = 0
    for i in range(b * THREADS + t, n, cuda.gridDim.x * THREADS):
        v0 = v[0, i]
        v1 = v[1, i]
        v2 = v[2, i] if d == 3 else 0.0
        if rescale:
            v0 = _thermostat(v0, thermo, r, 0)
            v1 = _thermostat(v1, thermo, r, 1)
            v2 = _thermostat(v2, thermo, r, 2) if d == 3 else 0.0
        if field_step != 0.0:
            code, v0, v1, v2 = _forced(v0, v1, v2, field_step, exact)
            if code != 0:
                failed = code
        if rescale or field_step != 0.0:
            v[0, i] = v0
            v[1, i] = v1
            if d == 3:
                v[2, i] = v2
        sum0 += v0
        sum1 += v1
        sum2 += v2
        speed_sq = v0 * v0 + v1 * v1 + v2 * v2
        total_sq += speed_sq
        top = max(top, speed_sq)
    if failed != 0:
        cuda.atomic.max(status, r, failed)
    sums = cuda.local.array(_N_FORCE_SUMS, np.float64)
    sums[0] = sum0
    sums[1] = sum1
    sums[2] = sum2
    sums[3] = total_sq
    _block_sums(shared, sums, partials[r, b])
    _block_max(shared, top, partials[r, b, _N_FORCE_SUMS:])
    if not last_block(done, r, last):
        return
    for f in range(_N_FORCE_SUMS):  # thread t: the blocks t, t + THREADS, ... in order
        sums[f] = 0.0
    top = 0.0
    for block in range(t, cuda.gridDim.x, THREADS):
        for f in range(_N_FORCE_SUMS):
            sums[f] += partials[r, block, f]
        top = max(top, partials[r, block, _N_FORCE_SUMS])
    _block_sums(shared, sums, folded)
    _block_max(shared, top, folded[_N_FORCE_SUMS:])
    if t == 0:
        _close(folded, thermo, status, close, r)


def _close(folded, thermo, status, close, r):
    """Realization r's thermostat from the folded sums of ``_force`` (``folded`` = ΣV,
    Σ|V|², the largest |V|²): its mean velocity and scale (``thermo[r, :4]`` = u, scale,
    applied later); ``thermo[r, 4]`` collects the step's ln(scale), ``thermo[r, 5]`` the
    largest |W|; at the ``end_of_step`` the step is closed in ``clock[r]`` and the next
    step's key is drawn (``_step_key``). ``close`` is (clock, reals, flags, end_of_step,
    keys)."""
    clock, reals, flags, end_of_step, keys = close
    thermo[r, _TOP] = math.sqrt(folded[_N_FORCE_SUMS])
    code, u0, u1, u2, scale, log_scale = _thermostat_scale(
        folded[0], folded[1], folded[2], folded[3], flags[_N], reals[_TARGET]
    )
    if code != 0:
        cuda.atomic.max(status, r, code)
    if status[r] != 0:
        u0 = 0.0
        u1 = 0.0
        u2 = 0.0
        scale = 1.0
        log_scale = 0.0
    thermo[r, 0] = u0
    thermo[r, 1] = u1
    thermo[r, 2] = u2
    thermo[r, _SCALE] = scale
    log_scale += thermo[r, _LOG_SCALE]
    if end_of_step:
        thermo[r, _LOG_SCALE] = 0.0
        _advance_clock(clock[r], reals[_DURATION], reals[_RATE_EXPONENT], log_scale)
        _step_key(keys, r, np.int64(clock[r, 3]))
    else:
        thermo[r, _LOG_SCALE] = log_scale


_close = device_inline(_close)


def _thermostat(value, thermo, r, k):
    """Component k of the thermostat of realization r: scale (V_k - u_k) (Eq. 4.2)."""
    return thermo[r, _SCALE] * (value - thermo[r, k])


_thermostat = device_inline(_thermostat)


# -------------------------------------------------------------------------- observers


def _observe(velocity, partials, histograms, reals, flags, histogram, thermo, rescale, private):
    """One snapshot (after the pending thermostat if ``rescale``): per-block sums of the
    N_MOMENTS particle moments in ``partials`` and, if ``histogram``, the c_x and |c|
    histograms ``histograms`` = (cx_counts, cx_weights, speed_counts) (integer atomics;
    the c_x weights in units of WEIGHT_UNIT). With ``private`` each block first counts
    into its own copy in the launch's dynamic shared memory (``_histogram_bytes``) and
    then adds its nonzero bins to the realization's: one atomic on global memory a bin a
    block instead of three a particle, the same integers (sums of integers do not depend
    on their order)."""
    cx_counts, cx_weights, speed_counts = histograms
    shared = cuda.shared.array((THREADS, N_MOMENTS), np.float64)
    local = cuda.shared.array(0, types.int64)  # a numba type: the simulator needs one here
    sums = cuda.local.array(N_MOMENTS, np.float64)
    r = cuda.blockIdx.y
    b = cuda.blockIdx.x
    t = cuda.threadIdx.x
    v = velocity[r].T if _BY_PARTICLE else velocity[r]
    d = v.shape[0]
    n = v.shape[1]
    n_cx = cx_counts.shape[1]
    n_bins = 2 * n_cx + speed_counts.shape[1]
    inverse_v0 = reals[_INVERSE_V0]
    p_full = 0.5 * d
    for f in range(N_MOMENTS):
        sums[f] = 0.0
    if histogram and private:
        for k in range(t, n_bins, THREADS):
            local[k] = 0
        cuda.syncthreads()
    for i in range(b * THREADS + t, n, cuda.gridDim.x * THREADS):
        if rescale:
            for k in range(d):
                v[k, i] = _thermostat(v[k, i], thermo, r, k)
        terms = _particle_moments(v, i, d, inverse_v0, p_full)
        for f in range(N_MOMENTS):
            sums[f] += terms[f]
        if histogram:
            cx_bin, weight, speed_bin = _histogram_bins(
                v,
                i,
                d,
                inverse_v0,
                reals[_CX_LOW],
                reals[_INVERSE_CX],
                flags[_N_CX],
                reals[_INVERSE_SPEED],
                flags[_N_SPEED],
            )
            if private:
                cuda.atomic.add(local, cx_bin, 1)
                cuda.atomic.add(local, n_cx + cx_bin, _fixed_point(weight))
                cuda.atomic.add(local, 2 * n_cx + speed_bin, 1)
            else:
                cuda.atomic.add(cx_counts, (r, cx_bin), 1)
                cuda.atomic.add(cx_weights, (r, cx_bin), _fixed_point(weight))
                cuda.atomic.add(speed_counts, (r, speed_bin), 1)
    if histogram and private:
        cuda.syncthreads()
        for k in range(t, n_bins, THREADS):
            count = local[k]
            if count != 0:
                if k < n_cx:
                    cuda.atomic.add(cx_counts, (r, k), count)
                elif k < 2 * n_cx:
                    cuda.atomic.add(cx_weights, (r, k - n_cx), count)
                else:
                    cuda.atomic.add(speed_counts, (r, k - 2 * n_cx), count)
    _block_sums(shared, sums, partials[r, b])


def _histogram_bytes(histograms) -> int:
    """Dynamic shared memory of a block's private histograms in ``_observe`` (int64 bins
    of c_x counts, c_x weights and speeds), or 0 where they would not fit beside the
    kernel's static shared memory in the 48 KiB a block may use without opting in (the
    kernel then adds every particle's bins to global memory)."""
    cx_counts, _, speed_counts = histograms
    size = 8 * (2 * cx_counts.shape[1] + speed_counts.shape[1])
    static = 8 * THREADS * N_MOMENTS
    return size if size + static <= _SHARED_BYTES else 0


_SHARED_BYTES = 48 * 1024
"""Shared memory a thread block may use without opting in to more."""


@kernel
def _fold_moments(partials, n_blocks, moment_sums, inverse_n):
    """One thread per realization r and moment f: ``moment_sums[r, f] += inverse_n Σ_b
    partials[r, b, f]``, the blocks summed in index order (a thread per realization
    until 72a92ab, the same numbers: up to 1024 blocks x N_MOMENTS loads in turn)."""
    k = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    if k >= partials.shape[0] * N_MOMENTS:
        return
    r = k // N_MOMENTS
    f = k - r * N_MOMENTS
    total = 0.0
    for b in range(n_blocks):
        total += partials[r, b, f]
    moment_sums[r, f] += inverse_n * total


_ACCEPTED = kernels.TALLY_ACCEPTED

_ACCEPTED_LANES = 8 if simulated() else 1024
"""Threads a realization that ``_sum_accepted`` sums its groups' accepted collisions
with (each a strided share of the groups, in a fixed order)."""


@kernel
def _sum_accepted(tally, lanes):
    """``lanes[r, c]`` = Σ_{g ≡ c mod C} ``tally[r, g, accepted]``: integers, in index order,
    so the window's counts do not depend on the launch."""
    c = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    r = cuda.blockIdx.y
    if c >= lanes.shape[1]:
        return
    total = 0
    for g in range(c, tally.shape[1], lanes.shape[1]):
        total += tally[r, g, _ACCEPTED]
    lanes[r, c] = total


@kernel
def _fold_lanes(lanes, accepted):
    """``accepted[r]`` = Σ_c ``lanes[r, c]``, one thread a realization."""
    r = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    if r >= lanes.shape[0]:
        return
    total = 0
    for c in range(lanes.shape[1]):
        total += lanes[r, c]
    accepted[r] = total


def _fixed_point(weight):
    """``weight`` in units of WEIGHT_UNIT, rounded to the nearest integer (int64)."""
    return np.int64(math.floor(weight * (1.0 / WEIGHT_UNIT) + 0.5))


_fixed_point = device_inline(_fixed_point)


# ------------------------------------------------------------------------------ host


class _Batch:
    """Device state of R realizations and the launches of one step."""

    def __init__(
        self,
        settings: HomogeneousSettings,
        samples: Samples,
        streams: np.ndarray,
    ):
        if STORAGE not in _STORAGES:
            raise ValueError(f"STORAGE must be one of {_STORAGES}, got {STORAGE!r}")
        d, n = settings.dimension, settings.n_particles
        count = streams.shape[0]
        # the CPU engine's Maxwellian starts (new_gas's numbers), built beside the last
        # run if simulate_homogeneous_points asked for them (prefetch_starts)
        velocity, group_keys, tops = _take_starts(d, n, streams)
        self.settings = settings
        self.exact = 1 if settings.force_step == "exact" else 0
        self.count = count
        self.n_groups = max(1, n // GROUP_SIZE)
        self.n_blocks = blocks_per_realization(n)
        self.done = device_zeros(count, np.int64)
        self.storage = STORAGE  # the kernels over particles: their copy for it
        self.velocity = to_device(velocity)
        if _STORAGE_IS_PARTICLES[STORAGE]:  # the starts rearranged on the device, not the host
            by_particle = device_empty((count, n, d))
            _store_by_particle[(grid(n, THREADS), count), THREADS](self.velocity, by_particle)
            self.velocity = by_particle
        n_columns = -(-n // self.n_groups)  # G rows of m columns, the last holding the rest
        layout = [self.n_groups, n_columns, n - (n_columns - 1) * self.n_groups]
        self.layout = to_device(np.array(layout, dtype=np.int64))
        keys = np.zeros((count, 5), dtype=np.uint64)
        keys[:, :4] = streams
        self.keys = to_device(keys)
        self.states = device_zeros((count, self.n_groups, 4), np.uint64)
        _seed_groups[(grid(self.n_groups, _SMALL), count), _SMALL](
            to_device(group_keys), self.states, self.keys
        )
        self.bounds = device_zeros((count, self.n_groups, d + 2))
        self.carry = device_zeros((count, self.n_groups, 1))
        self.tally = device_zeros((count, self.n_groups, 4), np.int64)
        self.lanes = device_zeros((count, _ACCEPTED_LANES), np.int64)
        self.accepted = device_zeros(count, np.int64)
        self.partials = device_zeros((count, self.n_blocks, N_MOMENTS))
        self.thermo = to_device(_start_thermo(tops))
        self.clock = device_zeros((count, 5))
        self.status = device_zeros(count, np.int64)
        self.moment_sums = device_zeros((count, N_MOMENTS))
        self.histograms = (
            device_zeros((count, samples.n_cx_bins + 2), np.int64),
            device_zeros((count, samples.n_cx_bins + 2), np.int64),
            device_zeros((count, samples.n_speed_bins + 1), np.int64),
        )
        self.reals, self.flags = _settings_arrays(settings, samples)
        self.histogram_bytes = _histogram_bytes(self.histograms)
        self.pending = False

    def step(self, sample: bool, histogram: bool) -> None:
        """Launch one time step for every realization: 2 launches (Lie splitting) or 3
        (Strang), and 2 more on a sampled step."""
        s = self.settings
        strang = s.splitting == "strang"
        field_step = 0.5 * s.half_field_step if strang else s.half_field_step
        if strang:
            self._force_and_thermostat(field_step, end_of_step=False)
        self._collide_sparse()
        self._force_and_thermostat(field_step, end_of_step=True)
        if sample:
            private = self.histogram_bytes if histogram else 0
            _observe[self.storage][(self.n_blocks, self.count), THREADS, 0, private](
                self.velocity,
                self.partials,
                self.histograms,
                self.reals,
                self.flags,
                histogram,
                self.thermo,
                self.pending,
                private > 0,
            )
            self.pending = False
            _fold_moments[grid(self.count * N_MOMENTS, _SMALL), _SMALL](
                self.partials, self.n_blocks, self.moment_sums, 1.0 / s.n_particles
            )

    def accepted_collisions(self) -> np.ndarray:
        """Each realization's accepted collisions so far, summed on the device: the host
        gets R integers, not the (R, groups, 4) tally (5 MB at 2 × 10⁷ particles in groups
        of 128, pageable, copied every window of the bench's 10 steps until 2026-11-30:
        50 MB a case, a few ms of the 180 ms of engine time of the H200 run of 5a93630 at
        N = 2 × 10⁵ × 100; not timed since)."""
        lanes = self.lanes.shape[1]
        _sum_accepted[(grid(lanes, _SMALL), self.count), _SMALL](self.tally, self.lanes)
        _fold_lanes[grid(self.count, _SMALL), _SMALL](self.lanes, self.accepted)
        return self.accepted.copy_to_host()

    def _groups(self) -> tuple:
        """The per-group device arrays and the settings the collision kernels take."""
        return self.states, self.bounds, self.carry, self.tally, self.reals, self.flags

    def _collide_sparse(self) -> None:
        """``sparse``: the collision stage of every group, in place (one launch; the
        pending thermostat stays pending)."""
        threads = min(BLOCK, self.n_groups)
        _collide_sparse[self.storage][(grid(self.n_groups, threads), self.count), threads](
            self.velocity,
            *self._groups(),
            self.keys,
            self.layout,
            self.thermo,
            self.pending,
        )

    def _force_and_thermostat(self, field_step: float, end_of_step: bool) -> None:
        """The force step, the thermostat's u and scale (applied later: ``pending``), the
        largest |W| and, at the ``end_of_step``, the clock (the pending thermostat
        first): one launch."""
        _force[self.storage][(self.n_blocks, self.count), THREADS](
            self.velocity,
            self.partials,
            self.status,
            field_step,
            self.exact,
            self.thermo,
            self.pending,
            self.done,
            (self.clock, self.reals, self.flags, end_of_step, self.keys),
        )
        self.pending = True

    def velocities(self) -> np.ndarray:
        """The stored velocities on the host, ``(R, d, N)`` whichever the ``STORAGE`` (the
        pending thermostat not applied)."""
        stored = self.velocity.copy_to_host()
        return stored.transpose(0, 2, 1) if _STORAGE_IS_PARTICLES[self.storage] else stored

    def check(self, step: int) -> None:
        """RuntimeError if a realization's force step failed or a bound was exceeded."""
        status = self.status.copy_to_host()
        failed = np.flatnonzero(status)
        if failed.size:
            s = self.settings
            per_unit = s.reduced_field * s.time_step / 2.0
            message = _STATUS_MESSAGES[int(status[failed[0]])].format(
                limit=-1.0 / per_unit if per_unit else -math.inf,
                euler=kernels.EULER_LIMIT / per_unit if per_unit else math.inf,
            )
            raise RuntimeError(
                f"realization {failed[0]} (of the batch), by step {step} (t = "
                f"{step * s.time_step:.6g} τ) of the run with {s.parameters()} on the GPU: "
                f"{message}; reduce time_step or reduced_field"
            )


def _start_thermo(tops: np.ndarray) -> np.ndarray:
    """``thermo`` at the start (``_N_THERMO`` columns a realization): no thermostat (u = 0,
    scale 1) and the largest speed of each realization's start, ``tops``."""
    thermo = np.zeros((tops.shape[0], _N_THERMO))
    thermo[:, _SCALE] = 1.0
    thermo[:, _TOP] = tops
    return thermo


_PREFETCHED: dict[tuple, Any] = {}
_PREFETCHER: list = []  # the one worker thread, made on first use


def prefetch_starts(dimension: int, n_particles: int, streams: np.ndarray) -> None:
    """Build the Maxwellian starts of a run that comes next (``maxwellian_starts``) in a
    worker thread, while this thread runs the current one: the compiled draw releases
    the GIL, and the current run's host thread mostly waits for the GPU or launches
    kernels. ``_Batch`` takes them when it starts that run (the same numbers as built on
    the spot). The host then holds two runs' velocities at once (24 bytes a particle
    each, inside ``cost.DSMC_GPU_BYTES_PER_PARTICLE``)."""
    from concurrent.futures import ThreadPoolExecutor

    key = (dimension, n_particles, np.ascontiguousarray(streams, dtype=np.uint64).tobytes())
    if key in _PREFETCHED:
        return
    if not _PREFETCHER:
        _PREFETCHER.append(ThreadPoolExecutor(max_workers=1, thread_name_prefix="starts"))
    _PREFETCHED[key] = _PREFETCHER[0].submit(
        maxwellian_starts, dimension, n_particles, np.array(streams, dtype=np.uint64)
    )


def _take_starts(dimension: int, n_particles: int, streams: np.ndarray):
    """The starts of ``streams``: those ``prefetch_starts`` built, else built now."""
    key = (dimension, n_particles, np.ascontiguousarray(streams, dtype=np.uint64).tobytes())
    future = _PREFETCHED.pop(key, None)
    if future is not None:
        return future.result()
    return maxwellian_starts(dimension, n_particles, streams)


def _settings_arrays(settings: HomogeneousSettings, samples: Samples):
    """The device arrays ``reals`` (float64) and ``flags`` (int64) the kernels read."""
    s = settings
    reals = np.zeros(9)
    reals[_RESTITUTION] = s.restitution
    reals[_PAIR_BASE] = s.pair_coefficient * (s.n_particles - 1)
    reals[_DURATION] = s.time_step * s.tau
    reals[_TARGET] = s.target_energy
    reals[_RATE_EXPONENT] = units.rate_exponent(s.kernel)
    reals[_INVERSE_V0] = 1.0 / units.thermal_speed(1.0)
    reals[_CX_LOW] = -samples.cx_max
    reals[_INVERSE_CX] = 1.0 / (2.0 * samples.cx_max / samples.n_cx_bins)
    reals[_INVERSE_SPEED] = 1.0 / (samples.speed_max / samples.n_speed_bins)
    flags = np.zeros(6, dtype=np.int64)
    flags[_KERNEL] = _KERNEL_ID[s.kernel]
    flags[_POISSON] = s.selection == "poisson"
    flags[_EXACT] = s.force_step == "exact"
    flags[_N_CX] = samples.n_cx_bins
    flags[_N_SPEED] = samples.n_speed_bins
    flags[_N] = s.n_particles
    return to_device(reals), to_device(flags)


def run_batch(
    settings: HomogeneousSettings,
    samples: Samples,
    streams: np.ndarray,
    n_windows: int,
    steps_per_window: int,
    first_histogram_window: int,
    out: dict[str, np.ndarray],
    progress=None,
) -> None:
    """Run the realizations of ``streams`` (one row each) together on the GPU.

    Fills ``out``, the per-window and per-realization arrays of ``simulate_homogeneous``
    (``homogeneous._empty_results``); ``cpu_seconds`` is the wall time of the run
    (launches and the GPU), compilation excluded, divided by the number of
    realizations. ``progress`` (a ``Progress`` over realizations x windows) is updated
    once per window.
    """
    count = streams.shape[0]
    _compile_outside_the_timer(settings, samples)
    batch = _Batch(settings, samples, streams)
    zeros = np.zeros((count, N_MOMENTS))
    synchronize()
    start = time.perf_counter()
    step = 0
    histogram_snapshots = 0
    for w in range(n_windows):
        batch.moment_sums.copy_to_device(zeros)
        histogram = w >= first_histogram_window
        count_w = 0
        for _ in range(steps_per_window):
            sample = (step + 1) % samples.stride == 0
            batch.step(sample, histogram)
            count_w += sample
            step += 1
        batch.check(step)
        sums = batch.moment_sums.copy_to_host()
        clock = batch.clock.copy_to_host()
        accepted = batch.accepted_collisions()
        out["snapshots"][:, w] = count_w
        if count_w:
            out["moments"][:, w] = sums / count_w
        if histogram:
            histogram_snapshots += count_w
        out["log_temperature"][:, w] = clock[:, 1]
        out["cooling_sum"][:, w] = clock[:, 4]
        out["time_free"][:, w] = clock[:, 2] / settings.tau
        out["collisions_per_particle"][:, w] = 2.0 * accepted / settings.n_particles
        if progress is not None:
            progress.update(count)
    tally = batch.tally.copy_to_host().sum(axis=1)
    synchronize()
    elapsed = time.perf_counter() - start
    if tally[:, kernels.TALLY_EXCEEDED].any():
        raise RuntimeError(
            "internal error: the collision bound was exceeded "
            f"{tally[:, kernels.TALLY_EXCEEDED].sum()} times although it is kept rigorous"
        )
    cx_counts, cx_weights, speed_counts = (h.copy_to_host() for h in batch.histograms)
    cx_weights = cx_weights * WEIGHT_UNIT
    out["cx_counts"][:] = cx_counts[:, 1:-1]
    out["cx_outside"][:] = cx_counts[:, [0, -1]]
    out["cx_weights"][:] = cx_weights[:, 1:-1]
    out["cx_outside_weights"][:] = cx_weights[:, [0, -1]]
    out["speed_counts"][:] = speed_counts[:, :-1]
    out["speed_overflow"][:] = speed_counts[:, -1]
    out["observations"][:] = histogram_snapshots * settings.n_particles
    out["collisions"][:] = tally[:, kernels.TALLY_ACCEPTED]
    out["candidates"][:] = tally[:, kernels.TALLY_CANDIDATES]
    out["bound_raises"][:] = tally[:, kernels.TALLY_RAISED]
    out["steps"][:] = step
    out["cpu_seconds"][:] = elapsed / count


def _compile_outside_the_timer(settings: HomogeneousSettings, samples: Samples) -> None:
    """One sampled step of a tiny batch with the same argument types, so that the timed
    run does not include numba-cuda's compilation, which goes to the cache once
    (``kinetic.gpu.warm``; skipped under the simulator)."""
    if simulated():
        return
    tiny = HomogeneousSettings(**{**settings.parameters_init(), "n_particles": 4})

    def compile_kernels():  # the cache then holds every kernel
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NumbaPerformanceWarning)  # a grid of one block
            streams = np.array([[1, 2, 3, 4]], dtype=np.uint64)
            batch = _Batch(tiny, samples, streams)
            batch.step(sample=True, histogram=True)
            batch.accepted_collisions()
            synchronize()

    warm("cuda_dsmc", "dsmc", compile_kernels)


# the kernels over particles, compiled once for each storage (``_BY_PARTICLE``), after
# every function they call is defined (a copy reads the module's names as they are here)
_collide_sparse = kernel_variants(_collide_sparse, "_BY_PARTICLE", _STORAGE_IS_PARTICLES)
_force = kernel_variants(_force, "_BY_PARTICLE", _STORAGE_IS_PARTICLES)
_observe = kernel_variants(_observe, "_BY_PARTICLE", _STORAGE_IS_PARTICLES)
