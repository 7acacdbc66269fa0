"""Numba kernels of the inhomogeneous DSMC engine (d = 2, periodic square box, M x M cells).

The gas is the stationary representation of the homogeneous cooling state
(costantini2010): between collisions dr/dτ = w and dw/dτ = ω0 w (ω0 = ``drag_rate``).
Units: m = σ = 1, initial temperature T0 = 1.

Data layout (struct of arrays, double-buffered)
-----------------------------------------------
``position`` and ``velocity`` are C-contiguous float64 arrays of shape ``(2, 2, n)`` and
``labels`` an int64 array of shape ``(2, 2, n)``: index 0 is the buffer, index 1 the
component (x, y) or, for ``labels``, (identity of the particle, identity of its last
collision partner, -1 before its first collision), index 2 the particle. The particles
live in buffer ``tally[TALLY_PARITY]``; every step sorts them by cell into the other
buffer (a counting sort) and flips the parity, so the particles of cell c are the
contiguous range ``cell_start[c]..cell_start[c + 1] - 1`` during the collision stage.
The identities follow the particles through the sort (they number the particles of
the initial state, 0..n-1). Moving all six arrays every step is not what the step costs:
a variant that left the particles in place and sorted only their indices (velocities
and moments read through them) took 10.3-13.1 ns a particle-step against this layout's
10.0-11.6, streaming and sort without the collisions, 3 x 10³ to 3 x 10⁵ particles
(Intel Xeon, 2026-11-28).

One step (``advance``)
----------------------
1. free streaming with drag, exact: r += w (e^{ω0 Δτ} - 1)/ω0 (w Δτ at ω0 = 0),
   w *= e^{ω0 Δτ}, periodic wrap into [0, L);
2. counting sort into the M x M cells (cell (ix, iy) = iy M + ix, ix = floor(x M/L)),
   accumulating each cell's Σw, Σ|w|² and its two largest speeds |w| on the way: the
   cell's temperature and its rigorous relative-speed bound B = top1 + top2 (speeds
   about the origin, the gas being at rest; raised after any collision that creates
   a faster particle, so an acceptance probability never exceeds 1);
3. collisions in every cell holding at least 2 particles (cells with fewer do nothing
   and leave their carried fraction as it is), with the real density of the cell
   n_c = count/(Λ A_c), A_c = (L/M)²:

   ``RULE_MAJORANT``: Bird's no-time-counter scheme with the rigorous majorant of
   :mod:`kinetic.dsmc.kernels` (the helpers of ``collide_range``): candidate pairs at
   the rate ``pair_coefficient x count(count - 1)/2 x B``, accepted with |w_ij|/B, σ̂
   from its conditional law ∝ |ŵ_ij·σ̂|, so each pair of a cell collides at the rate
   ``pair_coefficient x |w_ij|``. The front passes ``pair_coefficient = S/(Λ A_c) x
   N_sim/(N_sim - 1)`` (S = 2σ, the 2D hard-disk cross section): a particle meets the
   real density (count - 1)/(Λ A_c) of the *other* particles of its cell, and since a
   particle's cell holds on average (N_sim - 1)/M² others, each particle collides on
   average at exactly n S <|w_ij|> = 2 n σ √(πT/m) at any M (at M = 1 the coefficient
   is the homogeneous engine's S n/(N_sim - 1)), as long as molecular chaos holds:
   with few particles per cell the rate comes out higher (+0.3 % at 16 simulated
   particles per cell, 1.5 % recollisions), since a pair that has just collided keeps
   its larger-than-average |w_ij| (elastic) and stays in the cell, where it meets
   again at a rate ∝ 1/count. The fraction of a candidate left at
   the end of the step is carried to the next step of the same cell (``carry[c]``).

   ``RULE_PAPER`` (costantini2010, Appendix): ½ count ω_c(T_c) Δτ collisions per step
   (the fractional part carried to the next step of the cell), T_c = Σ|w - ū|²/(2(count
   - 1)) the cell's (unbiased) velocity variance, ω_c = 2 n_c σ √(π T_c/m); each
   collision's pair and σ̂ drawn at random in the cell, accepted with probability
   ∝ Θ(w_ij·σ̂) w_ij·σ̂, redrawn until one is accepted. Since n_c counts the colliding
   particle itself, the mean number of collisions per particle exceeds 2 n σ √(πT/m)
   by the factor 1 + (M² - 1)/N_sim (Σ_c count² over multinomial counts), i.e. by one
   over the mean number of simulated particles per cell. Drawn as in ``RULE_MAJORANT``
   (accept the pair with |w_ij|/B, then σ̂ from its conditional law): the accepted
   (i, j, σ̂) have exactly the law ∝ Θ(w_ij·σ̂) w_ij·σ̂ (σ̂ and -σ̂ give the same
   collision), with fewer random numbers than drawing σ̂ first.

   Both: w_i' = w_i - (1+α)/2 (w_ij·σ̂)σ̂, w_j' = w_j + (1+α)/2 (w_ij·σ̂)σ̂; the energy
   lost, (1 - α²)(w_ij·σ̂)²/4 per collision (m = 1), is summed in ``energy[0]``. A
   collision whose two partners' previous collisions were with each other is counted
   in ``tally[TALLY_REPEATED]`` (a recollision of the same pair in a row);
4. the centre-of-mass velocity (from the cell sums, before the collisions, which
   conserve momentum) is subtracted, in the next step's streaming (so it is applied
   in the same passes; ``moments`` carries it from one call to the next): the total
   momentum never exceeds the round-off of the last two steps' collisions (the drag
   would amplify round-off momentum exponentially).

Random numbers: one xoshiro256+ stream per realization (a ``state`` row of
:mod:`kinetic.rng`), held in four scalars inside the step loop. No kernel allocates in
its loops, prints, or touches files.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from kinetic.dsmc.kernels import (
    BOUND_SAFETY,
    HARD_SPHERES,
    _apply,
    _majorant,
    _pair,
    _raise,
    _trial,
    _two_largest,
    maxwellian,
)
from kinetic.fourier import mode_sums, mode_terms
from kinetic.jit import inline, kernel, refcount_free
from kinetic.rng import load_state, store_state
from kinetic.rng import xoshiro_uniform as _uniform

__all__ = [
    "CROSS_SECTION",
    "RULE_MAJORANT",
    "RULE_PAPER",
    "TALLY_CANDIDATES",
    "TALLY_COLLISIONS",
    "TALLY_EXCEEDED",
    "TALLY_PARITY",
    "TALLY_PARTICLE_STEPS",
    "TALLY_REPEATED",
    "TALLY_SIZE",
    "TALLY_STEPS",
    "Cells",
    "Gas",
    "Step",
    "advance",
    "collide_cells",
    "initial_state",
    "observe",
    "run_samples",
]

RULE_PAPER = 0
RULE_MAJORANT = 1

CROSS_SECTION = 2.0
"""S = 2σ (σ = 1): ∫ over the half circle of ĝ·σ̂, the 2D hard-disk collision cross section."""

TALLY_CANDIDATES = 0
TALLY_COLLISIONS = 1
TALLY_REPEATED = 2
TALLY_PARTICLE_STEPS = 3
TALLY_STEPS = 4
TALLY_PARITY = 5
TALLY_EXCEEDED = 6
TALLY_SIZE = 7

MAX_ATTEMPTS = 1_000_000
"""Rule "paper": draws of a pair before a cell gives up a collision. Only a cell whose
particles all move alike (no pair approaches, while round-off leaves T_c > 0) reaches
it; a real cell accepts a pair within a few draws."""

N_OBSERVABLES = 9
"""Row of ``observe``: T, Re/Im of the modes wy_kx and wx_ky, their normalisers Σ w_y²
and Σ w_x², momentum x and y (Σ w/(n √T))."""


@kernel
def initial_state(position, velocity, labels, state, box_side):
    """Uniform positions in [0, L)², Gaussian velocities with zero total momentum and
    Σ|w|² = 2 n exactly (T0 = 1), identities 0..n-1, no previous partner.

    position, velocity: (2, 2, n) float64, labels: (2, 2, n) int64, filled in buffer 0.
    state: (4,) uint64 stream, advanced (positions first, then velocities).
    """
    n = position.shape[2]
    s0, s1, s2, s3 = load_state(state)
    for i in range(n):
        u, s0, s1, s2, s3 = _uniform(s0, s1, s2, s3)
        v, s0, s1, s2, s3 = _uniform(s0, s1, s2, s3)
        position[0, 0, i] = u * box_side
        position[0, 1, i] = v * box_side
        labels[0, 0, i] = i
        labels[0, 1, i] = -1
    store_state(state, s0, s1, s2, s3)
    maxwellian(velocity[0], state, 1.0)


class Step(NamedTuple):
    """The settings of every step: ``rule`` (RULE_PAPER or RULE_MAJORANT), ``restitution``
    α in (0, 1], ``box_side`` L, ``cells_per_side`` M, ``density_per_count`` 1/(Λ A_c)
    (a cell's real density is count x density_per_count: RULE_PAPER),
    ``pair_coefficient`` (collision rate per pair per unit relative speed:
    RULE_MAJORANT), ``time_step`` Δτ and ``drag_rate`` ω0 (>= 0)."""

    rule: int
    restitution: float
    box_side: float
    cells_per_side: int
    density_per_count: float
    pair_coefficient: float
    time_step: float
    drag_rate: float


class Cells(NamedTuple):
    """Per-cell arrays: work arrays ``cell_of`` (n,) int64, ``cell_start`` (M² + 1,) int64
    (left holding the cell ranges of the last sort), ``cell_fill`` (M²,) int64;
    ``carry`` (M²,) float64, the carried fraction of each cell (a candidate for
    RULE_MAJORANT, a collision for RULE_PAPER); ``moments`` (M², 5) float64, each cell's
    Σw_x, Σw_y, Σ|w|² and two largest |w|² after the sort (its temperature and
    relative-speed bound; zeros for a new state, then kept between calls: it holds the
    momentum to remove); ``terms`` (4, n) float64, the observer's work array (the mode
    terms of ``observe``)."""

    cell_of: np.ndarray
    cell_start: np.ndarray
    cell_fill: np.ndarray
    carry: np.ndarray
    moments: np.ndarray
    terms: np.ndarray


class Gas(NamedTuple):
    """One realization: ``position``, ``velocity`` (2, 2, n) float64 and ``labels`` (2, 2,
    n) int64 (layout above; the current buffer is ``tally[TALLY_PARITY]``), ``state``
    (4,) uint64 stream, ``tally`` (TALLY_SIZE,) int64 += candidates, collisions,
    repeated collisions, particle steps, steps (and the parity, flipped each step),
    ``energy`` (1,) float64 += energy lost in collisions (sum over simulated particles,
    m = 1)."""

    position: np.ndarray
    velocity: np.ndarray
    labels: np.ndarray
    state: np.ndarray
    tally: np.ndarray
    energy: np.ndarray


@inline
def _cell_statistics(velocity, first, last):
    """Mean velocity, Σ|w - ū|² and the two largest |w - ū| of particles first..last-1."""
    n = last - first
    m0 = 0.0
    m1 = 0.0
    for i in range(first, last):
        m0 += velocity[0, i]
        m1 += velocity[1, i]
    m0 /= n
    m1 /= n
    total = 0.0
    top1 = 0.0
    top2 = 0.0
    for i in range(first, last):
        a = velocity[0, i] - m0
        b = velocity[1, i] - m1
        s = a * a + b * b
        total += s
        top1, top2 = _two_largest(s, top1, top2)
    return m0, m1, total, math.sqrt(top1), math.sqrt(top2)


@inline
def _accumulate(moments, c, wx, wy):
    """Add a particle of velocity (wx, wy) to row c of the cell moments: Σw_x, Σw_y,
    Σ|w|² and the two largest |w|² (columns 0..4), in place (the sort's order of
    particles visits the cells in turn)."""
    s = wx * wx + wy * wy
    moments[c, 0] += wx
    moments[c, 1] += wy
    moments[c, 2] += s
    if s > moments[c, 4]:
        if s > moments[c, 3]:
            moments[c, 4] = moments[c, 3]
            moments[c, 3] = s
        else:
            moments[c, 4] = s


@kernel
def _accumulated(m0, m1, m2, m3, m4, wx, wy):
    """``_accumulate`` on a cell's moments held as values (m0..m4, its columns 0..4):
    the same arithmetic, for a loop over one cell's particles (``_cell_moments``, the GPU
    engine's gather), which keeps them in registers."""
    s = wx * wx + wy * wy
    m0 += wx
    m1 += wy
    m2 += s
    if s > m4:
        if s > m3:
            m4 = m3
            m3 = s
        else:
            m4 = s
    return m0, m1, m2, m3, m4


