"""kinetic.sources.script_sources: the package files a workflow script runs, read from its
import statements, agree with what Python imports when the script runs."""

from pathlib import Path

import pytest

from kinetic.sources import PACKAGE, script_sources
from kinetic.trace import package_modules

SCRIPTS = Path(__file__).resolve().parents[2] / "workflow" / "scripts"
# scripts of the rules that join, analyse and plot (simulation rules list engine_sources)
READING_SCRIPTS = sorted(
    path
    for path in SCRIPTS.glob("*.py")
    if "_simulate" not in path.stem and path.stem != "warm_numba"
)


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
