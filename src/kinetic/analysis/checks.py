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


@functools.cache
def _student_sums_of_squares(n_values: int, dof: int, draws: int):
    """``draws`` sums of ``n_values`` squared Student's t with ``dof`` degrees of freedom,
    sorted: a Monte Carlo seeded by its arguments (the same numbers every call), computed
    once per process."""
    import numpy as np

    if dof < 1 or n_values < 1:
        raise ValueError(f"need >= 1 value and >= 1 degree of freedom, got {n_values}, {dof}")
    rng = np.random.default_rng(n_values * 100_003 + dof)
    chunk = max(1, 4_000_000 // n_values)
    sums = np.concatenate(
        [
            np.sum(rng.standard_t(dof, size=(min(chunk, draws - start), n_values)) ** 2, axis=1)
            for start in range(0, draws, chunk)
        ]
    )
    sums.sort()
    return sums


def sum_of_squares_tolerance(n_values: int, dof: int, false_alarm: float = 1e-3) -> float:
    """Bound on Σ z² over ``n_values`` independent z-scores, each Student's t with ``dof``
    degrees of freedom (errors from dof + 1 realizations), exceeded with probability
    ``false_alarm``. χ²'s quantile holds for exact errors only: with 12 realizations, Σ z²
    over 40 bins exceeds χ²_40's 10⁻³ quantile (73.4) with probability 4.4 %; this bound is
    107.5. A seeded Monte Carlo of 200/``false_alarm`` sums (at least 10⁶: the quantile to
    about a percent), χ²'s quantile beyond 10⁴ degrees of freedom."""
    import numpy as np
    from scipy import stats

    if dof > 10_000:
        return float(stats.chi2.isf(false_alarm, n_values))
    sums = _student_sums_of_squares(n_values, dof, max(10**6, int(200 / false_alarm)))
    return float(np.quantile(sums, 1.0 - false_alarm))


def sum_of_squares_p_value(total: float, n_values: int, dof: int) -> float:
    """Probability that Σ z² of ``n_values`` Student's t with ``dof`` degrees of freedom
    reaches ``total`` (the χ² test's p-value when the errors come from dof + 1
    realizations; :func:`sum_of_squares_tolerance`): (exceedances + 1)/(draws + 1) of 10⁶
    seeded sums, so never 0; χ²'s beyond 10⁴ degrees of freedom."""
    import numpy as np
    from scipy import stats

    if dof > 10_000:
        return float(stats.chi2.sf(total, n_values))
    sums = _student_sums_of_squares(n_values, dof, 10**6)
    exceeding = sums.size - int(np.searchsorted(sums, total, side="left"))
    return float((exceeding + 1) / (sums.size + 1))


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


def _z(value: float, error: float, expected: float) -> float:
    difference = value - expected
    if error > 0:
        return difference / error
    return math.nan


def agrees(claim: str, value: float, error: float, expected: float, sigmas: float) -> Check:
    """``value`` equals ``expected`` within ``sigmas`` standard errors."""
    value, error, expected = float(value), float(error), float(expected)
    z = _z(value, error, expected)
    passed = abs(z) <= sigmas if error > 0 else value == expected
    return Check(claim, value, error, expected, z, f"|z| <= {sigmas:.3g}", bool(passed))


def exceeds(claim: str, value: float, error: float, bound: float, sigmas: float) -> Check:
    """``value`` is above ``bound`` by more than ``sigmas`` standard errors."""
    value, error, bound = float(value), float(error), float(bound)
    z = _z(value, error, bound)
    passed = z > sigmas if error > 0 else value > bound
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
