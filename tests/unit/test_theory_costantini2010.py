"""kinetic.theory.costantini2010: the reconstruction's table, exact limits, the stability
bound, the extraction formulas, and the elastic viscosity beyond first Sonine."""

import math

import numpy as np
import pytest

from kinetic.theory import costantini2010 as theory

# costantini2010.md, "Theory curves": α, a2 (vNE), ζ*, ν*, ν̄* (white), ν̄*/ν*, L_c/ℓ, max N nσ²
TABLE = [
    (0.9, -0.0269, 0.2369, 0.2046, 0.2093, 1.023, 8.26, 68.2),
    (0.8, -0.0219, 0.4493, 0.2108, 0.2278, 1.080, 6.09, 37.0),
    (0.7, +0.0022, 0.6395, 0.2183, 0.2543, 1.165, 5.19, 27.0),
    (0.6, +0.0387, 0.8079, 0.2273, 0.2892, 1.272, 4.71, 22.2),
    (0.5, +0.0829, 0.9546, 0.2380, 0.3335, 1.401, 4.44, 19.7),
]


@pytest.mark.parametrize("row", TABLE)
def test_the_reconstructions_table(row):
    alpha, a2, zeta, nu, nu_bar, ratio, critical, most = row
    assert float(theory.a2_van_noije_ernst(alpha)) == pytest.approx(a2, abs=5e-5)
    assert float(theory.zeta_star(alpha)) == pytest.approx(zeta, abs=5e-5)
    assert float(theory.nu_star(alpha)) == pytest.approx(nu, abs=5e-5)
    assert float(theory.nu_bar_star_white(alpha)) == pytest.approx(nu_bar, abs=5e-5)
    assert float(theory.fdr_ratio_white(alpha)) == pytest.approx(ratio, abs=5e-4)
    assert float(theory.critical_length(alpha)) == pytest.approx(critical, abs=5e-3)
    assert float(theory.max_n_density(alpha)) == pytest.approx(most, abs=0.05)


def test_elastic_limit():
    assert float(theory.nu_star(1.0)) == pytest.approx(1.0 / (2.0 * math.sqrt(2.0 * math.pi)))
    assert float(theory.nu_star(1.0)) == pytest.approx(0.19947, abs=5e-6)
    assert float(theory.zeta_star(1.0)) == 0.0
    assert float(theory.fdr_ratio_white(1.0)) == 1.0
    assert math.isinf(float(theory.critical_length(1.0)))
    assert float(theory.zeta_star(1.0 - 1e-9)) == pytest.approx(0.0, abs=1e-8)
    assert theory.drag_rate(1.0, 0.005) == 0.0


def test_stability_bound_refuses_large_boxes_with_the_bound():
    theory.check_stable(3000, 0.005, 0.5)  # N nσ² = 15 < 19.7
    with pytest.raises(ValueError, match=r"L_c = 4\.44"):
        theory.check_stable(3000, 0.01, 0.5)  # N nσ² = 30 > 19.7
    assert math.isinf(float(theory.correlation_time(0.5, 3000, 0.01)))


def test_extraction_formulas_invert_the_prediction():
    for alpha, n in ((1.0, 1000), (0.8, 2000), (0.6, 3000)):
        k_star = theory.reduced_wavenumber(n, 0.005)
        tau_c = theory.correlation_time(alpha, n, 0.005)
        amplitude = theory.correlation_amplitude(alpha, n, 0.005)
        zeta = theory.zeta_star(alpha)
        assert theory.nu_star_from_fit(tau_c, zeta, k_star) == pytest.approx(theory.nu_star(alpha))
        assert theory.nu_bar_star_from_fit(amplitude, tau_c, k_star) == pytest.approx(
            theory.nu_bar_star_white(alpha)
        )


def test_the_wavenumber_and_correlation_time_are_the_documents():
    """Literals, not the module's own functions: k* = kℓ = 2π/√(N nσ²) with Brey's ℓ =
    1/(nσ) (costantini2010.md, item 8), and Eq. 9's τ_c from the table's rounded ν* and ζ*
    at α = 0.8, N = 2000, nσ² = 0.005 (their rounding: 3 × 10⁻⁴ of τ_c). Every ν* and ν̄*
    the analysis extracts scales as 1/k*²."""
    assert float(theory.reduced_wavenumber(1000, 0.005)) == pytest.approx(2 * math.pi / 5**0.5)
    k2 = 4 * math.pi**2 / (2000 * 0.005)
    assert float(theory.correlation_time(0.8, 2000, 0.005)) == pytest.approx(
        1 / (0.2108 * k2 - 0.4493 / 2), rel=1e-3
    )
    assert float(theory.correlation_time(0.8, 2000, 0.005)) == pytest.approx(1.6459, abs=1e-3)


