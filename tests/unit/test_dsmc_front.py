"""The DSMC fronts: validation before work, reproducibility, batching, dataset conventions."""

import math
import re

import numpy as np
import pytest

from kinetic import io
from kinetic.dsmc import (
    HomogeneousSettings,
    Samples,
    advance_gas,
    new_gas,
    realization_streams,
    simulate_free_flights,
    simulate_homogeneous,
)

SMALL = dict(
    n_particles=200,
    restitution=0.9,
    duration=1.0,
    time_step=0.05,
    sample_interval=0.5,
    seed=3,
    sample_stride=2,
)


@pytest.mark.parametrize(
    ("changes", "fragment"),
    [
        ({"restitution": 0.0}, "restitution = 0.0 is outside the allowed range (0, 1]"),
        ({"restitution": 1.2}, "restitution = 1.2 is outside the allowed range (0, 1]"),
        ({"restitution": math.nan}, "restitution = nan"),
        ({"n_particles": 1}, "n_particles = 1 is not allowed: must be >= 2"),
        ({"reduced_field": -0.1}, "reduced_field = -0.1 is outside the allowed range [0, 0.2]"),
        ({"reduced_field": 0.25}, "reduced_field = 0.25 is outside the allowed range [0, 0.2]"),
        ({"time_step": 0.6}, "time_step = 0.6 τ is not allowed: must be in (0, 0.4431] τ"),
        ({"time_step": -0.01}, "time_step = -0.01 τ is not allowed"),
        ({"time_step": math.inf}, "time_step = inf τ is not allowed"),
        ({"dimension": 4}, "dimension = 4 is not allowed: must be in [2, 3]"),
        ({"kernel": "soft"}, "kernel = 'soft' is not allowed: must be one of hard_spheres"),
        ({"force_step": "rk4"}, "force_step = 'rk4' is not allowed: must be one of euler, exact"),
        ({"sample_interval": 0.07}, "sample_interval = 0.07 must be a whole multiple"),
        ({"duration": 1.2}, "duration = 1.2 must be a whole multiple (>= 1) of sample_interval"),
        ({"sample_stride": 20}, "sample_stride = 20 is not allowed: must be in [1, 10]"),
        ({"histogram_start": 1.0}, "histogram_start = 1.0 τ is outside the allowed range"),
        # inside the last window: rounded up to 1.0 τ, it left the histograms empty
        ({"histogram_start": 0.75}, "leaves no window of the 1 τ run to histogram"),
        ({"n_cx_bins": 7}, "n_cx_bins = 7 must be an even integer"),
        ({"seed": -1}, "seed = -1 is not allowed"),
        ({"n_realizations": 0}, "n_realizations = 0 is not allowed"),
        ({"backend": "cuda", "n_realizations": 70_000}, "at most 65535 realizations"),
    ],
)
def test_bad_parameters_are_refused_with_the_value_and_range(changes, fragment):
    with pytest.raises((ValueError, TypeError)) as error:
        simulate_homogeneous(**{**SMALL, **changes})
    assert fragment in str(error.value)


def test_force_step_too_coarse_is_refused():
    """Above ε* = 0.1, where the c_x tail is a power law and a long run would stop at its
    first runaway particle, ε* δt <= 0.02; at 0.1 the time step's own limit is enough."""
    HomogeneousSettings(n_particles=10, restitution=1.0, time_step=0.4, reduced_field=0.1)
    HomogeneousSettings(n_particles=10, restitution=1.0, time_step=0.1, reduced_field=0.2)
    with pytest.raises(ValueError, match=r"must be <= 0.02 at reduced_field > 0.1"):
        HomogeneousSettings(n_particles=10, restitution=1.0, time_step=0.2, reduced_field=0.2)


def test_time_step_limit_names_the_collision_time():
    with pytest.raises(ValueError, match=r"collision time is 0.886"):
        HomogeneousSettings(n_particles=10, restitution=1.0, time_step=1.0)


