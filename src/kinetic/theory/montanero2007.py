"""Theory of Montanero, Santos & Garzó (2007): heat flux of a dilute granular gas.

First-order Chapman–Enskog (Navier–Stokes) distribution of inelastic hard disks (d = 2)
or spheres (d = 3) with a constant coefficient of normal restitution α, measured by
a homogeneous heat-flux force (Eq. 3.2) instead of a temperature gradient.

Units and notation
------------------
Everything here is dimensionless unless a function says otherwise:

- ``c = V / v_0`` is the velocity relative to the *thermal speed* ``v_0 = sqrt(2T/m)``
  (Eq. 2.11, 2.45);
- the *effective collision frequency* of Eq. (2.15) is written ``nu0`` here.  The paper's
  markdown writes it ``v_0`` as well (Eqs. 2.14, 2.15, 2.46, 2.47): the two are different
  quantities.  Reduced rates are ``zeta* = zeta / nu0`` and
  ``nu_kappa* = nu_kappa / nu0``;
- the simulation units of Section 4: mean free path ``lambda = 1 / (sqrt(2) pi n sigma^2)``
  (d = 3; :func:`mean_free_path` gives the d-dimensional analogue), mean free time
  ``tau = lambda / v_0`` and reduced field ``eps* = lambda * eps``.  ``nu0 * tau`` is a
  pure number (:func:`nu0_tau`, 8/(5 sqrt(pi)) in d = 3) and is the single place where
  the two systems of units meet.

Typos of the source fixed here
------------------------------
- Eqs. (2.41)/(2.42) read ``kappa = (d+2)/2 (nT/m) (1 + 2 a2) / (nu_kappa - 2 zeta)`` and
  ``kappa' = (d+2)/2 (nT/m) (1 + 3 a2 / 2) / (nu_kappa' - 3 zeta / 2)``;
- Eq. (3.5): the left side is the thermostat parameter, the right side the cooling rate;
- Eq. (4.6) integrates over ``0 <= u_x <= |c_x|`` (the printed upper limit ``c_x^2`` is
  the argument of beta_1, not a bound on u_x): only then does beta_1 tend to b'_1.

Modified first Sonine approximation (Garzó, Santos & Montanero, Physica A 376, 94
(2007), the paper's Ref. [28]): same structure as (2.41)–(2.42) with the collision
frequency of :func:`reduced_nu_kappa_modified`, which follows from the trial function
``f0 (c^2 - (d+2)(1+a2)/2) c`` (the HCS distribution replaces the Gaussian weight).
"""

from __future__ import annotations

import numpy as np
from scipy import special

__all__ = [
    "KAPPA_ELASTIC_HIGHER_SONINE",
    "b_coefficients",
    "beta1",
    "beta1_sonine",
    "effective_collision_frequency",
    "elastic_conductivity",
    "full_route_prefactor",
    "hcs_a2",
    "kappa_prime_ratio",
    "kappa_prime_ratio_from_b1",
    "kappa_prime_ratio_from_heat_flux",
    "kappa_ratio",
    "laguerre",
    "marginal_route_prefactor",
    "mean_free_path",
    "mean_free_time",
    "nu0_tau",
    "phi_sonine",
    "reduced_a2_from_moment",
    "reduced_cooling_rate",
    "reduced_nu_kappa",
    "reduced_nu_kappa_modified",
    "sonine_b1_from_kappa_prime_ratio",
    "sonine_weights_full",
    "sonine_weights_marginal",
    "thermal_speed",
]

KAPPA_ELASTIC_HIGHER_SONINE = 1.025218
"""kappa/kappa0 of elastic hard spheres (d = 3) with higher Sonine orders (paper's Ref. [37]);
the arrow of Fig. 3.  For alpha = 1, kappa' = kappa."""

FIG07_QUOTED_SHARES = {1.0: 0.87, 0.3: 0.66}
"""Fig. 7: the share of b'_1 below c_x^2 = 6 that the document quotes, by alpha.  The
caption sets the eps* -> 0 share beside each, so only these alpha need their larger-field
partner run.  A document number, kept here (not in the study) so that the figure script
does not depend on the study module and its cost model."""

APPROXIMATIONS = ("standard", "modified")


def _check_dimension(d: int) -> int:
    if isinstance(d, bool) or not isinstance(d, int | np.integer) or d < 2:
        raise ValueError(f"dimension d must be an integer >= 2, got {d!r}")
    return int(d)