def test_coloured_noise_raises_the_tail_amplitude():
    factor = theory.coloured_noise_amplitude(np.array([1.0, 0.8, 0.6]), 2000, 0.005)
    assert np.all(factor > 1.0)
    # by hand from costantini2010.md at α = 0.8 (a2 = −0.0219): ν_η† = (3/8)(1.5333)(1.8)
    # (1 + 0.0219/32) = 1.03571, ζ† = (1/2)(0.36)(1 − 3 × 0.0219/16) = 0.17926, in v_s/ℓ
    # (× √(2π)) γ = ν_η* − ζ* = 2.5961 − 0.4493 = 2.1468 (the stress noise's rate, not
    # ν_η* − ζ*/2) and λ = ν* k*² − ζ*/2 = 0.6076: γ²/(γ² − λ²) = 1.0871
    assert float(factor[1]) == pytest.approx(1.0871, abs=2e-4)
    # a larger system decays more slowly, closer to white noise
    assert theory.coloured_noise_amplitude(0.8, 3000, 0.005) < theory.coloured_noise_amplitude(
        0.8, 1000, 0.005
    )


def test_drag_rate_balances_the_first_sonine_cooling_at_the_initial_temperature():
    # ζ(T0) = ζ* v0/ℓ with v0 = √2, ℓ = 1/n; ω0 = ζ/2
    assert theory.drag_rate(0.8, 0.005) == pytest.approx(
        0.4493 * math.sqrt(2) * 0.005 / 2, rel=1e-4
    )
    assert theory.drag_rate(0.8, 0.005, a2="montanero") != theory.drag_rate(0.8, 0.005)
    with pytest.raises(ValueError, match="a2"):
        theory.drag_rate(0.8, 0.005, a2="sonine")


def test_sonine_viscosity_second_order_is_exact_in_two_and_three_dimensions():
    # independent checks: the second Sonine approximation is 1 + 1/50 for hard disks and
    # Chapman and Cowling's 1 + 3/202 for hard spheres
    assert theory.viscosity_sonine_ratio(1, 2) == pytest.approx(1.0, abs=1e-12)
    assert theory.viscosity_sonine_ratio(2, 2) == pytest.approx(1.0 + 1.0 / 50.0, abs=1e-12)
    assert theory.viscosity_sonine_ratio(2, 3) == pytest.approx(1.0 + 3.0 / 202.0, abs=1e-12)


def test_sonine_viscosity_converges_for_hard_disks():
    ratios = [theory.viscosity_sonine_ratio(order, 2) for order in range(1, 9)]
    steps = np.diff(ratios)
    assert np.all(steps > 0)  # a variational sequence: each order raises η
    assert np.all(steps[1:] < steps[:-1])
    assert steps[-1] < 2e-6
    # the converged hard-disk factor to the three digits Gass gives (J. Chem. Phys. 54,
    # 1898 (1971): η = 1.022 η of the first Sonine approximation), the last digit's half
    assert ratios[-1] == pytest.approx(1.022, abs=5e-4)
    assert theory.nu_star_elastic() == pytest.approx(
        1.022 / (2.0 * math.sqrt(2.0 * math.pi)), abs=1e-4
    )


def _cell_collision_transfer(dimension, alpha, samples, rng, shear=0.1):
    """Monte Carlo of one DSMC cell of unit side across the linear flow u_x = shear y:
    Maxwellian pairs (T = m = 1) at independent uniform positions, the line of centres
    uniform on the sphere, each pair weighted by the acceptance |g·σ̂| of hard particles
    and kicked by −(1 + α)/2 (g·σ̂)σ̂. Returns the mean of Δp1x Δy over the collisions in
    units of shear ⟨Δy²⟩ = shear/6, with its standard error: minus the collisional
    transfer. The same pairs without the flow are subtracted (their mean is zero), which
    leaves only the part linear in the flow."""
    velocity = rng.normal(size=(2, samples, dimension))
    height = rng.uniform(-0.5, 0.5, size=(2, samples))
    separation = height[0] - height[1]
    normal = rng.normal(size=(samples, dimension))
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    values = []
    for rate in (shear, 0.0):
        relative = velocity[0] - velocity[1]
        relative[:, 0] += rate * separation
        approach = np.sum(relative * normal, axis=1)
        weight = np.abs(approach)
        kick = -(1.0 + alpha) / 2.0 * approach * normal[:, 0]
        values.append(weight * kick * separation / weight.mean())
    flow_part = (values[0] - values[1]) / (shear / 6.0)
    return flow_part.mean(), flow_part.std(ddof=1) / math.sqrt(samples)


@pytest.mark.parametrize("dimension", [2, 3])
@pytest.mark.parametrize("alpha", [1.0, 0.8, 0.0])
def test_collisional_transfer_matches_a_monte_carlo_of_one_cell(dimension, alpha):
    # the factor 1 + 1/d of the acceptance ∝ |g| is 50 or 33 % of the answer; the
    # Monte Carlo resolves it to 0.5 %
    rng = np.random.default_rng(20 + dimension + int(10 * alpha))
    estimate, error = _cell_collision_transfer(dimension, alpha, 200_000, rng)
    expected = float(theory.collisional_transfer(alpha, dimension))
    assert abs(-estimate - expected) < 4.0 * error
    assert abs(-estimate - expected * dimension / (dimension + 1)) > 20.0 * error