def test_free_flight_front_validates_before_work():
    with pytest.raises(ValueError, match=r"duration = 0\.0 /omega is outside"):
        simulate_free_flights(n_particles=10, duration=0.0, seed=1)
    with pytest.raises(ValueError, match="kernel = 'hard' is not allowed"):
        simulate_free_flights(n_particles=10, duration=1.0, seed=1, kernel="hard")


def test_initial_velocities_must_be_finite_and_shaped():
    settings = HomogeneousSettings(n_particles=4, restitution=1.0, time_step=0.1, dimension=2)
    stream = realization_streams(1, 0, 1)[0]
    with pytest.raises(ValueError, match=r"velocity has shape \(3, 4\), expected"):
        new_gas(settings, stream, np.ones((3, 4)))
    bad = np.ones((2, 4))
    bad[1, 2] = np.inf
    with pytest.raises(ValueError, match=r"velocity\[1, 2\] = inf is not finite"):
        new_gas(settings, stream, bad)


def test_same_seed_same_data_and_batching_does_not_matter():
    whole = simulate_homogeneous(**SMALL, n_realizations=3)
    again = simulate_homogeneous(**SMALL, n_realizations=3)
    first = simulate_homogeneous(**SMALL, n_realizations=1)
    rest = simulate_homogeneous(**SMALL, n_realizations=2, first_realization=1)
    np.testing.assert_array_equal(whole.moments.values, again.moments.values)
    np.testing.assert_array_equal(whole.moments.values[:1], first.moments.values)
    np.testing.assert_array_equal(whole.moments.values[1:], rest.moments.values)
    np.testing.assert_array_equal(whole.cx_counts.values[1:], rest.cx_counts.values)
    assert list(rest.realization.values) == [1, 2]


def test_datasets_follow_the_io_conventions(tmp_path):
    homogeneous = simulate_homogeneous(**SMALL, reduced_field=0.05, force_step="exact")
    flights = simulate_free_flights(
        n_particles=50,
        duration=2.0,
        seed=1,
        n_time_bins=10,
        n_path_bins=10,
        max_flight_time=5.0,
        max_free_path=5.0,
    )
    for dataset in (homogeneous, flights):
        io.check_conventions(dataset)
        path = io.write_dataset(dataset, tmp_path / "run.nc")
        back = io.read_dataset(path)
        assert io.parameters_of(back)["n_particles"] == dataset.attrs["n_particles"]
    assert homogeneous.attrs["seed"] == 3
    assert int(homogeneous.snapshots.sum()) == 10  # 20 steps, every 2nd step
    assert np.all(homogeneous.cpu_seconds.values > 0)


@pytest.fixture
def unchecked_fields(monkeypatch):
    """Looser limits than the front's (ε* <= 1, ε* δt <= 0.1 at any field): the run-time guards
    below must stop a run that validation did not foresee, so they are tested past it."""
    from kinetic.dsmc import arguments

    monkeypatch.setattr(arguments, "MAX_REDUCED_FIELD", 1.0)
    monkeypatch.setattr(arguments, "MAX_FIELD_STEP", 0.1)


@pytest.mark.parametrize(("splitting", "n", "limit"), [("lie", 1000, 20), ("strang", 4000, 40)])
def test_exact_force_step_blow_up_stops_with_a_clear_message(splitting, n, limit, unchecked_fields):
    """ε* δt = 0.1: Lie's whole step a = ε δt/2 after the collisions blows up at c_x <= -20,
    Strang's half step ε δt/4 before them at c_x <= -40, and the message says which. The
    fast particle has c_x of about -38 (N = 1000) or -77 (N = 4000) once the gas is
    rescaled to T0. With Lie it collides first, and keeps c_x below -20 in about half of
    the streams (56 of 100 here; the test used to hang on one stream): at least 20 of 100
    must blow up, all with the message."""
    settings = HomogeneousSettings(
        n_particles=n,
        restitution=1.0,
        time_step=0.1,
        reduced_field=1.0,
        force_step="exact",
        splitting=splitting,
    )
    velocity = np.random.default_rng(1).normal(size=(3, n))
    velocity[0, 0] = -400.0 * math.sqrt(n / 1000)
    message = rf"exact force step diverged: .* c_x <= -{limit}\b"
    if splitting == "strang":
        gas = new_gas(settings, realization_streams(1, 0, 1)[0], velocity)
        with pytest.raises(RuntimeError, match=message):
            advance_gas(gas, 1)
        return
    blown = 0
    for stream in realization_streams(1, 0, 100):
        gas = new_gas(settings, stream, velocity)
        try:
            advance_gas(gas, 1)
        except RuntimeError as error:
            assert re.search(message, str(error)), error
            blown += 1
    assert blown >= 20


