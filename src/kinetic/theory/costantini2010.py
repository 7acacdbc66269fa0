"""costantini2010: first-Sonine hydrodynamics of the transverse mode of the cooling gas.

d = 2 inelastic hard disks, m = σ = 1. Reduced units of the document: lengths in
ℓ = 1/(nσ), times in ℓ/v_s with v_s = √(2T_s/m); then ν* = ν/(ℓ v_s), ν̄* = ν̄/(ℓ v_s),
ζ* = ζℓ/v_s and k* = kℓ = 2π/√(N nσ²) for the longest transverse mode k = 2π/L.
Equation numbers are those of the reconstruction (``costantini2010.md``); confidence
labels there: TEXT, RECON-H (high), RECON-M (form right, prefactors may differ).

The first Sonine approximation of Brey, Dufty, Kim and Santos (PRE 58, 4638, 1998) gives,
in units of ν0 = nT/η0 (η0 = ((d+2)/8) Γ(d/2) π^{-(d-1)/2} √(mT)/σ^{d-1}, the elastic
first-Sonine shear viscosity), ν_η† = (3/(4d))(1 − α + 2d/3)(1 + α)(1 − a2/32) and
ζ† = ((d+2)/(4d))(1 − α²)(1 + 3a2/16). In d = 2, ν0 = 2√π n √T, i.e. √(2π) in units of
v_s/ℓ: every rate† times √(2π) is the same rate in the document's units.
"""

from __future__ import annotations

import functools
import logging
import math

import numpy as np

from kinetic import gas

__all__ = [
    "MIN_LAGS",
    "a2_montanero",
    "a2_van_noije_ernst",
    "check_stable",
    "collisional_transfer",
    "coloured_noise_amplitude",
    "correlation_amplitude",
    "correlation_time",
    "critical_length",
    "drag_rate",
    "fdr_ratio_coloured",
    "fdr_ratio_white",
    "heated_temperature",
    "in_cell_flow",
    "max_n_density",
    "mean_free_path",
    "mean_free_time",
    "nu_bar_star_from_fit",
    "nu_bar_star_white",
    "nu_eta_dagger",
    "nu_star",
    "nu_star_elastic",
    "nu_star_from_fit",
    "reduced_wavenumber",
    "viscosity_sonine_ratio",
    "warn_if_unstable",
    "zeta_dagger",
    "zeta_star",
]

MIN_LAGS = 3
"""Fewest lags of C a run's analysis takes (``kinetic.analysis.costantini2010``): a block
of a realization needs twice as many samples."""


def mean_free_time(density: float) -> float:
    """1/ω_c of hard disks at T0 = 1 in engine time units σ√(m/T0): ω_c = 2nσ√(πT0/m)."""
    return 1.0 / gas.equilibrium_collision_frequency("hard_spheres", 2, density)


def mean_free_path(density: float) -> float:
    """λ = 1/(2√2 nσ) of hard disks, in σ."""
    return gas.mean_free_path(2, density)


DIMENSION = 2
RATE_UNIT = math.sqrt(2.0 * math.pi)
"""ν0 = nT/η0 in units of v_s/ℓ (d = 2)."""


def a2_van_noije_ernst(alpha, dimension: int = DIMENSION):
    """a2 of the homogeneous cooling state, van Noije and Ernst (Eq. 13, RECON-H):
    16(1−α)(1−2α²)/(9 + 24d − α(41 − 8d) + 30(1−α)α²)."""
    alpha = np.asarray(alpha, dtype=float)
    d = dimension
    return (
        16.0
        * (1.0 - alpha)
        * (1.0 - 2.0 * alpha**2)
        / (9.0 + 24.0 * d - alpha * (41.0 - 8.0 * d) + 30.0 * (1.0 - alpha) * alpha**2)
    )


def a2_montanero(alpha, dimension: int = DIMENSION):
    """a2 of montanero2007's Eq. (2.16) (the estimate that paper calls excellent)."""
    from kinetic.theory.montanero2007 import hcs_a2

    return hcs_a2(np.asarray(alpha, dtype=float), dimension)


A2 = {"van_noije_ernst": a2_van_noije_ernst, "montanero": a2_montanero}
"""The two a2 estimates by name (the config key ``a2``)."""


