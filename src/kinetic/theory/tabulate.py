"""Theory curves tabulated on grids, as datasets the figures read.

Figures never compute: every line they draw comes from one of these datasets, written
to ``results/<paper>/theory/*.nc`` by the workflow. Each function takes its grid as
keyword arguments (from the config) and returns an ``xarray.Dataset`` following the
conventions of ``kinetic.io``.
"""

from __future__ import annotations

import numpy as np

from kinetic.io import make_dataset
from kinetic.theory import visco2008
from kinetic.theory.visco2008_exact import (
    RESOLVED_LAMBDA_MAX,
    exact_cumulants,
    reference_solution,
    window_cumulants,
)

__all__ = [
    "coarse_nodes",
    "visco2008_cloning_reference",
    "visco2008_closures",
    "visco2008_finite_time",
    "visco2008_free_flights",
    "visco2008_free_paths",
    "visco2008_large_deviations",
]

_RATE_UNIT = "omega"  # time in mean free times, the unit of visco2008's figures


def visco2008_large_deviations(*, rate_max: float, points: int, d: int = 2):
    """π(n) of Fig. 3: Gaussian closure (Legendre of Eq. 43), uncorrelated flights (Eq. 23),
    Poisson(1) and Poisson(1/√2); n = N/t in units of ω."""
    rate = np.linspace(0.0, rate_max, points)
    ldf = "large deviation function pi(n)"
    return make_dataset(
        {
            "gaussian": (
                "rate",
                visco2008.gaussian_ldf(rate),
                _RATE_UNIT,
                f"{ldf}, Gaussian closure (Legendre transform of Eq. 43)",
            ),
            "uncorrelated": (
                "rate",
                visco2008.uncorrelated_ldf(rate, d),
                _RATE_UNIT,
                f"{ldf}, uncorrelated free flights (Eq. 23)",
            ),
            "poisson": (
                "rate",
                visco2008.poisson_ldf(rate, 1.0),
                _RATE_UNIT,
                f"{ldf}, Poisson of rate omega (Eq. 40)",
            ),
            "poisson_slow": (
                "rate",
                visco2008.poisson_ldf(rate, 1 / np.sqrt(2)),
                _RATE_UNIT,
                f"{ldf}, Poisson of rate omega/sqrt(2)",
            ),
        },
        coords={"rate": ("rate", rate, _RATE_UNIT, "collision rate n = N/t")},
        attrs={"dimension": d},
    )


def visco2008_free_flights(*, time_max: float, points: int, d: int = 2):
    """Free-flight-time densities of Figs. 1, 10 and 11, t in mean free times."""
    time = np.linspace(0.0, time_max, points)
    pdf = "free flight time density"
    return make_dataset(
        {
            "hard_spheres": (
                "time",
                visco2008.free_flight_time_pdf(time, d),
                _RATE_UNIT,
                f"{pdf}, hard spheres (Eq. 9)",
            ),
            "hard_spheres_asymptotic": (
                "time",
                visco2008.free_flight_time_pdf_asymptotic(time, d),
                _RATE_UNIT,
                f"{pdf}, large-time form (Eq. 11)",
            ),
            "weighted": (
                "time",
                visco2008.weighted_free_flight_time_pdf(time, d),
                _RATE_UNIT,
                f"{pdf} with the Gaussian weight (A1)",
            ),
            "weighted_asymptotic": (
                "time",
                visco2008.weighted_free_flight_time_pdf_asymptotic(time, d),
                _RATE_UNIT,
                f"{pdf} with the Gaussian weight, large-time form (A8)",
            ),
            "very_hard_particles": (
                "time",
                visco2008.vhp_free_flight_time_pdf(time, d),
                _RATE_UNIT,
                f"{pdf}, very hard particles (B4)",
            ),
            "hard_spheres_survival": (
                "time",
                visco2008.free_flight_time_survival(time, d),
                "1",
                "probability of a free flight longer than t, hard spheres (Eq. 9)",
            ),
            "weighted_survival": (
                "time",
                visco2008.weighted_free_flight_time_survival(time, d),
                "1",
                "probability of a free flight longer than t under (A1)",
            ),
            "maxwell": (
                "time",
                np.exp(-time),
                _RATE_UNIT,
                f"{pdf}, Maxwell molecules (exponential, Eq. D1)",
            ),
        },
        coords={"time": ("time", time, "1/omega", "time since the last collision")},
        attrs={"dimension": d},
    )


