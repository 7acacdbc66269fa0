"""DSMC collisions conserve momentum always and energy for α = 1, to round-off."""

import numpy as np
import pytest

from kinetic import rng
from kinetic.dsmc import kernels
from kinetic.gas import KERNELS, candidate_coefficient

KERNEL_IDS = {
    "hard_spheres": kernels.HARD_SPHERES,
    "maxwell": kernels.MAXWELL,
    "very_hard": kernels.VERY_HARD,
}


@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("restitution", [1.0, 0.5])
@pytest.mark.parametrize("poisson", [False, True])
def test_collisions_conserve_momentum_and_elastic_energy(d, kernel, restitution, poisson):
    n = 2000
    state = rng.stream_states(17, 1)[0].copy()
    velocity = np.empty((d, n))
    kernels.maxwellian(velocity, state, 1.0)
    velocity += 0.3  # a moving gas: momentum conservation is not trivially zero
    bounds = np.empty(d + 2)
    kernels.speed_bounds(velocity, 0, n, bounds)
    momentum, energy = velocity.sum(axis=1), 0.5 * np.sum(velocity**2)
    tally = np.zeros(4, dtype=np.int64)
    coefficient = candidate_coefficient(kernel, d, 1.0, n)

    kernels.collide_range(
        velocity,
        0,
        n,
        state,
        kernels.Collisions(
            KERNEL_IDS[kernel], restitution, coefficient, 2.0, poisson, bounds, np.zeros(1), tally
        ),
    )

    assert tally[kernels.TALLY_ACCEPTED] > n  # every particle collided about once or more
    np.testing.assert_allclose(velocity.sum(axis=1), momentum, rtol=0, atol=1e-10)
    if restitution == 1.0:
        assert 0.5 * np.sum(velocity**2) == pytest.approx(energy, rel=1e-13)
    else:
        assert 0.5 * np.sum(velocity**2) < energy