def test_cell_viscosity_of_elastic_spheres_is_alexander_garcia_and_alder_s():
    # Δν/ν0 = transfer ν_c Δx²/12 with ν_c/ν0 = 32/(5π λ²) for first-Sonine hard spheres
    assert float(theory.collisional_transfer(1.0, 3)) * 32.0 / (5.0 * math.pi) / 12.0 == (
        pytest.approx(16.0 / (45.0 * math.pi), rel=1e-12)
    )


def test_cell_viscosity_scales_as_the_squared_cell_side_and_vanishes_in_one_cell():
    # leading order: Δν* = (1 + α)√(2π)Δx*²/24 for cells much smaller than the mode (F → 1)
    n_particles, density = 2000, 0.005
    for cells in (400, 4000):
        spacing_sq = n_particles * density / cells**2
        leading = theory.dsmc_cell_viscosity(0.8, n_particles, density, cells, flattened=False)
        assert float(leading) == pytest.approx(
            1.8 * math.sqrt(2.0 * math.pi) * spacing_sq / 24.0, rel=1e-4
        )
    # nine cells a side of N = 2000 (0.99 mean free paths): the longest mode spans nine
    # cells, F = 12(1 − sinc²(π/9))/(2π/9)² = 0.984 of the square law
    half_phase = math.pi / 9.0
    finite_mode = 12.0 * (1.0 - (math.sin(half_phase) / half_phase) ** 2) / (2 * half_phase) ** 2
    assert finite_mode == pytest.approx(0.984, abs=5e-4)
    leading = 1.8 * math.sqrt(2.0 * math.pi) * 10.0 / 81.0 / 24.0 * finite_mode
    coarse = theory.dsmc_cell_viscosity(0.8, n_particles, density, 9, flattened=False)
    assert float(coarse) == pytest.approx(leading, rel=1e-12)
    # the flattened flow inside the cells: the model's factor at Δx/λ = 2√2 √10/9
    flattened = theory.dsmc_cell_viscosity(0.8, n_particles, density, 9)
    side = 2.0 * math.sqrt(2.0) * math.sqrt(10.0) / 9.0
    assert float(flattened) == pytest.approx(leading * float(theory.in_cell_flow(0.8, side)))
    assert float(theory.dsmc_cell_viscosity(1.0, 1000, density, 1)) == 0.0
    # arrays of cells, as the scalars give
    many = theory.dsmc_cell_viscosity(0.8, n_particles, density, np.array([1, 9, 18]))
    singles = [float(theory.dsmc_cell_viscosity(0.8, n_particles, density, m)) for m in (1, 9, 18)]
    assert many.tolist() == pytest.approx(singles, rel=1e-12)
    with pytest.raises(ValueError, match="dimension"):
        theory.collisional_transfer(1.0, 4)


def _in_cell_flow_by_quadrature(alpha, side, harmonics=60):
    """The same sum with each flight factor K_m = ∫e^{−u − a u²}du by quadrature, and the
    harmonics beyond ``harmonics`` from their asymptote K_m ≈ Δx/(4mλ) (ζ(3)'s tail)."""
    from scipy.integrate import quad
    from scipy.special import zeta

    kappa = (1.0 + alpha) / 2.0
    total = 0.0
    for m in range(1, harmonics + 1):
        a = 4.0 * math.pi * m**2 / side**2
        flights = quad(lambda u, a=a: math.exp(-u - a * u * u), 0.0, math.inf)[0]
        total += flights / (m**2 * (1.0 - (1.0 - kappa) * flights))
    tail = side / 4.0 * (zeta(3.0) - sum(1.0 / m**3 for m in range(1, harmonics + 1)))
    return 1.0 - 6.0 / math.pi**2 * kappa * (total + tail)


@pytest.mark.parametrize("alpha", [1.0, 0.8])
def test_in_cell_flow_matches_its_sum_by_quadrature_and_its_small_cell_limit(alpha):
    sides = [0.25, 0.5, 1.0, 2.24]
    factors = [float(theory.in_cell_flow(alpha, side)) for side in sides]
    for side, factor in zip(sides, factors, strict=True):
        assert factor == pytest.approx(_in_cell_flow_by_quadrature(alpha, side), abs=1e-5)
    assert all(0.0 < f < 1.0 for f in factors) and factors == sorted(factors, reverse=True)
    # b → 1 − (3ζ(3)/(2π²)) κ Δx/λ as the cell shrinks (κ = (1 + α)/2)
    slope = 3.0 * 1.2020569031595942 / (2.0 * math.pi**2) * (1.0 + alpha) / 2.0
    assert (1.0 - float(theory.in_cell_flow(alpha, 1e-3))) / 1e-3 == pytest.approx(slope, rel=2e-3)
