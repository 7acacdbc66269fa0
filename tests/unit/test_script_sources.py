"""kinetic.sources: the package files a workflow script runs, read from its import
statements, agree with what Python imports when the script runs; simulation rules list
every module whose edit changes their jobs' numbers."""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

from kinetic import sources, studies
from kinetic.config import load_configs
from kinetic.sources import BOOKKEEPING, PACKAGE, front_sources, script_sources
from kinetic.trace import package_modules

SCRIPTS = Path(__file__).resolve().parents[2] / "workflow" / "scripts"
# scripts of the rules that join, analyse and plot (simulation rules list their fronts')
READING_SCRIPTS = sorted(path for path in SCRIPTS.glob("*.py") if path.stem != "simulate")


def test_imports_are_followed_through_the_package(tmp_path):
    script = tmp_path / "script.py"
    script.write_text(
        "import numpy\n"
        "from kinetic.analysis import montanero2007 as analysis\n"
        "def late():\n"
        "    from kinetic.io import write_table\n"
    )
    files = {path.relative_to(PACKAGE).as_posix() for path in script_sources(script)}
    # the module, the packages on the way, what the module imports (statistics), and an
    # import inside a function body
    assert {"__init__.py", "analysis/__init__.py", "analysis/montanero2007.py"} <= files
    assert {"analysis/statistics.py", "io.py"} <= files
    assert not any(name.startswith(("edmd/", "cloning/", "bench/")) for name in files)
    assert all(path.is_file() for path in script_sources(script))


def test_the_scripts_glue_brings_in_no_study_cost_model_or_engine(tmp_path):
    """Every reading script starts with ``kinetic.workflow_support``: its code inputs are
    the writing and logging modules only (and ``sources``, whose stamps a job marks as
    built on), so that an edit of the studies, the cost model,
    numba's cache or an engine's argument checks reruns no figure that does not import
    them (the simulation jobs' glue, which imports the studies, is
    ``kinetic.simulation_job``)."""
    script = tmp_path / "script.py"
    script.write_text("from kinetic.workflow_support import start, write_caption, write_output\n")
    files = {path.relative_to(PACKAGE).as_posix() for path in script_sources(script)}
    glue = {"__init__.py", "batches.py", "config.py", "io.py", "sources.py", "workflow_support.py"}
    assert files == glue
    simulate = script_sources(SCRIPTS / "simulate.py")
    assert PACKAGE / "studies" / "__init__.py" in simulate


def test_no_analysis_reruns_on_an_edit_of_the_studies_or_the_cost_model(tmp_path):
    """The reading scripts that analyse and plot depend on no study module and not on the
    cost model (its GPU constants are edited after each device run): a study's
    annotation-only import of the cost model and two helpers the analyses took from the
    studies made 54 of them rerun on a one-line edit of kinetic/cost.py. Only the
    job-listing report (workflow_jobs) plans the jobs. An ``if TYPE_CHECKING:`` import
    is not a dependency."""
    for script in READING_SCRIPTS:
        if script.stem == "workflow_jobs":
            continue
        files = {path.relative_to(PACKAGE).as_posix() for path in script_sources(script)}
        assert "cost.py" not in files, script.stem
        assert not {name for name in files if name.startswith("studies/")}, script.stem
    annotated = tmp_path / "annotated.py"
    annotated.write_text(
        "from typing import TYPE_CHECKING\n\nif TYPE_CHECKING:\n"
        "    from kinetic.cost import Estimate\n"
        "else:\n    from kinetic.io import read_dataset\n"
    )
    files = {path.relative_to(PACKAGE).as_posix() for path in script_sources(annotated)}
    assert "cost.py" not in files and "io.py" in files


def test_a_figure_depends_on_the_style_file_its_plotting_module_reads():
    """kinetic.plotting applies kinetic.mplstyle when imported: the style is a code input
    of every script that draws (an edit of it rerendered no figure), of no other."""
    style = PACKAGE / "plotting" / "kinetic.mplstyle"
    assert style in script_sources(SCRIPTS / "visco2008_fig01.py")
    assert style not in script_sources(SCRIPTS / "aggregate.py")


def test_a_script_without_package_imports_runs_no_package_file(tmp_path):
    script = tmp_path / "script.py"
    script.write_text("import numpy as np\nprint(np.pi)\n")
    assert script_sources(script) == []


@pytest.mark.parametrize("script", READING_SCRIPTS, ids=lambda path: path.stem)
def test_static_reading_covers_what_the_script_imports(script, repository):
    """Every file that the script's imports resolve to at run time is an input of its rule
    (not the engine fronts that a study module it imports would call: the packages load
    those on first use, and a reading script never calls them)."""
    static = {path.resolve() for path in script_sources(script)}
    imported = {
        (repository / path).resolve() for path in package_modules(script, repository, engines=False)
    }
    assert imported <= static, sorted(map(str, imported - static))


