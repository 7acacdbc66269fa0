"""``python -m kinetic.bench <engine> [--quick] [--out results/benchmarks]``."""

from __future__ import annotations

import argparse
import ast
import importlib
import inspect
import logging
import pkgutil
from pathlib import Path

import kinetic.bench as bench


def available_engines() -> list[str]:
    """The bench modules that time something (those with a ``run``; ``summary`` reads
    their reports)."""

    def times_something(name: str) -> bool:  # a top-level ``def run``, read, not imported
        tree = ast.parse((Path(bench.__path__[0]) / f"{name}.py").read_text())
        return any(isinstance(node, ast.FunctionDef) and node.name == "run" for node in tree.body)

    return sorted(
        m.name
        for m in pkgutil.iter_modules(bench.__path__)
        if not m.name.startswith("_") and times_something(m.name)
    )


def main(argv: list[str] | None = None) -> None:
    engines = available_engines()
    parser = argparse.ArgumentParser(prog="python -m kinetic.bench", description=__doc__)
    parser.add_argument("engine", choices=engines, help="engine to time")
    parser.add_argument("--quick", action="store_true", help="fewer sizes and repeats")
    parser.add_argument("--out", default="results/benchmarks", help="output directory")
    parser.add_argument(
        "--sections", help="comma-separated sections to run (engines that have sections: cuda)"
    )
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    module = importlib.import_module(f"kinetic.bench.{args.engine}")
    if hasattr(module, "precondition"):  # cuda: a GPU, not the simulator
        try:
            module.precondition()
        except RuntimeError as error:
            parser.error(str(error))
    options = {}
    accepted = inspect.signature(module.run).parameters
    if "checkpoint" in accepted:  # long reports are rewritten after every section
        options["checkpoint"] = lambda report: bench.write_report(args.engine, report, args.out)
    if args.sections:
        if "sections" not in accepted:
            parser.error(f"{args.engine} has no sections")
        options["sections"] = args.sections.split(",")
    report = module.run(quick=args.quick, **options)
    path = bench.write_report(args.engine, report, args.out)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
