"""Gas quantities every engine and theory uses (Maxwellian speeds, cross-sections, collision
frequencies, mean free paths, time units): the one place where the units are converted.

Simulation units: mass m = 1, diameter σ = 1, temperature in units of T0 (= 1 at the
start, and held there by the thermostat). The two conventions of the documents:

- ``visco2008``: time in units of the mean free time 1/ω, ω the equilibrium collision
  frequency per particle (Eq. 7: ω = 2 π^((d-1)/2) n σ^(d-1) sqrt(T) / Γ(d/2) for hard
  spheres), lengths in units of the mean free path l = <v>/ω;
- ``montanero2007``: mean free path λ = 1/(√2 S n) with S = π^((d-1)/2)/Γ((d+1)/2) σ^(d-1)
  (π σ² in d = 3: the paper's 1/(√2 π n σ²); λ = <v>/ω for elastic hard spheres in
  every d), thermal speed v0 = sqrt(2 T/m), time unit τ = λ/v0, reduced field ε* = λ ε.

Collision kernels (rate of a pair per unit "density per particle", integrated over the
collision hemisphere, at relative speed g): hard spheres S g; Maxwell molecules S <g>_ref
(a constant equal to the hard-sphere rate at the reference temperature, so both share ω
there); very hard particles Ω_d/(2d) g²/sqrt(T_ref) (visco2008 Eq. B1, ω_VHP of B3).
"""

from __future__ import annotations

import math

__all__ = [
    "HARD_SPHERES",
    "KERNELS",
    "MAXWELL",
    "VERY_HARD",
    "candidate_coefficient",
    "cell_changing_fraction",
    "cross_section",
    "equilibrium_collision_frequency",
    "mean_free_path",
    "mean_relative_speed",
    "mean_speed",
    "montanero_time_unit",
    "rate_exponent",
    "solid_angle",
    "thermal_speed",
]

# Collision kernels, by the codes every engine's kernels take (a compile-time constant).
HARD_SPHERES = 0
"""Hard spheres (hard disks in d = 2): collision rate ∝ |g·σ̂| (σ̂ the unit vector between
the centres at contact)."""
MAXWELL = 1
"""Maxwell molecules: a collision rate independent of the relative velocity."""
VERY_HARD = 2
"""Very hard particles: collision rate ∝ |g|² (visco2008 Appendix B)."""

KERNELS = ("hard_spheres", "maxwell", "very_hard")
"""Names of the collision kernels (index = kernel id of :mod:`kinetic.dsmc.kernels`)."""


def _dimension(d: int) -> int:
    if d not in (2, 3):
        raise ValueError(f"dimension must be 2 or 3, got {d!r}")
    return int(d)


def _kernel(kernel: str) -> str:
    if kernel not in KERNELS:
        raise ValueError(f"kernel must be one of {', '.join(KERNELS)}, got {kernel!r}")
    return kernel


def cross_section(d: int) -> float:
    """S = π^((d-1)/2)/Γ((d+1)/2) (σ = 1): ∫ over the hemisphere of ĝ·σ̂; 2 in d=2, π in d=3."""
    d = _dimension(d)
    return math.pi ** ((d - 1) / 2) / math.gamma((d + 1) / 2)


def solid_angle(d: int) -> float:
    """Ω_d = 2 π^(d/2)/Γ(d/2), the area of the unit sphere (2π in d=2, 4π in d=3)."""
    d = _dimension(d)
    return 2.0 * math.pi ** (d / 2) / math.gamma(d / 2)


def mean_speed(d: int, temperature: float = 1.0) -> float:
    """<|v|> of a Maxwellian in any dimension d >= 1: sqrt(2T) Γ((d+1)/2)/Γ(d/2)."""
    if isinstance(d, bool) or int(d) != d or d < 1:
        raise ValueError(f"dimension must be an integer >= 1, got {d!r}")
    return math.sqrt(2.0 * temperature) * math.exp(math.lgamma((d + 1) / 2) - math.lgamma(d / 2))


def mean_relative_speed(d: int, temperature: float = 1.0) -> float:
    """<|v1 - v2|> of two Maxwellian particles: √2 <|v|>."""
    return math.sqrt(2.0) * mean_speed(d, temperature)


def thermal_speed(temperature: float = 1.0) -> float:
    """v0 = sqrt(2 T / m) (montanero2007 Eq. 2.11)."""
    return math.sqrt(2.0 * temperature)


def rate_exponent(kernel: str) -> int:
    """p such that the collision rate scales as g^p: 1, 0, 2."""
    return {"hard_spheres": 1, "maxwell": 0, "very_hard": 2}[_kernel(kernel)]


def equilibrium_collision_frequency(
    kernel: str,
    d: int,
    density: float,
    temperature: float = 1.0,
    reference_temperature: float = 1.0,
) -> float:
    """Collisions per particle per unit time in a Maxwellian gas (ω; ω_VHP of visco2008 B3)."""
    kernel = _kernel(kernel)
    if kernel == "hard_spheres":
        return density * cross_section(d) * mean_relative_speed(d, temperature)
    if kernel == "maxwell":
        return density * cross_section(d) * mean_relative_speed(d, reference_temperature)
    # Ω_d/(2d) <g²>/sqrt(T_ref) with <g²> = 2 d T
    return density * solid_angle(d) * temperature / math.sqrt(reference_temperature)


def candidate_coefficient(
    kernel: str, d: int, density: float, n_particles: int, reference_temperature: float = 1.0
) -> float:
    """``pair_coefficient`` of the kernels: candidates per pair per unit time per bound**p.

    A particle meets each of the other N - 1 at the density n/(N - 1), so its collision
    rate is n x (pair rate) exactly, whatever N. Hard spheres (accepted with |g|/B):
    n/(N-1) S; Maxwell (always accepted): n/(N-1) S <g>_ref; very hard particles
    (σ̂ uniform on the whole sphere, accepted with (g·σ̂)²/B²): n/(N-1) Ω_d/2 /sqrt(T_ref).
    """
    kernel = _kernel(kernel)
    per_pair = density / (n_particles - 1)
    if kernel == "hard_spheres":
        return per_pair * cross_section(d)
    if kernel == "maxwell":
        return per_pair * cross_section(d) * mean_relative_speed(d, reference_temperature)
    return per_pair * solid_angle(d) / 2.0 / math.sqrt(reference_temperature)


def cell_changing_fraction(
    d: int, time_step: float, box_side: float, cells_per_side: int, temperature: float = 1.0
) -> float:
    """Fraction of the particles of a gas at rest (m = 1) in a periodic box of side L cut
    into ``cells_per_side``^d square or cubic cells of side a = L/cells_per_side that fly
    into another cell in a time Δt: ⟨Σ_k |v_k|⟩ Δt/a = d √(2T/π) Δt/a (for Δt ⟨|v|⟩
    small against a; each crossing of a face counted once); 0 in one cell, which a
    particle leaving through a face re-enters."""
    if cells_per_side == 1:
        return 0.0
    cell_side = box_side / cells_per_side
    return d * math.sqrt(2.0 * temperature / math.pi) * time_step / cell_side


def mean_free_path(d: int, density: float) -> float:
    """λ = 1/(√2 S n): montanero2007's mean free path (= <v>/ω of elastic hard spheres)."""
    return 1.0 / (math.sqrt(2.0) * cross_section(d) * density)


def montanero_time_unit(d: int, density: float, temperature: float = 1.0) -> float:
    """τ = λ/v0 (montanero2007 Section 4)."""
    return mean_free_path(d, density) / thermal_speed(temperature)
