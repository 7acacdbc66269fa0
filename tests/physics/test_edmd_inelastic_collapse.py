"""Strong dissipation: inelastic collapse is reported, never an endless loop; the TC model
(elastic collisions within a contact time) avoids it."""

import numpy as np
import pytest
from _edmd_checks import all_pairs_min_distance

from kinetic.edmd import HardSphereSystem, InelasticCollapseError


def column_of_disks(n=12, length=40.0):
    """Disks on one line of a periodic strip moving along it: one-dimensional dynamics,
    which collapse for α = 0.3 (N (1 − α) ≫ π)."""
    x = np.column_stack([(np.arange(n) + 0.5) * length / n, np.full(n, 2.0)])
    v = np.column_stack([np.random.default_rng(1).normal(size=n), np.zeros(n)])
    v[:, 0] -= v[:, 0].mean()
    return {"n_particles": n, "box": [length, 4.0], "positions": x, "velocities": v}


def test_collapse_of_a_column_is_detected_and_reported():
    # arrange
    system = HardSphereSystem(restitution=0.3, **column_of_disks())
    # act
    with pytest.raises(InelasticCollapseError) as report:
        system.run(collisions=10_000_000)
    # assert: a prompt report (long before the collisions asked for) naming the time, the
    # count and the particles
    assert report.value.collisions < 10_000_000
    assert "inelastic collapse" in str(report.value)
    assert all(0 <= p < 12 for p in report.value.particles)
    assert report.value.system.min_distance() >= 1 - 1e-9


def test_tc_model_avoids_the_collapse():
    # arrange
    system = HardSphereSystem(restitution=0.3, contact_time=1e-3, **column_of_disks())
    # act
    system.run(collisions=5_000)
    # assert: no report; part of the collisions were made elastic; the column keeps cooling
    assert system.collisions == 5_000
    assert 0 < system.counters()["inelastic_collisions"] < 5_000
    assert system.kinetic_temperature() < 1e-3
    assert system.min_distance() >= 1 - 1e-9


def test_strongly_inelastic_gas_in_two_dimensions_holds():
    """α = 0.3 in a 2D gas: the clusters of a freely cooling gas do not collapse within 20
    collisions a particle (seeds 1, 2, 3 and 9 all held; the column above collapses), it
    cools by 5 to 6 decades, keeps its momentum and never overlaps (all pairs checked)."""
    system = HardSphereSystem(n_particles=500, density=0.05, restitution=0.3, seed=9)
    momentum = system.velocities().sum(axis=0)
    system.run(collisions=20 * 500)
    assert system.collisions == 20 * 500
    assert 1e-8 < system.kinetic_temperature() < 1e-4
    np.testing.assert_allclose(system.velocities().sum(axis=0), momentum, atol=1e-9)
    assert all_pairs_min_distance(system) >= 1 - 1e-9
