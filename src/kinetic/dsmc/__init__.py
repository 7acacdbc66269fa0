"""Homogeneous DSMC engine (Bird's method): hard spheres, Maxwell molecules, very hard
particles, restitution α, the heat-flux force and thermostat of montanero2007, and a
continuous-time variant with free-flight observers (visco2008). See ``simulate`` for the
fronts and ``kernels`` for the numba kernels (shared with the inhomogeneous engine)."""

from __future__ import annotations

import numpy as np

from kinetic.dsmc.simulate import (
    MOMENT_NAMES,
    HomogeneousGas,
    HomogeneousSettings,
    Samples,
    advance_gas,
    new_gas,
    realization_streams,
    simulate_free_flights,
    simulate_homogeneous,
)

__all__ = [
    "MOMENT_NAMES",
    "HomogeneousGas",
    "HomogeneousSettings",
    "Samples",
    "advance_gas",
    "new_gas",
    "realization_streams",
    "simulate_free_flights",
    "simulate_homogeneous",
    "warmup",
]


def warmup() -> None:
    """Compile (or load from numba's cache) every kernel with the production argument types.

    Runs each kernel once on a tiny system in d = 2 and d = 3, with the NTC and Poisson
    clocks, the Euler and exact force steps and the free-flight observers.
    """
    from kinetic.dsmc import kernels

    for dimension in (2, 3):
        for selection, force_step, splitting in (
            ("ntc", "euler", "lie"),
            ("poisson", "exact", "strang"),
        ):
            settings = HomogeneousSettings(
                n_particles=8,
                restitution=0.9,
                time_step=0.01,
                dimension=dimension,
                reduced_field=0.05,
                force_step=force_step,
                selection=selection,
                splitting=splitting,
            )
            gas = new_gas(settings, realization_streams(0, 0, 1)[0])
            advance_gas(gas, 2, Samples(stride=1, histogram=True))
        simulate_free_flights(n_particles=8, duration=0.5, seed=0, dimension=dimension, chunk=0.5)
        velocity = np.zeros((dimension, 4))
        velocity[0] = [1.0, -1.0, 0.5, -0.5]
        members = np.arange(4, dtype=np.int64)
        bounds = np.empty(dimension + 2)
        kernels.members_speed_bounds(velocity, members, 0, 4, bounds)
        kernels.collide_members(
            velocity,
            members,
            0,
            4,
            realization_streams(0, 0, 1)[0],
            kernels.HARD_SPHERES,
            1.0,
            0.1,
            0.1,
            False,
            bounds,
            np.zeros(1),
            np.zeros(4, dtype=np.int64),
        )
