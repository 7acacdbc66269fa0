"""Compare two results trees: ``python -m kinetic.compare results_a results_b``.

For every table (``*.csv``) and dataset (``*.nc``) under either tree, by relative path:

- a file present in only one tree is a difference;
- tables: the same columns in the same order and the same rows; numeric cells equal
  (within ``--rtol``/``--atol``, exact by default), other cells identical;
- datasets: the same data variables with the same dimensions and values (attributes,
  which carry provenance such as the git revision, are not compared). Variables that time
  the run (names containing ``cpu``, ``wall`` or ``inefficiency``, and ``--ignore``
  patterns) are skipped, and so is the build's own record under ``workflow/``: they
  differ between any two runs of the same code. The results roots of other configs
  nested in a tree (``results/ci`` inside ``results``) are not part of it.

``--rename old=new`` maps a dimension or variable name of the first tree to its name in
the second, for a refactor that renamed a dimension but no number.

Prints one line per differing file (the largest absolute and relative difference of each
variable or column) and a summary; exits 1 when anything differs, 0 otherwise. Used to
show that a refactor changed no number: build the same config with the same seed before
and after, then compare.
"""

from __future__ import annotations

import argparse
import fnmatch
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from kinetic.config import root_files

__all__ = ["Report", "compare_trees", "main"]

TIMING_PATTERNS = ("*cpu*", "*wall*", "*inefficiency*")
"""Names of variables and columns that time the run, or derive from its timing (an
inefficiency is an error squared times CPU seconds)."""

RECORD_FILES = ("workflow/*",)
"""Files that record the build itself (results/workflow/jobs.csv: rules, run times,
memory), not results: they differ between any two builds."""


@dataclass
class Report:
    """Outcome of a comparison: files compared, and the differences found."""

    compared: int = 0
    differences: list[str] = field(default_factory=list)

    @property
    def identical(self) -> bool:
        return not self.differences


def _skipped(name: str, patterns) -> bool:
    return any(fnmatch.fnmatch(name.lower(), pattern) for pattern in patterns)


def _numeric_difference(a, b, rtol: float, atol: float) -> str | None:
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape:
        return f"shape {a.shape} against {b.shape}"
    if a.dtype.kind in "fciub" and b.dtype.kind in "fciub":
        a, b = a.astype(float), b.astype(float)
        same_nan = np.isnan(a) & np.isnan(b)
        close = np.isclose(a, b, rtol=rtol, atol=atol, equal_nan=True) | same_nan
        if close.all():
            return None
        diff = np.abs(a - b)[~close]
        scale = np.maximum(np.abs(a), np.abs(b))[~close]
        with np.errstate(divide="ignore", invalid="ignore"):
            relative = np.nanmax(np.where(scale > 0, diff / scale, np.inf))
        count = int((~close).sum())
        return f"{count} values differ, max |diff| {np.nanmax(diff):.3g}, max rel {relative:.3g}"
    if a.shape == b.shape and np.array_equal(a.astype(str), b.astype(str)):
        return None
    return "non-numeric values differ"


def _compare_tables(path_a: Path, path_b: Path, rtol, atol, patterns) -> list[str]:
    import pandas as pd

    a, b = pd.read_csv(path_a), pd.read_csv(path_b)
    if list(a.columns) != list(b.columns):
        return [f"columns {list(a.columns)} against {list(b.columns)}"]
    if len(a) != len(b):
        return [f"{len(a)} rows against {len(b)}"]
    problems = []
    for column in a.columns:
        if _skipped(column, patterns):
            continue
        difference = _numeric_difference(a[column].to_numpy(), b[column].to_numpy(), rtol, atol)
        if difference:
            problems.append(f"column {column}: {difference}")
    return problems


def _compare_datasets(path_a: Path, path_b: Path, rtol, atol, patterns, renames=None) -> list[str]:
    import xarray as xr

    with xr.open_dataset(path_a) as a, xr.open_dataset(path_b) as b:
        a = a.rename(
            {
                old: new
                for old, new in (renames or {}).items()
                if old in a.variables or old in a.dims
            }
        )
        names_a = {n for n in a.variables if not _skipped(str(n), patterns)}
        names_b = {n for n in b.variables if not _skipped(str(n), patterns)}
        problems = [f"variable {n} only in the first" for n in sorted(names_a - names_b, key=str)]
        problems += [f"variable {n} only in the second" for n in sorted(names_b - names_a, key=str)]
        for name in sorted(names_a & names_b, key=str):
            if a[name].dims != b[name].dims:
                problems.append(
                    f"variable {name}: dimensions {a[name].dims} against {b[name].dims}"
                )
                continue
            difference = _numeric_difference(a[name].values, b[name].values, rtol, atol)
            if difference:
                problems.append(f"variable {name}: {difference}")
    return problems


def compare_trees(
    first: Path,
    second: Path,
    *,
    rtol: float = 0.0,
    atol: float = 0.0,
    ignore=(),
    renames=None,
) -> Report:
    """Compare every ``*.csv`` and ``*.nc`` under ``first`` and ``second`` (see the module
    docstring); ``ignore`` adds glob patterns of variable or column names to skip;
    ``renames`` maps dataset dimension and variable names of ``first`` to those of
    ``second``."""
    first, second = Path(first), Path(second)
    patterns = TIMING_PATTERNS + tuple(p.lower() for p in ignore)
    report = Report()
    files = set()
    for root in (first, second):
        for suffix in ("*.csv", "*.nc"):
            files |= {
                path.relative_to(root)
                for path in root_files(root, suffix)
                if not _skipped(path.relative_to(root).as_posix(), RECORD_FILES)
            }
    for relative in sorted(files):
        a, b = first / relative, second / relative
        if not a.exists() or not b.exists():
            report.differences.append(f"{relative}: only in {first if a.exists() else second}")
            continue
        report.compared += 1
        if relative.suffix == ".csv":
            problems = _compare_tables(a, b, rtol, atol, patterns)
        else:
            problems = _compare_datasets(a, b, rtol, atol, patterns, renames)
        for problem in problems:
            report.differences.append(f"{relative}: {problem}")
    return report


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m kinetic.compare", description=__doc__.splitlines()[0]
    )
    parser.add_argument("first", type=Path, help="a results directory")
    parser.add_argument("second", type=Path, help="another results directory")
    parser.add_argument("--rtol", type=float, default=0.0, help="relative tolerance (0: exact)")
    parser.add_argument("--atol", type=float, default=0.0, help="absolute tolerance (0: exact)")
    parser.add_argument(
        "--ignore", action="append", default=[], help="glob of variable/column names to skip"
    )
    parser.add_argument(
        "--rename",
        action="append",
        default=[],
        metavar="OLD=NEW",
        help="a dataset dimension or variable named OLD in the first tree is NEW in the second",
    )
    args = parser.parse_args(argv)
    renames = {}
    for pair in args.rename:
        old, sep, new = pair.partition("=")
        if not (sep and old and new):
            parser.error(f"--rename takes OLD=NEW, got {pair!r}")
        renames[old] = new
    for directory in (args.first, args.second):
        if not directory.is_dir():
            parser.error(f"{directory} is not a directory")
    report = compare_trees(
        args.first,
        args.second,
        rtol=args.rtol,
        atol=args.atol,
        ignore=args.ignore,
        renames=renames,
    )
    for line in report.differences:
        print(line)
    verdict = "identical" if report.identical else f"{len(report.differences)} differences"
    print(f"{report.compared} files compared in both trees: {verdict}")
    return 0 if report.identical else 1


if __name__ == "__main__":
    sys.exit(main())
