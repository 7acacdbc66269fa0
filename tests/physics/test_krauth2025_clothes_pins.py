"""Clothes-pin samplers (krauth2025 §4.4.1) against the exact densities of Eqs. (4.6, 4.7).

Each test runs fixed seeds; the tolerances are the samples' own standard errors (from
the spread of B = 16 independent realizations (runs or chains), so a bin's z-score follows Student's
t with 15 degrees of freedom): the largest |z| of the bins within the quantile of a 0.1 %
family-wise false alarm (6.4 errors for 78 bins), and the sum of z² over the bins within
the quantile of a 0.1 % false alarm of a sum of as many squared Student's t (bins on the
line are nearly independent), which is what carries the power.
"""

import numpy as np
import pytest

from kinetic.analysis.checks import (
    largest_z_tolerance,
    sum_of_squares_tolerance,
    tolerance_factor,
)
from kinetic.analysis.krauth2025 import pin_contact_density
from kinetic.analysis.statistics import mean_and_sem
from kinetic.samplers import kernels, naive_acceptance, pin_snapshots, sample_line, sample_ring
from kinetic.theory import krauth2025 as theory


def _z_scores(measured, error, exact):
    """z-scores of the bins that hold samples (an empty bin has no error bar)."""
    filled = error > 0
    return (measured[filled] - exact[filled]) / error[filled]


def _check(z, realizations):
    # the largest |z| of the bins: Student's quantile at a family-wise false-alarm rate of
    # 0.1 % (6.4 for 78 bins of 16 realizations; a fixed 4.5, 4e-4 per bin, failed for
    # about one run in 30)
    assert np.abs(z).max() < largest_z_tolerance(z.size, realizations - 1)
    # Σ z² of 78 Student's t with 15 degrees of freedom: 152.7 at 0.1 %, where χ²₇₈'s
    # quantile (122.3) would fail one correct run in 30
    assert np.sum(z**2) < sum_of_squares_tolerance(z.size, realizations - 1)


@pytest.mark.parametrize(
    ("method", "length", "samples"),
    [("direct", 20.0, 50_000), ("naive", 40.0, 500), ("direct", 40.0, 50_000)],
)
def test_line_density_matches_eq_4_7(method, length, samples):
    n, sigma, realizations = 15, 0.5, 16
    data = sample_line(
        method,
        n_pins=n,
        length=length,
        sigma=sigma,
        samples=samples,
        realizations=realizations,
        bins=78,
        seed=11,
    )
    exact = theory.bin_average(
        lambda x: n * theory.pin_density(x, n, length, sigma), data.bin_edges.values
    )
    _check(_z_scores(data.density.values, data.density_sem.values, exact), realizations)
    # every configuration puts its N pins inside [σ, L − σ]
    assert int(data.counts.sum()) == n * samples * realizations


@pytest.mark.parametrize(("method", "samples"), [("direct", 20_000), ("naive", 4000)])
def test_wall_rift_pressure_is_the_contact_density(method, samples):
    """§4.4.3 in one dimension: the pin density at contact with a post is βP, exactly
    N/(L − 2Nσ) = 0.6 for 15 pins of width 1 on L = 40; the extrapolation to the post
    leaves no visible bias on the exact bin averages. The standard error comes from 12
    realizations, so the band is Student's 4 sigma (6.2 errors): a realization's contact
    value is an extrapolation from the first bins, with heavier tails than a Gaussian,
    and the normal 4.5 failed for one seed in 60. naive-pin draws 4000 configurations a
    realization: with 2000 the standard error was 0.013-0.032 over 60 seeds, so whether
    the check had power (< 0.03) hung on the seed; with 4000 it is 0.010-0.022 (40)."""
    n, length, sigma, realizations = 15, 40.0, 0.5, 12
    data = sample_line(
        method,
        n_pins=n,
        length=length,
        sigma=sigma,
        samples=samples,
        realizations=realizations,
        bins=390,
        seed=13,
    )
    edges = data.bin_edges.values
    width = edges[1] - edges[0]
    per_realization = data.counts.values / (samples * width)
    contact, sem = mean_and_sem([pin_contact_density(edges, row) for row in per_realization])
    beta_p = n / (length - 2 * n * sigma)
    assert abs(contact - beta_p) < tolerance_factor(4.0, realizations - 1) * sem
    assert sem < 0.05 * beta_p  # the check has power
    exact = theory.bin_average(lambda x: n * theory.pin_density(x, n, length, sigma), edges)
    assert abs(pin_contact_density(edges, exact) - beta_p) < 0.1 * sem


def test_naive_acceptance_is_the_ratio_of_partition_functions():
    """Tabula-rasa rejection keeps a started configuration with probability
    Z_{N,L}/(L − 2σ)^N (Eq. 4.6): the counted fraction agrees within 4 standard errors."""
    n, length, sigma, samples, realizations = 10, 25.0, 0.5, 2000, 16
    data = sample_line(
        "naive",
        n_pins=n,
        length=length,
        sigma=sigma,
        samples=samples,
        realizations=realizations,
        bins=10,
        seed=5,
    )
    per_realization = samples / data.started.values
    mean, error = per_realization.mean(), per_realization.std(ddof=1) / np.sqrt(realizations)
    expected = theory.partition_function(n, length, sigma) / (length - 2 * sigma) ** n
    assert expected == pytest.approx(naive_acceptance(n, length, sigma))
    assert abs(mean - expected) < 4 * error
    assert error < 0.05 * expected  # the test has power


