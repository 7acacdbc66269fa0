"""The numba flags of every kernel, in one place.

``kernel`` compiles a function with the flags every engine uses: ``cache=True`` (the
machine code is written beside the source, so later processes load it instead of
compiling; :func:`warm` fills the cache once, under a lock, before a job runs) and
``error_model="numpy"`` (a division by zero gives inf or nan instead of a checked
exception: no test-and-branch on every division in the hot loops). ``inline`` adds
``inline="always"``: numba inlines the function's IR into its callers (small helpers of
the event loops and the random-number generator).

    from kinetic.jit import inline, kernel

    @kernel
    def step(...): ...

Cached machine code is keyed on the code of every file the kernel depends on
(``kinetic.sources.kernel_sources``: its engine's package and the shared modules). Numba
checks only the file that defines the compiled function, so a kernel whose inlined
helpers live in other files (the EDMD event loop and ``kinetic.edmd.cells``, every engine
and ``kinetic.rng``) would otherwise keep running the old helpers after they are edited,
or after a checkout that changed only those files. Here such a change invalidates the
cached kernels, which recompile on their next use. The key is each file's syntax tree
without comments, docstrings and layout (``kinetic.sources.code_fingerprint``, as for the
workflow's code stamps), not numba's modification time and size: an edit of a docstring
recompiles nothing, as it reruns nothing. (A traceback through a kernel compiled before
such an edit may name the line numbers the file had then.)

Several processes compiling into one cache at once can corrupt it (numba issue 4807).
Every simulation job therefore starts with :func:`warm` for each engine it runs: the first
job after an edit compiles the kernels its front runs (where the engine lists them by
front, else all the engine's) while holding the engine's lock beside the cache, the
others wait for it and then load; once a marker records that the cache holds the kernels
of these sources, for this CPU and numba version, jobs skip the lock.
"""

import fcntl
import functools
import hashlib
import importlib
import time
from pathlib import Path

import numba
from llvmlite import ir
from numba import njit, types
from numba.core import caching, cgutils
from numba.extending import intrinsic

from kinetic.sources import PACKAGE, engine_sources, kernel_sources, remembered_fingerprint

__all__ = [
    "FLAGS",
    "cache_directory",
    "inline",
    "kernel",
    "once",
    "prefetch_row",
    "refcount_free",
    "source_stamp",
    "warm",
]


@functools.cache
def _digest(files: tuple[Path, ...]) -> str:
    digest = hashlib.sha256()
    for path in files:
        digest.update(path.relative_to(PACKAGE).as_posix().encode())
        digest.update(b"\0")
        digest.update(remembered_fingerprint(path).encode())
    return digest.hexdigest()


def source_stamp(py_file: str | Path, extra: tuple[Path, ...] = ()) -> str:
    """SHA-256 over the relative paths and the code of ``kernel_sources(py_file)`` and the
    ``extra`` package files (``kinetic.sources.code_fingerprint``: the syntax tree without
    comments, docstrings or layout; computed once per process and set of files, and read
    from memos beside the sources while a file is untouched:
    ``kinetic.sources.fingerprint_memo``)."""
    return _digest(tuple(sorted({*kernel_sources(py_file), *extra})))


class _PackageStamp:
    """Locator mixin: the package's functions are fresh only if none of the files they
    depend on changed; functions of other packages keep numba's own locators."""

    def get_source_stamp(self):
        return source_stamp(self._py_file)

    @classmethod
    def from_function(cls, py_func, py_file):
        if not Path(py_file).resolve().is_relative_to(PACKAGE):
            return None
        return super().from_function(py_func, py_file)


class _PackageUserDirLocator(_PackageStamp, caching.UserProvidedCacheLocator):
    """``NUMBA_CACHE_DIR`` set: the cache there, stamped with the kernel's sources."""


