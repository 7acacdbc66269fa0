"""The CUDA target: the one module of the package that imports ``numba.cuda``.

The GPU engines (``kinetic.cloning.gpu``, ``kinetic.dsmc.gpu``,
``kinetic.dsmc.inhomogeneous_gpu``) take ``cuda`` from here, so that a move to another
CUDA binding (numba-cuda is in maintenance mode) is a change of this file. What lives here:

- :func:`require`: the machine's GPU, or ``BackendUnavailable`` before any work;
- :data:`kernel`, the decorator of every GPU kernel, and :func:`warm`: compiled kernels
  go to numba-cuda's disk cache, keyed on all their sources, filled once under a lock;
- :func:`device_function`: the physics written once. A collision rule, a random draw, a
  rate is a plain function compiled by ``kinetic.jit.kernel``/``inline`` for the CPU
  engine (and covered by its tests); ``device_function`` compiles the *same source* as a
  CUDA device function, with every package kernel it calls replaced by its own device
  twin. The GPU layer is launch, grouping, random streams and reductions;
- :func:`device_inline`, the decorator of every device function (twins included): NVVM
  inlines them, which compiles the kernels 9 times faster than numba's IR inlining;
- deterministic reductions: float sums are folded in a fixed order (a tree inside a
  thread block, then one thread over the blocks), never with floating-point atomics, so
  the same seed gives the same numbers on the same GPU model.

Under ``NUMBA_ENABLE_CUDASIM=1`` numba runs the kernels as Python on the CPU, a block's
threads as greenlets here (tests on machines without a GPU; slow, so tiny systems only).
numpy then warns about the wrapping uint64 arithmetic of the random streams, which is
intended.
"""

from __future__ import annotations

import functools
import hashlib
import inspect
import math
import threading
import time
import types
from pathlib import Path

import numpy as np
from numba import cuda
from numba.core.registry import CPUDispatcher

from kinetic.backends import BackendUnavailable, simulated

try:  # the engines launch small grids on purpose (one block per realization, say)
    from numba.cuda.core import config as _cuda_config

    _cuda_config.CUDA_LOW_OCCUPANCY_WARNINGS = 0
except ImportError:  # another numba-cuda layout: the warning stays
    pass

_THIS_FILE = Path(__file__).resolve()


@functools.cache
def _lock_simulated_shared_arrays() -> bool:
    """Under the simulator, make ``cuda.shared.array`` give every thread of a block the same
    array. numba's ``FakeCUDAShared.array`` looks its array up by the calling line and,
    when absent, creates it, without a lock: two threads of a block arriving together can
    each create their own (uninitialised) array and never see each other's writes (seen
    as a cloning batch that did not repeat its realizations, and as about one run in ten
    of a script running the homogeneous DSMC's ``_collide_columns``, since removed, whose
    threads started with their shared arrays). The replacement keys on the caller's file
    and line as numba does, under a lock; the GPU has no such race. Returns whether it is
    installed (False for a numba-cuda without this layout)."""
    import sys
    import threading

    from numba.core import types as numba_types
    from numba.np import numpy_support

    try:
        from numba.cuda.simulator.kernelapi import FakeCUDAShared
    except ImportError:
        return False
    original = FakeCUDAShared.array
    lock = threading.Lock()

    def array(self, shape, dtype, alignment=None):
        if shape == 0 or alignment is not None:  # dynamic shared memory: one buffer
            return original(self, shape, dtype, alignment)
        frame = sys._getframe(1)
        caller = (frame.f_code.co_filename, frame.f_lineno)
        with lock:
            allocated = self._allocations.get(caller)
            if allocated is None:
                if isinstance(dtype, numba_types.Type):
                    dtype = numpy_support.as_dtype(dtype)
                allocated = self._allocations[caller] = np.empty(shape, dtype)
        return allocated

    FakeCUDAShared.array = array
    return True


