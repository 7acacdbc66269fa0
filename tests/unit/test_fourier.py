"""kinetic.fourier: cos and sin of 2πu without libm, which both costantini2010 engines'
mode observers use (their sums are checked against numpy's complex exponentials in
test_edmd_cooling_front.py and test_dsmc_inhomogeneous_front.py)."""

import numpy as np
import pytest
from numba import njit

from kinetic.fourier import cos_sin_turns, mode_sums, mode_terms
from kinetic.jit import FLAGS

EXTENDED = np.finfo(np.longdouble).eps < 1e-18


@njit(**{**FLAGS, "cache": False})
def _turns(u, cosine, sine):
    for i in range(u.shape[0]):
        cosine[i], sine[i] = cos_sin_turns(u[i])


def _reference(u):
    """cos 2πu and sin 2πu in x87 extended precision (64-bit significand): u − round(u)
    is exact, the angle and the functions round at 5e-20."""
    turns = u.astype(np.longdouble)
    reduced = turns - np.floor(turns + np.longdouble(0.5))
    angle = 8 * np.arctan(np.longdouble(1)) * reduced
    return np.cos(angle), np.sin(angle)


@pytest.mark.skipif(not EXTENDED, reason="numpy's long double is not x87 extended here")
def test_cos_sin_turns_is_within_two_ulp_of_the_exact_values():
    """Every octant and its edges (k/8 and its neighbours a few ulp away), negative u,
    u far from 0 (positions of a box side L, 10³ L) and 2 × 10⁵ random u: the error is at
    most 2 ulp of 1 (4.4e-16; 2.4e-16 measured), where a polynomial one term short is off
    by 2e-14 and a quadrant sign or swap by order 1."""
    edges = np.arange(-24, 25) / 8.0
    u = np.concatenate(
        [
            edges,
            np.nextafter(edges, np.inf),
            np.nextafter(edges, -np.inf),
            np.random.default_rng(1).uniform(-3.0, 3.0, 200_000),
            np.random.default_rng(2).uniform(-1e3, 1e3, 20_000),
        ]
    )
    cosine, sine = np.empty_like(u), np.empty_like(u)
    _turns(u, cosine, sine)
    exact_cosine, exact_sine = _reference(u)
    assert float(np.max(np.abs(cosine - exact_cosine))) <= 2 * np.spacing(1.0)
    assert float(np.max(np.abs(sine - exact_sine))) <= 2 * np.spacing(1.0)


def test_cos_sin_turns_is_exact_at_the_quarter_turns():
    u = np.array([0.0, 0.25, 0.5, 0.75, 1.0, -0.25, -0.5, 7.0, -3.75])
    cosine, sine = np.empty_like(u), np.empty_like(u)
    _turns(u, cosine, sine)
    np.testing.assert_array_equal(cosine, [1, 0, -1, 0, 1, 0, -1, 1, 0])
    np.testing.assert_array_equal(sine, [0, 1, 0, -1, 0, -1, 0, 0, 1])


@njit(**{**FLAGS, "cache": False})
def _modes(x, y, wx, wy, inverse_side, terms):
    for i in range(x.shape[0]):
        terms[0, i], terms[1, i], terms[2, i], terms[3, i] = mode_terms(
            inverse_side * x[i], inverse_side * y[i], wx[i], wy[i]
        )
    return mode_sums(terms, x.shape[0])


def test_the_mode_sums_are_the_complex_exponential_sums():
    """Σ w_y e^{ikx} and Σ w_x e^{iky} (k = 2π/L) of 500 particles, against numpy's
    complex exponentials (which round k x, up to 2π, and the sum in another order)."""
    rng = np.random.default_rng(3)
    side = 37.5
    x, y = rng.uniform(0.0, side, (2, 500))
    wx, wy = rng.normal(size=(2, 500))
    terms = np.empty((4, 500))
    re_y, im_y, re_x, im_x = _modes(x, y, wx, wy, 1.0 / side, terms)
    k = 2 * np.pi / side
    np.testing.assert_allclose(re_y + 1j * im_y, np.sum(wy * np.exp(1j * k * x)), atol=1e-12)
    np.testing.assert_allclose(re_x + 1j * im_x, np.sum(wx * np.exp(1j * k * y)), atol=1e-12)
