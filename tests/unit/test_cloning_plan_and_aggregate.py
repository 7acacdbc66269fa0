"""Job plan (config -> simulate arguments) and aggregation of the cloning batches."""

import math

import numpy as np
import pandas as pd
import pytest

from kinetic.analysis import cloning as aggregate
from kinetic.cloning import simulate
from kinetic.config import validate_config
from kinetic.studies import visco2008_cloning as plan


@pytest.fixture(scope="module")
def section():
    config = {
        "seed": 1,
        "visco2008": {
            "cloning": {
                "kernels": {
                    "hard_disks": {"lambdas": [-1.0, 0.5, 8.0], "populations": [20, 40]},
                    "maxwell": {"lambdas": [1.0], "populations": [30]},
                },
                "collisions_per_realization": 2.0e4,
                "realizations": 4,
                "realizations_per_job": 2,
                "n_blocks": 4,
                "transient": 5.0,
                "transient_kept_collisions": 2,
            }
        },
    }
    validate_config(config)  # fills the schema defaults
    return config["visco2008"]["cloning"]


def test_plan_lists_every_batch(section):
    keys = plan.batch_keys(section, "scan")
    assert len(keys) == (3 * 2 + 1) * 2
    assert ("hard_disks", "lam-1.000", "N20", 1) in keys
    assert len(plan.batch_keys(section, "error_vs_time")) == 2 * 7  # schema defaults


def test_job_parameters_follow_the_config(section):
    p = plan.job_parameters(section, "scan", "hard_disks", "lam-1.000", "N40", 1, seed=9)
    rate_factor = 2 * math.e - 1  # Eq. 56 at λ = -1
    assert p["duration"] == pytest.approx(2.0e4 / (40 * rate_factor))
    assert p["first_realization"] == 2 and p["n_realizations"] == 2 and p["seed"] == 9
    assert p["transient"] == 5.0
    large = plan.job_parameters(section, "scan", "hard_disks", "lam+8.000", "N20", 0, seed=9)
    assert large["transient"] == pytest.approx(2 * math.exp(8.0) * math.sqrt(2))
    simulate_arguments = set(simulate.__kwdefaults__) | {
        "lam",
        "population",
        "duration",
        "transient",
        "seed",
    }
    assert set(p) <= simulate_arguments


def test_unknown_point_or_batch_is_refused(section):
    with pytest.raises(ValueError, match="no cloning point"):
        plan.job_parameters(section, "scan", "hard_disks", "lam+0.700", "N20", 0, seed=1)
    with pytest.raises(ValueError, match="batch 2 outside"):
        plan.job_parameters(section, "scan", "hard_disks", "lam+0.500", "N20", 2, seed=1)


def test_reference_grid_contains_every_simulated_lambda(section):
    grid = plan.reference_lambdas(section)
    for lam in (-1.0, 0.5, 1.0, 8.0, -0.5):
        assert lam in grid
    assert grid == sorted(grid)


def batch(section, kernel, lam, n, index):
    parameters = plan.job_parameters(
        section, "scan", kernel, plan.lambda_token(lam), plan.population_token(n), index, 5
    )
    return simulate(**parameters)


def test_batches_pool_into_the_single_call_result(section):
    # arrange: two batches of one point, and the same four realizations in one call
    parts = [batch(section, "hard_disks", 0.5, 20, b) for b in (1, 0)]
    p = plan.job_parameters(section, "scan", "hard_disks", "lam+0.500", "N20", 0, 5)
    whole = simulate(**{**p, "n_realizations": 4})
    # act
    (record,) = aggregate.combine_points(parts)
    # assert
    assert record["n_realizations"] == 4
    assert record["mu"] == pytest.approx(float(whole.mu), rel=1e-12)
    assert record["a2_err"] == pytest.approx(float(whole.a2_err), rel=1e-12)
    with pytest.raises(ValueError, match=r"appears in both a\.nc and b\.nc"):
        aggregate.combine_points([parts[0], parts[0]], names=["a.nc", "b.nc"])