def _a2(alpha, a2):
    if a2 is None:
        return a2_van_noije_ernst(alpha)
    if isinstance(a2, str):
        if a2 not in A2:
            raise ValueError(f"a2 = {a2!r} is not allowed: must be one of {sorted(A2)}")
        return A2[a2](alpha)
    return np.asarray(a2, dtype=float)


def nu_eta_dagger(alpha, a2=None):
    """ν_η† = (3/(4d))(1 − α + 2d/3)(1 + α)(1 − a2/32), in units of ν0."""
    alpha = np.asarray(alpha, dtype=float)
    d = DIMENSION
    return (
        3.0
        / (4.0 * d)
        * (1.0 - alpha + 2.0 * d / 3.0)
        * (1.0 + alpha)
        * (1.0 - _a2(alpha, a2) / 32.0)
    )


def zeta_dagger(alpha, a2=None):
    """ζ† = ((d+2)/(4d))(1 − α²)(1 + 3a2/16), in units of ν0."""
    alpha = np.asarray(alpha, dtype=float)
    d = DIMENSION
    return (d + 2.0) / (4.0 * d) * (1.0 - alpha**2) * (1.0 + 3.0 * _a2(alpha, a2) / 16.0)


def zeta_star(alpha, a2=None):
    """Reduced cooling rate (Eq. 12, RECON-H): ζ* = √(π/2)(1 − α²)(1 + 3a2/16)."""
    return RATE_UNIT * zeta_dagger(alpha, a2)


def nu_star(alpha, a2=None):
    """Reduced kinematic viscosity, first Sonine: 1/(2√(2π)(ν_η† − ζ†/2)); 0.19947 at
    α = 1."""
    return 1.0 / (2.0 * RATE_UNIT * (nu_eta_dagger(alpha, a2) - zeta_dagger(alpha, a2) / 2.0))


def fdr_ratio_white(alpha, a2=None):
    """ν̄*/ν* with white stress noise (RECON-M): (1 + a2)(ν_η† − ζ†/2)/(ν_η† − ζ†)."""
    nu, zeta = nu_eta_dagger(alpha, a2), zeta_dagger(alpha, a2)
    return (1.0 + _a2(alpha, a2)) * (nu - zeta / 2.0) / (nu - zeta)


def nu_bar_star_white(alpha, a2=None):
    """Reduced noise viscosity with white noise: ν* times ``fdr_ratio_white``."""
    return nu_star(alpha, a2) * fdr_ratio_white(alpha, a2)


def reduced_wavenumber(n_particles, density):
    """k* = kℓ = 2π/√(N nσ²) of the longest mode k = 2π/L of a square box."""
    return 2.0 * math.pi / np.sqrt(np.asarray(n_particles, dtype=float) * density)


def decay_rate(alpha, n_particles, density, a2=None):
    """λ = ν* k*² − ζ*/2, the decay rate of the mode in units of v_s/ℓ (Eq. 8)."""
    k2 = reduced_wavenumber(n_particles, density) ** 2
    return nu_star(alpha, a2) * k2 - zeta_star(alpha, a2) / 2.0


def correlation_time(alpha, n_particles, density, a2=None):
    """τ_c = 1/(ν* k*² − ζ*/2) in ℓ/v_s (Eq. 9); infinite at and beyond the instability."""
    rate = decay_rate(alpha, n_particles, density, a2)
    return np.where(rate > 0, 1.0 / np.where(rate > 0, rate, 1.0), np.inf)


def correlation_amplitude(alpha, n_particles, density, a2=None):
    """C(0) = ν̄* k*²/(ν* k*² − ζ*/2) with white noise (Eq. 9)."""
    k2 = reduced_wavenumber(n_particles, density) ** 2
    return nu_bar_star_white(alpha, a2) * k2 * correlation_time(alpha, n_particles, density, a2)


