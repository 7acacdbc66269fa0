"""numba's CUDA simulator as the GPU tests use it: every thread of a block gets the block's
shared arrays. numba's ``FakeCUDAShared.array`` looks a line's array up and, when absent,
creates it, without a lock, so two threads arriving together can each get their own;
``kinetic.gpu`` replaces it with a locked lookup. And a block's threads are greenlets
that take turns between barriers (``kinetic.gpu._run_simulated_blocks_as_greenlets``),
not operating-system threads, with the simulator's barriers and errors intact; a device
function's module is pointed at the launch's fake ``cuda`` once per launch
(``kinetic.gpu._swap_device_modules_once_per_launch``)."""

import os
import threading
import time

os.environ.setdefault("NUMBA_ENABLE_CUDASIM", "1")

import numpy as np
import pytest

pytest.importorskip("numba.cuda")

from kinetic import backends
from kinetic.gpu import block_reduce_sum, cuda, kernel

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


@kernel
def _tree_sums(values, out):
    """Each block sums its row of ``values`` by ``block_reduce_sum``'s tree: log2(THREADS)
    barriers, each round reading what the others wrote in the one before; every thread
    then reads the total."""
    shared = cuda.shared.array(THREADS, np.float64)
    t = cuda.threadIdx.x
    out[cuda.blockIdx.x, t] = block_reduce_sum(shared, values[cuda.blockIdx.x, t], THREADS)


def test_the_greenlet_blocks_keep_every_barrier(monkeypatch):
    """Every thread of every block reads the block's total after the last barrier: a
    thread released early from any barrier would read a partial sum. No operating-system
    thread is started for them."""
    from numba.cuda.simulator.kernel import BlockManager

    from kinetic import gpu

    assert gpu._run_simulated_blocks_as_greenlets()
    assert BlockManager.run.__module__ == "kinetic.gpu"
    values = np.arange(3 * THREADS, dtype=np.float64).reshape(3, THREADS) ** 2
    out = np.zeros_like(values)
    started = threading.Thread.start
    threads = []

    def count(thread):
        threads.append(thread)
        started(thread)

    monkeypatch.setattr(threading.Thread, "start", count)
    _tree_sums[3, THREADS](values, out)
    monkeypatch.undo()
    np.testing.assert_array_equal(out, np.broadcast_to(values.sum(axis=1)[:, None], out.shape))
    assert threads == []


@kernel
def _indices(out):
    t = cuda.threadIdx.x
    out[cuda.blockIdx.x, t, 0] = cuda.blockIdx.x
    out[cuda.blockIdx.x, t, 1] = t
    out[cuda.blockIdx.x, t, 2] = cuda.laneid
    cuda.syncthreads()
    out[cuda.blockIdx.x, t, 3] = cuda.threadIdx.x  # still its own after a barrier


def test_each_greenlet_sees_its_own_indices():
    blocks = 2
    out = np.full((blocks, THREADS, 4), -1, dtype=np.int64)
    _indices[blocks, THREADS](out)
    block, thread = np.meshgrid(np.arange(blocks), np.arange(THREADS), indexing="ij")
    np.testing.assert_array_equal(out[..., 0], block)
    for column in (1, 2, 3):
        np.testing.assert_array_equal(out[..., column], thread)


def test_the_greenlets_replace_only_the_loop_they_were_checked_against(monkeypatch):
    """A numba-cuda whose block manager runs another loop keeps it: the greenlets are
    installed over numba-cuda 0.30.4's loop only (the digest of its source), never over a
    loop whose logic has not been checked."""
    from numba.cuda.simulator.kernel import BlockManager

    from kinetic import gpu

    def other_loop(self, grid_point, *args):  # pragma: no cover - never run
        raise AssertionError("not called")

    monkeypatch.setattr(BlockManager, "run", other_loop)
    assert not gpu._run_simulated_blocks_as_greenlets.__wrapped__()
    assert BlockManager.run is other_loop


@kernel
def _fails_in_one_thread(out):
    t = cuda.threadIdx.x
    cuda.syncthreads()
    out[t + (THREADS if t == 5 else 0)] = 1.0  # thread 5 writes past the end
    cuda.syncthreads()


def test_device_modules_are_swapped_for_a_launch_and_back_after_it():
    """``_tree_sums`` calls ``kinetic.gpu.block_reduce_sum``, whose module numba's simulator
    would swap at every call: it is swapped once for the launch, and ``kinetic.gpu``'s
    ``cuda`` is numba's module again after it, also after a launch that failed."""
    from kinetic import gpu

    real = vars(gpu)["cuda"]
    assert gpu._swap_device_modules_once_per_launch()
    values = np.arange(2 * THREADS, dtype=np.float64).reshape(2, THREADS)
    out = np.zeros_like(values)
    _tree_sums[2, THREADS](values, out)
    np.testing.assert_array_equal(out, np.broadcast_to(values.sum(axis=1)[:, None], out.shape))
    assert vars(gpu)["cuda"] is real
    with pytest.raises(IndexError):
        _fails_in_one_thread[1, THREADS](np.zeros(THREADS))
    assert vars(gpu)["cuda"] is real


def test_the_launch_swap_wraps_only_the_call_it_was_checked_against(monkeypatch):
    from numba.cuda.simulator.kernel import FakeCUDAKernel

    from kinetic import gpu

    def other_call(self, *args):  # pragma: no cover - never run
        raise AssertionError("not called")

    monkeypatch.setattr(FakeCUDAKernel, "__call__", other_call)
    assert not gpu._swap_device_modules_once_per_launch.__wrapped__()
    assert FakeCUDAKernel.__call__ is other_call


def test_a_failing_thread_stops_its_block_with_its_error():
    """A thread's error reaches the launch, naming the thread and its block, while the
    others wait at a barrier (they are dropped, and the next launch runs as usual)."""
    out = np.zeros(THREADS)
    with pytest.raises(IndexError, match=r"tid=\[5, 0, 0\] ctaid=\[0, 0, 0\]"):
        _fails_in_one_thread[1, THREADS](out)
    values = np.ones((1, THREADS))
    sums = np.zeros_like(values)
    _tree_sums[1, THREADS](values, sums)
    np.testing.assert_array_equal(sums, THREADS)
