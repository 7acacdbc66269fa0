"""The eps* -> 0 extrapolation of montanero2007's even estimates and the share of b'_1
below c_x^2 = 6 (Fig 7): exact limits and agreement with the histogram estimator."""

import numpy as np
import pytest

from kinetic.analysis import montanero2007 as analysis
from kinetic.studies import montanero2007 as study
from kinetic.theory import montanero2007 as theory


def _row(alpha, field, values, errors):
    row = {"alpha": alpha, "reduced_field": field}
    for key in analysis.FIELD_EVEN_KEYS:
        row[key], row[f"{key}_err"] = values[key], errors[key]
    return row


def test_extrapolation_removes_an_exact_quadratic_bias():
    x0 = {"kappa_ratio": 0.83, "b1_full": 0.21, "b2_full": -0.04, "b3_full": 0.013}
    c = {"kappa_ratio": -7.0, "b1_full": 3.0, "b2_full": 11.0, "b3_full": -25.0}
    errors = dict.fromkeys(x0, 1e-3)

    def at(field):
        return _row(0.5, field, {k: x0[k] + c[k] * field**2 for k in x0}, errors)

    out = analysis.field_extrapolation(at(0.025), at(0.05))
    for key in x0:
        assert out[f"{key}_extrapolated"] == pytest.approx(x0[key], abs=1e-12)
        assert out[f"{key}_bias"] == pytest.approx(c[key] * 0.025**2, abs=1e-12)


def test_extrapolation_errors_match_the_scatter_of_noisy_pairs():
    """The propagated standard error equals the scatter of the estimate over many
    independent noisy pairs (2000 pairs: the scatter is known to 1.6 %, checked at 5 %)."""
    rng = np.random.default_rng(11)
    s1, s2 = 0.004, 0.007
    keys = ("kappa_ratio",)
    estimates, biases = [], []
    for _ in range(2000):
        low = {
            "alpha": 1.0,
            "reduced_field": 0.025,
            "kappa_ratio": 1.0 + rng.normal(0, s1),
            "kappa_ratio_err": s1,
        }
        high = {
            "alpha": 1.0,
            "reduced_field": 0.05,
            "kappa_ratio": 1.0 + rng.normal(0, s2),
            "kappa_ratio_err": s2,
        }
        out = analysis.field_extrapolation(low, high, keys=keys)
        estimates.append(out["kappa_ratio_extrapolated"])
        biases.append(out["kappa_ratio_bias"])
    assert np.std(estimates) == pytest.approx(out["kappa_ratio_extrapolated_err"], rel=0.05)
    assert np.std(biases) == pytest.approx(out["kappa_ratio_bias_err"], rel=0.05)


def test_extrapolation_refuses_mismatched_pairs():
    row = _row(
        0.5,
        0.025,
        dict.fromkeys(analysis.FIELD_EVEN_KEYS, 1.0),
        dict.fromkeys(analysis.FIELD_EVEN_KEYS, 0.1),
    )
    with pytest.raises(ValueError, match="restitution"):
        analysis.field_extrapolation(row, {**row, "alpha": 0.3, "reduced_field": 0.05})
    with pytest.raises(ValueError, match="fields"):
        analysis.field_extrapolation(row, row)


@pytest.mark.parametrize("b", [(0.2,), (0.2, 0.03, -0.01)])
def test_share_below_cx2_matches_the_histogram_estimator(b):
    """beta_1(6)/b'_1 from the Sonine series (quadrature) against the workflow's estimator
    on the exact expected histogram of the marginal (Eq. 4.3): equal to the estimator's
    O(bin width^2) quadrature error; the first Sonine value 0.8419 is alpha-independent."""
    edges = np.linspace(-5.0, 5.0, 201)
    centres = 0.5 * (edges[1:] + edges[:-1])
    eps, n = 0.025, 1e9
    phi = sum(bk * theory.laguerre(k + 1, 0.5, centres**2) for k, bk in enumerate(b))
    density = np.exp(-(centres**2)) / np.sqrt(np.pi) * (1 + eps * centres * phi)
    counts = np.tile(n * density * np.diff(edges), (2, 1))
    cx2, beta, _ = analysis.beta1_estimate(counts, np.full(2, n), edges, eps)
    assert beta[-1] == pytest.approx(b[0], rel=1e-4)  # beta_1 -> b'_1
    share = np.interp(6.0, cx2, beta) / beta[-1]
    assert share == pytest.approx(theory.beta1_share(6.0, b), abs=5e-4)
    assert theory.beta1_share(6.0) == pytest.approx(0.84189, abs=1e-5)


def test_every_scan_run_has_a_larger_field_partner():
    section = {
        "alphas": [0.3, 0.5, 1.0],
        "field_check": {"restitution": 0.3, "reduced_field": 0.05},
        "field_bias": {"reduced_field": 0.05},
    }
    assert study.field_partner(section, 0.3) == "field_alpha030"  # the Fig 1 partner
    assert study.field_partner(section, 0.5) == "bias_field050_alpha050"
    section["field_bias"]["reduced_field"] = 0.1
    assert study.field_partner(section, 0.3) == "bias_field100_alpha030"


def test_b3_over_b2_error_holds_their_covariance():
    """b'_2 and b'_3 of one run come from the same particles (per realization they
    correlate at -0.8 in the default build): the extrapolated ratio's error with their
    covariance is the scatter of 3000 synthetic experiments of 16 realizations a run
    (within 10 %), and the error without it is well above that scatter."""
    rng = np.random.default_rng(12)
    correlation, realizations = -0.8, 16
    spread = np.array([0.02, 0.03])
    covariance = np.outer(spread, spread) * np.array([[1, correlation], [correlation, 1]])

    def run(field, b2, b3):
        draws = rng.multivariate_normal([b2, b3], covariance, size=realizations)
        means, sems = draws.mean(axis=0), draws.std(axis=0, ddof=1) / np.sqrt(realizations)
        return {
            "alpha": 0.3,
            "reduced_field": field,
            "b2_full": means[0],
            "b2_full_err": sems[0],
            "b3_full": means[1],
            "b3_full_err": sems[1],
            "b2_b3_full_cov": np.cov(draws[:, 0], draws[:, 1])[0, 1] / realizations,
        }

    ratios, errors, naive = [], [], []
    for _ in range(3000):
        row = analysis.field_extrapolation(
            run(0.025, 0.10, -0.14), run(0.05, 0.11, -0.15), keys=("b2_full", "b3_full")
        )
        ratio, error = analysis.extrapolated_b3_over_b2(row)
        ratios.append(ratio)
        errors.append(error)
        naive.append(
            abs(ratio)
            * np.hypot(
                row["b3_full_extrapolated_err"] / row["b3_full_extrapolated"],
                row["b2_full_extrapolated_err"] / row["b2_full_extrapolated"],
            )
        )
    scatter = np.std(ratios, ddof=1)
    assert np.median(errors) == pytest.approx(scatter, rel=0.1)
    assert np.median(naive) > 1.3 * scatter
