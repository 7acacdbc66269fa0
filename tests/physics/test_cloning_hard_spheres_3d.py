"""The cloning Monte Carlo in d = 3 (hard spheres): μ, T and a2 at λ = -0.5 and 1 agree
with the deterministic solution of visco2008 Eq. (28) for d = 3 (the document treats
d = 2 only; Eq. 50 gives the d = 3 Sonine cumulants 1.1344 and 1.1033)."""

import pytest

from kinetic.analysis.checks import tolerance_factor
from kinetic.cloning import simulate
from kinetic.theory.visco2008_exact import reference_solution

LAMBDAS = [-0.5, 1.0]
REALIZATIONS = 24
BAND = tolerance_factor(4, REALIZATIONS - 1)
"""The two-sided probability of 4 Gaussian sigmas for an error estimated from 24
realizations (Student's t, 23 degrees of freedom): 5.0 errors. The tests ran 6
realizations 4 times as long before (the same simulated time), where that band is 12.3
errors and the 4 they asserted fails about 1 % of seeds a check."""


@pytest.fixture(scope="module")
def measured():
    return {
        lam: simulate(
            kernel="hard_spheres",
            dimension=3,
            lam=lam,
            population=2000,
            duration=75.0,
            transient=20.0,
            n_blocks=5,
            n_realizations=REALIZATIONS,
            seed=303,
        )
        for lam in LAMBDAS
    }


@pytest.fixture(scope="module")
def exact():
    fine = reference_solution(LAMBDAS, 3, n_nodes=300)
    coarse = reference_solution(LAMBDAS, 3, n_nodes=200)
    names = ("mu", "temperature", "a2")
    return {
        lam: {
            name: (fine[k][i], 2 * abs(fine[k][i] - coarse[k][i])) for k, name in enumerate(names)
        }
        for i, lam in enumerate(LAMBDAS)
    }


@pytest.mark.parametrize("lam", LAMBDAS)
@pytest.mark.parametrize("name", ["mu", "temperature", "a2"])
def test_three_dimensional_eigenvalue_problem(measured, exact, lam, name):
    ds = measured[lam]
    reference, discretisation = exact[lam][name]
    assert abs(float(ds[name]) - reference) < BAND * float(ds[f"{name}_err"]) + discretisation


def test_three_dimensional_mean_rate_estimator(measured, exact):
    for lam in LAMBDAS:
        ds = measured[lam]
        reference, discretisation = exact[lam]["mu"]
        assert abs(float(ds.mu_rate) - reference) < BAND * float(ds.mu_rate_err) + discretisation
