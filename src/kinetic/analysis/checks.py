"""Checks of a document's claims: one type and one table for every document.

A check compares one measured ``value`` (with its standard ``error``; 0 for an exact
quantity) with what a document, a theory or a conservation law says (``expected``), by one
``rule`` written out in the table:

- :func:`agrees`: the same within ``sigmas`` standard errors, ``|z| <= sigmas``;
- :func:`exceeds`: larger, by more than ``sigmas`` errors, ``z > sigmas`` (a difference
  claimed: "ν̄*/ν* > 1");
- :func:`within`: ``|value - expected| <= tolerance`` (a bound that is not a number of
  errors: a percent-level claim, a conservation law to round-off, χ² below its quantile);
- :func:`reported`: measured beside the expectation, with no verdict (``passed`` empty).

:func:`tolerance_factor` widens a number of standard errors to Student's t when the
error comes from few realizations, and :func:`largest_z_tolerance` bounds the largest of
many such z-scores (histogram bins) at a family-wise false-alarm rate (for checks and
tests alike), :func:`sum_of_squares_tolerance` and :func:`sum_of_squares_p_value` do the
same for a χ² over such z-scores; :func:`band_exceedance` measures how often a band fails
by chance when the realizations' scatter is not Gaussian.

``z = (value - expected) / error`` wherever ``error > 0``. Every document writes its checks
with :func:`write` to ``<results>/<document>/checks.csv`` (and ``.md``) with the columns
:data:`COLUMNS`; a failed check stops the build only for the documents the config's
``fail_on_checks`` lists (:func:`write` raises after writing the table).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterable
from dataclasses import asdict, dataclass

__all__ = [
    "COLUMNS",
    "SIGMAS",
    "Check",
    "ChecksFailed",
    "agrees",
    "band_exceedance",
    "exceeds",
    "failures",
    "largest_z_tolerance",
    "overview",
    "overview_rst",
    "reported",
    "sum_of_squares_p_value",
    "sum_of_squares_tolerance",
    "table",
    "tolerance_factor",
    "welch_dof",
    "within",
    "write",
]

SIGMAS = 3.0
"""Standard errors within which a check of equality passes (beyond which one of
difference passes), where a document's config sets no other number."""

COLUMNS = ("claim", "value", "error", "expected", "z", "rule", "passed")
"""Columns of every checks.csv (read by kinetic.docs and the report: keep the names)."""


class ChecksFailed(RuntimeError):
    """Checks of a document whose config asks failed checks to stop the build."""


@dataclass(frozen=True)
class Check:
    """One claim tested on the data (see the module docstring)."""

    claim: str
    value: float
    error: float
    expected: float
    z: float
    rule: str
    passed: bool | None


def tolerance_factor(sigmas: float, dof: int) -> float:
    """Multiple of a standard error with the two-sided probability of ``sigmas`` Gaussian
    standard deviations, for an error estimated from ``dof`` degrees of freedom.

    A standard error from R realizations is itself uncertain (Student's t with R - 1
    degrees of freedom): with R = 4, a "4 sigma" check needs about 20 estimated errors,
    with R = 32 about 4.9, and it tends to ``sigmas`` as R grows.
    """
    from scipy import stats

    if dof < 1:
        raise ValueError(f"need >= 1 degree of freedom (>= 2 realizations), got {dof}")
    tail = stats.norm.sf(sigmas)
    return float(stats.t.isf(tail, dof))


def welch_dof(errors, dofs) -> float:
    """Degrees of freedom of the error √(Σ s²) combined from independent ``errors``, each
    estimated with its ``dofs`` (Welch–Satterthwaite: (Σ s²)² / Σ s⁴/ν, never below the
    smallest ν of a nonzero part); an exact part (s = 0) adds nothing."""
    parts = [(float(s) ** 2, float(nu)) for s, nu in zip(errors, dofs, strict=True) if s > 0]
    if not parts:
        raise ValueError("no error to combine")
    total = sum(square for square, _ in parts)
    return total**2 / sum(square**2 / nu for square, nu in parts)


def largest_z_tolerance(n_values: int, dof: int, false_alarm: float = 1e-3) -> float:
    """Bound on the largest |z| of ``n_values`` independent z-scores, each Student's t
    with ``dof`` degrees of freedom, exceeded with probability ``false_alarm`` in all
    (Bonferroni): 5.6 for 20 bins and 6.4 for 78 bins of 16 realizations, where a fixed
    4.5 gives false alarms in 0.8 % and 3 % of runs."""
    from scipy import stats

    if dof < 1:
        raise ValueError(f"need >= 1 degree of freedom (>= 2 realizations), got {dof}")
    return float(stats.t.isf(false_alarm / (2 * n_values), dof))