def _is_upstream(function, digest: str) -> bool:
    """Whether the source of ``function`` is the numba-cuda code whose SHA-256 is ``digest``:
    the code a replacement below was checked against (another numba-cuda keeps its own)."""
    try:
        source = inspect.getsource(function)
    except (OSError, TypeError):
        return False
    return hashlib.sha256(source.encode()).hexdigest() == digest


_UPSTREAM_BLOCK_RUN = "54626c6819f55d514a598517b1467ed1cc2e7c3bf1f3b9814e13ef2a4ba3541f"
"""SHA-256 of the source of numba-cuda 0.30.4's ``BlockManager.run``, the loop that
:func:`_run_simulated_blocks_as_greenlets` replaces."""


@functools.cache
def _run_simulated_blocks_as_greenlets() -> bool:
    """Under the simulator, run the threads of a block as greenlets that take turns, each
    until its next barrier, instead of a Python thread each. numba's ``BlockManager.run``
    starts an operating-system thread per CUDA thread and polls them in a loop (to
    release them when all wait in ``syncthreads``, and to learn when they are done), so
    every barrier costs every thread two switches of the GIL and the poller its passes
    over the set. Here a block is a list of greenlets (the ``greenlet`` package's
    coroutines, one C stack each): each runs in ``threadIdx`` order until it reaches a
    barrier or ends; when all have, the ones at the barrier run on, and so on. The same
    kernels, barriers and numbers (a block's threads share nothing between two barriers
    whose order matters, or the kernel would race on the GPU); an error stops the launch
    naming its thread, as numba's does. ``threading.current_thread()``, through which
    numba's ``cuda`` module of the simulator finds threadIdx and the barrier, is made to
    return the running greenlet. Measured on the development machine: the inhomogeneous
    engine, 2 realizations of 200 simulated particles and 12 steps, 5.5 CPU-s with
    numba's threads (polls paused), 1.9 with greenlets, the same datasets bit for bit
    (and so the homogeneous engine's and the cloning's, docs/gpu.md).
    Installed over numba-cuda 0.30.4's loop only (the digest of its source); another
    numba-cuda keeps its own, and tests/gpu/test_simulator.py then fails. Returns
    whether it is installed."""
    try:
        import greenlet
        from numba.cuda.simulator import kernel as simulator
        from numba.cuda.simulator import kernelapi

        upstream = simulator.BlockManager.run
    except (ImportError, AttributeError):
        return False
    if not _is_upstream(upstream, _UPSTREAM_BLOCK_RUN):
        return False
    if getattr(kernelapi, "threading", None) is not threading:
        return False
    thread_class = simulator.BlockThread

    class CudaThread(greenlet.greenlet):
        """One CUDA thread: what numba's ``BlockThread`` offers the kernel (its indices,
        ``syncthreads`` and the counting barriers), as a greenlet."""

        syncthreads_count = thread_class.syncthreads_count
        syncthreads_and = thread_class.syncthreads_and
        syncthreads_or = thread_class.syncthreads_or

        def __init__(self, target, manager, block_index, thread_index):
            super().__init__(run=target)
            self._manager = manager
            self.blockIdx = kernelapi.Dim3(*block_index)
            self.threadIdx = kernelapi.Dim3(*thread_index)
            x, y, _ = manager._block_dim
            self.thread_id = self.threadIdx.x + x * (self.threadIdx.y + y * self.threadIdx.z)

        def syncthreads(self):
            self.parent.switch()  # back to the block's loop, until every thread is here

    def current_thread():
        running = greenlet.getcurrent()
        return running if isinstance(running, CudaThread) else threading.current_thread()

    class Threading(types.ModuleType):
        """``threading`` as the simulator's ``cuda`` module sees it: its current thread is
        the running greenlet."""

        def __getattr__(self, name):
            return getattr(threading, name)

    shim = Threading("threading")
    shim.current_thread = current_thread

    def run(self, grid_point, *args):
        def target():
            if self._debug:
                np.seterr(divide="raise")
            self._f(*args)

        waiting = [
            CudaThread(target, self, grid_point, thread_index)
            for thread_index in np.ndindex(*self._block_dim)
        ]
        while waiting:
            for thread in waiting:
                try:
                    thread.switch()
                except Exception as error:
                    where = f"tid={list(thread.threadIdx)} ctaid={list(thread.blockIdx)}"
                    message = f"{where}: {error}" if str(error) else where
                    raise type(error)(message).with_traceback(error.__traceback__) from None
            waiting = [thread for thread in waiting if not thread.dead]

    simulator.BlockManager.run = run
    kernelapi.threading = shim
    return True