def visco2008_free_paths(*, path_max: float, points: int, d: int = 2):
    """Free-path densities of Figs. 2 and 12, x in mean free paths l = <v>/ω."""
    path = np.linspace(0.0, path_max, points)
    pdf = "free path density"
    # both densities are finite at x = 0: Eq. (14) gives 1.2193, (D3) gives π/2 (d = 2)
    hard = visco2008.free_path_pdf(path, d)
    maxwell = visco2008.maxwell_free_path_pdf(path, d)
    return make_dataset(
        {
            "hard_spheres": ("path", hard, "1/l", f"{pdf}, hard spheres (Eq. 14)"),
            "hard_spheres_tail": (
                "path",
                visco2008.free_path_pdf_tail(path, d),
                "1/l",
                "dominant exponential exp(-x/(sqrt(2) l)) (Eq. 16)",
            ),
            "hard_spheres_survival": (
                "path",
                visco2008.free_path_survival(path, d),
                "1",
                "probability of a free path longer than x, hard spheres (Eq. 14)",
            ),
            "maxwell": ("path", maxwell, "1/l", f"{pdf}, Maxwell molecules (D3)"),
            "maxwell_survival": (
                "path",
                visco2008.maxwell_free_path_survival(path, d),
                "1",
                "probability of a free path longer than x, Maxwell molecules (D3)",
            ),
            "maxwell_asymptotic": (
                "path",
                visco2008.maxwell_free_path_pdf_asymptotic(path, d),
                "1/l",
                f"{pdf}, Maxwell molecules, large-x form (D4)",
            ),
        },
        coords={"path": ("path", path, "l", "free path length")},
        attrs={"dimension": d},
    )


def visco2008_closures(
    *, lambda_min: float, lambda_max: float, points: int, windows=(), d: int = 2
):
    """μ(λ), T(λ), a2(λ) of the Gaussian (Eq. 43) and Sonine (47–49) closures, the
    Poisson generating functions, and the cumulants of Table I's theory rows (the
    closures' and those of Eq. (28) solved, ``visco2008_exact.exact_cumulants``, also at
    the MD rows' finite ``windows``, ``visco2008_exact.window_cumulants``)."""
    lam = np.linspace(lambda_min, lambda_max, points)
    if not np.any(lam == 0):
        lam = np.sort(np.append(lam, 0.0))
    mu_sonine, temperature_sonine, a2_sonine = visco2008.sonine_solution(lam, d)
    order = np.arange(1, 4)
    closures = make_dataset(
        {
            "mu_gaussian": (
                "lam",
                visco2008.gaussian_mu(lam),
                _RATE_UNIT,
                "mu(lambda), Gaussian closure (Eq. 43a)",
            ),
            "temperature_gaussian": (
                "lam",
                visco2008.gaussian_temperature(lam),
                "T0",
                "T(lambda), Gaussian closure (Eq. 43b)",
            ),
            "mu_sonine": (
                "lam",
                mu_sonine,
                _RATE_UNIT,
                "mu(lambda), first Sonine closure (Eqs. 47-49), NaN past the fold",
            ),
            "temperature_sonine": (
                "lam",
                temperature_sonine,
                "T0",
                "T(lambda), first Sonine closure",
            ),
            "a2_sonine": ("lam", a2_sonine, "1", "a2(lambda), first Sonine closure"),
            "mu_poisson": (
                "lam",
                visco2008.poisson_mu(lam, 1.0),
                _RATE_UNIT,
                "Poisson generating function omega (exp(-lambda) - 1)",
            ),
            "mu_poisson_slow": (
                "lam",
                visco2008.poisson_mu(lam, 1 / np.sqrt(2)),
                _RATE_UNIT,
                "Poisson generating function (omega/sqrt 2)(exp(-lambda) - 1)",
            ),
            "cumulant_poisson": ("order", np.ones(3), "1", "<N^p>_c/(omega t), Poisson"),
            "cumulant_gaussian": (
                "order",
                visco2008.gaussian_cumulants(),
                "1",
                "<N^p>_c/(omega t), Gaussian closure (Eq. 43)",
            ),
            "cumulant_sonine": (
                "order",
                visco2008.sonine_cumulants(d),
                "1",
                "<N^p>_c/(omega t), Sonine closure (Eq. 50)",
            ),
            "cumulant_exact": (
                "order",
                exact_cumulants(d),
                "1",
                "<N^p>_c/(omega t), Eq. (28) solved (eigenvalue derivatives at lambda = 0)",
            ),
            "cumulant_sonine_solved": (
                "order",
                visco2008.sonine_cumulants_numerical(d),
                "1",
                "<N^p>_c/(omega t), derivatives of the solved Sonine closure",
            ),
        },
        coords={
            "lam": ("lam", lam, "1", "counting field lambda"),
            "order": ("order", order, "1", "cumulant order p"),
        },
        attrs={"dimension": d},
    )
    if len(windows) == 0:
        return closures
    windows = np.asarray(windows, dtype=float)
    at_windows = make_dataset(
        {
            "cumulant_exact_window": (
                ("window", "order"),
                window_cumulants(windows, d),
                "1",
                "<N^p>_c/<N> in a window of length t, Eq. (28) solved",
            )
        },
        coords={
            "window": ("window", windows, "1/omega", "counting window t (Table I's MD rows)"),
            "order": ("order", order, "1", "cumulant order p"),
        },
    )
    return closures.merge(at_windows, combine_attrs="override")


