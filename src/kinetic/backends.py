"""Which machine runs an engine's kernels: ``cpu`` (numba.njit, the default) or ``cuda``
(numba.cuda, one NVIDIA GPU).

This module imports neither numba nor numba.cuda, so that the workflow can check a
config's ``backend`` key while it parses the Snakefile. An engine's front calls
:func:`require` with the backend it was given, before any work: a ``cuda`` job that lands
on a machine without a GPU (or without the ``cuda`` extra installed) stops there with a
message that says so. Everything of the CUDA target lives in :mod:`kinetic.gpu`, the one
module of the package that imports ``numba.cuda``.

    from kinetic import backends
    device = backends.require("cuda")   # 'NVIDIA H100 80GB HBM3', or BackendUnavailable
"""

from __future__ import annotations

import os

import numpy as np

__all__ = [
    "BACKENDS",
    "MAX_CUDA_REALIZATIONS",
    "BackendUnavailable",
    "check",
    "check_realizations",
    "require",
    "simulated",
]

BACKENDS = ("cpu", "cuda")
"""The backends an engine front accepts (``backend=`` argument, ``backend:`` config key)."""


class BackendUnavailable(RuntimeError):
    """The requested backend cannot run on this machine (no GPU, no driver, no numba-cuda)."""


def check(backend) -> str:
    """``backend`` if it names a known backend, else ``ValueError`` (no hardware probed)."""
    if backend not in BACKENDS:
        raise ValueError(f"backend must be one of {list(BACKENDS)}, got {backend!r}")
    return backend


MAX_CUDA_REALIZATIONS = 65_535
"""Most realizations one ``cuda`` call runs: its kernels put the realization on a CUDA
grid's y (or a block's x) index, whose y extent is 65 535."""


def check_realizations(backend, count: int) -> int:
    """``count`` realizations in one call of ``backend``, checked against the GPU's grid
    (``MAX_CUDA_REALIZATIONS`` for ``cuda``, no limit on the ``cpu``): ``ValueError``
    before any work. A count that is not an integer is left to the front's own check."""
    integral = isinstance(count, int | np.integer) and not isinstance(count, bool)
    if backend == "cuda" and integral and count > MAX_CUDA_REALIZATIONS:
        raise ValueError(
            f"a cuda call runs at most {MAX_CUDA_REALIZATIONS} realizations (the CUDA grid's "
            f"y extent), got {count}: split them into jobs (first_realization, n_realizations)"
        )
    return count


def simulated() -> bool:
    """True under numba's CUDA simulator (``NUMBA_ENABLE_CUDASIM=1``): the ``cuda`` kernels
    run as Python on the CPU (a block's threads as greenlets, ``kinetic.gpu``), for tests on
    machines without a GPU."""
    return os.environ.get("NUMBA_ENABLE_CUDASIM", "0") == "1"


def require(backend) -> str:
    """Check that ``backend`` can run here; return a description of the machine that will
    run the kernels (the GPU's model for ``cuda``, ``'cpu'`` otherwise).

    Raises ``BackendUnavailable`` for ``cuda`` without numba-cuda or without a usable GPU.
    """
    check(backend)
    if backend == "cpu":
        return "cpu"
    try:
        from kinetic import gpu
    except ImportError as error:
        raise BackendUnavailable(
            "backend 'cuda' needs the numba-cuda package, which is not installed here "
            f"({error}); install it with `pip install -e .[cuda]`, or set backend: cpu"
        ) from error
    return gpu.require()
