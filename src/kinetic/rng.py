"""Seeds and random streams.

Every stochastic run takes one integer root seed from the config. Jobs derive their own
seed from it and a stable text key (``derive_seed``), and each job spawns independent
streams for its realizations (``stream_states``) with ``numpy.random.SeedSequence``.

Inside numba kernels the streams are xoshiro256+ generators whose whole state is one row
``state[4]`` of a ``uint64`` array (about 1 ns a draw, against about 10 ns for numba's
global ``np.random``, whose state is not numpy's and is shared by all realizations).
The jitted draws below take that row and advance it in place::

    states = stream_states(seed, n_realizations)      # (n_realizations, 4) uint64
    kernel(states[r], ...)                             # inside: uniform(state), normal(state)

References: D. Blackman and S. Vigna, "Scrambled linear pseudorandom number generators",
ACM TOMS 47, 36 (2021); the upper 53 bits of xoshiro256+ pass BigCrush.
"""

from __future__ import annotations

import zlib

import numpy as np
from numba import njit

__all__ = [
    "derive_seed",
    "exponential",
    "normal",
    "normal_pair",
    "random_unit_vector",
    "stream_states",
    "uniform",
    "uniform_open",
]

_U64 = np.uint64
_SHIFT_17 = _U64(17)
_SHIFT_45 = _U64(45)
_SHIFT_11 = _U64(11)
_ROT_LEFT = _U64(64 - 45)
_TWO_M53 = 2.0**-53


def derive_seed(root_seed: int, key: str) -> int:
    """Return a 63-bit seed for the job named ``key`` of a run with ``root_seed``.

    The key is hashed with CRC-32 (stable across processes, unlike ``hash``) and mixed
    with the root seed by ``SeedSequence``, so distinct keys give unrelated seeds.
    """
    if isinstance(root_seed, bool) or not isinstance(root_seed, int | np.integer):
        raise TypeError(f"root_seed must be an integer, got {root_seed!r}")
    if root_seed < 0:
        raise ValueError(f"root_seed must be >= 0, got {root_seed}")
    sequence = np.random.SeedSequence(int(root_seed), spawn_key=(zlib.crc32(key.encode()),))
    return int(sequence.generate_state(1, np.uint64)[0] >> np.uint64(1))


def stream_states(seed: int, n_streams: int) -> np.ndarray:
    """Independent xoshiro256+ states, one row per stream.

    Returns a C-contiguous ``uint64`` array of shape ``(n_streams, 4)``; row ``k`` is
    spawned child ``k`` of ``SeedSequence(seed)``, so the first rows do not depend on
    how many streams are asked for.
    """
    if n_streams < 1:
        raise ValueError(f"n_streams must be >= 1, got {n_streams}")
    children = np.random.SeedSequence(int(seed)).spawn(int(n_streams))
    states = np.empty((n_streams, 4), dtype=np.uint64)
    for k, child in enumerate(children):
        words = child.generate_state(4, np.uint64)
        if not words.any():  # the all-zero state is the one fixed point of xoshiro
            words[0] = 1
        states[k] = words
    return states


@njit(inline="always")
def _next_u64(state):
    s0 = state[0]
    s1 = state[1]
    s2 = state[2]
    s3 = state[3]
    result = s0 + s3
    t = s1 << _SHIFT_17
    s2 ^= s0
    s3 ^= s1
    s1 ^= s2
    s0 ^= s3
    s2 ^= t
    s3 = (s3 << _SHIFT_45) | (s3 >> _ROT_LEFT)
    state[0] = s0
    state[1] = s1
    state[2] = s2
    state[3] = s3
    return result


@njit(inline="always")
def uniform(state):
    """Uniform float64 in [0, 1) from the upper 53 bits; advances ``state`` in place."""
    return float(_next_u64(state) >> _SHIFT_11) * _TWO_M53


@njit(inline="always")
def uniform_open(state):
    """Uniform float64 in (0, 1]: safe under ``log``."""
    return (float(_next_u64(state) >> _SHIFT_11) + 1.0) * _TWO_M53


@njit(inline="always")
def exponential(state):
    """Exponential variate of unit mean."""
    return -np.log(uniform_open(state))


@njit(inline="always")
def normal_pair(state):
    """Two independent standard normal variates (Marsaglia's polar method)."""
    while True:
        x = 2.0 * uniform(state) - 1.0
        y = 2.0 * uniform(state) - 1.0
        r2 = x * x + y * y
        if 0.0 < r2 < 1.0:
            factor = np.sqrt(-2.0 * np.log(r2) / r2)
            return x * factor, y * factor


@njit(inline="always")
def normal(state):
    """One standard normal variate (the polar method's second variate is dropped)."""
    return normal_pair(state)[0]


@njit(inline="always")
def random_unit_vector(state, out):
    """Fill ``out`` (length d = 2 or 3) with a direction uniform on the unit sphere."""
    d = out.shape[0]
    if d == 2:
        angle = 2.0 * np.pi * uniform(state)
        out[0] = np.cos(angle)
        out[1] = np.sin(angle)
    elif d == 3:
        z = 2.0 * uniform(state) - 1.0
        angle = 2.0 * np.pi * uniform(state)
        rho = np.sqrt(max(0.0, 1.0 - z * z))
        out[0] = rho * np.cos(angle)
        out[1] = rho * np.sin(angle)
        out[2] = z
    else:
        norm2 = 0.0
        while norm2 == 0.0:
            norm2 = 0.0
            for k in range(d):
                out[k] = normal(state)
                norm2 += out[k] * out[k]
        inv = 1.0 / np.sqrt(norm2)
        for k in range(d):
            out[k] *= inv