def _check_alpha(alpha) -> np.ndarray:
    alpha = np.asarray(alpha, dtype=float)
    if np.any(~np.isfinite(alpha)) or np.any(alpha < 0.0) or np.any(alpha > 1.0):
        raise ValueError(f"coefficient of restitution alpha must lie in [0, 1], got {alpha}")
    return alpha


# --------------------------------------------------------------------------- units


def thermal_speed(temperature=1.0, mass=1.0):
    """Thermal speed ``v_0 = sqrt(2 T / m)`` of Eq. (2.11) [velocity units]."""
    return np.sqrt(2.0 * np.asarray(temperature, dtype=float) / mass)


def mean_free_path(density, diameter=1.0, d: int = 3):
    """Mean free path ``lambda = 1 / (sqrt(2) n S)`` [length units].

    ``S = pi^((d-1)/2) / Gamma((d+1)/2) sigma^(d-1)`` is the collision cross-section
    (``pi sigma^2`` in d = 3, which gives the paper's ``1 / (sqrt(2) pi n sigma^2)``;
    ``2 sigma`` in d = 2).  ``density`` is the number density n [length^-d].
    """
    d = _check_dimension(d)
    cross_section = np.pi ** ((d - 1) / 2) / special.gamma((d + 1) / 2) * diameter ** (d - 1)
    return 1.0 / (np.sqrt(2.0) * np.asarray(density, dtype=float) * cross_section)


def mean_free_time(density, temperature=1.0, diameter=1.0, mass=1.0, d: int = 3):
    """Time unit of Section 4, ``tau = lambda / v_0`` [time units]."""
    return mean_free_path(density, diameter, d) / thermal_speed(temperature, mass)


def effective_collision_frequency(density, temperature=1.0, diameter=1.0, mass=1.0, d: int = 3):
    """Effective collision frequency nu0 of Eq. (2.15) [1/time].

    ``nu0 = 8/(d+2) pi^((d-1)/2) / Gamma(d/2) n sigma^(d-1) sqrt(T/m)``.  Written ``v_0``
    in the paper's markdown, not to be confused with the thermal speed.
    """
    d = _check_dimension(d)
    prefactor = 8.0 / (d + 2) * np.pi ** ((d - 1) / 2) / special.gamma(d / 2)
    return (
        prefactor
        * np.asarray(density, dtype=float)
        * diameter ** (d - 1)
        * np.sqrt(np.asarray(temperature, dtype=float) / mass)
    )


def nu0_tau(d: int = 3) -> float:
    """The pure number ``nu0 * tau`` (Eq. 2.15 times ``lambda / v_0``).

    ``8 / (5 sqrt(pi)) = 0.902703...`` in d = 3; independent of n, T, sigma and m.
    """
    return float(effective_collision_frequency(1.0, d=d) * mean_free_time(1.0, d=d))


def elastic_conductivity(density, temperature=1.0, diameter=1.0, mass=1.0, d: int = 3):
    """Elastic first-Sonine thermal conductivity kappa0 of Eq. (2.47) [n T / (m nu0) units].

    ``kappa0 = d (d+2) / (2 (d-1)) n T / (m nu0)`` with nu0 from Eq. (2.15) (Boltzmann
    constant 1, so kappa0 has units of 1/(length^(d-2) time)).
    """
    d = _check_dimension(d)
    nu0 = effective_collision_frequency(density, temperature, diameter, mass, d)
    return d * (d + 2) / (2.0 * (d - 1)) * density * temperature / (mass * nu0)


# ------------------------------------------------------------------- HCS and rates


def hcs_a2(alpha, d: int = 3):
    """Fourth cumulant a2 of the homogeneous cooling state, Eq. (2.16) (dimensionless).

    ``a2 = 16 (1-alpha)(1-2 alpha^2) / [25 + 24 d - alpha (57 - 8 d) - 2 (1-alpha) alpha^2]``;
    zero at alpha = 1 and at alpha = 1/sqrt(2).
    """
    d = _check_dimension(d)
    alpha = _check_alpha(alpha)
    numerator = 16.0 * (1.0 - alpha) * (1.0 - 2.0 * alpha**2)
    denominator = 25.0 + 24.0 * d - alpha * (57.0 - 8.0 * d) - 2.0 * (1.0 - alpha) * alpha**2
    return numerator / denominator


