"""The workflow's numpy check that a disk box can be sampled agrees with the engine."""

import numpy as np
import pytest

from kinetic.rng import stream_states
from kinetic.samplers import disk_configuration
from kinetic.studies.krauth2025 import _legal_configuration, check_disks


def test_the_configured_box_passes():
    check_disks({"n_disks": 4, "sigma": 0.15, "box": [1.0, 1.0]})


@pytest.mark.parametrize(
    ("sigma", "message"),
    [
        (0.26, "too dense"),  # four disks of radius > 1/4 do not fit in a unit square
        (0.245, "too dense"),  # they fit, but one draw in far more than 10^6 is legal
        (0.6, "cannot hold a disk"),
    ],
)
def test_boxes_that_cannot_be_sampled_are_refused(sigma, message):
    with pytest.raises(ValueError, match=message):
        check_disks({"n_disks": 4, "sigma": sigma, "box": [1.0, 1.0]})


def test_acceptance_of_two_disks_is_the_exact_one():
    """Two disks of radius σ in a box of side 1 with walls: the centres are uniform in a
    square of side a = 1 − 2σ, and they overlap with probability P(|x − y| < 2σ) for two
    uniform points of that square, π r² / a² − (8/3) r³ / a³ + r⁴ / (2 a⁴) with r = 2σ
    (r ≤ a). The chunked filter keeps each draw independently with 1 − P, so the number
    of survivors of single draws is binomial: compare within 4 standard deviations."""
    sigma, draws = 0.1, 4000
    a, r = 1 - 2 * sigma, 2 * sigma
    overlap = np.pi * r**2 / a**2 - 8 / 3 * r**3 / a**3 + r**4 / (2 * a**4)
    rng = np.random.default_rng(3)
    kept = sum(_legal_configuration(2, sigma, (1.0, 1.0), 1, rng) for _ in range(draws))
    p = 1 - overlap
    assert abs(kept - draws * p) < 4 * np.sqrt(draws * p * (1 - p))


@pytest.mark.parametrize("sigma", [0.15, 0.2])
def test_engine_samples_what_the_check_admits(sigma):
    check_disks({"n_disks": 4, "sigma": sigma, "box": [1.0, 1.0]})
    positions = disk_configuration(4, sigma, (1.0, 1.0), state=stream_states(1, 1)[0])
    gaps = np.linalg.norm(positions[:, None] - positions[None], axis=-1)[np.triu_indices(4, 1)]
    assert np.all(gaps > 2 * sigma)


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