class _PackageInTreeLocator(_PackageStamp, caching.InTreeCacheLocator):
    """Otherwise the ``__pycache__`` beside the source, stamped with the kernel's sources."""


class _PackageUserWideLocator(_PackageStamp, caching.UserWideCacheLocator):
    """A read-only installation: the user's cache directory, stamped the same way."""


# numba tries its locators in order and takes the first that accepts the function
_LOCATORS = caching.CacheImpl._locator_classes
_LOCATORS[:] = [
    _PackageUserDirLocator,
    _PackageInTreeLocator,
    _PackageUserWideLocator,
    *(c for c in _LOCATORS if not issubclass(c, _PackageStamp)),
]


def cache_directory(engine: str) -> Path:
    """The directory where numba caches the kernels of ``engine``'s package: the locator
    numba would choose (``NUMBA_CACHE_DIR``, the package's ``__pycache__`` if writable, the
    user's cache directory otherwise)."""
    py_file = str(PACKAGE / engine / "__init__.py")
    for locator_class in _LOCATORS[:3]:
        locator = locator_class.from_function(cache_directory, py_file)
        if locator is not None:
            locator.ensure_cache_path()
            return Path(locator.get_cache_path())
    raise OSError(f"no writable cache directory for the kernels of kinetic.{engine}")


def _warm_key(engine: str) -> str:
    """What the cached kernels of ``engine`` are valid for: their sources (the stamp of
    :func:`source_stamp`), numba's version and the CPU the machine code was built for
    (numba's own index keys its entries by the CPU name and features)."""
    from numba.core.registry import cpu_target

    digest = hashlib.sha256(_digest(tuple(engine_sources(engine))).encode())
    digest.update(numba.__version__.encode())
    digest.update(repr(cpu_target.target_context.codegen().magic_tuple()).encode())
    return digest.hexdigest()[:16]


def warm(engine: str, front: str | None = None) -> float:
    """Make sure numba's cache holds the kernels of ``engine`` for the current sources;
    returns the seconds spent compiling or waiting.

    ``front`` names a function of the engine package (``"simulate_homogeneous"``): where
    the package's ``WARMUPS`` has an entry for it, only the kernels that front runs are
    compiled (a montanero2007 job does not compile costantini2010's cooling-modes
    kernels); otherwise, or without ``front``, every kernel (``kinetic.<engine>``'s
    ``warmup()``).

    A marker file beside the cache, named by :func:`_warm_key`, records a finished warm-up
    (of the whole engine, or for one front, whether or not the engine lists it): with the
    engine's marker or the front's, nothing is done (the job loads the kernels it calls).
    Without it, the process takes an exclusive lock on ``kinetic-warm-<engine>.lock``
    there (one lock per engine, whatever the front), checks the marker again (another job
    may have compiled meanwhile), runs the warm-up (compiling into the cache, or loading
    what is there), writes the marker and removes the markers of earlier sources.
    Parallel jobs of one build, and two builds of one checkout, thus compile each kernel
    once, never two at the same time into the same cache files.
    """
    directory = cache_directory(engine)
    key = _warm_key(engine)
    if _marker(directory, engine, key).exists():
        return 0.0

    def warmup():  # the engine is imported only if its cache needs warming
        module = importlib.import_module(f"kinetic.{engine}")
        getattr(module, "WARMUPS", {}).get(front, module.warmup)()

    name = engine if front is None else f"{engine}.{front}"
    return once(directory, name, key, warmup, lock=engine)


def _marker(directory: Path, name: str, key: str) -> Path:
    return directory / f"kinetic-warm-{name}-{key}.done"


