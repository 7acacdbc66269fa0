"""Shared fixtures: the repository root and a headless matplotlib; under pytest-xdist,
one numba cache per worker, seeded with every engine compiled once, the longest tests
first, and costly module fixtures computed by one worker for both (``once``)."""

import fcntl
import os
import pickle
import shutil
import subprocess
import sys
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

REPOSITORY = Path(__file__).resolve().parents[1]

# The GPU kernels (tests/gpu) run under numba's CUDA simulator unless NUMBA_ENABLE_CUDASIM=0
# asks for a real GPU. Set before any test module can import numba.cuda (kinetic.trace and
# the packaging tests import every module of the package), which reads it once.
os.environ.setdefault("NUMBA_ENABLE_CUDASIM", "1")

# Two processes compiling the same kernel into one numba cache can corrupt it (numba
# issue 4807). Each xdist worker (and every Snakemake build a workflow test starts from
# it, which inherits the variable) gets a cache of its own, set before numba is imported.
_CACHES = REPOSITORY / ".pytest_cache" / "numba"
_WORKER = os.environ.get("PYTEST_XDIST_WORKER")
if _WORKER:
    os.environ["NUMBA_CACHE_DIR"] = str(_CACHES / _WORKER)


def _salt_the_seeds(salt: int) -> None:
    """Every random stream of the package (``kinetic.seeds``) drawn from SeedSequence
    entropy (seed, ``salt``) instead of seed: the same tests on other random numbers.
    ``KINETIC_TEST_SEED_SALT=1 make test-fast`` shows which fixed-seed tests hold only
    for their seeds (a test whose tolerance comes from its error bars should fail about
    as rarely with any salt)."""
    import types

    import numpy

    import kinetic.seeds

    def salted(entropy=None, **options):
        return numpy.random.SeedSequence([int(entropy), salt], **options)

    class SaltedNumpy(types.ModuleType):
        random = types.SimpleNamespace(SeedSequence=salted)

        def __getattr__(self, name):
            return getattr(numpy, name)

    kinetic.seeds.np = SaltedNumpy("numpy")


if os.environ.get("KINETIC_TEST_SEED_SALT"):
    _salt_the_seeds(int(os.environ["KINETIC_TEST_SEED_SALT"]))

SEEDS = (("edmd", "event_disks", "samplers", "cloning"), ("dsmc", "experimental"))
"""Engines compiled by the controller before the workers start, in two processes (48 and 68 s
side by side on 2 cores: the DSMC engine and the experimental variants, which call its
kernels and so compile after it in one process, take the longest; the cloning engine, 9 s
alone, goes with the others) and two caches of their own, which every worker's cache then
starts from: each engine compiles once per test run instead of once per worker and once
more in the first Snakemake build of each worker. ``kinetic.jit.warm``'s markers come with
the copies, so the builds' jobs load the kernels instead of compiling them. The
experimental variants, which the tests compare with the engines, are compiled
along (numba's own stamps keep them fresh; no marker)."""


def _seed_caches() -> None:
    """Compile every engine into the seed caches (kinetic.jit.warm: nothing to do when the
    sources did not change since the last run)."""
    processes = [
        subprocess.Popen(
            [
                sys.executable,
                "-c",
                "import importlib\nfrom kinetic import jit\nfrom kinetic.sources import ENGINES\n"
                f"for engine in {engines!r}:\n"
                "    if engine in ENGINES: jit.warm(engine)\n"
                "    else: importlib.import_module(f'kinetic.{engine}').warmup()",
            ],
            env={**os.environ, "NUMBA_CACHE_DIR": str(_CACHES / f"seed-{index}")},
        )
        for index, engines in enumerate(SEEDS)
    ]
    for process in processes:
        if process.wait() != 0:
            raise RuntimeError("compiling the engines into the seed caches failed")


def pytest_configure(config):
    if _WORKER:
        for seed in sorted(_CACHES.glob("seed-*")):
            shutil.copytree(seed, os.environ["NUMBA_CACHE_DIR"], dirs_exist_ok=True)
    elif getattr(config.option, "numprocesses", None):
        _seed_caches()


LONGEST = ("test_ci_config_builds_every_target_with_provenance",)
"""The longest tests (the whole ci build), started before every other."""


def pytest_collection_modifyitems(config, items):
    """The whole ci build first, then the other end-to-end builds, then the other slow
    tests: with two workers the longest test starts at once, and the short ones fill the
    end instead of one long build running alone. Last, the tests that read a value which
    an earlier test has ``once`` compute."""

    def rank(item):
        if item.originalname in LONGEST:
            return -1
        slow = item.get_closest_marker("slow") is not None
        workflow = item.get_closest_marker("workflow") is not None
        return 0 if slow and workflow else 1 if slow else 2

    items.sort(key=rank)
    # The first test of each fixture that ``once`` computes keeps its place; the others
    # go to the end, when that value is stored. In their place they would go to the other
    # worker at the same time and wait for the lock while the first computes (31 s for
    # the elastic GPU run, about 50 worker-seconds in all).
    first, later, claimed = [], [], set()
    for item in items:
        shared = _once_fixtures(item)
        (later if shared and shared <= claimed else first).append(item)
        claimed |= shared
    items[:] = first + later


def _once_fixtures(item) -> set[tuple]:
    """The fixtures of ``item`` that request ``once`` themselves, each with the parameters
    it depends on (a parametrized fixture computes a value per parameter)."""
    definitions = getattr(getattr(item, "_fixtureinfo", None), "name2fixturedefs", {})
    params = getattr(getattr(item, "callspec", None), "params", {})

    def closure(name, seen):
        if name not in seen:
            seen.add(name)
            for fixture in definitions.get(name, ()):
                for argument in fixture.argnames:
                    closure(argument, seen)
        return seen

    keys = set()
    for name, fixtures in definitions.items():
        if any("once" in fixture.argnames for fixture in fixtures):
            needed = closure(name, set())
            keys.add((name, tuple(sorted(repr(p) for p in params.items() if p[0] in needed))))
    return keys


@pytest.fixture(scope="session")
def repository() -> Path:
    return REPOSITORY


@pytest.fixture(scope="session")
def annotate():
    """``annotate(path)`` edits the docstring that opens the module at ``path`` and appends
    a comment and a bare string: the same code, other text (what must rebuild nothing)."""

    def edit(path: Path) -> None:
        text = path.read_text()
        assert text.startswith('"""'), path
        path.write_text('"""Edited. ' + text[3:] + '\n# a comment\n"""A note."""\n')

    return edit


@pytest.fixture(scope="session")
def once(tmp_path_factory):
    """``once(key, compute)`` is ``compute()``, computed by one pytest-xdist worker and read
    by the others. The workers share a module's tests, so a costly module fixture would
    otherwise run once per worker (the simulations behind several tests, 3-11 s each).
    The value is pickled under ``key`` in the run's shared temporary directory, under a
    lock: a worker that needs it while the other computes it waits, as long as it would
    have taken to compute it itself. A failed computation stores nothing. Without xdist
    it is ``compute()``."""
    if not _WORKER:
        return lambda key, compute: compute()
    shared = tmp_path_factory.getbasetemp().parent / "computed-once"
    shared.mkdir(exist_ok=True)

    def get(key: str, compute):
        path = shared / f"{key}.pickle"
        with open(shared / f"{key}.lock", "a") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            if path.is_file():
                return pickle.loads(path.read_bytes())
            value = compute()
            partial = path.with_suffix(".partial")
            partial.write_bytes(pickle.dumps(value))
            partial.replace(path)
            return value

    return get
