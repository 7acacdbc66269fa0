"""The numbers of the README and of docs/, taken from the files the build and the bench write.

Three commands (``make docs`` runs the first two after a build of the default config and
the benches)::

    python -m kinetic.docs collect   # results/ -> docs/data/summary.json, docs/gallery/*.png
                                     # (--benchmarks-only: only the bench reports)
    python -m kinetic.docs render    # summary.json and the configs -> the generated blocks
    python -m kinetic.docs check     # exit 1 if a block differs from what render writes

``collect`` reads, from a finished build: every document's ``checks.csv`` (the counts and
the headline claims, :data:`HEADLINES`), the figures and tables it holds, the timings
that ``make figures`` and ``make test`` record (``results/timings/*.json``, written by
:func:`timed`) and the bench reports (``results/benchmarks/*.json``); it also writes one
small thumbnail per document (:data:`GALLERY`). ``render`` replaces every block between
``<!-- generated: NAME -->`` and ``<!-- end: NAME -->`` in README.md and docs/*.md by
what :func:`blocks` makes of the summary (and of ``kinetic.plan`` for the cost tables,
which need no build). A test runs ``check``, so no quoted number can drift from its
source.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import re
import resource
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from kinetic import DOCUMENTS

__all__ = [
    "BLOCK",
    "DOCUMENTS",
    "GALLERY",
    "HEADLINES",
    "apply_blocks",
    "blocks",
    "collect",
    "main",
    "measurement",
    "timed",
]

REPOSITORY = Path(__file__).resolve().parents[2]
SUMMARY = Path("docs/data/summary.json")
GALLERY_DIR = Path("docs/gallery")

TITLES = {
    "visco2008": "Visco, van Wijland, Trizac (2008), collisional statistics of the hard-sphere gas",
    "montanero2007": "Montanero, Santos, Garzó (2007), first-order Chapman–Enskog distribution",
    "krauth2025": "Krauth (2025), Oxford lecture 4: from Newtonian to Boltzmann mechanics",
    "costantini2010": "Costantini, Puglisi (2010), fluctuating hydrodynamics of granular gases",
}

HEADLINES = {
    "visco2008": (
        (
            "Table I, MD row t = 10: k2 equals",
            "Table I, MD k2 at t = 10 (ρ → 0) against the printed value",
        ),
        (
            "hard disks, 1/N_c -> 0: mu equals Eq. (28) at lambda = 1",
            "cloning μ(1) of hard disks against Eq. (28)",
        ),
    ),
    "montanero2007": (("kappa'/kappa0 at alpha = 1", "κ′/κ0 at α = 1 against 1.025218"),),
    "krauth2025": (
        ("direct-pin, 15 pins on L = 20: beta P", "βP of 15 pins on L = 20 against 3"),
        ("four disks: beta P_x, kinematic", "βP of four disks, kinematic against contact"),
    ),
    "costantini2010": (
        ("nu*(1/N -> 0) = converged elastic value: md", "MD ν*(α = 1, N → ∞) against 0.2039"),
        (
            "nu*(1/N -> 0) = converged elastic value: dsmc",
            "DSMC ν*(α = 1, N → ∞) against 0.2039",
        ),
    ),
}
"""Per document, the claims the README quotes, (first words of the claim, short label):
the first check whose claim starts so."""

GALLERY = {
    "visco2008": "fig05",
    "montanero2007": "fig03",
    "krauth2025": "fig04_11",
    "costantini2010": "fig05",
}
"""The figure of each document shown on the front page (docs/gallery/<document>.png)."""

THUMBNAIL_WIDTH = 480
"""Width in pixels of the gallery's thumbnails."""

BLOCK = re.compile(
    r"(<!-- generated: (?P<name>[\w-]+) .*?-->\n)(?P<body>.*?)(<!-- end: (?P=name) -->)",
    re.DOTALL,
)
"""A generated block of a Markdown file."""


