"""Finite-population bias of the cloning Monte Carlo, and the strong-duplication extreme
λ = -1.5 (visco2008 §IV.A, Eq. 56).

μ, T and a2 of a population of N_c members are biased by O(1/N_c) (the compensation
couples the members). Measured for hard disks (N_c = 25 ... 1600): μ ≈ μ∞ - 0.065/N_c,
T ≈ T∞ + 0.38/N_c, a2 ≈ a2∞ - 0.48/N_c at λ = 1; μ ≈ μ∞ - 0.35/N_c at λ = -1.5 and
μ∞ - 0.016/N_c at λ = -0.5. A weighted linear fit in 1/N_c over small populations, whose
raw values are visibly biased, extrapolates to the deterministic solution of Eq. (28).

Accuracy at λ = -1.5 (2e6 collisions per point): Maxwell μ = e^{1.5} - 1 within its
0.05% error (no bias: the rate does not depend on v); hard disks within 0.05% of the
exact 3.7192 once the -0.35/N_c bias is extrapolated away (N_c >= 1000 makes it
< 0.01%). Below ``LAMBDA_MIN`` the front refuses.
"""

import math

import pytest

from kinetic.analysis.checks import tolerance_factor
from kinetic.cloning import LAMBDA_MIN, extrapolate_population, simulate
from kinetic.theory.visco2008_exact import reference_solution

SIZES = [25, 50, 100]


def _strong_duplication():
    return [
        simulate(
            kernel="hard_spheres",
            dimension=2,
            lam=-1.5,
            population=n,
            duration=1.0e5 / n,
            transient=20.0,
            n_blocks=5,
            n_realizations=8,
            seed=56,
        )
        for n in SIZES
    ]


@pytest.fixture(scope="module")
def strong_duplication(once):
    return once("cloning_population_size.strong_duplication", _strong_duplication)


def _exact():
    """μ and T of Eq. (28) at λ = -1.5, each with twice its change from 200 to 300 nodes
    (the discretisation's error)."""
    fine = reference_solution([-1.5], 2, n_nodes=300)
    coarse = reference_solution([-1.5], 2, n_nodes=200)
    return {
        name: (float(fine[k][0]), 2 * abs(float(fine[k][0] - coarse[k][0])))
        for k, name in ((0, "mu"), (1, "temperature"))
    }


@pytest.fixture(scope="module")
def exact(once):
    return once("cloning_population_size.exact", _exact)


@pytest.fixture(scope="module")
def exact_mu(exact):
    return exact["mu"]


@pytest.mark.slow
def test_small_populations_are_biased_low(strong_duplication, exact_mu):
    reference, discretisation = exact_mu
    smallest = strong_duplication[0]
    band = tolerance_factor(4, 7) * float(smallest.mu_rate_err)  # Student's, 8 realizations
    assert float(smallest.mu_rate) < reference - discretisation - band


@pytest.mark.slow
@pytest.mark.parametrize("estimator", ["mu", "mu_rate"])
def test_extrapolation_to_infinite_population_recovers_the_eigenvalue(
    strong_duplication, exact_mu, estimator
):
    reference, discretisation = exact_mu
    values = [float(ds[estimator]) for ds in strong_duplication]
    errors = [float(ds[f"{estimator}_err"]) for ds in strong_duplication]
    fit = extrapolate_population(SIZES, values, errors)
    assert fit.slope < 0
    # Student's t for the 3 x 7 degrees of freedom behind the line's errors
    band = tolerance_factor(4, 3 * 7) * fit.intercept_err + discretisation
    assert abs(fit.intercept - reference) < band


def test_maxwell_strong_duplication_is_exact():
    ds = simulate(
        kernel="maxwell",
        dimension=2,
        lam=-1.5,
        population=500,
        duration=50.0,
        transient=5.0,
        n_blocks=5,
        n_realizations=24,
        seed=57,
    )
    # Student's t for 24 realizations (5.0 errors; 6 of 4 times the length gave 12.3)
    assert abs(float(ds.mu) - math.expm1(1.5)) < tolerance_factor(4, 23) * float(ds.mu_err)
    assert float(ds.mu_err) / math.expm1(1.5) < 1e-3


@pytest.mark.slow
def test_temperature_bias_also_extrapolates(strong_duplication, exact):
    """T of the small populations lies below Eq. (28)'s T(-1.5) (the duplicated fast
    members are shared), and the line in 1/N_c reaches it."""
    reference, discretisation = exact["temperature"]
    values = [float(ds.temperature) for ds in strong_duplication]
    errors = [float(ds.temperature_err) for ds in strong_duplication]
    fit = extrapolate_population(SIZES, values, errors)
    # Student's t for the 8 realizations of a size, and for the 3 × 7 degrees of freedom
    # behind the line (seeds 56-59: the limit lies -2.6 to +2.6 of its errors off)
    assert values[0] < reference - discretisation - tolerance_factor(4, 7) * errors[0]
    assert fit.slope < 0
    band = tolerance_factor(4, 3 * 7) * fit.intercept_err + discretisation
    assert abs(fit.intercept - reference) < band


def test_below_the_supported_range_is_refused():
    with pytest.raises(ValueError, match=rf"lam must be in \[{LAMBDA_MIN}"):
        simulate(
            kernel="hard_spheres",
            lam=LAMBDA_MIN - 0.1,
            population=100,
            duration=1.0,
            transient=1.0,
            seed=1,
        )