_SUM_POINTS = 2**20
"""Grid points of :func:`_sum_of_squares_cdf`. Read at its midpoint, a sum of rounded
values is off by at most half of ``n_values`` grid steps: 1.5 × 10⁻⁴ of the quantile for
78 values on a grid four times the quantile, and much less on average."""

_SUM_DAMPING = 36.0
"""e^{-36} (2 × 10⁻¹⁶): what is left of the probability that wraps around the grid's end in
:func:`_sum_of_squares_cdf`."""


@functools.cache
def _sum_of_squares_cdf(n_values: int, dof: int, top: float):
    """``(step, cdf)``: ``cdf[k]`` = P(S ≤ k step) for S the sum of ``n_values`` squared
    Student's t with ``dof`` degrees of freedom, each rounded down to the grid of
    :data:`_SUM_POINTS` steps up to ``top`` (so the true sum lies in [S, S + n_values
    step)), exact on the grid but for round-off, for k step up to ``top``/3, where ``cdf``
    ends.

    One t² is F(1, dof): its mass on each step is a difference of the regularised
    incomplete beta function (:func:`_student_square_sf`). The n-fold
    convolution is a power of its discrete Fourier transform, taken of the masses damped
    by e^{-θx} with θ top = :data:`_SUM_DAMPING`, so that the sums beyond ``top``, which
    the transform wraps round to the grid's start, come back weighted by e^{-θ top}, and
    undamped after; a t² beyond ``top`` is dropped, which changes no sum below ``top``.
    The undamping multiplies the transform's round-off, 10⁻¹⁶ of the largest mass, by at
    most e^{θ top/3} = 1.6 × 10⁵ below a third of the grid."""
    import numpy as np

    if dof < 1 or n_values < 1:
        raise ValueError(f"need >= 1 value and >= 1 degree of freedom, got {n_values}, {dof}")
    step = top / _SUM_POINTS
    beyond = _student_square_sf(np.arange(_SUM_POINTS + 1) * step, dof)
    damping = np.exp(-(_SUM_DAMPING / _SUM_POINTS) * np.arange(_SUM_POINTS))
    spectrum = np.fft.rfft((beyond[:-1] - beyond[1:]) * damping)
    power = np.ones_like(spectrum)
    exponent = n_values
    while exponent:  # by squaring: numpy's complex ** is slower and no more exact
        if exponent & 1:
            power *= spectrum
        exponent >>= 1
        if exponent:
            spectrum = spectrum * spectrum
    kept = _SUM_POINTS // 3 + 1
    cdf = np.cumsum(np.fft.irfft(power, _SUM_POINTS)[:kept] / damping[:kept])
    return step, np.maximum.accumulate(cdf)  # round-off can break the order of equal values


def _sum_of_squares_sf(total: float, n_values: int, dof: int, top: float) -> float:
    """P(S > ``total``) from :func:`_sum_of_squares_cdf` on the grid up to ``top`` (``total``
    at most a third of it): each rounded t² is short of the true one by half a step on
    average, so the sum at ``total`` is the rounded sum at ``total`` less half the
    ``n_values`` steps, between whose grid points the distribution is read linearly."""
    import numpy as np

    step, cdf = _sum_of_squares_cdf(n_values, dof, top)
    where = (total - 0.5 * n_values * step) / step
    if where < 0:
        return 1.0
    return float(1.0 - np.interp(where, np.arange(cdf.size), cdf))


def _student_square_sf(value, dof: int):
    """P(t² > ``value``) for Student's t with ``dof`` degrees of freedom (a number or an
    array of them): t² is F(1, dof), whose tail is the regularised incomplete beta
    function I_{dof/(dof + x)}(dof/2, 1/2)."""
    from scipy import special

    return special.betainc(0.5 * dof, 0.5, dof / (dof + value))


