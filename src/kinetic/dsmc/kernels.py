"""Numba kernels of the homogeneous DSMC engine (Bird's method), d = 2 and 3.

Data layout (struct of arrays)
------------------------------
``velocity`` is a C-contiguous float64 array of shape ``(d, N)``: ``velocity[k, i]`` is
component k of particle i (row k holds one component of every particle, so each row is
contiguous). Units: m = σ = 1; a temperature T means ``<|v - u|^2> = d T``.

Collision model
---------------
A pair (i, j) with relative velocity g = v_i - v_j and unit vector σ̂ (uniform on the
full sphere, σ̂ and -σ̂ give the same collision) collides at the rate
``pair_rate(g, σ̂) ∝ K(|g·σ̂|)``: hard spheres K = |g·σ̂|, Maxwell molecules K = const,
very hard particles K = (g·σ̂)². Inelastic smooth spheres with restitution α:

    v_i' = v_i - (1 + α)/2 (g·σ̂) σ̂,    v_j' = v_j + (1 + α)/2 (g·σ̂) σ̂.

Momentum is conserved exactly, the energy changes by -(1 - α²)(g·σ̂)²/4.

Selection: candidate pairs are drawn uniformly among the n(n-1)/2 pairs of a range at
the rate ``pair_coefficient * n(n-1)/2 * B**p`` (p = 1 hard spheres, 0 Maxwell, 2 very
hard particles) and accepted with probability ``K / K(B)``. ``B`` is a rigorous upper
bound of every relative speed of the range, ``B = s1 + s2`` with ``s1 >= s2`` upper
bounds of the two largest speeds |v_i - c| about a reference velocity ``c`` (any c
works; the range's mean velocity gives the tightest bound). The bound is kept rigorous
at every candidate: after each accepted collision the two new speeds are compared with
``s1, s2`` and the bound (and the candidate rate) is raised at once when a collision
created a faster particle, so an acceptance probability above 1 never occurs. Should a
caller pass a stale bound (velocities changed behind the kernel's back), the first
candidate that exceeds it is detected, counted in ``tally[TALLY_EXCEEDED]``, the bound is
recomputed from the velocities and the run goes on at the corrected candidate rate (that
candidate is dropped); the pairs drawn before the detection were under-sampled, so fronts
treat a nonzero count as an error.

Two clocks: no-time-counter (NTC: deterministic spacing 1/rate between candidates, the
fraction of a candidate left at the end of a call carried in ``carry[0]``) and Poisson
(exponential spacing: exact continuous-time event times by thinning, used by the
tagged-particle observers; memoryless, no carry).

Kernels are reusable by a cell-based engine: ``collide_range`` collides the pairs of
particles ``first..last-1`` (particles sorted by cell). Each range/cell has its own
``bounds``, ``carry`` and ``pair_coefficient`` (which holds its density).

Random numbers: xoshiro256+ streams of :mod:`kinetic.rng`, one ``state`` row (4 uint64)
advanced in place. No kernel allocates inside its loops, prints, or touches files.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from kinetic.gas import HARD_SPHERES, MAXWELL, VERY_HARD
from kinetic.jit import inline, kernel, refcount_free, unlocked
from kinetic.rng import load_state, normal_pair, store_state
from kinetic.rng import xoshiro_exponential as _exponential
from kinetic.rng import xoshiro_next as _next
from kinetic.rng import xoshiro_uniform as _uniform
from kinetic.rng import xoshiro_unit_2d as _unit_2d
from kinetic.rng import xoshiro_unit_3d as _unit_3d

__all__ = [
    "BOUND_SAFETY",
    "HARD_SPHERES",
    "MAXWELL",
    "STATUS_EULER_STEP_TOO_LARGE",
    "STATUS_FORCE_BLOW_UP",
    "STATUS_NONFINITE",
    "STATUS_OK",
    "TALLY_ACCEPTED",
    "TALLY_CANDIDATES",
    "TALLY_EXCEEDED",
    "TALLY_RAISED",
    "VERY_HARD",
    "Collisions",
    "Flights",
    "Forcing",
    "Sampling",
    "accumulate_histograms",
    "accumulate_moments",
    "advance",
    "apply_thermostat",
    "collide_members",
    "collide_observed",
    "collide_range",
    "force_and_thermostat",
    "force_update",
    "maxwellian",
    "speed_bounds",
    "thermostat_sums",
]


TALLY_CANDIDATES = 0
TALLY_ACCEPTED = 1
TALLY_RAISED = 2
TALLY_EXCEEDED = 3

STATUS_OK = 0
STATUS_FORCE_BLOW_UP = 1
STATUS_EULER_STEP_TOO_LARGE = 2
STATUS_NONFINITE = 3

BOUND_SAFETY = 1.0 + 1e-12
"""Relative margin on the relative-speed bound, above floating-point rounding of g."""

EULER_LIMIT = 0.5
"""Largest |ε V_x δt / 2| the Euler force step accepts (beyond it the step is not small)."""


class Collisions(NamedTuple):
    """How a range of particles collides during one call (``collide_range``, ``advance``,
    ``collide_observed``).

    kernel: HARD_SPHERES, MAXWELL or VERY_HARD. restitution: α in (0, 1].
    pair_coefficient: candidate rate per pair per unit bound**p (see the module
    docstring; it holds the range's density and 1/(n - 1)). duration: time of one call
    (>= 0; ``advance``: the time step). poisson: False = NTC clock (carry[0] holds the
    fraction of a candidate carried to the next call), True = exact exponential event
    times (carry unused; ``collide_observed`` always uses them). bounds: (d + 2,)
    float64 from ``speed_bounds`` (kept valid in place). carry: (1,) float64. tally: (4,)
    int64 += candidates, accepted, bound raises, stale-bound detections.
    """

    kernel: int
    restitution: float
    pair_coefficient: float
    duration: float
    poisson: bool
    bounds: np.ndarray
    carry: np.ndarray
    tally: np.ndarray


class Forcing(NamedTuple):
    """montanero2007's heat-flux force and thermostat in ``advance`` (Section 4).

    half_field_step: a = ε δt/2 (0: no force). exact: the exact force step instead of
    the paper's Euler step. strang: force and thermostat for half a step before and
    after the collisions (Strang splitting) instead of a whole step after them (Lie).
    target_energy: the thermostat's kinetic energy per particle. rate_exponent: p of the
    collision rate ∝ T^(p/2) (1 hard spheres, 0 Maxwell, 2 very hard particles), for the
    free-cooling clock.
    """

    half_field_step: float
    exact: bool
    strang: bool
    target_energy: float
    rate_exponent: float


class Sampling(NamedTuple):
    """Snapshot observers of ``advance``: every ``stride``-th step, the moments (``moment_sums``:
    [0] += 1, [1:] += ``accumulate_moments`` with ``inverse_v0``) and, if ``histogram``,
    the histograms of ``accumulate_histograms`` (c_x bins from ``cx_low``, width
    ``cx_width``, into ``cx_counts`` and ``cx_weights``; speed bins of width
    ``speed_width`` into ``speed_counts``)."""

    stride: int
    inverse_v0: float
    moment_sums: np.ndarray
    histogram: bool
    cx_low: float
    cx_width: float
    cx_counts: np.ndarray
    cx_weights: np.ndarray
    speed_width: float
    speed_counts: np.ndarray


class Flights(NamedTuple):
    """Free-flight observers of ``collide_observed``: the time of each particle's last
    collision (``last_collision``, (N,) float64, < 0 if none) and the histograms of the
    flights that start in [record_start, record_end): times in bins of ``time_bin_width``
    (``time_counts``), paths in bins of ``path_bin_width`` (``path_counts``), both
    (n_bins + 1,) int64 whose last entry is the overflow."""

    last_collision: np.ndarray
    record_start: float
    record_end: float
    time_bin_width: float
    time_counts: np.ndarray
    path_bin_width: float
    path_counts: np.ndarray


_SHIFT_32 = np.uint64(32)
_SHIFT_16 = np.uint64(16)
_SHIFT_15 = np.uint64(15)
_LOW_32 = np.uint64(0xFFFFFFFF)
_MIX_1 = np.uint64(0x7FEB352D)
_MIX_2 = np.uint64(0x846CA68B)

CONTIGUOUS = (0, 0, 0, 0, np.uint64(0))
"""``members`` of a range of consecutive particles (``_member``: first + a)."""

# ----------------------------------------------------------------------------- helpers
#
# Small helpers are plain jitted functions that LLVM inlines; ``_trial`` and the loop
# bodies are inlined at numba's IR level (``inline="always"``), which specialises the
# loops on a literal dimension (twice faster than a runtime d) at a moderate compile cost.
#
# The loops keep the xoshiro256+ state in four local uint64 scalars (loaded from the
# caller's ``state`` row at entry, stored back at exit) instead of advancing the array
# in memory at every draw: numba cannot prove that the state row and the velocities do
# not alias, so with the array every velocity store forces the state to be reloaded and
# the loop runs about twice slower. The scalar draws are kinetic.rng's ``xoshiro_*``.


@kernel
def _pair(n, s0, s1, s2, s3):
    """Two distinct uniform indices in ``0..n-1`` from one 64-bit draw, independent of
    each other: i from its top 32 bits, j from its low 32 bits, each by multiply-shift
    (relative non-uniformity below n / 2³²). j's value rests on the top bits of its half
    (bits 14..31 at N = 2 × 10⁵), clear of the few lowest bits of xoshiro256+, which fail
    linearity tests. j from bits 11..42 shared 11 bits with i: j given i was uneven by
    ±5 % at N = 2 × 10⁵, and at N = 2²² half the pairs of an even i could not be drawn.
    A second draw for j, or j from the fraction of u n, slowed the collision stage 11-22 %.
    Returns ``(i, j, s0, s1, s2, s3)``.
    """
    x, s0, s1, s2, s3 = _next(s0, s1, s2, s3)
    nu = np.uint64(n)
    i = np.int64(((x >> _SHIFT_32) * nu) >> _SHIFT_32)
    j = np.int64(((x & _LOW_32) * (nu - np.uint64(1))) >> _SHIFT_32)
    if j >= i:
        j += 1
    return i, j, s0, s1, s2, s3


@kernel
def _candidate_rate(kernel, pair_coefficient, n_pairs, bound):
    """Candidates per unit time for a range: coefficient * pairs * bound**p."""
    if kernel == HARD_SPHERES:
        return pair_coefficient * n_pairs * bound
    if kernel == VERY_HARD:
        return pair_coefficient * n_pairs * bound * bound
    return pair_coefficient * n_pairs


@inline
def _trial(velocity, i, j, d, kernel, bound_sq, s0, s1, s2, s3):
    """Test the candidate pair (i, j) of ``velocity``: ``_trial_relative`` of v_i - v_j."""
    g0 = velocity[0, i] - velocity[0, j]
    g1 = velocity[1, i] - velocity[1, j]
    g2 = 0.0
    if d == 3:
        g2 = velocity[2, i] - velocity[2, j]
    return _trial_relative(g0, g1, g2, d, kernel, bound_sq, s0, s1, s2, s3)


@inline
def _trial_relative(g0, g1, g2, d, kernel, bound_sq, s0, s1, s2, s3):
    """Test one candidate pair of relative velocity g; return
    ``(code, h0, h1, h2, s0, s1, s2, s3)``.

    h = (g·σ̂)σ̂ with g = v_i - v_j. code 0: rejected; 1: accepted; 2: the pair's rate
    exceeds the bound (stale bound; nothing drawn). Hard spheres are accepted with
    probability |g|/B and σ̂ is then drawn from its conditional law ∝ |ĝ·σ̂|: in d = 3
    the elastic post-collision direction g - 2(g·σ̂)σ̂ is then isotropic, so
    (g·σ̂)σ̂ = (g - |g| n̂)/2 with n̂ uniform; in d = 2 sin∠(σ̂, ĝ) is uniform on (-1, 1).
    Very hard particles: σ̂ uniform, accepted with probability (g·σ̂)²/B². Maxwell
    molecules: σ̂ uniform, always accepted.
    """
    gg = g0 * g0 + g1 * g1 + g2 * g2
    if kernel == HARD_SPHERES:
        if gg > bound_sq:
            return 2, 0.0, 0.0, 0.0, s0, s1, s2, s3
        u, s0, s1, s2, s3 = _uniform(s0, s1, s2, s3)
        if u * u * bound_sq >= gg:
            return 0, 0.0, 0.0, 0.0, s0, s1, s2, s3
        if d == 3:
            n0, n1, n2, s0, s1, s2, s3 = _unit_3d(s0, s1, s2, s3)
            gm = math.sqrt(gg)
            return (
                1,
                0.5 * (g0 - gm * n0),
                0.5 * (g1 - gm * n1),
                0.5 * (g2 - gm * n2),
                s0,
                s1,
                s2,
                s3,
            )
        u, s0, s1, s2, s3 = _uniform(s0, s1, s2, s3)
        sine = 2.0 * u - 1.0
        c2 = 1.0 - sine * sine
        cs = math.sqrt(c2) * sine
        return 1, c2 * g0 - cs * g1, c2 * g1 + cs * g0, 0.0, s0, s1, s2, s3
    if d == 3:
        e0, e1, e2, s0, s1, s2, s3 = _unit_3d(s0, s1, s2, s3)
    else:
        e0, e1, s0, s1, s2, s3 = _unit_2d(s0, s1, s2, s3)
        e2 = 0.0
    gs = g0 * e0 + g1 * e1 + g2 * e2
    if kernel == VERY_HARD:
        if gg > bound_sq:
            return 2, 0.0, 0.0, 0.0, s0, s1, s2, s3
        u, s0, s1, s2, s3 = _uniform(s0, s1, s2, s3)
        if u * bound_sq >= gs * gs:
            return 0, 0.0, 0.0, 0.0, s0, s1, s2, s3
    return 1, gs * e0, gs * e1, gs * e2, s0, s1, s2, s3


@kernel
def _apply(velocity, i, j, d, half, h0, h1, h2, c0, c1, c2):
    """v_i -= (1+α)/2 h, v_j += (1+α)/2 h (``half`` = (1+α)/2).

    Returns the new squared speeds ``(|v_i - c|², |v_j - c|²)`` about c = (c0, c1, c2).
    """
    a0 = velocity[0, i] - half * h0
    a1 = velocity[1, i] - half * h1
    b0 = velocity[0, j] + half * h0
    b1 = velocity[1, j] + half * h1
    velocity[0, i] = a0
    velocity[1, i] = a1
    velocity[0, j] = b0
    velocity[1, j] = b1
    a0 -= c0
    a1 -= c1
    b0 -= c0
    b1 -= c1
    sa = a0 * a0 + a1 * a1
    sb = b0 * b0 + b1 * b1
    if d == 3:
        a2 = velocity[2, i] - half * h2
        b2 = velocity[2, j] + half * h2
        velocity[2, i] = a2
        velocity[2, j] = b2
        a2 -= c2
        b2 -= c2
        sa += a2 * a2
        sb += b2 * b2
    return sa, sb


@kernel
def _raise(sa, sb, top1, top2):
    """Update the speed bounds ``top1 >= top2`` with the new squared speeds sa, sb.

    Invariant: every particle's speed about c is <= top1 and all but at most one are
    <= top2, so top1 + top2 bounds every relative speed. Returns ``(raised, top1, top2)``.
    """
    if sa < sb:
        sa, sb = sb, sa
    if sa <= top2 * top2:
        return False, top1, top2
    a = math.sqrt(sa)
    if a > top1:
        return True, a, max(top1, math.sqrt(sb))
    return True, top1, a


@kernel
def _speed_sq(velocity, i, d, c0, c1, c2):
    """|v_i - c|²."""
    a = velocity[0, i] - c0
    b = velocity[1, i] - c1
    s = a * a + b * b
    if d == 3:
        c = velocity[2, i] - c2
        s += c * c
    return s


@inline
def column_particle(j, g, shift, n_rows, n_columns, full_rows):
    """The particle that group g takes from column j in the column layout of N particles
    (``n_columns`` columns of ``n_rows`` rows, particle j n_rows + row in column j; the
    last column holds ``full_rows`` = N - (n_columns - 1) n_rows): the one of row
    (g + shift) mod n_rows, the column's ``shift`` drawn for the step; -1 where the last
    column has no such row. For every shift, each particle belongs to exactly one of the
    n_rows groups, which hold n_columns or n_columns - 1 particles (the CUDA backend's
    groups). 0 <= g, shift < n_rows: the row wraps by one subtraction,
    not a 64-bit remainder (a long instruction sequence on a GPU)."""
    row = g + shift
    if row >= n_rows:
        row -= n_rows
    if j < n_columns - 1 or row < full_rows:
        return j * n_rows + row
    return -1


@kernel
def _hash32(x):
    """C. Wellons' ``lowbias32`` integer hash of x < 2**32 (held in a uint64): every
    product is below 2**64, so the arithmetic never wraps (the same numbers compiled for
    the CPU, for the GPU and under numba's CUDA simulator, where numpy would warn about
    wrapping)."""
    x ^= x >> _SHIFT_16
    x = (x * _MIX_1) & _LOW_32
    x ^= x >> _SHIFT_15
    x = (x * _MIX_2) & _LOW_32
    return x ^ (x >> _SHIFT_16)


@kernel
def feistel_round(right, key):
    """Round function of a Feistel network: the half word ``right`` (< 2**32) hashed with
    the low and then the high half of the 64-bit round key."""
    return _hash32(_hash32(right ^ (key & _LOW_32)) ^ (key >> _SHIFT_32))


@kernel
def column_shift(j, key, n_rows):
    """The row shift of column j in a step of the columns layout (``column_particle``):
    the Feistel round function of j with the step's key, scaled to 0..n_rows-1."""
    return np.int64((feistel_round(np.uint64(j), key) * np.uint64(n_rows)) >> _SHIFT_32)


@kernel
def _member(first, a, members):
    """The particle index of member a of a range: ``first + a`` where ``members`` is
    ``CONTIGUOUS``; else, with ``members`` = (n_rows, n_columns, full_rows, g, key), the
    particle group g takes from column a of the columns layout in the step of ``key``
    (``column_particle`` with the shift ``column_shift``; first is 0)."""
    n_rows = members[0]
    if n_rows == 0:
        return first + a
    shift = column_shift(a, members[4], n_rows)
    return column_particle(a, members[3], shift, n_rows, members[1], members[2])


@kernel
def group_size(members):
    """Particles of the group of ``members`` (not ``CONTIGUOUS``): n_columns, or one fewer
    where the last column has no row for it."""
    last = _member(0, members[1] - 1, members)
    return members[1] if last >= 0 else members[1] - 1


@kernel
def _two_largest(s, top1, top2):
    """``(top1, top2)``, the two largest of ``top1 >= top2`` and ``s``: a compiled helper
    that LLVM inlines (as an IR-inlined one, the pair it returns cost the force pass a
    third of its time; this one costs nothing measurable)."""
    if s > top2:
        if s > top1:
            return s, top1
        return top1, s
    return top1, top2


@kernel
def speed_bounds(velocity, first, last, bounds):
    """Fill ``bounds`` (length d + 2) for particles ``first..last-1``.

    ``bounds[:d]`` = their mean velocity c, ``bounds[d] >= bounds[d+1]`` = the two
    largest speeds |v_i - c| (the second is 0 for a single particle).
    """
    member_bounds(velocity, first, last, CONTIGUOUS, bounds)


@kernel
def member_bounds(velocity, first, last, members, bounds):
    """``speed_bounds`` of the members ``first..last-1`` of a range (``_member``), summed
    and ranked in member order."""
    d = velocity.shape[0]
    n = last - first
    for k in range(d):
        total = 0.0
        for a in range(n):
            total += velocity[k, _member(first, a, members)]
        bounds[k] = total / max(n, 1)
    c0 = bounds[0]
    c1 = bounds[1]
    c2 = bounds[2] if d == 3 else 0.0
    top1 = 0.0
    top2 = 0.0
    for a in range(n):
        s = _speed_sq(velocity, _member(first, a, members), d, c0, c1, c2)
        top1, top2 = _two_largest(s, top1, top2)
    bounds[d] = math.sqrt(top1)
    bounds[d + 1] = math.sqrt(top2)


@inline
def _bound_terms(bounds, d):
    """``(c0, c1, c2, top1, top2)`` of a ``bounds`` row (centre and the two top speeds)."""
    c2 = bounds[2] if d == 3 else 0.0
    return bounds[0], bounds[1], c2, bounds[d], bounds[d + 1]


@inline
def _majorant(kernel, pair_coefficient, n_pairs, top1, top2):
    """``(bound², mean candidate spacing)`` for the relative-speed bound top1 + top2."""
    bound = (top1 + top2) * BOUND_SAFETY
    return bound * bound, 1.0 / _candidate_rate(kernel, pair_coefficient, n_pairs, bound)


@inline
def _collide_loop(velocity, first, last, members, state, collisions, d):
    """Body of ``collide_members`` for a literal dimension ``d`` (specialised by
    inlining)."""
    kernel = collisions.kernel
    restitution = collisions.restitution
    pair_coefficient = collisions.pair_coefficient
    duration = collisions.duration
    poisson = collisions.poisson
    bounds = collisions.bounds
    carry = collisions.carry
    tally = collisions.tally
    n = last - first
    if n < 2 or duration <= 0.0:
        return
    n_pairs = 0.5 * n * (n - 1.0)
    half = 0.5 * (1.0 + restitution)
    c0, c1, c2, top1, top2 = _bound_terms(bounds, d)
    bound_sq, spacing = _majorant(kernel, pair_coefficient, n_pairs, top1, top2)
    budget = duration
    if not poisson:
        budget += carry[0] * spacing
    s0, s1, s2, s3 = load_state(state)
    candidates = 0
    accepted = 0
    while True:
        if poisson:
            e, s0, s1, s2, s3 = _exponential(s0, s1, s2, s3)
            step = e * spacing
        else:
            step = spacing
        if not step <= budget:  # a NaN spacing ends the call instead of looping forever
            break
        budget -= step
        candidates += 1
        a, b, s0, s1, s2, s3 = _pair(n, s0, s1, s2, s3)
        i = _member(first, a, members)
        j = _member(first, b, members)
        code, h0, h1, h2, s0, s1, s2, s3 = _trial(
            velocity, i, j, d, kernel, bound_sq, s0, s1, s2, s3
        )
        if code == 2:
            tally[TALLY_EXCEEDED] += 1
            member_bounds(velocity, first, last, members, bounds)
            c0, c1, c2, top1, top2 = _bound_terms(bounds, d)
            bound_sq, spacing = _majorant(kernel, pair_coefficient, n_pairs, top1, top2)
            continue  # the candidate drawn under the stale bound is dropped
        if code == 0:
            continue
        sa, sb = _apply(velocity, i, j, d, half, h0, h1, h2, c0, c1, c2)
        accepted += 1
        if kernel != MAXWELL:
            raised, top1, top2 = _raise(sa, sb, top1, top2)
            if raised:
                tally[TALLY_RAISED] += 1
                bound_sq, spacing = _majorant(kernel, pair_coefficient, n_pairs, top1, top2)
    store_state(state, s0, s1, s2, s3)
    bounds[d] = top1
    bounds[d + 1] = top2
    if not poisson:
        carry[0] = budget / spacing
    tally[TALLY_CANDIDATES] += candidates
    tally[TALLY_ACCEPTED] += accepted


@kernel
def collide_range(velocity, first, last, state, collisions):
    """Collide the particles ``first..last-1`` for a time ``collisions.duration``.

    velocity: (d, N) float64, updated in place. state: (4,) uint64 stream, advanced.
    collisions: a :class:`Collisions` (its bounds, carry and tally updated in place).
    """
    if velocity.shape[0] == 3:
        _collide_loop(velocity, first, last, CONTIGUOUS, state, collisions, 3)
    else:
        _collide_loop(velocity, first, last, CONTIGUOUS, state, collisions, 2)


@kernel
def collide_members(velocity, first, last, members, state, collisions):
    """``collide_range`` on the members ``first..last-1`` of a range (``_member``): with
    ``members`` of the columns layout, the particles of one group, in place (the CUDA
    backend's ``sparse`` collision stage)."""
    if velocity.shape[0] == 3:
        _collide_loop(velocity, first, last, members, state, collisions, 3)
    else:
        _collide_loop(velocity, first, last, members, state, collisions, 2)


@kernel
def _record_flight(
    velocity,
    i,
    d,
    now,
    last_collision,
    record_start,
    record_end,
    inverse_time_width,
    time_counts,
    inverse_path_width,
    path_counts,
):
    """Histogram particle i's free flight ending at ``now`` (speed before the collision).

    Only flights that start (at a collision) in [record_start, record_end) are recorded:
    histogramming the flights that *end* in a window would under-count long flights
    (by a factor 1 - t/window). Bins are uniform from 0; the last entry of each counts
    array is the overflow bin. A particle that has not collided yet has
    ``last_collision < 0`` (its first interval does not start at a collision).
    """
    start = last_collision[i]
    if record_start <= start < record_end:
        flight = now - start
        speed = velocity[0, i] * velocity[0, i] + velocity[1, i] * velocity[1, i]
        if d == 3:
            speed += velocity[2, i] * velocity[2, i]
        path = np.sqrt(speed) * flight
        overflow = time_counts.shape[0] - 1
        b = int(flight * inverse_time_width)
        time_counts[min(b, overflow)] += 1
        overflow = path_counts.shape[0] - 1
        b = int(path * inverse_path_width)
        path_counts[min(b, overflow)] += 1
    last_collision[i] = now


@inline
def _collide_observed_loop(velocity, state, collisions, start_time, flights, d):
    """Body of ``collide_observed`` for a literal dimension ``d`` (specialised by inlining)."""
    kernel = collisions.kernel
    restitution = collisions.restitution
    pair_coefficient = collisions.pair_coefficient
    duration = collisions.duration
    bounds = collisions.bounds
    tally = collisions.tally
    last_collision = flights.last_collision
    record_start = flights.record_start
    record_end = flights.record_end
    time_bin_width = flights.time_bin_width
    time_counts = flights.time_counts
    path_bin_width = flights.path_bin_width
    path_counts = flights.path_counts
    n = velocity.shape[1]
    if n < 2 or duration <= 0.0:
        return
    n_pairs = 0.5 * n * (n - 1.0)
    half = 0.5 * (1.0 + restitution)
    inverse_time_width = 1.0 / time_bin_width
    inverse_path_width = 1.0 / path_bin_width
    c0, c1, c2, top1, top2 = _bound_terms(bounds, d)
    bound_sq, spacing = _majorant(kernel, pair_coefficient, n_pairs, top1, top2)
    s0, s1, s2, s3 = load_state(state)
    now = start_time
    end = start_time + duration
    while True:
        e, s0, s1, s2, s3 = _exponential(s0, s1, s2, s3)
        now += e * spacing
        if now > end:
            break
        tally[TALLY_CANDIDATES] += 1
        i, j, s0, s1, s2, s3 = _pair(n, s0, s1, s2, s3)
        code, h0, h1, h2, s0, s1, s2, s3 = _trial(
            velocity, i, j, d, kernel, bound_sq, s0, s1, s2, s3
        )
        if code == 2:
            tally[TALLY_EXCEEDED] += 1
            speed_bounds(velocity, 0, n, bounds)
            c0, c1, c2, top1, top2 = _bound_terms(bounds, d)
            bound_sq, spacing = _majorant(kernel, pair_coefficient, n_pairs, top1, top2)
            continue  # the candidate drawn under the stale bound is dropped
        if code == 0:
            continue
        _record_flight(
            velocity,
            i,
            d,
            now,
            last_collision,
            record_start,
            record_end,
            inverse_time_width,
            time_counts,
            inverse_path_width,
            path_counts,
        )
        _record_flight(
            velocity,
            j,
            d,
            now,
            last_collision,
            record_start,
            record_end,
            inverse_time_width,
            time_counts,
            inverse_path_width,
            path_counts,
        )
        sa, sb = _apply(velocity, i, j, d, half, h0, h1, h2, c0, c1, c2)
        tally[TALLY_ACCEPTED] += 1
        if kernel != MAXWELL:
            raised, top1, top2 = _raise(sa, sb, top1, top2)
            if raised:
                tally[TALLY_RAISED] += 1
                bound_sq, spacing = _majorant(kernel, pair_coefficient, n_pairs, top1, top2)
    store_state(state, s0, s1, s2, s3)
    bounds[d] = top1
    bounds[d + 1] = top2


@kernel
def collide_observed(velocity, state, collisions, start_time, flights):
    """Continuous-time collisions of all particles with free-flight observers.

    Exact event times (Poisson clock, thinning with the rigorous bound) from
    ``start_time`` to ``start_time + collisions.duration`` (memoryless: consecutive calls
    make one Poisson process; ``collisions.poisson`` and ``carry`` are not used). At each
    collision the free-flight time and the free path (speed x time; speeds about the
    origin, the gas being at rest) of both partners since their previous collision are
    histogrammed into ``flights`` (a :class:`Flights`) if that flight started in
    [record_start, record_end) (run until record_end + the longest flight of interest
    so that every such flight is either complete or known to be longer).
    """
    if velocity.shape[0] == 3:
        _collide_observed_loop(velocity, state, collisions, start_time, flights, 3)
    else:
        _collide_observed_loop(velocity, state, collisions, start_time, flights, 2)


# --------------------------------------------------------------- forcing and thermostat


@kernel
def _force_factor(ax, exact):
    """Factor f of one particle's force step V -> f V, from ax = a V_x (a = ε δt/2):
    Euler (Eq. 4.1) f = 1 - ax, exact f = 1/(1 + ax). Returns ``(status, f)``: status
    STATUS_FORCE_BLOW_UP (exact, 1 + ax <= 0; f = 1), STATUS_EULER_STEP_TOO_LARGE (Euler,
    |ax| > EULER_LIMIT) or STATUS_OK. Shared by ``force_update`` and the GPU
    engine (one thread per particle)."""
    if exact:
        denominator = 1.0 + ax
        if denominator <= 0.0:
            return STATUS_FORCE_BLOW_UP, 1.0
        return STATUS_OK, 1.0 / denominator
    if abs(ax) > EULER_LIMIT:
        return STATUS_EULER_STEP_TOO_LARGE, 1.0 - ax
    return STATUS_OK, 1.0 - ax


@kernel
def _thermostat_scale(sum0, sum1, sum2, total_sq, n, target_energy):
    """The thermostat (Eq. 4.2) from the particle sums ΣV_k and Σ|V|² of n particles:
    ``(status, u0, u1, u2, scale, log_scale)`` with u the mean velocity, scale =
    sqrt(K0/K') (K' = <|V - u|²>/2, K0 = ``target_energy``) and its logarithm; status
    STATUS_NONFINITE (and scale 1) if K' is not finite and positive. Shared by
    ``advance`` and the GPU engine (sums from its reductions)."""
    u0 = sum0 / n
    u1 = sum1 / n
    u2 = sum2 / n
    energy = 0.5 * (total_sq / n - (u0 * u0 + u1 * u1 + u2 * u2))
    if not (math.isfinite(energy) and energy > 0.0):
        return STATUS_NONFINITE, u0, u1, u2, 1.0, 0.0
    scale = math.sqrt(target_energy / energy)
    return STATUS_OK, u0, u1, u2, scale, math.log(scale)


@kernel
def force_update(velocity, scale, u0, u1, u2, half_field_step, exact):
    """A force step of montanero2007 (Eq. 4.1), the thermostat of the step before (Eq.
    4.2) applied on the way, particle by particle.

    ``velocity`` holds W, whose thermostatted velocities are V = ``scale`` (W - u) (the
    thermostat deferred, see ``advance``). Each particle's V is given the force step,
    a = ε δt/2 = ``half_field_step`` (velocity-dependent part of Eq. 3.2 with ε = ε x̂):
    Euler V -> V (1 - a V_x); exact (``exact`` True) V -> V / (1 + a V_x), the solution
    of dV/dt = -(ε/2) V_x V over δt; and stored (W := V). No particle depends on another
    and nothing is summed in floating point, so the compiler runs the loop on SIMD lanes
    with the same numbers as one particle at a time (0.5 ns a particle at N = 2 × 10⁵
    here, against 2 ns for a loop that also sums). Returns STATUS_OK, or
    STATUS_FORCE_BLOW_UP (exact step: 1 + a V_x <= 0 for a particle, which would reach
    infinite speed within δt) or STATUS_EULER_STEP_TOO_LARGE (|a V_x| > EULER_LIMIT).
    """
    n = velocity.shape[1]
    failed = 0
    if velocity.shape[0] == 3:
        for i in range(n):
            v0 = scale * (velocity[0, i] - u0)
            code, f = _force_factor(half_field_step * v0, exact)
            failed += code != STATUS_OK
            velocity[0, i] = v0 * f
            velocity[1, i] = scale * (velocity[1, i] - u1) * f
            velocity[2, i] = scale * (velocity[2, i] - u2) * f
    else:
        for i in range(n):
            v0 = scale * (velocity[0, i] - u0)
            code, f = _force_factor(half_field_step * v0, exact)
            failed += code != STATUS_OK
            velocity[0, i] = v0 * f
            velocity[1, i] = scale * (velocity[1, i] - u1) * f
    if failed == 0:
        return STATUS_OK
    if exact:
        return STATUS_FORCE_BLOW_UP
    return STATUS_EULER_STEP_TOO_LARGE


@kernel
def _components(velocity, i, d):
    """``(v_0, v_1, v_2, |v|²)`` of particle i (v_2 = 0 in d = 2)."""
    x = velocity[0, i]
    y = velocity[1, i]
    z = velocity[2, i] if d == 3 else 0.0
    return x, y, z, x * x + y * y + z * z


@kernel
def thermostat_sums(velocity, bounds):
    """The sums a thermostat takes, ``(ΣW_0, ΣW_1, ΣW_2, Σ|W|²)`` (for
    ``_thermostat_scale``), and ``bounds`` refilled with centre 0 and the two largest
    |W|: one read of the particles, two particles an iteration on separate sums (the
    additions of one sum wait for each other; 1 ns a particle at N = 2 × 10⁵ here)."""
    d = velocity.shape[0]
    n = velocity.shape[1]
    a0 = 0.0
    a1 = 0.0
    a2 = 0.0
    aq = 0.0
    b0 = 0.0
    b1 = 0.0
    b2 = 0.0
    bq = 0.0
    top1 = 0.0
    top2 = 0.0
    top = n - n % 2
    for i in range(0, top, 2):
        x, y, z, s = _components(velocity, i, d)
        a0 += x
        a1 += y
        a2 += z
        aq += s
        top1, top2 = _two_largest(s, top1, top2)
        x, y, z, s = _components(velocity, i + 1, d)
        b0 += x
        b1 += y
        b2 += z
        bq += s
        top1, top2 = _two_largest(s, top1, top2)
    for i in range(top, n):  # the last particle of an odd n
        x, y, z, s = _components(velocity, i, d)
        a0 += x
        a1 += y
        a2 += z
        aq += s
        top1, top2 = _two_largest(s, top1, top2)
    for k in range(d):
        bounds[k] = 0.0
    bounds[d] = math.sqrt(top1)
    bounds[d + 1] = math.sqrt(top2)
    return a0 + b0, a1 + b1, a2 + b2, aq + bq


@kernel
def apply_thermostat(velocity, scale, u0, u1, u2, bounds):
    """The deferred thermostat (see ``force_update``) made explicit: W -> ``scale`` (W - u)
    in place. ``bounds`` (of W about its centre c) becomes the bounds of the result:
    centre scale (c - u), speeds times ``scale``."""
    d = velocity.shape[0]
    n = velocity.shape[1]
    if d == 3:
        for i in range(n):
            velocity[0, i] = scale * (velocity[0, i] - u0)
            velocity[1, i] = scale * (velocity[1, i] - u1)
            velocity[2, i] = scale * (velocity[2, i] - u2)
        bounds[2] = scale * (bounds[2] - u2)
    else:
        for i in range(n):
            velocity[0, i] = scale * (velocity[0, i] - u0)
            velocity[1, i] = scale * (velocity[1, i] - u1)
    bounds[0] = scale * (bounds[0] - u0)
    bounds[1] = scale * (bounds[1] - u1)
    bounds[d] *= scale
    bounds[d + 1] *= scale


@kernel
def _force_step(velocity, scale, u0, u1, u2, half_field_step, exact, target_energy, bounds):
    """``force_update`` then ``thermostat_sums`` and the thermostat they give (deferred):
    ``(status, scale, u0, u1, u2, log_scale)`` of the new pending thermostat."""
    status = force_update(velocity, scale, u0, u1, u2, half_field_step, exact)
    if status != STATUS_OK:
        return status, scale, u0, u1, u2, 0.0
    t0, t1, t2, total_sq = thermostat_sums(velocity, bounds)
    status, u0, u1, u2, scale, log_scale = _thermostat_scale(
        t0, t1, t2, total_sq, velocity.shape[1], target_energy
    )
    return status, scale, u0, u1, u2, log_scale


@kernel
def force_and_thermostat(velocity, half_field_step, exact, target_energy, bounds):
    """A force step and its thermostat (Eqs. 4.1, 4.2) on thermostatted velocities, made
    explicit: the force step (``force_update``), then V -> sqrt(K0/K')(V - u') with u'
    the mean velocity and K' = <|V - u'|²>/2 (m = 1), so that the total momentum is zero
    and the energy per particle is ``target_energy`` = K0 to round-off
    (``apply_thermostat``); ``bounds`` refilled. ``advance`` defers the thermostat into
    the next step's force update instead. Returns ``(status, log_scale)``, log_scale =
    ln sqrt(K0/K') (the thermostat's energy injection), status as ``force_update``'s or
    STATUS_NONFINITE."""
    status, scale, u0, u1, u2, log_scale = _force_step(
        velocity, 1.0, 0.0, 0.0, 0.0, half_field_step, exact, target_energy, bounds
    )
    if status != STATUS_OK:
        return status, 0.0
    apply_thermostat(velocity, scale, u0, u1, u2, bounds)
    return STATUS_OK, log_scale


# ------------------------------------------------------------------------- observers

N_MOMENTS = 14
"""Entries of ``accumulate_moments``: see ``MOMENT_NAMES`` in :mod:`kinetic.dsmc.state`."""


@kernel
def _laguerre_123(p, x):
    """(L_1^(p)(x), L_2^(p)(x), L_3^(p)(x)), generalized Laguerre polynomials."""
    l1 = 1.0 + p - x
    l2 = 0.5 * (p + 1.0) * (p + 2.0) - (p + 2.0) * x + 0.5 * x * x
    l3 = (
        (p + 1.0) * (p + 2.0) * (p + 3.0) / 6.0
        - 0.5 * (p + 2.0) * (p + 3.0) * x
        + 0.5 * (p + 3.0) * x * x
        - x * x * x / 6.0
    )
    return l1, l2, l3


@kernel
def _particle_moments(velocity, i, d, inverse_v0, p_full):
    """The N_MOMENTS terms of particle i (c = V * inverse_v0, p_full = d/2), in the order
    of ``accumulate_moments``: c_x, c², c_x², c⁴, c² c_x, c_x L_k^(d/2)(c²) (k = 1..3),
    c_x L_k^(1/2)(c_x²) (k = 1..3), c⁶, c_x⁴, c_x c_y. Shared with the GPU engine."""
    cx = velocity[0, i] * inverse_v0
    cy = velocity[1, i] * inverse_v0
    c2 = cx * cx + cy * cy
    if d == 3:
        cz = velocity[2, i] * inverse_v0
        c2 += cz * cz
    cx2 = cx * cx
    f1, f2, f3 = _laguerre_123(p_full, c2)
    g1, g2, g3 = _laguerre_123(0.5, cx2)
    return (
        cx,
        c2,
        cx2,
        c2 * c2,
        c2 * cx,
        cx * f1,
        cx * f2,
        cx * f3,
        cx * g1,
        cx * g2,
        cx * g3,
        c2 * c2 * c2,
        cx2 * cx2,
        cx * cy,
    )


@kernel
def accumulate_moments(velocity, inverse_v0, sums):
    """Add the particle averages of one snapshot to ``sums`` (N_MOMENTS,).

    c = V * inverse_v0 (V peculiar velocity, v0 = sqrt(2T) the thermal speed). Entries:
    <c_x>, <c²>, <c_x²>, <c⁴>, <c² c_x>, <c_x L_k^(d/2)(c²)> for k = 1, 2, 3 (Eq. 3.10),
    <c_x L_k^(1/2)(c_x²)> for k = 1, 2, 3 (Eq. 3.12), <c⁶>, <c_x⁴>, <c_x c_y>.
    """
    d = velocity.shape[0]
    n = velocity.shape[1]
    p_full = 0.5 * d
    m0 = m1 = m2 = m3 = m4 = m5 = m6 = m7 = m8 = m9 = m10 = m11 = m12 = m13 = 0.0
    for i in range(n):
        t0, t1, t2, t3, t4, t5, t6, t7, t8, t9, t10, t11, t12, t13 = _particle_moments(
            velocity, i, d, inverse_v0, p_full
        )
        m0 += t0
        m1 += t1
        m2 += t2
        m3 += t3
        m4 += t4
        m5 += t5
        m6 += t6
        m7 += t7
        m8 += t8
        m9 += t9
        m10 += t10
        m11 += t11
        m12 += t12
        m13 += t13
    sums[0] += m0 / n
    sums[1] += m1 / n
    sums[2] += m2 / n
    sums[3] += m3 / n
    sums[4] += m4 / n
    sums[5] += m5 / n
    sums[6] += m6 / n
    sums[7] += m7 / n
    sums[8] += m8 / n
    sums[9] += m9 / n
    sums[10] += m10 / n
    sums[11] += m11 / n
    sums[12] += m12 / n
    sums[13] += m13 / n


@kernel
def _histogram_bins(velocity, i, d, inverse_v0, cx_low, inverse_cx, n_cx, inverse_speed, n_speed):
    """Particle i's bins in ``accumulate_histograms``: ``(cx_bin, weight, speed_bin)``, with
    cx_bin in 0..n_cx + 1 (0 below, n_cx + 1 above the range), weight = c_x (3/2 - c_x²)
    and speed_bin in 0..n_speed (n_speed: beyond the range). Shared with the GPU engine."""
    cx = velocity[0, i] * inverse_v0
    c2 = 0.0
    for k in range(d):
        c = velocity[k, i] * inverse_v0
        c2 += c * c
    position = (cx - cx_low) * inverse_cx
    if position < 0.0:
        b = 0
    elif position >= n_cx:
        b = n_cx + 1
    else:
        b = 1 + int(position)
    s = int(math.sqrt(c2) * inverse_speed)
    return b, cx * (1.5 - cx * cx), min(s, n_speed)


@kernel
def accumulate_histograms(
    velocity, inverse_v0, cx_low, cx_width, cx_counts, cx_weights, speed_width, speed_counts
):
    """Histogram c_x (bins from ``cx_low``) and |c| (bins from 0) of one snapshot.

    cx_counts: (n_bins + 2,) int64 with [0] = underflow and [-1] = overflow;
    cx_weights: (n_bins + 2,) float64, same bins, += c_x (3/2 - c_x²) of each particle
    (the integrand of montanero2007 Eq. 4.6, so that β1 at the bin edges needs no
    interpolation); speed_counts: (n_bins + 1,) int64 with [-1] = overflow.
    """
    d = velocity.shape[0]
    n = velocity.shape[1]
    n_cx = cx_counts.shape[0] - 2
    n_speed = speed_counts.shape[0] - 1
    inverse_cx = 1.0 / cx_width
    inverse_speed = 1.0 / speed_width
    for i in range(n):
        b, weight, s = _histogram_bins(
            velocity, i, d, inverse_v0, cx_low, inverse_cx, n_cx, inverse_speed, n_speed
        )
        cx_counts[b] += 1
        cx_weights[b] += weight
        speed_counts[s] += 1


# ----------------------------------------------------------------------- composition


@kernel
def _advance_clock(clock, time_step, rate_exponent, log_scale):
    """Close one step in ``clock`` (see ``advance``) from the step's ``log_scale`` (the
    logarithm of the thermostat's total rescaling factor). Shared with the GPU engine."""
    # free-cooling picture: during the step the internal velocities are the physical
    # ones times sqrt(T0/T_k), T_k the physical temperature at the step's start, so
    # the step lasts time_step (T0/T_k)^(p/2) of physical time (exactly)
    clock[2] += time_step * math.exp(-0.5 * rate_exponent * clock[1])
    clock[1] -= 2.0 * log_scale
    clock[0] += time_step
    clock[3] += 1.0
    # Haff within the step: T^(-p/2) grows linearly, so the cooling rate at the
    # step's start is (2/p)((T_k/T_k+1)^(p/2) - 1)/time_step (2 ln(scale)/time_step
    # for p = 0), exact whatever the step
    if rate_exponent > 0.0:
        clock[4] += (2.0 / rate_exponent) * math.expm1(rate_exponent * log_scale)
    else:
        clock[4] += 2.0 * log_scale


@inline
def _deferred(collisions, scale, rate_exponent):
    """``collisions`` for velocities W whose thermostatted values are scale (W - u): the
    relative velocities are scale (W_i - W_j), so the same pairs collide in the same way
    at ``scale``**p times the candidate rate of W's bound (p = ``rate_exponent``)."""
    return Collisions(
        collisions.kernel,
        collisions.restitution,
        collisions.pair_coefficient * scale**rate_exponent,
        collisions.duration,
        collisions.poisson,
        collisions.bounds,
        collisions.carry,
        collisions.tally,
    )


@refcount_free
def advance(velocity, state, collisions, forcing, sampling, clock, n_steps):
    """``n_steps`` DSMC steps: collisions (:class:`Collisions`, whose ``duration`` is the
    time step), force and thermostat (:class:`Forcing`), observers (:class:`Sampling`).

    Per step, in the order of montanero2007 Section 4 (``strang`` False, Lie splitting):
    collide all particles for ``time_step``; apply the force step (a = ``half_field_step``
    = ε δt/2) and the thermostat. With ``strang`` True the force and thermostat act for
    half a step before and after the collisions (Strang splitting: splitting error O(δt²)
    instead of O(δt), for twice the force work). Then, every ``sample_stride``-th step
    (counted by clock[3]) add the snapshot moments to ``moment_sums[1:]`` (and 1 to
    moment_sums[0]) and, if ``histogram``, the snapshot to the histograms.

    The thermostat of a force step needs sums over all its particles, so it is deferred,
    kept as (scale, u), and applied by the next force update, which reads and writes the
    particles anyway (``_force_step``: ``force_update``, then ``thermostat_sums``, a
    read). The collisions in between run on the stored velocities W at the candidate rate
    of the thermostatted ones (``_deferred``: a collision is linear in the pair's
    velocities and conserves their momentum, so it commutes with V = scale (W - u)). The
    same steps as ``collide_range`` then ``force_and_thermostat`` (the engine's loop before
    2026-11-27), to round-off, with every update on SIMD lanes: the force and thermostat
    of a Lie step cost 1.5 ns a particle at N = 2 × 10⁵ here, against 2.7 ns. A snapshot
    and the end of the call apply the pending thermostat (``apply_thermostat``).

    clock: (5,) float64, updated: [0] time (thermostatted gas, = steps x time_step), [1]
    ln(T/T0) and [2] time of the freely cooling gas that the same run represents at zero
    field (the thermostat only rescales, and the dynamics is invariant under v -> v/s,
    t -> s^p t with p = ``rate_exponent``: 1 hard spheres, 0 Maxwell, 2 very hard
    particles); at nonzero field -d clock[1]/d clock[0] is the thermostat rate (Eq. 3.5's
    left side), [3] steps, [4] the sum over steps of ζ_k time_step with ζ_k the free
    cooling rate at the start of step k (at zero field; exact for any step since T(t)
    follows Haff's law within a step).
    Returns a STATUS_* code (the step that failed is left applied, its thermostat not).
    """
    time_step = collisions.duration
    bounds = collisions.bounds
    n = velocity.shape[1]
    half_field_step = forcing.half_field_step
    exact_force = forcing.exact
    strang = forcing.strang
    target_energy = forcing.target_energy
    rate_exponent = forcing.rate_exponent
    force_step = 0.5 * half_field_step if strang else half_field_step
    sample_stride = sampling.stride
    inverse_v0 = sampling.inverse_v0
    moment_sums = sampling.moment_sums
    scale = 1.0  # the pending thermostat: the gas's velocities are scale (velocity - u)
    u0 = 0.0
    u1 = 0.0
    u2 = 0.0
    for _ in range(n_steps):
        log_scale = 0.0
        if strang:
            status, scale, u0, u1, u2, log_scale = _force_step(
                velocity, scale, u0, u1, u2, force_step, exact_force, target_energy, bounds
            )
            if status != STATUS_OK:
                return status
        collide_range(velocity, 0, n, state, _deferred(collisions, scale, rate_exponent))
        status, scale, u0, u1, u2, second_scale = _force_step(
            velocity, scale, u0, u1, u2, force_step, exact_force, target_energy, bounds
        )
        if status != STATUS_OK:
            return status
        log_scale += second_scale
        _advance_clock(clock, time_step, rate_exponent, log_scale)
        if int(clock[3]) % sample_stride == 0:
            apply_thermostat(velocity, scale, u0, u1, u2, bounds)
            scale = 1.0
            u0 = 0.0
            u1 = 0.0
            u2 = 0.0
            moment_sums[0] += 1.0
            accumulate_moments(velocity, inverse_v0, moment_sums[1:])
            if sampling.histogram:
                accumulate_histograms(
                    velocity,
                    inverse_v0,
                    sampling.cx_low,
                    sampling.cx_width,
                    sampling.cx_counts,
                    sampling.cx_weights,
                    sampling.speed_width,
                    sampling.speed_counts,
                )
    if scale != 1.0 or u0 != 0.0 or u1 != 0.0 or u2 != 0.0:
        apply_thermostat(velocity, scale, u0, u1, u2, bounds)
    return STATUS_OK


@kernel
def maxwellian(velocity, state, temperature):
    """Fill velocity (d, N) with a Maxwellian of zero total momentum and exact energy.

    Draws standard normals, removes the mean and rescales so that
    <|v|^2> = d * temperature exactly (to round-off). Needs N >= 2.
    """
    d = velocity.shape[0]
    n = velocity.shape[1]
    for k in range(d):
        i = 0
        while i < n:
            a, b = normal_pair(state)
            velocity[k, i] = a
            if i + 1 < n:
                velocity[k, i + 1] = b
            i += 2
    total_sq = 0.0
    for k in range(d):
        mean = 0.0
        for i in range(n):
            mean += velocity[k, i]
        mean /= n
        for i in range(n):
            velocity[k, i] -= mean
            total_sq += velocity[k, i] * velocity[k, i]
    scale = np.sqrt(d * temperature * n / total_sq)
    for k in range(d):
        for i in range(n):
            velocity[k, i] *= scale


@unlocked
def maxwellian_batch(velocity, states, tops):
    """``maxwellian(velocity[r], states[r], 1.0)`` for every realization r of a batch
    (velocity (R, d, N), states (R, 4) advanced in place), and ``tops[r]`` = the largest
    speed of realization r, sqrt(max_i |v_i|²) with |v|² summed over the components in
    order. Without the GIL, so that a thread can build the next run's starts while the
    current run launches its kernels (``kinetic.dsmc.gpu.prefetch_starts``)."""
    d = velocity.shape[1]
    for r in range(velocity.shape[0]):
        v = velocity[r]
        maxwellian(v, states[r], 1.0)
        top = 0.0
        for i in range(velocity.shape[2]):
            speed_sq = v[0, i] * v[0, i] + v[1, i] * v[1, i]
            if d == 3:
                speed_sq += v[2, i] * v[2, i]
            top = max(top, speed_sq)
        tops[r] = math.sqrt(top)
