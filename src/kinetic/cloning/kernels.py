"""Numba kernels of the cloning Monte Carlo (visco2008 §IV.A, Eqs. 51-56).

A population of ``n`` independent tagged particles, each in an equilibrium bath at
T0 = 1, evolves under the tilted linear Boltzmann operator of visco2008 Eq. (28),

    L_λ f = e^{-λ} Gain[f] - Loss[f],

realised as a branching process: every collision is kept (elastic post-collision
velocity) with probability e^{-λ}; otherwise the particle is annihilated (λ > 0) or
duplicated (λ < 0, at the collision rate multiplied by 2e^{-λ} - 1 with keep probability
e^{-λ}/(2e^{-λ} - 1), i.e. the time rescaling of Eq. 56 read in the original time). The
population is held at ``n`` by cloning (resp. removing) a uniformly chosen *other* member,
and μ(λ) is the net rate of duplications minus annihilations per member.

Units: m = 1, T0 = 1 and time in mean free times of the bath (ω = 1, visco2008 Eq. 7).

Collision sampling is exact (no time step). For hard spheres the rate density of a
collision with apse direction σ̂ (uniform on the unit sphere) and bath normal velocity
u = v2·σ̂ ~ N(0, 1) is K (v·σ̂ - u)⁺ with K = √π, which gives ω = 1 in every dimension
(g·σ̂ ~ N(0, 2) so <(g·σ̂)⁺> = 1/√π) and r(0) = 1/√2 (Eq. 36). The post-collision
velocity is v' = v - (v·σ̂ - u) σ̂: the normal component is replaced by u. Candidates are
proposed with the majorant K[(v·σ̂)⁺ + (-u)⁺] ≥ K(v·σ̂ - u)⁺, split in two channels:

- channel A, rate K1·|v| (K1 = K β_d/Ω_d: 1/√π in d = 2, √π/4 in d = 3): σ̂ drawn with
  density ∝ (v̂·σ̂)⁺, u ~ N(0, 1);
- channel B, rate K/√(2π) = 1/√2: σ̂ uniform, u = -Rayleigh (density ∝ (-u)⁺ φ(u));

and accepted with probability (v·σ̂ - u)⁺ / [(v·σ̂)⁺ + (-u)⁺]. At population level the
particle is chosen uniformly and channel A/B/rejection is decided against the global
bound K1·v_max + 1/√2, where v_max ≥ max_i |v_i| is recomputed at every block start and
every n/4 collision events (an O(n) scan per O(n) events: the bound follows the fastest
member down when it slows or is replaced) and raised the moment a collision produces a
faster particle. Velocities change only at
events, so the bound is predictable and the thinning is exact (uniformisation).

Maxwell molecules: constant rate ω = 1 per particle, σ̂ uniform, u ~ N(0, 1), same
post-collision rule (isotropic scattering); every candidate is a collision.

Time bookkeeping: the uniformised chain has candidates at total rate
Λ = c_λ · n · bound; each candidate advances time by its conditional mean 1/Λ instead of
an exponential variate (Rao-Blackwellisation: the population's jump chain and every
time average are unchanged, one logarithm per candidate is saved and the variance of
μ drops).

Arrays are struct-of-arrays: ``velocity[k, i]`` is component k (0 <= k < d) of member i,
shape (d, n), C order; ``speed[i] = |velocity[:, i]|``; ``state`` is one xoshiro256+ row
(4 uint64) from ``kinetic.rng.stream_states``, advanced in place.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from kinetic.gas import HARD_SPHERES, MAXWELL
from kinetic.jit import inline, kernel, refcount_free
from kinetic.rng import (
    load_state,
    store_state,
    xoshiro_disk_point,
    xoshiro_normal_pair,
    xoshiro_uniform,
    xoshiro_uniform_open,
    xoshiro_unit_3d,
)

__all__ = [
    "BLOCK_FIELDS",
    "HARD_SPHERES",
    "MAXWELL",
    "Observers",
    "compensation_parameters",
    "draw_population",
    "run_blocks",
]


BLOCK_FIELDS = (
    "elapsed_time",  # time the block covered
    "net_compensations",  # duplications - annihilations (= clones removed - clones made)
    "elastic_collisions",  # kept collisions
    "collision_events",  # kept + annihilating/duplicating collisions
    "candidates",  # proposals of the uniformised chain, rejected ones included
    "proposals",  # candidates that reached the collision-acceptance test (hard spheres)
    "integral_v2",  # ∫ Σ_i |v_i|² dt over the block
    "integral_v4",  # ∫ Σ_i |v_i|⁴ dt over the block
    "integral_rate",  # ∫ Σ_i r(|v_i|) dt over the block (r from the rate table)
    "max_speed",  # largest velocity bound used in the block
)
"""Columns of the ``blocks`` output array of ``run_blocks``, in order."""

_SQRT_PI = math.sqrt(math.pi)
_RATE_AT_REST = 1.0 / math.sqrt(2.0)  # r(0)/ω, visco2008 Eq. (36); also channel B's rate
#: the hard-sphere bound's v_max is rescanned from the population every
#: ``_REBUILD_EVENTS_PER_MEMBER`` x n collision events (an O(n) scan per O(n) events)
_REBUILD_EVENTS_PER_MEMBER = 0.25


@kernel
def compensation_parameters(lam):
    """Rate factor c_λ and keep probability of a collision for the tilt ``lam``.

    λ >= 0: events at the collision rate (c = 1), kept with probability e^{-λ}, else the
    particle is annihilated. λ < 0: events at c = 2e^{-λ} - 1 times the collision rate,
    kept with probability e^{-λ}/c, else the particle is duplicated (Eq. 56).
    Returns ``(rate_factor, keep_probability, duplicating)``.
    """
    if lam >= 0.0:
        return 1.0, math.exp(-lam), False
    factor = 2.0 * math.exp(-lam) - 1.0
    return factor, math.exp(-lam) / factor, True


@kernel
def channel_a_rate(d):
    """K1 = √π β_d/Ω_d: channel-A rate per unit speed (1/√π in d = 2, √π/4 in d = 3)."""
    if d == 2:
        return 1.0 / _SQRT_PI
    return _SQRT_PI / 4.0


@inline
def _normal(s0, s1, s2, s3, waiting, held):
    """A standard normal variate, the stream and the cache in scalars (loops keep them in
    registers): the polar method's second variate is ``held`` while ``waiting``.
    Returns ``(z, s0, s1, s2, s3, waiting, held)``."""
    if waiting:
        return held, s0, s1, s2, s3, False, held
    z0, z1, s0, s1, s2, s3 = xoshiro_normal_pair(s0, s1, s2, s3)
    return z0, s0, s1, s2, s3, True, z1


@inline
def _hard_sphere_proposal_2d(vx, vy, speed, use_channel_a, s0, s1, s2, s3, waiting, held):
    """One hard-disk candidate of member with velocity (vx, vy) and |v| = ``speed``.

    Channel A (``use_channel_a``): σ̂ at angle θ from v̂ with sin θ uniform on (-1, 1)
    (density ∝ cos θ), u ~ N(0, 1). Channel B: σ̂ uniform and u = -Rayleigh from one
    disk point. The stream and the normal cache are scalars (see ``_normal``).
    Returns ``(accepted, new_vx, new_vy, s0, s1, s2, s3, waiting, held)``.
    """
    if use_channel_a:
        w, s0, s1, s2, s3 = xoshiro_uniform(s0, s1, s2, s3)
        sin_t = 2.0 * w - 1.0
        cos_t = math.sqrt(1.0 - sin_t * sin_t)
        nx = vx / speed
        ny = vy / speed
        sx = cos_t * nx - sin_t * ny
        sy = cos_t * ny + sin_t * nx
        a = speed * cos_t
        u, s0, s1, s2, s3, waiting, held = _normal(s0, s1, s2, s3, waiting, held)
        majorant = a + max(-u, 0.0)
    else:
        x, y, r2, s0, s1, s2, s3 = xoshiro_disk_point(s0, s1, s2, s3)
        inv = 1.0 / math.sqrt(r2)
        sx = x * inv
        sy = y * inv
        u = -math.sqrt(-2.0 * math.log(r2))
        a = vx * sx + vy * sy
        majorant = max(a, 0.0) - u
    gap = a - u
    if gap <= 0.0:
        return False, vx, vy, s0, s1, s2, s3, waiting, held
    w, s0, s1, s2, s3 = xoshiro_uniform(s0, s1, s2, s3)
    if w * majorant >= gap:
        return False, vx, vy, s0, s1, s2, s3, waiting, held
    return True, vx - gap * sx, vy - gap * sy, s0, s1, s2, s3, waiting, held


@inline
def _hard_sphere_proposal_3d(vx, vy, vz, speed, use_channel_a, s0, s1, s2, s3, waiting, held):
    """One hard-sphere candidate in d = 3; see ``_hard_sphere_proposal_2d``.

    Channel A draws σ̂ = (v̂ + w)/|v̂ + w| with w uniform on S², which has density ∝
    (v̂·σ̂)⁺ (Lambert's law); channel B draws σ̂ uniform and u = -√(-2 ln U).
    Returns ``(accepted, new_vx, new_vy, new_vz, s0, s1, s2, s3, waiting, held)``.
    """
    wx, wy, wz, s0, s1, s2, s3 = xoshiro_unit_3d(s0, s1, s2, s3)
    if use_channel_a:
        inv_speed = 1.0 / speed
        px = vx * inv_speed + wx
        py = vy * inv_speed + wy
        pz = vz * inv_speed + wz
        norm2 = px * px + py * py + pz * pz
        if norm2 <= 0.0:  # w = -v̂ exactly: probability zero, treat as a rejection
            return False, vx, vy, vz, s0, s1, s2, s3, waiting, held
        inv = 1.0 / math.sqrt(norm2)
        sx = px * inv
        sy = py * inv
        sz = pz * inv
        u, s0, s1, s2, s3, waiting, held = _normal(s0, s1, s2, s3, waiting, held)
        a = vx * sx + vy * sy + vz * sz
        majorant = max(a, 0.0) + max(-u, 0.0)
    else:
        sx = wx
        sy = wy
        sz = wz
        w, s0, s1, s2, s3 = xoshiro_uniform_open(s0, s1, s2, s3)
        u = -math.sqrt(-2.0 * math.log(w))
        a = vx * sx + vy * sy + vz * sz
        majorant = max(a, 0.0) - u
    gap = a - u
    if gap <= 0.0:
        return False, vx, vy, vz, s0, s1, s2, s3, waiting, held
    w, s0, s1, s2, s3 = xoshiro_uniform(s0, s1, s2, s3)
    if w * majorant >= gap:
        return False, vx, vy, vz, s0, s1, s2, s3, waiting, held
    return True, vx - gap * sx, vy - gap * sy, vz - gap * sz, s0, s1, s2, s3, waiting, held


@inline
def _maxwell_collision(velocity, i, s0, s1, s2, s3, waiting, held):
    """Elastic Maxwell-molecule collision of member ``i``, in place.

    σ̂ uniform, bath normal velocity u ~ N(0, 1): the component of v_i along σ̂ becomes u.
    Returns ``(new squared speed, s0, s1, s2, s3, waiting, held)``.
    """
    d = velocity.shape[0]
    u, s0, s1, s2, s3, waiting, held = _normal(s0, s1, s2, s3, waiting, held)
    if d == 2:
        x, y, r2, s0, s1, s2, s3 = xoshiro_disk_point(s0, s1, s2, s3)
        inv = 1.0 / math.sqrt(r2)
        sx = x * inv
        sy = y * inv
        vx = velocity[0, i]
        vy = velocity[1, i]
        gap = vx * sx + vy * sy - u
        vx -= gap * sx
        vy -= gap * sy
        velocity[0, i] = vx
        velocity[1, i] = vy
        return vx * vx + vy * vy, s0, s1, s2, s3, waiting, held
    sx, sy, sz, s0, s1, s2, s3 = xoshiro_unit_3d(s0, s1, s2, s3)
    vx = velocity[0, i]
    vy = velocity[1, i]
    vz = velocity[2, i]
    gap = vx * sx + vy * sy + vz * sz - u
    vx -= gap * sx
    vy -= gap * sy
    vz -= gap * sz
    velocity[0, i] = vx
    velocity[1, i] = vy
    velocity[2, i] = vz
    return vx * vx + vy * vy + vz * vz, s0, s1, s2, s3, waiting, held


@inline
def _other_member(i, n, s0, s1, s2, s3):
    """A member index uniform over {0, ..., n-1} minus {i} (n >= 2):
    ``(j, s0, s1, s2, s3)``."""
    w, s0, s1, s2, s3 = xoshiro_uniform(s0, s1, s2, s3)
    j = int(w * (n - 1))
    if j >= i:
        j += 1
    return j, s0, s1, s2, s3


@inline
def _copy_member(velocity, speed, source, target):
    """Member ``target`` becomes a clone of member ``source``."""
    for k in range(velocity.shape[0]):
        velocity[k, target] = velocity[k, source]
    speed[target] = speed[source]


@kernel
def draw_population(velocity, speed, state):
    """Fill ``velocity`` (d, n) with bath velocities N(0, T0 = 1) and ``speed`` with |v|."""
    d, n = velocity.shape
    s0, s1, s2, s3 = load_state(state)
    waiting = False
    held = 0.0
    for i in range(n):
        total = 0.0
        for k in range(d):
            value, s0, s1, s2, s3, waiting, held = _normal(s0, s1, s2, s3, waiting, held)
            velocity[k, i] = value
            total += value * value
        speed[i] = math.sqrt(total)
    store_state(state, s0, s1, s2, s3)


@inline
def _tabulated_rate(speed, rate_table, table_step):
    """r(speed) by linear interpolation in ``rate_table`` (r at speeds k·table_step).

    Beyond the table r grows linearly with the slope of its last interval (r(v) ~ K1 v).
    """
    position = speed / table_step
    k = int(position)
    last = rate_table.shape[0] - 2
    if k > last:
        k = last
    fraction = position - k
    return rate_table[k] + fraction * (rate_table[k + 1] - rate_table[k])


@kernel
def _population_sums(velocity, speed, rate_table, table_step):
    """Recompute ``speed`` from ``velocity``; return (Σ|v|², Σ|v|⁴, Σ r(|v|), max |v|)."""
    d, n = velocity.shape
    sum2 = 0.0
    sum4 = 0.0
    sum_rate = 0.0
    largest = 0.0
    for i in range(n):
        s2 = 0.0
        for k in range(d):
            s2 += velocity[k, i] * velocity[k, i]
        speed[i] = math.sqrt(s2)
        sum2 += s2
        sum4 += s2 * s2
        sum_rate += _tabulated_rate(speed[i], rate_table, table_step)
        largest = max(largest, speed[i])
    return sum2, sum4, sum_rate, largest


@inline
def _largest(values):
    """max(values, 0) by a loop: ``ndarray.max`` does not lower in the loop compiled
    without reference counting. Four running maxima, so that the comparisons do not wait
    for each other (one chain is latency-bound; the compiler may not reorder a max of
    floats)."""
    a = 0.0
    b = 0.0
    c = 0.0
    e = 0.0
    n = values.shape[0]
    top = n - n % 4
    for k in range(0, top, 4):
        a = max(a, values[k])
        b = max(b, values[k + 1])
        c = max(c, values[k + 2])
        e = max(e, values[k + 3])
    for k in range(top, n):
        a = max(a, values[k])
    return max(max(a, b), max(c, e))


@kernel
def _snapshot_histogram(velocity, weight, half_width, histogram):
    """Add ``weight`` to the bin of every velocity component in [-half_width, half_width)."""
    d, n = velocity.shape
    n_bins = histogram.shape[0]
    scale = n_bins / (2.0 * half_width)
    for k in range(d):
        for i in range(n):
            position = (velocity[k, i] + half_width) * scale
            if 0.0 <= position < n_bins:
                histogram[int(position)] += weight


class Observers(NamedTuple):
    """What ``run_blocks`` records: ``blocks`` (float64[n_blocks, len(BLOCK_FIELDS)], one
    row per block), ``histogram`` (float64[n_bins], velocity components on [-half_width,
    half_width)) and, for the ``integral_rate`` column, ``rate_table`` (the collision rate
    of one member at the speeds k·table_step)."""

    blocks: np.ndarray
    half_width: float
    histogram: np.ndarray
    rate_table: np.ndarray
    table_step: float


@refcount_free
def run_blocks(kernel, lam, velocity, speed, state, block_duration, observers):
    """Advance the population through ``blocks.shape[0]`` blocks of ``block_duration``.

    Parameters
    ----------
    kernel : int
        ``HARD_SPHERES`` or ``MAXWELL``.
    lam : float
        Tilt λ conjugate to the number of collisions.
    velocity : float64[d, n]
        Members' velocities (d = 2 or 3, n >= 2), advanced in place.
    speed : float64[n]
        Work array, overwritten with |velocity[:, i]|.
    state : uint64[4]
        xoshiro256+ state of this realisation, advanced in place.
    block_duration : float
        Time (units 1/ω) per block; a block ends at the first candidate at or past it.
    observers : Observers
        Its fields:
    blocks : float64[n_blocks, len(BLOCK_FIELDS)]
        Output, one row per block (columns in ``BLOCK_FIELDS``).
    half_width : float
        Velocity-component histogram range [-half_width, half_width).
    histogram : float64[n_bins]
        Accumulates, at the end of each block, the population's velocity components
        weighted by the current candidate time step (this makes the snapshots of the
        uniformised chain time averages); the caller normalises.
    rate_table : float64[m], m >= 2
        Collision rate r(k·table_step)/ω of one member, k = 0..m-1, used only for the
        ``integral_rate`` column: since ∫ L_λ f dv = (e^{-λ} - 1) ∫ r f dv (Eq. 28),
        μ = (e^{-λ} - 1) <r> over the population is an estimator with the same
        expectation as the compensation count and without its counting noise.
    table_step : float
        Speed spacing of ``rate_table``.

    Returns the total weight added to ``histogram`` (sum of the snapshot weights).
    The polar-method variate cache is reset at each call, so results do not depend on
    how blocks are split into calls.

    Compiled without reference counting (``kinetic.jit.refcount_free``): 17 % more
    hard-sphere events and 20-30 % more Maxwell events per second, the same numbers.
    The stream (``state``) and the polar method's held variate live in scalars during the
    loop, the stream stored back at the end: in memory, every velocity store would force
    them to be reloaded (numba cannot prove that the arrays do not alias), on the critical
    path of every draw.
    """
    blocks = observers.blocks
    half_width = observers.half_width
    histogram = observers.histogram
    rate_table = observers.rate_table
    table_step = observers.table_step
    d, n = velocity.shape
    rate_factor, keep, duplicating = compensation_parameters(lam)
    always_keep = keep >= 1.0
    k1 = channel_a_rate(d)
    s0, s1, s2, s3 = load_state(state)
    waiting = False
    held = 0.0
    histogram_weight = 0.0
    for block in range(blocks.shape[0]):
        sum2, sum4, sum_rate, v_max = _population_sums(velocity, speed, rate_table, table_step)
        bound = k1 * v_max + _RATE_AT_REST if kernel == HARD_SPHERES else 1.0
        dt = 1.0 / (rate_factor * n * bound)
        block_max = v_max
        elapsed = 0.0
        net = 0
        elastic = 0
        events = 0
        candidates = 0
        proposals = 0
        rebuild_every = max(1, int(_REBUILD_EVENTS_PER_MEMBER * n))
        next_rebuild = rebuild_every
        integral2 = 0.0
        integral4 = 0.0
        integral_rate = 0.0
        while elapsed < block_duration:
            # the state before this candidate held during its waiting time
            integral2 += sum2 * dt
            integral4 += sum4 * dt
            integral_rate += sum_rate * dt
            elapsed += dt
            candidates += 1
            w, s0, s1, s2, s3 = xoshiro_uniform(s0, s1, s2, s3)
            position = w * n
            i = int(position)
            if i >= n:  # guard against rounding of uniform * n
                i = n - 1
            if kernel == HARD_SPHERES:
                threshold = (position - i) * bound
                if threshold < _RATE_AT_REST:
                    use_a = False
                elif threshold < _RATE_AT_REST + k1 * speed[i]:
                    use_a = True
                else:
                    continue  # thinned: no event
                proposals += 1
                if d == 2:
                    accepted, nx, ny, s0, s1, s2, s3, waiting, held = _hard_sphere_proposal_2d(
                        velocity[0, i], velocity[1, i], speed[i], use_a, s0, s1, s2, s3, waiting,
                        held,
                    )  # fmt: skip
                    nz = 0.0
                else:
                    accepted, nx, ny, nz, s0, s1, s2, s3, waiting, held = (
                        _hard_sphere_proposal_3d(
                            velocity[0, i], velocity[1, i], velocity[2, i], speed[i], use_a,
                            s0, s1, s2, s3, waiting, held,
                        )
                    )  # fmt: skip
                if not accepted:
                    continue
                events += 1
                if events >= next_rebuild:
                    # the fastest member may have changed: scan for the current maximum
                    # (the bound only ever has to cover the speeds of now)
                    next_rebuild = events + rebuild_every
                    v_max = _largest(speed)
                    bound = k1 * v_max + _RATE_AT_REST
                    dt = 1.0 / (rate_factor * n * bound)
                kept = always_keep
                if not kept:
                    w, s0, s1, s2, s3 = xoshiro_uniform(s0, s1, s2, s3)
                    kept = w < keep
                if kept:
                    old2 = speed[i] * speed[i]
                    velocity[0, i] = nx
                    velocity[1, i] = ny
                    new2 = nx * nx + ny * ny
                    if d == 3:
                        velocity[2, i] = nz
                        new2 += nz * nz
                    elastic += 1
                else:
                    old2 = -1.0
            else:
                proposals += 1
                events += 1
                kept = always_keep
                if not kept:
                    w, s0, s1, s2, s3 = xoshiro_uniform(s0, s1, s2, s3)
                    kept = w < keep
                if kept:
                    old2 = speed[i] * speed[i]
                    new2, s0, s1, s2, s3, waiting, held = _maxwell_collision(
                        velocity, i, s0, s1, s2, s3, waiting, held
                    )
                    elastic += 1
                else:
                    old2 = -1.0
            if old2 >= 0.0:  # elastic: member i has a new velocity
                new_speed = math.sqrt(new2)
                sum_rate += _tabulated_rate(new_speed, rate_table, table_step) - _tabulated_rate(
                    speed[i], rate_table, table_step
                )
                speed[i] = new_speed
                sum2 += new2 - old2
                sum4 += new2 * new2 - old2 * old2
                if new_speed > v_max and kernel == HARD_SPHERES:
                    # raise the bound the moment it would be exceeded
                    v_max = new_speed
                    bound = k1 * v_max + _RATE_AT_REST
                    dt = 1.0 / (rate_factor * n * bound)
                    block_max = max(block_max, v_max)
                continue
            j, s0, s1, s2, s3 = _other_member(i, n, s0, s1, s2, s3)
            if duplicating:
                source = i
                target = j
                net += 1
            else:
                source = j
                target = i
                net -= 1
            old2 = speed[target] * speed[target]
            new2 = speed[source] * speed[source]
            sum_rate += _tabulated_rate(speed[source], rate_table, table_step) - _tabulated_rate(
                speed[target], rate_table, table_step
            )
            _copy_member(velocity, speed, source, target)
            sum2 += new2 - old2
            sum4 += new2 * new2 - old2 * old2
        row = blocks[block]
        row[0] = elapsed
        row[1] = net
        row[2] = elastic
        row[3] = events
        row[4] = candidates
        row[5] = proposals
        row[6] = integral2
        row[7] = integral4
        row[8] = integral_rate
        row[9] = block_max
        # one snapshot a block, the blocks of equal length: each weighs the same (a weight
        # of the step dt, which shrinks when a fast member raises the bound, biased the
        # histogram's temperature by about -0.28/N)
        histogram_weight += 1.0
        _snapshot_histogram(velocity, 1.0, half_width, histogram)
    store_state(state, s0, s1, s2, s3)
    return histogram_weight
