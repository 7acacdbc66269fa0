"""visco2008 Eq. (38) and Figs. 5-7 at large λ, and the extreme case λ = 8.

What theory guarantees: μ(λ) >= -r(0) = -1/√2 for every λ (no collision during t has
probability ~ e^{-t/√2}), μ decreases with λ and tends to -1/√2, and T(λ) -> 0 (the
eigenfunction concentrates at v = 0). The first-order term of Eq. (38), +e^{-λ}/√2, does
not hold: the deterministic solution of Eq. (28) gives μ(4) = -1/√2 to 1e-7 while Eq. (38)
says -0.6942 (see ``kinetic.theory.visco2008_exact``); the Monte Carlo resolves the difference.

Finite population and finite time bias μ low at large λ (the population cannot hold the
slowest members of the exact eigenfunction): measured -0.001 to -0.003 at λ = 4 and
-0.002 to -0.005 at λ = 8 for N = 100 to 3000. At λ = 8 almost every collision
annihilates and the population collapses onto the clones of one slow member (diversity
collapse): μ keeps that accuracy, T and a2 are those of a single clone and are flagged.
"""

import itertools
import math

import pytest

from kinetic.analysis.checks import tolerance_factor
from kinetic.cloning import simulate

EDGE = -1.0 / math.sqrt(2.0)
BIAS = {4.0: 0.004, 8.0: 0.008}  # stated accuracy (finite N_c and time), see docstring
REALIZATIONS = 16
BAND = tolerance_factor(4, REALIZATIONS - 1)
"""The two-sided probability of 4 Gaussian sigmas for errors from 16 realizations
(Student's t, 15 degrees of freedom): 6.0 errors (with the 4 realizations this test ran
before, 32.6; it asserted 4)."""


@pytest.fixture(scope="module")
def large():
    common = {
        "kernel": "hard_spheres",
        "dimension": 2,
        "n_blocks": 5,
        "n_realizations": REALIZATIONS,
    }
    return {
        1.0: simulate(lam=1.0, population=1000, duration=200.0, transient=20.0, seed=31, **common),
        2.0: simulate(lam=2.0, population=1000, duration=200.0, transient=50.0, seed=32, **common),
        4.0: simulate(
            lam=4.0, population=1000, duration=1000.0, transient=1000.0, seed=33, **common
        ),
        8.0: simulate(
            lam=8.0, population=300, duration=4000.0, transient=5000.0, seed=34, **common
        ),
    }


@pytest.mark.parametrize("lam", [4.0, 8.0])
def test_mu_reaches_minus_one_over_root_two(large, lam):
    ds = large[lam]
    mu, error = float(ds.mu), float(ds.mu_err)
    assert EDGE - BIAS[lam] - BAND * error < mu < EDGE + BAND * error


def test_first_order_of_eq38_is_not_the_eigenvalue(large):
    ds = large[4.0]
    eq38 = (math.exp(-4.0) - 1.0) / math.sqrt(2.0)
    # Eq. (38) lies 0.013 above the edge; the data sit at the edge
    assert float(ds.mu) < eq38 - BAND * float(ds.mu_err) - BIAS[4.0]


def test_mu_decreases_and_temperature_vanishes(large):
    lams = sorted(large)
    for low, high in itertools.pairwise(lams):
        a, b = large[low], large[high]
        assert float(b.mu) < float(a.mu) + BAND * float(a.mu_err + b.mu_err)
        if high < 8.0:  # T(λ) falls, resolved: 0.68, 0.33, 0.045 at λ = 1, 2, 4
            assert float(b.temperature) < float(a.temperature) - BAND * float(
                a.temperature_err + b.temperature_err
            )
    # at λ = 8 the population is the clones of one member (flagged below): its T is
    # one clone's, 0.02-0.05 ± 0.012-0.016 with other seeds, at most T(4) within errors
    a, b = large[4.0], large[8.0]
    assert float(b.temperature) < float(a.temperature) + BAND * float(
        a.temperature_err + b.temperature_err
    )


def test_lambda_8_is_flagged_as_diversity_collapse(large):
    ds = large[8.0]
    assert ds.attrs["diversity_collapse"] == 1
    assert int(ds.distinct_velocities.min()) < 10
    assert large[1.0].attrs["diversity_collapse"] == 0


def test_lambda_8_refuses_a_transient_without_renewal():
    with pytest.raises(ValueError, match=r"Use transient >= 4216"):
        simulate(
            kernel="hard_spheres", lam=8.0, population=300, duration=100.0, transient=1000.0, seed=1
        )
