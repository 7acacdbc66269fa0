"""Theory of Visco, van Wijland and Trizac (2008), *Collisional statistics of the hard-sphere gas*.

Units: mass m = 1, bath temperature T0 = 1, and time in mean free times (ω = 1, the
collision frequency of Eq. 7) unless a function says otherwise; speeds are in units of
sqrt(T0/m). Lengths of free paths are in units of the mean free path l = <v>/ω (the
document writes l = ω/<v>, an inversion). ``d`` is the space dimension (any d >= 2 where
the formula is general).

Contents, by equation of the document:

- r(v) (6) with Kummer's transformation, ω (7), r(v) at large d (12);
- P_FFT(t) (9), its large-t form (11); the erroneous weighting P_FFT^W (A1), (A8);
- P_FPL(x) (14), the decay rate A (15) and the exponential tail (16, sign restored);
- the Laplace transform of P_FFT (18) and the uncorrelated large deviation function (23);
- Poisson generating functions and large deviation functions (38–40);
- the Gaussian closure μ(λ), T(λ) (43);
- the first Sonine closure (47–49): the collisional moments of Appendix E are computed
  here for any d by exact Gaussian moment algebra (``_collisional_moments``); Appendix E
  itself (d = 2, with the sign of E3 corrected) is kept as ``appendix_e_moments`` for an
  independent check; the cumulants (50);
- Legendre transforms μ(λ) -> π(n) (32);
- very hard particles (B2–B4) and Maxwell molecules' free paths (D3, D4).

All quadratures keep the dominant exponential outside the integral (log space), so the
tails of the distributions do not underflow before their logarithm is needed.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import lru_cache

import numpy as np
from scipy import special

from kinetic.gas import mean_speed

__all__ = [
    "TABLE_I_DOCUMENT",
    "collision_frequency",
    "collision_rate",
    "collision_rate_large_d",
    "free_flight_time_laplace",
    "free_flight_time_pdf",
    "free_flight_time_pdf_asymptotic",
    "free_flight_time_survival",
    "free_path_decay_rate",
    "free_path_pdf",
    "free_path_pdf_tail",
    "free_path_survival",
    "gaussian_count_ldf",
    "gaussian_cumulants",
    "gaussian_mu",
    "gaussian_temperature",
    "legendre_transform",
    "log_free_flight_time_pdf",
    "maxwell_free_path_pdf",
    "maxwell_free_path_pdf_asymptotic",
    "maxwell_free_path_survival",
    "mean_free_path",
    "mean_speed",
    "poisson_cloning_estimator",
    "poisson_count_ldf",
    "poisson_ldf",
    "poisson_mu",
    "rate_moment",
    "saddle_point_count_ldf",
    "sonine_cumulants",
    "sonine_cumulants_numerical",
    "sonine_solution",
    "uncorrelated_ldf",
    "vhp_collision_rate",
    "vhp_free_flight_time_pdf",
    "weighted_free_flight_time_pdf",
    "weighted_free_flight_time_pdf_asymptotic",
    "weighted_free_flight_time_survival",
]

SQRT2 = np.sqrt(2.0)

TABLE_I_DOCUMENT = {
    "MD t=10": (1.0, 1.1228, 1.1282),
    "MD t=50": (1.0, 1.1354, 1.1045),
    "Poisson": (1.0, 1.0, 1.0),
    "Gaussian": (1.0, 1.125, 1.1289),
    "Sonine": (1.0, 1.1377, 1.1073),
}
"""Table I of the document as printed: ⟨N^p⟩_c/t, p = 1, 2, 3 (the MD rows do not say
which of the two simulated densities they come from)."""


# --------------------------------------------------------------------------- basics
def collision_frequency(
    d: int,
    density: float,
    *,
    diameter: float = 1.0,
    temperature: float = 1.0,
    mass: float = 1.0,
    chi: float = 1.0,
) -> float:
    """Collision frequency per particle, Eq. (7): ω = 2 π^{(d-1)/2} sqrt(T/m) / (ℓ Γ(d/2)).

    ``ℓ = 1 / (σ^{d-1} ρ χ)``; in d = 2 this is the Enskog value 2 sqrt(π) ρ σ sqrt(T/m) χ.
    """
    ell = 1.0 / (diameter ** (d - 1) * density * chi)
    return 2.0 * np.pi ** ((d - 1) / 2) * np.sqrt(temperature / mass) / (ell * special.gamma(d / 2))


def mean_free_path(d: int) -> float:
    """Mean free path l = <v>/ω in the units of this module (ω = 1, T0 = 1)."""
    return mean_speed(d)


def collision_rate(speed, d: int):
    """r(v)/ω of Eq. (6) for a particle of speed v (units of sqrt(T0/m)).

    Kummer's transformation e^{-x} 1F1((d-1)/2, d/2, x) = 1F1(1/2, d/2, -x) removes the
    overflow of the printed form; both hypergeometric functions then stay in [0, 1].
    r(0)/ω = 1/sqrt(2); r(v)/(ω v) -> 1/(sqrt(2) l) as v -> ∞ (Eq. 15).
    """
    v = np.asarray(speed, dtype=float)
    x = 0.5 * v * v
    return (v * v / d * special.hyp1f1(0.5, 1 + d / 2, -x) + special.hyp1f1(0.5, d / 2, -x)) / SQRT2


def collision_rate_large_d(speed, d: int):
    """r(v)/ω at large d, Eq. (12) corrected: sqrt(1 + v²/(T0 d)) / sqrt(2).

    The document prints v²/(2 T0 d), a typo: its own Appendix C gives
    r ∝ I1 - I2 ∝ sqrt(1 + 2ṽ²) with ṽ = v/sqrt(2 T0 d), i.e. v²/(T0 d); so does the
    concentration |v - v2|² ≈ v² + d T0 of the relative speed in high dimension, and Eq. (6)
    converges to this form (tests/physics/test_visco2008_free_flights.py).
    """
    v = np.asarray(speed, dtype=float)
    return np.sqrt(1.0 + v * v / d) / SQRT2


def _log_speed_density(v, d: int):
    """log of the Maxwell speed density S_d v^{d-1} (2π)^{-d/2} e^{-v²/2} (T = 1)."""
    log_surface = np.log(2.0) + (d / 2) * np.log(np.pi) - special.gammaln(d / 2)
    return log_surface + (d - 1) * np.log(v) - 0.5 * d * np.log(2 * np.pi) - 0.5 * v * v


@lru_cache(maxsize=8)
def _log_speed_rule(d: int, points: int = 6000):
    """The speed integrals' quadrature: the trapezoid rule in ln v on [1e-15, 40].

    Returns the speeds v, the logs of their weights times the Maxwell speed density
    (ln(h v φ(v)), halved at both ends) and r(v)/ω there. In ln v every integrand of this
    module is smooth and decays at both ends (as v^d, or v^(d-1) for the densities of a
    free path at x = 0, at v -> 0; as e^{-v²/2} at v -> ∞), where the trapezoid rule
    converges exponentially: it gives the values of the adaptive quadrature it replaced to
    within 8e-12 (t and x from 0 to 2000, z from -0.707 to 100, d = 2 and 3) in 20-100 µs
    a point instead of 5-12 ms. The log grid resolves the near-singular
    integrands of the Laplace transform close to z = -1/√2 (width √(z + 1/√2) in v)."""
    log_v = np.linspace(np.log(1e-15), np.log(40.0), points)
    v = np.exp(log_v)
    log_weights = _log_speed_density(v, d) + log_v + np.log(log_v[1] - log_v[0])
    log_weights[[0, -1]] += np.log(0.5)
    return v, log_weights, collision_rate(v, d)


def _log_speed_integrals(log_terms: Callable, points, d: int) -> np.ndarray:
    """log ∫ dv φ(v) exp(log_terms(v, r, point)) for each of ``points`` (φ the Maxwell
    speed density, r = r(v)/ω of Eq. 6), in log space: the tails of the distributions do
    not underflow before their logarithm is taken."""
    v, log_weights, rate = _log_speed_rule(d)
    points = np.asarray(points, dtype=float)
    out = np.empty(points.shape)
    for index, point in np.ndenumerate(points):
        out[index] = special.logsumexp(log_weights + log_terms(v, rate, point))
    return out


def rate_moment(power: int, d: int) -> float:
    """<(r/ω)^power> over the Maxwellian; (A6) is rate_moment(2, 2) = 1.06354."""
    return float(np.exp(_log_speed_integrals(lambda v, r, _: power * np.log(r), 0.0, d)))


# --------------------------------------------------------------------------- free flights
def log_free_flight_time_pdf(t, d: int):
    """log P_FFT(t) of Eq. (9): log ∫ dv φ(v) r(v)² e^{-r(v) t} / ω (t in 1/ω)."""

    return _log_speed_integrals(lambda v, r, time: 2 * np.log(r) - r * time, t, d)


def free_flight_time_pdf(t, d: int):
    """P_FFT(t), Eq. (9), with the on-collision weight φ_coll = r φ / ω (Eq. 10)."""
    return np.exp(log_free_flight_time_pdf(t, d))


def free_flight_time_pdf_asymptotic(t, d: int):
    """Large-t form of P_FFT, Eq. (11): e^{-t/√2} (1/2) (1 - 2/d + t/(√2 d))^{-d/2}.

    Not normalised: an asymptotic expansion, valid for t ≫ 1.
    """
    t = np.asarray(t, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.exp(-t / SQRT2) * 0.5 * (1 - 2 / d + t / (SQRT2 * d)) ** (-d / 2)


def weighted_free_flight_time_pdf(t, d: int):
    """P_FFT^W(t) of (A1): the erroneous Gaussian weighting ∫ dv φ(v) r e^{-r t}."""

    return np.exp(_log_speed_integrals(lambda v, r, time: np.log(r) - r * time, t, d))


def free_flight_time_survival(t, d: int):
    """Probability that a free flight lasts longer than t: ∫_t^∞ P_FFT = ∫ dv φ r e^{-r t}
    (ω = 1), which is P_FFT^W(t) of (A1). Histogram bins [a, b] hold exactly
    (S(a) - S(b))/(b - a), the bin average the data estimate."""
    return weighted_free_flight_time_pdf(t, d)


def weighted_free_flight_time_survival(t, d: int):
    """∫_t^∞ P_FFT^W = ∫ dv φ(v) e^{-r t} (bin averages of (A1), as for P_FFT)."""

    return np.exp(_log_speed_integrals(lambda v, r, time: -r * time, t, d))


def weighted_free_flight_time_pdf_asymptotic(t, d: int):
    """(A8): e^{-t/√2} 2^{(d-1)/2} (2 - 2/d + √2 t/d)^{-d/2}.

    The document prints sqrt(2 ω t); the saddle point of (A1) gives √2 ω t (the same
    expansion as Eq. 11), which is what is implemented.
    """
    t = np.asarray(t, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.exp(-t / SQRT2) * 2 ** ((d - 1) / 2) * (2 - 2 / d + SQRT2 * t / d) ** (-d / 2)


def free_flight_time_laplace(z, d: int):
    """Laplace transform (18) of P_FFT: ∫ dv φ(v) r² / (r + z), for z > -1/√2."""
    z = np.asarray(z, dtype=float)
    if np.any(z <= -1 / SQRT2):
        raise ValueError(f"the Laplace transform of P_FFT exists for z > -1/sqrt(2), got {z}")

    return np.exp(_log_speed_integrals(lambda v, r, shift: 2 * np.log(r) - np.log(r + shift), z, d))


# --------------------------------------------------------------------------- free paths
def free_path_decay_rate(d: int) -> float:
    """A of Eq. (15), the decay rate of P_FPL in units of 1/l: 1/sqrt(2)."""
    del d  # A l = 1/sqrt(2) in every dimension
    return 1 / SQRT2


def free_path_pdf(x, d: int):
    """P_FPL(x), Eq. (14), x in units of the mean free path l = <v>/ω (per unit of l)."""
    scale = mean_free_path(d)

    def log_terms(v, r, length):
        return 2 * np.log(r) - np.log(v) - r * length * scale / v

    return scale * np.exp(_log_speed_integrals(log_terms, x, d))


def free_path_survival(x, d: int):
    """Probability that a free path is longer than x (units of l): ∫ dv φ r e^{-r x l/v}."""
    scale = mean_free_path(d)

    def log_terms(v, r, length):
        return np.log(r) - r * length * scale / v

    return np.exp(_log_speed_integrals(log_terms, x, d))


def maxwell_free_path_survival(x, d: int):
    """Maxwell molecules: probability that a free path exceeds x, ∫ dv φ(v) e^{-x l/v}."""
    scale = mean_free_path(d)

    return np.exp(_log_speed_integrals(lambda v, r, length: -length * scale / v, x, d))


def free_path_pdf_tail(x, d: int, amplitude: float = 1.0):
    """Dominant exponential of P_FPL, Eq. (16) with its sign restored: e^{-x/(√2 l)}."""
    return amplitude * np.exp(-free_path_decay_rate(d) * np.asarray(x, dtype=float))


def maxwell_free_path_pdf(x, d: int):
    """Maxwell molecules' P_FPL, Eq. (D3): ∫ dv φ(v) (ω/v) e^{-ω x / v}; x in units of l."""
    scale = mean_free_path(d)

    def log_terms(v, r, length):
        return -np.log(v) - length * scale / v

    return scale * np.exp(_log_speed_integrals(log_terms, x, d))


