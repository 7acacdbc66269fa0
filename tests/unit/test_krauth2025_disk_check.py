"""The check that a disk box can be sampled by direct-disks (numpy, at the workflow's
parse and in the sampler's front) agrees with the engine, and the fronts of the disk
engines refuse what they cannot run before any work."""

import math

import numpy as np
import pytest

from kinetic import samplers
from kinetic.rng import stream_states
from kinetic.samplers import disk_configuration
from kinetic.studies.krauth2025 import check_disks
from kinetic.theory.krauth2025 import direct_disks_acceptance, snapshot_count

CONFIGURED = {"n_disks": 4, "sigma": 0.15, "box": [1.0, 1.0]}
SAMPLES = {"direct_samples": 1_000_000, "sampler_realizations": 16}  # config.yaml's


def test_the_configured_box_passes():
    assert 0.03 < check_disks(CONFIGURED | SAMPLES) < 0.045


@pytest.mark.parametrize(
    ("sigma", "message"),
    [
        (0.26, "too dense"),  # four disks of radius > 1/4 do not fit in a unit square
        (0.245, "too dense"),  # they fit, but far too rarely for a start to be found
        (0.23, "would start about"),  # 1.6e7 configurations at 3e-7: 5e13 starts, days
        (0.6, "cannot hold a disk"),
    ],
)
def test_boxes_that_cannot_be_sampled_are_refused(sigma, message):
    with pytest.raises(ValueError, match=message):
        check_disks(CONFIGURED | SAMPLES | {"sigma": sigma})


def test_boxes_with_room_by_area_but_not_by_shape_are_refused_at_once():
    """2 disks of radius 1 in a 3 x 3 box cover 70 % of it, but their centres (in a unit
    square) cannot be 2 apart; 6 disks of radius 0.1 do not fit in a row of 1 x 0.21."""
    for n_disks, sigma, box in ((2, 1.0, (3.0, 3.0)), (6, 0.1, (1.0, 0.21))):
        assert direct_disks_acceptance(n_disks, sigma, box) == 0.0
        with pytest.raises(ValueError, match="too dense"):
            check_disks({"n_disks": n_disks, "sigma": sigma, "box": box} | SAMPLES)


def test_acceptance_of_two_disks_is_the_exact_one():
    """Two disks of radius σ in a box of side 1 with walls: the centres are uniform in a
    square of side a = 1 − 2σ, and they overlap with probability P(|x − y| < 2σ) for two
    uniform points of that square, π r² / a² − (8/3) r³ / a³ + r⁴ / (2 a⁴) with r = 2σ
    (r ≤ a). The estimate is the legal fraction of ``population`` second disks, each
    beside a first disk drawn again from ``population`` uniform ones: its variance is at
    most twice the binomial p(1 − p)/population (the first disks' own spread); compare
    within 4 of that."""
    sigma, population = 0.1, 20_000
    a, r = 1 - 2 * sigma, 2 * sigma
    p = 1 - (np.pi * r**2 / a**2 - 8 / 3 * r**3 / a**3 + r**4 / (2 * a**4))
    estimate = direct_disks_acceptance(2, sigma, (1.0, 1.0), population=population, seed=3)
    assert abs(estimate - p) < 4 * math.sqrt(2 * p * (1 - p) / population)


@pytest.mark.parametrize("sigma", [0.15, 0.2])
def test_the_engine_starts_as_many_configurations_as_the_estimate_says(sigma):
    """direct-disks' legal fraction of its starts (samples over the configurations it
    started, ``work``) against the estimate's mean over 8 seeds: within 4 combined
    errors (the engine's is the geometric count's, sqrt((1 − p)/samples) relative)."""
    estimates = [direct_disks_acceptance(4, sigma, (1.0, 1.0), seed=seed) for seed in range(8)]
    estimate, estimate_err = np.mean(estimates), np.std(estimates, ddof=1) / math.sqrt(8)
    samples = 2000
    data = samplers.sample_disks(
        "direct", **CONFIGURED | {"sigma": sigma}, samples=samples, realizations=2, bins=4, seed=5
    )
    measured = 2 * samples / int(data["work"].sum())
    measured_err = measured * math.sqrt((1 - measured) / (2 * samples))
    assert abs(measured - estimate) < 4 * math.hypot(estimate_err, measured_err)
    positions = disk_configuration(4, sigma, (1.0, 1.0), state=stream_states(1, 1)[0])
    gaps = np.linalg.norm(positions[:, None] - positions[None], axis=-1)[np.triu_indices(4, 1)]
    assert np.all(gaps > 2 * sigma)


