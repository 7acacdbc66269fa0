"""Exact clothes-pin densities of krauth2025 §4.4.1 (Eqs. 4.6, 4.7 and the ring mapping)."""

import numpy as np
import pytest
from scipy.integrate import quad

from kinetic.theory import krauth2025 as theory


@pytest.mark.parametrize(("n", "length"), [(1, 3.0), (2, 5.0), (15, 20.0), (15, 40.0), (40, 41.0)])
def test_pin_density_is_a_normalised_symmetric_density(n, length):
    sigma = 0.5
    # Eq. 4.7 is a polynomial between kinks at multiples of 2 sigma from the posts
    kinks = np.arange(sigma, length - sigma, 2 * sigma)
    total = sum(
        quad(lambda x: float(theory.pin_density(x, n, length, sigma)), a, b)[0]
        for a, b in zip(kinks, [*kinks[1:], length - sigma], strict=True)
    )
    assert total == pytest.approx(1.0, rel=1e-9)
    x = np.linspace(sigma, length - sigma, 101)
    np.testing.assert_allclose(
        theory.pin_density(x, n, length, sigma),
        theory.pin_density(length - x, n, length, sigma),
        rtol=1e-10,
        atol=1e-14,
    )
    assert theory.pin_density(0.9 * sigma, n, length, sigma) == 0.0


def test_two_pins_by_hand():
    """N = 2: pin 1 at x leaves pin 2 the line [σ, L − σ] minus (x − 2σ, x + 2σ)."""
    sigma, length = 0.5, 4.0
    x = np.linspace(sigma, length - sigma, 41)
    blocked = np.minimum(x + 2 * sigma, length - sigma) - np.maximum(x - 2 * sigma, sigma)
    by_hand = (length - 2 * sigma - blocked) / theory.partition_function(2, length, sigma)
    np.testing.assert_allclose(theory.pin_density(x, 2, length, sigma), by_hand, atol=1e-12)


def test_wall_density_is_about_four_times_the_bulk():
    """The lecture's N = 15 pins of width 1 on L = 20: "4 times larger than in the bulk";
    at the post π(σ) = 1/(L − 2Nσ) exactly (every other pin to the right)."""
    n, length, sigma = 15, 20.0, 0.5
    wall = theory.pin_density(sigma, n, length, sigma)
    assert wall == pytest.approx(1.0 / (length - 2 * n * sigma), rel=1e-12)
    centre = theory.pin_density(length / 2, n, length, sigma)
    assert 3.8 < wall / centre < 4.1


def test_partition_function_and_limits():
    assert theory.partition_function(3, 10.0, 0.5) == pytest.approx(7.0**3)
    assert theory.partition_function(3, 3.0, 0.5) == 0.0
    # one pin: uniform on [σ, L − σ]
    np.testing.assert_allclose(theory.pin_density([0.5, 2.0, 3.5], 1, 4.0, 0.5), 1 / 3.0)


def test_ring_pair_density():
    """Integrates to N − 1; for N = 2 the other pin is uniform on [2σ, L − 2σ]."""
    sigma = 0.5
    r = np.linspace(0, 6.0, 601)
    two = theory.ring_pair_density(r, 2, 6.0, sigma)
    inside = (r > 2 * sigma) & (r < 6.0 - 2 * sigma)
    np.testing.assert_allclose(two[inside], 1 / (6.0 - 4 * sigma))
    assert np.all(two[r < 2 * sigma - 1e-12] == 0)
    edges = np.linspace(0, 20.0, 401)
    averages = theory.bin_average(lambda z: theory.ring_pair_density(z, 15, 20.0, sigma), edges)
    assert averages.sum() * 0.05 == pytest.approx(14.0, rel=1e-6)


@pytest.mark.parametrize(
    ("n", "length", "sigma", "message"),
    [
        (0, 5.0, 0.5, "n_pins"),
        (3, 3.0, 0.5, "cannot hold"),
        (3, 5.0, 0.0, "sigma"),
        (2.5, 5, 0.5, "n_pins"),
    ],
)
def test_bad_arguments_are_refused(n, length, sigma, message):
    with pytest.raises(ValueError, match=message):
        theory.pin_density(1.0, n, length, sigma)


@pytest.mark.parametrize("n", [1, 4, 20])
def test_eqs_4_13_and_4_14_against_sampled_velocities(n):
    """Velocities uniform on the sphere Σ v² = R² in 2N dimensions (normalised Gaussians);
    averages over wall collisions weigh a component by its flux |v_x|, over pair
    collisions the relative normal velocity (here along x: v_x of disk 1 minus v_x of
    disk 2) by its flux. Each average within 4.5 standard errors of the formulas; the
    printed (4.14a) is far off."""
    rng = np.random.default_rng(41)
    radius = 2.5
    samples = 400_000
    v = rng.standard_normal((samples, 2 * n))
    v *= radius / np.linalg.norm(v, axis=1, keepdims=True)

    def weighted(values, weights):
        ratio = values * weights
        mean = ratio.mean() / weights.mean()
        # delta method for the ratio of means
        error = np.std(ratio - mean * weights, ddof=1) / (weights.mean() * np.sqrt(samples))
        return mean, error

    component = np.abs(v[:, 0])
    wall = theory.wall_speed_averages(n, radius)
    for values, expected in ((1 / component, wall["inverse"]), (component, wall["mean"])):
        mean, error = weighted(values, component)
        assert abs(mean - expected) < 4.5 * error
    if n >= 2:
        relative = np.abs(v[:, 0] - v[:, 2])  # Δv⊥ along x of disks 1 and 2
        pair = theory.pair_speed_averages(n, radius)
        for values, expected in ((1 / relative, pair["inverse"]), (relative, pair["mean"])):
            mean, error = weighted(values, relative)
            assert abs(mean - expected) < 4.5 * error
        mean, error = weighted(1 / relative, relative)
        assert abs(mean - pair["inverse_printed"]) > 50 * error


def test_figure_curves_hold_every_pin_on_the_samplers_bins():
    """The exact curves the figures draw (theory rule): N pins on the line and N - 1 other
    pins around the ring, bin by bin on the samplers' bins; the naive-pin acceptance is
    Eq. 4.6 and tends to 1 as the pins shrink."""
    line = theory.line_dataset(10, 40.0, 1.0, bins=76)
    width = np.diff(line["bin_edges"].values)
    assert np.sum(line["density_exact"].values * width) == pytest.approx(10.0, rel=1e-6)
    assert line["x"].values[0] == pytest.approx(1.0 + 0.5 * width[0])
    assert float(line["acceptance_exact"]) == pytest.approx((20.0 / 38.0) ** 10)
    ring = theory.ring_dataset(8, 30.0, 1.0, bins=60)
    width = np.diff(ring["bin_edges"].values)
    assert np.sum(ring["pair_density_exact"].values * width) == pytest.approx(7.0, rel=1e-6)
    # no other pin within one pin width (2 sigma) of a pin
    assert np.all(ring["pair_density_curve"].values[ring["r_curve"].values < 1.999] == 0.0)