def maxwell_free_path_pdf_asymptotic(x, d: int):
    """Large-x saddle point of (D3), Eq. (D4); x in units of l.

    C e^{-3 y} 1F1((d-1)/2, 1/2, 3y/2), y = (ω x/√T)^{2/3}, with C = √2 ω Γ((d-1)/2) /
    (√T 3^{(d-1)/2} Γ(d/2)) (the square root of the printed prefactor covers 2 only, as
    the saddle point shows). Evaluated as C e^{-3y/2} 1F1(1 - d/2, 1/2, -3y/2) (Kummer).
    """
    scale = mean_free_path(d)
    y = (np.asarray(x, dtype=float) * scale) ** (2 / 3)
    prefactor = SQRT2 * special.gamma((d - 1) / 2) / (3 ** ((d - 1) / 2) * special.gamma(d / 2))
    return scale * prefactor * np.exp(-1.5 * y) * special.hyp1f1(1 - d / 2, 0.5, -1.5 * y)


# --------------------------------------------------------------------------- very hard particles
def vhp_collision_rate(speed, d: int):
    """r_VHP(v)/ω_VHP, Eq. (B2): 1/2 + v²/(2 d T0)."""
    v = np.asarray(speed, dtype=float)
    return 0.5 + v * v / (2.0 * d)