_UPSTREAM_KERNEL_CALL = "71c9d298b7bc62785c792eacfd2c24323bfaf7eaf98d0fa61c920781e81dbada"
"""SHA-256 of the source of numba-cuda 0.30.4's ``FakeCUDAKernel.__call__``, the call that
:func:`_swap_device_modules_once_per_launch` wraps."""


@functools.cache
def _swap_device_modules_once_per_launch() -> bool:
    """Under the simulator, point a device function's module at the launch's fake ``cuda``
    module once per launch, not at every call. numba's ``FakeCUDAKernel.__call__`` wraps
    every call of a device function in ``swapped_cuda_module``, which, for a module the
    launch has not swapped (a device function beside the engine's kernels, a
    ``device_function`` twin, this module's block sums), looks through the module's
    globals for ``cuda``, swaps them, and swaps them back at return: 27 000 passes, 30 %
    of the greenlet simulator's time, in the inhomogeneous engine's run of
    :func:`_run_simulated_blocks_as_greenlets`. Here the first call of a launch into a
    module swaps its ``cuda`` names and the launch's end (normal or not) swaps back every
    module it swapped; a kernel's own module, which numba swaps for the whole launch, is
    left to numba. The same functions see the same fake module. Installed over
    numba-cuda 0.30.4's call only (the digest of its source). Returns whether it is
    installed."""
    try:
        from numba.cuda.simulator import kernel as simulator

        launch = simulator.FakeCUDAKernel.__call__
    except (ImportError, AttributeError):
        return False
    if not _is_upstream(launch, _UPSTREAM_KERNEL_CALL):
        return False
    real = cuda  # this module's ``cuda`` is swapped too while its helpers run
    swapped: dict[int, tuple[dict, list[str]]] = {}  # a module's globals: the names swapped

    def call(self, *args):
        fake = simulator._kernel_context
        if fake is None:  # a launch, or a device function called on the host
            try:
                return launch(self, *args)
            finally:
                for module, names in swapped.values():
                    for name in names:
                        module[name] = real
                swapped.clear()
        module = self.fn.__globals__
        if id(module) not in swapped:
            names = [name for name, value in module.items() if value is real]
            for name in names:
                module[name] = fake
            swapped[id(module)] = (module, names)
        return self.fn(*args)

    simulator.FakeCUDAKernel.__call__ = call
    return True


if simulated():
    _lock_simulated_shared_arrays()
    _run_simulated_blocks_as_greenlets()
    _swap_device_modules_once_per_launch()


class _PackageStamp:
    """Locator mixin: a package kernel's cache entry is fresh only while none of the files
    it depends on changed (``kinetic.jit.source_stamp`` of its engine, and this module);
    functions outside the package keep numba-cuda's own locators."""

    def get_source_stamp(self):
        from kinetic.jit import source_stamp

        return source_stamp(self._py_file, (_THIS_FILE,))

    @classmethod
    def from_function(cls, py_func, py_file):
        from kinetic.sources import PACKAGE

        if not Path(py_file).resolve().is_relative_to(PACKAGE):
            return None
        return super().from_function(py_func, py_file)


