"""Deterministic reference solution of the eigenvalue problem visco2008 Eq. (28).

Used to validate the cloning Monte Carlo beyond the Gaussian (Eq. 43) and first-Sonine
(Eqs. 47-49, Appendix E) approximations. Hard spheres, d = 2 or 3, T0 = 1, ω = 1.

Derivation. A collision of a particle at v' with apse vector σ̂ (uniform on the sphere,
measure dσ̂/Ω_d) and bath normal velocity u = v2·σ̂ ~ N(0, 1) happens at rate density
K (v'·σ̂ - u)⁺ with K = √π (ω = 1) and yields v = v' - (v'·σ̂ - u) σ̂. Changing variables
from (σ̂, u) to the jump Δ = v - v' (|Δ| = v'·σ̂ - u, σ̂ = -Δ̂, so u = -v·Δ̂ and
d^dΔ = |Δ|^{d-1} d|Δ| dσ̂) gives the transition rate density (Eq. 4 with its garbled
exponent restored)

    W(v | v') = (K/Ω_d) |v - v'|^{2-d} φ1(v·n),  n = (v - v')/|v - v'|,

with φ1 the standard normal density. For an isotropic eigenfunction F(|v|), the gain term
is ∫ k(v, w) F(w) dw with the radial kernel

    d = 2:  k(v, w) = (K w/2π) ∫_0^{2π} dθ φ1(A),
    d = 3:  k(v, w) = (K w²/2) ∫_{-1}^{1} dx φ1(A)/D,
    D² = v² + w² - 2vwx,  A = (v² - vwx)/D,  x = cos θ,

and Eq. (28) becomes μ F(v) = e^{-λ} ∫ k(v, w) F(w) dw - r(v) F(v). It is discretised by
Nyström quadrature on graded Gauss-Legendre nodes w = v_max t^2; the loss rate r(w_j) is
the discrete column sum of the gain kernel (number conservation), so λ = 0 gives μ = 0
and the Maxwellian exactly, and ⟨r⟩ = ω = 1 to quadrature accuracy. The largest real
eigenvalue is μ(λ); T and a2 follow from the eigenvector's moments.

Accuracy (d = 2; the error decreases as n_nodes^-2, so 600 and 900 nodes extrapolate to
the converged value): at 300 nodes μ is 4.3e-4, 1.9e-4, 5.9e-5 and -1.6e-5 off at
λ = -1.5, -1, -0.5 and 1 (at 600 nodes a quarter of that), below 1e-5 from λ = 1.5 on;
T and a2 to ~1e-4, about three times worse in d = 3; at λ = -3 the error of μ is ~2e-3.
For λ >~ 3 (d = 2) the eigenfunction spreads
logarithmically towards v = 0 (note below) and T, a2 are not resolved by any fixed
grid, while μ approaches -1/√2 fast (μ + 1/√2 = 5.9e-4, 1.1e-5, 3e-7 and 1.5e-8 at
λ = 2.5, 3, 3.3 and 3.5; 300 nodes); in d = 3 the eigenvalue reaches the edge -1/√2 between
λ = 2 and 3 and the eigenvector is then meaningless.

Note on large λ. μ(λ) >= -r(0) = -1/√2 for every λ (the probability of no collision up
to t decays as e^{-t/√2}), and the eigenvalue sits just above that edge of the continuous
spectrum of -r(v): in d = 2 the bound state exists but μ + 1/√2 ~ exp(-C e^{λ}) with
C ≈ 1/2 (r(v) - r(0) ≈ v²/(4√2) makes the Birman-Schwinger integral diverge only
logarithmically); in d = 3 it disappears above a finite λ. The first-order term of
visco2008 Eq. (38), +e^{-λ}/√2, treats the δ(v) eigenfunction of L0 as isolated; it is
not. Eq. (37) projects L1 δ on the constant (the left eigenvector of the full operator
at λ = 0), whereas first-order perturbation theory needs the left eigenvector of
L0 = -r(v), which is δ(v) too: the collisions move the particle away from v = 0, and the
projection vanishes. The exact μ lies below Eq. (38) by nearly e^{-λ}/√2 (by 0.088 at
λ = 2, 0.035 at λ = 3, 0.013 at λ = 4), differences the cloning Monte Carlo resolves.
"""

