"""Strong dissipation: inelastic collapse is reported, never an endless loop; the TC model
(elastic collisions within a contact time) avoids it."""

import numpy as np
import pytest

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


def test_strongly_inelastic_gas_holds_or_stops_with_the_report():
    # arrange: α = 0.3 in a 2D gas; one outcome or the other, within the collisions asked for
    system = HardSphereSystem(n_particles=500, density=0.05, restitution=0.3, seed=9)
    # act
    try:
        system.run(collisions=20 * 500)
        outcome = "held"
    except InelasticCollapseError as report:
        outcome = "collapse"
        assert report.time > 0
    # assert
    assert system.min_distance() >= 1 - 1e-9
    if outcome == "held":
        assert system.kinetic_temperature() < 0.1  # α = 0.3 cools fast