def sum_of_squares_tolerance(n_values: int, dof: int, false_alarm: float = 1e-3) -> float:
    """Bound on Σ z² over ``n_values`` independent z-scores, each Student's t with ``dof``
    degrees of freedom (errors from dof + 1 realizations), exceeded with probability
    ``false_alarm``. χ²'s quantile holds for exact errors only: with 12 realizations, Σ z²
    over 40 bins exceeds χ²_40's 10⁻³ quantile (73.4) with probability 4.4 %; this bound is
    107.8. The distribution of the sum is computed (:func:`_sum_of_squares_cdf`), to about
    10⁻⁴ of the bound, in half a second per (``n_values``, ``dof``) and process; χ²'s
    quantile beyond 10⁴ degrees of freedom."""
    import numpy as np
    from scipy import stats

    if dof > 10_000:
        return float(stats.chi2.isf(false_alarm, n_values))
    if not 0.0 < false_alarm < 1.0:
        raise ValueError(f"false_alarm must lie in (0, 1), got {false_alarm}")
    # a first guess: χ²'s quantile scaled by E[t²], or the largest value's alone
    mean = dof / (dof - 2.0) if dof > 2 else 3.0
    guess = max(
        stats.chi2.isf(false_alarm, n_values) * mean,
        stats.f.isf(false_alarm / n_values, 1, dof),
    )
    top = 4.0 * guess
    while True:
        step, cdf = _sum_of_squares_cdf(n_values, dof, top)
        if cdf[-1] > 1.0 - false_alarm:
            rounded = np.interp(1.0 - false_alarm, cdf, np.arange(cdf.size)) * step
            return float(rounded + 0.5 * n_values * step)
        top *= 2.0


def sum_of_squares_p_value(total: float, n_values: int, dof: int) -> float:
    """Probability that Σ z² of ``n_values`` Student's t with ``dof`` degrees of freedom
    exceeds ``total`` (the χ² test's p-value when the errors come from dof + 1
    realizations; :func:`sum_of_squares_tolerance`), computed; never below the
    probability that the largest t² alone exceeds it (where the computed tail is lost in
    round-off, about 10⁻¹⁰), so never 0; χ²'s beyond 10⁴ degrees of freedom."""
    from scipy import stats

    if dof > 10_000:
        return float(stats.chi2.sf(total, n_values))
    if total <= 0.0:
        return 1.0
    largest = -math.expm1(n_values * math.log1p(-float(_student_square_sf(total, dof))))
    top = 3.0 * 2.0 ** math.ceil(math.log2(total))  # neighbouring totals share a grid
    return max(_sum_of_squares_sf(total, n_values, dof, top), largest)


def band_exceedance(
    samples: Iterable, n: int, sigmas: float, *, draws: int = 400_000, seed: int = 0
) -> float:
    """How often a check of ``sigmas`` errors fails by chance when realizations scatter as
    ``samples`` do rather than as a Gaussian: the fraction of ``draws`` means of ``n``
    values, drawn with replacement from the pooled ``samples``, that lie beyond
    :func:`tolerance_factor` (``sigmas``, n - 1) of their own standard errors from the
    pool's mean. ``samples``: arrays (one a run: its realizations' values), each
    standardised on its own mean and scatter before they are pooled, so that runs of
    other means and errors share one shape. A Gaussian scatter gives the nominal 2 Φ(−
    ``sigmas``); heavier tails or a skew give more (b'_3 of montanero2007: about three
    times it at 4 errors, docs/reproduced.md)."""
    import numpy as np

    if n < 2:
        raise ValueError(f"need >= 2 realizations a mean, got {n}")
    pool = np.concatenate(
        [(values - np.mean(values)) / np.std(values, ddof=1) for values in map(np.asarray, samples)]
    )
    pool -= pool.mean()
    bound = tolerance_factor(sigmas, n - 1)
    rng = np.random.default_rng(seed)
    beyond = 0
    for start in range(0, draws, 50_000):
        drawn = rng.choice(pool, size=(min(50_000, draws - start), n))
        t = drawn.mean(axis=1) / (drawn.std(axis=1, ddof=1) / math.sqrt(n))
        beyond += int(np.count_nonzero(np.abs(t) > bound))
    return beyond / draws


def _usable(error: float) -> bool:
    """An error a verdict can rest on: finite and >= 0 (0: an exact value). A NaN error (a
    jackknife over an infinite τ_c, say) passed ``exceeds`` whenever the value lay above
    its bound, and an infinite one passed ``agrees`` with z = 0: both now fail."""
    return math.isfinite(error) and error >= 0.0


def _z(value: float, error: float, expected: float) -> float:
    difference = value - expected
    if error > 0:
        return difference / error
    return math.nan


def agrees(claim: str, value: float, error: float, expected: float, sigmas: float) -> Check:
    """``value`` equals ``expected`` within ``sigmas`` standard errors."""
    value, error, expected = float(value), float(error), float(expected)
    z = _z(value, error, expected)
    passed = _usable(error) and (abs(z) <= sigmas if error > 0 else value == expected)
    return Check(claim, value, error, expected, z, f"|z| <= {sigmas:.3g}", bool(passed))


