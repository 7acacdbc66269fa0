"""Cumulants from count histograms, and the conversion to mean-free-time units."""

import numpy as np
import pytest

from kinetic.analysis import collision_statistics
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
    assert mean == pytest.approx([1, 1, 1], abs=4 * sem.max() + 1e-3)
