"""Elastic collisions conserve energy to round-off; every collision conserves momentum."""

import numpy as np
import pytest

from kinetic.edmd import HardSphereSystem


@pytest.mark.parametrize(
    ("dimension", "walls"), [(2, False), (2, True), (3, False)], ids=["2d", "2d-walls", "3d"]
)
def test_energy_conserved_to_round_off_at_unit_restitution(dimension, walls):
    # arrange
    system = HardSphereSystem(
        n_particles=500, density=0.05, dimension=dimension, walls=walls, seed=5
    )
    energy = np.sum(system.velocities() ** 2)
    # act: 100 collisions per particle
    system.run(collisions=50_000)
    # assert: relative drift at the level of accumulated double-precision round-off
    drift = abs(np.sum(system.velocities() ** 2) / energy - 1.0)
    assert drift < 1e-11, drift


@pytest.mark.parametrize("restitution", [1.0, 0.5])
def test_momentum_conserved_exactly_in_a_periodic_box(restitution):
    # arrange: a non-zero total momentum, to see it carried unchanged
    rng = np.random.default_rng(8)
    velocities = rng.normal(size=(400, 2)) + np.array([0.3, -0.2])
    system = HardSphereSystem(
        n_particles=400,
        density=0.05,
        velocities=velocities,
        seed=5,
        restitution=restitution,
        contact_time=1e-3,
    )
    momentum = system.velocities().sum(axis=0)
    # act: 20 collisions per particle (at α = 0.5 the relative motion then has almost
    # stopped, while the centre of mass keeps streaming)
    system.run(collisions=4_000)
    # assert: each collision adds ±Δv to two particles; only round-off remains
    assert np.allclose(system.velocities().sum(axis=0), momentum, rtol=0, atol=1e-10)
    if restitution < 1:
        thermal = system.velocities() - system.velocities().mean(axis=0)
        assert np.mean(thermal**2) < 0.05
