"""kinetic.analysis.statistics: standard errors and cumulants."""

import numpy as np
import pytest

from kinetic.analysis.statistics import block_sem, count_cumulants, mean_and_sem


def test_mean_and_sem_of_known_samples():
    mean, sem = mean_and_sem([1.0, 2.0, 3.0, 4.0])
    assert mean == 2.5
    assert sem == pytest.approx(np.std([1, 2, 3, 4], ddof=1) / 2)


def test_one_sample_has_no_error_bar():
    with pytest.raises(ValueError, match="at least 2"):
        mean_and_sem([1.0])


def test_poisson_counts_have_equal_cumulants():
    rate = 7.0
    counts = np.random.default_rng(1).poisson(rate, size=(20, 20_000))
    cumulants = count_cumulants(counts, axis=1)  # (order, realization)
    mean, sem = mean_and_sem(cumulants, axis=1)
    assert np.all(np.abs(mean - rate) < 5 * sem)


def test_block_sem_covers_the_true_mean_of_a_correlated_series():
    rng = np.random.default_rng(2)
    series = np.empty(100_000)
    x = 0.0
    for i in range(series.size):  # AR(1) with correlation time 10
        x = 0.9 * x + rng.normal()
        series[i] = x
    mean, sem = block_sem(series, n_blocks=20)
    naive = series.std() / np.sqrt(series.size)
    assert abs(mean) < 5 * sem
    assert sem > 2 * naive  # correlations make the honest error larger
