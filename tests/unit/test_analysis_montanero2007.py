"""kinetic.analysis.montanero2007: observers against numpy, estimators on a known distribution."""

from __future__ import annotations

import numpy as np
import pytest

from kinetic.analysis import montanero2007 as analysis
from kinetic.theory import montanero2007 as theory

B_TRUE = np.array([1.7, -0.35, 0.12])


@pytest.mark.parametrize("d", [2, 3])
def test_snapshot_moments_match_numpy_reference(d):
    rng = np.random.default_rng(7)
    velocities = rng.normal(size=(1000, d)) * 1.3 + 0.05
    inv_v0 = 1 / np.sqrt(2.0)
    out = np.empty(len(analysis.MOMENTS))
    analysis.snapshot_moments(velocities, inv_v0, out)
    c = velocities * inv_v0
    c2 = np.sum(c**2, axis=1)
    expected = np.concatenate(
        [
            [c[:, 0].mean(), c2.mean(), (c[:, 0] ** 2).mean(), (c2**2).mean()],
            [(c2 * c[:, 0]).mean()],
            theory.sonine_weights_full(c).mean(axis=1),
            theory.sonine_weights_marginal(c[:, 0]).mean(axis=1),
        ]
    )
    np.testing.assert_allclose(out, expected, rtol=1e-12, atol=1e-14)


def test_histogram_observer_matches_numpy():
    rng = np.random.default_rng(8)
    velocities = rng.normal(size=(5000, 3))
    inv_v0 = 0.5
    c_max, n_bins = 2.0, 40
    counts, weights, outside = np.zeros(n_bins), np.zeros(n_bins), np.zeros(2)
    analysis.accumulate_cx_histogram(velocities, inv_v0, c_max, counts, weights, outside)
    cx = velocities[:, 0] * inv_v0
    edges = analysis.histogram_edges(c_max, n_bins)
    inside = np.abs(cx) < c_max
    np.testing.assert_array_equal(counts, np.histogram(cx, edges)[0])
    w = cx * (1.5 - cx**2)
    np.testing.assert_allclose(weights, np.histogram(cx, edges, weights=w)[0], atol=1e-12)
    assert outside[0] == np.count_nonzero(~inside)
    assert outside[1] == pytest.approx(w[~inside].sum())


def _phi_full(c):
    c2 = np.sum(c**2, axis=1)
    return sum(b * theory.laguerre(k, 1.5, c2) for k, b in enumerate(B_TRUE, start=1))


@pytest.fixture(scope="module")
def weighted_realizations():
    """Eight 'realizations' of f = f_M (1 + eps c_x Phi(c^2)) as weighted Gaussian samples."""
    rng = np.random.default_rng(2007)
    eps, n, edges = 0.05, 200_000, analysis.histogram_edges(4.0, 160)
    data = {"eps": eps, "edges": edges, "moments": [], "counts": [], "weights": []}
    data.update(outside=[], n_samples=[])
    for _ in range(8):
        c = rng.normal(scale=np.sqrt(0.5), size=(n, 3))
        w = 1.0 + eps * c[:, 0] * _phi_full(c)
        cx = c[:, 0]
        data["moments"].append(
            np.concatenate(
                [
                    theory.sonine_weights_full(c) @ w / n,
                    theory.sonine_weights_marginal(cx) @ w / n,
                    [np.sum(w * cx * np.sum(c**2, axis=1)) / n],
                ]
            )
        )
        inside = np.abs(cx) < edges[-1]
        data["counts"].append(np.histogram(cx, edges, weights=w)[0])
        data["weights"].append(np.histogram(cx, edges, weights=w * cx * (1.5 - cx**2))[0])
        data["outside"].append(np.sum((w * cx * (1.5 - cx**2))[~inside]))
        data["n_samples"].append(n)
    return {key: np.asarray(value) for key, value in data.items()}


def test_b_estimates_recover_known_coefficients(weighted_realizations):
    data = weighted_realizations
    moments = data["moments"]
    for route, block in (("full", moments[:, 0:3]), ("marginal", moments[:, 3:6])):
        mean, sem = analysis.b_estimates(block, data["eps"], route)
        assert np.all(np.abs(mean - B_TRUE) < 5 * sem), (route, mean, sem)
    ratio, ratio_sem = analysis.kappa_prime_estimate(moments[:, 6], data["eps"])
    expected = theory.kappa_prime_ratio_from_b1(B_TRUE[0])
    assert abs(ratio - expected) < 5 * ratio_sem


def test_phi_and_odd_marginal_recover_eq_a10(weighted_realizations):
    data = weighted_realizations
    cx2, phi, phi_sem = analysis.phi_estimate(
        data["counts"], data["n_samples"], data["edges"], data["eps"]
    )
    near = cx2 < 6.0
    exact = theory.phi_sonine(cx2[near], B_TRUE)
    assert np.all(np.abs(phi[near] - exact) < 5 * phi_sem[near] + 2e-3 * np.abs(exact))
    centres, g, _, odd, odd_sem = analysis.odd_marginal_estimate(
        data["counts"], data["n_samples"], data["edges"]
    )
    # the even part is the Gaussian marginal pi^(-1/2) exp(-c_x^2), normalised
    assert np.sum(g * np.diff(data["edges"])) == pytest.approx(1.0, abs=1e-3)
    positive = centres[centres > 0]
    odd_exact = (
        data["eps"] * positive * np.exp(-(positive**2)) * theory.phi_sonine(positive**2, B_TRUE)
    ) / np.sqrt(np.pi)
    near = positive < 2.5
    deviation = np.abs(odd - odd_exact)[near]
    assert np.all(deviation < 5 * odd_sem[near] + 2e-3 * np.abs(odd_exact[near]))


def test_beta1_recovers_eq_4_6(weighted_realizations):
    data = weighted_realizations
    args = (data["weights"], data["outside"], data["n_samples"], data["edges"], data["eps"])
    cx2, beta, beta_sem, b1, b1_sem = analysis.beta1_estimate(*args)
    assert abs(b1 - B_TRUE[0]) < 5 * b1_sem
    exact = theory.beta1_sonine(cx2, B_TRUE)
    assert np.all(np.abs(beta - exact) < 5 * beta_sem + 1e-9)
    _, ratio, ratio_sem = analysis.beta1_ratio_estimate(*args)
    assert ratio[0] == 0.0
    near = cx2 <= 9.0  # beyond, the rare-event tail of the weighted Gaussian samples
    assert np.all(np.abs(ratio - exact / B_TRUE[0])[near] < 5 * ratio_sem[near] + 1e-9)


def test_steady_average_and_errors():
    times = np.arange(10.0)
    series = np.tile(times, (3, 1))
    np.testing.assert_allclose(analysis.steady_average(series, times, 5.0), 7.0)
    with pytest.raises(ValueError, match="t_start"):
        analysis.steady_average(series, times, 50.0)
    with pytest.raises(ValueError, match="n_bins"):
        analysis.histogram_edges(4.0, 7)