def vhp_free_flight_time_pdf(t, d: int):
    """P_FFT for very hard particles, Eq. (B4), t in units of 1/ω_VHP."""
    t = np.asarray(t, dtype=float)
    return (
        0.25
        * d ** (d / 2)
        * np.exp(-t / 2)
        * (d + t) ** (-d / 2 - 2)
        * (4 * d * d + (4 * t + 2) * d + t * t)
    )


# --------------------------------------------------------------------------- Poisson and Gaussian
def poisson_mu(lam, rate: float = 1.0):
    """Cumulant generating function of a Poisson process of ``rate``: rate (e^{-λ} - 1)."""
    return rate * np.expm1(-np.asarray(lam, dtype=float))


def poisson_cloning_estimator(lam, population, interval, duration, rate: float = 1.0):
    """Bias and standard deviation of one realization of the discrete-time cloning
    estimator of μ(λ) (``kinetic.cloning``'s ``cuda`` backend) where a clone's count in a
    control interval Δ is Poisson(rate Δ) whatever its state: Maxwell molecules.

    A weight w = e^{-λK} then has relative variance v = exp(rate Δ (e^{-λ} - 1)²) - 1
    (E e^{-sK} = exp(rate Δ (e^{-s} - 1)) at s = λ and 2λ), and the N_c weights of an
    interval are independent of each other and of the other intervals, copies of one
    clone included. ln of their mean, to first order in 1/N_c, has the mean
    rate Δ (e^{-λ} - 1) - v/(2 N_c) and the variance v/N_c; μ is the sum over the
    duration/Δ intervals divided by the duration. Returns (bias, standard deviation):
    -v/(2 N_c Δ) and sqrt(v/(N_c Δ duration)). The first order overstates the spread
    where N_c is not large against v (at N_c = 16, Δ = 4, λ = 1, v = 3.9: 0.088 against
    0.069 measured), where the log of the mean is far from linear in it; the next order
    is smaller by about v/N_c."""
    lam = np.asarray(lam, dtype=float)
    v = np.expm1(rate * interval * np.expm1(-lam) ** 2)
    return -v / (2.0 * population * interval), np.sqrt(v / (population * interval * duration))


