"""Figures of visco2008 Figs 4-8 and the cloning studies: read the aggregated scan
(results/visco2008/cloning.nc, or one kernel's, cloning/scan/<kernel>.nc, for Figs 4-8),
never simulate, and draw it in the cloning style. Figs 4-8
are whole functions here (``fig04`` ... ``fig08``: the data in, the PDF written, the
caption's numbers returned), so that a figure is read in one place; their scripts only
read the files and write the caption.

The plotted Monte Carlo value at each λ is the 1/N_c -> 0 extrapolation when the scan has
two or more population sizes there (and, for T and a2, no diversity collapse); otherwise
the largest population's value, drawn with another marker. Kept out of the cloning
package: a change here reruns no simulation and leaves numba's cache of the kernels valid.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kinetic import io, plotting

__all__ = [
    "Series",
    "closure_lines",
    "collapsed_points",
    "data_limits",
    "draw_series",
    "fig04",
    "fig05",
    "fig06",
    "fig07",
    "fig08",
    "finite",
    "scan_series",
]

MU_BOUND = -1.0 / np.sqrt(2.0)
"""The exact lower bound of hard disks' μ(λ), -ω/√2 (ω = 1): Figs 5 and 6 and their captions."""

_POINT_NAMES = {"mu": "mu", "T": "temperature", "a2": "a2", "mu_rate": "mu_rate"}


@dataclass
class Series:
    """Monte Carlo values of one observable against λ: extrapolated (``limit_*``) and
    largest-N_c fallbacks (``single_*``), each sorted by λ."""

    limit_lambda: np.ndarray
    limit_value: np.ndarray
    limit_error: np.ndarray
    single_lambda: np.ndarray
    single_value: np.ndarray
    single_error: np.ndarray
    single_population: int


def scan_series(path, kernel: str, observable: str) -> Series:
    """Read a scan file (cloning.nc or one kernel's) and return the series of ``observable``
    ('mu', 'mu_rate', 'T' or 'a2') of ``kernel`` ('hard_disks' or 'maxwell')."""
    ds = io.read_dataset(path)
    name = _POINT_NAMES[observable]
    point_kernel = ds["point_kernel"].values.astype(str)
    limit_kernel = ds["limit_kernel"].values.astype(str)
    limits = {}
    for k in np.flatnonzero(limit_kernel == kernel):
        value = float(ds[f"limit_{name}"].values[k])
        error = float(ds[f"limit_{name}_err"].values[k])
        if np.isfinite(value) and np.isfinite(error):
            limits[float(ds["limit_lambda"].values[k])] = (value, error)
    mine = np.flatnonzero(point_kernel == kernel)
    largest = int(ds["point_population"].values[mine].max())
    singles = {}
    for k in mine:
        lam = float(ds["point_lambda"].values[k])
        if lam in limits or int(ds["point_population"].values[k]) != largest:
            continue
        if name in ("temperature", "a2") and int(ds["point_collapse"].values[k]):
            continue
        singles[lam] = (
            float(ds[f"point_{name}"].values[k]),
            float(ds[f"point_{name}_err"].values[k]),
        )

    def arrays(table):
        lams = np.array(sorted(table))
        values = np.array([table[x][0] for x in lams]) if table else np.array([])
        errors = np.array([table[x][1] for x in lams]) if table else np.array([])
        return lams, values, errors

    return Series(*arrays(limits), *arrays(singles), largest)


def finite(x, y):
    """The points of a theory curve where it is defined (the Sonine closure ends at its
    fold near λ ≈ 1.61 and is NaN beyond)."""
    x, y = np.asarray(x), np.asarray(y)
    keep = np.isfinite(y)
    return x[keep], y[keep]