def coloured_noise_amplitude(alpha, n_particles, density, a2=None):
    """Factor γ²/(γ² − λ²) by which coloured stress noise raises the amplitude of the
    exponential tail of C (RECON-M): the stress fluctuations relax at γ = ν_η* − ζ*
    (ν_η* = √(2π) ν_η†, ζ* = √(2π) ζ†), the mode at λ = ν* k*² − ζ*/2 (both in v_s/ℓ).
    Meaningful for λ < γ (NaN otherwise)."""
    gamma = RATE_UNIT * (nu_eta_dagger(alpha, a2) - zeta_dagger(alpha, a2))
    rate = decay_rate(alpha, n_particles, density, a2)
    denominator = gamma**2 - rate**2
    return np.where(denominator > 0, gamma**2 / np.where(denominator > 0, denominator, 1.0), np.nan)


def fdr_ratio_coloured(alpha, n_particles, density, a2=None):
    """ν̄*/ν* that a fit of the exponential tail measures with coloured noise: the white
    ratio times ``coloured_noise_amplitude``."""
    return fdr_ratio_white(alpha, a2) * coloured_noise_amplitude(alpha, n_particles, density, a2)


def collisional_transfer(alpha, dimension=DIMENSION):
    """(1 + 1/d) c: the mean momentum that a collision of inelastic hard disks (d = 2) or
    spheres (d = 3) exchanges, in units of m times the pair's mean relative velocity u,
    for the collisions of a gas whose pairs are accepted ∝ |g|: ⟨Δp1⟩ = −(1 + 1/d) c m u.

    c = (1 + α)/2 ⟨cos²θ⟩ for a given g (θ between g and the line of centres: ⟨cos²θ⟩ =
    2/3 for disks, 1/2 for spheres), and ⟨|g| g_x⟩ = (1 + 1/d)⟨|g|⟩u_x to first order in u.
    (1 + α)/2 in d = 2; 2/3 for elastic spheres."""
    if dimension not in (2, 3):
        raise ValueError(f"dimension must be 2 or 3, got {dimension!r}")
    cosine_sq = 2.0 / 3.0 if dimension == 2 else 0.5
    return (1.0 + 1.0 / dimension) * (1.0 + np.asarray(alpha, dtype=float)) / 2.0 * cosine_sq


def in_cell_flow(alpha, cell_side, harmonics: int = 20_000):
    """b: the slope of the flow inside a DSMC cell over the flow's, in a relaxation model;
    multiplies the leading-order collisional transfer of ``dsmc_cell_viscosity``.

    The cell's collisions pull each particle's mean velocity towards the cell's mean, at
    κν_c with κ = ``collisional_transfer`` (= (1 + α)/2 in d = 2): after a collision it is
    (1 − κ) its own plus κ the cell's, where a point collision would give the flow's at
    that place. Free flights since the last collision, Maxwellian in y over an
    exponential age, carry it to where the particle is seen. So the flow inside a cell,
    γy + δ(y), has δ = (1 − κ) K∗δ − κγ K∗s, s(y) the sawtooth of the position in its
    cell and K the flights' displacement distribution: per harmonic m of the sawtooth
    (wavenumber 2πm/Δx), δ_m = −κγ K_m s_m/(1 − (1 − κ)K_m), with
    K_m = ∫e^{−u − a u²}du = √(π/4a) erfcx(1/(2√a)), a = 4πm²(λ/Δx)². Pairs of a cell
    then see the slope b = 1 + ⟨δs⟩/(γ⟨s²⟩) = 1 − (6/π²) κ Σ_m K_m/(m²(1 − (1 − κ)K_m)).

    A model, not an exact result (speed-dependent collision rates and the persistence of
    velocities are averaged out): b → 1 − (3ζ(3)/(2π²)) κ Δx/λ as Δx → 0, 0.92 at half a
    mean free path and 0.85 at one (α = 0.8). ``cell_side`` Δx/λ; sums ``harmonics``
    terms (the rest is below 10⁻⁹ Δx/λ)."""
    from scipy.special import erfcx

    kappa = np.asarray(collisional_transfer(alpha), dtype=float)
    side = np.asarray(cell_side, dtype=float)
    m = np.arange(1, harmonics + 1, dtype=float)
    shape = np.broadcast(kappa, side).shape
    kappa, side = np.broadcast_to(kappa, shape)[..., None], np.broadcast_to(side, shape)[..., None]
    a = 4.0 * math.pi * m**2 / side**2
    flights = np.sqrt(math.pi / (4.0 * a)) * erfcx(1.0 / (2.0 * np.sqrt(a)))
    terms = flights / (m**2 * (1.0 - (1.0 - kappa) * flights))
    return 1.0 - 6.0 / math.pi**2 * kappa[..., 0] * terms.sum(axis=-1)


