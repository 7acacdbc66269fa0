"""Limits every front checks before any work: the last realization index of a batch fits a
dataset's int64 ``realization`` coordinate (2**64 ran a whole simulation, then failed at
the write), a histogram has at most a million bins, and a run's arrays fit the machine's
memory (a second point of 10¹¹ particles passed the checks, and numpy's MemoryError after
the first point's run lost it)."""

import pytest

from kinetic import edmd, validate
from kinetic.cloning import simulate as simulate_cloning
from kinetic.dsmc import (
    simulate_cooling_modes,
    simulate_free_flights,
    simulate_homogeneous,
    simulate_homogeneous_points,
)
from kinetic.seeds import MAX_SEED

COOLING = dict(
    n_particles=100,
    density=0.05,
    restitution=0.8,
    drag_rate=0.01,
    equilibration=2.0,
    sample_interval=1.0,
    n_samples=3,
    seed=3,
)

HOMOGENEOUS = dict(
    n_particles=200, restitution=0.9, duration=1.0, time_step=0.05, sample_interval=0.5, seed=3
)

FRONTS = {
    "homogeneous DSMC": lambda first: simulate_homogeneous(
        **HOMOGENEOUS, sample_stride=2, n_realizations=2, first_realization=first
    ),
    "free flights": lambda first: simulate_free_flights(
        n_particles=100, duration=1.0, seed=3, n_realizations=2, first_realization=first
    ),
    "inhomogeneous DSMC": lambda first: simulate_cooling_modes(
        **COOLING,
        fictive_factor=2,
        cells_per_side=3,
        time_step=0.5,
        collision_rule="paper",
        n_realizations=2,
        first_realization=first,
    ),
    "cooling MD": lambda first: edmd.simulate_cooling_modes(
        **COOLING, n_realizations=2, first_realization=first
    ),
    "equilibrium MD": lambda first: edmd.simulate(
        n_particles=100,
        density=0.01,
        seed=3,
        duration=10.0,
        realizations=2,
        first_realization=first,
    ),
    "cloning": lambda first: simulate_cloning(
        lam=0.5,
        population=50,
        duration=8.0,
        transient=4.0,
        n_blocks=4,
        seed=3,
        n_realizations=2,
        first_realization=first,
    ),
}


@pytest.mark.parametrize("front", sorted(FRONTS))
def test_the_last_realization_index_must_fit_an_int64(front):
    with pytest.raises(ValueError, match="last realization's index"):
        FRONTS[front](MAX_SEED)


def test_the_largest_index_is_allowed():
    assert validate.realizations(MAX_SEED - 1, 2, count_name="n") == (MAX_SEED - 1, 2)


TOO_LARGE = {
    "a second point of 1e11 particles": (
        lambda: simulate_homogeneous_points([HOMOGENEOUS, HOMOGENEOUS | {"n_particles": 10**11}]),
        "n_particles = 100000000000, n_realizations = 1 and 2 windows",
    ),
    "a second point of 1e10 windows": (
        lambda: simulate_homogeneous_points(
            [
                HOMOGENEOUS,
                HOMOGENEOUS | {"duration": 1e9, "sample_interval": 0.1, "sample_stride": 1},
            ]
        ),
        "10000000000 windows",
    ),
    "1e12 c_x bins": (
        lambda: simulate_homogeneous(**HOMOGENEOUS, n_cx_bins=10**12),
        "n_cx_bins = 1000000000000 must be an even integer in",
    ),
    "1e12 flight-time bins": (
        lambda: simulate_free_flights(n_particles=100, duration=1.0, seed=1, n_time_bins=10**12),
        "n_time_bins = 1000000000000 is not allowed",
    ),
    "1e12 MD particles": (
        lambda: edmd.simulate(
            n_particles=10**12, density=0.01, seed=1, duration=100.0, realizations=1
        ),
        "n_particles = 1000000000000 would need about",
    ),
    "1e12 MD histogram bins": (
        lambda: edmd.simulate(
            n_particles=100,
            density=0.01,
            seed=1,
            duration=100.0,
            realizations=1,
            flight_time_bins=10**12,
        ),
        "flight_time_bins = 1000000000000 is not allowed",
    ),
    "1e12 DSMC samples": (
        lambda: simulate_cooling_modes(
            **COOLING | {"n_samples": 10**12},
            fictive_factor=2,
            cells_per_side=3,
            time_step=0.5,
            collision_rule="paper",
        ),
        "n_samples = 1000000000000 would need about",
    ),
    "1e12 MD samples": (
        lambda: edmd.simulate_cooling_modes(**COOLING | {"n_samples": 10**9}, n_realizations=1000),
        "n_samples = 1000000000 would need about",
    ),
    "1e6 realizations of 1e8 clones on cuda": (
        lambda: simulate_cloning(
            lam=0.5,
            population=10**8,
            duration=8.0,
            transient=4.0,
            n_blocks=4,
            seed=3,
            n_realizations=10**4,
            backend="cuda",
        ),
        "population = 100000000, n_realizations = 10000",
    ),
}


@pytest.mark.parametrize("case", sorted(TOO_LARGE))
def test_what_cannot_fit_is_refused_before_any_work(case):
    front, message = TOO_LARGE[case]
    with pytest.raises(ValueError, match=message):
        front()
