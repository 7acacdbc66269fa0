"""Continuous-time DSMC free flights against visco2008 (d = 2, equilibrium, ω = 1).

Hard disks: free-flight times against Eq. (9) (the curve of Fig. 1's DSMC squares);
Maxwell molecules: free paths against Eq. (D3) (Fig. 12) and flight times against the
exponential (D1); very hard particles: flight times against Eq. (B4). Bin averages of the
theory (Gauss-Legendre on each bin) against the histograms of 16 independent
realizations: chi²/dof and the largest deviation in units of the standard error.
"""

import numpy as np
import pytest

from kinetic.analysis.checks import (
    largest_z_tolerance,
    sum_of_squares_tolerance,
    tolerance_factor,
)
from kinetic.analysis.statistics import mean_and_sem
from kinetic.dsmc import simulate_free_flights
from kinetic.theory import visco2008

NODES, WEIGHTS = np.polynomial.legendre.leggauss(8)


def _bin_average(pdf, edges):
    """(1/Δ) ∫_bin pdf for every bin of ``edges``."""
    low, high = edges[:-1, None], edges[1:, None]
    x = 0.5 * (high + low) + 0.5 * (high - low) * NODES
    return 0.5 * np.sum(WEIGHTS * pdf(x.ravel()).reshape(x.shape), axis=1)


BINS, REALIZATIONS = 20, 16


def _chi2_max() -> float:
    """Largest mean of z² over the 20 bins: each z is Student's t with 15 degrees of freedom
    (errors from 16 realizations), so the mean of 20 z² is 1.15 on average, and exceeds 2.0
    (the bound before 3.0: one seed in four failed one of the four tests) with probability
    3.7 %, 3.0 (the bound until salt 28 of KINETIC_TEST_SEED_SALT failed it at 3.12) with
    0.12 %, and this bound, 3.84, with 10⁻⁴. Over 300 seeds the hard disks' Eq. (9)
    comparison had a mean of 1.169, a largest of 3.34 and two above 3.0. The Poisson law that
    hard disks must reject gives more than 20."""
    return sum_of_squares_tolerance(BINS, REALIZATIONS - 1, 1e-4) / BINS  # cached


WORST_MAX = largest_z_tolerance(BINS, REALIZATIONS - 1)
"""Largest |z| of the bins: Student's quantile at a family-wise false-alarm rate of
0.1 % (5.6 errors). A fixed 4.5 (4e-4 a bin, 0.8 % a test) failed for one salted seed
in 20 (4.7)."""


def _compare(measured, theory):
    mean, sem = mean_and_sem(measured)
    z = (mean - theory) / sem
    return np.mean(z**2), np.max(np.abs(z))


@pytest.fixture(scope="module")
def runs():
    common = dict(
        n_particles=2000,
        duration=30.0,
        seed=61,
        n_realizations=REALIZATIONS,
        dimension=2,
        max_flight_time=10.0,
        n_time_bins=BINS,
        max_free_path=10.0,
        n_path_bins=BINS,
    )
    return {
        kernel: simulate_free_flights(kernel=kernel, **common)
        for kernel in ("hard_spheres", "maxwell", "very_hard")
    }


def test_hard_disk_free_flight_times_follow_eq_9(runs):
    run = runs["hard_spheres"]
    theory = _bin_average(lambda t: visco2008.free_flight_time_pdf(t, 2), run.time_edges.values)
    chi2, worst = _compare(run.time_pdf.values, theory)
    assert chi2 < _chi2_max() and worst < WORST_MAX
    # the Poisson expectation e^{-t} is clearly rejected by the same data
    poisson = _bin_average(lambda t: np.exp(-t), run.time_edges.values)
    assert _compare(run.time_pdf.values, poisson)[0] > 20
    mean, sem = mean_and_sem(run.collision_frequency.values)
    assert abs(mean - 1.0) < tolerance_factor(4.0, run.sizes["realization"] - 1) * sem


def test_maxwell_free_paths_follow_d3(runs):
    run = runs["maxwell"]
    theory = _bin_average(lambda x: visco2008.maxwell_free_path_pdf(x, 2), run.path_edges.values)
    chi2, worst = _compare(run.path_pdf.values, theory)
    assert chi2 < _chi2_max() and worst < WORST_MAX
    # flights still open at the end with a path below the histogram's range: about 0.1 a
    # realization (e^{-10} of 2000 flights, half of them slow), too few to bias it
    assert int(run.unresolved_paths.sum()) <= 1e-5 * int(run.flights.sum())


def test_maxwell_free_flight_times_are_exponential(runs):
    run = runs["maxwell"]
    exponential = _bin_average(lambda t: np.exp(-t), run.time_edges.values)
    chi2, worst = _compare(run.time_pdf.values, exponential)
    assert chi2 < _chi2_max() and worst < WORST_MAX


def test_very_hard_particle_flight_times_follow_b4(runs):
    run = runs["very_hard"]
    theory = _bin_average(lambda t: visco2008.vhp_free_flight_time_pdf(t, 2), run.time_edges.values)
    chi2, worst = _compare(run.time_pdf.values, theory)
    assert chi2 < _chi2_max() and worst < WORST_MAX
