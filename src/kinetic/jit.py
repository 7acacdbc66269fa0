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
"""

from numba import njit

__all__ = ["FLAGS", "inline", "kernel"]

FLAGS = {"cache": True, "error_model": "numpy"}
"""Options of numba.njit shared by every kernel of the package."""

kernel = njit(**FLAGS)
"""Decorator: numba.njit with :data:`FLAGS`."""

inline = njit(**FLAGS, inline="always")
"""Decorator: numba.njit with :data:`FLAGS`, inlined into its callers."""
