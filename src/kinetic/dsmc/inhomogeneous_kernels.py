"""Numba kernels of the inhomogeneous DSMC engine (d = 2, periodic square box, M x M cells).

The gas is the stationary representation of the homogeneous cooling state
(costantini2010): between collisions dr/dτ = w and dw/dτ = ω0 w (ω0 = ``drag_rate``).
Units: m = σ = 1, initial temperature T0 = 1.

Data layout (struct of arrays, cells with room to spare)
-------------------------------------------------------
``position`` and ``velocity`` are C-contiguous float64 arrays of shape ``(2, S)`` and
``labels`` an int64 array of shape ``(2, S)``: index 0 is the component (x, y) or, for
``labels``, (identity of the particle, identity of its last collision partner, -1 before
its first collision), index 1 the slot. Cell c owns the slots
``start[c]..start[c + 1] - 1`` and its particles fill the first ``count[c]`` of them
(S = N_sim + M² x slack: every layout gives each cell ``slack`` free slots beyond its
particles). A step moves only the particles that leave their cell: 3-12 % of them
at the documents' time steps and cells of 1-0.25 mean free paths, where a counting sort
of all of them into a second buffer (until revision 654b818) moved six arrays for every
particle. At 3 x 10⁴ particles (AMD EPYC, 2026-11-29, the old and new engines in one
process) a step took 1.3-1.6 times less time with cells of 0.5 mean free paths at the
paper's Δτ = 0.025 mean free times, 1.5-2.0 times less at 1, 1.1-1.2 at 0.25, and
1.1 times more at 0.125 and 0.1 (where it sorts). The identities follow the particles
(they number the particles of the initial state, 0..n-1); the order inside a cell is
whatever the moves left, which the collisions (pairs drawn at random in the cell) do not
see.

One step (``advance``)
----------------------
1. free streaming with drag, exact: r += w (e^{ω0 Δτ} - 1)/ω0 (w Δτ at ω0 = 0),
   w *= e^{ω0 Δτ}, periodic wrap into [0, L);
2. the cells brought up to date (cell (ix, iy) = iy M + ix, ix = floor(x M/L)), with
   each cell's Σw, Σ|w|² and its two largest speeds |w| on the way: the cell's
   temperature and its rigorous relative-speed bound B = top1 + top2 (speeds about the
   origin, the gas being at rest; raised after any collision that creates a faster
   particle, so an acceptance probability never exceeds 1). Cell by cell, a particle
   that stays is written back in its slot; one that leaves goes to the ``moving``
   buffer, and the cell's last particle fills its slot. The movers then join the end of
   their new cells. Where a cell has no free slot left, every particle is laid out
   afresh (``_lay_out``: a counting sort, each cell ``slack`` free slots again). A step
   after one in which more than ``RESORT_FRACTION`` of the particles changed cell sorts
   them all instead (``_sort_packed``: the cells packed without room, at one end of the
   slots and at the other in turn; the small cells of the convergence study, where
   moving that many one by one costs more than the sort);
3. collisions in every cell holding at least 2 particles (cells with fewer do nothing
   and leave their carried fraction, rule "paper", as it is), with the real density of the cell
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
   is the homogeneous engine's S n/(N_sim - 1)), as long as molecular chaos holds. A
   step's candidates are the ``x = Δτ/spacing`` its state calls for, rounded up or down
   with a fresh uniform phase (``floor(x + u)``, mean x; SPARTA's ``collide_modify remain
   no``), so that they depend on the cell's present state only. Carrying the fraction
   left at the end of a step into the cell's next step instead (until 2026-11-30, and
   SPARTA's default) makes each cell an integrate-and-fire clock: a cell that has just
   collided waits for a whole spacing, and with a few particles that stay in a cell for
   several steps the candidates then fall more often on states long without a
   collision. Measured at N = 1000, Λ = 10, α = 0.8 with the drag, cells of 0.125 mean
   free paths (3.8 simulated particles a cell; 2 realizations of 200 mean free times):
   the carried fraction raised the collision rate at a given T by 0.42 % and the
   dissipation by 1.07 %, and T_s fell 1.9 % below one cell's; with the fresh phase it
   lies 0.12, 0.33 and 0.28 % below at cells of 0.5, 0.25 and 0.125 mean free paths
   (± 0.04–0.05 %; 16 realizations of 1000 mean free times; docs/reproduced.md): in one
   cell a step's later collisions see the gas cooled by its earlier ones, which small
   cells do not, and at smaller steps the cells' loss of chaos takes over. (The elastic
   rate at 5 simulated particles a cell: +0.10 ± 0.02 % carried, +0.01 ± 0.05 % fresh.)
   With few particles a cell that stay in it a while DSMC also loses chaos
   (recollisions; ``tally[TALLY_REPEATED]``): at 3.8 simulated particles in cells of
   0.36 mean free paths T_s is 0.7 % above one cell's.

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
    "RESORT_FRACTION",
    "RULE_MAJORANT",
    "RULE_PAPER",
    "TALLY_CANDIDATES",
    "TALLY_COLLISIONS",
    "TALLY_EXCEEDED",
    "TALLY_LAST_MOVED",
    "TALLY_LAYOUTS",
    "TALLY_MOVED",
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
    "lay_out_initial",
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
TALLY_LAST_MOVED = 5
"""Not a sum: the particles that changed cell in the last step (it chooses the route of
the next one, ``RESORT_FRACTION``)."""
TALLY_EXCEEDED = 6
TALLY_MOVED = 7
TALLY_LAYOUTS = 8
"""Steps that laid every particle out afresh (the sorting route, or a cell without room)."""
TALLY_SIZE = 9

RESORT_FRACTION = 0.15
"""A step sorts every particle (``_sort_packed``) when more than this fraction changed cell
in the step before; fewer are moved one by one. Measured at 3 x 10⁴ particles (AMD EPYC,
2026-11-29), against the sort of every step: 12 % of the particles changing cell (cells of
0.25 mean free paths) still ran faster one by one (22 against 26 ns a particle-step), 21 %
(0.125) twice as slow (46-61 against 32)."""

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

    position, velocity: (2, n) float64, labels: (2, n) int64, filled (particle i in
    column i: ``lay_out_initial`` puts them in their cells).
    state: (4,) uint64 stream, advanced (positions first, then velocities).
    """
    n = position.shape[1]
    s0, s1, s2, s3 = load_state(state)
    for i in range(n):
        u, s0, s1, s2, s3 = _uniform(s0, s1, s2, s3)
        v, s0, s1, s2, s3 = _uniform(s0, s1, s2, s3)
        position[0, i] = u * box_side
        position[1, i] = v * box_side
        labels[0, i] = i
        labels[1, i] = -1
    store_state(state, s0, s1, s2, s3)
    maxwellian(velocity, state, 1.0)


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
    """Per-cell arrays and the buffer of the particles that change cell. ``start`` (M² + 1,) int64:
    cell c owns the slots start[c]..start[c + 1] - 1 (start[M²] = S); ``count`` (M²,) int64: its
    particles, in the first count[c] of them; ``carry`` (M²,) float64, the fraction of a collision
    each cell carries to its next step (RULE_PAPER; RULE_MAJORANT draws a fresh phase each step and
    leaves it alone); ``moments`` (M², 5) float64, each cell's Σw_x, Σw_y, Σ|w|² and two largest
    |w|² after the streaming (its temperature and relative-speed bound; zeros for a new state, then
    kept between calls: it holds the momentum to remove); ``terms`` (4, n) float64, the observer's
    work array (the mode terms of ``observe``); ``moving_position``, ``moving_velocity`` (2, n)
    float64, ``moving_labels`` (2, n) int64 and ``moving_cell`` (n,) int64, the particles on their
    way to another cell (n = N_sim: its length is the number of particles); ``fill`` (M²,) int64,
    the work array of a sort."""

    start: np.ndarray
    count: np.ndarray
    carry: np.ndarray
    moments: np.ndarray
    terms: np.ndarray
    moving_position: np.ndarray
    moving_velocity: np.ndarray
    moving_labels: np.ndarray
    moving_cell: np.ndarray
    fill: np.ndarray


