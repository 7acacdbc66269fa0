"""Velocity rescaling keeps an inelastic gas at its temperature (stationary representation
of the homogeneous cooling state) without redoing event predictions."""

import numpy as np

from kinetic.edmd import HardSphereSystem


def test_rescaling_holds_the_temperature_and_conserves_momentum():
    # arrange
    system = HardSphereSystem(
        n_particles=1000, density=0.02, restitution=0.8, rescale_every=100, seed=4
    )
    # act
    system.run(collisions=30_000)
    # assert: rescaled right after the last collision: T = 1 to round-off
    assert system.counters()["rescalings"] == 300
    assert abs(system.kinetic_temperature() - 1.0) < 1e-12
    assert np.allclose(system.velocities().sum(axis=0), np.zeros(2), atol=1e-9)
    assert system.min_distance() >= 1 - 1e-9
