"""kinetic.analysis.statistics: standard errors and cumulants."""

import numpy as np
import pytest

from kinetic.analysis.statistics import (
    block_sem,
    count_cumulants,
    cpu_for_error,
    error_against_cpu,
    line_error,
    mean_and_sem,
    ratio_and_sem,
    weighted_line,
)


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


def test_error_against_cpu_falls_as_one_over_root_cpu_and_predicts_the_cost():
    """Independent unit-variance samples costing 2 CPU-s each: the standard error of the
    first n falls as 1/√n (within the spread of a standard error from n samples), and the
    CPU time predicted for an error of 0.01 from the first 100 samples is 2 σ²/0.01², the
    cost of the 10^4 samples that error takes."""
    samples = np.random.default_rng(5).normal(size=4000)
    parts = [10, 100, 1000, 4000]
    curve = error_against_cpu(
        parts, lambda n: mean_and_sem(samples[:n]) if n >= 2 else None, lambda n: 2.0 * n
    )
    np.testing.assert_array_equal(curve.part, parts)
    np.testing.assert_array_equal(curve.cpu_seconds, 2.0 * np.array(parts))
    for n, error in zip(parts, curve.error, strict=True):
        assert abs(error * np.sqrt(n) - 1.0) < 4.0 / np.sqrt(2.0 * (n - 1))
    needed = cpu_for_error(curve.cpu_seconds[1], curve.error[1], 0.01)
    assert needed == pytest.approx(2.0 * 1e4, rel=4.0 / np.sqrt(2.0 * 99))


def test_error_against_cpu_stops_where_a_part_has_no_error_bar():
    curve = error_against_cpu([5, 1, 3], lambda n: (n, 1.0) if n > 1 else None, float)
    np.testing.assert_array_equal(curve.part, [5])


def test_a_bias_as_large_as_the_target_cannot_be_averaged_away():
    assert cpu_for_error(10.0, 0.1, 0.05, bias=0.05) == np.inf
    assert cpu_for_error(10.0, 0.1, 0.05, bias=0.03) == pytest.approx(
        10.0 * 0.01 / (0.05**2 - 0.03**2)
    )


def test_chi2_per_dof_counts_only_entries_with_an_error_and_an_expectation():
    from kinetic.analysis.statistics import chi2_per_dof

    values = np.array([1.0, 2.0, 3.0, 4.0])
    errors = np.array([0.5, 0.0, 1.0, 2.0])
    expected = np.array([0.0, 2.0, np.nan, 0.0])
    chi2, dof = chi2_per_dof(values, errors, expected)
    assert dof == 2 and chi2 == pytest.approx((2.0**2 + 2.0**2) / 2)
    assert chi2_per_dof(values, np.zeros(4), 0.0) == (pytest.approx(float("nan"), nan_ok=True), 0)
    # Gaussian noise around the truth gives chi2/dof near 1
    rng = np.random.default_rng(1)
    noise = rng.normal(size=100_000)
    assert chi2_per_dof(noise, np.ones_like(noise), 0.0)[0] == pytest.approx(1.0, abs=0.02)


def test_ratio_and_sem_is_the_spread_of_the_pooled_ratio():
    """The delta-method error of Σa/Σb over 8 realizations of binomial counts with
    unequal totals is the spread of that ratio over 4000 repetitions (rms 3.7 % low: the
    residuals about the estimated ratio, O(1/n) at 8 samples; 4000 repetitions resolve
    1 %), within 10 %; a constant ratio has 0."""
    rng = np.random.default_rng(12)
    totals = rng.integers(500, 5000, size=(4000, 8))
    hits = rng.binomial(totals, 0.03)
    pooled = hits.sum(axis=1) / totals.sum(axis=1)
    errors = np.array([ratio_and_sem(a, b)[1] for a, b in zip(hits, totals, strict=True)])
    assert np.sqrt(np.mean(errors**2)) == pytest.approx(pooled.std(ddof=1), rel=0.1)
    assert ratio_and_sem(hits[0], totals[0])[0] == pytest.approx(pooled[0])
    assert ratio_and_sem([2.0, 4.0, 6.0], [1.0, 2.0, 3.0]) == (2.0, 0.0)
    assert np.isnan(ratio_and_sem([1.0], [3.0])[1])


def test_weighted_line_is_numpys_fit_and_its_band_the_scatter_of_refits():
    """The one weighted line of every 1/N extrapolation: its coefficients and covariance
    are numpy.polyfit's (an independent solver, 'unscaled' covariance: the errors as
    given), and the band of line_error at each x is the scatter of 4000 refits of
    synthetic data drawn within those errors (within 5 %), narrowest inside the data and
    σ_a at x = 0; adding σ_a and x σ_b in quadrature overstates it there by 29 %."""
    x = 1.0 / np.array([25.0, 100.0, 400.0, 1600.0])
    sigma = np.array([0.004, 0.002, 0.0012, 0.0008])
    truth = -0.576 - 0.1 * x
    fit = weighted_line(x, truth, sigma)
    coefficients, covariance = np.polyfit(x, truth, 1, w=1.0 / sigma, cov="unscaled")
    np.testing.assert_allclose([fit.slope, fit.intercept], coefficients, rtol=1e-10)
    np.testing.assert_allclose(
        [fit.slope_err**2, fit.intercept_err**2, fit.covariance],
        [covariance[0, 0], covariance[1, 1], covariance[0, 1]],
        rtol=1e-10,
    )
    assert fit.chi2 == pytest.approx(0.0, abs=1e-20) and fit.dof == 2

    grid = np.array([0.0, 0.005, 0.02, 0.04])
    rng = np.random.default_rng(3)
    lines = []
    for _ in range(4000):
        refit = weighted_line(x, truth + sigma * rng.standard_normal(x.size), sigma)
        lines.append(refit.intercept + refit.slope * grid)
    band = line_error(grid, fit.intercept_err, fit.slope_err, fit.covariance)
    np.testing.assert_allclose(band, np.std(lines, axis=0, ddof=1), rtol=0.05)
    assert band[0] == pytest.approx(fit.intercept_err, rel=1e-12)
    assert band[1] < band[0]  # inside the data the line is better known than at x = 0
    assert np.hypot(fit.intercept_err, grid[1] * fit.slope_err) > 1.2 * band[1]


def test_weighted_line_refuses_what_it_cannot_fit():
    with pytest.raises(ValueError, match="2 distinct x"):
        weighted_line([0.1, 0.1], [1.0, 1.1], [0.1, 0.1])
    with pytest.raises(ValueError, match="errors finite and > 0"):
        weighted_line([0.1, 0.2], [1.0, 1.1], [0.1, 0.0])
