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

from llvmlite import ir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

__all__ = ["FLAGS", "inline", "kernel", "prefetch", "refcount_free"]

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
