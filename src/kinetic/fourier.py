"""The Fourier factor e^{2πi u} of the transverse modes, without a call into libm.

Both engines of costantini2010 sample the modes Σ_j w_{j,y} e^{ikx_j} (k = 2π/L) of every
particle at every sample: one to four libm calls (``cos``, ``sin``) a particle cost about
30 ns, a third of the inhomogeneous DSMC's time at the paper's four steps a sample and a
quarter of the cooling MD's. :func:`cos_sin_turns` takes the argument in turns
(u = x/L), reduces it exactly to an eighth of a turn and evaluates two short polynomials
without a branch, so the observers' loops stay straight-line arithmetic. The GPU's
observer of the inhomogeneous DSMC calls the same :func:`mode_terms` (numba-cuda compiles
these helpers for the device), so both backends define the modes once.
"""

from __future__ import annotations

import math

from kinetic.jit import inline

__all__ = ["cos_sin_turns", "mode_sums", "mode_terms"]

_TWO_PI = 2.0 * math.pi
# Taylor coefficients θ^(2m+1)/(2m+1)! and θ^(2m)/(2m)! up to θ^15 and θ^16: on
# |θ| <= π/4 the first terms left out are below 5e-17 and 2e-18 (half an ulp of the
# results is at least 5.5e-17 for sin near π/4, 5.5e-17 for cos)
_S1, _S2, _S3, _S4, _S5, _S6, _S7 = ((-1) ** m / math.factorial(2 * m + 1) for m in range(1, 8))
_C1, _C2, _C3, _C4, _C5, _C6, _C7, _C8 = ((-1) ** m / math.factorial(2 * m) for m in range(1, 9))


_ROUNDING = 1.5 * 2.0**52
"""(x + _ROUNDING) − _ROUNDING is x rounded to the nearest integer (ties to even) for
|x| < 2⁵¹: two additions, the same on both targets (numba-cuda has no ``np.floor``, and
``math.floor``'s integer result costs the CPU loop a third more)."""


@inline
def cos_sin_turns(u):
    """(cos 2πu, sin 2πu) for |u| < 2⁵¹, within 2 ulp of 1 of the exact values (tested).

    u − round(u) and the split into a quarter turn q/4 and f ∈ [−1/8, 1/8] are exact
    (Sterbenz), so the only rounding before the polynomials is θ = 2πf; the quadrant
    then swaps and signs the pair by arithmetic, not branches (the quadrant of a random
    position is a coin flip for a branch predictor).
    """
    r = u - ((u + _ROUNDING) - _ROUNDING)
    q = (4.0 * r + _ROUNDING) - _ROUNDING
    theta = _TWO_PI * (r - 0.25 * q)
    z = theta * theta
    s = theta + theta * z * (
        _S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * (_S6 + z * _S7)))))
    )
    c = 1.0 + z * (
        _C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * (_C6 + z * (_C7 + z * _C8))))))
    )
    # products by 0 or 1 and sums with 0 are exact: the swap and the signs by arithmetic
    quadrant = int(q) & 3
    swap = float(quadrant & 1)
    keep = 1.0 - swap
    cosine_sign = 1.0 - 2.0 * float(((quadrant + 1) >> 1) & 1)
    sine_sign = 1.0 - 2.0 * float((quadrant >> 1) & 1)
    return cosine_sign * (c * keep + s * swap), sine_sign * (s * keep + c * swap)


@inline
def mode_terms(turns_x, turns_y, wx, wy):
    """w_y cos kx, w_y sin kx, w_x cos ky, w_x sin ky of a particle at (x, y) =
    L (turns_x, turns_y) with velocity (wx, wy). A loop that only stores them vectorizes
    (no reduction in it): 5.3 ns a particle here (AVX2 lanes), against 30 for the four
    libm calls summed on the fly. Store them where the loop's own index is
    (``terms[0, i]``): passed into a helper, the index loses numba's proof that it is not
    negative, and the wraparound check that comes back stops the vectorizer."""
    cos_x, sin_x = cos_sin_turns(turns_x)
    cos_y, sin_y = cos_sin_turns(turns_y)
    return wy * cos_x, wy * sin_x, wx * cos_y, wx * sin_y


@inline
def mode_sums(terms, n):
    """The transverse modes (Re, Im Σ w_y e^{ikx}, Re, Im Σ w_x e^{iky}) from the first n
    columns of ``terms``, each summed in particle order (as the loop that filled them)."""
    re_y = 0.0
    im_y = 0.0
    re_x = 0.0
    im_x = 0.0
    for i in range(n):
        re_y += terms[0, i]
        im_y += terms[1, i]
        re_x += terms[2, i]
        im_x += terms[3, i]
    return re_y, im_y, re_x, im_x