class Gas(NamedTuple):
    """One realization: ``position``, ``velocity`` (2, S) float64 and ``labels`` (2, S)
    int64 by slot (layout above), ``state`` (4,) uint64 stream, ``tally`` (TALLY_SIZE,)
    int64 += candidates, collisions, repeated collisions, particle steps, steps,
    particles that changed cell and whole layouts (and the last step's movers),
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
def _cell_moments(velocity, start, count, moments):
    """Fill ``moments`` (M², 5) from the particles of each cell's slots."""
    for c in range(moments.shape[0]):
        m0 = 0.0
        m1 = 0.0
        m2 = 0.0
        m3 = 0.0
        m4 = 0.0
        for i in range(start[c], start[c] + count[c]):
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
    """Collision stage of cell c for one step: particles ``first..last-1`` of ``velocity`` (2, n)
    (``ident``, ``partner``: their labels), the cell's moments row ``moments[c]`` and carried
    fraction ``carry[c]`` (rule "paper"; updated), settings of the :class:`Step` (``half`` =
    (1+α)/2). The tallies ``candidates``, ``collisions``, ``repeated``, ``exceeded``, the sum of
    |h|² ``lost`` and the stream are passed through and returned, in that order: ``_collide_cells``
    runs it on every cell of a realization with one stream (CPU), the CUDA backend on one thread per
    cell, each with its own stream (:mod:`kinetic.dsmc.inhomogeneous_gpu`)."""
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
        # a fresh phase, not the fraction left by the cell's last step: see the docstring
        u, s0, s1, s2, s3 = _uniform(s0, s1, s2, s3)
        budget = time_step + u * spacing
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
    """Collision stage of every cell (``moments`` filled by the streaming or by
    ``_cell_moments``), the cells in order with one stream. Returns the stream."""
    start = cells.start
    count = cells.count
    half = 0.5 * (1.0 + step.restitution)
    loss = 0.25 * (1.0 - step.restitution * step.restitution)
    ident = labels[0]
    partner = labels[1]
    candidates = 0
    collisions = 0
    repeated = 0
    exceeded = 0
    lost = 0.0
    for c in range(count.shape[0]):
        candidates, collisions, repeated, exceeded, lost, s0, s1, s2, s3 = _collide_cell(
            velocity,
            ident,
            partner,
            start[c],
            start[c] + count[c],
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
    """The collision stage of one step alone (step 3), for particles in their cells.

    velocity: (2, S) float64 and labels: (2, S) int64 by slot (cell c's particles in
    slots cells.start[c]..cells.start[c] + cells.count[c] - 1). ``cells.moments`` is
    filled here from the velocities. state: (4,) uint64 stream. Other arguments as in
    ``advance``.
    """
    _cell_moments(velocity, cells.start, cells.count, cells.moments)
    s0, s1, s2, s3 = _collide_cells(
        velocity, labels, cells, step, tally, energy, state[0], state[1], state[2], state[3]
    )
    store_state(state, s0, s1, s2, s3)


@inline
def _copy_slot(position, velocity, labels, source, target):
    """The particle of slot ``source`` into slot ``target`` (all three arrays)."""
    position[0, target] = position[0, source]
    position[1, target] = position[1, source]
    velocity[0, target] = velocity[0, source]
    velocity[1, target] = velocity[1, source]
    labels[0, target] = labels[0, source]
    labels[1, target] = labels[1, source]


@inline
def _to_buffer(cells, k, x, y, wx, wy, ident, partner, d):
    """Row k of the moving buffer: a particle at (x, y), velocity (wx, wy), labels
    (ident, partner), bound for cell d."""
    cells.moving_position[0, k] = x
    cells.moving_position[1, k] = y
    cells.moving_velocity[0, k] = wx
    cells.moving_velocity[1, k] = wy
    cells.moving_labels[0, k] = ident
    cells.moving_labels[1, k] = partner
    cells.moving_cell[k] = d


@inline
def _from_buffer(cells, k, position, velocity, labels, p):
    """Row k of the moving buffer into slot p."""
    position[0, p] = cells.moving_position[0, k]
    position[1, p] = cells.moving_position[1, k]
    velocity[0, p] = cells.moving_velocity[0, k]
    velocity[1, p] = cells.moving_velocity[1, k]
    labels[0, p] = cells.moving_labels[0, k]
    labels[1, p] = cells.moving_labels[1, k]


@inline
def _lay_out(position, velocity, labels, cells, moving, slack):
    """Every particle laid out afresh: the first ``moving`` rows of the moving buffer
    (bound for ``moving_cell``) and the particles still in the cells (gathered into the
    buffer behind them), counting-sorted back into ranges of count + ``slack`` slots
    (the room every cell gets: (S - n)/M² at most); the moments recomputed on the way."""
    start = cells.start
    count = cells.count
    moments = cells.moments
    bound = cells.moving_cell
    n_cells = count.shape[0]
    k = moving
    for c in range(n_cells):
        for p in range(start[c], start[c] + count[c]):
            _to_buffer(
                cells,
                k,
                position[0, p],
                position[1, p],
                velocity[0, p],
                velocity[1, p],
                labels[0, p],
                labels[1, p],
                c,
            )
            k += 1
        count[c] = 0
    for i in range(k):
        count[bound[i]] += 1
    first = 0
    for c in range(n_cells):
        start[c] = first
        first += count[c] + slack
        count[c] = 0
        for m in range(5):
            moments[c, m] = 0.0
    start[n_cells] = first
    for i in range(k):
        c = bound[i]
        p = start[c] + count[c]
        count[c] += 1
        _from_buffer(cells, i, position, velocity, labels, p)
        _accumulate(moments, c, velocity[0, p], velocity[1, p])


@inline
def _room(gas, cells):
    """The free slots of every cell when the particles spread over all S slots."""
    return (gas.position.shape[1] - cells.moving_cell.shape[0]) // cells.count.shape[0]


@kernel
def lay_out_initial(gas, cells, step):
    """The particles of ``initial_state`` (in the moving buffer, particle i in row i)
    into their cells; the moments zeroed (no momentum to remove before the first step)."""
    n = cells.moving_cell.shape[0]
    m = step.cells_per_side
    inverse_cell = m / step.box_side
    for i in range(n):
        cells.moving_cell[i] = _cell_index(
            cells.moving_position[0, i], cells.moving_position[1, i], inverse_cell, m
        )
    cells.count[:] = 0
    cells.start[:] = 0
    _lay_out(gas.position, gas.velocity, gas.labels, cells, n, _room(gas, cells))
    cells.moments[:] = 0.0


@inline
def _stream_in_place(gas, cells, u0, u1, growth, shift, box_side, inverse_cell, m):
    """Steps 1-2 for the particles that stay: streamed and written back in their slots,
    the cells' moments summed; those that leave go to the moving buffer (the cell's last
    particle fills the slot). Returns how many left."""
    position = gas.position
    velocity = gas.velocity
    labels = gas.labels
    start = cells.start
    count = cells.count
    moments = cells.moments
    moving = 0
    for c in range(count.shape[0]):
        last = start[c] + count[c]
        m0 = 0.0
        m1 = 0.0
        m2 = 0.0
        m3 = 0.0
        m4 = 0.0
        p = start[c]
        while p < last:
            wx = velocity[0, p] - u0
            wy = velocity[1, p] - u1
            x, y, d = _streamed(
                position[0, p], position[1, p], wx, wy, shift, box_side, inverse_cell, m
            )
            wx *= growth
            wy *= growth
            if d == c:
                position[0, p] = x
                position[1, p] = y
                velocity[0, p] = wx
                velocity[1, p] = wy
                m0, m1, m2, m3, m4 = _accumulated(m0, m1, m2, m3, m4, wx, wy)
                p += 1
            else:
                _to_buffer(cells, moving, x, y, wx, wy, labels[0, p], labels[1, p], d)
                moving += 1
                last -= 1
                if p < last:  # the last particle, not streamed yet, takes the slot
                    _copy_slot(position, velocity, labels, last, p)
        count[c] = last - start[c]
        moments[c, 0] = m0
        moments[c, 1] = m1
        moments[c, 2] = m2
        moments[c, 3] = m3
        moments[c, 4] = m4
    return moving


@inline
def _join_cells(gas, cells, moving):
    """The first ``moving`` rows of the moving buffer onto the ends of their cells, their
    moments added. Those whose cell has no free slot left stay in the buffer, moved to
    its front; returns how many."""
    position = gas.position
    velocity = gas.velocity
    labels = gas.labels
    start = cells.start
    count = cells.count
    bound = cells.moving_cell
    left = 0
    for k in range(moving):
        d = bound[k]
        p = start[d] + count[d]
        if p < start[d + 1]:
            count[d] += 1
            _from_buffer(cells, k, position, velocity, labels, p)
            _accumulate(cells.moments, d, velocity[0, p], velocity[1, p])
        else:
            if left < k:
                _to_buffer(
                    cells,
                    left,
                    cells.moving_position[0, k],
                    cells.moving_position[1, k],
                    cells.moving_velocity[0, k],
                    cells.moving_velocity[1, k],
                    cells.moving_labels[0, k],
                    cells.moving_labels[1, k],
                    d,
                )
            left += 1
    return left


@inline
def _stream_all(gas, cells, u0, u1, growth, shift, box_side, inverse_cell, m):
    """Step 1 for every particle, each into row i of the moving buffer (the cells left
    empty for ``_lay_out``); returns how many changed cell."""
    position = gas.position
    velocity = gas.velocity
    labels = gas.labels
    start = cells.start
    count = cells.count
    k = 0
    moved = 0
    for c in range(count.shape[0]):
        for p in range(start[c], start[c] + count[c]):
            wx = velocity[0, p] - u0
            wy = velocity[1, p] - u1
            x, y, d = _streamed(
                position[0, p], position[1, p], wx, wy, shift, box_side, inverse_cell, m
            )
            _to_buffer(cells, k, x, y, wx * growth, wy * growth, labels[0, p], labels[1, p], d)
            moved += d != c
            k += 1
        count[c] = 0
    return moved


@inline
def _sort_packed(gas, cells, u0, u1, growth, shift, box_side, inverse_cell, m, base):
    """Steps 1-2 for every particle as a counting sort, from a layout without room (the
    last step's sort: slots start[0]..start[0] + n - 1) to slots base..base + n - 1
    (which must not overlap them: S >= 2n leaves room at one end or the other, so sorts
    alternate between the two ends): the positions streamed in place, then every
    particle copied to its cell's next slot, the drag applied to its velocity and the
    moments summed on the way (the old sort's two passes: a pass more, or the velocities
    written twice, made a step 10 % slower). Returns how many changed cell (the cell
    before the flight recomputed from the position: the slot's cell would take a search
    of the ranges)."""
    position = gas.position
    velocity = gas.velocity
    labels = gas.labels
    start = cells.start
    moments = cells.moments
    bound = cells.moving_cell
    fill = cells.fill
    n_cells = fill.shape[0]
    first = start[0]
    n = bound.shape[0]
    for c in range(n_cells):
        fill[c] = 0
    moved = 0
    for k in range(n):
        p = first + k
        x = position[0, p]
        y = position[1, p]
        c = _cell_index(x, y, inverse_cell, m)
        x, y, d = _streamed(
            x, y, velocity[0, p] - u0, velocity[1, p] - u1, shift, box_side, inverse_cell, m
        )
        position[0, p] = x
        position[1, p] = y
        bound[k] = d
        fill[d] += 1
        moved += d != c
    target = base
    for c in range(n_cells):
        size = fill[c]
        fill[c] = target
        target += size
        for j in range(5):
            moments[c, j] = 0.0
    for k in range(n):
        d = bound[k]
        q = fill[d]
        fill[d] = q + 1
        p = first + k
        wx = (velocity[0, p] - u0) * growth
        wy = (velocity[1, p] - u1) * growth
        position[0, q] = position[0, p]
        position[1, q] = position[1, p]
        velocity[0, q] = wx
        velocity[1, q] = wy
        labels[0, q] = labels[0, p]
        labels[1, q] = labels[1, p]
        _accumulate(moments, d, wx, wy)
    target = base
    for c in range(n_cells):  # fill[c] is where cell c now ends
        start[c] = target
        cells.count[c] = fill[c] - target
        target = fill[c]
    start[n_cells] = target
    return moved


@refcount_free
def advance(gas, cells, step, n_steps):
    """``n_steps`` steps of the inhomogeneous DSMC (see the module docstring) of ``gas``
    (a :class:`Gas`, updated) with the :class:`Step` settings ``step``; ``cells``: the
    :class:`Cells` arrays (laid out by ``lay_out_initial`` for a new state, then kept
    between calls)."""
    tally = gas.tally
    moments = cells.moments
    n = cells.moving_cell.shape[0]
    slots = gas.position.shape[1]
    m = step.cells_per_side
    n_cells = m * m
    box_side = step.box_side
    inverse_cell = m / box_side
    rate = step.drag_rate
    growth = np.exp(rate * step.time_step)
    shift = step.time_step if rate == 0.0 else np.expm1(rate * step.time_step) / rate
    s0, s1, s2, s3 = load_state(gas.state)
    for _ in range(n_steps):
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
        # 1-2: streaming, the cells brought up to date
        if tally[TALLY_LAST_MOVED] > RESORT_FRACTION * n:
            if cells.start[0] >= n:
                moved = _sort_packed(
                    gas, cells, u0, u1, growth, shift, box_side, inverse_cell, m, 0
                )
            elif cells.start[n_cells] <= slots - n:
                moved = _sort_packed(
                    gas, cells, u0, u1, growth, shift, box_side, inverse_cell, m, slots - n
                )
            else:  # the particles spread over every slot (room in each cell): via the buffer
                moved = _stream_all(gas, cells, u0, u1, growth, shift, box_side, inverse_cell, m)
                _lay_out(gas.position, gas.velocity, gas.labels, cells, n, 0)
            tally[TALLY_LAYOUTS] += 1
        else:
            moved = _stream_in_place(gas, cells, u0, u1, growth, shift, box_side, inverse_cell, m)
            left = _join_cells(gas, cells, moved)
            if left > 0:
                _lay_out(gas.position, gas.velocity, gas.labels, cells, left, _room(gas, cells))
                tally[TALLY_LAYOUTS] += 1
        tally[TALLY_LAST_MOVED] = moved
        tally[TALLY_MOVED] += moved
        # 3: collisions
        s0, s1, s2, s3 = _collide_cells(
            gas.velocity, gas.labels, cells, step, tally, gas.energy, s0, s1, s2, s3
        )
        tally[TALLY_STEPS] += 1
        tally[TALLY_PARTICLE_STEPS] += n
    store_state(gas.state, s0, s1, s2, s3)


@inline
def _streamed(x, y, wx, wy, shift, box_side, inverse_cell, m):
    """Free flight of a particle at (x, y) with velocity (wx, wy) (the centre-of-mass
    velocity already removed) over a step (``shift`` = (e^{ω0 Δτ} - 1)/ω0), wrapped into
    [0, L)²; returns ``(x, y, c)``, c = iy M + ix its cell (``inverse_cell`` = M/L)."""
    x = _wrapped(x + wx * shift, box_side)
    y = _wrapped(y + wy * shift, box_side)
    return x, y, _cell_index(x, y, inverse_cell, m)


@inline
def _cell_index(x, y, inverse_cell, m):
    """Cell iy M + ix of a point (x, y) in [0, L)² (``inverse_cell`` = M/L; a coordinate
    that rounds up to M lands in the last cell)."""
    return min(int(y * inverse_cell), m - 1) * m + min(int(x * inverse_cell), m - 1)


@inline
def _wrapped(x, box_side):
    """x in [0, L): one period added or taken away (a flight is far shorter than the box),
    the general reduction only behind that (a test LLVM would otherwise hoist: the
    division it needs for every particle took half of the streaming's time)."""
    if x >= box_side:
        x -= box_side  # exact for x < 2L
        if x >= box_side:
            x = _reduced(x, box_side)
    elif x < 0.0:
        x += box_side
        if x < 0.0:
            x = _reduced(x, box_side)
        elif x >= box_side:  # rounding of a tiny negative x + L
            x = 0.0
    return x


@inline
def _reduced(x, box_side):
    """x - L floor(x/L), kept in [0, L) where the quotient rounds across an integer."""
    x -= box_side * math.floor(x / box_side)
    if x < 0.0:
        x += box_side
    if x >= box_side:
        x = 0.0
    return x


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
def observe(position, velocity, start, count, wavenumber, terms, out):
    """Observables of the particles in the cells' slots into ``out`` (N_OBSERVABLES,).

    out = [T, Re Σ w_y e^{ik x}, Im Σ w_y e^{ik x}, Re Σ w_x e^{ik y}, Im Σ w_x e^{ik y},
    Σ w_y², Σ w_x², Σ w_x/(n √T), Σ w_y/(n √T)] with T = Σ|w - u|²/(2n) about the mean
    velocity u (which the step has already removed, to round-off). ``start``, ``count``:
    the cells' slots (``Cells``; one range [0, n) for particles side by side);
    ``terms`` (4, ≥ n) float64 is a work array (``kinetic.fourier.mode_terms``), filled
    cell after cell without the gaps between the cells. Its indices are unsigned: numba
    then adds no check for negative ones, which would stop the loop's vectorization
    (12.6 ns a particle; gathering the particles into one array first took 14, the
    terms in the slots' own places 26, at 59 particles a cell).
    """
    px = 0.0
    py = 0.0
    sum_yy = 0.0
    sum_xx = 0.0
    turns = wavenumber / (2.0 * math.pi)  # k x in turns: x / L
    n = 0
    for c in range(count.shape[0]):
        first = start[c]
        size = count[c]
        for i in range(first, first + size):
            wx = velocity[0, i]
            wy = velocity[1, i]
            px += wx
            py += wy
            sum_xx += wx * wx
            sum_yy += wy * wy
        to = np.uint64(n)
        origin = np.uint64(first)
        for k in range(np.uint64(size)):
            i = origin + k
            j = to + k
            terms[0, j], terms[1, j], terms[2, j], terms[3, j] = mode_terms(
                turns * position[0, i], turns * position[1, i], velocity[0, i], velocity[1, i]
            )
        n += size
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
    n = cells.moving_cell.shape[0]
    energy = gas.energy
    for s in range(observables.shape[0]):
        steps = steps_first if s == 0 else stride
        advance(gas, cells, step, steps)
        observe(
            gas.position,
            gas.velocity,
            cells.start,
            cells.count,
            wavenumber,
            cells.terms,
            observables[s],
        )
        dissipated[s] = energy[0] / n
        energy[0] = 0.0