def dsmc_cell_viscosity(alpha, n_particles, density, cells_per_side, *, flattened: bool = True):
    """Δν* that DSMC's collision cells add to the ν* of the longest transverse mode (d = 2,
    M = ``cells_per_side`` cells a side).

    DSMC collides partners anywhere in one cell: a pair a distance Δy apart across the
    flow u(y) exchanges x-momentum −``collisional_transfer`` m (u(y1) − u(y2)) on average,
    and so carries momentum a distance Δy, a transfer that the point collisions of the
    Boltzmann equation (and MD at this density) lack. With positions uniform and
    independent in a cell, ⟨Δy²⟩ = Δx²/6, and n ν_c/2 collisions per unit area and time
    (ν_c = √(2π) v_s/ℓ a particle) add the kinematic viscosity
    Δν = collisional_transfer ν_c Δx²/12; with Δx* = √(N nσ²)/M in ℓ,
    Δν* = (1 + α) √(2π) Δx*²/24, exact to leading order in Δx/λ. (For elastic hard
    spheres the same sum, over their first-Sonine viscosity, is (16/(45π))(Δx/λ)², the
    cell-size error of viscosity that Alexander, Garcia and Alder derived, Phys. Fluids
    10, 1540 (1998).)

    The mode k = 2π/L spans only M cells: the pair average of (sin ky1 − sin ky2)²
    replaces k²Δy²/2, which multiplies Δν* by F = 12(1 − sinc²(kΔx/2))/(kΔx)² with
    kΔx = 2π/M (0.984 at M = 9; 1 as M → ∞). With ``flattened`` (the default), Δν* is
    also multiplied by ``in_cell_flow``: the cell's collisions flatten the flow inside
    it, by 8 % at half a mean free path and 15 % at one (a model; measured at α = 0.8,
    N = 2000: docs/reproduced.md). One cell (M = 1, the homogeneous gas) has no flow: 0.
    """
    cells = np.asarray(cells_per_side, dtype=float)
    spacing_sq = np.asarray(n_particles, dtype=float) * density / cells**2  # Δx*² in ℓ²
    phase = 2.0 * math.pi / cells  # kΔx
    finite_mode = 12.0 * (1.0 - np.sinc(phase / (2.0 * math.pi)) ** 2) / phase**2
    excess = collisional_transfer(alpha) * RATE_UNIT * spacing_sq / 12.0 * finite_mode
    if flattened:
        excess = excess * in_cell_flow(alpha, 2.0 * np.sqrt(2.0 * spacing_sq))  # Δx/λ
    return np.where(cells > 1, excess, 0.0)


def nu_star_from_fit(tau_c, zeta_star, k_star):
    """Eq. 10: ν* = (1/τ_c + ζ*/2)/k*² (τ_c in ℓ/v_s)."""
    return (1.0 / np.asarray(tau_c, dtype=float) + np.asarray(zeta_star) / 2.0) / np.asarray(
        k_star
    ) ** 2


def nu_bar_star_from_fit(amplitude, tau_c, k_star):
    """Eq. 11: ν̄* = A/(τ_c k*²), A the amplitude of C (the fitted tail's or C(0))."""
    return np.asarray(amplitude, dtype=float) / (
        np.asarray(tau_c, dtype=float) * np.asarray(k_star) ** 2
    )


def critical_length(alpha, a2=None):
    """L_c/ℓ = 2π √(2ν*/ζ*): boxes at least that large are shear-unstable (∞ at α = 1)."""
    zeta = zeta_star(alpha, a2)
    nu = nu_star(alpha, a2)
    return np.where(
        zeta > 0, 2.0 * math.pi * np.sqrt(2.0 * nu / np.where(zeta > 0, zeta, 1.0)), np.inf
    )


def max_n_density(alpha, a2=None):
    """Largest N nσ² of a stable box: (L_c/ℓ)² (L/ℓ = √(N nσ²))."""
    return critical_length(alpha, a2) ** 2