# ------------------------------------------------------------------ numbers as text
def measurement(value: float, error: float) -> str:
    """``value ± error`` with the error to two significant digits and the value to the same
    decimal place (``1.0265 ± 0.0064``); an exact value (error 0) with six digits."""
    if not (error > 0 and math.isfinite(error)):
        return f"{value:.6g}"
    decimals = max(0, 1 - math.floor(math.log10(error)))
    return f"{value:.{decimals}f} ± {error:.{decimals}f}"


def _seconds(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def _rate(value: float) -> str:
    exponent = math.floor(math.log10(value)) if value > 0 else 0
    return f"{value / 10**exponent:.2f} × 10^{exponent}"


# ------------------------------------------------------------------ timings
def timed(out: str | os.PathLike, command: list[str]) -> int:
    """Run ``command``, then write its wall time, the CPU time of everything it started,
    the date, the machine and the git revision to ``out`` (JSON); returns its exit code.
    ``make figures`` and ``make test`` run through it, so the README's durations come
    from a file the build writes."""
    from kinetic.bench import machine

    start = time.perf_counter()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    code = subprocess.call(command)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    record = {
        "command": command,
        "exit_code": code,
        "wall_seconds": time.perf_counter() - start,
        "cpu_seconds": cpu,
        "date": datetime.date.today().isoformat(),
        "machine": machine(),
    }
    path = Path(out)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(record, indent=2) + "\n")
    return code


# ------------------------------------------------------------------ collect
def _plain(value):
    """A table cell as JSON takes it: None for a missing value, Python numbers."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return None
    return value.item() if hasattr(value, "item") else value


def _checks(root: Path, document: str) -> dict[str, Any] | None:
    import pandas as pd

    path = root / document / "checks.csv"
    if not path.is_file():
        return None
    table = pd.read_csv(path)
    passed = table["passed"]
    verdicts = passed.dropna().astype(bool)
    headlines = []
    for prefix, label in HEADLINES[document]:
        rows = table[table["claim"].str.startswith(prefix)]
        if len(rows):
            row = rows.iloc[0].to_dict()
            columns = ("claim", "value", "error", "expected", "z", "rule", "passed")
            values = {key: _plain(row[key]) for key in columns}
            headlines.append(values | {"label": label})
    return {
        "checks": len(table),
        "passed": int(verdicts.sum()),
        "failed": int((~verdicts).sum()),
        "reported": int(passed.isna().sum()),
        "failures": list(table.loc[passed.notna() & ~passed.fillna(True).astype(bool), "claim"]),
        "headlines": headlines,
    }


def _artefacts(root: Path, document: str) -> dict[str, list[str]]:
    folder = root / document
    figures = sorted(path.stem for path in folder.glob("*.pdf"))
    tables = sorted(path.stem for path in folder.glob("*.csv"))
    return {"figures": figures, "tables": tables}


def _thumbnail(source: Path, target: Path) -> None:
    import matplotlib.image as image
    import matplotlib.pyplot as plt

    picture = image.imread(source)
    height, width = picture.shape[:2]
    scale = THUMBNAIL_WIDTH / width
    figure = plt.figure(figsize=(THUMBNAIL_WIDTH / 100, height * scale / 100), dpi=100)
    axes = figure.add_axes((0, 0, 1, 1))
    axes.imshow(picture, interpolation="antialiased")
    axes.set_axis_off()
    target.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(target, dpi=100, metadata={"Software": None})
    plt.close(figure)


def _benchmarks(directory: Path, kept: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The rows of the bench reports in ``directory``; an engine without a report there
    keeps its rows of ``kept`` (the summary before), so timing one engine again replaces
    only that engine's rows."""
    from kinetic.bench.summary import rows

    found = []
    for path in sorted(directory.glob("*.json")):
        report = json.loads(path.read_text())
        found += rows(report)
    timed_now = {row["engine"] for row in found}
    merged = [row for row in kept if row["engine"] not in timed_now] + found
    return sorted(merged, key=lambda row: row["engine"])  # stable: each report's order


