"""Where a figure comes from: ``python -m kinetic.trace results/<document>/<name>.pdf``
(with ``--configfile``, a path under that config's results root).

Prints the whole pipeline of one target, from the simulations up to the figure or table:
the config section it reads, every rule Snakemake would run for it (with the file and
line that define the rule), the files each rule writes (the netCDF files a figure's
numbers can be recomputed from), the script each rule runs, and the package modules each
script calls (resolved to the file that defines what is imported, so a re-exported engine
front is shown where it is written). Ends with the list of distinct files, the reading
list of someone who wants to follow or change that figure.

The rules and their files come from Snakemake itself (``--rulegraph`` and ``--summary`` of
the target with ``--forceall`` and the given config files), so the trace is what a build
would run, not a guess.
"""

from __future__ import annotations

import argparse
import ast
import importlib
import inspect
import re
import subprocess
import sys
from dataclasses import dataclass, field
from graphlib import TopologicalSorter
from pathlib import Path

from kinetic.config import load_configs, results_root
from kinetic.sources import ENGINES, PACKAGE

__all__ = ["Step", "Trace", "main", "rule_graph", "trace"]

SKIPPED_RULES = frozenset({"all"})
"""Rules that only collect targets."""


@dataclass
class Step:
    """One rule of the pipeline: where it is defined, its script and the modules it calls."""

    rule: str
    rule_file: str
    line: int
    script: str | None = None
    modules: list[str] = field(default_factory=list)
    outputs: list[str] = field(default_factory=list)


@dataclass
class Trace:
    """The pipeline of one target, in the order the rules run."""

    target: str
    config_files: list[str]
    document: str
    config_line: int | None
    steps: list[Step]

    @property
    def files(self) -> list[str]:
        """Every distinct file of the pipeline, in reading order (config first)."""
        seen = dict.fromkeys(self.config_files[-1:])
        for step in self.steps:
            seen.update(dict.fromkeys([step.rule_file, *([step.script] if step.script else [])]))
            seen.update(dict.fromkeys(step.modules))
        return list(seen)


def _snakemake(target: str, config_files: list[str], root: Path, *options: str) -> str:
    command = [sys.executable, "-m", "snakemake", target, "--forceall", *options]
    if config_files:
        command += ["--configfile", *config_files]
    done = subprocess.run(command, cwd=root, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"snakemake could not plan {target}:\n{done.stderr.strip()}")
    return done.stdout


def rule_graph(target: str, config_files: list[str], root: Path) -> dict[str, set[str]]:
    """Rule -> the rules it takes input from, for ``target`` as Snakemake plans it."""
    dot = _snakemake(target, config_files, root, "--rulegraph")
    labels = dict(re.findall(r'^\s*(\d+)\[label = "([^"]+)"', dot, re.MULTILINE))
    graph = {name: set() for name in labels.values()}
    for source, sink in re.findall(r"^\s*(\d+) -> (\d+)", dot, re.MULTILINE):
        graph[labels[sink]].add(labels[source])
    return graph


def rule_outputs(target: str, config_files: list[str], root: Path) -> dict[str, list[str]]:
    """Rule -> the files its jobs write for ``target`` (Snakemake's ``--summary``)."""
    outputs: dict[str, list[str]] = {}
    for line in _snakemake(target, config_files, root, "--summary").splitlines()[1:]:
        columns = line.split("\t")
        if len(columns) > 2:
            outputs.setdefault(columns[2], []).append(columns[0])
    return outputs


def rule_locations(root: Path) -> dict[str, tuple[str, int, str | None]]:
    """Rule name -> (rule file, line, script) for every rule under workflow/rules."""
    found = {}
    for path in sorted((root / "workflow" / "rules").rglob("*.smk")):
        rule, lines = None, path.read_text().splitlines()
        for number, line in enumerate(lines, 1):
            match = re.match(r"(?:rule|checkpoint) (\w+):", line)
            if match:
                rule = match.group(1)
                found[rule] = (str(path.relative_to(root)), number, None)
            elif rule and line.strip() == "script:" and number < len(lines):
                script = (path.parent / lines[number].strip().strip("\"'")).resolve()
                found[rule] = (*found[rule][:2], str(script.relative_to(root.resolve())))
    return found


def _defining_file(module: str, name: str | None) -> str | None:
    """The source file of ``module``, or of what ``from module import name`` imports (a
    submodule, or a function or class, wherever it is defined)."""
    parent = importlib.import_module(module)
    if name is None:
        return inspect.getsourcefile(parent)
    obj = getattr(parent, name, None)
    if obj is None:
        obj = importlib.import_module(f"{module}.{name}")
    try:
        return inspect.getsourcefile(obj)
    except TypeError:  # a constant: it lives in the module itself
        return inspect.getsourcefile(parent)


