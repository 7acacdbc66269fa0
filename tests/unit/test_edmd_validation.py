"""Bad input fails before any work, with a message naming the value and the allowed range."""

import math

import numpy as np
import pytest

from kinetic.edmd import HardSphereSystem, simulate


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"restitution": 0.0}, r"restitution must be in \(0, 1\], got 0.0"),
        ({"restitution": 1.5}, r"restitution must be in \(0, 1\], got 1.5"),
        ({"restitution": math.nan}, "restitution must be in"),
        ({"density": math.inf}, "density must be finite and > 0, got inf"),
        ({"density": -0.1}, "density must be finite and > 0"),
        ({"density": 1.2}, "cannot fit"),
        ({"density": 0.7}, "random insertion is refused"),
        ({"n_particles": 1}, "n_particles must be >= 2, got 1"),
        ({"dimension": 4}, "dimension must be 2 or 3, got 4"),
        ({"diameter": math.nan}, "diameter must be finite and > 0"),
        ({"temperature": 0.0}, "temperature = 0.0 is outside the allowed range"),
        ({"temperature": 1e308}, r"temperature = 1e\+308 is outside the allowed range"),
        ({"contact_time": -1.0}, "contact_time must be finite and >= 0"),
        ({"density": None, "box": [2.5, 100.0]}, "a periodic axis needs at least 3"),
        ({"prefetch": 3}, "prefetch must be 0, 1 or 2, got 3"),
        ({"sort_every": -1}, r"sort_every must be >= 0 \(0: never\), got -1"),
        ({"sort_every": 2.5}, "sort_every must be an integer, got 2.5"),
        # accepted before: 2.0 crashed later, the strings became walls, zeros never moved,
        # the all-zero stream piled every disk on one point ("placed only 1 of 100")
        ({"dimension": 2.0}, "dimension must be 2 or 3, got 2.0"),
        ({"walls": "no"}, "walls must be a bool or one bool per axis, got 'no'"),
        ({"walls": ["False", "False"]}, "walls must be a bool or one bool per axis"),
        ({"velocities": np.zeros((100, 2))}, "velocities are all zero"),
        ({"stream": np.zeros(4, np.uint64)}, "stream is the all-zero xoshiro state"),
    ],
)
def test_bad_parameters_are_refused(options, message):
    arguments = {"n_particles": 100, "density": 0.01, "seed": 1, **options}
    with pytest.raises((ValueError, TypeError), match=message):
        HardSphereSystem(**arguments)


def test_overlapping_initial_configuration_is_refused():
    positions = np.array([[1.0, 1.0], [1.5, 1.0], [5.0, 5.0]])
    with pytest.raises(ValueError, match=r"initial configuration overlaps: closest centres 0\.5"):
        HardSphereSystem(n_particles=3, box=[10.0, 10.0], positions=positions, seed=1)


def test_overlap_across_the_periodic_boundary_is_refused():
    positions = np.array([[0.2, 5.0], [9.9, 5.0], [5.0, 5.0]])
    with pytest.raises(ValueError, match="overlaps"):
        HardSphereSystem(n_particles=3, box=[10.0, 10.0], positions=positions, seed=1)


def test_particle_outside_the_walls_is_refused():
    positions = np.array([[0.2, 5.0], [5.0, 5.0]])
    with pytest.raises(ValueError, match=r"outside the box along axis 0 \(allowed \[0.5, 9.5\]\]"):
        HardSphereSystem(n_particles=2, box=[10.0, 10.0], walls=True, positions=positions, seed=1)


def test_non_finite_velocities_are_refused():
    velocities = np.zeros((4, 2))
    velocities[2, 1] = np.nan
    with pytest.raises(ValueError, match="velocities must be a finite"):
        HardSphereSystem(n_particles=4, box=[10.0, 10.0], velocities=velocities, seed=1)