def poisson_ldf(n, rate: float = 1.0):
    """Large deviation function of a Poisson process, Eq. (40): n - n ln(n/rate) - rate."""
    n = np.asarray(n, dtype=float)
    return n - special.xlogy(n, n / rate) - rate


def gaussian_temperature(lam):
    """T(λ)/T0 of the Gaussian closure, Eq. (43b): sqrt(2) / sqrt(1 + e^λ)."""
    lam = np.asarray(lam, dtype=float)
    return SQRT2 * np.exp(-0.5 * np.logaddexp(0.0, lam))


def gaussian_mu(lam):
    """μ(λ)/ω of the Gaussian closure, Eq. (43a): -(1 - e^{-λ}) sqrt(1 + T(λ)) / sqrt(2)."""
    lam = np.asarray(lam, dtype=float)
    return np.expm1(-lam) * np.sqrt(1 + gaussian_temperature(lam)) / SQRT2


def gaussian_cumulants(step: float = 0.02) -> np.ndarray:
    """<N^p>_c/(ω t) = (-1)^p μ^(p)(0), p = 1, 2, 3, of the Gaussian closure (Eq. 43).

    Table I gives 1, 1.125, 1.1289; the derivatives are taken by central differences of
    order h^4 (error ~1e-8).
    """
    return _derivatives_at_zero(gaussian_mu, step) * np.array([-1.0, 1.0, -1.0])


# --------------------------------------------------------------------------- Sonine closure
# Collisional moments of f = Gaussian(T) × polynomial against the bath φ = Gaussian(T0).
# By isotropy σ̂ can be fixed to e1; then g = (v1 - v2)·σ̂ ~ N(0, T + T0) contributes
# only for g > 0 with weight g; W ~ N(0, T T0/(T + T0)) is independent of g; the tagged
# velocity is v1 = (W + β g, u) before and v1' = (W - (1 - β) g, u) after the collision,
# β = T/(T + T0); R = |u|² is T times a chi-square with d - 1 degrees of freedom. Every
# moment needed (polynomials of degree <= 8 in W and g, <= 4 in R) is then an exact
# Gauss quadrature: Gauss–Hermite in W, Gauss–Laguerre in g²/2 for the even part in g
# and generalised Laguerre (α = 1/2) for the odd part, generalised Laguerre in R/(2T).
_ORDER = 6  # exact for degree <= 11 in each variable


@lru_cache(maxsize=8)
def _quadrature(d: int):
    w_nodes, w_weights = special.roots_hermitenorm(_ORDER)
    w_weights = w_weights / np.sqrt(2 * np.pi)
    y0, c0 = special.roots_genlaguerre(_ORDER, 0.0)
    y1, c1 = special.roots_genlaguerre(_ORDER, 0.5)
    r_nodes, r_weights = special.roots_genlaguerre(_ORDER, (d - 1) / 2 - 1)
    r_weights = r_weights / special.gamma((d - 1) / 2)
    return w_nodes, w_weights, np.sqrt(2 * y0), c0, np.sqrt(2 * y1), c1, 2 * r_nodes, r_weights