from __future__ import annotations

import numpy as np
from numpy.polynomial.legendre import leggauss

__all__ = [
    "RESOLVED_LAMBDA_MAX",
    "collision_rate",
    "exact_cumulants",
    "reference_solution",
    "window_cumulants",
]

_K = np.sqrt(np.pi)


def _phi1(x):
    return np.exp(-0.5 * x * x) / np.sqrt(2.0 * np.pi)


def _nodes(n_nodes, v_max, grade):
    t, weights = leggauss(n_nodes)
    t = 0.5 * (t + 1.0)
    weights = 0.5 * weights
    return v_max * t**grade, v_max * grade * t ** (grade - 1.0) * weights


def _radial_kernel(dimension, v, w, n_angles):
    """k(v_i, w_j) for 1-D arrays v (rows) and w (columns), shape (v.size, w.size)."""
    t, weights = leggauss(n_angles)
    t = 0.5 * (t + 1.0)
    weights = 0.5 * weights
    big_v = v[:, None, None]
    big_w = w[None, :, None]
    if dimension == 2:
        # θ = π t³ clusters the points near θ = 0 where A varies fast when v ≈ w
        theta = np.pi * t**3
        jacobian = 3.0 * np.pi * t**2 * weights
        x = np.cos(theta)[None, None, :]
        d = np.sqrt(np.maximum(big_v**2 + big_w**2 - 2.0 * big_v * big_w * x, 1e-300))
        a = (big_v**2 - big_v * big_w * x) / d
        integral = 2.0 * np.sum(_phi1(a) * jacobian, axis=-1)  # θ and -θ
        return _K * w[None, :] / (2.0 * np.pi) * integral
    # x = 1 - 2 s², clustering at x = 1 where D -> 0 when v ≈ w
    x = (1.0 - 2.0 * t**2)[None, None, :]
    jacobian = 4.0 * t * weights
    d = np.sqrt(np.maximum(big_v**2 + big_w**2 - 2.0 * big_v * big_w * x, 1e-300))
    a = (big_v**2 - big_v * big_w * x) / d
    integral = np.sum(_phi1(a) / d * jacobian, axis=-1)
    return _K * w[None, :] ** 2 / 2.0 * integral


def _operator(dimension, n_nodes, v_max, grade, n_angles):
    speeds, weights = _nodes(n_nodes, v_max, grade)
    gain = np.empty((n_nodes, n_nodes))
    for start in range(0, n_nodes, 32):
        gain[start : start + 32] = _radial_kernel(
            dimension, speeds[start : start + 32], speeds, n_angles
        )
    gain *= weights[None, :]
    measure = speeds ** (dimension - 1) * weights
    loss = (measure[:, None] * gain).sum(axis=0) / measure
    return speeds, measure, gain, loss


def collision_rate(speeds, dimension=2, n_nodes=300, v_max=9.0):
    """r(v)/ω of the discretised operator, interpolated at ``speeds`` (for checks)."""
    nodes, _, _, loss = _operator(dimension, n_nodes, v_max, 2.0, n_nodes)
    return np.interp(speeds, nodes, loss)


