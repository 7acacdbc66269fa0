"""The numba flags of every kernel, in one place.

``kernel`` compiles a function with the flags every engine uses: ``cache=True`` (the
machine code is written beside the source, so later processes load it instead of
compiling; rule ``warm_numba`` fills the cache once before parallel jobs) and
``error_model="numpy"`` (a division by zero gives inf or nan instead of a checked
exception: no test-and-branch on every division in the hot loops). ``inline`` adds
``inline="always"``: numba inlines the function's IR into its callers (small helpers of
the event loops and the random-number generator).

    from kinetic.jit import inline, kernel

    @kernel
    def step(...): ...

Cached machine code is keyed on every file the kernel depends on
(``kinetic.sources.kernel_sources``: its engine's package and the shared modules). Numba
checks only the file that defines the compiled function, so a kernel whose inlined
helpers live in other files (the EDMD event loop and ``kinetic.edmd.cells``, every engine
and ``kinetic.rng``) would otherwise keep running the old helpers after they are edited,
or after a checkout that changed only those files. Here such a change invalidates the
cached kernels, which recompile on their next use (rule ``warm_numba`` reruns on the same
files).
"""

import functools
import hashlib
from pathlib import Path

from llvmlite import ir
from numba import njit, types
from numba.core import caching, cgutils
from numba.extending import intrinsic

from kinetic.sources import PACKAGE, kernel_sources

__all__ = ["FLAGS", "inline", "kernel", "prefetch", "refcount_free", "source_stamp"]


@functools.cache
def _digest(files: tuple[Path, ...]) -> str:
    digest = hashlib.sha256()
    for path in files:
        digest.update(path.relative_to(PACKAGE).as_posix().encode())
        digest.update(b"\0")
        digest.update(path.read_bytes())
    return digest.hexdigest()


def source_stamp(py_file: str | Path) -> str:
    """SHA-256 over the relative paths and the bytes of ``kernel_sources(py_file)`` (read
    once per process and set of files)."""
    return _digest(tuple(kernel_sources(py_file)))


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

FLAGS = {"cache": True, "error_model": "numpy"}
"""Options of numba.njit shared by every kernel of the package."""

kernel = njit(**FLAGS)
"""Decorator: numba.njit with :data:`FLAGS`."""

inline = njit(**FLAGS, inline="always")
"""Decorator: numba.njit with :data:`FLAGS`, inlined into its callers."""

refcount_free = njit(**FLAGS, _nrt=False)
"""Decorator: :data:`kernel` compiled without numba's reference counting, for event loops
that allocate nothing. With it, every ``inline`` helper that takes an array and sits in
a branch of the loop (a random draw from a state row, say) costs an atomic increment and
decrement of the array's count: about a tenth of the cloning kernel's time."""


@intrinsic
def prefetch(typingctx, array, row):
    """Ask the cache for the line of ``array[row]`` (``array[row, 0]`` of a 2-D array).

    A hint only: results do not change. Loops that know their next random addresses
    early (a few candidates ahead) issue it to overlap the memory latency of several
    candidates instead of waiting for each in turn.
    """
    sig = types.void(array, row)

    def codegen(context, builder, signature, args):
        array_type = signature.args[0]
        ary = context.make_array(array_type)(context, builder, args[0])
        indices = [args[1]] + [context.get_constant(types.intp, 0)] * (array_type.ndim - 1)
        pointer = cgutils.get_item_pointer(
            context, builder, array_type, ary, indices, wraparound=False
        )
        byte_pointer = ir.IntType(8).as_pointer()
        i32 = ir.IntType(32)
        function = cgutils.get_or_insert_function(
            builder.module,
            ir.FunctionType(ir.VoidType(), [byte_pointer, i32, i32, i32]),
            "llvm.prefetch.p0",
        )
        # read access, high temporal locality, data cache
        builder.call(function, [builder.bitcast(pointer, byte_pointer), i32(0), i32(3), i32(1)])
        return context.get_dummy_value()

    return sig, codegen