@inline
def _cell_moments(velocity, cell_start, moments):
    """Fill ``moments`` (M², 5) from particles sorted by cell (as the sort does)."""
    for c in range(moments.shape[0]):
        m0 = 0.0
        m1 = 0.0
        m2 = 0.0
        m3 = 0.0
        m4 = 0.0
        for i in range(cell_start[c], cell_start[c + 1]):
            m0, m1, m2, m3, m4 = _accumulated(m0, m1, m2, m3, m4, velocity[0, i], velocity[1, i])
        moments[c, 0] = m0
        moments[c, 1] = m1
        moments[c, 2] = m2
        moments[c, 3] = m3
        moments[c, 4] = m4


@inline
def _collided(velocity, ident, partner, i, j, half, h0, h1, c0, c1, top1, top2):
    """Apply an accepted collision; returns (repeated, |h|², raised, top1, top2)."""
    sa, sb = _apply(velocity, i, j, 2, half, h0, h1, 0.0, c0, c1, 0.0)
    pi = ident[i]
    pj = ident[j]
    repeated = partner[i] == pj and partner[j] == pi
    partner[i] = pj
    partner[j] = pi
    raised, top1, top2 = _raise(sa, sb, top1, top2)
    return repeated, h0 * h0 + h1 * h1, raised, top1, top2


