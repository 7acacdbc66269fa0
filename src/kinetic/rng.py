"""Random streams inside numba kernels.

Every stochastic run takes one integer root seed from the config. Jobs derive their own
seed from it and a stable text key (``derive_seed``), and each job spawns independent
streams for its realizations (``stream_states``) with ``numpy.random.SeedSequence``; both
live in ``kinetic.seeds`` (no numba) and are re-exported here.

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

import math

import numpy as np

from kinetic.jit import inline, kernel
from kinetic.seeds import derive_seed, stream_states

__all__ = [
    "derive_seed",
    "disk_point",
    "exponential",
    "load_state",
    "normal",
    "normal_pair",
    "random_unit_vector",
    "store_state",
    "stream_states",
    "thread_state",
    "uniform",
    "uniform_open",
    "unit_vector_3d",
    "xoshiro_disk_point",
    "xoshiro_exponential",
    "xoshiro_next",
    "xoshiro_normal_pair",
    "xoshiro_uniform",
    "xoshiro_uniform_open",
    "xoshiro_unit_2d",
    "xoshiro_unit_3d",
]

_U64 = np.uint64
_SHIFT_17 = _U64(17)
_SHIFT_45 = _U64(45)
_SHIFT_11 = _U64(11)
_ROT_LEFT = _U64(64 - 45)
_TWO_M53 = 2.0**-53


@kernel
def xoshiro_next(s0, s1, s2, s3):
    """One xoshiro256+ output from a state held in four scalars: ``(x, s0, s1, s2, s3)``.

    The ``xoshiro_*`` draws take and return the state as scalars, for loops that keep it
    in registers: with a state row in memory, numba cannot prove that the row and the
    arrays the loop writes do not alias, so every store reloads the state (DSMC's
    collision loop runs about twice slower that way). Same stream as ``uniform(state)``.
    """
    x = s0 + s3
    t = s1 << _SHIFT_17
    s2 ^= s0
    s3 ^= s1
    s1 ^= s2
    s0 ^= s3
    s2 ^= t
    s3 = (s3 << _SHIFT_45) | (s3 >> _ROT_LEFT)
    return x, s0, s1, s2, s3


@inline
def load_state(state):
    """The four words of a stream's state row, for a loop that holds them in scalars and
    draws with the ``xoshiro_*`` functions: ``s0, s1, s2, s3 = load_state(state)``."""
    return state[0], state[1], state[2], state[3]


@inline
def store_state(state, s0, s1, s2, s3):
    """Write the four scalars of :func:`load_state` back to the stream's state row."""
    state[0] = s0
    state[1] = s1
    state[2] = s2
    state[3] = s3


@kernel
def xoshiro_uniform(s0, s1, s2, s3):
    """Uniform float64 in [0, 1) (upper 53 bits), as ``uniform``: ``(u, s0, s1, s2, s3)``."""
    x, s0, s1, s2, s3 = xoshiro_next(s0, s1, s2, s3)
    return float(x >> _SHIFT_11) * _TWO_M53, s0, s1, s2, s3


@kernel
def xoshiro_uniform_open(s0, s1, s2, s3):
    """Uniform float64 in (0, 1], as ``uniform_open``: ``(u, s0, s1, s2, s3)``."""
    x, s0, s1, s2, s3 = xoshiro_next(s0, s1, s2, s3)
    return (float(x >> _SHIFT_11) + 1.0) * _TWO_M53, s0, s1, s2, s3


@kernel
def xoshiro_disk_point(s0, s1, s2, s3):
    """Uniform point in the open unit disk minus its centre, as ``disk_point``:
    ``(x, y, r2, s0, s1, s2, s3)`` with r2 = x² + y²."""
    while True:
        a, s0, s1, s2, s3 = xoshiro_uniform(s0, s1, s2, s3)
        b, s0, s1, s2, s3 = xoshiro_uniform(s0, s1, s2, s3)
        x = 2.0 * a - 1.0
        y = 2.0 * b - 1.0
        r2 = x * x + y * y
        if 0.0 < r2 < 1.0:
            return x, y, r2, s0, s1, s2, s3


@kernel
def xoshiro_normal_pair(s0, s1, s2, s3):
    """Two independent standard normal variates, as ``normal_pair`` (polar method):
    ``(z0, z1, s0, s1, s2, s3)``."""
    x, y, r2, s0, s1, s2, s3 = xoshiro_disk_point(s0, s1, s2, s3)
    factor = math.sqrt(-2.0 * math.log(r2) / r2)
    return x * factor, y * factor, s0, s1, s2, s3