def _a2_or_default(alpha, d, a2):
    return hcs_a2(alpha, d) if a2 is None else np.asarray(a2, dtype=float)


def reduced_a2_from_moment(c4_mean, d: int = 3):
    """a2 from the measured ``<c^4>`` (c = V / v_0), inverting Eq. (2.13).

    ``<c^4> = d (d+2) / 4 (1 + a2)``.
    """
    d = _check_dimension(d)
    return np.asarray(c4_mean, dtype=float) / (d * (d + 2) / 4.0) - 1.0


def reduced_cooling_rate(alpha, d: int = 3, a2=None):
    """Reduced cooling rate ``zeta* = zeta^(0) / nu0``, Eq. (2.14).

    ``zeta* = (d+2)/(4d) (1 - alpha^2) (1 + 3 a2 / 16)``; a2 defaults to Eq. (2.16).
    """
    d = _check_dimension(d)
    alpha = _check_alpha(alpha)
    a2 = _a2_or_default(alpha, d, a2)
    return (d + 2) / (4.0 * d) * (1.0 - alpha**2) * (1.0 + 3.0 * a2 / 16.0)


def reduced_nu_kappa(alpha, d: int = 3, a2=None):
    """First-Sonine collision frequency ``nu_kappa* = nu_kappa' * = nu_kappa / nu0``, Eq. (2.46).

    ``(1+alpha)/d [(d-1)/2 + 3 (d+8)(1-alpha)/16 + (4 + 5d - 3 (4-d) alpha) a2 / 512]``.
    At alpha = 1: ``(d-1)/d``.
    """
    d = _check_dimension(d)
    alpha = _check_alpha(alpha)
    a2 = _a2_or_default(alpha, d, a2)
    bracket = (
        (d - 1) / 2.0
        + 3.0 * (d + 8) * (1.0 - alpha) / 16.0
        + (4.0 + 5.0 * d - 3.0 * (4.0 - d) * alpha) * a2 / 512.0
    )
    return (1.0 + alpha) / d * bracket


def reduced_nu_kappa_modified(alpha, d: int = 3, a2=None):
    """Collision frequency of the modified first Sonine approximation (Ref. [28]).

    ``(1+alpha)/d [(d-1)/2 + 3 (d+8)(1-alpha)/16 + (296 + 217 d - 3 (160 + 11 d) alpha) a2/256]``.
    Equal to Eq. (2.46) at a2 = 0.
    """
    d = _check_dimension(d)
    alpha = _check_alpha(alpha)
    a2 = _a2_or_default(alpha, d, a2)
    bracket = (
        (d - 1) / 2.0
        + 3.0 * (d + 8) * (1.0 - alpha) / 16.0
        + (296.0 + 217.0 * d - 3.0 * (160.0 + 11.0 * d) * alpha) * a2 / 256.0
    )
    return (1.0 + alpha) / d * bracket


def _nu_for(approximation: str):
    if approximation == "standard":
        return reduced_nu_kappa
    if approximation == "modified":
        return reduced_nu_kappa_modified
    raise ValueError(f"approximation must be one of {APPROXIMATIONS}, got {approximation!r}")


def kappa_ratio(alpha, d: int = 3, approximation: str = "standard", a2=None):
    """Thermal conductivity ``kappa / kappa0``, Eq. (2.41) (typo fixed) over Eq. (2.47).

    ``kappa/kappa0 = (d-1)/d (1 + 2 a2) / (nu_kappa* - 2 zeta*)``; ``approximation`` is
    ``"standard"`` (Eq. 2.46) or ``"modified"`` (Ref. [28]).  Equal to 1 at alpha = 1.
    """
    d = _check_dimension(d)
    alpha = _check_alpha(alpha)
    a2 = _a2_or_default(alpha, d, a2)
    nu = _nu_for(approximation)(alpha, d, a2)
    zeta = reduced_cooling_rate(alpha, d, a2)
    return (d - 1) / d * (1.0 + 2.0 * a2) / (nu - 2.0 * zeta)