@functools.cache
def _install_cache_locators() -> bool:
    """Key numba-cuda's on-disk cache of the package's kernels on every file they depend
    on (:class:`_PackageStamp`), as ``kinetic.jit`` does for the CPU kernels: numba-cuda's
    own locators look at the kernel's file only, and the device twins of
    ``device_function`` and this module's helpers live in others. Returns whether the
    locators are in place (False for a numba-cuda without this layout: its kernels are
    then compiled in every process, without a cache)."""
    try:
        from numba.cuda.core import caching
    except ImportError:
        return False
    bases = ("_UserProvidedCacheLocator", "_InTreeCacheLocator", "_UserWideCacheLocator")
    if not all(hasattr(caching, name) for name in bases):
        return False
    locators = caching.CacheImpl._locator_classes
    ours = [type(f"Package{name}", (_PackageStamp, getattr(caching, name)), {}) for name in bases]
    locators[:] = [*ours, *(c for c in locators if not issubclass(c, _PackageStamp))]
    return True


CACHED = not simulated() and _install_cache_locators()
"""Whether compiled kernels go to numba-cuda's on-disk cache (beside the package's sources,
or in ``NUMBA_CACHE_DIR``), keyed on their sources and the GPU's compute capability."""

kernel = cuda.jit(cache=CACHED)
"""Decorator of every GPU kernel of the package: ``numba.cuda.jit``, cached on disk when
:data:`CACHED` (a job then loads the machine code instead of compiling it: 10-30 s a
process on the development machine's CPU for each engine)."""


def kernel_within(registers: int):
    """``kernel`` whose machine code uses at most ``registers`` registers a thread
    (``max_registers``: ptxas spills the rest to local memory), so that more threads fit
    on a multiprocessor (65 536 registers); no effect under the simulator."""
    if simulated():
        return kernel
    return cuda.jit(cache=CACHED, max_registers=registers)


def kernel_variants(function, constant: str, values: dict[str, object]) -> dict[str, object]:
    """``{label: kernel}``: ``function`` compiled as a ``kernel`` once for each of
    ``values``, each copy with the module-level name ``constant`` fixed to its value. numba
    reads a global as a constant and prunes the branches on it, so each copy is compiled
    for one case only (its types too: a branch between two array layouts would otherwise
    join them in a strided one). The copies read the module's other names as they are
    when this is called (call it after everything ``function`` uses is defined; numba
    freezes them at compilation anyway), and their qualified names carry the label, so
    each has its own entry in the kernel cache. (``device_function`` copies functions
    the same way.)"""
    variants = {}
    for label, value in values.items():
        names = dict(function.__globals__)
        names[constant] = value
        copy = types.FunctionType(
            function.__code__, names, function.__name__, function.__defaults__, function.__closure__
        )
        copy.__qualname__ = f"{function.__qualname__}_{label}"
        copy.__module__ = function.__module__
        copy.__doc__ = function.__doc__
        variants[label] = kernel(copy)
    return variants


def warm(name: str, engine: str, compile_kernels) -> float:
    """Have this process's kernels of a GPU module ready: ``compile_kernels()`` is a tiny
    launch of each with its production types. The first process after an edit (or on a
    new GPU model or numba-cuda version) runs it under a lock beside the cache
    (``kinetic.jit.once``, marker ``kinetic-warm-<name>-<key>.done``), compiling into
    the cache while concurrent processes wait; they then run it too, loading from the
    cache, so that no two processes compile into the same cache files at once (numba
    issue 4807). Without the cache, or under the simulator, it just calls
    ``compile_kernels()``. Returns the seconds spent."""
    begin = time.perf_counter()
    if not CACHED:
        compile_kernels()
        return time.perf_counter() - begin
    from importlib.metadata import version

    from kinetic import jit
    from kinetic.sources import PACKAGE

    capability = cuda.get_current_device().compute_capability
    stamp = jit.source_stamp(PACKAGE / engine / "__init__.py", (_THIS_FILE,))
    key = hashlib.sha256(f"{stamp} {version('numba-cuda')} {capability}".encode())
    compiled = []

    def compile_into_the_cache():
        compile_kernels()
        compiled.append(True)

    jit.once(jit.cache_directory(engine), name, key.hexdigest()[:16], compile_into_the_cache)
    if not compiled:  # another process filled the cache: load from it, outside any timer
        compile_kernels()
    return time.perf_counter() - begin


