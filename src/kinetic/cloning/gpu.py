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
   λ >= 0, max K_i for λ < 0), and their inclusive float64 scan in index order.
3. *Select*: systematic resampling keeps N_c clones: slot j takes the clone whose
   cumulative weight first exceeds (u + j)/N_c of the total (one uniform u per
   realization and interval). μ(λ) accumulates ln(Σw/N_c) - λK*, i.e. ln<e^{-λK}>, and
   the population after selection (distributed as the eigenfunction f̃(v, λ) of
   visco2008 Eq. 28) gives the snapshot moments, rate and velocity histogram.

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

Determinism: the float sums (weights' scan, block sums) are folded in a fixed order, the
histogram counts and K*, max speed by integer (or max) atomics, whose results do not
depend on the order: the same seed gives the same numbers on the same GPU model.
Clone i of realization r draws from ``thread_state(row r, i)``; the selection uniforms from
row r itself.
"""

from __future__ import annotations

import math
import time

import numpy as np

from kinetic.cloning import kernels
from kinetic.gpu import (
    BLOCK,
    block_exclusive_scan,
    block_reduce_sum,
    cuda,
    device_function,
    fold_partials,
    grid,
    to_device,
)
from kinetic.rng import (
    thread_state,
    xoshiro_exponential,
    xoshiro_normal_pair,
    xoshiro_uniform,
)

__all__ = ["run"]

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

# columns of the per-block partial sums written by the kernels
_COUNT_FIELDS = ("elastic_collisions", "candidates")
_SNAPSHOT_FIELDS = ("integral_v2", "integral_v4", "integral_rate")
_FIELD = {name: k for k, name in enumerate(kernels.BLOCK_FIELDS)}
_ELAPSED = _FIELD["elapsed_time"]
_NET = _FIELD["net_compensations"]


@cuda.jit
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


@cuda.jit
def _advance(velocity, states, counts, extremes, partials, code, interval, rate_a):
    """One control interval of the untilted process for every clone (thread (i, r))."""
    shared = cuda.shared.array(BLOCK, np.float64)
    i = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    r = cuda.blockIdx.y
    n = states.shape[1]
    d = velocity.shape[1]
    collisions = 0
    candidates = 0
    if i < n:
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
                if t > interval:
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
                if t > interval:
                    break
                candidates += 1
                collisions += 1
                _, s0, s1, s2, s3, waiting, held = _maxwell(
                    members, i, s0, s1, s2, s3, waiting, held
                )
        states[r, i, 0] = s0
        states[r, i, 1] = s1
        states[r, i, 2] = s2
        states[r, i, 3] = s3
        counts[r, i] = collisions
        cuda.atomic.min(extremes, (r, 0), collisions)
        cuda.atomic.max(extremes, (r, 1), collisions)
    total = block_reduce_sum(shared, float(collisions))
    if cuda.threadIdx.x == 0:
        partials[r, cuda.blockIdx.x, 0] = total
    total = block_reduce_sum(shared, float(candidates))
    if cuda.threadIdx.x == 0:
        partials[r, cuda.blockIdx.x, 1] = total


@cuda.jit
def _weigh(counts, extremes, lam, cumulative, block_sums):
    """w_i = e^{-λ(K_i - K*)} and its inclusive scan inside each thread block (a fixed
    Hillis-Steele tree); the block's total in ``block_sums``."""
    shared = cuda.shared.array(BLOCK, np.float64)
    t = cuda.threadIdx.x
    i = cuda.blockIdx.x * cuda.blockDim.x + t
    r = cuda.blockIdx.y
    n = counts.shape[1]
    shift = extremes[r, 0] if lam >= 0.0 else extremes[r, 1]
    value = 0.0
    if i < n:
        value = math.exp(-lam * (counts[r, i] - shift))
    shared[t] = value
    cuda.syncthreads()
    offset = 1
    while offset < BLOCK:
        add = shared[t - offset] if t >= offset else 0.0
        cuda.syncthreads()
        shared[t] += add
        cuda.syncthreads()
        offset *= 2
    if i < n:
        cumulative[r, i] = shared[t]
    if t == BLOCK - 1:
        block_sums[r, cuda.blockIdx.x] = shared[t]


@cuda.jit
def _close_interval(block_sums, extremes, controls, lam, totals, uniforms, out, interval):
    """One thread block per realization: the block offsets (exclusive scan of the block
    totals, in a fixed order), then, in thread 0, the selection uniform and N_c ln<w>
    into the block's ``net_compensations``. ``extremes[r]`` holds (K min, K max, N_c); K
    min and max are reset for the next interval."""
    shared = cuda.shared.array(BLOCK, np.float64)
    r = cuda.blockIdx.x
    total = block_exclusive_scan(shared, block_sums[r], block_sums.shape[1])
    if cuda.threadIdx.x != 0:
        return
    totals[r] = total
    s0 = controls[r, 0]
    s1 = controls[r, 1]
    s2 = controls[r, 2]
    s3 = controls[r, 3]
    u, s0, s1, s2, s3 = _uniform(s0, s1, s2, s3)
    controls[r, 0] = s0
    controls[r, 1] = s1
    controls[r, 2] = s2
    controls[r, 3] = s3
    uniforms[r] = u
    shift = extremes[r, 0] if lam >= 0.0 else extremes[r, 1]
    n_clones = extremes[r, 2]
    out[r, _ELAPSED] += interval
    out[r, _NET] += n_clones * (math.log(total / n_clones) - lam * shift)
    extremes[r, 0] = _NO_MIN
    extremes[r, 1] = -1


@cuda.jit
def _select(source, target, cumulative, block_offsets, totals, uniforms, observers):
    """Slot j of realization r takes the clone whose cumulative weight first exceeds
    (u + j)/N_c of the total; then the snapshot sums and histogram of the new population."""
    shared = cuda.shared.array(BLOCK, np.float64)
    partials, table, table_step, histogram, half_width, block_max, record = observers
    j = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    r = cuda.blockIdx.y
    n = cumulative.shape[1]
    d = source.shape[1]
    v2 = 0.0
    v4 = 0.0
    rate = 0.0
    if j < n:
        goal = (uniforms[r] + j) * totals[r] / n
        lo = 0
        hi = n - 1
        while lo < hi:  # first i with cumulative weight > goal
            mid = (lo + hi) // 2
            if cumulative[r, mid] + block_offsets[r, mid // BLOCK] > goal:
                hi = mid
            else:
                lo = mid + 1
        bins = histogram.shape[1]
        for k in range(d):
            value = source[r, k, lo]
            target[r, k, j] = value
            v2 += value * value
            if record:
                b = math.floor((value + half_width) * bins / (2.0 * half_width))
                if 0 <= b < bins:
                    cuda.atomic.add(histogram, (r, b), 1)
        v4 = v2 * v2
        speed = math.sqrt(v2)
        rate = _tabulated_rate(speed, table, table_step)
        cuda.atomic.max(block_max, r, speed)
    total = block_reduce_sum(shared, v2)
    if cuda.threadIdx.x == 0:
        partials[r, cuda.blockIdx.x, 0] = total
    total = block_reduce_sum(shared, v4)
    if cuda.threadIdx.x == 0:
        partials[r, cuda.blockIdx.x, 1] = total
    total = block_reduce_sum(shared, rate)
    if cuda.threadIdx.x == 0:
        partials[r, cuda.blockIdx.x, 2] = total


def run(p, durations, n_transient, rows, progress):
    """Run every realization of ``rows`` (one ``stream_states`` row each) at once.

    ``p`` are the validated parameters of ``kinetic.cloning.simulate``, ``durations`` the
    block durations (the first ``n_transient`` discarded); each block is cut into whole
    control intervals of at most ``p["control_interval"]``. Returns ``(blocks, histograms,
    distinct, seconds)`` shaped as the CPU engine's: per-block sums (realization, block,
    field), velocity-component densities, distinct final velocities per realization and
    the wall time per realization (the run's wall time shared equally).
    """
    from kinetic.cloning.rates import TABLE_STEP, rate_table

    count, n, d = rows.shape[0], p["population"], p["dimension"]
    lam = p["lam"]
    n_bins = p["histogram_bins"]
    launch = ((grid(n), count), BLOCK)
    started = time.perf_counter()
    velocity = [cuda.device_array((count, d, n)), cuda.device_array((count, d, n))]
    states = cuda.device_array((count, n, 4), dtype=np.uint64)
    _seed[launch](states, velocity[0], to_device(rows))
    controls = to_device(rows)
    counts = cuda.device_array((count, n), dtype=np.int64)
    extremes = to_device(np.tile(np.array([_NO_MIN, -1, n], dtype=np.int64), (count, 1)))
    cumulative = cuda.device_array((count, n))
    block_sums = cuda.device_array((count, grid(n)))
    totals = cuda.device_array(count)
    uniforms = cuda.device_array(count)
    count_partials = cuda.device_array((count, grid(n), len(_COUNT_FIELDS)))
    snapshot_partials = cuda.device_array((count, grid(n), len(_SNAPSHOT_FIELDS)))
    count_fields = to_device(np.array([_FIELD[f] for f in _COUNT_FIELDS], dtype=np.int64))
    snapshot_fields = to_device(np.array([_FIELD[f] for f in _SNAPSHOT_FIELDS], dtype=np.int64))
    histogram = to_device(np.zeros((count, n_bins), dtype=np.int64))
    blocks = to_device(np.zeros((count, len(durations), len(kernels.BLOCK_FIELDS))))
    table = to_device(rate_table(p["kernel"], d))
    code = kernels.HARD_SPHERES if p["kernel"] == "hard_spheres" else kernels.MAXWELL
    rate_a = kernels.channel_a_rate(d)
    snapshots = 0
    for b, duration in enumerate(durations):
        steps = max(1, math.ceil(duration / p["control_interval"] - 1e-9))
        interval = duration / steps
        out = blocks[:, b, :]
        record = b >= n_transient
        snapshots += steps if record else 0
        observers = (
            snapshot_partials,
            table,
            TABLE_STEP,
            histogram,
            p["histogram_half_width"],
            blocks[:, b, _FIELD["max_speed"]],
            record,
        )
        for _ in range(steps):
            _advance[launch](
                velocity[0], states, counts, extremes, count_partials, code, interval, rate_a
            )
            _weigh[launch](counts, extremes, lam, cumulative, block_sums)
            _close_interval[count, BLOCK](
                block_sums, extremes, controls, lam, totals, uniforms, out, interval
            )
            _select[launch](
                velocity[0], velocity[1], cumulative, block_sums, totals, uniforms, observers
            )
            fold_partials(count_partials, out, count_fields, 1.0)
            fold_partials(snapshot_partials, out, snapshot_fields, interval)
            velocity.reverse()
        cuda.synchronize()
        progress.update(count * duration)
    sums = blocks.copy_to_host()
    sums[:, :, _FIELD["collision_events"]] = sums[:, :, _FIELD["elastic_collisions"]]
    sums[:, :, _FIELD["proposals"]] = sums[:, :, _FIELD["candidates"]]
    bin_width = 2.0 * p["histogram_half_width"] / n_bins
    densities = histogram.copy_to_host() / (max(snapshots, 1) * d * n * bin_width)
    final = velocity[0].copy_to_host()
    distinct = np.array([np.unique(final[r, 0]).size for r in range(count)], dtype=float)
    seconds = np.full(count, (time.perf_counter() - started) / count)
    return sums, densities, distinct, seconds