def collapsed_points(path, kernel: str, observable: str):
    """(λ, value, error) of the largest population's points whose runs collapsed onto a
    few clones: not estimates of the eigenfunction, shown only as such."""
    ds = io.read_dataset(path)
    name = _POINT_NAMES[observable]
    kernels = ds["point_kernel"].values.astype(str)
    population = ds["point_population"].values
    largest = population[kernels == kernel].max()
    chosen = np.flatnonzero(
        (kernels == kernel) & (population == largest) & (ds["point_collapse"].values == 1)
    )
    order = chosen[np.argsort(ds["point_lambda"].values[chosen])]
    return (
        ds["point_lambda"].values[order],
        ds[f"point_{name}"].values[order],
        ds[f"point_{name}_err"].values[order],
    )


def draw_series(ax, series: Series, *, scale=None, label="cloning", lam_max=np.inf, **kwargs):
    """Error bars of a Series up to ``lam_max`` in the cloning style (METHOD_STYLE):
    filled where extrapolated to 1/N_c -> 0, open where only the largest population was
    usable (finite-population values, which carry the 1/N_c bias). ``scale(lam, value,
    error) -> (value, error)`` transforms the values first. Returns the values drawn as a
    dict {"limit": (λ, value, error), "single": (...)} for axis limits and captions."""
    color = plotting.METHOD_STYLE["cloning"]["color"]
    parts = [
        (
            "limit",
            series.limit_lambda,
            series.limit_value,
            series.limit_error,
            {"mfc": color},
            rf"{label}, $N_c\to\infty$",
        ),
        (
            "single",
            series.single_lambda,
            series.single_value,
            series.single_error,
            {},
            rf"{label}, $N_c={series.single_population}$ only",
        ),
    ]
    drawn = {}
    for key, lam, value, error, fill, text in parts:
        shown = lam <= lam_max
        lam, value, error = lam[shown], value[shown], error[shown]
        if scale is not None and lam.size:
            value, error = scale(lam, value, error)
        drawn[key] = (lam, value, error)
        if lam.size == 0:
            continue
        plotting.method_errorbar(
            ax,
            "cloning",
            lam,
            value,
            error,
            label=text if label else None,
            zorder=5,
            **fill,
            **kwargs,
        )
    return drawn


def data_limits(drawn, *, pad: float = 0.06, include=()):
    """(low, high) covering every drawn point with its error bar (and the values in
    ``include``), padded: no point is clipped by the axis."""
    values = [np.asarray(include, dtype=float).ravel()]
    for _, value, error in drawn.values():
        ok = np.isfinite(value)
        values += [value[ok] - error[ok], value[ok] + error[ok]]
    values = np.concatenate(values)
    low, high = float(values.min()), float(values.max())
    margin = pad * (high - low)
    return low - margin, high + margin


# ---------------------------------------------------------------- the figures


def fig04(scan, closures, pdf):
    """visco2008 Fig. 4: μ(λ) of Maxwell molecules, cloning Monte Carlo against the Poisson
    generating function e^{-λ} - 1; inset μ + 1 on a log scale.

    Drawn from ``scan``, ``closures`` and saved at ``pdf``."""
    series = scan_series(scan, "maxwell", "mu")
    lam = closures["lam"].values

    fig, ax = plotting.figure()
    ax.plot(lam, closures["mu_poisson"], "-", label=r"Poisson: $e^{-\lambda}-1$")
    draw_series(ax, series)
    ax.set_xlabel(r"$\lambda$")
    ax.set_ylabel(r"$\mu(\lambda)$")
    ax.set_xlim(lam.min(), lam.max())
    plotting.legend_outside(ax)

    inner = plotting.inset(ax, (0.42, 0.18, 0.5, 0.42))
    inner.semilogy(lam, closures["mu_poisson"] + 1.0, "-")
    draw_series(inner, series, label="", scale=lambda _, v, e: (v + 1.0, e))
    inner.set_xlabel(r"$\lambda$", fontsize=7)
    inner.set_ylabel(r"$\mu+1$", fontsize=7)
    inner.set_xlim(lam.min(), lam.max())
    inner.set_ylim(0.5 * np.exp(-lam.max()), 2.0 * np.exp(-lam.min()))
    plotting.save(fig, pdf)