def kappa_prime_ratio(alpha, d: int = 3, approximation: str = "standard", a2=None):
    """Modified thermal conductivity ``kappa' / kappa0``, Eq. (2.42), typo fixed.

    ``kappa'/kappa0 = (d-1)/d (1 + 3 a2 / 2) / (nu_kappa'* - 3 zeta* / 2)`` with
    ``nu_kappa'*`` from Eq. (2.46) (``"standard"``) or Ref. [28] (``"modified"``).
    The first Sonine line of Fig. 3; equal to 1 at alpha = 1.
    """
    d = _check_dimension(d)
    alpha = _check_alpha(alpha)
    a2 = _a2_or_default(alpha, d, a2)
    nu = _nu_for(approximation)(alpha, d, a2)
    zeta = reduced_cooling_rate(alpha, d, a2)
    return (d - 1) / d * (1.0 + 1.5 * a2) / (nu - 1.5 * zeta)


def kappa_prime_ratio_from_b1(b1, d: int = 3):
    """``kappa'/kappa0 = (d-1)/d nu0 tau b'_1``, from Eqs. (2.45) and (2.47).

    ``16 / (15 sqrt(pi)) b'_1`` in d = 3.
    """
    d = _check_dimension(d)
    return (d - 1) / d * nu0_tau(d) * np.asarray(b1, dtype=float)


def sonine_b1_from_kappa_prime_ratio(ratio, d: int = 3):
    """Inverse of :func:`kappa_prime_ratio_from_b1`: b'_1 from kappa'/kappa0."""
    d = _check_dimension(d)
    return np.asarray(ratio, dtype=float) * d / ((d - 1) * nu0_tau(d))


def kappa_prime_ratio_from_heat_flux(c2_cx_mean, eps_star, d: int = 3):
    """kappa'/kappa0 from the reduced heat flux, Eqs. (2.7), (3.9), (2.47).

    ``q_x = (m/2) n v_0^3 <c^2 c_x>`` and ``kappa' = -q_x / (T eps)`` give
    ``kappa'/kappa0 = -4 (d-1) / (d (d+2)) nu0 tau <c^2 c_x> / eps*``
    (``-64 / (75 sqrt(pi)) <c^2 c_x> / eps*`` in d = 3).
    """
    d = _check_dimension(d)
    factor = 4.0 * (d - 1) / (d * (d + 2)) * nu0_tau(d)
    return -factor * np.asarray(c2_cx_mean, dtype=float) / eps_star


# --------------------------------------------------------------- Laguerre machinery


def laguerre(k: int, p: float, x):
    """Generalized Laguerre polynomial ``L_k^(p)(x)`` (orthogonality: Eq. 2.12)."""
    if k < 0:
        raise ValueError(f"Laguerre order k must be >= 0, got {k}")
    return special.eval_genlaguerre(int(k), float(p), np.asarray(x, dtype=float))


def full_route_prefactor(k, d: int = 3):
    """``2 Gamma(1 + d/2) k! / Gamma(k + 1 + d/2)``, the prefactor of Eq. (3.10)."""
    d = _check_dimension(d)
    k = np.asarray(k, dtype=float)
    return 2.0 * special.gamma(1.0 + d / 2) * special.gamma(k + 1.0) / special.gamma(k + 1 + d / 2)


def marginal_route_prefactor(k):
    """``2 Gamma(3/2) k! / Gamma(k + 3/2)``, the prefactor of Eq. (3.12)."""
    k = np.asarray(k, dtype=float)
    return 2.0 * special.gamma(1.5) * special.gamma(k + 1.0) / special.gamma(k + 1.5)


def sonine_weights_full(velocities, k_max: int = 3):
    """Per-particle ``c_x L_k^(d/2)(c^2)`` for k = 1..k_max (the averages of Eq. 3.10).

    ``velocities``: (n, d) reduced velocities c = V/v_0 (x is column 0).
    Returns (k_max, n).
    """
    c = np.asarray(velocities, dtype=float)
    d = c.shape[1]
    c2 = np.einsum("ij,ij->i", c, c)
    return np.stack([c[:, 0] * laguerre(k, d / 2, c2) for k in range(1, k_max + 1)])


def sonine_weights_marginal(cx, k_max: int = 3):
    """Per-particle ``c_x L_k^(1/2)(c_x^2)`` for k = 1..k_max (the averages of Eq. 3.12).

    ``cx``: (n,) reduced x-velocities.  Returns (k_max, n).
    """
    cx = np.asarray(cx, dtype=float)
    return np.stack([cx * laguerre(k, 0.5, cx**2) for k in range(1, k_max + 1)])