@inline
def _collide_cell(
    velocity,
    ident,
    partner,
    first,
    last,
    moments,
    c,
    carry,
    rule,
    half,
    density_per_count,
    pair_coefficient,
    time_step,
    candidates,
    collisions,
    repeated,
    exceeded,
    lost,
    s0,
    s1,
    s2,
    s3,
):
    """Collision stage of cell c for one step: particles ``first..last-1`` of ``velocity``
    (2, n) (``ident``, ``partner``: their labels), the cell's moments row ``moments[c]``
    and carried fraction ``carry[c]`` (updated), settings of the :class:`Step` (``half`` =
    (1+α)/2). The tallies ``candidates``, ``collisions``, ``repeated``, ``exceeded``, the
    sum of |h|² ``lost`` and the stream are passed through and returned, in that order:
    ``_collide_cells`` runs it on every cell of a realization with one stream (CPU), the
    CUDA backend on one thread per cell, each with its own stream
    (:mod:`kinetic.dsmc.inhomogeneous_gpu`)."""
    count = last - first
    if count < 2:
        return candidates, collisions, repeated, exceeded, lost, s0, s1, s2, s3
    # speeds about the origin (the gas is at rest): |w_ij| <= top1 + top2
    c0 = 0.0
    c1 = 0.0
    top1 = math.sqrt(moments[c, 3])
    top2 = math.sqrt(moments[c, 4])
    if top1 + top2 <= 0.0:
        # all velocities equal: no pair approaches
        return candidates, collisions, repeated, exceeded, lost, s0, s1, s2, s3
    if rule == RULE_MAJORANT:
        n_pairs = 0.5 * count * (count - 1.0)
        coefficient = pair_coefficient
        bound_sq, spacing = _majorant(HARD_SPHERES, coefficient, n_pairs, top1, top2)
        budget = time_step + carry[c] * spacing
        while spacing <= budget:
            budget -= spacing
            candidates += 1
            a, b, s0, s1, s2, s3 = _pair(count, s0, s1, s2, s3)
            i = first + a
            j = first + b
            code, h0, h1, _h2, s0, s1, s2, s3 = _trial(
                velocity, i, j, 2, HARD_SPHERES, bound_sq, s0, s1, s2, s3
            )
            if code == 0:
                continue
            if code == 2:  # impossible with a rigorous bound; counted, bound redone
                exceeded += 1
                c0, c1, total, top1, top2 = _cell_statistics(velocity, first, last)
                bound_sq, spacing = _majorant(HARD_SPHERES, coefficient, n_pairs, top1, top2)
                continue
            again, hh, raised, top1, top2 = _collided(
                velocity, ident, partner, i, j, half, h0, h1, c0, c1, top1, top2
            )
            collisions += 1
            repeated += again
            lost += hh
            if raised:
                bound_sq, spacing = _majorant(HARD_SPHERES, coefficient, n_pairs, top1, top2)
        carry[c] = budget / spacing
    else:
        m0 = moments[c, 0]
        m1 = moments[c, 1]
        total = moments[c, 2] - (m0 * m0 + m1 * m1) / count  # Σ|w - ū|²
        temperature = max(total, 0.0) / (2.0 * (count - 1.0))
        real_density = count * density_per_count
        omega = 2.0 * real_density * math.sqrt(math.pi * temperature)
        expected = 0.5 * count * omega * time_step + carry[c]
        n_collisions = int(expected)
        carry[c] = expected - n_collisions
        bound = (top1 + top2) * BOUND_SAFETY
        bound_sq = bound * bound
        for _ in range(n_collisions):
            code = 0
            for _attempt in range(MAX_ATTEMPTS):
                candidates += 1
                a, b, s0, s1, s2, s3 = _pair(count, s0, s1, s2, s3)
                i = first + a
                j = first + b
                code, h0, h1, _h2, s0, s1, s2, s3 = _trial(
                    velocity, i, j, 2, HARD_SPHERES, bound_sq, s0, s1, s2, s3
                )
                if code == 1:
                    break
                if code == 2:
                    exceeded += 1
                    c0, c1, total, top1, top2 = _cell_statistics(velocity, first, last)
                    bound = (top1 + top2) * BOUND_SAFETY
                    bound_sq = bound * bound
            if code != 1:  # no pair approaches (equal velocities): nothing to do
                carry[c] = 0.0
                break
            again, hh, raised, top1, top2 = _collided(
                velocity, ident, partner, i, j, half, h0, h1, c0, c1, top1, top2
            )
            collisions += 1
            repeated += again
            lost += hh
            if raised:
                bound = (top1 + top2) * BOUND_SAFETY
                bound_sq = bound * bound
    return candidates, collisions, repeated, exceeded, lost, s0, s1, s2, s3