def _fronts():
    """(front, engines) of every simulation job of the shipped configs."""
    found = set()
    for name in ("ci", "config", "paper"):
        config = load_configs([SCRIPTS.parents[1] / "config" / f"{name}.yaml"])
        found |= {(job.front, job.engines) for job in studies.jobs(config)}
    return sorted(found)


FRONTS = _fronts()


def test_every_engine_and_document_has_simulation_jobs():
    assert len(FRONTS) >= 10
    engines = {engine for _, names in FRONTS for engine in names}
    assert engines == {"edmd", "event_disks", "dsmc", "cloning", "samplers"}
    jobs = studies.jobs(load_configs([SCRIPTS.parents[1] / "config" / "ci.yaml"]))
    assert {job.document for job in jobs} == set(studies.DOCUMENTS)
    assert len({job.output for job in jobs}) == len(jobs)  # one job per file


@pytest.mark.parametrize(("front", "engines"), FRONTS, ids=lambda value: str(value))
def test_a_simulation_rerun_follows_every_module_its_front_loads(front, engines):
    """Import the front's module and take the front in a fresh interpreter (names that a
    package loads on first use included): every package module loaded is an input of the
    job's rule (kinetic.sources.front_sources), unless it only names, writes or logs."""
    module, _, function = front.partition(":")
    probe = (
        f"import importlib, sys\n"
        f"getattr(importlib.import_module({module!r}), {function!r})\n"
        "print('\\n'.join(m.__file__ for n, m in list(sys.modules.items())"
        " if n.split('.')[0] == 'kinetic' and getattr(m, '__file__', None)))"
    )
    loaded = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, check=True
    ).stdout.split()
    bookkeeping = {PACKAGE / f"{module}.py" for module in BOOKKEEPING}
    loaded = {Path(file).resolve() for file in loaded} - bookkeeping
    inputs = {path.resolve() for path in front_sources(front, engines)}
    assert loaded and loaded <= inputs, sorted(map(str, loaded - inputs))


def test_the_cost_model_reruns_no_simulation():
    """The studies load ``kinetic.cost`` to plan their jobs, and the cost model imports the
    cloning engine's argument checks: neither is an input of a simulation that does not
    run them (montanero2007's DSMC had both, so that an edit of a cost constant reran its
    1144 paper.yaml jobs)."""
    cost = PACKAGE / "cost.py"
    cloning = PACKAGE / "cloning"
    for front, engines in FRONTS:
        files = front_sources(front, engines)
        assert cost not in files, front
        if "cloning" not in engines:
            assert not any(path.is_relative_to(cloning) for path in files), front


def test_a_planning_edit_reruns_no_simulation():
    """A study's planning module (``kinetic.studies.<document>``: the run plan, the
    batches, the groups) and the studies' job glue (``kinetic.studies``) are no input of a
    simulation job: montanero2007's front lived in its planning module, so that any edit
    of its planning reran all its simulations."""
    planning = {PACKAGE / "studies" / f"{name}.py" for name in (*studies.DOCUMENTS, "__init__")}
    for front, engines in FRONTS:
        assert not planning & set(front_sources(front, engines)), front


def test_each_md_engine_reruns_only_its_own_jobs():
    """visco2008's and costantini2010's MD (kinetic.edmd) and krauth2025's four disks
    (kinetic.event_disks) share no source file but the shared modules: an edit of one
    engine reruns none of the other's jobs."""
    edmd = PACKAGE / "edmd"
    event_disks = PACKAGE / "event_disks"
    for front, engines in FRONTS:
        files = front_sources(front, engines)
        if "edmd" not in engines:
            assert not any(path.is_relative_to(edmd) for path in files), front
        if "event_disks" not in engines:
            assert not any(path.is_relative_to(event_disks) for path in files), front
    engines = [names for _, names in FRONTS]
    assert ("event_disks", "samplers") in engines
    assert sum("edmd" in names for names in engines) >= 2


def test_reading_import_lines_finds_what_parsing_whole_modules_finds(monkeypatch):
    """kinetic.sources parses only the lines that start a package import; every script's
    and every front's files are those that parsing each whole module gives."""

    def read(front_or_script):
        if isinstance(front_or_script, Path):
            return script_sources(front_or_script)
        return front_sources(*front_or_script)

    cases = [*READING_SCRIPTS, *FRONTS]
    sources._imported_files.cache_clear()
    fast = [read(case) for case in cases]
    sources._imported_files.cache_clear()  # each file read again, by the whole module
    monkeypatch.setattr(
        sources,
        "_package_imports",
        lambda path: list(sources._import_statements(ast.parse(path.read_text()))),
    )
    for case, files in zip(cases, fast, strict=True):
        assert read(case) == files, case
    sources._imported_files.cache_clear()


def test_an_import_split_by_a_commented_parenthesis_is_still_read(tmp_path):
    script = tmp_path / "script.py"
    script.write_text(
        "from kinetic.analysis import (  # the analysis (and its figures)\n    montanero2007,\n)\n"
    )
    files = {path.relative_to(PACKAGE).as_posix() for path in script_sources(script)}
    assert "analysis/montanero2007.py" in files
