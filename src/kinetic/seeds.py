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

__all__ = ["checked_stream", "derive_seed", "stream_states"]


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
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0:
        raise TypeError(f"seed must be an integer >= 0, got {seed!r}")
    if isinstance(n_streams, bool) or not isinstance(n_streams, int | np.integer):
        raise TypeError(f"n_streams must be an integer, got {n_streams!r}")
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
