"""The GPU tests run their kernels under numba's CUDA simulator, which runs every thread
of a block as a Python thread and polls them at each ``syncthreads``: with Python's default
thread switch interval (5 ms) a barrier of 16 threads costs about 80 ms. A 50 µs interval
during these tests makes them about 4 times faster (a cloning run of 64 threads: 26 s ->
5 s).

Faster switching exposes a race in the simulator itself: ``cuda.shared.array`` looks up,
creates and stores a block's array without a lock, so two threads arriving together can
each get an array of their own and a block reduction then sums half the block (seen once
in a dozen runs as a batch that did not repeat its realizations). The simulator's method
is wrapped in a lock here; the GPU has no such race."""

import sys
import threading

import pytest

from kinetic import backends

if backends.simulated():
    import numpy as np
    from numba.core import types
    from numba.cuda.simulator import kernelapi
    from numba.np import numpy_support

    _allocate = kernelapi.FakeCUDAShared.array
    _lock = threading.Lock()

    def _locked_array(self, shape, dtype, alignment=None):
        """The simulator's static shared array (one per block and source line of the
        call), found or made under a lock."""
        if alignment is not None or shape == 0:
            return _allocate(self, shape, dtype, alignment)
        if isinstance(dtype, types.Type):
            dtype = numpy_support.as_dtype(dtype)
        caller = sys._getframe(1)
        key = (caller.f_code.co_filename, caller.f_lineno)
        with _lock:
            found = self._allocations.get(key)
            if found is None:
                found = self._allocations[key] = np.empty(shape, dtype)
        return found

    kernelapi.FakeCUDAShared.array = _locked_array


@pytest.fixture(autouse=True)
def fast_thread_switching():
    interval = sys.getswitchinterval()
    sys.setswitchinterval(5e-5)
    yield
    sys.setswitchinterval(interval)