def visco2008_finite_time(*, windows, rate_max: float, d: int = 2):
    """π_t(n) at the finite windows t of Fig. 9, the estimator the MD uses applied to models:
    the exact Poisson(1) count and the Gaussian closure at saddle-point order (leading 1/t
    correction). Counts k = 0 .. ceil(rate_max × max t); n = k/t; NaN where k/t > rate_max."""
    windows = np.asarray(windows, dtype=float)
    counts = np.arange(int(np.ceil(rate_max * windows.max())) + 1)
    poisson = np.full((windows.size, counts.size), np.nan)
    gaussian = np.full((windows.size, counts.size), np.nan)
    for w, t in enumerate(windows):
        shown = counts <= rate_max * t
        poisson[w, shown] = visco2008.poisson_count_ldf(t, counts[shown])
        gaussian[w, shown] = visco2008.gaussian_count_ldf(t, counts[shown])
    rate = counts[None, :] / windows[:, None]
    ldf = "finite-t estimate (1/t) ln[P(N = k)/max P] of pi(n)"
    return make_dataset(
        {
            "rate": (("window", "count"), rate, _RATE_UNIT, "collision rate n = k/t"),
            "poisson": (("window", "count"), poisson, _RATE_UNIT, f"{ldf}, Poisson(t) exact"),
            "gaussian": (
                ("window", "count"),
                gaussian,
                _RATE_UNIT,
                f"{ldf}, Gaussian closure (Eq. 43) at saddle-point order",
            ),
        },
        coords={
            "window": ("window", windows, "1/omega", "counting window t"),
            "count": ("count", counts, "1", "number of collisions k"),
        },
        attrs={"dimension": d},
    )


def coarse_nodes(n_nodes: int) -> int:
    """The second grid of :func:`visco2008_cloning_reference`'s extrapolation: two thirds
    of ``n_nodes`` (at least 40)."""
    return max(40, round(2 * n_nodes / 3))


def visco2008_cloning_reference(*, lambdas, n_nodes: int = 300, d: int = 2):
    """μ, T, a2 of the deterministic solution of Eq. (28)
    (``kinetic.theory.visco2008_exact.reference_solution``) on the grid ``lambdas``, drawn
    beside the cloning data and checked against it: solved on ``n_nodes`` and
    :func:`coarse_nodes` nodes and extrapolated in n_nodes^-2 (Richardson). At 300 nodes
    alone μ is 4.3e-4 off at λ = -1.5 (0.4 of the default build's cloning error bar there,
    about 3 of paper.yaml's); from 300 and 200 within 1.1e-6 of the 600/900-node
    extrapolation (5e-8 at λ = 1), T within 3.3e-7 (1.3e-4 at 300 alone) and a2 within
    8.6e-7 (2.8e-4 at λ = 2.5 at 300 alone) for -1.5 <= λ <= 2.5. T and a2 are NaN above
    ``RESOLVED_LAMBDA_MAX`` (the eigenfunction's logarithmic spread towards v = 0 is not
    resolved there), μ is kept (it lies 5.9e-4 above -1/√2 at λ = 2.5, 1.1e-5 at 3, 3e-7
    at 3.3 and 1.5e-8 at 3.5)."""
    lams = np.asarray(lambdas, dtype=float)
    coarse = coarse_nodes(n_nodes)
    fine = np.array(reference_solution(lams, d, n_nodes=n_nodes))
    rough = np.array(reference_solution(lams, d, n_nodes=coarse))
    # the discretisation error falls as n_nodes^-2: Richardson's combination of the two
    weight = n_nodes**2 / (n_nodes**2 - coarse**2)
    mu, temperature, a2 = rough + weight * (fine - rough)
    mu = np.maximum(mu, -1.0 / np.sqrt(2.0))  # μ >= -r(0); the extrapolation may overshoot
    unresolved = lams > RESOLVED_LAMBDA_MAX
    temperature = np.where(unresolved, np.nan, temperature)
    a2 = np.where(unresolved, np.nan, a2)
    what = "deterministic solution of visco2008 Eq. 28 (Nystrom quadrature)"
    return make_dataset(
        {
            "mu": ("lam", mu, "omega", f"mu(lambda), {what}"),
            "temperature": ("lam", temperature, "T0", f"T(lambda), {what}"),
            "a2": ("lam", a2, "1", f"a2(lambda), {what}"),
        },
        coords={"lam": ("lam", lams, "1", "counting field lambda")},
        attrs={
            "dimension": int(d),
            "n_nodes": int(n_nodes),
            "coarse_nodes": coarse,
            "extrapolation": "Richardson in n_nodes^-2 from n_nodes and coarse_nodes",
            "resolved_lambda_max": RESOLVED_LAMBDA_MAX,
        },
    )