def fig05(scan, closures, reference, pdf):
    """visco2008 Fig. 5: μ(λ) of hard disks, cloning Monte Carlo against the Gaussian (Eq. 43)
    and first-Sonine (Eqs. 47-49, ends at its fold) closures, the Poisson(ω/√2) generating
    function (Eq. 38) and the deterministic solution of Eq. (28); inset: zoom near λ = 0.
    Open triangles are finite-population values (one N_c usable): their 1/N_c bias can put
    them below the exact bound μ >= -ω/√2; the caption counts them from the scan file.

    Drawn from ``scan``, ``closures``, ``reference`` and saved at ``pdf``. Returns the
    numbers its caption quotes."""
    series = scan_series(scan, "hard_disks", "mu")
    lam = closures["lam"].values
    bound = MU_BOUND

    def curves(axis):
        closure_lines(axis, lam, closures["mu_gaussian"].values, closures["mu_sonine"].values)
        axis.plot(
            lam,
            closures["mu_poisson_slow"],
            **plotting.METHOD_STYLE["theory_alt"],
            label=r"Poisson($\omega/\sqrt{2}$)",
        )
        axis.plot(
            reference["lam"],
            reference["mu"],
            "-",
            color="0.3",
            lw=0.7,
            label="Eq. (28), quadrature",
        )

    fig, ax = plotting.figure(figsize=(3.4, 3.6))
    curves(ax)
    drawn = draw_series(ax, series)
    ax.axhline(bound, color="0.7", lw=0.5, ls=":", zorder=0)
    ax.set_xlabel(r"$\lambda$")
    ax.set_ylabel(r"$\mu(\lambda)$")
    ax.set_xlim(lam.min() - 0.2, lam.max() + 0.2)
    ax.set_ylim(*data_limits(drawn, include=closures["mu_gaussian"].values))
    fig.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2)

    inner = plotting.inset(ax, (0.47, 0.52, 0.5, 0.45))
    curves(inner)
    draw_series(inner, series, label="")
    zoom = (0.4, 1.6)  # where the closures separate
    inner.set_xlim(*zoom)
    inner.set_ylim(*_zoom_limits(zoom, closures, reference))
    plotting.save(fig, pdf)

    single_lam, single_mu, single_error = drawn["single"]
    below = single_mu < bound
    return dict(
        population=series.single_population,
        n_single=int(single_lam.size),
        n_below=int(below.sum()),
        n_below_2se=int(np.sum(single_mu + 2.0 * single_error < bound)),
        lambdas_below=", ".join(f"{x:g}" for x in single_lam[below]) or "none",
        n_limit=int(drawn["limit"][0].size),
    )


def _zoom_limits(zoom, closures, reference, pad=0.05):
    """y-limits of Fig. 5's inset: the range of the closures and of Eq. (28) over the
    λ-window ``zoom``, padded by ``pad`` of it (the range was a fixed (-0.72, -0.33))."""
    values = []
    for lam, mu in (
        (closures["lam"].values, closures["mu_gaussian"].values),
        (closures["lam"].values, closures["mu_sonine"].values),
        (reference["lam"].values, reference["mu"].values),
    ):
        lam, mu = finite(lam, mu)
        values.append(mu[(lam >= zoom[0]) & (lam <= zoom[1])])
    values = np.concatenate(values)
    low, high = values.min(), values.max()
    return low - pad * (high - low), high + pad * (high - low)


