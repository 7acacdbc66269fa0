"""No two particles ever overlap (beyond round-off), in every geometry the engine offers."""

import numpy as np
import pytest
from _edmd_checks import all_pairs_min_distance

from kinetic.edmd import HardSphereSystem


@pytest.mark.parametrize(
    "options",
    [
        {"dimension": 2, "density": 0.05, "n_particles": 400},
        {"dimension": 2, "density": 0.3, "n_particles": 400},
        {"dimension": 2, "box": [20.0, 30.0], "walls": True, "n_particles": 150},
        {"dimension": 2, "box": [25.0, 25.0], "walls": [True, False], "n_particles": 150},
        {"dimension": 3, "density": 0.05, "n_particles": 400},
        {
            "dimension": 2,
            "density": 0.05,
            "n_particles": 400,
            "restitution": 0.8,
            "rescale_every": 200,
        },
    ],
    ids=["2d-dilute", "2d-dense", "2d-walls", "2d-channel", "3d", "2d-inelastic-thermostat"],
)
def test_no_overlap_at_any_sampled_time(options):
    # arrange
    system = HardSphereSystem(seed=3, **options)
    walls = np.broadcast_to(np.asarray(options.get("walls", False)), (system.dimension,))
    closest = []
    # act: 60 snapshots, 100 to 150 collisions apart (irregular, so snapshots fall anywhere)
    for step in range(60):
        system.run(collisions=100 + 17 * (step % 4))
        closest.append(all_pairs_min_distance(system))
        x = system.positions()
        for axis in np.flatnonzero(walls):
            assert x[:, axis].min() >= 0.5 - 1e-9
            assert x[:, axis].max() <= system.box[axis] - 0.5 + 1e-9
    # assert
    assert min(closest) >= 1.0 - 1e-9
    assert system.counters()["collisions"] >= 6000