def check_stable(n_particles, density, alpha, a2=None) -> None:
    """Raise ``ValueError`` with the bound if an N-particle box at this density and α is at
    or beyond the shear instability (L >= L_c, where τ_c diverges)."""
    length = math.sqrt(n_particles * density)
    limit = float(critical_length(alpha, a2))
    if length >= limit:
        raise ValueError(
            f"N = {n_particles} at n sigma^2 = {density:g} and alpha = {alpha:g} is "
            "shear-unstable: "
            f"L = {length:.3g} l is not below the critical L_c = {limit:.3g} l (first Sonine); "
            f"N n sigma^2 must stay below {limit**2:.3g}"
        )


def warn_if_unstable(n_particles, density, alpha) -> None:
    """Log a warning (the ``kinetic`` logger) if the box is at or beyond the shear
    instability (``check_stable``): the cooling fronts of both engines run it, since it is
    physics, but the transverse modes then grow instead of decaying (τ_c diverges)."""
    try:
        check_stable(n_particles, density, alpha)
    except ValueError as error:
        logging.getLogger("kinetic").warning(
            "%s: the transverse modes grow instead of decaying, and their correlation "
            "time is not the hydrodynamic one",
            error,
        )


def drag_rate(alpha, density, a2=None, temperature: float = 1.0) -> float:
    """ω0 = ζ(T)/2 in engine units (m = σ = 1, time σ√(m/T0)): the drag that holds the
    rescaled temperature at ``temperature`` (Eq. 12 with the chosen a2;
    ζ = ζ* v/ℓ with v = √(2T), ℓ = 1/n)."""
    return float(zeta_star(alpha, a2)) * math.sqrt(2.0 * temperature) * density / 2.0


def heated_temperature(alpha: float, density: float, drag_rate: float, duration: float) -> float:
    """The largest mean temperature (units of T0) that a drag ``drag_rate`` = ω0 (engine
    units) reaches within ``duration``, by the homogeneous balance dT/dτ = (2ω0 − ζ(T)) T
    with ζ(T) = ζ(T0) √T from Eq. 12 (a2 of van Noije and Ernst): x = √T is logistic,
    x(τ) = x_s/(1 + (x_s − 1) e^(−ω0 τ)) with x_s = 2ω0/ζ(T0), so T rises monotonically to
    T(duration) when T_s = x_s² > 1 and never exceeds T0 otherwise; an elastic gas with
    drag heats as e^(2ω0 τ). What the cooling fronts of both engines check a drag by."""
    if drag_rate == 0.0:
        return 1.0
    # ζ(T0) = ζ* v/ℓ with v = √2 and ℓ = 1/n (engine units)
    zeta0 = float(zeta_star(alpha)) * math.sqrt(2.0) * density
    growth = min(drag_rate * duration, 700.0)
    if zeta0 == 0.0:
        return math.exp(2.0 * growth)
    steady = 2.0 * drag_rate / zeta0
    if steady <= 1.0:
        return 1.0
    return (steady / (1.0 + (steady - 1.0) * math.exp(-growth))) ** 2


