"""Cumulants from count histograms, and the conversion to mean-free-time units."""

import numpy as np
import pytest

from kinetic.analysis import collision_statistics
from kinetic.analysis.checks import tolerance_factor
from kinetic.analysis.statistics import count_cumulants


def test_histogram_cumulants_equal_direct_cumulants():
    counts = np.random.default_rng(3).poisson(7.0, size=(3, 5000))
    histogram = np.stack([np.bincount(row, minlength=40) for row in counts])
    from_histogram = collision_statistics.histogram_cumulants(histogram)
    direct = count_cumulants(counts, axis=-1)
    np.testing.assert_allclose(from_histogram, direct, rtol=1e-12)


def test_poisson_counts_have_unit_scaled_cumulants():
    # synthetic dataset: Poisson counts with rate omega in windows of simulation length T
    import xarray as xr

    rng = np.random.default_rng(4)
    omega, window_time, n = 0.5, 20.0, 1000
    histograms = np.stack(
        [np.bincount(rng.poisson(omega * window_time, 20 * n), minlength=60) for _ in range(6)]
    )
    dataset = xr.Dataset(
        {
            "window_histogram": (
                ("realization", "checkpoint", "window", "count"),
                histograms[:, None, None, :],
            ),
            "collisions": (("realization", "checkpoint"), np.full((6, 1), 1e6)),
            "production_time": (("realization", "checkpoint"), np.full((6, 1), 2e6 / (n * omega))),
            "window_time": (("realization", "window"), np.full((6, 1), window_time)),
        },
        coords={"window": [10.0], "checkpoint": [100.0]},
        attrs={"n_particles": n},
    )
    table = collision_statistics.cumulant_table(dataset)
    mean, sem = table["scaled_cumulant"][0], table["scaled_cumulant_sem"][0]
    # each order within its own error (6 realizations: Student's band): one band from the
    # largest error, k3's, passed a mean-free-time conversion 5-7 % off in k1
    z = (np.asarray(mean) - 1.0) / np.asarray(sem)
    assert np.all(np.abs(z) <= tolerance_factor(4.0, 5)), z


def _stationary_erlang2_counts(windows, realizations, samples, seed):
    """Count histograms of a stationary renewal process with Erlang-2 intervals of mean 1:
    N_t = floor((U + M_t)/2), M_t ~ Poisson(2t), U a fair bit (the phase), for which
    Var N_t = t/2 + 1/8 - e^{-4t}/8 exactly, i.e. <N²>_c/t = 1/2 + 1/(8t)."""
    import xarray as xr

    rng = np.random.default_rng(seed)
    bins = int(2 * max(windows)) + 60
    histograms = np.zeros((realizations, 1, len(windows), bins))
    for r in range(realizations):
        for w, t in enumerate(windows):
            counts = (rng.integers(0, 2, samples) + rng.poisson(2 * t, samples)) // 2
            histograms[r, 0, w] = np.bincount(counts, minlength=bins)
    n = 1000  # collisions and time chosen so that omega = 1
    return xr.Dataset(
        {
            "window_histogram": (("realization", "checkpoint", "window", "count"), histograms),
            "collisions": (("realization", "checkpoint"), np.full((realizations, 1), 5e5)),
            "production_time": (("realization", "checkpoint"), np.full((realizations, 1), 1e3)),
            "window_time": (
                ("realization", "window"),
                np.tile(np.asarray(windows, float), (realizations, 1)),
            ),
        },
        coords={"window": list(windows), "checkpoint": [1e3]},
        attrs={"n_particles": n},
    )


def test_one_over_t_extrapolation_recovers_the_long_time_variance():
    # arrange: k2(t) = 1/2 + 1/(8t), so k2(10) = 0.5125 and k2(∞) = 1/2
    windows = (10.0, 20.0, 50.0)
    dataset = _stationary_erlang2_counts(windows, realizations=8, samples=100_000, seed=5)
    # act
    limit = collision_statistics.extrapolated_cumulants(dataset, windows)
    finite = collision_statistics.cumulant_table(dataset)
    # assert: the limit within 4 standard errors, the slope 1/8 likewise, and the finite-t
    # value at t = 10 distinguishably above the limit
    assert limit["value"][1] == pytest.approx(0.5, abs=4 * limit["sem"][1])
    assert limit["slope"][1] == pytest.approx(0.125, abs=4 * limit["slope_sem"][1])
    k2_10, sem_10 = finite["scaled_cumulant"][0, 1], finite["scaled_cumulant_sem"][0, 1]
    assert k2_10 == pytest.approx(0.5125, abs=4 * sem_10)
    assert k2_10 - 0.5 > 5 * np.hypot(sem_10, limit["sem"][1])