@inline
def _collide_cells(velocity, labels, cells, step, tally, energy, s0, s1, s2, s3):
    """Collision stage of every cell (particles sorted by cell, ``moments`` filled by
    ``_cell_moments`` or the sort), the cells in order with one stream. Returns the
    stream."""
    cell_start = cells.cell_start
    n_cells = cell_start.shape[0] - 1
    half = 0.5 * (1.0 + step.restitution)
    loss = 0.25 * (1.0 - step.restitution * step.restitution)
    ident = labels[0]
    partner = labels[1]
    candidates = 0
    collisions = 0
    repeated = 0
    exceeded = 0
    lost = 0.0
    for c in range(n_cells):
        candidates, collisions, repeated, exceeded, lost, s0, s1, s2, s3 = _collide_cell(
            velocity,
            ident,
            partner,
            cell_start[c],
            cell_start[c + 1],
            cells.moments,
            c,
            cells.carry,
            step.rule,
            half,
            step.density_per_count,
            step.pair_coefficient,
            step.time_step,
            candidates,
            collisions,
            repeated,
            exceeded,
            lost,
            s0,
            s1,
            s2,
            s3,
        )
    tally[TALLY_CANDIDATES] += candidates
    tally[TALLY_COLLISIONS] += collisions
    tally[TALLY_REPEATED] += repeated
    tally[TALLY_EXCEEDED] += exceeded
    energy[0] += loss * lost
    return s0, s1, s2, s3