def _collision_average(function, temperature: float, d: int, bath: float = 1.0) -> float:
    """E[g Θ(g) F(W, g, R)] for a polynomial F(W, g, R) (see the comment above)."""
    w, w_weights, g_even, c_even, g_odd, c_odd, r, r_weights = _quadrature(d)
    s_w = np.sqrt(temperature * bath / (temperature + bath))
    s_g = np.sqrt(temperature + bath)
    W = (s_w * w)[:, None, None]
    R = (temperature * r)[None, None, :]
    weights_wr = w_weights[:, None, None] * r_weights[None, None, :]

    def summed(values, coefficients):
        return float(np.sum(weights_wr * coefficients[None, :, None] * values))

    def at(g):
        return function(W, s_g * g[None, :, None], R)

    even = summed(0.5 * (at(g_even) + at(-g_even)), c_even)
    odd = summed(0.5 * (at(g_odd) - at(-g_odd)) / g_odd[None, :, None], c_odd)
    return s_g * (even + np.sqrt(2.0) * odd) / np.sqrt(2 * np.pi)


@lru_cache(maxsize=65536)
def _moment_tables(temperature: float, d: int):
    """gain[n][s] and loss[n][s] / ω for ψ = v^n (n = 0, 2, 4) and f = Gaussian(T)
    (s = 0) or Gaussian(T) × S2(v²/2T) (s = 1): ν_n = e^{-λ} gain - loss."""
    beta = temperature / (temperature + 1.0)
    omega = 1.0 / np.sqrt(np.pi)  # E[g Θ(g)] at T = T0 = 1, so moments come in units of ω

    def sonine2(y):
        return 0.5 * y * y - (d + 2) / 2 * y + d * (d + 2) / 8

    def table(after: bool, n: int, with_sonine: bool) -> float:
        def integrand(W, g, R):
            speed2 = (W + beta * g) ** 2 + R
            moved = (W + (beta - 1.0) * g) ** 2 + R if after else speed2
            weight = sonine2(speed2 / (2 * temperature)) if with_sonine else 1.0
            return weight * moved ** (n // 2)

        return _collision_average(integrand, temperature, d) / omega

    gain = {n: [table(True, n, s) for s in (False, True)] for n in (0, 2, 4)}
    loss = {n: [table(False, n, s) for s in (False, True)] for n in (0, 2, 4)}
    return gain, loss


def _collisional_moments(lam: float, temperature: float, a2: float, d: int) -> np.ndarray:
    """ν_0, ν_2, ν_4 of Eq. (42)/(E1–E2) in units of ω, for f = Gaussian(T)(1 + a2 S2)."""
    gain, loss = _moment_tables(float(temperature), d)
    keep = np.exp(-lam)
    return np.array(
        [keep * (gain[n][0] + a2 * gain[n][1]) - (loss[n][0] + a2 * loss[n][1]) for n in (0, 2, 4)]
    )


def appendix_e_moments(lam: float, temperature: float, a2: float) -> np.ndarray:
    """ν_0, ν_2, ν_4 of Appendix E (d = 2, T0 = 1) as printed, E3 with its sign corrected.

    The appendix's time unit has |μ'(0)| = 1/sqrt(π); the values returned are divided by
    that, so they are in units of ω like ``_collisional_moments``.
    """
    t, e = temperature, np.exp(lam)
    s = np.sqrt(2 * np.pi)
    nu0_0 = (np.exp(-lam) - 1) * np.sqrt(t + 1) / s
    nu2_0 = (t * t + 2 * t + 2 - e * t * (3 * t + 2)) / (e * s * np.sqrt(t + 1))
    rp = np.sqrt(np.pi)
    nu4_0 = (
        rp * (-(e * t * t * (8 * t * t + 12 * t + 3)) + (3 * t * t + 12 * t + 8))
        - 4
        * t
        * (t + 1)
        * (3 * (e - 1) * rp * t * (t + 1) / 4 + rp * (e * t * (2 * t + 1) - (t + 2)) / 2)
    ) / (SQRT2 * e * np.pi * (t + 1) ** 1.5)
    nu0_1 = (e - 1) * t * t / (8 * e * s * (t + 1) ** 1.5)
    nu2_1 = (
        t
        * t
        * (-3 * (1 + e + 2 * (e - 1)) * t * t - (22 * e - 6) * t - 2 * (8 * e - 3))
        / (8 * e * s * (t + 1) ** 2.5)
    )
    nu4_1 = (
        t
        * t
        * (
            -45 * (5 * e - 1) * t**4
            + 6 * (28 - 132 * e) * t**3
            - (1000 * e - 228) * t * t
            + 4 * (36 - 128 * e) * t
            + 8 * (3 - 8 * e)
        )
        / (8 * e * s * (t + 1) ** 3.5)
    )
    unit = np.sqrt(np.pi)
    return unit * np.array([nu0_0 + a2 * nu0_1, nu2_0 + a2 * nu2_1, nu4_0 + a2 * nu4_1])


def _closure_residual(unknowns, lam: float, d: int, moments) -> np.ndarray:
    temperature, a2 = unknowns
    nu0, nu2, nu4 = moments(lam, temperature, a2, d)
    mu = nu0
    return np.array(
        [nu2 - mu * d * temperature, nu4 - mu * d * (d + 2) * temperature**2 * (1 + a2)]
    )


def _solve_branch(lams: np.ndarray, d: int, moments, gaussian: bool) -> np.ndarray:
    """Continue the root (T, a2) from λ = 0 along sorted ``lams`` (all of one sign).

    Returns rows (μ, T, a2); NaN from the first λ the branch cannot reach (the fold:
    the Jacobian vanishes and no real root continues the branch).
    """
    from scipy import optimize  # here: 0.4 s of import that most jobs of this module never use

    out = np.full((lams.size, 3), np.nan)
    state = np.array([1.0, 0.0])
    current = 0.0

    def residual(unknowns, lam):
        if gaussian:
            t = unknowns[0]
            nu0, nu2, _ = moments(lam, t, 0.0, d)
            return np.array([nu2 - nu0 * d * t])
        return _closure_residual(unknowns, lam, d, moments)

    for index, target in enumerate(lams):
        step = target - current
        ok = True
        while abs(target - current) > 0:
            trial = current + step if abs(step) < abs(target - current) else target
            guess = state[:1] if gaussian else state
            solution = optimize.root(
                residual, guess, args=(trial,), method="hybr", options={"xtol": 1e-13}
            )
            jump = np.max(np.abs(solution.x - guess))
            converged = np.max(np.abs(residual(solution.x, trial))) < 1e-11
            if converged and solution.x[0] > 0 and jump < 0.05 + 2 * abs(trial - current):
                state = np.array([solution.x[0], 0.0 if gaussian else solution.x[1]])
                current = trial
            else:
                step /= 2
                if abs(step) < 1e-6:
                    ok = False
                    break
        if not ok:
            break
        nu0 = moments(target, state[0], state[1], d)[0]
        out[index] = (nu0, state[0], state[1])
    return out


def _solve_closure(lam, d: int, moments, gaussian: bool) -> np.ndarray:
    lam = np.atleast_1d(np.asarray(lam, dtype=float))
    result = np.full((lam.size, 3), np.nan)
    for sign in (1.0, -1.0):
        picked = np.flatnonzero(sign * lam > 0)
        order = picked[np.argsort(sign * lam[picked])]
        if order.size:
            result[order] = _solve_branch(lam[order], d, moments, gaussian)
    zero = lam == 0
    result[zero] = (0.0, 1.0, 0.0)
    return result


def sonine_solution(lam, d: int = 2, *, moments: str = "exact"):
    """μ(λ)/ω, T(λ)/T0 and a2(λ) of the first Sonine closure, Eqs. (47)–(49).

    Solves μ m_n = ν_n for n = 0, 2, 4 with m0 = 1, m2 = d T, m4 = d(d+2) T² (1 + a2) by
    continuation from (T, a2) = (1, 0) at λ = 0. ``moments='exact'`` uses the collisional
    moments computed for any d; ``moments='appendix_e'`` uses Appendix E (d = 2 only).
    Beyond the fold of the branch (near λ ≈ 1.61 in d = 2) there is no real solution
    and NaN is returned.

    Returns three arrays (mu, temperature, a2) with the shape of ``lam``.
    """
    if moments == "exact":
        moment_function = _collisional_moments
    elif moments == "appendix_e":
        if d != 2:
            raise ValueError(f"Appendix E holds for d = 2 only, got d = {d}")

        def moment_function(lam_, t, a2, _d):
            return appendix_e_moments(lam_, t, a2)
    else:
        raise ValueError(f"moments must be 'exact' or 'appendix_e', got {moments!r}")
    shape = np.shape(lam)
    result = _solve_closure(lam, d, moment_function, gaussian=False)
    return tuple(result[:, k].reshape(shape) for k in range(3))


def gaussian_solution(lam, d: int = 2):
    """μ(λ)/ω and T(λ) of the Gaussian closure (Eq. 41) solved numerically in any d.

    In every d this reproduces Eq. (43), a check of the moment algebra.
    """
    shape = np.shape(lam)
    result = _solve_closure(lam, d, _collisional_moments, gaussian=True)
    return result[:, 0].reshape(shape), result[:, 1].reshape(shape)


def sonine_cumulants(d: int) -> np.ndarray:
    """<N^p>_c/(ω t), p = 1, 2, 3 of the Sonine closure, Eq. (50)."""
    k2 = 9 / 64 * (8 + 1 / (4 * d + 3))
    k3 = (28 * d * (64 * d * (320 * d + 729) + 35775) + 257391) / (8192 * (4 * d + 3) ** 3)
    return np.array([1.0, k2, k3])


def _derivatives_at_zero(function: Callable[[np.ndarray], np.ndarray], step: float) -> np.ndarray:
    """First three derivatives at 0 by central differences of order h^4."""
    h = step
    f = function(np.array([-3 * h, -2 * h, -h, h, 2 * h, 3 * h]))
    fm3, fm2, fm1, fp1, fp2, fp3 = f
    f0 = function(np.array([0.0]))[0]
    d1 = (fp3 - 9 * fp2 + 45 * fp1 - 45 * fm1 + 9 * fm2 - fm3) / (60 * h)
    d2 = (2 * fp3 - 27 * fp2 + 270 * fp1 - 490 * f0 + 270 * fm1 - 27 * fm2 + 2 * fm3) / (
        180 * h * h
    )
    d3 = (-fp3 + 8 * fp2 - 13 * fp1 + 13 * fm1 - 8 * fm2 + fm3) / (8 * h**3)
    return np.array([d1, d2, d3])


def sonine_cumulants_numerical(d: int = 2, *, moments: str = "exact", step: float = 0.02):
    """Cumulants (-1)^p μ^(p)(0) of the solved Sonine closure, to compare with Eq. (50)."""
    derivatives = _derivatives_at_zero(lambda x: sonine_solution(x, d, moments=moments)[0], step)
    return derivatives * np.array([-1.0, 1.0, -1.0])


# --------------------------------------------------------------------------- Legendre transforms
def legendre_transform(
    mu: Callable[[np.ndarray], np.ndarray],
    n,
    *,
    slope: Callable | None = None,
    bracket: tuple[float, float] = (-40.0, 700.0),
    mu_at_infinity: float | None = None,
):
    """π(n) = min_λ [μ(λ) + λ n] (Eq. 32) for a convex μ, at rates n >= 0.

    The minimiser solves μ'(λ) = -n by bracketing (μ' increases with λ). ``slope`` is μ'
    (central differences when omitted). If μ' stays below -n on the whole bracket the
    infimum is reached as λ -> +∞: ``mu_at_infinity`` when given (n = 0 only), else NaN.
    An approximate μ need not be monotone: the Gaussian closure (43) has μ' > 0 beyond
    λ ≈ 2.91, where its minimum μ = -0.76857 lies (its approach to -1/√2 from below,
    Eq. 44), so its π(0) = min μ < -1/√2.
    """
    from scipy import optimize

    n = np.asarray(n, dtype=float)
    if np.any(n < 0):
        raise ValueError("the collision rate n must be >= 0")

    def scalar(x):
        return float(np.asarray(mu(np.array([x])))[0])

    def derivative(x):
        if slope is not None:
            return float(np.asarray(slope(np.array([x])))[0])
        h = 1e-5 * max(1.0, abs(x))
        return (scalar(x + h) - scalar(x - h)) / (2 * h)

    out = np.full(n.shape, np.nan)
    lo, hi = bracket
    for index, rate in np.ndenumerate(n):
        f_lo, f_hi = derivative(lo) + rate, derivative(hi) + rate
        if f_lo < 0 < f_hi:
            root = optimize.brentq(
                lambda x, r=rate: derivative(x) + r, lo, hi, xtol=1e-13, rtol=1e-13
            )
            out[index] = scalar(root) + root * rate
        elif f_hi <= 0 and rate == 0 and mu_at_infinity is not None:
            out[index] = mu_at_infinity
    return out


def _gaussian_mu_slope(lam):
    """dμ/dλ of Eq. (43) (analytic)."""
    lam = np.asarray(lam, dtype=float)
    t = gaussian_temperature(lam)
    dt = -0.5 * t * np.exp(lam - np.logaddexp(0.0, lam))
    one_minus = -np.expm1(-lam)
    return -(np.exp(-lam) * np.sqrt(1 + t) + one_minus * dt / (2 * np.sqrt(1 + t))) / SQRT2


def gaussian_ldf(n):
    """π(n) of the Gaussian closure: numerical Legendre transform of Eq. (43) (Fig. 3)."""
    return legendre_transform(gaussian_mu, n, slope=_gaussian_mu_slope)


# --------------------------------------------------------------------- finite-time estimates
# The MD estimate of π(n) at a window t is π_t(n) = (1/t) ln[P(N = k)/max_j P(N = j)],
# n = k/t. It tends to π(n) as t -> ∞ only with an O(ln t / t) error: comparing the data at
# t = 10 or 50 with the t -> ∞ curves mixes that error with the physics. The functions
# below apply the same estimator to the count distribution of a model at the same t.
def _normalised_log_probability(log_probability, t: float):
    """(1/t) [ln P(k) - max_j ln P(j)] over the counts given (they must hold the mode)."""
    log_probability = np.asarray(log_probability, dtype=float)
    return (log_probability - np.nanmax(log_probability)) / t


def poisson_count_ldf(t: float, counts, rate: float = 1.0):
    """Exact π_t(k/t) of a Poisson count of mean ``rate`` t: P(k) = (rate t)^k e^{-rate t}/k!.

    ``counts`` (integers >= 0) must include the mode floor(rate t) or the value there.
    """
    counts = np.asarray(counts, dtype=float)
    if t <= 0 or np.any(counts < 0):
        raise ValueError(f"need t > 0 and counts >= 0, got t = {t}")
    log_probability = special.xlogy(counts, rate * t) - rate * t - special.gammaln(counts + 1)
    return _normalised_log_probability(log_probability, t)


def saddle_point_count_ldf(
    mu: Callable[[np.ndarray], np.ndarray],
    slope: Callable[[np.ndarray], np.ndarray],
    t: float,
    counts,
    *,
    bracket: tuple[float, float] = (-40.0, 60.0),
):
    """π_t(k/t) of a count whose generating function is ⟨e^{-λN}⟩ ≈ e^{t μ(λ)}, to the
    leading order in 1/t: the saddle point of the inverse transform gives

        P(N = k) ≈ e^{t π(n)} / sqrt(2π t μ''(λ*)),   μ'(λ*) = -n,  π(n) = μ(λ*) + λ* n,

    (for Poisson this is Stirling's formula). The O(1/t) term from the overlap of the
    initial state with the eigenvectors of the tilted operator is left out (it is 1 for
    a Poisson process). Returns NaN at k = 0, where a continuous saddle point does not
    describe an integer count (Stirling's formula fails there too), and where μ' = -n has no
    root in ``bracket``.
    """
    from scipy import optimize

    counts = np.asarray(counts, dtype=float)
    if t <= 0 or np.any(counts < 0):
        raise ValueError(f"need t > 0 and counts >= 0, got t = {t}")
    lo, hi = bracket

    def derivative(x):
        return float(np.asarray(slope(np.array([x])))[0])

    log_probability = np.full(counts.shape, np.nan)
    for index, count in np.ndenumerate(counts):
        rate = count / t
        if count == 0 or not derivative(lo) + rate < 0 < derivative(hi) + rate:
            continue
        root = optimize.brentq(lambda x, r=rate: derivative(x) + r, lo, hi, xtol=1e-13)
        h = 1e-4 * max(1.0, abs(root))
        curvature = (derivative(root + h) - derivative(root - h)) / (2 * h)
        ldf = float(np.asarray(mu(np.array([root])))[0]) + root * rate
        log_probability[index] = t * ldf - 0.5 * np.log(2 * np.pi * t * curvature)
    return _normalised_log_probability(log_probability, t)


def gaussian_count_ldf(t: float, counts):
    """π_t(k/t) of the Gaussian closure (Eq. 43) at window t, saddle-point order."""
    return saddle_point_count_ldf(gaussian_mu, _gaussian_mu_slope, t, counts)


@lru_cache(maxsize=8)
def _speed_table(d: int):
    """Speeds, weights (of the Maxwell speed density, with dv) and r(v)/ω of the speed
    integrals' quadrature (``_log_speed_rule``), out of log space (once per dimension:
    the minimisations of ``uncorrelated_ldf`` read it at every step)."""
    v, log_weights, rate = _log_speed_rule(d)
    return v, np.exp(log_weights), rate


def _log_laplace_and_slope(z: float, d: int) -> tuple[float, float]:
    """ln P̃_FFT(z) and its derivative in z (trapezoid on the log-speed grid)."""
    _, weights, rate = _speed_table(d)
    terms = weights * rate * rate / (rate + z)
    total = terms.sum()
    return float(np.log(total)), float(-(terms / (rate + z)).sum() / total)


def uncorrelated_ldf(n, d: int = 2):
    """π(n) = min_z [z + n ln P̃_FFT(z)], Eq. (23), for z > -1/√2 (uncorrelated flights).

    z + n ln P̃(z) is convex (ln P̃ is the log of a Laplace transform); its minimiser
    solves 1 + n d ln P̃/dz = 0. At n = 0 the infimum -1/√2 is approached as z -> -1/√2.
    """
    from scipy import optimize

    n = np.asarray(n, dtype=float)
    if np.any(n < 0):
        raise ValueError("the collision rate n must be >= 0")
    z_min = -1 / SQRT2
    out = np.empty(n.shape)

    def slope(z, rate):
        return 1 + rate * _log_laplace_and_slope(z, d)[1]

    for index, rate in np.ndenumerate(n):
        if rate == 0:
            out[index] = z_min
            continue
        lo = z_min + 1e-12
        hi = max(10.0, 4 * rate)
        while slope(hi, rate) <= 0:
            hi *= 4
        z = lo if slope(lo, rate) >= 0 else optimize.brentq(slope, lo, hi, args=(rate,), xtol=1e-14)
        out[index] = z + rate * _log_laplace_and_slope(z, d)[0]
    return out