# ------------------------------------------------------- elastic viscosity beyond first Sonine
def _sonine_bracket_matrix(order: int, dimension: int) -> np.ndarray:
    """Bracket integrals A_pq = [S_p(c²) c°c, S_q(c²) c°c] of the linearised Boltzmann
    operator of elastic hard disks/spheres, p, q < ``order`` (up to a common factor).

    c°c = c_i c_j − δ_ij c²/d (contracted over i, j: by isotropy each component carries the
    same share), S_p the Sonine polynomial L_p^{(d/2+1)}, velocities in units of √(2T/m).
    A_pq = ∫dc1 dc2 e^{−c1²−c2²} ∫dσ̂ Θ(g·σ̂)(g·σ̂) ΔF_p ΔF_q with ΔF = F(c1') + F(c2')
    − F(c1) − F(c2). The integrand is a polynomial times Gaussians in the centre-of-mass
    velocity C and in g²: Gauss–Hermite in each component of C and generalised
    Gauss–Laguerre in u = g²/2 are exact; by rotational invariance g lies along x and
    only σ̂ turns (Gauss–Legendre in its angle or polar cosine, trapezoid in azimuth).
    """
    from scipy.special import eval_genlaguerre, roots_genlaguerre, roots_hermite, roots_legendre

    d = dimension
    nodes, weights = roots_hermite(2 * order + 4)  # e^{-x²}; C = x/√2 carries e^{-2C²}
    axes = np.meshgrid(*([nodes / math.sqrt(2.0)] * d), indexing="ij")
    centre = np.stack([axis.ravel() for axis in axes], axis=1)
    centre_weight = np.ones(centre.shape[0])
    for axis in np.meshgrid(*([weights / math.sqrt(2.0)] * d), indexing="ij"):
        centre_weight *= axis.ravel()
    u, u_weight = roots_genlaguerre(2 * order + 4, (d - 1) / 2.0)  # g^{d-1} dg · g e^{-g²/2}
    t, t_weight = roots_legendre(40 if d == 2 else 24)
    if d == 2:
        angle = t * math.pi / 2.0  # σ̂ at angle φ ∈ (−π/2, π/2) from g
        directions = np.stack([np.cos(angle), np.sin(angle)], axis=1)
        direction_weight = t_weight * math.pi / 2.0 * np.cos(angle)
    else:
        cosine, azimuth = (t + 1.0) / 2.0, 2.0 * math.pi * np.arange(24) / 24
        mu, phi = np.meshgrid(cosine, azimuth, indexing="ij")
        sine = np.sqrt(1.0 - mu**2)
        directions = np.stack(
            [mu.ravel(), (sine * np.cos(phi)).ravel(), (sine * np.sin(phi)).ravel()], 1
        )
        direction_weight = np.outer(
            t_weight / 2.0 * cosine, np.full(24, 2.0 * math.pi / 24)
        ).ravel()
    identity = np.eye(d)

    def tensors(c):
        c2 = np.sum(c * c, axis=-1)
        traceless = c[:, :, None] * c[:, None, :] - identity * (c2 / d)[:, None, None]
        return np.stack(
            [
                eval_genlaguerre(p, d / 2.0 + 1.0, c2)[:, None, None] * traceless
                for p in range(order)
            ],
            axis=1,
        )

    matrix = np.zeros((order, order))
    for speed, speed_weight in zip(np.sqrt(2.0 * u), u_weight, strict=True):
        g = np.zeros(d)
        g[0] = speed
        first, second = centre + g / 2.0, centre - g / 2.0
        before = tensors(first) + tensors(second)
        for sigma, sigma_weight in zip(directions, direction_weight, strict=True):
            transfer = speed * sigma[0] * sigma
            change = tensors(first - transfer) + tensors(second + transfer) - before
            weight = centre_weight * speed_weight * sigma_weight
            matrix += np.einsum("n,npij,nqij->pq", weight, change, change)
    return matrix


@functools.cache
def viscosity_sonine_ratio(order: int, dimension: int = DIMENSION) -> float:
    """η in the Sonine approximation of ``order`` polynomials over the first Sonine η0 of
    elastic hard disks (d = 2) or spheres (d = 3): A_00 (A⁻¹)_00 of the bracket matrix (the
    Chapman–Enskog source c°c projects on S_0 only). Order 2 gives 1 + 1/50 in d = 2 and
    1 + 3/202 in d = 3 exactly; converged (order 8, d = 2): 1.02197."""
    if isinstance(order, bool) or not isinstance(order, int) or order < 1:
        raise ValueError(f"order must be an integer >= 1, got {order!r}")
    if dimension not in (2, 3):
        raise ValueError(f"dimension must be 2 or 3, got {dimension!r}")
    matrix = _sonine_bracket_matrix(order, dimension)
    return float(matrix[0, 0] * np.linalg.inv(matrix)[0, 0])


ELASTIC_SONINE_ORDER = 8
"""Sonine order of ``nu_star_elastic`` (the ratio changes by 1e-6 from order 7 to 8)."""


def nu_star_elastic(order: int = ELASTIC_SONINE_ORDER) -> float:
    """ν* of elastic hard disks converged in the Sonine order: 1/(2√(2π)) times
    ``viscosity_sonine_ratio(order)`` = 0.20385 (first Sonine: 0.19947)."""
    return float(nu_star(1.0)) * viscosity_sonine_ratio(order, 2)