__all__ = [
    "BLOCK",
    "block_exclusive_scan",
    "block_inclusive_scan",
    "block_reduce_extreme",
    "block_reduce_sum",
    "cuda",
    "device_empty",
    "device_function",
    "device_name",
    "first_pair",
    "fold_partials",
    "grid",
    "kernel",
    "kernel_variants",
    "kernel_within",
    "last_block",
    "next_pair",
    "require",
    "synchronize",
    "to_device",
    "warm",
]

BLOCK = 16 if simulated() else 128
"""Threads per block of the engines' kernels (a power of two: the in-block reductions
halve it); small under the simulator, which runs every thread of a block as a Python
thread."""


def require() -> str:
    """The GPU that will run the kernels (its model name), or ``BackendUnavailable``."""
    if simulated():
        return "numba CUDA simulator (NUMBA_ENABLE_CUDASIM=1)"
    if not cuda.is_available():
        raise BackendUnavailable(
            "backend 'cuda' was asked for, but this machine has no usable NVIDIA GPU "
            "(numba.cuda.is_available() is False: no device, or no driver). Run the job "
            "where a GPU is (on SLURM the workflow asks for one with the job's gpu "
            "resource), or set backend: cpu"
        )
    return device_name()


@functools.cache
def device_name() -> str:
    """Model of the current GPU, e.g. 'NVIDIA H100 80GB HBM3'."""
    if simulated():
        return "numba CUDA simulator"
    name = cuda.get_current_device().name
    return name.decode() if isinstance(name, bytes) else str(name)


def _is_package_kernel(value) -> bool:
    return isinstance(value, CPUDispatcher) and value.py_func.__module__.startswith("kinetic.")


def device_inline(function):
    """``function`` as a CUDA device function that NVVM inlines into every caller
    (``forceinline``: LLVM's ``alwaysinline``; the simulator, whose ``cuda.jit`` has no such
    option, runs it as called Python).

    Not numba's ``inline="always"``, which inlines at numba's IR level before typing: there
    every call site deep-copies the callee's IR and runs its untyped passes again.
    Compiling every kernel of the package for sm_90 (tests/gpu/test_kernels_compile.py)
    took 184 s so, three kernels 20-73 s each, and a profile of the homogeneous collisions
    found 81 % of their 80 s in those copies; inlined by NVVM the same kernels took 21 s.
    The PTX is within 10 % of the same length, and the registers a thread leave as many
    blocks resident at the sizes the kernels are launched with: the homogeneous
    collisions 124 and 102 before (two stores), 128 and 112 after (4 blocks of 128
    either way); the inhomogeneous step 206, 194 (2 of 128); cloning's resident kernel
    127, 119 (2 of 256); no spills. The CPU engine keeps numba's IR-level inlining
    (``kinetic.jit.inline``), whose literal dimension makes its loops twice faster."""
    if simulated():
        return cuda.jit(device=True)(function)
    return cuda.jit(device=True, forceinline=True)(function)


_TWINS: dict = {}


