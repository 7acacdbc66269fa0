"""numba's CUDA simulator as the GPU tests use it: every thread of a block gets the block's
shared arrays. numba's ``FakeCUDAShared.array`` looks a line's array up and, when absent,
creates it, without a lock, so two threads arriving together can each get their own;
``kinetic.gpu`` replaces it with a locked lookup."""

import os
import time

os.environ.setdefault("NUMBA_ENABLE_CUDASIM", "1")

import numpy as np
import pytest

pytest.importorskip("numba.cuda")

from kinetic import backends
from kinetic.gpu import cuda, kernel

pytestmark = [
    pytest.mark.cuda,
    pytest.mark.skipif(not backends.simulated(), reason="a property of the simulator"),
]

THREADS = 16


@kernel
def _neighbours(out):
    first = cuda.shared.array(THREADS, np.int64)
    second = cuda.shared.array(THREADS, np.int64)
    t = cuda.threadIdx.x
    first[t] = t
    second[t] = -t
    cuda.syncthreads()
    out[cuda.blockIdx.x, t, 0] = first[(t + 1) % THREADS]
    out[cuda.blockIdx.x, t, 1] = second[(t + 1) % THREADS]


def test_every_thread_of_a_block_sees_the_blocks_shared_arrays(monkeypatch):
    """Allocation made slow (a millisecond), so that the threads of a block all ask for the
    array while the first is creating it: numba's own lookup then hands most of them an
    array of their own, and each thread reads its neighbour's entry from the wrong one."""
    allocate = np.empty

    def slow_empty(*args, **kwargs):
        time.sleep(1e-3)
        return allocate(*args, **kwargs)

    blocks = 4
    out = np.zeros((blocks, THREADS, 2), dtype=np.int64)
    monkeypatch.setattr(np, "empty", slow_empty)
    _neighbours[blocks, THREADS](out)
    monkeypatch.undo()
    expected = np.broadcast_to(np.roll(np.arange(THREADS), -1), (blocks, THREADS))
    np.testing.assert_array_equal(out[:, :, 0], expected)
    np.testing.assert_array_equal(out[:, :, 1], -expected)