def test_ring_pair_density_matches_the_mapping():
    n, length, sigma, realizations = 15, 20.0, 0.5, 16
    data = sample_ring(
        n_pins=n,
        length=length,
        sigma=sigma,
        step=0.5,
        sweeps=5000,
        burn_in=500,
        realizations=realizations,
        bins=80,
        seed=3,
    )
    exact = theory.bin_average(
        lambda r: theory.ring_pair_density(r, n, length, sigma), data.bin_edges.values
    )
    z = _z_scores(data.pair_density.values, data.pair_density_sem.values, exact)
    # one chain's fluctuations move neighbouring bins together: the largest |z| only (its
    # Bonferroni bound holds for correlated bins too; Σ z² does not), and the empty bins
    # (r < 2σ, r > L − 2σ) are exactly empty
    assert np.abs(z).max() < largest_z_tolerance(z.size, realizations - 1)
    empty = (data.r.values < 2 * sigma) | (data.r.values > length - 2 * sigma)
    assert np.all(data.pair_density.values[empty] == 0)
    assert 0.2 < float(data.acceptance.mean()) < 0.9


def test_direct_pin_configurations_are_legal_and_reproducible():
    a = pin_snapshots(n_pins=15, length=20.0, sigma=0.5, count=200, seed=9).position.values
    b = pin_snapshots(n_pins=15, length=20.0, sigma=0.5, count=200, seed=9).position.values
    np.testing.assert_array_equal(a, b)
    assert np.all(np.diff(a, axis=1) >= 1.0 - 1e-12)  # no overlap (width 2σ = 1)
    assert a.min() >= 0.5 and a.max() <= 19.5


def test_markov_moves_never_create_an_overlap():
    n, length, sigma = 12, 14.0, 0.5
    positions = np.arange(n) * (length / n)
    state = np.array([1, 2, 3, 4], dtype=np.uint64)
    histogram = np.zeros(10, dtype=np.int64)
    kernels.ring_markov(n, length, sigma, 0.7, 2000, 0, state, positions, histogram)
    ordered = np.sort(positions)
    gaps = np.diff(np.append(ordered, ordered[0] + length))
    assert gaps.min() >= 2 * sigma - 1e-12
    assert np.all((positions >= 0) & (positions < length))


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"method": "naive", "length": 20.0, "samples": 10_000}, "naive-pin would start"),
        ({"method": "direct", "length": 7.0}, "cannot hold"),
        ({"method": "direct", "realizations": 1}, "realizations"),
        ({"method": "direct", "samples": -5}, "samples"),
        ({"method": "rejection"}, "method"),
    ],
)
def test_bad_line_arguments_fail_before_sampling(kwargs, message):
    arguments = {
        "n_pins": 15,
        "length": 20.0,
        "sigma": 0.5,
        "samples": 10,
        "realizations": 4,
        "bins": 10,
        "seed": 1,
    }
    arguments.update(kwargs)
    method = arguments.pop("method")
    with pytest.raises(ValueError, match=message):
        sample_line(method, **arguments)


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"step": True}, TypeError, "step must be a real number, got True"),
        ({"step": 0.0}, ValueError, r"step = 0.0 is outside the allowed range \(0, 10\]"),
        ({"step": 10.5}, ValueError, "step = 10.5 is outside"),
        ({"sigma": True}, TypeError, "sigma must be a real number, got True"),
        ({"length": "20"}, TypeError, "length must be a real number"),
        ({"n_pins": 1}, ValueError, "n_pins >= 2"),
    ],
)
def test_bad_ring_arguments_fail_before_sampling(monkeypatch, kwargs, error, message):
    def no_work(*args, **kwargs):
        raise AssertionError("the chain started before the arguments were validated")

    monkeypatch.setattr(kernels, "ring_markov", no_work)
    arguments = {"n_pins": 15, "length": 20.0, "sigma": 0.5, "step": 1.0, "sweeps": 2}
    arguments |= {"burn_in": 0, "realizations": 2, "bins": 4, "seed": 0}
    with pytest.raises(error, match=message):
        sample_ring(**arguments | kwargs)


def test_fronts_compile_one_signature_per_kernel():
    """Integers from a YAML config (length: 20) and floats reach the kernels as the same
    types, so the kernels warmed once before parallel jobs are the ones the jobs run
    (a job compiling a new signature into the shared numba cache could corrupt it)."""
    for length, sigma in ((20, 1), (20.0, 0.5)):
        sample_line(
            "direct",
            n_pins=3,
            length=length,
            sigma=sigma,
            samples=2,
            realizations=2,
            bins=4,
            seed=0,
        )
        sample_line(
            "naive", n_pins=3, length=length, sigma=sigma, samples=2, realizations=2, bins=4, seed=0
        )
        sample_ring(
            n_pins=3,
            length=length,
            sigma=sigma,
            step=1,
            sweeps=2,
            burn_in=0,
            realizations=2,
            bins=4,
            seed=0,
        )
        pin_snapshots(n_pins=3, length=length, sigma=sigma, count=1, seed=0)
    for name in ("direct_pin", "naive_pin", "ring_markov", "direct_pin_configuration"):
        assert len(getattr(kernels, name).signatures) == 1, name