@kernel
def xoshiro_exponential(s0, s1, s2, s3):
    """Exponential variate of unit mean, as ``exponential``: ``(e, s0, s1, s2, s3)``."""
    x, s0, s1, s2, s3 = xoshiro_next(s0, s1, s2, s3)
    return -math.log((float(x >> _SHIFT_11) + 1.0) * _TWO_M53), s0, s1, s2, s3


@kernel
def xoshiro_unit_3d(s0, s1, s2, s3):
    """Uniform direction on the sphere (Marsaglia 1972, no trigonometry) from one disk
    point. Returns ``(e0, e1, e2, s0, s1, s2, s3)``.
    """
    x, y, r2, s0, s1, s2, s3 = xoshiro_disk_point(s0, s1, s2, s3)
    f = 2.0 * math.sqrt(1.0 - r2)
    return x * f, y * f, 1.0 - 2.0 * r2, s0, s1, s2, s3


@kernel
def xoshiro_unit_2d(s0, s1, s2, s3):
    """Uniform direction on the circle (von Neumann's rejection, no trigonometry): the
    doubled angle of one disk point. Returns ``(e0, e1, s0, s1, s2, s3)``.
    """
    x, y, r2, s0, s1, s2, s3 = xoshiro_disk_point(s0, s1, s2, s3)
    return (x * x - y * y) / r2, 2.0 * x * y / r2, s0, s1, s2, s3


_GOLDEN = _U64(0x9E3779B97F4A7C15)
_MIX_1 = _U64(0xBF58476D1CE4E5B9)
_MIX_2 = _U64(0x94D049BB133111EB)
_SHIFT_30 = _U64(30)
_SHIFT_27 = _U64(27)
_SHIFT_31 = _U64(31)


@kernel
def _splitmix64(z):
    """One output of Vigna's splitmix64 and its next counter: ``(x, z)``."""
    z = z + _GOLDEN
    x = (z ^ (z >> _SHIFT_30)) * _MIX_1
    x = (x ^ (x >> _SHIFT_27)) * _MIX_2
    return x ^ (x >> _SHIFT_31), z


@kernel
def thread_state(key0, key1, key2, key3, index):
    """The xoshiro256+ state of thread ``index`` of the stream whose state row is
    ``(key0, key1, key2, key3)``: four splitmix64 outputs from a counter that mixes the
    row's first word with the index, each XORed with a word of the row.

    The GPU engines give every member (a clone, a particle group) its own stream this
    way, from one ``stream_states`` row per realization: realization ``r`` of a batch has
    the same numbers whatever else runs beside it, and no two threads share a stream.
    Returns ``(s0, s1, s2, s3)``, never all zero.
    """
    z = key0 ^ (_U64(index) * _MIX_2)
    a, z = _splitmix64(z)
    b, z = _splitmix64(z)
    c, z = _splitmix64(z)
    e, z = _splitmix64(z)
    a ^= key1
    b ^= key2
    c ^= key3
    if (a | b | c | e) == _U64(0):
        a = _U64(1)
    return a, b, c, e


@inline
def _next_u64(state):
    result, s0, s1, s2, s3 = xoshiro_next(state[0], state[1], state[2], state[3])
    store_state(state, s0, s1, s2, s3)
    return result


@inline
def uniform(state):
    """Uniform float64 in [0, 1) from the upper 53 bits; advances ``state`` in place."""
    return float(_next_u64(state) >> _SHIFT_11) * _TWO_M53


@inline
def uniform_open(state):
    """Uniform float64 in (0, 1]: safe under ``log``."""
    return (float(_next_u64(state) >> _SHIFT_11) + 1.0) * _TWO_M53


@inline
def exponential(state):
    """Exponential variate of unit mean."""
    return -np.log(uniform_open(state))


@inline
def disk_point(state):
    """Uniform point (x, y) in the open unit disk minus its centre, and r2 = x² + y²."""
    x, y, r2, s0, s1, s2, s3 = xoshiro_disk_point(state[0], state[1], state[2], state[3])
    store_state(state, s0, s1, s2, s3)
    return x, y, r2


@inline
def normal_pair(state):
    """Two independent standard normal variates (Marsaglia's polar method)."""
    z0, z1, s0, s1, s2, s3 = xoshiro_normal_pair(state[0], state[1], state[2], state[3])
    store_state(state, s0, s1, s2, s3)
    return z0, z1


@inline
def unit_vector_3d(state):
    """Uniform direction on the sphere (Marsaglia 1972): returns ``(x, y, z)``."""
    x, y, z, s0, s1, s2, s3 = xoshiro_unit_3d(state[0], state[1], state[2], state[3])
    store_state(state, s0, s1, s2, s3)
    return x, y, z


@inline
def normal(state):
    """One standard normal variate (the polar method's second variate is dropped)."""
    return normal_pair(state)[0]


@inline
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