def device_function(function):
    """The CUDA device twin of a package kernel (a ``kinetic.jit`` dispatcher or its
    Python function): the same code object, compiled by ``numba.cuda.jit(device=True)``
    and inlined, with every package kernel it calls replaced by its twin in turn."""
    py_func = getattr(function, "py_func", function)
    twin = _TWINS.get(py_func)
    if twin is not None:
        return twin
    namespace = dict(py_func.__globals__)
    for name in py_func.__code__.co_names:
        value = namespace.get(name)
        if _is_package_kernel(value):
            namespace[name] = device_function(value)
    source = types.FunctionType(
        py_func.__code__, namespace, py_func.__name__, py_func.__defaults__, py_func.__closure__
    )
    source.__qualname__ = py_func.__qualname__
    source.__module__ = py_func.__module__
    source.__doc__ = py_func.__doc__
    twin = device_inline(source)
    _TWINS[py_func] = twin
    return twin


def grid(n: int, block: int = BLOCK) -> int:
    """Blocks of ``block`` threads that cover ``n`` threads."""
    return max(1, math.ceil(n / block))


def synchronize() -> None:
    """Wait for the GPU (a no-op under the simulator)."""
    cuda.synchronize()


@kernel
def stream_copy(source, target):
    """``target[i] = source[i]`` for the flat float64 arrays (threads over the elements,
    the grid's stride): the coalesced read and write that bound a pass over particles
    (``python -m kinetic.bench cuda --sections memory_bound``)."""
    start = cuda.blockIdx.x * cuda.blockDim.x + cuda.threadIdx.x
    for i in range(start, source.shape[0], cuda.gridDim.x * cuda.blockDim.x):
        target[i] = source[i]


def fold_partials(partials, out, field_of, scale=1.0):
    """Add ``scale`` times the per-block partial sums ``partials[r, b, f]`` (float64, one
    row per realization ``r`` and thread block ``b``) to ``out[r, field_of[f]]``, in a
    fixed order (deterministic; no atomics): one thread block per (r, f), each thread
    summing the rows b = t, t + BLOCK, ... in order, then a fixed tree."""
    _fold[(partials.shape[0], partials.shape[2]), BLOCK](partials, out, field_of, scale)


def first_pair(k, n, stride):
    """A grid-stride walk over the pairs (q, i) of a flat index k = q n + i, without a
    64-bit division a step (a long instruction sequence on a GPU): ``(q, i, dq, di)``,
    k's pair and the stride's, stride = dq n + di; ``next_pair`` takes the next."""
    q = k // n
    dq = stride // n
    return q, k - q * n, dq, stride - dq * n


first_pair = device_inline(first_pair)


def next_pair(q, i, dq, di, n):
    """The pair ``stride`` after (q, i) in ``first_pair``'s walk over rows of ``n``."""
    i += di
    q += dq
    if i >= n:
        i -= n
        q += 1
    return q, i


next_pair = device_inline(next_pair)


def block_reduce_sum(shared, value, threads=BLOCK):
    """Sum of ``value`` over the threads of a block of ``threads`` threads (a power of two,
    by default ``BLOCK``, a compile-time constant), by a fixed tree in the shared array
    ``shared`` (at least ``threads`` long); every thread must call it. Returns the sum in
    thread 0 (other threads get a partial sum)."""
    t = cuda.threadIdx.x
    shared[t] = value
    cuda.syncthreads()
    stride = threads // 2
    while stride > 0:
        if t < stride:
            shared[t] += shared[t + stride]
        cuda.syncthreads()
        stride //= 2
    total = shared[0]
    cuda.syncthreads()
    return total


block_reduce_sum = device_inline(block_reduce_sum)


def block_reduce_extreme(shared, value, largest, threads=BLOCK):
    """Largest (``largest``) or smallest ``value`` over the threads of a block of
    ``threads``, by a fixed tree in ``shared`` (of the values' type); every thread must
    call it and gets the result. One atomic per block then replaces one per thread:
    thousands of threads hitting one address serialise at the L2 cache."""
    t = cuda.threadIdx.x
    shared[t] = value
    cuda.syncthreads()
    stride = threads // 2
    while stride > 0:
        if t < stride:
            other = shared[t + stride]
            if (other > shared[t]) == largest and other != shared[t]:
                shared[t] = other
        cuda.syncthreads()
        stride //= 2
    result = shared[0]
    cuda.syncthreads()
    return result


