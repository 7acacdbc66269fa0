"""visco2008 Eqs. (43), (47)-(49) and Appendix E: the moment closures of μ(λ)."""

import numpy as np
import pytest

from kinetic.theory import visco2008

LAMBDAS = np.array([-1.5, -0.7, 0.3, 0.9, 1.4])


@pytest.mark.parametrize("d", [2, 3])
def test_gaussian_closure_solved_in_any_d_is_eq_43(d):
    mu, temperature = visco2008.gaussian_solution(LAMBDAS, d)
    np.testing.assert_allclose(mu, visco2008.gaussian_mu(LAMBDAS), rtol=1e-9)
    np.testing.assert_allclose(temperature, visco2008.gaussian_temperature(LAMBDAS), rtol=1e-9)


def test_appendix_e_agrees_with_the_exact_moment_algebra():
    # two independent computations of ν_0, ν_2, ν_4 (Appendix E with E3's sign fixed,
    # and Gauss quadrature of the collisional moments)
    for lam, temperature, a2 in [(0.5, 0.8, 0.05), (-1.0, 1.3, -0.04), (2.0, 0.4, 0.6)]:
        exact = visco2008._collisional_moments(lam, temperature, a2, 2)
        printed = visco2008.appendix_e_moments(lam, temperature, a2)
        np.testing.assert_allclose(exact, printed, rtol=1e-11, atol=1e-13)


@pytest.mark.parametrize(
    ("lam", "mu", "temperature", "a2"),
    [(0.5, -0.378325, 0.853572, 0.046533), (1.0, -0.578512, 0.684897, 0.140143)],
)
def test_sonine_reference_points(lam, mu, temperature, a2):
    solution = visco2008.sonine_solution(np.array([lam]), 2)
    np.testing.assert_allclose([s[0] for s in solution], [mu, temperature, a2], atol=2e-6)


def test_sonine_branch_ends_at_its_fold_near_1_61():
    lam = np.linspace(1.5, 1.7, 21)
    mu, _, a2 = visco2008.sonine_solution(lam, 2)
    last = lam[np.isfinite(mu)].max()
    assert 1.58 <= last <= 1.64
    assert np.all(np.isnan(mu[lam > 1.64]))
    assert a2[np.isfinite(a2)].max() > 0.6  # the closure has left its small-a2 domain


def test_large_lambda_limit_eq_38_and_44():
    lam = np.array([20.0, 40.0])
    mu = visco2008.gaussian_mu(lam)
    np.testing.assert_allclose(mu, -1 / np.sqrt(2), atol=1e-4)  # μ(∞) = -ω/√2 (36), (38)
    # the Gaussian closure approaches it as -sqrt(e^{-λ})/2 (Eq. 44), not as e^{-λ} (38)
    np.testing.assert_allclose((mu + 1 / np.sqrt(2)) / -np.sqrt(np.exp(-lam)) * 2, 1, rtol=1e-3)
    assert visco2008.gaussian_temperature(40.0) < 1e-8


def test_closures_vanish_at_lambda_zero():
    mu, temperature, a2 = visco2008.sonine_solution(np.array([0.0]), 2)
    assert (mu[0], temperature[0], a2[0]) == (0.0, 1.0, 0.0)
    assert visco2008.gaussian_mu(0.0) == 0.0