def test_run_arguments_are_checked():
    system = HardSphereSystem(n_particles=50, density=0.01, seed=1)
    with pytest.raises(ValueError, match="give until"):
        system.run()
    with pytest.raises(ValueError, match="collisions = 0 is not allowed"):
        system.run(collisions=0)
    with pytest.raises(TypeError, match="collisions must be an integer"):
        system.run(collisions=1.7)  # ran one collision
    with pytest.raises(TypeError, match="collisions must be an integer"):
        system.run(collisions="3")
    with pytest.raises(ValueError, match="max_events = 0 is not allowed"):
        system.run(collisions=1, max_events=0)  # said the particles stopped colliding
    system.run(until=5.0)
    with pytest.raises(ValueError, match="until must be finite and >= the current time"):
        system.run(until=1.0)
    with pytest.raises(TypeError, match="until must be a real number"):
        system.run(until="10")  # failed inside math.isfinite, naming no argument


def test_a_gas_that_stopped_colliding_exhausts_the_event_budget():
    # two disks flying apart in parallel never collide: a count-limited run must stop
    positions = np.array([[2.0, 2.0], [2.0, 8.0]])
    velocities = np.array([[1.0, 0.0], [1.0, 0.0]])
    system = HardSphereSystem(
        n_particles=2, box=[10.0, 10.0], positions=positions, velocities=velocities
    )
    with pytest.raises(RuntimeError, match="stopped colliding"):
        system.run(collisions=1)


def test_a_very_dilute_gas_is_not_taken_for_one_that_stopped_colliding():
    """At ρσ² = 1e-7 a collision takes thousands of cell crossings, more than the event
    budget of a count-limited call allows (1000 a collision): it stopped after 111
    collisions of a normal gas, saying the particles had stopped colliding."""
    system = HardSphereSystem(n_particles=200, density=1e-7, seed=2)
    system.run(collisions=400)
    assert system.collisions == 400
    assert system.counters()["crossings"] > 1000 * 400


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"windows": [10.0, 5.0]}, "windows must be strictly increasing"),
        ({"windows": [0.0]}, "windows must be finite and > 0"),
        ({"windows": [100.0]}, "the longest window 100.0 exceeds duration 50"),
        ({"checkpoints": [10.0, 20.0]}, "the last checkpoint 20.0 must equal duration 50"),
        ({"realizations": 0}, "realizations must be >= 1, got 0"),
        ({"equilibration": 0.5}, "equilibration must be >= 1"),
        ({"density": 1.2}, "cannot fit"),
        ({"seed": -1}, "seed = -1 is not allowed"),
        ({"seed": 2**63}, "seed = 9223372036854775808 is not allowed"),
        ({"duration": "50"}, "duration must be a real number"),
        ({"equilibration": "5"}, "equilibration must be a real number"),
        ({"windows": "abc"}, "windows must be a sequence of numbers"),
    ],
)
def test_simulate_refuses_bad_protocols(options, message):
    arguments = {
        "n_particles": 100,
        "density": 0.01,
        "seed": 1,
        "realizations": 2,
        "duration": 50.0,
        "windows": [1.0, 10.0],
        **options,
    }
    with pytest.raises((ValueError, TypeError), match=message):
        simulate(**arguments)


@pytest.mark.parametrize(
    ("options", "message"),
    [
        # a NaN sample time blocked every later sample; -1 bins gave numpy's own error and
        # 0 count bins became 1 without a word
        ({"sample_times": [math.nan, 1e6]}, "sample_times must be finite"),
        ({"flight_bins": -1}, "flight_bins = -1 is not allowed"),
        ({"count_bins": 0}, "count_bins = 0 is not allowed"),
        ({"path_bins": 2.5}, "path_bins must be an integer"),
        ({"flight_bin_width": 0.0}, "flight_bin_width = 0.0 is outside"),
    ],
)
def test_bad_observers_are_refused(options, message):
    from kinetic.edmd import Observers

    with pytest.raises((TypeError, ValueError), match=message):
        Observers.create(10, **options)
