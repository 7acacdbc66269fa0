"""Front of the cloning Monte Carlo: validation, reproducibility, dataset conventions."""

import math

import numpy as np
import pytest

from kinetic.analysis.statistics import weighted_line
from kinetic.cloning import LAMBDA_MAX, LAMBDA_MIN, extrapolate_population, simulate
from kinetic.io import check_conventions, parameters_of

SMALL = {
    "kernel": "hard_spheres",
    "dimension": 2,
    "lam": 0.5,
    "population": 50,
    "duration": 8.0,
    "transient": 4.0,
    "n_blocks": 4,
    "n_realizations": 2,
    "seed": 3,
}


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"lam": LAMBDA_MIN - 0.5}, "lam must be in"),
        ({"lam": LAMBDA_MAX + 1.0}, "lam must be in"),
        ({"lam": math.nan}, "lam must be finite"),
        ({"lam": math.inf}, "lam must be finite"),
        ({"population": 1}, "population must be >= 2"),
        ({"population": 2.5}, "population must be an integer"),
        ({"duration": 0.0}, "duration must be > 0"),
        ({"duration": math.inf}, "duration must be finite"),
        ({"transient": -1.0}, "transient must be >= 0"),
        ({"transient": math.nan}, "transient must be finite"),
        ({"kernel": "vhp"}, "kernel must be one of"),
        ({"dimension": 4}, "dimension must be >= 2 and <= 3"),
        ({"seed": -1}, "seed = -1 is not allowed"),
        ({"seed": 2**64}, "seed = 18446744073709551616 is not allowed"),
        ({"n_realizations": 1, "n_blocks": 1}, "n_blocks >= 2"),
        ({"n_realizations": 1, "n_blocks": 10, "duration": 1e-12}, "blocks of duration/n_blocks"),
        ({"lam": 8.0, "transient": 100.0}, "transient=100 is too short at lam=8"),
        # one candidate in 1e-6 mean free times returned mu = 0 +- 0 (exact 0.665)
        ({"lam": -0.5, "duration": 1e-6}, "about 2.29e-05 compensation events"),
        ({"n_realizations": 1, "lam": 2.0, "duration": 400.0}, "use n_realizations >= 2"),
        ({"backend": "cuda", "n_realizations": 65_536}, "at most 65535 realizations"),
        ({"control_interval": 0.5}, "control_interval = 0.5 is for backend 'cuda' only"),
        # Δ = 1 at λ = -2 and 32 clones gave μ = 4.49 ± 0.29 against e² - 1 = 6.39
        (
            {"backend": "cuda", "lam": -2.0, "population": 32, "control_interval": 1.0},
            "control_interval = 1 is too long at lam = -2 for 32 clones",
        ),
    ],
)
def test_bad_input_is_refused_before_work(change, message):
    # arrange
    arguments = {**SMALL, **change}
    # act / assert
    with pytest.raises((ValueError, TypeError), match=message):
        simulate(**arguments)


def test_lambda_refusal_names_the_range_and_reason():
    with pytest.raises(ValueError) as error:
        simulate(**{**SMALL, "lam": -6.0})
    text = str(error.value)
    assert str(LAMBDA_MIN) in text and "-6" in text and "Eq. 56" in text


def test_same_seed_gives_identical_data_and_batches_do_not_matter():
    # arrange / act
    whole = simulate(**{**SMALL, "n_realizations": 4})
    again = simulate(**{**SMALL, "n_realizations": 4})
    first = simulate(**{**SMALL, "n_realizations": 2, "first_realization": 0})
    second = simulate(**{**SMALL, "n_realizations": 2, "first_realization": 2})
    # assert
    np.testing.assert_array_equal(whole.net_compensations, again.net_compensations)
    np.testing.assert_array_equal(whole.integral_v2.values[:2], first.integral_v2.values)
    np.testing.assert_array_equal(whole.integral_v2.values[2:], second.integral_v2.values)
    np.testing.assert_array_equal(whole.velocity_density.values[2:], second.velocity_density)


