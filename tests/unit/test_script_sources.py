"""kinetic.sources: the package files a workflow script runs, read from its import
statements, agree with what Python imports when the script runs; simulation rules list
every module whose edit changes their numbers."""

import ast
import re
import subprocess
import sys
from pathlib import Path

import pytest

from kinetic.sources import BOOKKEEPING, PACKAGE, script_sources, simulation_sources
from kinetic.trace import package_modules

SCRIPTS = Path(__file__).resolve().parents[2] / "workflow" / "scripts"
# scripts of the rules that join, analyse and plot (simulation rules list engine_sources)
READING_SCRIPTS = sorted(path for path in SCRIPTS.glob("*.py") if "_simulate" not in path.stem)


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


def test_a_script_without_package_imports_runs_no_package_file(tmp_path):
    script = tmp_path / "script.py"
    script.write_text("import numpy as np\nprint(np.pi)\n")
    assert script_sources(script) == []


@pytest.mark.parametrize("script", READING_SCRIPTS, ids=lambda path: path.stem)
def test_static_reading_covers_what_the_script_imports(script, repository):
    """Every file that the script's imports resolve to at run time is an input of its rule."""
    static = {path.resolve() for path in script_sources(script)}
    imported = {(repository / path).resolve() for path in package_modules(script, repository)}
    assert imported <= static, sorted(map(str, imported - static))


def _simulation_rules():
    """(script, engines) of every simulation_code(...) call in the rule files."""
    calls = set()
    for path in (SCRIPTS.parent / "rules").rglob("*.smk"):
        for args in re.findall(r"simulation_code\(([^)]*)\)", path.read_text()):
            names = re.findall(r'"(\w+)"', args)
            if names:  # not the helper's own definition
                calls.add((names[0], tuple(names[1:])))
    return sorted(calls)


SIMULATIONS = _simulation_rules()


def test_every_simulation_rule_names_its_script_and_engines():
    assert len(SIMULATIONS) >= 10
    for name, engines in SIMULATIONS:
        assert (SCRIPTS / f"{name}.py").is_file() and engines


@pytest.mark.parametrize(
    ("name", "engines"),
    SIMULATIONS,
    ids=lambda value: "-".join(value) if isinstance(value, tuple) else value,
)
def test_a_simulation_rerun_follows_every_module_its_imports_load(name, engines):
    """Run the script's import statements in a fresh interpreter (fronts that a package
    loads on first use included): every package module they load is an input of the
    rule, unless it only names, writes or logs results."""
    script = SCRIPTS / f"{name}.py"
    imports = [
        ast.unparse(node)
        for node in ast.parse(script.read_text()).body
        if isinstance(node, (ast.Import, ast.ImportFrom))
    ]
    probe = "\n".join(
        [
            *imports,
            "import sys",
            "print('\\n'.join(m.__file__ for n, m in list(sys.modules.items())"
            " if n.split('.')[0] == 'kinetic' and getattr(m, '__file__', None)))",
        ]
    )
    loaded = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, check=True
    ).stdout.split()
    bookkeeping = {PACKAGE / f"{module}.py" for module in BOOKKEEPING}
    loaded = {Path(file).resolve() for file in loaded} - bookkeeping
    inputs = {path.resolve() for path in simulation_sources(script, engines)}
    assert loaded and loaded <= inputs, sorted(map(str, loaded - inputs))
