"""kinetic.theory.montanero2007: limits, hand-computed values, Laguerre machinery."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy import integrate

from kinetic.theory import montanero2007 as theory

ALPHAS = np.array([0.1, 0.3, 0.5, 0.7, 0.9, 1.0])


# ------------------------------------------------------------------ elastic limits


@pytest.mark.parametrize("d", [2, 3])
def test_elastic_limits(d):
    assert theory.hcs_a2(1.0, d) == 0.0
    assert theory.reduced_cooling_rate(1.0, d) == 0.0
    assert theory.reduced_nu_kappa(1.0, d) == pytest.approx((d - 1) / d, rel=1e-15)
    for approximation in ("standard", "modified"):
        assert theory.kappa_ratio(1.0, d, approximation) == pytest.approx(1.0, rel=1e-14)
        assert theory.kappa_prime_ratio(1.0, d, approximation) == pytest.approx(1.0, rel=1e-14)


def test_a2_vanishes_at_inverse_sqrt_two():
    assert theory.hcs_a2(1 / math.sqrt(2), 3) == pytest.approx(0.0, abs=1e-15)


# ------------------------------------------------------- values recomputed by hand


def test_a2_hand_values():
    # Eq. (2.16), d = 3, alpha = 0.5: 16*0.5*0.5 / (97 - 16.5 - 0.25)
    assert theory.hcs_a2(0.5, 3) == pytest.approx(4.0 / 80.25, rel=1e-14)
    # alpha = 0: 16 / 97; d = 2, alpha = 0.5: 4 / (73 - 20.5 - 0.25)
    assert theory.hcs_a2(0.0, 3) == pytest.approx(16.0 / 97.0, rel=1e-14)
    assert theory.hcs_a2(0.5, 2) == pytest.approx(4.0 / 52.25, rel=1e-14)


def test_first_sonine_kappa_prime_hand_value_alpha_03():
    # d = 3, alpha = 0.3 worked through Eqs. (2.14), (2.16), (2.42), (2.46) by hand
    a2 = 16 * 0.7 * (1 - 2 * 0.09) / (97 - 0.3 * 33 - 2 * 0.7 * 0.09)
    zeta = 5 / 12 * (1 - 0.09) * (1 + 3 * a2 / 16)
    nu = 1.3 / 3 * (1 + 33 * 0.7 / 16 + (19 - 0.9) * a2 / 512)
    expected = 2 / 3 * (1 + 1.5 * a2) / (nu - 1.5 * zeta)
    assert theory.kappa_prime_ratio(0.3) == pytest.approx(expected, rel=1e-14)
    assert expected == pytest.approx(1.6068, abs=2e-4)
    nu_modified = 1.3 / 3 * (1 + 33 * 0.7 / 16 + (947 - 3 * 193 * 0.3) * a2 / 256)
    expected_modified = 2 / 3 * (1 + 1.5 * a2) / (nu_modified - 1.5 * zeta)
    assert theory.kappa_prime_ratio(0.3, approximation="modified") == pytest.approx(
        expected_modified, rel=1e-14
    )
    kappa = 2 / 3 * (1 + 2 * a2) / (nu - 2 * zeta)
    assert theory.kappa_ratio(0.3) == pytest.approx(kappa, rel=1e-14)


def test_modified_sonine_lowers_kappa_prime_at_strong_dissipation():
    # a2 > 0 for alpha < 1/sqrt(2): the larger nu of Ref. [28] lowers kappa'
    alpha = np.array([0.3, 0.5, 0.6])
    assert np.all(
        theory.kappa_prime_ratio(alpha, approximation="modified") < theory.kappa_prime_ratio(alpha)
    )


def test_units_meet_in_nu0_tau():
    assert theory.nu0_tau(3) == pytest.approx(8 / (5 * math.sqrt(math.pi)), rel=1e-14)
    # independent of density, temperature, diameter and mass
    density, temperature, diameter, mass = 0.37, 2.5, 1.3, 0.7
    product = theory.effective_collision_frequency(
        density, temperature, diameter, mass
    ) * theory.mean_free_time(density, temperature, diameter, mass)
    assert product == pytest.approx(theory.nu0_tau(3), rel=1e-14)
    assert theory.mean_free_path(1.0, 1.0, 3) == pytest.approx(1 / (math.sqrt(2) * math.pi))
    assert theory.mean_free_path(1.0, 1.0, 2) == pytest.approx(1 / (2 * math.sqrt(2)))
    # Eq. (2.15) in d = 3: 16 sqrt(pi) / 5 n sigma^2 sqrt(T/m)
    assert theory.effective_collision_frequency(1.0) == pytest.approx(16 * math.sqrt(math.pi) / 5)
    # Eq. (2.47): kappa0 = 15/4 n T / (m nu0)
    assert theory.elastic_conductivity(2.0, 3.0) == pytest.approx(
        15 / 4 * 6 / theory.effective_collision_frequency(2.0, 3.0)
    )


def test_heat_flux_and_b1_routes_to_kappa_prime_agree():
    # <c^2 c_x> = -(d+2)/4 b'_1 eps* (Eq. 3.10, k = 1) in any d
    for d in (2, 3):
        b1, eps = 1.7, 0.025
        c2cx = -(d + 2) / 4 * b1 * eps
        assert theory.kappa_prime_ratio_from_heat_flux(c2cx, eps, d) == pytest.approx(
            theory.kappa_prime_ratio_from_b1(b1, d), rel=1e-14
        )
    assert theory.kappa_prime_ratio_from_b1(1.0) == pytest.approx(16 / (15 * math.sqrt(math.pi)))
    ratio = theory.kappa_prime_ratio_from_b1(1.234)
    assert theory.sonine_b1_from_kappa_prime_ratio(ratio) == pytest.approx(1.234)


def test_invalid_arguments_are_named():
    with pytest.raises(ValueError, match="alpha"):
        theory.hcs_a2(1.2)
    with pytest.raises(ValueError, match="dimension"):
        theory.hcs_a2(0.5, d=1)
    with pytest.raises(ValueError, match="approximation"):
        theory.kappa_prime_ratio(0.5, approximation="second")
    with pytest.raises(ValueError, match="route"):
        theory.b_coefficients([1.0], 0.1, route="half")


def test_vectorised_over_alpha():
    values = theory.kappa_prime_ratio(ALPHAS)
    assert values.shape == ALPHAS.shape
    assert np.all(np.isfinite(values)) and np.all(values > 0)


# --------------------------------------------------------------- Laguerre machinery


@pytest.mark.parametrize("p", [0.0, 0.5, 1.0, 1.5])
def test_laguerre_orthogonality_eq_2_12(p):
    for k, ell in itertools.product(range(4), repeat=2):
        value = integrate.quad(
            lambda x, k=k, ell=ell: (
                x**p * np.exp(-x) * theory.laguerre(k, p, x) * theory.laguerre(ell, p, x)
            ),
            0,
            np.inf,
        )[0]
        expected = math.gamma(k + 1 + p) / math.factorial(k) if k == ell else 0.0
        assert value == pytest.approx(expected, abs=1e-9)


def test_prefactors():
    # k = 1: 2 Gamma(5/2)/Gamma(7/2) = 4/5 and 2 Gamma(3/2)/Gamma(5/2) = 4/3 (d = 3)
    assert theory.full_route_prefactor(1, 3) == pytest.approx(0.8)
    assert theory.marginal_route_prefactor(1) == pytest.approx(4 / 3)
    assert theory.full_route_prefactor(2, 2) == pytest.approx(2 * 1 * 2 / math.gamma(4))


B_TRUE = np.array([1.7, -0.35, 0.12])


def _gauss_hermite_grid(d, n_nodes=24):
    """Gauss–Hermite product rule for int dc pi^(-d/2) exp(-c^2) F(c): nodes (m, d), weights."""
    nodes, weights = np.polynomial.hermite.hermgauss(n_nodes)
    grid = np.array(list(itertools.product(nodes, repeat=d)))
    w = np.prod(np.array(list(itertools.product(weights, repeat=d))), axis=1) / np.pi ** (d / 2)
    return grid, w


def _phi_full(c, d):
    """Phi(c^2) = sum_k b_k L_k^(d/2)(c^2) (Eq. A.2)."""
    c2 = np.sum(c**2, axis=1)
    return sum(b * theory.laguerre(k, d / 2, c2) for k, b in enumerate(B_TRUE, start=1))


@pytest.mark.parametrize("d", [2, 3])
def test_two_routes_recover_known_coefficients_by_quadrature(d):
    # f = f_M (1 + eps c_x Phi(c^2)) with known b'_k: Eq. (3.10) and Eq. (3.12) give them back
    eps = 0.025
    c, w = _gauss_hermite_grid(d)
    weight = w * (1.0 + eps * c[:, 0] * _phi_full(c, d))
    full = theory.sonine_weights_full(c) @ weight
    marginal = theory.sonine_weights_marginal(c[:, 0]) @ weight
    assert np.sum(weight) == pytest.approx(1.0, rel=1e-13)
    np.testing.assert_allclose(theory.b_coefficients(full, eps, "full", d), B_TRUE, atol=1e-11)
    np.testing.assert_allclose(
        theory.b_coefficients(marginal, eps, "marginal", d), B_TRUE, atol=1e-11
    )


@pytest.mark.parametrize("d", [2, 3])
def test_marginal_of_full_expansion_is_eq_a10(d):
    # phi(c_x^2) = pi^(-(d-1)/2) int dc_perp exp(-c_perp^2) Phi(c^2) = sum_k b_k L_k^(1/2)(c_x^2)
    perp, w = _gauss_hermite_grid(d - 1)
    for cx in (0.0, 0.4, 1.3, 2.7):
        c = np.column_stack([np.full(len(w), cx), perp])
        assert w @ _phi_full(c, d) == pytest.approx(theory.phi_sonine(cx**2, B_TRUE), rel=1e-11)


def test_two_routes_agree_on_sampled_distribution():
    # importance-weighted Gaussian samples of the same f: the array helpers give both routes
    rng = np.random.default_rng(20070101)
    eps, n = 0.2, 400_000
    c = rng.normal(scale=np.sqrt(0.5), size=(n, 3))  # pi^(-3/2) exp(-c^2)
    weight = 1.0 + eps * c[:, 0] * _phi_full(c, 3)
    estimates = {}
    for route, samples in (
        ("full", theory.sonine_weights_full(c) * weight),
        ("marginal", theory.sonine_weights_marginal(c[:, 0]) * weight),
    ):
        mean = samples.mean(axis=1)
        sem = samples.std(axis=1, ddof=1) / np.sqrt(n)
        estimates[route] = (
            theory.b_coefficients(mean, eps, route),
            theory.b_coefficients(sem, eps, route),
        )
    for route, (b, b_err) in estimates.items():
        assert np.all(np.abs(b - B_TRUE) < 5 * b_err), route


def test_beta1_tends_to_b1_and_grid_matches_quadrature():
    b = B_TRUE
    assert theory.beta1_sonine(60.0, b) == pytest.approx(b[0], rel=1e-10)
    u = np.linspace(0.0, np.sqrt(40.0), 20001)
    grid = u**2
    on_grid = theory.beta1(grid, theory.phi_sonine(grid, b))
    check = np.array([1.0, 3.0, 6.0, 12.0])
    np.testing.assert_allclose(
        np.interp(check, grid, on_grid), theory.beta1_sonine(check, b), atol=1e-7
    )
    assert on_grid[-1] == pytest.approx(b[0], abs=1e-7)


def test_beta1_of_first_sonine_by_incomplete_gamma_functions():
    # phi = phi_1 = b (3/2 - u^2): int_0^a u^2 (3/2 - u^2)^2 exp(-u^2) du in closed form,
    # with int_0^a u^(2n) exp(-u^2) du = gamma_lower(n + 1/2, a^2) / 2
    from scipy.special import gamma, gammainc

    def lower(s, x):
        return gammainc(s, x) * gamma(s)

    x = np.array([0.5, 2.0, 6.0, 10.0])
    closed = (9 / 4 * lower(1.5, x) - 3 * lower(2.5, x) + lower(3.5, x)) / 2
    expected = 8 / (3 * np.sqrt(np.pi)) * closed
    np.testing.assert_allclose(theory.beta1_sonine(x, [1.0]), expected, rtol=1e-10)
    # first Sonine: particles with c_x^2 <= 6 carry 84 % of b'_1
    assert expected[2] == pytest.approx(0.8419, abs=1e-4)