def test_dataset_follows_conventions_and_stores_parameters():
    ds = simulate(**SMALL)
    check_conventions(ds)
    parameters = parameters_of(ds)
    assert parameters["lam"] == 0.5 and parameters["kernel_label"] == "hard_disks"
    assert ds.attrs["seed"] == 3
    assert int(ds.measured.sum()) == SMALL["n_blocks"]
    # the velocity-component density is normalised over its range
    width = float(ds.velocity[1] - ds.velocity[0])
    assert np.allclose(ds.velocity_density.sum("velocity") * width, 1.0, atol=1e-3)


def test_single_realization_uses_block_errors():
    ds = simulate(**{**SMALL, "n_realizations": 1, "n_blocks": 4, "duration": 40.0})
    assert ds.attrs["error_method"] == "blocks"
    assert float(ds.mu_err) > 0


def test_extrapolation_recovers_a_line_and_refuses_one_size():
    sizes = np.array([100, 200, 400, 800])
    values = 2.0 - 3.0 / sizes
    fit = extrapolate_population(sizes, values, np.full(4, 1e-3))
    assert fit.intercept == pytest.approx(2.0, abs=1e-12)
    assert fit.slope == pytest.approx(-3.0, abs=1e-9)
    assert fit.intercept_err > 0 and fit.dof == 2
    with pytest.raises(ValueError, match="2 distinct population sizes"):
        extrapolate_population([100, 100], [1.0, 1.1], [0.1, 0.1])
    # points scattered 10x beyond their errors: every error, and the covariance of the
    # line's band, grow by the Birge ratio sqrt(chi2/dof) (the covariance by its square)
    scattered = values + 1e-2 * np.array([1.0, -1.0, 1.0, -1.0])
    plain = weighted_line(1.0 / sizes, scattered, np.full(4, 1e-3))
    fit = extrapolate_population(sizes, scattered, np.full(4, 1e-3))
    birge = plain.chi2 / plain.dof
    assert birge > 50
    assert fit.intercept_err == pytest.approx(plain.intercept_err * np.sqrt(birge), rel=1e-12)
    assert fit.slope_err == pytest.approx(plain.slope_err * np.sqrt(birge), rel=1e-12)
    assert fit.covariance == pytest.approx(plain.covariance * birge, rel=1e-12)
    with pytest.raises(ValueError, match="errors finite and > 0"):
        extrapolate_population([100, 200, 400], [1.0, 1.1, 1.2], [0.1, np.inf, 0.1])


def test_a_single_realizations_values_use_every_measured_block():
    """19 measured blocks in 10 error groups: the values come from all 19 blocks' sums
    (10 of them were used, the remainder dropped), the error from groups of 1 or 2."""
    from kinetic.cloning.estimators import observables_from_sums, summarize_realizations
    from kinetic.cloning.kernels import BLOCK_FIELDS

    rng = np.random.default_rng(4)
    blocks = rng.uniform(0.5, 1.5, size=(1, 19, len(BLOCK_FIELDS)))
    summary = summarize_realizations(blocks, np.ones(19, bool), 50, 2, 0.5)
    whole = observables_from_sums(blocks[0].sum(axis=0), 50, 2, 0.5)
    for name, value in zip(("mu", "temperature", "a2", "mu_rate"), whole, strict=True):
        assert summary[name] == pytest.approx(float(value), rel=1e-12)
        assert summary[f"{name}_err"] > 0
    assert summary["error_method"] == "blocks"


