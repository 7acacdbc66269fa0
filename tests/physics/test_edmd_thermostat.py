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


def test_a_flight_across_a_rescaling_is_the_scaled_motion():
    """The kernel's thermostat and ``scale_velocities`` scale the same gas at the same
    collision (T from 4 to 1): the same trajectory, so the same flights, times and paths
    (the kernel's thermostat kept the flights' start times, so a flight across the
    rescaling had the new speed over the whole old time: its summed path was 3.4 % low)."""
    from kinetic.edmd import Observers

    rng = np.random.default_rng(1)
    velocities = rng.normal(size=(400, 2)) * 2.0
    velocities -= velocities.mean(axis=0)

    def gas(rescale_every):
        system = HardSphereSystem(
            n_particles=400,
            density=0.05,
            seed=3,
            velocities=velocities,
            rescale_every=rescale_every,
            temperature=1.0,
        )
        observers = Observers.create(400, flight_bins=10, path_bins=10)
        observers.start(system)
        return system, observers

    kernel, kernel_observers = gas(2000)
    kernel.run(collisions=2000, observers=kernel_observers)
    kernel.run(collisions=300, observers=kernel_observers)
    front, front_observers = gas(0)
    front.run(collisions=2000, observers=front_observers)
    front.scale_velocities(np.sqrt(1.0 / front.kinetic_temperature()))
    front.run(collisions=300, observers=front_observers)
    np.testing.assert_allclose(kernel.positions(), front.positions(), atol=1e-8)
    np.testing.assert_allclose(kernel.last_collision, front.last_collision, rtol=1e-9)
    np.testing.assert_allclose(kernel_observers.flight_sums, front_observers.flight_sums, rtol=1e-9)