def reference_solution(lams, dimension=2, *, n_nodes=300, v_max=9.0, grade=2.0):
    """μ(λ), T(λ), a2(λ) of hard spheres from the discretised Eq. (28).

    ``lams`` is a 1-D sequence of tilts; returns three arrays of the same length
    (time unit 1/ω, temperature unit T0). Cost: ~1 s for 300 nodes.
    """
    if dimension not in (2, 3):
        raise ValueError(f"dimension must be 2 or 3, got {dimension}")
    lams = np.atleast_1d(np.asarray(lams, dtype=float))
    if not np.all(np.isfinite(lams)):
        raise ValueError("lams must be finite")
    speeds, measure, gain, loss = _operator(dimension, n_nodes, v_max, grade, n_nodes)
    mu = np.empty(lams.size)
    temperature = np.empty(lams.size)
    a2 = np.empty(lams.size)
    for k, lam in enumerate(lams):
        matrix = np.exp(-lam) * gain - np.diag(loss)
        values, vectors = np.linalg.eig(matrix)
        top = np.argmax(values.real)
        mu[k] = values[top].real
        density = np.abs(vectors[:, top].real)
        m0 = (measure * density).sum()
        m2 = (measure * density * speeds**2).sum() / m0
        m4 = (measure * density * speeds**4).sum() / m0
        temperature[k] = m2 / dimension
        a2[k] = dimension / (dimension + 2.0) * m4 / m2**2 - 1.0
    return mu, temperature, a2


def exact_cumulants(dimension=2, *, n_nodes=300, v_max=9.0, step=0.02):
    """⟨N^p⟩_c/(ω t), p = 1, 2, 3, of the discretised Eq. (28): (-1)^p μ^(p)(0) by central
    differences of its eigenvalue (order h^4), divided by -μ'(0) so that k1 = 1 exactly
    (the discretised operator's mean rate is 1 + 7e-5 at 300 nodes). In d = 2: k2 =
    1.14090 and k3 = 1.09947 (300 nodes, v_max = 9), against 1.14100 and 1.09961 at 200
    nodes and 1.14092 and 1.09950 at v_max = 11: about 1e-4 and 2e-4 of discretisation
    error, against Eq. (50)'s first-Sonine 1.13778 and 1.10733."""
    from kinetic.theory.visco2008 import _derivatives_at_zero

    def mu(lams):
        return reference_solution(lams, dimension, n_nodes=n_nodes, v_max=v_max)[0]

    derivatives = _derivatives_at_zero(mu, step) * np.array([-1.0, 1.0, -1.0])
    return derivatives / derivatives[0]


def window_cumulants(windows, dimension=2, *, n_nodes=300, v_max=9.0, step=0.02):
    """⟨N^p⟩_c/⟨N⟩, p = 1, 2, 3, of the collisions N a particle of the equilibrium gas
    suffers in a window of length t (units 1/ω), for each t of ``windows``: the finite-time
    counterpart of :func:`exact_cumulants` (Table I's MD rows at t = 10 and 50), from the
    generating function ⟨e^{-λN}⟩ = 1ᵀ exp(t M(λ)) f_M of the discretised Eq. (28), with
    M(λ) = e^{-λ} G − diag(r) and the stationary start f_M, by central differences in λ.
    Returns an array (len(windows), 3) with k1 = 1. In d = 2: k2 = 1.12476 at t = 10,
    1.13767 at 50, 1.14074 at 1000 (→ 1.14090); k3 = 1.13003, 1.10561, 1.09977."""
    from scipy.linalg import expm

    from kinetic.theory.visco2008 import _derivatives_at_zero

    speeds, measure, gain, loss = _operator(dimension, n_nodes, v_max, 2.0, n_nodes)
    start = np.exp(-0.5 * speeds**2)  # the Maxwellian (T = 1), stationary at λ = 0
    norm = measure @ start
    h = step
    out = []
    for t in np.atleast_1d(np.asarray(windows, dtype=float)):
        if not (np.isfinite(t) and t > 0):
            raise ValueError(f"windows must be finite and > 0, got {t!r}")

        def log_z(lams, t=t):
            return np.array(
                [
                    np.log(
                        measure @ (expm(t * (np.exp(-lam) * gain - np.diag(loss))) @ start) / norm
                    )
                    for lam in lams
                ]
            )

        derivatives = _derivatives_at_zero(log_z, h) * np.array([-1.0, 1.0, -1.0])
        out.append(derivatives / derivatives[0])
    return np.array(out)


RESOLVED_LAMBDA_MAX = 2.5
"""Largest λ at which the d = 2 eigenvector (hence T and a2) is resolved by the grid."""