@kernel
def collide_cells(velocity, labels, cells, state, step, tally, energy):
    """The collision stage of one step alone (step 3), for particles already sorted.

    velocity: (2, n) float64 and labels: (2, n) int64 of one buffer (particles of cell
    c at cells.cell_start[c]..cell_start[c + 1] - 1). ``cells.moments`` is filled here
    from the velocities. state: (4,) uint64 stream. Other arguments as in ``advance``.
    """
    _cell_moments(velocity, cells.cell_start, cells.moments)
    s0, s1, s2, s3 = _collide_cells(
        velocity, labels, cells, step, tally, energy, state[0], state[1], state[2], state[3]
    )
    store_state(state, s0, s1, s2, s3)


@refcount_free
def advance(gas, cells, step, n_steps):
    """``n_steps`` steps of the inhomogeneous DSMC (see the module docstring) of ``gas``
    (a :class:`Gas`, updated) with the :class:`Step` settings ``step``; ``cells``: the
    :class:`Cells` arrays (zeros for a new state, then kept between calls)."""
    position = gas.position
    velocity = gas.velocity
    labels = gas.labels
    state = gas.state
    tally = gas.tally
    energy = gas.energy
    cell_of = cells.cell_of
    cell_start = cells.cell_start
    cell_fill = cells.cell_fill
    moments = cells.moments
    box_side = step.box_side
    cells_per_side = step.cells_per_side
    time_step = step.time_step
    drag_rate = step.drag_rate
    n = position.shape[2]
    m = cells_per_side
    n_cells = m * m
    inverse_cell = m / box_side
    growth = np.exp(drag_rate * time_step)
    shift = time_step if drag_rate == 0.0 else np.expm1(drag_rate * time_step) / drag_rate
    s0, s1, s2, s3 = load_state(state)
    for _ in range(n_steps):
        now = tally[TALLY_PARITY]
        r_src = position[now]
        w_src = velocity[now]
        l_src = labels[now]
        r_dst = position[1 - now]
        w_dst = velocity[1 - now]
        l_dst = labels[1 - now]
        # 4 of the previous step: its centre-of-mass velocity, from its cell sums
        # (before its collisions, which conserve momentum: what is left over is their
        # round-off, removed one step later)
        u0 = 0.0
        u1 = 0.0
        for c in range(n_cells):
            u0 += moments[c, 0]
            u1 += moments[c, 1]
        u0 /= n
        u1 /= n
        # 1: stream the positions (in place) and count the particles of each cell
        for c in range(n_cells + 1):
            cell_start[c] = 0
        for i in range(n):
            x, y, c = _streamed(
                r_src[0, i],
                r_src[1, i],
                w_src[0, i] - u0,
                w_src[1, i] - u1,
                shift,
                box_side,
                inverse_cell,
                m,
            )
            r_src[0, i] = x
            r_src[1, i] = y
            cell_of[i] = c
            cell_start[c + 1] += 1
        for c in range(n_cells):
            cell_start[c + 1] += cell_start[c]
            cell_fill[c] = cell_start[c]
            for k in range(5):
                moments[c, k] = 0.0
        # 2: counting sort into the other buffer, with the drag on the velocities and
        # the cells' velocity moments
        for i in range(n):
            c = cell_of[i]
            p = cell_fill[c]
            cell_fill[c] = p + 1
            wx = (w_src[0, i] - u0) * growth
            wy = (w_src[1, i] - u1) * growth
            r_dst[0, p] = r_src[0, i]
            r_dst[1, p] = r_src[1, i]
            w_dst[0, p] = wx
            w_dst[1, p] = wy
            l_dst[0, p] = l_src[0, i]
            l_dst[1, p] = l_src[1, i]
            _accumulate(moments, c, wx, wy)
        # 3: collisions
        s0, s1, s2, s3 = _collide_cells(w_dst, l_dst, cells, step, tally, energy, s0, s1, s2, s3)
        tally[TALLY_PARITY] = 1 - now
        tally[TALLY_STEPS] += 1
        tally[TALLY_PARTICLE_STEPS] += n
    store_state(state, s0, s1, s2, s3)