block_reduce_extreme = device_inline(block_reduce_extreme)


@kernel
def _fold(partials, out, field_of, scale):
    shared = cuda.shared.array(BLOCK, np.float64)
    r = cuda.blockIdx.x
    f = cuda.blockIdx.y
    total = 0.0
    for b in range(cuda.threadIdx.x, partials.shape[1], BLOCK):
        total += partials[r, b, f]
    total = block_reduce_sum(shared, total)
    if cuda.threadIdx.x == 0:
        out[r, field_of[f]] += scale * total


def block_inclusive_scan(shared, value, zero, threads=BLOCK):
    """Inclusive prefix sum of ``value`` over the threads of a block of ``threads`` threads,
    by a fixed Hillis-Steele tree in ``shared`` (of the values' type, ``zero`` its 0);
    every thread must call it. Returns ``(this thread's prefix, the block's total)``."""
    t = cuda.threadIdx.x
    shared[t] = value
    cuda.syncthreads()
    offset = 1
    while offset < threads:
        add = shared[t - offset] if t >= offset else zero
        cuda.syncthreads()
        shared[t] += add
        cuda.syncthreads()
        offset *= 2
    prefix = shared[t]
    total = shared[threads - 1]
    cuda.syncthreads()
    return prefix, total


block_inclusive_scan = device_inline(block_inclusive_scan)


def block_exclusive_scan(shared, values, count, zero):
    """Exclusive prefix sums of ``values[:count]`` in place, by one block of ``BLOCK``
    threads (every thread must call it) in a fixed order: thread t sums its contiguous
    chunk, :func:`block_inclusive_scan` over the chunk totals, then each thread writes its
    chunk's prefixes. ``zero`` is 0 of the values' type (integer scans are exact, hence
    monotone). Returns the total (in every thread)."""
    t = cuda.threadIdx.x
    chunk = (count + BLOCK - 1) // BLOCK
    first = min(t * chunk, count)
    last = min(first + chunk, count)
    total = zero
    for k in range(first, last):
        total += values[k]
    prefix, grand = block_inclusive_scan(shared, total, zero)
    running = prefix - total  # exclusive prefix of this thread's chunk
    for k in range(first, last):
        value = values[k]
        values[k] = running
        running += value
    cuda.syncthreads()
    return grand


block_exclusive_scan = device_inline(block_exclusive_scan)


def last_block(done, r, flag):
    """True, in every thread of the block, for the last thread block of grid row r to
    get here: thread 0 takes a ticket ``done[r]`` (an integer atomic after a memory
    fence, so that what it wrote reaches memory first) and the block learns through
    ``flag``, a shared int64 array of one. The last block sees every block's writes
    (another fence) and resets the ticket for the next launch. A kernel then folds its
    blocks' partial sums in that block, with no launch of its own."""
    if cuda.threadIdx.x == 0:
        cuda.threadfence()
        flag[0] = 1 if cuda.atomic.add(done, r, 1) == cuda.gridDim.x - 1 else 0
    cuda.syncthreads()
    if flag[0] == 0:
        return False
    cuda.threadfence()
    if cuda.threadIdx.x == 0:
        done[r] = 0
    return True


last_block = device_inline(last_block)


def to_device(array):
    """Copy a host array to the GPU."""
    return cuda.to_device(np.ascontiguousarray(array))


def device_zeros(shape, dtype=np.float64):
    """A zeroed array on the GPU."""
    return cuda.to_device(np.zeros(shape, dtype=dtype))


def device_empty(shape, dtype=np.float64):
    """An array on the GPU that is not initialised (for one a kernel fills entirely): no
    host array and no copy, unlike ``device_zeros``."""
    return cuda.device_array(shape, dtype=dtype)
