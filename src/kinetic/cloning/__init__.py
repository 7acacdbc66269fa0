"""Cloning Monte Carlo of visco2008 §IV.A: μ(λ), T(λ), a2(λ) of the number of collisions.

Public fronts: ``simulate`` (returns an ``xarray.Dataset``), ``simulate_points`` (several
points in the same GPU launches, a dataset each); estimators and the 1/N_c
extrapolation in ``estimators``; ``warmup()`` compiles every kernel once (the workflow
runs it in its own job before the parallel simulation jobs, numba issue 4807).
"""

from kinetic.cloning.estimators import Extrapolation, extrapolate_population
from kinetic.cloning.simulate import (
    KERNELS,
    LAMBDA_MAX,
    LAMBDA_MIN,
    MIN_KEPT_COLLISIONS,
    kernel_label,
    simulate,
    simulate_points,
)

__all__ = [
    "KERNELS",
    "LAMBDA_MAX",
    "LAMBDA_MIN",
    "MIN_KEPT_COLLISIONS",
    "Extrapolation",
    "extrapolate_population",
    "kernel_label",
    "simulate",
    "simulate_points",
    "warmup",
]


def warmup() -> None:
    """Compile (or load from numba's cache) every kernel with the production types.

    Runs a tiny population through every kernel code and both dimensions, for a
    positive and a negative tilt, through the same front as production runs.
    """
    for kernel in KERNELS:
        for dimension in (2, 3):
            for lam in (0.5, -0.5):
                simulate(
                    kernel=kernel,
                    dimension=dimension,
                    lam=lam,
                    population=64,
                    duration=0.2,
                    transient=3.0,
                    n_blocks=2,
                    n_realizations=2,
                    seed=0,
                )
