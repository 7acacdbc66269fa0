"""Reruns that can be trusted: after an edit of the code of any file a result depends on,
or of a config value, one invocation rebuilds exactly the affected outputs and leaves
nothing stale, while an edit of comments and docstrings rebuilds nothing; each config
builds under its own results root.

The edits are made on a copy of the tree (its own package on PYTHONPATH, its own numba
cache), for two figures of the ``ci`` config that share no job: montanero2007 Fig. 5
(DSMC runs, their joins, the figure) and krauth2025 Fig. 4.13 (a sampler run, the exact
curve, the figure).
"""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path, PurePosixPath

import pytest
import xarray as xr
import yaml
from numba.core import caching

REPOSITORY = Path(__file__).resolve().parents[2]
ROOT = "results/ci"
TARGETS = [f"{ROOT}/montanero2007/fig05.pdf", f"{ROOT}/krauth2025/fig04_13.pdf"]

STAGES = {
    "montanero2007 simulations": "montanero2007/dsmc/*/batch*.nc",
    "montanero2007 joins": "montanero2007/dsmc/*.nc",
    "montanero2007 figure": "montanero2007/fig05.*",
    "krauth2025 simulation": "krauth2025/pins/ring.nc",
    "krauth2025 theory": "krauth2025/theory/ring.nc",
    "krauth2025 figure": "krauth2025/fig04_13.*",
}
"""Every output of the two targets, by the stage (rule) that writes it."""

MONTANERO2007 = {"montanero2007 simulations", "montanero2007 joins", "montanero2007 figure"}

pytestmark = [pytest.mark.workflow, pytest.mark.slow]


def _snakemake(tree, *args, config="config/ci.yaml"):
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(tree / "Snakefile")]
    result = subprocess.run(
        [*command, "--directory", str(tree), *args, "--configfile", str(tree / config)],
        capture_output=True,
        text=True,
        timeout=900,
        env={
            **os.environ,
            "MPLBACKEND": "Agg",
            "PYTHONPATH": str(tree / "src"),
            "NUMBA_CACHE_DIR": str(tree / "numba-cache"),
        },
    )
    assert result.returncode == 0, result.stdout + result.stderr
    return result.stdout + result.stderr


def _outputs(tree):
    """{path under the ci root: modification time} of every result file (logs aside)."""
    root = tree / ROOT
    files = (path for path in root.rglob("*") if path.is_file() and path.name[0] != ".")
    return {
        path.relative_to(root).as_posix(): path.stat().st_mtime_ns
        for path in files
        if path.relative_to(root).parts[0] != "logs"
    }


def _stage(path):
    path = PurePosixPath(path)
    matches = [
        name
        for name, pattern in STAGES.items()
        if path.match(pattern) and len(path.parts) == len(PurePosixPath(pattern).parts)
    ]
    assert len(matches) == 1, f"{path} belongs to {matches}"
    return matches[0]


def _seed_numba_cache(tree):
    """Start the tree's numba cache from the kernels this worker's cache holds (if it has
    one): numba names a cache directory after the absolute path of the sources' directory,
    and ``kinetic.jit`` stamps the entries and its warm-up markers with the sources'
    contents, which the copy shares. The directories, renamed for the tree's paths, are
    thus hits until an edit changes a stamp, as if the tree had compiled them itself (its
    first build then loads instead of compiling for about 15 s)."""
    worker = os.environ.get("NUMBA_CACHE_DIR")
    if not worker:
        return
    subpath = caching.UserProvidedCacheLocator.get_suitable_cache_subpath
    for package in sorted((REPOSITORY / "src" / "kinetic").rglob("__init__.py")):
        source = Path(worker) / subpath(str(package))
        if source.is_dir():
            copy = tree / "numba-cache" / subpath(str(tree / package.relative_to(REPOSITORY)))
            shutil.copytree(source, copy)


@pytest.fixture
def tree(tmp_path):
    """A copy of the workflow and the package with both targets built."""
    tree = tmp_path
    for name in ("Snakefile", "profiles", "workflow", "config", "src"):
        if (REPOSITORY / name).is_dir():
            ignore = shutil.ignore_patterns("__pycache__", "*.egg-info")
            shutil.copytree(REPOSITORY / name, tree / name, ignore=ignore)
        else:
            shutil.copy(REPOSITORY / name, tree / name)
    _seed_numba_cache(tree)
    _snakemake(tree, *TARGETS, "--cores", "2")
    assert {_stage(path) for path in _outputs(tree)} == set(STAGES)
    return tree


def _rebuilt_after(tree, edit):
    """Apply ``edit``, invoke Snakemake once, and return the stages whose outputs were
    rebuilt."""
    before = _outputs(tree)
    edit()
    _snakemake(tree, *TARGETS, "--cores", "2")
    after = _outputs(tree)
    assert set(after) == set(before)
    rebuilt = {_stage(path) for path in after if after[path] != before[path]}
    # every output of a rebuilt stage is rebuilt, not some of them
    for path in after:
        if _stage(path) in rebuilt:
            assert after[path] != before[path], f"{path} kept its old version"
    return rebuilt


