"""Engine fronts refuse values that Python would silently truncate or convert: a seed of
1.9 (would give seed 1's stream), a restitution given as text, a fractional count."""

import math

import pytest

from kinetic import dsmc, edmd, rng
from kinetic.studies.costantini2010 import mean_free_time

DENSITY = 0.005
MEAN_FREE_TIME = mean_free_time(DENSITY)


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        ({"seed": 1.9}, "seed must be an integer"),
        ({"seed": -1}, "seed must be an integer >= 0"),
        ({"seed": True}, "seed must be an integer"),
        ({"restitution": "0.5"}, "restitution must be a number"),
        ({"rescale_every": 2.7}, "rescale_every must be an integer"),
        ({"collapse_streak": 3.0}, "collapse_streak must be an integer"),
        ({"contact_time": "0"}, "contact_time must be a number"),
        ({"restitution": math.nan}, "restitution must be in"),
    ],
)
def test_hard_sphere_system_refuses_truncation(arguments, message):
    with pytest.raises((TypeError, ValueError), match=message):
        edmd.HardSphereSystem(n_particles=10, density=0.01, **({"seed": 1} | arguments))


def test_streams_refuse_non_integer_seeds():
    with pytest.raises(TypeError, match="seed"):
        rng.stream_states(1.9, 2)
    with pytest.raises(TypeError, match="n_streams"):
        rng.stream_states(1, 2.0)


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        ({"seed": 1.9}, "seed must be an integer"),
        ({"restitution": "0.5"}, "restitution must be a real number"),
        ({"fictive_factor": 2.5}, "fictive_factor must be an integer"),
        ({"n_particles": 1e3}, "n_particles must be an integer"),
        ({"drag_rate": math.nan}, "drag_rate"),
    ],
)
def test_cooling_dsmc_refuses_truncation(arguments, message):
    base = {
        "n_particles": 100,
        "density": DENSITY,
        "restitution": 0.9,
        "drag_rate": 0.0,
        "equilibration": 0.0,
        "sample_interval": 0.1 * MEAN_FREE_TIME,
        "n_samples": 2,
        "fictive_factor": 1,
        "cells_per_side": 2,
        "time_step": 0.05 * MEAN_FREE_TIME,
        "collision_rule": "paper",
        "seed": 1,
    }
    with pytest.raises((TypeError, ValueError), match=message):
        dsmc.simulate_cooling_modes(**(base | arguments))