def _imports(path: Path, wanted) -> list[str]:
    """Source files of what ``path`` imports from package modules accepted by ``wanted``."""
    files = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and wanted(node.module or ""):
            files += [_defining_file(node.module, alias.name) for alias in node.names]
        elif isinstance(node, ast.Import):
            files += [_defining_file(a.name, None) for a in node.names if wanted(a.name)]
    return [file for file in files if file]


def _is_package(module: str) -> bool:
    return module.split(".")[0] == "kinetic"


def _is_engine(module: str) -> bool:
    parts = module.split(".")
    return len(parts) > 1 and parts[0] == "kinetic" and parts[1] in ENGINES


def _in_engine(file: str) -> bool:
    """Whether a package file belongs to an engine package."""
    path = Path(file).resolve()
    return path.is_relative_to(PACKAGE) and path.relative_to(PACKAGE).parts[0] in ENGINES


def package_modules(script: Path, root: Path, *, engines: bool = True) -> list[str]:
    """The package files a script calls, relative to ``root``; with ``engines``, followed
    by the engine fronts that those files call in turn (a study module that runs an engine
    shows the engine)."""
    direct = _imports(script, _is_package)
    fronts = [
        front
        for file in direct
        if engines and not _in_engine(file)
        for front in _imports(Path(file), _is_engine)
    ]
    relative = []
    for file in dict.fromkeys(direct + fronts):
        path = Path(file).resolve()
        inside = path.is_relative_to(root.resolve())
        relative.append(str(path.relative_to(root.resolve())) if inside else file)
    return relative


def _relative(files, root: Path) -> list[str]:
    relative = []
    for file in dict.fromkeys(files):
        path = Path(file).resolve()
        inside = path.is_relative_to(root.resolve())
        relative.append(str(path.relative_to(root.resolve())) if inside else file)
    return relative


def front_modules(rule: str, config, root: Path) -> list[str]:
    """The files defining the fronts that the jobs of simulation rule ``rule`` call
    (``kinetic.studies.Job.front``), relative to ``root``; behind a study's front (one that
    prepares an engine's arguments), the engine fronts it calls."""
    from kinetic import studies

    fronts = dict.fromkeys(job.front for job in studies.jobs(config) if job.rule == rule)
    files = []
    for name in fronts:
        file = inspect.getsourcefile(studies.front(name))
        files.append(file)
        if not _in_engine(file):
            files += _imports(Path(file), _is_engine)
    return _relative(files, root)


def trace(target: str, config_files: list[str] | None = None, root: Path | str = ".") -> Trace:
    """The pipeline of ``target`` (a path under the config's results root) with these
    config files."""
    root = Path(root)
    config_files = list(config_files or ["config/config.yaml"])
    config = load_configs([root / path for path in config_files])
    results = Path(results_root(config))
    graph = rule_graph(target, config_files, root)
    outputs = rule_outputs(target, config_files, root)
    locations = rule_locations(root)
    steps = []
    for rule in TopologicalSorter(graph).static_order():
        if rule in SKIPPED_RULES:
            continue
        rule_file, line, script = locations[rule]
        # the rule grammar: only <document>_simulate_<what> rules run an engine, through the
        # front their jobs name (kinetic.studies); the others run what their script imports
        if "_simulate_" in rule:
            modules = front_modules(rule, config, root)
        else:
            modules = package_modules(root / script, root, engines=False) if script else []
        steps.append(Step(rule, rule_file, line, script, modules, outputs.get(rule, [])))
    inside = Path(target).is_relative_to(results)
    relative = Path(target).relative_to(results).parts if inside else ()
    document = relative[0] if len(relative) > 1 else ""
    config_line = None
    for number, text in enumerate((root / config_files[-1]).read_text().splitlines(), 1):
        if text.startswith(f"{document}:"):
            config_line = number
            break
    return Trace(target, config_files, document, config_line, steps)


def render(result: Trace) -> str:
    """The trace as the command prints it."""
    config = result.config_files[-1]
    where = f", section {result.document}: line {result.config_line}" if result.config_line else ""
    lines = [result.target, f"  config   {config}{where}"]
    for step in result.steps:
        lines.append(f"  rule     {step.rule}  ({step.rule_file}:{step.line})")
        if step.outputs:
            more = f" (+{len(step.outputs) - 1} more)" if len(step.outputs) > 1 else ""
            lines.append(f"    writes {step.outputs[0]}{more}")
        if step.script:
            lines.append(f"    script {step.script}")
        lines += [f"    uses   {module}" for module in step.modules]
    files = result.files
    lines.append(f"{len(files)} files:")
    lines += [f"  {file}" for file in files]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m kinetic.trace", description=__doc__.split("\n")[0]
    )
    parser.add_argument(
        "targets",
        nargs="+",
        help="files under the config's results root, e.g. results/visco2008/fig03.pdf",
    )
    parser.add_argument("--configfile", nargs="+", default=["config/config.yaml"])
    parser.add_argument("--root", default=".", help="the workflow's directory (default: here)")
    args = parser.parse_args(argv)
    for target in args.targets:
        print(render(trace(target, args.configfile, args.root)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