def fig06(scan, closures, reference, pdf):
    """visco2008 Fig. 6: hard-disk μ(λ) divided by the Poisson(ω/√2) generating function
    (e^{-λ} - 1)/√2, which Eq. (38) predicts to dominate at large λ. The exact bound
    μ >= -1/√2 gives the ratio 1/(1 - e^{-λ}) when μ sits at that edge.

    Drawn from ``scan``, ``closures``, ``reference`` and saved at ``pdf``. Returns the
    numbers its caption quotes."""
    lambda_min = 0.5  # the ratio is shown where e^{-λ} is small, as in the document
    series = scan_series(scan, "hard_disks", "mu")

    def poisson(lam):
        return np.expm1(-np.asarray(lam)) / np.sqrt(2.0)

    def ratio_curve(axis, lam, mu, style, **kwargs):
        lam, mu = finite(lam, mu)
        keep = lam >= lambda_min
        axis.plot(lam[keep], mu[keep] / poisson(lam[keep]), style, **kwargs)

    lam = closures["lam"].values
    fig, ax = plotting.figure()
    ratio_curve(
        ax, lam, closures["mu_gaussian"].values, "-", color="tab:green", label="Gaussian (Eq. 43)"
    )
    ratio_curve(
        ax, lam, closures["mu_sonine"].values, "--", color="tab:green", label="Sonine (Eqs. 47-49)"
    )
    ax.axhline(
        1.0, **plotting.METHOD_STYLE["theory_alt"], label=r"Poisson($\omega/\sqrt{2}$), Eq. (38)"
    )
    ratio_curve(
        ax,
        reference["lam"].values,
        reference["mu"].values,
        "-",
        color="0.3",
        lw=0.7,
        label="Eq. (28), quadrature",
    )
    grid = lam[lam >= lambda_min]
    ax.plot(
        grid, 1.0 / -np.expm1(-grid), "-.", color="0.5", lw=0.8, label=r"$\mu=-\omega/\sqrt{2}$"
    )

    def scaled(lam, value, error):
        # divided only where drawn: the generating function is 0 at λ = 0
        keep, scale = lam >= lambda_min, poisson(lam)

        def divided(numerator):
            out = np.full(np.shape(numerator), np.nan)
            return np.divide(numerator, scale, out=out, where=keep)

        return divided(value), np.abs(divided(error))

    drawn = draw_series(ax, series, scale=scaled)
    ax.set_xlim(lambda_min - 0.1, lam.max() + 0.2)
    low, high = data_limits(drawn, include=[0.95, 1.4])  # every point inside the axes
    ax.set_ylim(low, high)
    ax.set_xlabel(r"$\lambda$")
    ax.set_ylabel(r"$\mu(\lambda)\,/\,[(e^{-\lambda}-1)\,\omega/\sqrt{2}]$")
    fig.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2)
    plotting.save(fig, pdf)
    single_lam, single_ratio, single_error = drawn["single"]
    edge = 1.0 / -np.expm1(-single_lam)
    return dict(
        population=series.single_population,
        n_single=int(single_lam.size),
        n_limit=int(drawn["limit"][0].size),
        lambdas_single=", ".join(f"{x:g}" for x in single_lam) or "none",
        n_above_bound=int(np.sum(single_ratio > edge)),
        n_above_bound_2se=int(np.sum(single_ratio - 2.0 * single_error > edge)),
        bound_at_top=_bound_at_top(series, reference, lambda_min),
    )


def _bound_at_top(series, reference, lambda_min):
    """The caption's sentence on how close the extrapolated μ at the largest drawn λ comes
    to the bound −1/√2, with the solution of Eq. (28) there (where its quadrature gave a
    value)."""
    lam, mu, error = series.limit_lambda, series.limit_value, series.limit_error
    usable = np.isfinite(mu) & np.isfinite(error) & (lam >= lambda_min)
    if not usable.any():
        return "No extrapolated point lies in the figure's range of λ."
    k = np.flatnonzero(usable)[np.argmax(lam[usable])]
    gap = mu[k] - MU_BOUND
    text = (
        f"At the largest λ of the extrapolated points, {lam[k]:g}, μ lies {gap:.2g} ± "
        f"{error[k]:.2g} above the bound ({gap / error[k]:+.1f} errors)"
    )
    ref_lam, ref_mu = finite(reference["lam"].values, reference["mu"].values)
    at = np.flatnonzero(np.isclose(ref_lam, lam[k]))
    if at.size:
        text += f", the solution of Eq. (28) {ref_mu[at[0]] - MU_BOUND:.2g} above it"
    return text + "."


