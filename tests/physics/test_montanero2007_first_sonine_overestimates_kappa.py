"""montanero2007 Fig. 3 and Section 4: at strong dissipation (alpha = 0.3) the first Sonine
approximation (Eqs. 2.42, 2.46) dramatically overestimates kappa' (1.61 kappa0), while
the modified first Sonine approximation of Ref. [28] (1.25 kappa0) is close; and the
two routes to b'_k, Eqs. (3.10) and (3.12), agree at this run's resolution (Student's 4
errors of 16 realizations: 0.12, 0.26 and 0.66 for b'_1..3 of 2.3, -1.4 and 2.6). Their
O(eps*^2) difference at eps* = 0.05 (a few 0.01, docs/reproduced.md) lies far below it;
the build checks the routes at eps* -> 0."""

import numpy as np
import pytest

from kinetic.analysis import montanero2007 as analysis
from kinetic.studies.montanero2007 import simulate_batch
from kinetic.theory import montanero2007 as theory

SIGMAS = 4.0


@pytest.fixture(scope="module")
def strong_dissipation():
    run = {
        "n_particles": 4000,
        "time_step": 0.01,
        "force_step": "euler",
        "selection": "ntc",
        "splitting": "lie",
        "reduced_field": 0.05,
        "duration": 30.0,
        "steady_from": 12.0,
        "sample_interval": 0.6,
        "sample_stride": 15,
        "realizations": 16,
        "realizations_per_job": 16,
        "cx_max": 5.0,
        "cx_bins": 100,
        "restitution": 0.3,
        "family": "scan",
    }
    dataset = simulate_batch(run, seed=2007, first=0, count=16, label="alpha = 0.3")
    return analysis.steady_summary_of(dataset)


def test_first_sonine_overestimates_kappa_prime(strong_dissipation):
    summary = strong_dissipation
    factor = analysis.tolerance_factor(SIGMAS, summary["realizations"] - 1)
    margin = factor * summary["kappa_ratio_err"]
    first_sonine = theory.kappa_prime_ratio(0.3)
    modified = theory.kappa_prime_ratio(0.3, approximation="modified")
    assert summary["kappa_ratio"] + margin < first_sonine
    # the modified Sonine estimate is within 10 % (plus the error) of the simulation
    assert abs(summary["kappa_ratio"] - modified) < 0.1 * modified + margin


def test_two_routes_to_the_sonine_coefficients_agree(strong_dissipation):
    summary = strong_dissipation
    factor = analysis.tolerance_factor(SIGMAS, summary["realizations"] - 1)
    difference = summary["route_difference"]
    assert np.all(np.abs(difference) <= factor * summary["route_difference_err"])
    # b'_2 is comparable to b'_1 at alpha = 0.3 (Fig. 4), clearly nonzero and negative
    b, b_err = summary["b_full"], summary["b_full_err"]
    assert b[1] < -factor * b_err[1]
    assert abs(b[1]) > 0.3 * b[0]
