"""Hard-sphere pair selection with a majorant per pair, drawn through speed classes.

Why: the uniform pairs of ``kernels.collide_range`` are tested against one bound for the
whole gas, the sum of the two largest speeds, so at N = 2·10⁵ four or five candidates
are drawn for each collision. Every relative speed also obeys
``|v_i - v_j| <= s_i + s_j`` with ``s_i = |v_i - c|`` about any fixed centre c; with that
bound per pair a Maxwellian accepts E|g| / (2 E s) = 1/√2 of the candidates, whatever N.

Selection (exact for any velocity distribution): candidates arrive at the total rate
``C Σ_{i<j} (s_i + s_j) = C (n - 1) Σ_i s_i`` (C = ``pair_coefficient``). A candidate takes
i with probability ``s_i / Σ s`` and j uniformly among the other n - 1, so the unordered
pair {i, j} is proposed with probability ``(s_i + s_j) / ((n - 1) Σ s)``; it is accepted
with probability ``|g| / (s_i + s_j)``, so each pair collides at ``C |g_ij|``, the
hard-sphere rate. σ̂ then follows its conditional law (``kernels._trial``).

Drawing i ∝ s_i in O(1): each particle sits in the speed class k of its s, the speeds
in ``[L_k, U_k)`` with ``U_k / L_k <= 1.25`` (the float64 bits of s: exponent and two
mantissa bits). Each class owns a run of slots in a record array, its members followed
by free slots. A class is drawn from an alias table with probability ∝ slots_k × U_k, a
slot uniformly in the class, and the draw is kept if the slot holds a particle, with
probability ``s_i / U_k`` (1.2-1.4 draws per candidate); j is a uniform occupied slot
other than i's. A particle whose speed changes class moves to the first free slot of its
new class and the last member of the old class fills its slot. A class with no free
slot left triggers a new layout (about once per 10⁵ collisions at α = 1; more often
when the gas cools within the call, as at α = 0.5 over two collisions per particle).

Memory: a record is (v_x, v_y, v_z, s) in 32 bytes, so a candidate reads two cache
lines where the structure-of-arrays ``velocity`` of the engine costs six, and the draws
of i and j are made AHEAD candidates in advance with their records prefetched, so that
several candidates' memory latencies overlap. The call copies the particles into the
records (O(N), about 12 ns a particle) and back at the end, in class order: particles
are exchangeable in a homogeneous gas, so the order of ``velocity`` changes and nothing
else.

Cost against ``kernels.collide_range`` (``python -m kinetic.bench dsmc``): a candidate
costs about three uniform-pair candidates (the weighted draw of i: alias table, slot,
rejection, each a data-dependent branch), so the 3.4 times fewer candidates buy little
while the gas fits in the cache (N = 2·10⁵: 0.8 times the uniform pairs' rate); once the
velocities no longer fit (N = 2·10⁶: 48 MB) the uniform pairs wait on memory for six
lines per candidate and this selection runs 2.5 times faster.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from kinetic.dsmc.kernels import (
    BOUND_SAFETY,
    HARD_SPHERES,
    TALLY_ACCEPTED,
    TALLY_CANDIDATES,
    TALLY_EXCEEDED,
    TALLY_RAISED,
    _raise,
    _speed_sq,
    _trial_relative,
)
from kinetic.jit import inline, kernel, prefetch_row
from kinetic.rng import load_state, store_state
from kinetic.rng import xoshiro_exponential as _exponential
from kinetic.rng import xoshiro_next as _next

__all__ = ["CLASS_COUNT", "SpeedClasses", "class_upper_speeds", "collide_speed_classes"]

MANTISSA_BITS = 2
"""Mantissa bits of the speed kept in the class index: U/L <= 1 + 2^-2."""

LOWEST_EXPONENT = -40
"""Class 0 holds every speed below 2^LOWEST_EXPONENT (its bound is that power)."""

CLASS_COUNT = 80 << MANTISSA_BITS
"""Classes cover [0, 2^(LOWEST_EXPONENT + 80)); a faster particle stops the call."""

MIN_SLACK = 16
"""Free slots of a class beyond its members: at least this many, or a quarter of the count
(fewer slots make new layouts frequent; more make more empty draws)."""

WINDOW_MARGIN = 8
"""Classes below the slowest and above the fastest occupied class that get free slots."""

AHEAD = 8
"""Draws of i and of j prepared (and their records prefetched) ahead of their use."""

SPEED = 3
"""Column of the record that holds s (columns 0..d-1 hold the velocity)."""

EMPTY = -1.0
"""``s`` of a free slot."""

_SHIFT = np.uint64(52 - MANTISSA_BITS)
_BASE = (1023 + LOWEST_EXPONENT) << MANTISSA_BITS
_SHIFT_32 = np.uint64(32)
_SHIFT_11 = np.uint64(11)
_LOW_32 = np.uint64(0xFFFFFFFF)
_TWO_M32 = 2.3283064365386963e-10

_BASE_ROW = 0  # first slot of class k
_COUNT_ROW = 1  # members of class k (slots base..base+count-1)
_CAPACITY_ROW = 2  # slots of class k
_ALIAS_ROW = 3  # alias of column c of the alias table
_STACK_ROW = 4  # work stack of the alias construction


def class_upper_speeds() -> np.ndarray:
    """U_k, the (exclusive) upper speed of class k."""
    bits = (np.arange(CLASS_COUNT, dtype=np.uint64) + np.uint64(_BASE + 1)) << _SHIFT
    return bits.view(np.float64).copy()


_UPPER = class_upper_speeds()


class Work(NamedTuple):
    """The work arrays of ``collide_speed_classes`` (``SpeedClasses.arrays()``)."""

    records: np.ndarray
    record_bits: np.ndarray
    layout: np.ndarray
    probability: np.ndarray


class SpeedClasses:
    """Work arrays of ``collide_speed_classes`` for a gas of ``n`` particles."""

    def __init__(self, n: int):
        slots = n + n // 4 + MIN_SLACK * CLASS_COUNT
        self.records = np.zeros((slots + 1, 4))  # the last row: scratch of _class_of_speed
        self.record_bits = self.records.view(np.uint64)
        self.layout = np.zeros((5, CLASS_COUNT), dtype=np.int64)
        self.probability = np.zeros(CLASS_COUNT)

    def arrays(self) -> Work:
        """The work arrays as ``collide_speed_classes`` takes them."""
        return Work(self.records, self.record_bits, self.layout, self.probability)


@inline
def _class_of(bits):
    """Speed class of a speed given by its float64 bits (0 below the lowest class)."""
    k = np.int64(bits >> _SHIFT) - _BASE
    if k < 0:
        return 0
    return k


@kernel
def _class_of_speed(s, records, record_bits):
    """Speed class of s (its bits read through the last, scratch row of the records)."""
    records[-1, SPEED] = s
    return _class_of(record_bits[-1, SPEED])


@kernel
def _lay_out(velocity, c0, c1, c2, records, record_bits, layout, probability, d):
    """Sort the particles of ``velocity`` into class records, build the alias table.

    Classes from WINDOW_MARGIN below the slowest to WINDOW_MARGIN above the fastest
    occupied class (the window) get ``count + max(MIN_SLACK, count // 4)`` slots, the
    free ones marked EMPTY; the alias table (Vose) draws a window class with probability
    ∝ slots × U_k. Speeds s = |v - c| are computed twice (to count, then to place) rather
    than stored. Returns (lowest window class, window width, slots of the window, Σ s,
    largest s, second largest s), or width 0 if a particle is beyond the last class.
    """
    n = velocity.shape[1]
    count = layout[_COUNT_ROW]
    base = layout[_BASE_ROW]
    capacity = layout[_CAPACITY_ROW]
    alias = layout[_ALIAS_ROW]
    stack = layout[_STACK_ROW]
    count[:] = 0
    total = 0.0
    top1 = 0.0
    top2 = 0.0
    for i in range(n):
        s = np.sqrt(_speed_sq(velocity, i, d, c0, c1, c2))
        k = _class_of_speed(s, records, record_bits)
        if k >= CLASS_COUNT:
            return 0, 0, 0, 0.0, 0.0, 0.0
        count[k] += 1
        total += s
        if s > top2:
            if s > top1:
                top2 = top1
                top1 = s
            else:
                top2 = s
    lowest = CLASS_COUNT
    highest = -1
    for k in range(CLASS_COUNT):
        if count[k] > 0:
            lowest = min(lowest, k)
            highest = k
    lo = max(lowest - WINDOW_MARGIN, 0)
    hi = min(highest + WINDOW_MARGIN, CLASS_COUNT - 1)
    width = hi - lo + 1
    slots = 0
    weight_sum = 0.0
    for k in range(CLASS_COUNT):
        base[k] = slots
        if lo <= k <= hi:
            capacity[k] = count[k] + max(MIN_SLACK, count[k] >> 2)
        else:
            capacity[k] = 0
        slots += capacity[k]
        weight_sum += capacity[k] * _UPPER[k]
    count[:] = 0
    for i in range(n):
        s = np.sqrt(_speed_sq(velocity, i, d, c0, c1, c2))
        k = _class_of_speed(s, records, record_bits)
        place = base[k] + count[k]
        count[k] += 1
        records[place, 0] = velocity[0, i]
        records[place, 1] = velocity[1, i]
        records[place, 2] = velocity[2, i] if d == 3 else 0.0
        records[place, SPEED] = s
    for k in range(lo, hi + 1):
        for slot in range(base[k] + count[k], base[k] + capacity[k]):
            records[slot, SPEED] = EMPTY
    # Vose's alias method over the window's columns c = k - lo
    small = 0
    large = width
    for c in range(width):
        k = lo + c
        probability[c] = capacity[k] * _UPPER[k] * width / weight_sum
        alias[c] = c
        if probability[c] < 1.0:
            stack[small] = c
            small += 1
        else:
            large -= 1
            stack[large] = c
    while small > 0 and large < width:
        small -= 1
        c = stack[small]
        big = stack[large]
        alias[c] = big
        probability[big] -= 1.0 - probability[c]
        if probability[big] < 1.0:
            large += 1
            stack[small] = big
            small += 1
    while small > 0:  # rounding leftovers
        small -= 1
        probability[stack[small]] = 1.0
    while large < width:
        probability[stack[large]] = 1.0
        large += 1
    return lo, width, slots, total, top1, top2


@kernel
def _gather(records, layout, lo, width, velocity, d):
    """Copy the particles of the records back into ``velocity``, class by class."""
    out = 0
    for k in range(lo, lo + width):
        first = layout[_BASE_ROW, k]
        for slot in range(first, first + layout[_COUNT_ROW, k]):
            for c in range(d):
                velocity[c, out] = records[slot, c]
            out += 1


@kernel
def _collide_records(records, a, b, d, half, h0, h1, h2, c0, c1, c2):
    """``kernels._apply`` for records: v_a -= (1+α)/2 h, v_b += (1+α)/2 h; returns the new
    squared speeds |v - c|² of a and b. (The kernels' own functions would need the
    records transposed, a view whose reference counting costs more than the collision.)"""
    sa = 0.0
    sb = 0.0
    for k in range(d):
        h = h0 if k == 0 else (h1 if k == 1 else h2)
        centre = c0 if k == 0 else (c1 if k == 1 else c2)
        va = records[a, k] - half * h
        vb = records[b, k] + half * h
        records[a, k] = va
        records[b, k] = vb
        sa += (va - centre) * (va - centre)
        sb += (vb - centre) * (vb - centre)
    return sa, sb


@kernel
def _draw_i(records, layout, probability, lo, width, s0, s1, s2, s3):
    """One draw of i: (class k, slot a, u) with k ∝ slots × U_k, a uniform in class k and
    u uniform; the slot's record is prefetched. Kept at use if u U_k < s of slot a."""
    x, s0, s1, s2, s3 = _next(s0, s1, s2, s3)
    c = np.int64(((x >> _SHIFT_32) * np.uint64(width)) >> _SHIFT_32)
    if np.float64((x >> _SHIFT_11) & _LOW_32) * _TWO_M32 >= probability[c]:
        c = layout[_ALIAS_ROW, c]
    k = lo + c
    x, s0, s1, s2, s3 = _next(s0, s1, s2, s3)
    a = layout[_BASE_ROW, k] + np.int64(
        ((x >> _SHIFT_32) * np.uint64(layout[_CAPACITY_ROW, k])) >> _SHIFT_32
    )
    prefetch_row(records, a)
    return k, a, np.float64((x >> _SHIFT_11) & _LOW_32) * _TWO_M32, s0, s1, s2, s3


@kernel
def _draw_j(records, slots, s0, s1, s2, s3):
    """One draw of j: a uniform slot (kept at use if it holds a particle other than i)."""
    x, s0, s1, s2, s3 = _next(s0, s1, s2, s3)
    b = np.int64(((x >> _SHIFT_32) * np.uint64(slots)) >> _SHIFT_32)
    prefetch_row(records, b)
    return b, s0, s1, s2, s3


@inline
def _classes_loop(velocity, state, collisions, work, d):
    """Body of ``collide_speed_classes`` for a literal dimension ``d``; returns the draws of i."""
    restitution = collisions.restitution
    pair_coefficient = collisions.pair_coefficient
    duration = collisions.duration
    poisson = collisions.poisson
    bounds = collisions.bounds
    carry = collisions.carry
    tally = collisions.tally
    records = work.records
    record_bits = work.record_bits
    layout = work.layout
    probability = work.probability
    n = velocity.shape[1]
    if n < 2 or duration <= 0.0:
        return 0
    half = 0.5 * (1.0 + restitution)
    c0 = bounds[0]
    c1 = bounds[1]
    c2 = bounds[2] if d == 3 else 0.0
    lo, width, slots, total, top1, top2 = _lay_out(
        velocity, c0, c1, c2, records, record_bits, layout, probability, d
    )
    if width == 0:
        tally[TALLY_EXCEEDED] += 1
        return 0
    if total <= 0.0:
        return 0
    s0, s1, s2, s3 = load_state(state)
    # rings of prepared draws; refilled whenever the layout changes (unused draws are
    # dropped: they are independent of everything, so dropping them biases nothing)
    ring_k = np.empty(AHEAD, dtype=np.int64)
    ring_a = np.empty(AHEAD, dtype=np.int64)
    ring_u = np.empty(AHEAD)
    ring_b = np.empty(AHEAD, dtype=np.int64)
    for r in range(AHEAD):
        ring_k[r], ring_a[r], ring_u[r], s0, s1, s2, s3 = _draw_i(
            records, layout, probability, lo, width, s0, s1, s2, s3
        )
        ring_b[r], s0, s1, s2, s3 = _draw_j(records, slots, s0, s1, s2, s3)
    head_i = 0
    head_j = 0
    coefficient = pair_coefficient * (n - 1.0) * BOUND_SAFETY  # the pair bounds carry it too
    spacing = 1.0 / (coefficient * total)
    budget = duration
    if not poisson:
        budget += carry[0] * spacing
    candidates = 0
    accepted = 0
    draws = 0
    raised = 0
    while True:
        if poisson:
            e, s0, s1, s2, s3 = _exponential(s0, s1, s2, s3)
            step = e * spacing
        else:
            step = spacing
        if step > budget:
            break
        budget -= step
        candidates += 1
        # i ∝ s_i: a class ∝ slots × U_k (alias table), a uniform slot of it, kept if it
        # holds a particle, with probability s_i / U_k
        while True:
            k = ring_k[head_i]
            a = ring_a[head_i]
            u = ring_u[head_i]
            ring_k[head_i], ring_a[head_i], ring_u[head_i], s0, s1, s2, s3 = _draw_i(
                records, layout, probability, lo, width, s0, s1, s2, s3
            )
            head_i = (head_i + 1) % AHEAD
            draws += 1
            if u * _UPPER[k] < records[a, SPEED]:
                break
        # j: a uniform occupied slot other than a
        while True:
            b = ring_b[head_j]
            ring_b[head_j], s0, s1, s2, s3 = _draw_j(records, slots, s0, s1, s2, s3)
            head_j = (head_j + 1) % AHEAD
            if b != a and records[b, SPEED] >= 0.0:
                break
        bound = (records[a, SPEED] + records[b, SPEED]) * BOUND_SAFETY
        g0 = records[a, 0] - records[b, 0]
        g1 = records[a, 1] - records[b, 1]
        g2 = records[a, 2] - records[b, 2]  # 0 in d = 2
        code, h0, h1, h2, s0, s1, s2, s3 = _trial_relative(
            g0, g1, g2, d, HARD_SPHERES, bound * bound, s0, s1, s2, s3
        )
        if code == 2:  # cannot happen: |v_i - v_j| <= |v_i - c| + |v_j - c|
            tally[TALLY_EXCEEDED] += 1
            continue
        if code == 0:
            continue
        sa, sb = _collide_records(records, a, b, d, half, h0, h1, h2, c0, c1, c2)
        accepted += 1
        if max(sa, sb) >= _UPPER[CLASS_COUNT - 1] ** 2:
            tally[TALLY_EXCEEDED] += 1
            break
        total -= records[a, SPEED] + records[b, SPEED]
        old_a = _class_of(record_bits[a, SPEED])
        old_b = _class_of(record_bits[b, SPEED])
        records[a, SPEED] = np.sqrt(sa)
        records[b, SPEED] = np.sqrt(sb)
        new_a = _class_of(record_bits[a, SPEED])
        new_b = _class_of(record_bits[b, SPEED])
        sa = records[a, SPEED]
        sb = records[b, SPEED]
        total += sa + sb
        grew, top1, top2 = _raise(sa * sa, sb * sb, top1, top2)
        if grew:
            raised += 1
        spacing = 1.0 / (coefficient * total)
        # move the records whose class changed to the first free slot of their new class;
        # the last member of the old class fills the vacated slot
        full = False
        for which in range(2):
            slot = a if which == 0 else b
            old = old_a if which == 0 else old_b
            new = new_a if which == 0 else new_b
            if new == old:
                continue
            if layout[_COUNT_ROW, new] >= layout[_CAPACITY_ROW, new]:
                full = True
                break
            target = layout[_BASE_ROW, new] + layout[_COUNT_ROW, new]
            layout[_COUNT_ROW, new] += 1
            records[target, 0] = records[slot, 0]
            records[target, 1] = records[slot, 1]
            records[target, 2] = records[slot, 2]
            records[target, SPEED] = records[slot, SPEED]
            last = layout[_BASE_ROW, old] + layout[_COUNT_ROW, old] - 1
            layout[_COUNT_ROW, old] -= 1
            if last != slot:
                records[slot, 0] = records[last, 0]
                records[slot, 1] = records[last, 1]
                records[slot, 2] = records[last, 2]
                records[slot, SPEED] = records[last, SPEED]
                if last == b:
                    b = slot  # b was the last member of a's class and filled a's slot
            records[last, SPEED] = EMPTY
        if full:  # a class with no free slot: lay everything out again
            _gather(records, layout, lo, width, velocity, d)
            lo, width, slots, total, top1, top2 = _lay_out(
                velocity, c0, c1, c2, records, record_bits, layout, probability, d
            )
            if width == 0:
                tally[TALLY_EXCEEDED] += 1
                break
            spacing = 1.0 / (coefficient * total)
            for r in range(AHEAD):
                ring_k[r], ring_a[r], ring_u[r], s0, s1, s2, s3 = _draw_i(
                    records, layout, probability, lo, width, s0, s1, s2, s3
                )
                ring_b[r], s0, s1, s2, s3 = _draw_j(records, slots, s0, s1, s2, s3)
    _gather(records, layout, lo, width, velocity, d)
    store_state(state, s0, s1, s2, s3)
    if not poisson:
        carry[0] = budget / spacing
    bounds[d] = top1
    bounds[d + 1] = top2
    tally[TALLY_CANDIDATES] += candidates
    tally[TALLY_ACCEPTED] += accepted
    tally[TALLY_RAISED] += raised
    return draws


@kernel
def collide_speed_classes(velocity, state, collisions, work):
    """Hard-sphere collisions of all particles for ``collisions.duration`` (module
    docstring).

    velocity (d, N), state and ``collisions`` (a ``kernels.Collisions``; its kernel is
    hard spheres whatever it says) as in ``kernels.collide_range``; ``bounds[:d]`` is the
    centre c of the speeds s_i (any fixed velocity is exact; the mean velocity is the
    tightest) and ``bounds[d], bounds[d+1]`` are refilled with bounds of the two largest
    speeds. The particles come back in another order. Work arrays: ``work``, a
    :class:`Work` (``SpeedClasses.arrays()``). ``tally`` += candidates,
    accepted, speed-bound raises, and in ``tally[TALLY_EXCEEDED]`` a particle beyond the
    last class (the call stops). Returns the number of draws of i (candidates plus
    redraws).
    """
    if velocity.shape[0] == 3:
        return _classes_loop(velocity, state, collisions, work, 3)
    return _classes_loop(velocity, state, collisions, work, 2)