def collect(
    results: str | os.PathLike = "results",
    benchmarks: str | os.PathLike = "results/benchmarks",
    timings: str | os.PathLike = "results/timings",
    out: str | os.PathLike = SUMMARY,
    gallery: str | os.PathLike | None = GALLERY_DIR,
    *,
    benchmarks_only: bool = False,
) -> dict[str, Any]:
    """The summary of a finished build of the default config (see the module docstring),
    written to ``out``; thumbnails of :data:`GALLERY` to ``gallery``. The bench rows of an
    engine with no report in ``benchmarks`` are kept from ``out``. With
    ``benchmarks_only`` only the bench rows change: the documents and timings are kept
    from ``out`` (after ``python -m kinetic.bench <engine>`` without a build)."""
    previous = json.loads(Path(out).read_text()) if Path(out).is_file() else {}
    kept = previous.get("benchmarks", [])
    if benchmarks_only:
        summary = previous | {"benchmarks": _benchmarks(Path(benchmarks), kept)}
        return _write_summary(summary, out)
    root = Path(results)
    summary: dict[str, Any] = {"results": str(results), "documents": {}, "timings": {}}
    for document in DOCUMENTS:
        summary["documents"][document] = {
            "title": TITLES[document],
            "artefacts": _artefacts(root, document),
            "checks": _checks(root, document),
        }
        if gallery is not None:
            source = root / document / f"{GALLERY[document]}.png"
            if source.is_file():
                _thumbnail(source, Path(gallery) / f"{document}.png")
    for path in sorted(Path(timings).glob("*.json")):
        record = json.loads(path.read_text())
        summary["timings"][path.stem] = {
            key: record[key] for key in ("wall_seconds", "cpu_seconds", "date", "exit_code")
        } | {
            "note": record.get("note", ""),
            "summary": record.get("summary", ""),
            "cpu": record["machine"]["cpu"],
            "logical_cpus": record["machine"]["logical_cpus"],
            "git_revision": record["machine"]["git_revision"],
        }
        # the folded history of earlier runs: kept, and a record of another revision that
        # this one replaces goes to its head
        before = previous.get("timings", {}).get(path.stem, {})
        earlier = before.get("earlier", "")
        revision = before.get("git_revision")
        if revision and revision != summary["timings"][path.stem]["git_revision"]:
            replaced = (
                f"Earlier, {revision[:7]}'s record "
                f"({float(before['wall_seconds']):.0f} s, {float(before['cpu_seconds']):.0f} "
                f"CPU-s, {before.get('date')}; {before.get('summary', '')}): "
                f"{before.get('note', '')}"
            )
            earlier = f"{replaced} {earlier}".strip()
        if earlier:
            summary["timings"][path.stem]["earlier"] = earlier
    summary["benchmarks"] = _benchmarks(Path(benchmarks), kept)
    return _write_summary(summary, out)


def _write_summary(summary: dict[str, Any], out: str | os.PathLike) -> dict[str, Any]:
    path = Path(out)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(summary, indent=2, sort_keys=True) + "\n")
    return summary


# ------------------------------------------------------------------ render
def _headline(check: dict[str, Any], *, short: bool = False) -> str:
    z = "" if check["z"] is None else f", z = {check['z']:+.1f}"
    verdict = {True: "", False: " (fails)", None: ""}[check["passed"]]
    value = measurement(check["value"], check["error"] or 0.0)
    if short:
        return f"{check['label']}: {value}{z}{verdict}"
    return f"{check['claim']}: {value} against {check['expected']:.7g}{z}{verdict}"