def _append_statement(tree, module):
    def edit():
        with open(tree / "src" / "kinetic" / module, "a") as source:
            source.write("\n_EDITED = True\n")

    return edit


def _more_sweeps(tree):
    def edit():
        path = tree / "config" / "ci.yaml"
        config = yaml.safe_load(path.read_text())
        config["krauth2025"]["ring"]["sweeps"] += 100
        path.write_text(yaml.safe_dump(config, sort_keys=False))

    return edit


KRAUTH2025 = {"krauth2025 simulation", "krauth2025 figure"}

EDITS = [
    # an engine kernel: every simulation of that engine and what is drawn from it
    ("samplers/kernels.py", KRAUTH2025),
    # a helper every engine's kernels inline: every simulation
    ("rng.py", MONTANERO2007 | KRAUTH2025),
    # the module of the study's job front (a run's settings -> the engine's arguments)
    ("studies/montanero2007_front.py", MONTANERO2007),
    # the study module that turns the config into runs: no job's numbers (the job list
    # alone, which no tracked stage is)
    ("studies/montanero2007.py", set()),
    # analysis that no simulation imports: the figure alone
    ("analysis/montanero2007.py", {"montanero2007 figure"}),
    # the plotting helpers every figure uses: the figures alone
    ("plotting/__init__.py", {"montanero2007 figure", "krauth2025 figure"}),
]


def test_one_invocation_after_an_edit_rebuilds_exactly_what_depends_on_it(tree, annotate):
    """The edits one after another on one tree (one test, so that one worker builds it).
    A stage that one invocation left stale would be rebuilt by the next and show up in
    the next edit's rebuilt set; after the last, a dry run must plan nothing."""

    # comments and docstrings, of an engine kernel, of what every kernel inlines and of the
    # scripts every simulation and every join run (Snakemake's own check of a script's
    # time is off: profiles/default), and the code of an engine variant no document runs:
    # nothing (one invocation for the edits that rebuild nothing)
    def comments():
        for module in ("samplers/kernels.py", "rng.py"):
            annotate(tree / "src" / "kinetic" / module)
        for script in ("simulate.py", "aggregate.py"):
            annotate(tree / "workflow" / "scripts" / script)

    variant = _append_statement(tree, "experimental/speed_classes.py")
    assert _rebuilt_after(tree, lambda: (comments(), variant())) == set()
    # an edit looked at with a dry run, then reverted: nothing (no output was made from it)
    rng = tree / "src" / "kinetic" / "rng.py"
    original = rng.read_text()
    _append_statement(tree, "rng.py")()
    assert "montanero2007_simulate" in _snakemake(tree, *TARGETS, "--dry-run")
    rng.write_text(original)
    assert _rebuilt_after(tree, lambda: None) == set()
    for module, expected in EDITS:
        rebuilt = _rebuilt_after(tree, _append_statement(tree, module))
        assert rebuilt == expected, f"after an edit of {module}"
    # a config value: the jobs whose parameters it changes, and what is drawn from them
    assert _rebuilt_after(tree, _more_sweeps(tree)) == KRAUTH2025
    dry = _snakemake(tree, *TARGETS, "--dry-run")
    assert "Nothing to be done" in dry, dry


def test_two_configs_keep_their_own_results(tmp_path):
    """The same job under two configs with different parameters: each config writes under
    its own root, and neither build reruns or deletes the other's file."""
    ci = yaml.safe_load((REPOSITORY / "config" / "ci.yaml").read_text())
    other = {**ci, "results": "results/other"}
    other["krauth2025"] = {
        **ci["krauth2025"],
        "ring": {**ci["krauth2025"]["ring"], "sweeps": ci["krauth2025"]["ring"]["sweeps"] + 100},
    }
    configs = {"ci": ci, "other": other}
    for name, settings in configs.items():
        (tmp_path / f"{name}.yaml").write_text(yaml.safe_dump(settings, sort_keys=False))
    job = "krauth2025/pins/ring.nc"

    def build(name, *args):
        target = f"{configs[name]['results']}/{job}"
        command = [sys.executable, "-m", "snakemake", "--snakefile", str(REPOSITORY / "Snakefile")]
        config = str(tmp_path / f"{name}.yaml")
        result = subprocess.run(
            [*command, "--directory", str(tmp_path), target, *args, "--configfile", config],
            capture_output=True,
            text=True,
            timeout=600,
            env={**os.environ, "MPLBACKEND": "Agg"},
        )
        assert result.returncode == 0, result.stdout + result.stderr
        return result.stdout + result.stderr

    for name in configs:
        build(name, "--cores", "1")
    for name in configs:
        assert "Nothing to be done" in build(name, "--dry-run")
    sweeps = {}
    for name, settings in configs.items():
        with xr.open_dataset(tmp_path / settings["results"] / job) as dataset:
            sweeps[name] = json.loads(dataset.attrs["parameters_json"])["sweeps"]
        assert sweeps[name] == settings["krauth2025"]["ring"]["sweeps"]
    assert sweeps["ci"] != sweeps["other"]
