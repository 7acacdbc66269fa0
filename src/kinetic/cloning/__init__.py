"""Cloning Monte Carlo of visco2008 §IV.A: μ(λ), T(λ), a2(λ) of the number of collisions.

Public fronts: ``simulate`` (returns an ``xarray.Dataset``), ``simulate_points`` (several
points in the same GPU launches, a dataset each); estimators and the 1/N_c
extrapolation in ``estimators``; ``warmup()`` compiles every kernel once (the workflow
runs it in its own job before the parallel simulation jobs, numba issue 4807).
"""

from kinetic.lazy import lazy_exports

_EXPORTS = {
    "KERNELS": "arguments",
    "LAMBDA_MAX": "arguments",
    "LAMBDA_MIN": "arguments",
    "MIN_KEPT_COLLISIONS": "arguments",
    "Extrapolation": "estimators",
    "extrapolate_population": "estimators",
    "kernel_label": "front",
    "simulate": "front",
    "simulate_points": "front",
}
"""Public names and the module that defines each: loaded on first use, so that importing
``kinetic.cloning.arguments`` (the numpy-only checks the workflow runs while it reads the
config, and the cost plan's constants) loads neither numba nor the kernels."""

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


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())


def warmup() -> None:
    """Compile (or load from numba's cache) every kernel with the production types.

    Runs a tiny population through every kernel code and both dimensions, for a
    positive and a negative tilt, through the same front as production runs.
    """
    from kinetic import cloning  # its lazy names: the package file imports no kernel

    for kernel in cloning.KERNELS:
        for dimension in (2, 3):
            for lam in (0.5, -0.5):
                cloning.simulate(
                    kernel=kernel,
                    dimension=dimension,
                    lam=lam,
                    population=64,
                    duration=1.0,
                    transient=3.0,
                    n_blocks=2,
                    n_realizations=2,
                    seed=0,
                )