def _agreement(summary: dict[str, Any]) -> str:
    lines = [
        "| document | reproduced | checks passed | key agreement |",
        "| --- | --- | --- | --- |",
    ]
    for document in DOCUMENTS:
        entry = summary["documents"][document]
        artefacts = entry["artefacts"]
        figures = len([name for name in artefacts["figures"] if name.startswith("fig")])
        others = len(artefacts["figures"]) - figures
        reproduced = f"{figures} figures, {len(artefacts['tables'])} tables, {others} studies"
        checks = entry["checks"]
        if checks is None:
            lines.append(f"| {document} | {reproduced} | — | — |")
            continue
        verdicts = checks["passed"] + checks["failed"]
        headline = "; ".join(_headline(check, short=True) for check in checks["headlines"])
        lines.append(
            f"| [{document}](docs/reproduced.md#{document}) | {reproduced} | "
            f"{checks['passed']} of {verdicts} | {headline} |"
        )
    return "\n".join(lines) + "\n"


def _timing(summary: dict[str, Any], name: str, detail: bool) -> str:
    """One timing record: wall, CPU, machine, date and revision, then its ``summary`` (a
    short outcome, the README's) or, with ``detail``, its whole ``note`` as well."""
    record = summary["timings"].get(name)
    if record is None:
        return "not measured yet"
    head = (
        f"{_seconds(record['wall_seconds'])} wall, {record['cpu_seconds'] / 3600:.2f} CPU-hours "
        f"on {record['logical_cpus']} cores ({record['cpu']}, {record['date']}, "
        f"revision {record['git_revision'][:7]})"
    )
    said = [record.get("summary", "")] + ([record.get("note", "")] if detail else [])
    said = [text for text in said if text]
    return head + (": " + "; ".join(said) if said else "")


TIMED_COMMANDS = {
    "figures-config": (
        "`make figures`",
        " (the build of the default config from a clean clone, numba's compilation "
        "included, the installation not)",
    ),
    "test": ("`make test`", ""),
}
"""The timing records the README and docs/benchmarks.md quote: name -> (command, what it
covers)."""


def _timings(summary: dict[str, Any], detail: bool = False) -> str:
    """A bullet per timed command; with ``detail``, each record's ``earlier`` (the records
    it replaced, as one text) follows the bullets, folded."""
    lines = [
        f"- {command}{covers}: {_timing(summary, name, detail)}"
        for name, (command, covers) in TIMED_COMMANDS.items()
    ]
    if detail:
        for name, (command, _) in TIMED_COMMANDS.items():
            earlier = summary["timings"].get(name, {}).get("earlier")
            if earlier:
                lines += ["", f"<details><summary>Earlier runs of {command}</summary>", ""]
                lines += [earlier, "", "</details>"]
    return "\n".join(lines) + "\n"


def _checks_tables(summary: dict[str, Any]) -> str:
    out = []
    for document in DOCUMENTS:
        checks = summary["documents"][document]["checks"]
        if checks is None:
            continue
        out.append(
            f"**{document}** ({checks['checks']} checks: {checks['passed']} passed, "
            f"{checks['failed']} failed, {checks['reported']} reported)"
        )
        out += [f"- {_headline(check)}" for check in checks["headlines"]]
        out += [f"- failed: {claim}" for claim in checks["failures"]]
        out.append("")
    return "\n".join(out)


