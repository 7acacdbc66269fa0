"""Seeds: the integers behind every random stream, without numba.

Every stochastic run takes one integer root seed from the config. Jobs derive their own
seed from it and a stable text key (``derive_seed``), and each job spawns independent
xoshiro256+ states for its realizations (``stream_states``) with
``numpy.random.SeedSequence``; the jitted draws that advance those states are in
``kinetic.rng``. This module imports only numpy, so that the workflow can derive seeds
while it parses the Snakefile without loading the compiler.
"""

from __future__ import annotations

import zlib

import numpy as np

__all__ = ["MAX_SEED", "checked_stream", "derive_seed", "stream_states"]


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


MAX_SEED = 2**63 - 1
"""Largest seed: what a netCDF attribute holds as a signed 64-bit integer (the config's
root seed has the same bound, and ``derive_seed`` gives 63 bits)."""


def stream_states(seed: int, n_streams: int, first: int = 0) -> np.ndarray:
    """Independent xoshiro256+ states, one row per stream: streams ``first`` to
    ``first + n_streams - 1``.

    Returns a C-contiguous ``uint64`` array of shape ``(n_streams, 4)``; stream ``k`` is
    child ``k`` of ``SeedSequence(seed)`` (what ``spawn`` would give as its k-th child,
    built alone: a job of the last realizations of a large run costs its own rows only),
    so a row does not depend on how many streams are asked for, nor on ``first``.
    """
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0:
        raise TypeError(f"seed must be an integer >= 0, got {seed!r}")
    if seed > MAX_SEED:
        raise ValueError(f"seed = {seed} is too large: must be <= 2**63 - 1")
    for name, value, low in (("n_streams", n_streams, 1), ("first", first, 0)):
        if isinstance(value, bool) or not isinstance(value, int | np.integer):
            raise TypeError(f"{name} must be an integer, got {value!r}")
        if value < low:
            raise ValueError(f"{name} must be >= {low}, got {value}")
    states = np.empty((n_streams, 4), dtype=np.uint64)
    for k in range(int(n_streams)):
        child = np.random.SeedSequence(int(seed), spawn_key=(int(first) + k,))
        words = child.generate_state(4, np.uint64)
        if not words.any():  # the all-zero state is the one fixed point of xoshiro
            words[0] = 1
        states[k] = words
    return states


def checked_stream(stream) -> np.ndarray:
    """A copy of one xoshiro256+ state (4 ``uint64``), refused with ``ValueError`` if it
    has another shape or is all zero: that state yields only zeros (a Maxwellian draw from
    it never ends, a random insertion piles every particle on one point). The states of
    :func:`stream_states` are never all zero."""
    state = np.array(stream, dtype=np.uint64).reshape(-1).copy()
    if state.shape != (4,):
        raise ValueError(f"stream must be one xoshiro state of 4 uint64, got {np.shape(stream)}")
    if not state.any():
        raise ValueError(
            "stream is the all-zero xoshiro state, which yields only zeros: take one from "
            "kinetic.seeds.stream_states"
        )
    return state
