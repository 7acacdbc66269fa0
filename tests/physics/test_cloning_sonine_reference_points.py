"""visco2008 Figs. 5, 7, 8 at λ = 0.5 and 1: the cloning μ, T, a2 of hard disks against
the first-Sonine closure (reference points of the document), the Gaussian closure (Eq. 43) and
the deterministic solution of Eq. (28) (``kinetic.theory.visco2008_exact``).

The closures are approximations, so the test asserts only what theory guarantees:
the Monte Carlo agrees with the exact eigenvalue problem within its error bars, and the
Sonine closure (exact through the second cumulant) is closer to it than the Gaussian
one for every observable. Observed deviations from the Sonine points, Monte Carlo of
this test (N = 2000, seed 1961) / exact solution:
λ = 0.5: μ +0.0007 / +0.0005 (0.1%), T -0.0041 / -0.0038 (-0.4%), a2 +0.0076 / +0.0090;
λ = 1:   μ +0.0022 / +0.0019 (0.3%), T -0.0088 / -0.0093 (-1.4%), a2 +0.025 / +0.025.
The Sonine a2 is thus ~18% low already at λ = 0.5; T and μ are good to 1.5%.
"""

import math

import numpy as np
import pytest

from kinetic.analysis.checks import tolerance_factor
from kinetic.cloning import simulate
from kinetic.theory.visco2008_exact import reference_solution

# Appendix E of the document, with the sign of (E3) corrected, ω = 1
SONINE = {
    0.5: {"mu": -0.378325, "temperature": 0.853572, "a2": 0.046533},
    1.0: {"mu": -0.578512, "temperature": 0.684897, "a2": 0.140143},
}
POPULATION = 2000
REALIZATIONS = 24
BAND = tolerance_factor(4, REALIZATIONS - 1)
"""The two-sided probability of 4 Gaussian sigmas for an error estimated from 24
realizations (Student's t, 23 degrees of freedom): 5.0 errors. The tests ran 6
realizations 4 times as long before (the same simulated time), where that band is 12.3
errors and the 4 they asserted fails about 1 % of seeds a check."""


def gaussian_closure(lam):
    """Eq. (43) with ω = T0 = 1: (μ, T, a2 = 0)."""
    temperature = math.sqrt(2.0) / math.sqrt(1.0 + math.exp(lam))
    mu = -(1.0 - math.exp(-lam)) * math.sqrt(1.0 + temperature) / math.sqrt(2.0)
    return {"mu": mu, "temperature": temperature, "a2": 0.0}


def _measured():
    return {
        lam: simulate(
            kernel="hard_spheres",
            dimension=2,
            lam=lam,
            population=POPULATION,
            duration=100.0,
            transient=20.0,
            n_blocks=5,
            n_realizations=REALIZATIONS,
            seed=1961,
        )
        for lam in SONINE
    }


@pytest.fixture(scope="module")
def measured(once):
    return once("cloning_sonine_reference_points.measured", _measured)


def _exact():
    lams = list(SONINE)
    fine = reference_solution(lams, 2, n_nodes=300)
    coarse = reference_solution(lams, 2, n_nodes=200)
    names = ("mu", "temperature", "a2")
    return {
        lam: {
            name: (fine[k][i], 2 * abs(fine[k][i] - coarse[k][i])) for k, name in enumerate(names)
        }
        for i, lam in enumerate(lams)
    }


@pytest.fixture(scope="module")
def exact(once):
    return once("cloning_sonine_reference_points.exact", _exact)


@pytest.mark.parametrize("lam", list(SONINE))
@pytest.mark.parametrize("name", ["mu", "temperature", "a2"])
def test_monte_carlo_solves_the_eigenvalue_problem(measured, exact, lam, name):
    ds = measured[lam]
    value, error = float(ds[name]), float(ds[f"{name}_err"])
    reference, discretisation = exact[lam][name]
    # finite-population bias is ~ -0.1/N in μ at λ = 1 (test_cloning_population_size),
    # far below the error bar at N = 2000
    assert abs(value - reference) < BAND * error + discretisation


@pytest.mark.parametrize("lam", list(SONINE))
@pytest.mark.parametrize("name", ["mu", "temperature", "a2"])
def test_sonine_closure_beats_gaussian_closure(measured, lam, name):
    ds = measured[lam]
    value, error = float(ds[name]), float(ds[f"{name}_err"])
    sonine_gap = abs(value - SONINE[lam][name])
    gaussian_gap = abs(value - gaussian_closure(lam)[name])
    assert sonine_gap + 4 * error < gaussian_gap


def test_gaussian_closure_limits():
    assert gaussian_closure(0.0)["temperature"] == pytest.approx(1.0)
    assert gaussian_closure(40.0)["mu"] == pytest.approx(-1 / math.sqrt(2), abs=1e-8)
    assert np.isclose(gaussian_closure(0.0)["mu"], 0.0)