def _benchmark_table(summary: dict[str, Any], engine: str | None = None) -> str:
    lines = [
        "| engine | case | rate | unit | date | CPU | load | revision |",
        "| --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for row in summary["benchmarks"]:
        if engine is not None and row["engine"] != engine:
            continue
        lines.append(
            f"| {row['engine']} | {row['case']} | {_rate(row['rate'])} | {row['unit']} | "
            f"{row['date']} | {row['cpu']} | {row['load']:.1f} | {row['revision'][:7]} |"
        )
    return "\n".join(lines) + "\n"


def _speed(summary: dict[str, Any], engine: str) -> str:
    """The headline rates of one engine, each group of rows measured on one machine and
    date followed by those (an engine's rows may come from benches of different days)."""
    rows = [row for row in summary["benchmarks"] if row["engine"] == engine and row["headline"]]
    if not rows:
        return "not measured yet\n"
    groups: dict[tuple[str, str], list[str]] = {}
    for row in rows:
        rate = f"{_rate(row['rate'])} {row['unit']} ({row['case']})"
        groups.setdefault((row["cpu"], row["date"]), []).append(rate)
    return (
        "; ".join(
            "; ".join(rates) + f" — one core of {cpu}, {date}"
            for (cpu, date), rates in groups.items()
        )
        + "\n"
    )


def _plan(*configs: str) -> str:
    from kinetic import plan
    from kinetic.config import load_configs

    jobs = plan.plan_jobs(load_configs([REPOSITORY / config for config in configs]))
    return plan.summary_table(jobs) + "\n"


def blocks(summary: dict[str, Any]) -> dict[str, str]:
    """Every generated block by name."""
    made = {
        "agreement": _agreement(summary),
        "timings": _timings(summary),
        "timings-detail": _timings(summary, detail=True),
        "checks": _checks_tables(summary),
        "benchmarks": _benchmark_table(summary),
        "plan-default": _plan("config/config.yaml"),
        "plan-paper": _plan("config/paper.yaml"),
        "plan-paper-gpu": _plan("config/paper.yaml", "config/paper-gpu.yaml"),
        "plan-ci": _plan("config/ci.yaml"),
    }
    for engine in ("edmd", "dsmc", "cloning", "samplers"):
        made[f"speed-{engine}"] = _speed(summary, engine)
    return made


def apply_blocks(text: str, made: dict[str, str]) -> str:
    """``text`` with every generated block's body replaced (an unknown name is an error)."""

    def replace(match: re.Match) -> str:
        name = match.group("name")
        if name not in made:
            raise KeyError(f"no generator for the block {name!r}")
        return match.group(1) + made[name] + match.group(4)

    return BLOCK.sub(replace, text)


def documents_with_blocks() -> list[Path]:
    """README.md and every docs/*.md."""
    return [REPOSITORY / "README.md", *sorted((REPOSITORY / "docs").glob("*.md"))]


def render(summary_path: str | os.PathLike = REPOSITORY / SUMMARY, *, write: bool = True):
    """Rewrite the generated blocks; returns the files whose text changed (or would)."""
    summary = json.loads(Path(summary_path).read_text())
    made = blocks(summary)
    changed = []
    for path in documents_with_blocks():
        text = path.read_text()
        new = apply_blocks(text, made)
        if new != text:
            changed.append(path)
            if write:
                path.write_text(new)
    return changed


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m kinetic.docs", description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    collecting = commands.add_parser("collect", help="summarise a finished build")
    collecting.add_argument("--results", default="results")
    collecting.add_argument("--benchmarks", default="results/benchmarks")
    collecting.add_argument("--timings", default="results/timings")
    collecting.add_argument("--out", default=str(SUMMARY))
    collecting.add_argument(
        "--benchmarks-only",
        action="store_true",
        help="replace only the bench rows of the engines with a report (no build needed)",
    )
    commands.add_parser("render", help="rewrite the generated blocks")
    commands.add_parser("check", help="exit 1 if a generated block is stale")
    timing = commands.add_parser("timed", help="run a command and record its duration")
    timing.add_argument("out", help="JSON file to write")
    timing.add_argument("cmd", nargs=argparse.REMAINDER, help="-- command ...")
    arguments = parser.parse_args(argv)
    if arguments.command == "collect":
        collect(
            arguments.results,
            arguments.benchmarks,
            arguments.timings,
            arguments.out,
            benchmarks_only=arguments.benchmarks_only,
        )
        return 0
    if arguments.command == "timed":
        command = arguments.cmd[1:] if arguments.cmd[:1] == ["--"] else arguments.cmd
        return timed(arguments.out, command)
    stale = render(write=arguments.command == "render")
    if arguments.command == "check" and stale:
        print("generated blocks out of date (python -m kinetic.docs render):", file=sys.stderr)
        for path in stale:
            print(f"  {path.relative_to(REPOSITORY)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
