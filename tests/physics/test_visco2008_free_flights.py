"""visco2008 Eqs. (6)-(16), (A1)-(A8), (B4), (D3)-(D4): distributions and their limits."""

import numpy as np
import pytest
from scipy import integrate

from kinetic.theory import visco2008


def _moments(pdf, upper=np.inf):
    norm = integrate.quad(lambda x: float(pdf(np.array([x]))[0]), 0, upper, limit=200)[0]
    mean = integrate.quad(lambda x: x * float(pdf(np.array([x]))[0]), 0, upper, limit=200)[0]
    return norm, mean


@pytest.mark.parametrize("d", [2, 3])
def test_exact_densities_are_normalised(d):
    norm, mean = _moments(lambda t: visco2008.free_flight_time_pdf(t, d))
    assert norm == pytest.approx(1, abs=1e-9)
    assert mean == pytest.approx(1, abs=1e-9)  # (A3): mean free time 1/ω
    norm, mean = _moments(lambda x: visco2008.free_path_pdf(x, d))
    assert norm == pytest.approx(1, abs=1e-9)
    norm, mean = _moments(lambda x: visco2008.maxwell_free_path_pdf(x, d))
    assert norm == pytest.approx(1, abs=1e-9)
    assert mean == pytest.approx(1, abs=1e-8)  # lengths in mean free paths
    norm, mean = _moments(lambda t: visco2008.vhp_free_flight_time_pdf(t, d))
    assert norm == pytest.approx(1, abs=1e-9)
    assert mean == pytest.approx(1, abs=1e-9)
    norm, _ = _moments(lambda t: visco2008.weighted_free_flight_time_pdf(t, d))
    assert norm == pytest.approx(1, abs=1e-9)


@pytest.mark.parametrize("d", [2, 3])
def test_collision_frequency_is_the_maxwell_average_of_r(d):
    assert visco2008.rate_moment(1, d) == pytest.approx(1, abs=1e-10)
    assert visco2008.collision_rate(0.0, d) == pytest.approx(1 / np.sqrt(2))


def test_collision_frequency_eq_7_in_2d_is_enskog():
    assert visco2008.collision_frequency(2, 0.01) == pytest.approx(2 * np.sqrt(np.pi) * 0.01)


@pytest.mark.parametrize("d", [2, 3, 7])
def test_kummer_form_is_stable_and_has_the_eq_15_slope(d):
    v = np.array([10.0, 1e2, 1e3, 1e4])
    rate = visco2008.collision_rate(v, d)
    assert np.all(np.isfinite(rate))
    slope = rate / v * visco2008.mean_free_path(d)  # r/v in units of 1/l
    np.testing.assert_allclose(slope[-1], visco2008.free_path_decay_rate(d), rtol=1e-6)


def test_large_d_form_eq_12_approaches_eq_6():
    errors = []
    for d in (10, 40, 160, 640):
        v = np.sqrt(2 * d) * np.linspace(0.0, 2.0, 9)  # speeds on the scale sqrt(2 T0 d)
        exact = visco2008.collision_rate(v, d)
        errors.append(np.max(np.abs(visco2008.collision_rate_large_d(v, d) / exact - 1)))
    assert errors[0] > errors[1] > errors[2] > errors[3]
    assert errors[3] < 5e-4  # O(1/d)
    # Eq. (12) as printed, v²/(2 T0 d), stays 25 % off at v = 2 sqrt(2 d): a typo
    v, d = 2 * np.sqrt(2 * 640), 640
    printed = np.sqrt(1 + v * v / (2 * d)) / np.sqrt(2)
    assert abs(printed / visco2008.collision_rate(v, d) - 1) > 0.2


@pytest.mark.parametrize("d", [2, 3])
def test_large_time_forms_eq_11_and_a8(d):
    # asymptotic expansions: the relative error falls at least like 1/t
    t = np.array([200.0, 800.0])
    exact = np.exp(visco2008.log_free_flight_time_pdf(t, d))
    error = np.abs(visco2008.free_flight_time_pdf_asymptotic(t, d) / exact - 1)
    assert error[1] < error[0] / 3 and error[1] < 2e-3
    weighted = visco2008.weighted_free_flight_time_pdf(t, d)
    error = np.abs(visco2008.weighted_free_flight_time_pdf_asymptotic(t, d) / weighted - 1)
    assert error[1] < error[0] / 3 and error[1] < 2e-3


def test_log_density_has_no_underflow_at_huge_times():
    log_pdf = visco2008.log_free_flight_time_pdf(np.array([2000.0]), 2)[0]
    assert np.isfinite(log_pdf)
    # Eq. (11) at d = 2: log[(1/2) (t/(2√2))^{-1}] - t/√2
    expected = -2000 / np.sqrt(2) + np.log(0.5 / (2000 / np.sqrt(2) / 2))
    assert log_pdf == pytest.approx(expected, abs=0.01)


def test_free_path_tail_eq_16():
    # dominant exponential -x/(√2 l) with algebraic corrections that fade slowly
    x = np.array([50.0, 100.0, 200.0, 400.0, 800.0])
    log_pdf = np.log(visco2008.free_path_pdf(x, 2))
    slopes = np.diff(log_pdf) / np.diff(x)
    assert np.all(np.diff(slopes) > 0) and np.all(slopes < -1 / np.sqrt(2))
    assert slopes[-1] == pytest.approx(-1 / np.sqrt(2), rel=0.03)


def test_maxwell_free_path_asymptote_d4():
    x = np.array([30.0, 100.0])
    ratio = visco2008.maxwell_free_path_pdf_asymptotic(x, 2) / visco2008.maxwell_free_path_pdf(x, 2)
    assert abs(ratio[1] - 1) < abs(ratio[0] - 1) < 0.05
