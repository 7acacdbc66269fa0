"""visco2008 Eqs. (23), (32), (40): Legendre transforms of cumulant generating functions."""

import numpy as np
import pytest

from kinetic.theory import visco2008

RATES = np.array([0.05, 0.3, 0.7, 1.0, 1.6, 2.5, 3.5])


@pytest.mark.parametrize("rate", [1.0, 1 / np.sqrt(2)])
def test_numerical_legendre_of_poisson_mu_is_eq_40(rate):
    numerical = visco2008.legendre_transform(lambda lam: visco2008.poisson_mu(lam, rate), RATES)
    np.testing.assert_allclose(numerical, visco2008.poisson_ldf(RATES, rate), atol=1e-8)


def test_poisson_ldf_at_zero_rate_is_minus_the_rate():
    exact = visco2008.legendre_transform(
        lambda lam: visco2008.poisson_mu(lam, 1.0), np.array([0.0]), mu_at_infinity=-1.0
    )
    assert exact[0] == -1.0


def test_gaussian_ldf_vanishes_at_the_mean_with_curvature_1_over_k2():
    assert visco2008.gaussian_ldf(np.array([1.0]))[0] == pytest.approx(0, abs=1e-10)
    h = 1e-3
    around = visco2008.gaussian_ldf(np.array([1 - h, 1 + h]))
    assert (around.sum() / h**2) == pytest.approx(-1 / 1.125, rel=1e-3)


def test_gaussian_ldf_at_zero_rate_is_the_minimum_of_mu():
    # the Gaussian closure approaches -1/√2 from below (Eq. 44), so its μ has a minimum
    # below -1/√2 and π(0) = min μ: a deficiency of the closure, not of the transform
    lam = np.linspace(0, 40, 400_001)
    minimum = visco2008.gaussian_mu(lam).min()
    assert minimum < -1 / np.sqrt(2) - 0.05
    values = visco2008.gaussian_ldf(np.array([0.0, 1e-12]))
    np.testing.assert_allclose(values, minimum, atol=1e-9)


def test_uncorrelated_ldf_eq_23_is_a_renewal_process_and_closer_to_gaussian_than_poisson():
    """Eq. (23) is the rate function of a renewal process with the free-flight time density:
    it vanishes at the mean rate and its curvature there is -<t>^3/var(t) (the count's
    variance per unit time is var(t)/<t>^3), here from the density's moments integrated
    directly, not through the Laplace transform Eq. (23) uses. Fig. 3's reading: the
    uncorrelated and Gaussian-closure rate functions lie closer to each other than either
    to Poisson(1), and both are wider than Poisson(1)."""
    from scipy import integrate

    def moment(k):
        return integrate.quad(
            lambda t: t**k * visco2008.free_flight_time_pdf(np.array([t]), 2)[0],
            0,
            np.inf,
            limit=400,
            epsabs=1e-13,
            epsrel=1e-12,
        )[0]

    mean, second = moment(1), moment(2)
    assert mean == pytest.approx(1.0, rel=1e-9)  # flights in mean free times
    h = 1e-3
    around = visco2008.uncorrelated_ldf(np.array([1 - h, 1, 1 + h]), 2)
    assert around[1] == pytest.approx(0, abs=1e-9)
    # the central difference is off by O(h^2) of the fourth derivative: about 1e-6
    curvature = (around[0] + around[2] - 2 * around[1]) / h**2
    assert curvature == pytest.approx(-(mean**3) / (second - mean**2), rel=1e-5)
    uncorrelated = visco2008.uncorrelated_ldf(RATES, 2)
    gaussian = visco2008.gaussian_ldf(RATES)
    poisson = visco2008.poisson_ldf(RATES, 1.0)
    away = RATES != 1
    gap = np.abs(uncorrelated - gaussian)[away]
    assert np.all(gap < np.abs(uncorrelated - poisson)[away])
    assert np.all(gap < np.abs(gaussian - poisson)[away])
    assert np.all(uncorrelated[away] > poisson[away])


def test_legendre_at_the_edges_of_its_range():
    edges = visco2008.gaussian_ldf(np.array([1e-9, 12.0]))
    assert np.all(np.isfinite(edges))
    assert visco2008.poisson_ldf(12.0, 1.0) < edges[1] < 0  # wider than Poisson(1)
    with pytest.raises(ValueError, match=">= 0"):
        visco2008.gaussian_ldf(np.array([-0.1]))


@pytest.mark.parametrize(("lam", "interval"), [(2.0, 0.5), (-1.0, 0.137)])
def test_poisson_cloning_estimator_bias_and_spread_match_a_direct_simulation(lam, interval):
    """The discrete-time cloning estimator of a Poisson count (Maxwell molecules), built
    directly: N_c independent Poisson(Δ) counts an interval, ln of the mean weight summed
    over the intervals. Its mean is off the exact e^{-λ} - 1 by the first-order bias, and
    its spread is the first-order one, within the fixed-seed run's errors (the next
    order, about v/N_c = 0.2 % of the bias, is far below them)."""
    population, duration, realizations = 200, 20.0, 2000
    intervals = round(duration / interval)
    duration = intervals * interval
    rng = np.random.default_rng(5)

    def estimates(count):  # μ of ``count`` realizations
        weights = np.exp(-lam * rng.poisson(interval, (count, intervals, population)))
        return np.log(weights.mean(axis=-1)).sum(axis=-1) / duration

    # 100 realizations at a time: 23 MB of counts, not 470
    mu = np.concatenate([estimates(100) for _ in range(realizations // 100)])
    bias, spread = visco2008.poisson_cloning_estimator(lam, population, interval, duration)
    measured_spread = mu.std(ddof=1)
    error = measured_spread / np.sqrt(realizations)
    assert abs(mu.mean() - np.expm1(-lam) - bias) < 4.5 * error
    assert 4.5 * error < abs(bias)  # the bias itself is resolved: the check can fail
    assert measured_spread == pytest.approx(spread, rel=4.5 / np.sqrt(2 * realizations))
