"""An engine against itself at another git revision, side by side in one process:
``python -m kinetic.bench.sidebyside REV [--case NAME] [--rounds N]``.

On the shared development machine the same code runs 6.4-8.9 × 10⁵ EDMD collisions per
CPU-s in processes started minutes apart, so two versions timed in turn, each in its own
process, cannot tell a change of a few per cent from the machine's drift. Here the
package of revision ``REV`` (``git archive``) is imported under another name
(``kinetic_ref``: its own absolute imports rewritten, its own numba cache under
``results/sidebyside/<rev>``) beside the working tree's ``kinetic``, both run the same
case from the same seed, and the rounds alternate: one slow spell slows both. Reports the
median rate of each, the median and range of the per-round ratios (this tree over
``REV``), and whether both made the same events (an optimisation that keeps the collision
sequence keeps the counters), to stdout and ``results/benchmarks/sidebyside-<case>.json``.
"""

from __future__ import annotations

import argparse
import importlib
import io
import math
import re
import shutil
import statistics
import subprocess
import sys
import tarfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from kinetic.bench import write_report
from kinetic.bench.edmd import PACKING_FRACTION_3D

__all__ = ["CASES", "compare", "rename_package", "round_ratios"]

REFERENCE = "kinetic_ref"
"""Name the revision's package is imported under."""

_NAME = re.compile(r"\bkinetic(?=[.\s\"'])")
"""The package name where it is a module path (``kinetic.x``, ``import kinetic``,
``"kinetic.x"``), not inside another word."""


def rename_package(source: Path, destination: Path, name: str = REFERENCE) -> Path:
    """Copy the package at ``source`` (a ``kinetic`` directory) to ``destination/name``
    with every module path ``kinetic...`` in its Python files rewritten to ``name...``;
    returns the new package's directory."""
    target = destination / name
    shutil.copytree(source, target, ignore=shutil.ignore_patterns("__pycache__"))
    for path in target.rglob("*.py"):
        path.write_text(_NAME.sub(name, path.read_text()))
    return target


def _reference_package(revision: str, root: Path) -> tuple[Path, str]:
    """``root/<commit>/kinetic_ref`` holding ``src/kinetic`` of ``revision`` (made once
    per commit, so its numba cache is kept between runs); returns its parent and the
    commit."""
    commit = subprocess.run(
        ["git", "rev-parse", "--short=12", f"{revision}^{{commit}}"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout.strip()
    parent = root / commit
    if not (parent / REFERENCE).is_dir():
        archive = subprocess.run(
            ["git", "archive", "--format=tar", commit, "src/kinetic"],
            check=True,
            capture_output=True,
        ).stdout
        staging = parent / "staging"
        shutil.rmtree(staging, ignore_errors=True)
        with tarfile.open(fileobj=io.BytesIO(archive)) as tar:
            tar.extractall(staging, filter="data")
        rename_package(staging / "src" / "kinetic", parent)
        shutil.rmtree(staging)
    return parent, commit


def _edmd_case(
    dimension: int, density: float
) -> Callable[[str], tuple[Callable[[], int], Callable[[], dict]]]:
    def make(package: str):
        system_class = importlib.import_module(f"{package}.edmd").HardSphereSystem
        system = system_class(n_particles=1000, density=density, dimension=dimension, seed=2025)
        system.run(collisions=300_000)  # compiled, equilibrated, warm

        def work() -> int:
            system.run(collisions=200_000)
            return 200_000

        return work, system.counters

    return make


CASES = {
    # the fast target's case: 2D, N = 1e3, rho sigma^2 = 1e-2
    "edmd-2d": _edmd_case(2, 1e-2),
    # the peer's case: 3D, N = 1e3, packing fraction 0.01
    "edmd-3d": _edmd_case(3, 6.0 * PACKING_FRACTION_3D / math.pi),
}
"""Each case: package name -> (a call doing some work and returning its amount, a call
returning the counters that identify the sequence of events)."""


def round_ratios(reference: list[float], current: list[float]) -> dict[str, float]:
    """Median, smallest and largest of the per-round ratios current/reference (rates of
    the same round)."""
    ratios = [b / a for a, b in zip(reference, current, strict=True)]
    return {"median": statistics.median(ratios), "min": min(ratios), "max": max(ratios)}


def compare(revision: str, case: str, rounds: int, root: Path) -> dict[str, Any]:
    """Time ``case`` of this tree against ``revision``'s, in alternating rounds."""
    parent, commit = _reference_package(revision, root)
    sys.path.insert(0, str(parent))
    runs = {name: CASES[case](name) for name in ("kinetic", REFERENCE)}
    rates: dict[str, list[float]] = {name: [] for name in runs}
    for _ in range(rounds):
        for name, (work, _) in runs.items():
            begin = time.process_time()
            amount = work()
            rates[name].append(amount / max(time.process_time() - begin, 1e-9))
    counters = {name: counts() for name, (_, counts) in runs.items()}
    return {
        "case": case,
        "reference_revision": commit,
        "rounds": rounds,
        "rate_unit": "work per CPU-second (process time)",
        "median_rate": {name: statistics.median(values) for name, values in rates.items()},
        "rates": rates,
        "ratio_this_tree_over_reference": round_ratios(rates[REFERENCE], rates["kinetic"]),
        "same_events": counters["kinetic"] == counters[REFERENCE],
    }


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(
        prog="python -m kinetic.bench.sidebyside", description=__doc__.splitlines()[0]
    )
    parser.add_argument("revision", help="git revision to time against (e.g. HEAD, main~3)")
    parser.add_argument("--case", choices=sorted(CASES), default="edmd-2d")
    parser.add_argument("--rounds", type=int, default=10, help="alternating rounds (>= 3)")
    parser.add_argument("--root", default="results/sidebyside", help="the revisions' copies")
    parser.add_argument("--out", default="results/benchmarks", help="output directory")
    args = parser.parse_args(argv)
    if args.rounds < 3:
        parser.error("--rounds must be at least 3 (a median of fewer says little)")
    try:
        report = compare(args.revision, args.case, args.rounds, Path(args.root))
    except subprocess.CalledProcessError as error:  # git: no repository here, no such revision
        said = error.stderr or ""
        said = said.decode(errors="replace") if isinstance(said, bytes) else said
        parser.error(
            f"cannot read revision {args.revision!r} with git (run from the repository's "
            f"root): {said.strip()}"
        )
    path = write_report(f"sidebyside-{args.case}", report, args.out)
    ratio = report["ratio_this_tree_over_reference"]
    print(
        f"{args.case}: this tree {report['median_rate']['kinetic']:.4g}, "
        f"{report['reference_revision']} {report['median_rate'][REFERENCE]:.4g} per CPU-s; "
        f"ratio {ratio['median']:.3f} (rounds {ratio['min']:.3f}-{ratio['max']:.3f}); "
        f"same events: {report['same_events']}; wrote {path}"
    )


if __name__ == "__main__":
    main()