@inline
def _streamed(x, y, wx, wy, shift, box_side, inverse_cell, m):
    """Free flight of a particle at (x, y) with velocity (wx, wy) (the centre-of-mass
    velocity already removed) over a step (``shift`` = (e^{ω0 Δτ} - 1)/ω0), wrapped into
    [0, L)²; returns ``(x, y, c)``, c = iy M + ix its cell (``inverse_cell`` = M/L)."""
    x = x + wx * shift
    y = y + wy * shift
    if x >= box_side or x < 0.0:
        x -= box_side * math.floor(x / box_side)
        if x >= box_side:  # rounding of a tiny negative x + L
            x = 0.0
    if y >= box_side or y < 0.0:
        y -= box_side * math.floor(y / box_side)
        if y >= box_side:
            y = 0.0
    ix = int(x * inverse_cell)
    iy = int(y * inverse_cell)
    if ix >= m:
        ix = m - 1
    if iy >= m:
        iy = m - 1
    return x, y, iy * m + ix


@inline
def _observables(n, px, py, re_y, im_y, re_x, im_x, sum_xx, sum_yy, out):
    """Row ``out`` of ``observe`` from the sums over the n particles of w_x, w_y, the mode
    terms w_y cos/sin(k x), w_x cos/sin(k y), w_x² and w_y²."""
    ux = px / n
    uy = py / n
    temperature = (sum_xx + sum_yy - n * (ux * ux + uy * uy)) / (2.0 * n)
    norm = 1.0 / (n * math.sqrt(temperature))
    out[0] = temperature
    out[1] = re_y
    out[2] = im_y
    out[3] = re_x
    out[4] = im_x
    out[5] = sum_yy
    out[6] = sum_xx
    out[7] = px * norm
    out[8] = py * norm


