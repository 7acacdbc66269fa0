"""visco2008 Eq. (50) / Table I: the cumulants <N^p>_c/(ωt) = (-1)^p μ^{(p)}(0) of the
number of collisions of a hard disk, from a fit of the cloning μ(λ) near λ = 0, agree
with the first-Sonine values 1, 1.137784, 1.107326 within the error of the fit, and with
the deterministic solution of Eq. (28) (``kinetic.theory.visco2008_exact``).

The fit uses both estimators of μ: the paper's compensation rate and the lower-noise
(e^{-λ} - 1)<r> (same expectation). With the first (~0.3 % on the second cumulant) the
Sonine values and the exact ones (1.1410, 1.0995) are indistinguishable. With the
second (~0.07 %) the Sonine 1.1378 and the exact second cumulant are 4 errors apart, so
one run can land anywhere between and beyond them (2.0 errors from Sonine and 1.8 from
exact with the test's seed, 6.8 and 2.7 with another): it is checked against the exact
solution only (the Sonine check failed with one seed in six).
"""

import math

import numpy as np
import pytest

from kinetic.analysis.checks import tolerance_factor
from kinetic.cloning import simulate
from kinetic.theory.visco2008 import sonine_cumulants
from kinetic.theory.visco2008_exact import reference_solution

SONINE = sonine_cumulants(
    2
)  # Eq. (50), checked against Table I in test_visco2008_table1_theory_rows
LAMBDAS = np.array([-0.6, -0.4, -0.2, 0.2, 0.4, 0.6])
REALIZATIONS = 24
BAND = tolerance_factor(4, REALIZATIONS - 1)
"""The two-sided probability of 4 Gaussian sigmas for an error estimated from 24
realizations (Student's t, 23 degrees of freedom): 5.0 errors. The tests ran 6
realizations 4 times as long before (the same simulated time), where that band is 12.3
errors and the 4 they asserted fails about 1 % of seeds a check."""
ORDER = 5  # μ = Σ_{p<=5} (-1)^p c_p λ^p / p!, truncation error < 1e-5 on |λ| <= 0.6


def fit_cumulants(lams, mu, err, order=ORDER):
    """Weighted least squares for c_1..c_order; returns (c, standard errors)."""
    design = np.stack([(-1) ** p * lams**p / math.factorial(p) for p in range(1, order + 1)], 1)
    weights = 1.0 / np.asarray(err) ** 2
    normal = design.T @ (design * weights[:, None])
    covariance = np.linalg.inv(normal)
    coefficients = covariance @ (design.T @ (weights * np.asarray(mu)))
    return coefficients, np.sqrt(np.diag(covariance))


def _scan():
    runs = [
        simulate(
            kernel="hard_spheres",
            dimension=2,
            lam=float(lam),
            population=2000,
            duration=125.0,
            transient=10.0,
            n_blocks=5,
            n_realizations=REALIZATIONS,
            seed=2008,
        )
        for lam in LAMBDAS
    ]
    return {
        name: np.array([float(ds[name]) for ds in runs])
        for name in ("mu", "mu_err", "mu_rate", "mu_rate_err")
    }


@pytest.fixture(scope="module")
def scan(once):
    return once("cloning_hard_disk_cumulants.scan", _scan)


@pytest.mark.slow
def test_cumulants_from_compensation_rate_match_sonine(scan):
    c, err = fit_cumulants(LAMBDAS, scan["mu"], scan["mu_err"])
    for p in range(3):
        assert abs(c[p] - SONINE[p]) < BAND * err[p], (p + 1, c[p], err[p])


@pytest.mark.slow
def test_cumulants_from_mean_rate_match_the_exact_solution(scan):
    c, err = fit_cumulants(LAMBDAS, scan["mu_rate"], scan["mu_rate_err"])
    # the deterministic solution, fitted the same way (noise-free)
    exact_mu = reference_solution(LAMBDAS, 2, n_nodes=300)[0]
    exact, _ = fit_cumulants(LAMBDAS, exact_mu, np.ones(LAMBDAS.size))
    for p in range(3):
        assert abs(c[p] - exact[p]) < BAND * err[p], (p + 1, c[p], exact[p], err[p])
    assert abs(c[0] - SONINE[0]) < BAND * err[0]  # the mean rate, ω = 1, is exact in both
    # the mean-rate estimator is the sharper one
    assert err[1] < fit_cumulants(LAMBDAS, scan["mu"], scan["mu_err"])[1][1]