def exceeds(claim: str, value: float, error: float, bound: float, sigmas: float) -> Check:
    """``value`` is above ``bound`` by more than ``sigmas`` standard errors."""
    value, error, bound = float(value), float(error), float(bound)
    z = _z(value, error, bound)
    passed = _usable(error) and (z > sigmas if error > 0 else value > bound)
    return Check(claim, value, error, bound, z, f"z > {sigmas:.3g}", bool(passed))


def within(
    claim: str,
    value: float,
    expected: float,
    tolerance: float,
    error: float = 0.0,
    *,
    relative: bool = False,
    upper: bool = False,
) -> Check:
    """``|value - expected| <= tolerance`` (``relative``: ``|value/expected - 1|``;
    ``upper``: only ``value - expected`` is bounded, as for a χ² against its quantile)."""
    value, error, expected = float(value), float(error), float(expected)
    deviation = value / expected - 1.0 if relative else value - expected
    measure = "value/expected - 1" if relative else "value - expected"
    if upper:
        passed, rule = deviation <= tolerance, f"{measure} <= {tolerance:.3g}"
    else:
        passed, rule = abs(deviation) <= tolerance, f"|{measure}| <= {tolerance:.3g}"
    return Check(claim, value, error, expected, _z(value, error, expected), rule, bool(passed))


def reported(claim: str, value: float, error: float, expected: float) -> Check:
    """``value`` beside ``expected``, with no verdict (an informative row)."""
    value, error, expected = float(value), float(error), float(expected)
    return Check(claim, value, error, expected, _z(value, error, expected), "reported", None)


def table(checks: Iterable[Check]):
    """The checks as a pandas DataFrame with the columns :data:`COLUMNS`."""
    import pandas as pd

    return pd.DataFrame([asdict(check) for check in checks], columns=list(COLUMNS))


def _verdict(passed) -> bool | None:
    """True, False, or None for a reported row (None, or NaN as read from a CSV)."""
    if passed is None or (isinstance(passed, float) and math.isnan(passed)):
        return None
    return bool(passed)


def _failed(passed) -> bool:
    """A verdict that is a failure: False, not an empty (reported) one."""
    return _verdict(passed) is False


def failures(checks) -> list[str]:
    """One line per failed check (``checks``: Check objects or a checks table)."""
    if hasattr(checks, "to_dict"):
        rows = checks.to_dict("records")
    else:
        rows = [asdict(check) for check in checks]
    return [
        f"{row['claim']}: {row['value']:.6g} +- {row['error']:.2g} against "
        f"{row['expected']:.6g} ({row['rule']}, z = {row['z']:.3g})"
        for row in rows
        if _failed(row["passed"])
    ]


def overview(tables):
    """One row per document of ``tables`` ({document: checks table}): the number of checks,
    passed, failed and reported, and the failed claims."""
    import pandas as pd

    rows = []
    for document, frame in tables.items():
        records = frame.to_dict("records")
        verdicts = [_verdict(row["passed"]) for row in records]
        failed = [row["claim"] for row in records if _failed(row["passed"])]
        rows.append(
            {
                "document": document,
                "checks": len(records),
                "passed": verdicts.count(True),
                "failed": len(failed),
                "reported": verdicts.count(None),
                "failed_claims": "; ".join(failed),
            }
        )
    return pd.DataFrame(
        rows, columns=["document", "checks", "passed", "failed", "reported", "failed_claims"]
    )


def overview_rst(frame) -> str:
    """:func:`overview` as a reStructuredText list-table (the report's front page)."""
    lines = [".. list-table::", "   :header-rows: 1", ""]
    columns = ["document", "checks", "passed", "failed", "reported", "failed_claims"]
    header = ["document", "checks", "passed", "failed", "reported", "failed checks"]
    for cells in [header, *frame[columns].astype(str).values.tolist()]:
        lines.append(f"   * - {cells[0]}")
        lines += [f"     - {cell if cell not in ('', 'nan') else '—'}" for cell in cells[1:]]
    return "\n".join(lines) + "\n"


def write(checks: Iterable[Check], csv: str, md: str | None = None, *, fail: bool = False):
    """Write the checks table (``csv`` and its Markdown twin ``md``) and return it; with
    ``fail``, then raise :class:`ChecksFailed` naming every failed check."""
    from kinetic import io

    checks = list(checks)
    frame = table(checks)
    io.write_table(frame, csv, md, float_format=".6g")
    failed = failures(checks)
    if fail and failed:
        raise ChecksFailed(
            f"{len(failed)} of {len(checks)} checks failed (the config's fail_on_checks asks "
            f"the build to stop):\n  " + "\n  ".join(failed)
        )
    return frame