@kernel
def observe(position, velocity, parity, wavenumber, terms, out):
    """Observables of the current buffer ``parity`` into ``out`` (N_OBSERVABLES,).

    out = [T, Re Σ w_y e^{ik x}, Im Σ w_y e^{ik x}, Re Σ w_x e^{ik y}, Im Σ w_x e^{ik y},
    Σ w_y², Σ w_x², Σ w_x/(n √T), Σ w_y/(n √T)] with T = Σ|w - u|²/(2n) about the mean
    velocity u (which the step has already removed, to round-off). ``terms`` (4, ≥ n)
    float64 is a work array (``kinetic.fourier.mode_terms``).
    """
    r = position[parity]
    w = velocity[parity]
    n = r.shape[1]
    px = 0.0
    py = 0.0
    sum_yy = 0.0
    sum_xx = 0.0
    for i in range(n):
        wx = w[0, i]
        wy = w[1, i]
        px += wx
        py += wy
        sum_xx += wx * wx
        sum_yy += wy * wy
    turns = wavenumber / (2.0 * math.pi)  # k x in turns: x / L
    for i in range(n):
        terms[0, i], terms[1, i], terms[2, i], terms[3, i] = mode_terms(
            turns * r[0, i], turns * r[1, i], w[0, i], w[1, i]
        )
    re_y, im_y, re_x, im_x = mode_sums(terms, n)
    _observables(n, px, py, re_y, im_y, re_x, im_x, sum_xx, sum_yy, out)


@refcount_free
def run_samples(gas, cells, step, steps_first, stride, wavenumber, observables, dissipated):
    """Advance and sample ``observables.shape[0]`` times: ``steps_first`` steps before
    the first sample, ``stride`` steps before each later one.

    observables: (n_samples, N_OBSERVABLES) float64 rows of ``observe``. dissipated:
    (n_samples,) float64 energy lost per simulated particle since the previous sample
    (``gas.energy[0]`` is reset at each sample; the caller resets it where the first
    interval starts). Other arguments as in ``advance``.
    """
    n = gas.position.shape[2]
    energy = gas.energy
    for s in range(observables.shape[0]):
        steps = steps_first if s == 0 else stride
        advance(gas, cells, step, steps)
        observe(
            gas.position,
            gas.velocity,
            gas.tally[TALLY_PARITY],
            wavenumber,
            cells.terms,
            observables[s],
        )
        dissipated[s] = energy[0] / n
        energy[0] = 0.0
