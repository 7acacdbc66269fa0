"""visco2008 Fig. 9: the finite-t estimator π_t(n) = (1/t) ln[P(N = nt)/max P] applied to
models at the MD's window, and the document's point that MD follows the Gaussian closure
while the Poisson prediction is distinctly off."""

import numpy as np
import pytest
import xarray as xr

from kinetic.analysis import collision_statistics
from kinetic.edmd import simulate
from kinetic.theory import visco2008


@pytest.mark.parametrize("t", [10.0, 50.0])
def test_saddle_point_of_poisson_is_stirling(t):
    # the saddle-point form of a Poisson count is Stirling's formula: relative error
    # 1/(12 k) in P(k), so (1/t)(1/(12 k) + 1/(12 k_mode)) after normalising at the mode
    counts = np.arange(1, int(3 * t))
    exact = visco2008.poisson_count_ldf(t, counts)
    saddle = visco2008.saddle_point_count_ldf(
        visco2008.poisson_mu, lambda lam: -np.exp(-lam), t, counts
    )
    bound = (1 / (12 * counts) + 1 / (12 * np.floor(t))) / t
    assert np.all(np.abs(saddle - exact) <= bound * 1.05)


def test_finite_t_gaussian_tends_to_the_legendre_transform_as_one_over_t():
    # π_t(n) - π(n) = (1/2t) ln[π''(n)/π''(1)] + O(1/t²): t times it does not depend on t,
    # and vanishes at the maximum n = 1
    rates = np.array([0.5, 0.75, 1.0, 1.5, 2.0])
    scaled = [
        t * (visco2008.gaussian_count_ldf(t, rates * t) - visco2008.gaussian_ldf(rates))
        for t in (2000.0, 8000.0)
    ]
    np.testing.assert_allclose(scaled[0], scaled[1], atol=2e-3)
    assert scaled[1][2] == 0.0
    assert np.all(np.abs(scaled[1][[0, 1, 3, 4]]) > 0.05)


def test_rare_bins_are_dropped_and_counted():
    rng = np.random.default_rng(11)
    histogram = np.bincount(rng.poisson(10.0, 20_000), minlength=40)
    dataset = xr.Dataset(
        {
            "window_histogram": (
                ("realization", "checkpoint", "window", "count"),
                histogram[None, None, None, :],
            ),
            "collisions": (("realization", "checkpoint"), np.array([[5.0e5]])),
            "production_time": (("realization", "checkpoint"), np.array([[1.0e3]])),
            "window_time": (("realization", "window"), np.array([[10.0]])),
        },
        coords={"window": [10.0], "checkpoint": [1.0e3]},
        attrs={"n_particles": 1000},
    )
    estimate = collision_statistics.count_ldf_estimate(dataset, 10.0, min_count=10)
    assert np.all(histogram[estimate["count"]] >= 10)
    assert estimate["dropped"] == np.sum((histogram > 0) & (histogram < 10))
    # the kept bins follow the exact finite-t Poisson curve within their counting errors
    exact = visco2008.poisson_count_ldf(estimate["t"], np.arange(40))[estimate["count"]]
    z = (estimate["ldf"] - exact) / estimate["error"]
    assert np.sqrt(np.mean(z**2)) < 1 + 5 * np.sqrt(0.5 / z.size)


def test_md_follows_the_gaussian_closure_not_poisson_at_t_10():
    # 2 realizations of 500 disks at ρσ² = 1e-3 for 1000 mean free times (about 2 s)
    md = simulate(
        n_particles=500,
        density=1e-3,
        seed=7,
        realizations=2,
        duration=1000,
        windows=(10.0,),
        equilibration=5,
    )
    estimate = collision_statistics.count_ldf_estimate(md, 10.0, min_count=10)
    counts = np.arange(estimate["count"].max() + 1, dtype=float)
    chi2 = {}
    for name, curve in (
        ("gaussian", visco2008.gaussian_count_ldf),
        ("poisson", visco2008.poisson_count_ldf),
    ):
        theory = curve(estimate["t"], counts)[estimate["count"]]
        ok = np.isfinite(theory)
        chi2[name] = np.mean(((estimate["ldf"][ok] - theory[ok]) / estimate["error"][ok]) ** 2)
    # Measured over 24 seeds (7-30): χ²/dof of the Gaussian closure 0.53-2.58 (median 1.5:
    # the bins share their normalisation and the closure is not exact, so not the
    # 1 ± √(2/dof) of independent bins), of Poisson 40-67, their ratio at least 15.
    assert chi2["gaussian"] < 4.0, chi2
    assert chi2["poisson"] > 8 * chi2["gaussian"], chi2