def once(directory: Path, name: str, key: str, action, lock: str | None = None) -> float:
    """Run ``action()`` unless the marker ``kinetic-warm-<name>-<key>.done`` in
    ``directory`` says it ran; under an exclusive lock ``kinetic-warm-<lock>.lock`` there
    (``lock`` defaults to ``name``), so that concurrent processes run it once, never at
    the same time. Removes the markers of other keys of ``name``. Returns the seconds
    spent running or waiting."""
    marker = _marker(directory, name, key)
    if marker.exists():
        return 0.0
    begin = time.perf_counter()
    with open(directory / f"kinetic-warm-{lock or name}.lock", "w") as lock_file:
        fcntl.flock(lock_file, fcntl.LOCK_EX)
        if not marker.exists():
            action()
            for stale in directory.glob(f"kinetic-warm-{name}-*.done"):
                stale.unlink(missing_ok=True)
            marker.touch()
    return time.perf_counter() - begin


FLAGS = {"cache": True, "error_model": "numpy"}
"""Options of numba.njit shared by every kernel of the package."""

kernel = njit(**FLAGS)
"""Decorator: numba.njit with :data:`FLAGS`."""

unlocked = njit(**FLAGS, nogil=True)
"""Decorator: :data:`kernel` that releases the GIL while it runs, for work a thread does
beside the main one (the next run's initial velocities while a GPU run launches)."""

inline = njit(**FLAGS, inline="always")
"""Decorator: numba.njit with :data:`FLAGS`, inlined into its callers."""

refcount_free = njit(**FLAGS, _nrt=False)
"""Decorator: :data:`kernel` compiled without numba's reference counting, for event loops
that allocate nothing. With it, every ``inline`` helper that takes an array and sits in
a branch of the loop (a random draw from a state row, say) costs an atomic increment and
decrement of the array's count: about a tenth of the cloning kernel's time, 15 times
the work of the EDMD calendar's rebuild.

Numba (0.68) compiles the ``kernel`` functions such a function calls without reference
counting too, and caches them so, under the signature a reference-counted caller would
use: which one a process gets depends on which caller compiled first. Call from it only
``inline`` helpers, other ``refcount_free`` functions and kernels that return no array
(numbers, tuples of numbers, nothing): a callee compiled without the counts hands back
an array it holds no reference to, which a counting caller (or Python) then releases.
Found by a crash: the homogeneous DSMC's ``advance`` made ``refcount_free``, then a
counting copy of it run on the callees it had cached, corrupted the heap ("malloc():
unaligned tcache chunk detected", 3 runs of 3) through ``_deferred``, a kernel that
returned the ``Collisions`` arrays; inlined, it runs clean."""


@intrinsic
def prefetch_row(typingctx, array, row):
    """Hint the processor to load the cache line of ``array[row]`` (a C-contiguous 1-D
    array) or the first cache line of row ``row`` (2-D) into every cache level; no effect
    on the program's results. Emits LLVM's ``llvm.prefetch`` (read, high locality, data
    cache)."""
    if not (
        isinstance(array, types.Array) and array.ndim in (1, 2) and isinstance(row, types.Integer)
    ):
        return None

    def codegen(context, builder, signature, args):
        array_type, row_type = signature.args
        view = context.make_array(array_type)(context, builder, args[0])
        index = context.cast(builder, args[1], row_type, types.intp)
        indices = [index] + [context.get_constant(types.intp, 0)] * (array_type.ndim - 1)
        pointer = cgutils.get_item_pointer2(
            context,
            builder,
            view.data,
            cgutils.unpack_tuple(builder, view.shape),
            cgutils.unpack_tuple(builder, view.strides),
            array_type.layout,
            indices,
            wraparound=False,
            boundscheck=False,
        )
        byte_pointer = ir.IntType(8).as_pointer()
        i32 = ir.IntType(32)
        function = cgutils.get_or_insert_function(
            builder.module,
            ir.FunctionType(ir.VoidType(), [byte_pointer, i32, i32, i32]),
            "llvm.prefetch.p0",
        )
        builder.call(function, [builder.bitcast(pointer, byte_pointer), i32(0), i32(3), i32(1)])
        return context.get_dummy_value()

    return types.void(array, row), codegen