def test_table_has_the_contract_columns_and_extrapolation_rows(section):
    datasets = [
        batch(section, kernel, lam, n, b)
        for kernel, grid in section["kernels"].items()
        for lam in grid["lambdas"]
        for n in grid["populations"]
        for b in range(len(plan.jobs(section, "scan")))
    ]
    records = aggregate.combine_points(datasets)
    limits = aggregate.extrapolate_points(records)
    table = aggregate.scan_table(records, limits)
    assert list(table.columns) == aggregate.TABLE_COLUMNS
    assert len(table) == 7 + 2  # 7 points, extrapolations at λ = -1 and 0.5 only
    extrapolated = table[table["n_c"].isna()]
    assert set(extrapolated["lambda"]) == {-1.0, 0.5}
    collapsed = table[(table["lambda"] == 8.0)]
    assert collapsed["mu"].notna().all() and collapsed["T"].isna().all()
    dataset = aggregate.scan_dataset(records, limits)
    assert dataset.sizes["point"] == 7 and dataset.sizes["limit"] == 4
    assert isinstance(table["n_c"].dtype, pd.Int64Dtype)
    assert np.isfinite(dataset["limit_mu_rate"].values[:2]).all()


def _record(lam, population, collapsed, value):
    record = {"kernel": "hard_disks", "lam": lam, "population": population}
    for name in aggregate.OBSERVABLES:
        record |= {name: value, f"{name}_err": 1e-3}
    return record | {"collapsed": collapsed}


def test_extrapolation_fits_the_populations_above_the_largest_collapsed_one():
    """A collapse of the smallest population (as at lambda = 2.5 with N_c = 100 in a
    default build of seed 31415) leaves the larger two to the 1/N_c fit instead of
    dropping the point's extrapolation, and with it the checks at that lambda; the
    collapsed value is left out (it would pull the line), and a collapse of the largest
    leaves no fit."""
    line = {n: 0.5 + 2.0 / n for n in (100, 300, 1000)}
    records = [_record(2.5, n, n == 100, line[n] + (0.3 if n == 100 else 0.0)) for n in line]
    records += [_record(4.0, n, n in (100, 1000), line[n]) for n in line]
    by_lam = {entry["lam"]: entry for entry in aggregate.extrapolate_points(records)}
    fit = by_lam[2.5]["temperature"]
    assert fit["value"] == pytest.approx(0.5, abs=1e-9) and fit["dof"] == 0
    assert by_lam[2.5]["fitted_populations"] == [300, 1000] and by_lam[2.5]["collapsed"]
    assert np.isnan(fit["deviation_err"][0]) and np.isfinite(fit["deviation_err"][1:]).all()
    assert all(by_lam[4.0][name] is None for name in aggregate.OBSERVABLES)
    table = aggregate.scan_table(records, list(by_lam.values()))
    limits = table[table["n_c"].isna()]
    assert list(limits["lambda"]) == [2.5] and limits["T"].iloc[0] == pytest.approx(0.5)
    assert table.loc[table["n_c"] == 100, "T"].isna().all()  # the collapsed points' T


@pytest.mark.parametrize("lam", [-2.0, -0.3, 0.0, 0.7])
def test_planned_event_rate_factor_is_the_kernels(lam):
    from kinetic.cloning import kernels
    from kinetic.studies.visco2008_cloning import event_rate_factor

    assert event_rate_factor(lam) == pytest.approx(kernels.compensation_parameters(lam)[0])


def test_deviation_from_the_extrapolation_has_the_fits_covariance():
    """A point's deviation from the 1/N_c -> 0 intercept of a fit through it: its error
    (with the covariance of the point and the intercept) is the scatter of 4000 synthetic
    scans within 5 % at every population, where adding the two errors as independent
    overstates it at the large populations and understates it at the smallest."""
    from kinetic.analysis.cloning import deviation_from_extrapolation_err
    from kinetic.cloning.estimators import extrapolate_population

    sizes = np.array([25.0, 100.0, 400.0, 1600.0])
    sigma = np.array([0.004, 0.002, 0.0012, 0.0008])
    truth = -0.576 - 0.1 / sizes
    rng = np.random.default_rng(9)
    deviations, intercept_errors = [], []
    for _ in range(4000):
        values = truth + sigma * rng.standard_normal(sizes.size)
        fit = extrapolate_population(sizes, values, sigma)
        deviations.append(values - fit.intercept)
        intercept_errors.append(fit.intercept_err / max(1.0, np.sqrt(fit.chi2 / fit.dof)))
    scatter = np.std(deviations, axis=0, ddof=1)
    predicted = [deviation_from_extrapolation_err(sizes, sigma, i) for i in range(sizes.size)]
    np.testing.assert_allclose(predicted, scatter, rtol=0.05)
    independent = np.hypot(sigma, np.median(intercept_errors))
    assert independent[-1] > 1.3 * scatter[-1] and independent[0] < scatter[0]