def b_coefficients(moments, eps_star, route: str, d: int = 3):
    """Sonine coefficients b'_k from measured averages, Eq. (3.10) or (3.12).

    ``moments[..., k-1]`` holds ``<c_x L_k^(d/2)(c^2)>`` (``route="full"``, Eq. 3.10) or
    ``<c_x L_k^(1/2)(c_x^2)>`` (``route="marginal"``, Eq. 3.12) for k = 1..K; the
    linear-response limit is taken as the ratio at the given small ``eps_star``.
    """
    moments = np.asarray(moments, dtype=float)
    k = np.arange(1, moments.shape[-1] + 1)
    if route == "full":
        prefactor = full_route_prefactor(k, d)
    elif route == "marginal":
        prefactor = marginal_route_prefactor(k)
    else:
        raise ValueError(f"route must be 'full' (Eq. 3.10) or 'marginal' (Eq. 3.12), got {route!r}")
    return prefactor * moments / eps_star


def phi_sonine(cx2, b):
    """Truncated Sonine series ``phi_p(c_x^2) = sum_{k=1}^p b'_k L_k^(1/2)(c_x^2)``, Eq. (4.5).

    ``b``: (p,) coefficients b'_1..b'_p (or (..., p), broadcast against ``cx2``'s shape
    with a trailing axis); p = len(b).
    """
    b = np.asarray(b, dtype=float)
    cx2 = np.asarray(cx2, dtype=float)
    total = np.zeros(np.broadcast_shapes(cx2.shape, b.shape[:-1]))
    for k in range(1, b.shape[-1] + 1):
        total = total + b[..., k - 1] * laguerre(k, 0.5, cx2)
    return total


def beta1(cx2, phi):
    """Cumulative contribution to b'_1 of the particles with ``u_x^2 < c_x^2``, Eq. (4.6).

    ``beta1(c_x^2) = 8/(3 sqrt(pi)) int_0^{|c_x|} du u^2 (3/2 - u^2) exp(-u^2) phi(u^2)``
    evaluated by the trapezoidal rule in u on the given grid.  ``cx2``: increasing
    grid of c_x^2 starting at 0 (or the first point is taken as the lower bound);
    ``phi``: values of phi on it (last axis).  Returns beta1 on the grid; it tends to
    b'_1 as c_x^2 -> infinity.
    """
    cx2 = np.asarray(cx2, dtype=float)
    u = np.sqrt(cx2)
    integrand = u**2 * (1.5 - u**2) * np.exp(-(u**2)) * np.asarray(phi, dtype=float)
    from scipy import integrate  # here: 0.25 s of import that most jobs never use

    return 8.0 / (3.0 * np.sqrt(np.pi)) * integrate.cumulative_trapezoid(integrand, u, initial=0)


def beta1_sonine(cx2, b):
    """Eq. (4.6) for the truncated series ``phi_p`` of Eq. (4.5), by adaptive quadrature.

    ``cx2``: (m,) values of c_x^2 >= 0; ``b``: (p,) coefficients.  Tends to b'_1.
    """
    from scipy import integrate

    b = np.asarray(b, dtype=float)

    def integrand(u):
        return u**2 * (1.5 - u**2) * np.exp(-(u**2)) * phi_sonine(u**2, b)

    values = [
        integrate.quad(integrand, 0.0, np.sqrt(x), epsabs=1e-13, epsrel=1e-12)[0]
        for x in np.atleast_1d(np.asarray(cx2, dtype=float))
    ]
    return 8.0 / (3.0 * np.sqrt(np.pi)) * np.asarray(values).reshape(np.shape(cx2))


def beta1_share(cx2, b=(1.0,)):
    """beta_1(cx2)/b'_1 (Eq. 4.6) for phi(c_x^2) = sum_k b'_k L_k^(1/2)(c_x^2) (Eq. 4.4).

    The share of b'_1 carried by particles with c_x^2 < ``cx2``; with ``b = (1,)`` (the first
    Sonine approximation) it does not depend on alpha: 0.8419 at cx2 = 6.  The series'
    higher terms integrate to zero over all c_x (orthogonality), so the limit is 1 for any b.
    """
    from scipy import integrate

    def integrand(u):
        phi = sum(bk * laguerre(k + 1, 0.5, u * u) for k, bk in enumerate(b))
        return u * u * (1.5 - u * u) * np.exp(-u * u) * phi

    total = integrate.quad(integrand, 0.0, np.inf)[0]
    return integrate.quad(integrand, 0.0, float(np.sqrt(cx2)))[0] / total
