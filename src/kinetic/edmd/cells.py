"""Cells and pair prediction: cell membership, the pair collision time, the scan of the
neighbouring cells, the next cell crossing or wall hit, and a particle's prediction."""

from __future__ import annotations

import numpy as np

from kinetic.edmd.layout import (
    CELL,
    COUNT_EVENTS,
    COUNT_PAIR_TESTS,
    FACE,
    G_L,
    G_SIGMA,
    G_SIGMA2,
    G_W,
    GATHER_HEAD,
    I_DIM,
    I_N,
    I_WALL,
    PARTNER,
    PREDICTED_AT,
    ROW_SLOT,
    T_CELL,
    T_PAIR,
    X0,
    V,
    smaller,
)
from kinetic.jit import inline

# ----------------------------------------------------------------------------- geometry


@inline
def cell_insert(i, flat, members, occupancy, ints):
    """Append particle i to cell ``flat``; False (nothing changed) if the cell is full.

    ``members`` (n_cells, C) int32 lists the particles of each cell in its first
    ``occupancy[flat]`` entries; ``ints[i, ROW_SLOT]`` is i's position there.
    """
    count = occupancy[flat]
    if count >= members.shape[1]:
        return False
    members[flat, count] = i
    ints[i, ROW_SLOT] = count
    occupancy[flat] = count + 1
    return True


@inline
def cell_remove(i, flat, members, occupancy, ints):
    """Remove particle i from cell ``flat`` (the cell's last member takes its place)."""
    last = occupancy[flat] - 1
    position = ints[i, ROW_SLOT]
    moved = members[flat, last]
    members[flat, position] = moved
    ints[moved, ROW_SLOT] = position
    occupancy[flat] = last


@inline
def pair_time(xi, yi, zi, ui, vi, wi, phase, j, sx, sy, sz, t, sigma2, dim):
    """Absolute time of the next contact of i (position (xi, yi, zi) at time t, velocity
    (ui, vi, wi)) with the image of j shifted by (sx, sy, sz); +inf if they never touch.

    Uses the cancellation-free root (|r|² − σ²)/(−b + √disc); an approaching pair that
    already overlaps by round-off collides at once (returns t).
    """
    dx = phase[j, X0] + phase[j, V] * t + sx - xi
    dy = phase[j, X0 + 1] + phase[j, V + 1] * t + sy - yi
    du = phase[j, V] - ui
    dv = phase[j, V + 1] - vi
    b = dx * du + dy * dv
    r2 = dx * dx + dy * dy
    g2 = du * du + dv * dv
    if dim == 3:
        dz = phase[j, X0 + 2] + phase[j, V + 2] * t + sz - zi
        dw = phase[j, V + 2] - wi
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


@inline
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
    c0 = ints[i, CELL]
    c1 = ints[i, CELL + 1]
    c2 = ints[i, CELL + 2]
    xi = phase[i, X0] + phase[i, V] * t
    yi = phase[i, X0 + 1] + phase[i, V + 1] * t
    zi = phase[i, X0 + 2] + phase[i, V + 2] * t
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
    ui = phase[i, V]
    vi = phase[i, V + 1]
    wi = phase[i, V + 2]
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


@inline
def next_crossing(i, phase, ints, geometry, grid):
    """Time and face code (2k + 1 upwards, 2k downwards) at which i leaves its cell or
    touches a wall. A wall face is the plane at σ/2 from the wall. Written with selects
    rather than branches: the direction of motion is a coin flip for the branch predictor."""
    dim = grid[I_DIM]
    best = np.inf
    code = -1
    half_sigma = 0.5 * geometry[G_SIGMA]
    for k in range(dim):
        velocity = phase[i, V + k]
        c = ints[i, CELL + k]
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
        tc = (boundary - phase[i, X0 + k]) / velocity
        tc = tc if velocity != 0.0 else np.inf
        face = 2 * k + (1 if upwards else 0)
        earlier = tc < best
        code = face if earlier else code
        best = tc if earlier else best
    return best, code


@inline
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
    phase[i, T_PAIR] = best_t
    ints[i, PARTNER] = best_j
    ints[i, PREDICTED_AT] = counters[COUNT_EVENTS]
    tc, code = next_crossing(i, phase, ints, geometry, grid)
    # never schedule in the past (round-off right after a crossing)
    phase[i, T_CELL] = tc if tc > t else t
    ints[i, FACE] = code