def closure_lines(ax, lam, gaussian, sonine):
    """The Gaussian (Eq. 43) and first-Sonine (Eqs. 47-49, up to its fold: ``finite``)
    closures of one quantity against λ, in the same style in every cloning figure."""
    ax.plot(lam, gaussian, **plotting.METHOD_STYLE["theory"], label="Gaussian (Eq. 43)")
    ax.plot(*finite(lam, sonine), color="tab:green", linestyle="--", label="Sonine (Eqs. 47-49)")


def fig07(scan, closures, reference, pdf):
    """visco2008 Fig. 7: T(λ), the variance per component of the hard-disk eigenfunction,
    cloning Monte Carlo against the Gaussian (Eq. 43b) and Sonine closures and the
    deterministic solution of Eq. (28). Crosses: T of populations that collapsed onto a few
    clones at large λ (not estimates of the eigenfunction; they only show T -> 0).

    Drawn from ``scan``, ``closures``, ``reference`` and saved at ``pdf``."""
    series = scan_series(scan, "hard_disks", "T")
    lam = closures["lam"].values

    fig, ax = plotting.figure()
    # the closures as in Figs 5, 6 and 8 (the default cycle made Sonine red, the cloning
    # points' colour)
    closure_lines(
        ax, lam, closures["temperature_gaussian"].values, closures["temperature_sonine"].values
    )
    ax.plot(
        *finite(reference["lam"].values, reference["temperature"].values),
        "-",
        color="0.6",
        lw=0.7,
        label="Eq. (28), quadrature",
    )
    draw_series(ax, series)
    lam_c, value_c, error_c = collapsed_points(scan, "hard_disks", "T")
    if lam_c.size:
        plotting.errorbar(
            ax,
            lam_c,
            value_c,
            error_c,
            marker="x",
            color="0.5",
            ms=3,
            label=rf"collapsed population, $N_c={series.single_population}$",
        )
    ax.set_xlim(lam.min(), lam.max())
    ax.set_ylim(0.0, None)
    ax.set_xlabel(r"$\lambda$")
    ax.set_ylabel(r"$T(\lambda)/T_0$")
    plotting.legend_outside(ax)
    plotting.save(fig, pdf)


def fig08(scan, closures, reference, pdf):
    """visco2008 Fig. 8: a2(λ), the kurtosis coefficient of the hard-disk eigenfunction,
    cloning Monte Carlo against the first-Sonine closure (valid for small a2, ends at its
    fold) and the deterministic solution of Eq. (28).

    Drawn from ``scan``, ``closures``, ``reference`` and saved at ``pdf``. Returns the
    numbers its caption quotes."""
    series = scan_series(scan, "hard_disks", "a2")
    lam = closures["lam"].values

    fig, ax = plotting.figure()
    ax.plot(
        *finite(lam, closures["a2_sonine"].values),
        "--",
        color="tab:green",
        label="Sonine (Eqs. 47-49)",
    )
    ax.plot(
        *finite(reference["lam"].values, reference["a2"].values),
        "-",
        color="0.3",
        lw=0.7,
        label="Eq. (28), quadrature",
    )
    ax.axhline(0.0, color="0.8", lw=0.5)
    # every usable point is drawn (runs whose population collapsed onto a few clones are
    # not estimates of a2 and are left out by scan_series); the axes follow the points
    drawn = draw_series(ax, series)
    shown_lam = np.concatenate([drawn["limit"][0], drawn["single"][0]])
    ax.set_xlim(lam.min() - 0.1, float(shown_lam.max()) + 0.2)
    ax.set_ylim(*data_limits(drawn, include=[-0.1, 1.2]))
    ax.set_xlabel(r"$\lambda$")
    ax.set_ylabel(r"$a_2(\lambda)$")
    ax.legend(loc="upper left")
    plotting.save(fig, pdf)
    return dict(
        population=series.single_population,
        n_single=int(drawn["single"][0].size),
        n_limit=int(drawn["limit"][0].size),
        lambdas_single=", ".join(f"{x:g}" for x in drawn["single"][0]) or "none",
    )
