"""visco2008 Table I theory rows, Eq. (50) and (A6)-(A7): closures against the document."""

import numpy as np
import pytest

from kinetic.theory import visco2008


def test_a6_a7_moments_of_the_collision_rate_in_2d():
    second = visco2008.rate_moment(2, 2)
    third = visco2008.rate_moment(3, 2)
    assert second == pytest.approx(1.06354, abs=5e-6)  # (A6), printed to 6 digits
    assert third / second == pytest.approx(1.13962, abs=5e-6)  # (A7)


def test_gaussian_row_is_1_1125_112890625():
    np.testing.assert_allclose(visco2008.gaussian_cumulants(), [1, 1.125, 1.12890625], atol=1e-7)


@pytest.mark.parametrize("d", [2, 3])
def test_solved_sonine_closure_reproduces_eq_50(d):
    # the λ-derivatives of the numerically solved closure against the closed form (50)
    solved = visco2008.sonine_cumulants_numerical(d)
    np.testing.assert_allclose(solved, visco2008.sonine_cumulants(d), atol=1e-7)


def test_sonine_row_values_of_the_document():
    np.testing.assert_allclose(visco2008.sonine_cumulants(2), [1, 1.13778, 1.10733], atol=5e-6)
    # d = 3 from Eq. (50): 9/64 (8 + 1/15) and the rational third cumulant
    np.testing.assert_allclose(visco2008.sonine_cumulants(3)[1], 9 / 64 * (8 + 1 / 15))
    assert visco2008.sonine_cumulants(3)[2] == pytest.approx(1.1032510, abs=1e-6)