def test_euler_force_step_too_large_stops_with_a_clear_message(unchecked_fields):
    n = 1000
    settings = HomogeneousSettings(
        n_particles=n, restitution=1.0, time_step=0.1, reduced_field=1.0, force_step="euler"
    )
    velocity = np.random.default_rng(1).normal(size=(3, n))
    velocity[0, 0] = 400.0
    gas = new_gas(settings, realization_streams(1, 0, 1)[0], velocity)
    with pytest.raises(RuntimeError, match=r"Euler force step is not small: .* \|c_x\| > 10"):
        advance_gas(gas, 1)


def test_state_api_exposes_reduced_velocities_and_timing():
    settings = HomogeneousSettings(n_particles=300, restitution=0.7, time_step=0.05)
    gas = new_gas(settings, realization_streams(2, 0, 1)[0])
    samples = Samples(stride=1)
    advance_gas(gas, 4, samples)
    c = gas.reduced_velocities()
    assert c.shape == (300, 3)
    assert np.mean(np.sum(c**2, axis=1)) == pytest.approx(1.5, rel=1e-12)
    assert samples.moment_sums[0] == 4
    assert gas.steps == 4 and gas.time == pytest.approx(0.2)
    assert gas.collisions > 0 and gas.cpu_seconds > 0


def test_beta1_weights_sum_to_the_marginal_moment():
    run = simulate_homogeneous(
        **{**SMALL, "histogram_start": 0.0, "cx_max": 8.0}, reduced_field=0.1
    )
    # c_x (3/2 - c_x^2) = c_x L_1^(1/2)(c_x^2): summed over particles and snapshots it is
    # N x the sum over snapshots of the moment marginal_1
    total = run.cx_weights.sum("cx") + run.cx_outside_weights.sum("side")
    per_snapshot = run.moments.sel(moment="marginal_1") * run.snapshots
    expected = per_snapshot.sum("time") * 200
    np.testing.assert_allclose(total.values, expected.values, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("dimension", [2, 3])
def test_batch_starts_are_new_gas_starts_bit_for_bit(dimension):
    """``maxwellian_starts`` (the cuda backend's starts, one compiled call for a batch)
    draws what ``new_gas`` draws for each realization: the same velocities and stream
    states, bit for bit, and each realization's largest speed."""
    from kinetic.dsmc.state import maxwellian_starts

    settings = HomogeneousSettings(
        n_particles=101, restitution=0.9, time_step=0.01, dimension=dimension
    )
    streams = realization_streams(4, 3, 5)
    velocity, states, tops = maxwellian_starts(dimension, 101, streams)
    for r in range(5):
        gas = new_gas(settings, streams[r])
        np.testing.assert_array_equal(velocity[r], gas.velocity)
        np.testing.assert_array_equal(states[r], gas.rng)
        assert tops[r] == np.sqrt(np.einsum("kn,kn->n", gas.velocity, gas.velocity).max())
    assert np.array_equal(streams, realization_streams(4, 3, 5))  # the input is not advanced


def test_an_all_zero_stream_is_refused_by_both_dsmc_engines():
    """The all-zero xoshiro state yields only zeros: the homogeneous gas's Maxwellian draw
    never ended, and the inhomogeneous gas put every particle on one point."""
    from kinetic.dsmc import CoolingModesSettings, new_cooling_gas, new_gas

    zero = np.zeros(4, np.uint64)
    with pytest.raises(ValueError, match="all-zero xoshiro state"):
        new_gas(HomogeneousSettings(n_particles=8, restitution=0.9, time_step=0.01), zero)
    settings = CoolingModesSettings(
        n_particles=8,
        density=0.05,
        restitution=0.9,
        drag_rate=0.0,
        fictive_factor=1,
        cells_per_side=1,
        time_step=0.5,
        collision_rule="majorant",
    )
    with pytest.raises(ValueError, match="all-zero xoshiro state"):
        new_cooling_gas(settings, zero)


def test_windows_are_labelled_by_the_mean_time_of_their_snapshots():
    """Snapshots come after the steps k = stride, 2 stride, ...: a window of 7 steps with a
    stride of 5 holds the snapshots of step 5, then 10, then 15 and 20 (its centre was
    the label, 0.05-0.075 τ early in the configs). The histograms' start is the window
    boundary actually used: asked for 0.3 τ with windows of 0.35 τ, it is 0.35 τ."""
    from kinetic.dsmc.homogeneous import snapshot_times

    run = SMALL | {"duration": 1.05, "time_step": 0.05, "sample_interval": 0.35}
    data = simulate_homogeneous(**run | {"sample_stride": 5, "histogram_start": 0.3})
    np.testing.assert_allclose(data.time.values, [0.25, 0.5, 0.875])
    np.testing.assert_array_equal(data.snapshots.values[0], [1, 1, 2])
    assert data.attrs["histogram_start_tau"] == pytest.approx(0.35)
    np.testing.assert_allclose(snapshot_times(2, 200, 50, 0.003), [0.375, 0.975])
    every = simulate_homogeneous(**SMALL | {"sample_stride": 1})  # the window's centre + δt/2
    np.testing.assert_allclose(every.time.values, [0.275, 0.775])


def test_runs_too_fine_for_their_memory_or_calls_are_refused_before_any_work():
    """10⁴ cells a side of 100 particles passed and would have allocated about 25 GB; a
    free-flight chunk of 1e-9 asked for 2e9 kernel calls (0.4 s at 1e-4)."""
    from kinetic.dsmc import simulate_cooling_modes

    with pytest.raises(ValueError, match=r"10000 cells a side|100000000 cells"):
        simulate_cooling_modes(
            n_particles=100,
            density=0.05,
            restitution=0.8,
            drag_rate=0.0,
            equilibration=0.0,
            sample_interval=0.5,
            n_samples=2,
            seed=1,
            fictive_factor=1,
            cells_per_side=10_000,
            time_step=0.5,
            collision_rule="paper",
        )
    with pytest.raises(ValueError, match="kernel calls"):
        simulate_free_flights(
            n_particles=50,
            duration=2.0,
            seed=1,
            n_time_bins=10,
            n_path_bins=10,
            max_flight_time=5.0,
            max_free_path=5.0,
            chunk=1e-9,
        )


def test_a_forced_run_with_a_coarse_lie_step_is_warned_of(caplog):
    """The Lie splitting biases κ'/κ0 by about +0.3 δt/τ: a forced run at 0.3 τ (+9 %) is
    warned of, Strang's at the same step and Lie's at 0.1 τ (+3 %) are not."""
    import logging

    run = SMALL | {"duration": 1.2, "time_step": 0.3, "sample_interval": 0.6, "sample_stride": 1}
    run |= {"reduced_field": 0.02, "force_step": "exact"}
    with caplog.at_level(logging.WARNING, logger="kinetic"):
        simulate_homogeneous(**run, splitting="lie")
        assert "biases kappa'/kappa0 by about +9 %" in caplog.text
        caplog.clear()
        simulate_homogeneous(**run, splitting="strang")
        simulate_homogeneous(**run | {"time_step": 0.1}, splitting="lie")
        assert "biases kappa'/kappa0" not in caplog.text