def test_the_sampler_refuses_bad_arguments_before_any_work(monkeypatch):
    from kinetic.samplers import kernels

    def no_run(*args, **kwargs):
        raise AssertionError("a run started")

    monkeypatch.setattr(kernels, "direct_disks", no_run)
    monkeypatch.setattr(kernels, "markov_disks", no_run)
    run = {"n_disks": 4, "sigma": 0.15, "samples": 10, "realizations": 2, "bins": 4, "seed": 0}
    with pytest.raises(ValueError, match="would start about"):
        samplers.sample_disks("direct", **run | {"sigma": 0.23, "samples": 10**6})
    with pytest.raises(TypeError, match="step"):
        samplers.sample_disks("markov", **run, step=True)
    with pytest.raises(TypeError, match="step"):
        samplers.sample_disks("markov", **run, step="0.05")
    with pytest.raises(ValueError, match="two sides"):
        samplers.sample_disks("direct", **run, box=(1.0, 1.0, 1.0))
    with pytest.raises(TypeError, match="sigma"):
        samplers.sample_disks("direct", **run | {"sigma": True})


def test_a_configuration_direct_disks_gave_up_on_is_an_error(monkeypatch):
    """The kernel returns −1 when one configuration took more than its cap of starts: the
    front stops, where it stored −1 and returned a density short of N."""
    from kinetic.samplers import kernels

    monkeypatch.setattr(kernels, "direct_disks", lambda *args: -1)
    with pytest.raises(RuntimeError, match=r"more than 1e\+09 starts"):
        samplers.sample_disks("direct", **CONFIGURED, samples=10, realizations=2, bins=4, seed=0)


@pytest.mark.parametrize(
    ("duration", "interval", "count"),
    [(1.25, 0.5, 2), (10.5, 1.0, 10), (20.0, 0.5, 40), (2.0, 0.3, 7), (0.7, 0.5, 1)],
)
def test_snapshots_integrate_to_the_disks(duration, interval, count):
    """The snapshots at (j + 1/2) Δt < T: the stroboscopic density integrates to N, where
    T/Δt − 1/2 a whole number counted one snapshot too many (1.333 for 2 disks)."""
    from kinetic import event_disks

    assert snapshot_count(duration, interval) == count
    data = event_disks.simulate_box(
        n_disks=2,
        sigma=0.1,
        duration=duration,
        snapshot_interval=interval,
        bins=8,
        realizations=2,
        seed=4,
    )
    width = float(data["bin_edges"][1] - data["bin_edges"][0])
    totals = data["density_snapshots"].sum("y").values * width
    np.testing.assert_allclose(totals, 2.0, rtol=1e-12)


@pytest.mark.parametrize(
    ("interval", "message"),
    [
        (1e-300, "snapshots of a realization"),  # the clock never advanced: an endless loop
        (1e-12, "snapshots of a realization"),  # 2 × 10¹² snapshots
        (3.0, "exceeds the duration"),
    ],
)
def test_the_engine_refuses_snapshot_intervals_before_any_run(interval, message, monkeypatch):
    from kinetic import event_disks

    def no_run(*args, **kwargs):
        raise AssertionError("a run started")

    monkeypatch.setattr(event_disks, "initial_state", no_run)
    with pytest.raises(ValueError, match=message):
        event_disks.simulate_box(
            n_disks=4,
            sigma=0.1,
            duration=2.0,
            snapshot_interval=interval,
            bins=5,
            realizations=2,
            seed=0,
        )