def test_a2_comes_from_the_pooled_moments_not_an_average_of_ratios():
    """Realizations whose m2 and m4 scatter by 10 % about m2 = 2, m4 = 8 (1 + a2), a2 = 0.1:
    the mean of the realizations' own m4/m2² is 3 x 0.01 x 1.1 = 0.033 high (6 of its errors
    here), the ratio of the pooled moments is unbiased. μ and T, ratios over equal times,
    are the realizations' mean and its standard error."""
    from kinetic.analysis.checks import tolerance_factor
    from kinetic.analysis.statistics import mean_and_sem
    from kinetic.cloning.estimators import realization_observables, summarize_realizations
    from kinetic.cloning.kernels import BLOCK_FIELDS

    realizations, population, a2 = 2000, 10, 0.1
    rng = np.random.default_rng(12)
    blocks = np.zeros((realizations, 1, len(BLOCK_FIELDS)))

    def put(name, values):
        blocks[:, 0, BLOCK_FIELDS.index(name)] = values

    put("elapsed_time", 5.0)
    member_time = population * 5.0
    put("net_compensations", member_time * rng.normal(-0.5, 0.05, realizations))
    put("integral_v2", member_time * 2.0 * rng.normal(1.0, 0.1, realizations))
    put("integral_v4", member_time * 8.0 * (1 + a2) * rng.normal(1.0, 0.1, realizations))
    summary = summarize_realizations(blocks, np.ones(1, bool), population, 2, 0.0)
    band = tolerance_factor(4.0, realizations - 1) * summary["a2_err"]
    assert abs(summary["a2"] - a2) < band
    averaged = realization_observables(blocks, np.ones(1, bool), population, 2, 0.0)
    assert abs(np.mean(averaged[2]) - a2) > band  # the bias of an average of ratios
    for name, values in (("mu", averaged[0]), ("temperature", averaged[1])):
        mean, sem = mean_and_sem(values)
        assert summary[name] == pytest.approx(mean, rel=1e-12)
        assert summary[f"{name}_err"] == pytest.approx(sem, rel=1e-9)


def test_the_velocity_histogram_of_a_small_population_has_the_bath_temperature():
    """At λ = 0 the members are bath particles: the histogram's temperature is 1 at any
    N_c. Its snapshots (one a block) were weighted by the step, which shrinks while a fast
    member raises the bound: about -0.28/N_c (0.972 at N_c = 10, 0.934 at 2). Within
    Student's band of its 64 realizations' error and the bins' w²/12."""
    from kinetic.analysis.checks import tolerance_factor
    from kinetic.analysis.statistics import mean_and_sem

    small = {"lam": 0.0, "population": 10, "duration": 400.0, "n_blocks": 400}
    ds = simulate(**{**SMALL, **small, "n_realizations": 64})
    v = ds.velocity.values
    width = float(v[1] - v[0])
    temperature, error = mean_and_sem((ds.velocity_density.values * v**2).sum(axis=1) * width)
    assert abs(temperature - 1.0) < tolerance_factor(4, 63) * error + width**2 / 12
    assert ds.attrs["diversity_collapse"] == 0  # 10 members, none cloned: no collapse


def test_a_population_still_relaxing_after_its_transient_is_reported(caplog):
    """Hard disks at λ = 3 after the shortest transient the front allows (one kept
    collision a member): T in the first half of the measured time lies 4.0 errors above
    the second's, reported as a drift; after a transient of 300 mean free times both
    halves agree (0.2 errors)."""
    import logging

    run = {**SMALL, "lam": 3.0, "population": 500, "duration": 20.0, "n_blocks": 10}
    run |= {"n_realizations": 16, "seed": 5}
    with caplog.at_level(logging.WARNING, logger="kinetic"):
        short = simulate(**run | {"transient": 28.41})
        long = simulate(**run | {"transient": 300.0})
    assert short.attrs["drift_z_temperature"] > 3.5
    assert abs(long.attrs["drift_z_temperature"]) < 2 and abs(long.attrs["drift_z_mu"]) < 2
    assert "a longer transient is safer" in caplog.text
    assert caplog.text.count("a longer transient is safer") == 1


@pytest.mark.parametrize(
    ("distinct", "population", "collapsed"),
    [
        (1, 2, True),
        (2, 2, False),
        (1, 3, True),
        (2, 4, False),
        (4, 10, True),
        (5, 10, False),
        (29, 1000, True),
        (30, 1000, False),
        (1, 10**6, True),
    ],
)
def test_one_velocity_left_is_a_collapse_at_any_size(distinct, population, collapsed):
    """Fewer distinct velocities than the larger of 10 and 3 % of the members, and than
    half of them, or a single one (two members with one velocity passed before)."""
    from kinetic.cloning.front import is_collapsed

    assert is_collapsed(distinct, population) is collapsed
