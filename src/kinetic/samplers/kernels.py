"""Numba kernels of the clothes-pin samplers of krauth2025 §4.4.1 (hard rods of width 2σ).

Arrays only; every kernel takes one xoshiro256+ state row (``kinetic.rng``) and advances
it in place, and adds its samples to a histogram (counts per bin of equal width on
[lower, upper)), so nothing but the histogram and a few counts leaves the kernel.

- ``naive_pin``: Alg. 4.6, N uniform centres in [σ, L − σ] drawn one after the other,
  the whole configuration thrown away ("tabula rasa") as soon as a pin overlaps an
  earlier one. Returns the numbers of configurations started (the fraction that gets
  through is Z_{N,L} / (L − 2σ)^N exactly) and of uniforms drawn.
- ``direct_pin``: Alg. 4.7, N uniform numbers in [0, L − 2Nσ], sorted, then the k-th
  (k = 1..N) shifted by (2k − 1)σ.
- ``ring_markov``: local Metropolis moves of N pins on a ring of circumference L (a pin
  moves by a uniform step in [−δ, δ] unless it would overlap another); after each sweep of
  N attempts, every forward pair distance (x_j − x_i) mod L, j ≠ i, goes to the histogram.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from kinetic.jit import inline, kernel
from kinetic.rng import load_state, store_state, uniform, xoshiro_uniform

MAX_CONFIGURATION_STARTS = 10**9
"""Starts after which ``direct_disks`` gives up on one configuration (and returns −1)."""

__all__ = ["Box", "Chain", "direct_pin", "markov_disks", "naive_pin", "ring_markov"]


@inline
def _add(histogram, value, lower, scale):
    """Count ``value`` in its bin (bins of width 1/scale from ``lower``); ignore values
    outside the histogram."""
    position = (value - lower) * scale
    if 0.0 <= position < histogram.shape[0]:
        histogram[int(position)] += 1


@kernel
def naive_pin(n, length, sigma, samples, state, positions, histogram, lower, upper):
    """Add ``samples`` accepted naive-pin configurations to ``histogram`` (pin centres);
    ``positions`` is work space of length ≥ n. Returns the number of configurations
    started (accepted ones included) and of uniforms drawn."""
    scale = histogram.shape[0] / (upper - lower)
    span = length - 2.0 * sigma
    width2 = 2.0 * sigma
    started = 0
    draws = 0
    for _ in range(samples):
        while True:
            started += 1
            legal = True
            for k in range(n):
                draws += 1
                x = sigma + span * uniform(state)
                for m in range(k):
                    if abs(x - positions[m]) < width2:
                        legal = False
                        break
                if not legal:
                    break
                positions[k] = x
            if legal:
                break
        for k in range(n):
            _add(histogram, positions[k], lower, scale)
    return started, draws


@inline
def _direct_configuration(n, free, sigma, positions, s0, s1, s2, s3):
    """One direct-pin configuration in ``positions[:n]`` (increasing) from the generator
    state held in scalars; returns the advanced state."""
    for k in range(n):
        u, s0, s1, s2, s3 = xoshiro_uniform(s0, s1, s2, s3)
        y = free * u
        # insertion sort: n is small and the draws arrive one by one
        m = k
        while m > 0 and positions[m - 1] > y:
            positions[m] = positions[m - 1]
            m -= 1
        positions[m] = y
    for k in range(n):
        positions[k] += (2 * k + 1) * sigma
    return s0, s1, s2, s3


@kernel
def direct_pin_configuration(n, length, sigma, state, positions):
    """One direct-pin configuration in ``positions[:n]``, in increasing order."""
    state[0], state[1], state[2], state[3] = _direct_configuration(
        n, length - 2.0 * n * sigma, sigma, positions, state[0], state[1], state[2], state[3]
    )


@kernel
def direct_pin(n, length, sigma, samples, state, positions, histogram, lower, upper):
    """Add ``samples`` direct-pin configurations to ``histogram`` (pin centres). The
    generator state stays in registers through the loop (``kinetic.rng.xoshiro_next``)."""
    scale = histogram.shape[0] / (upper - lower)
    free = length - 2.0 * n * sigma
    s0, s1, s2, s3 = load_state(state)
    for _ in range(samples):
        s0, s1, s2, s3 = _direct_configuration(n, free, sigma, positions, s0, s1, s2, s3)
        for k in range(n):
            _add(histogram, positions[k], lower, scale)
    store_state(state, s0, s1, s2, s3)


@kernel
def ring_markov(n, length, sigma, step, sweeps, burn_in, state, positions, histogram):
    """Run ``burn_in`` then ``sweeps`` sweeps of N attempted moves from the legal
    configuration ``positions[:n]`` (centres in [0, L), updated in place); after each of
    the ``sweeps`` sweeps add the n(n − 1) forward pair distances to ``histogram`` (bins
    on [0, L)). Returns the number of accepted moves."""
    scale = histogram.shape[0] / length
    width2 = 2.0 * sigma
    accepted = 0
    for sweep in range(burn_in + sweeps):
        for _ in range(n):
            i = int(uniform(state) * n)
            x = positions[i] + step * (2.0 * uniform(state) - 1.0)
            x -= length * np.floor(x / length)
            if x >= length:  # round-off of the wrap
                x = 0.0
            legal = True
            for j in range(n):
                if j != i:
                    d = abs(x - positions[j])
                    if d > length - d:
                        d = length - d
                    if d < width2:
                        legal = False
                        break
            if legal:
                positions[i] = x
                accepted += 1
        if sweep >= burn_in:
            for i in range(n):
                for j in range(n):
                    if j != i:
                        d = positions[j] - positions[i]
                        if d < 0.0:
                            d += length
                        _add(histogram, d, 0.0, scale)
    return accepted


# ----------------------------------------------------------------------------- hard disks


@inline
def _disk_fits(x, y, k, positions, sigma):
    """True if a disk at (x, y) overlaps none of disks 0..k−1 of ``positions``."""
    reach2 = 4.0 * sigma * sigma
    for m in range(k):
        dx = x - positions[m, 0]
        dy = y - positions[m, 1]
        if dx * dx + dy * dy < reach2:
            return False
    return True


@kernel
def direct_disks_configuration(n, sigma, box_x, box_y, state, positions, max_starts):
    """One direct-disks configuration (Alg. 4.4: uniform centres in [σ, L − σ]², the whole
    configuration restarted at the first overlap) in ``positions[:n]``. Returns the number
    of configurations started, or −1 if ``max_starts`` were not enough."""
    for started in range(1, max_starts + 1):
        legal = True
        for k in range(n):
            x = sigma + (box_x - 2.0 * sigma) * uniform(state)
            y = sigma + (box_y - 2.0 * sigma) * uniform(state)
            if not _disk_fits(x, y, k, positions, sigma):
                legal = False
                break
            positions[k, 0] = x
            positions[k, 1] = y
        if legal:
            return started
    return -1


@kernel
def direct_disks(n, sigma, box_x, box_y, samples, state, positions, histogram, lower, upper):
    """Add the y of every disk of ``samples`` direct-disks configurations to
    ``histogram``. Returns the configurations started (−1: one needed more than
    :data:`MAX_CONFIGURATION_STARTS`)."""
    scale = histogram.shape[0] / (upper - lower)
    started = 0
    for _ in range(samples):
        tries = direct_disks_configuration(
            n, sigma, box_x, box_y, state, positions, MAX_CONFIGURATION_STARTS
        )
        if tries < 0:
            return -1
        started += tries
        for k in range(n):
            _add(histogram, positions[k, 1], lower, scale)
    return started


class Box(NamedTuple):
    """``n`` disks of radius ``sigma`` in the box [0, box_x] × [0, box_y] with walls."""

    n: int
    sigma: float
    box_x: float
    box_y: float


class Chain(NamedTuple):
    """A Markov chain's moves: displacements uniform in [−step, step]², ``sweeps`` recorded
    sweeps after ``burn_in`` discarded ones."""

    step: float
    sweeps: int
    burn_in: int


@kernel
def markov_disks(box, chain, state, positions, histogram, lower, upper):
    """Alg. 4.5 in the :class:`Box` ``box`` from the legal configuration
    ``positions[:box.n]`` (updated in place), with the :class:`Chain` settings ``chain``: a
    random disk tries a displacement uniform in [−δ, δ]², refused if it leaves [σ, L − σ]²
    or overlaps another disk. After each sweep (n attempts) past ``chain.burn_in``, the y of
    every disk goes to ``histogram`` (bins over [lower, upper)). Returns the accepted
    moves."""
    n = box.n
    sigma = box.sigma
    box_x = box.box_x
    box_y = box.box_y
    step = chain.step
    sweeps = chain.sweeps
    burn_in = chain.burn_in
    scale = histogram.shape[0] / (upper - lower)
    reach2 = 4.0 * sigma * sigma
    accepted = 0
    for sweep in range(burn_in + sweeps):
        for _ in range(n):
            k = int(uniform(state) * n)
            x = positions[k, 0] + step * (2.0 * uniform(state) - 1.0)
            y = positions[k, 1] + step * (2.0 * uniform(state) - 1.0)
            if x < sigma or x > box_x - sigma or y < sigma or y > box_y - sigma:
                continue
            legal = True
            for m in range(n):
                if m != k:
                    dx = x - positions[m, 0]
                    dy = y - positions[m, 1]
                    if dx * dx + dy * dy < reach2:
                        legal = False
                        break
            if legal:
                positions[k, 0] = x
                positions[k, 1] = y
                accepted += 1
        if sweep >= burn_in:
            for k in range(n):
                _add(histogram, positions[k, 1], lower, scale)
    return accepted
