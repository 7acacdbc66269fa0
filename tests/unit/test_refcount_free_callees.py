"""kinetic.jit.refcount_free: numba compiles (and caches) the kernels a refcount-free
function calls without reference counting, so none of them may hand back an array.
A counting caller that meets such a callee releases memory it does not own."""

import os
import subprocess
import sys
import textwrap

import pytest

SCRIPT = textwrap.dedent(
    """
    from numba import njit
    from kinetic.dsmc import kernels, simulate_homogeneous
    from kinetic.jit import FLAGS

    arguments = dict(n_particles=20_000, restitution=0.5, reduced_field=0.025,
                     time_step=0.05, duration=2.0, sample_interval=0.5, sample_stride=10,
                     seed=3)
    simulate_homogeneous(**arguments)  # the engine's refcount-free advance compiles its callees
    kernels.advance = njit(**{**FLAGS, "cache": False})(kernels.advance.py_func)
    for _ in range(6):  # a counting advance on those callees
        simulate_homogeneous(**arguments)
    print("clean")
    """
)


@pytest.mark.slow
def test_a_counting_caller_survives_the_callees_of_a_refcount_free_kernel(tmp_path):
    """The homogeneous DSMC's ``advance`` is ``refcount_free``; a reference-counted copy of
    it, compiled after it in a fresh cache, runs on the callees it compiled. While one of
    them (``_deferred``) returned the ``Collisions`` arrays, this corrupted the heap (the
    process died: "malloc(): unaligned tcache chunk detected", 3 runs of 3)."""
    result = subprocess.run(
        [sys.executable, "-c", SCRIPT],
        capture_output=True,
        text=True,
        env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)},
        timeout=600,
    )
    assert result.returncode == 0 and "clean" in result.stdout, result.stderr[-2000:]
