"""Shared fixtures: the repository root and a headless matplotlib; under pytest-xdist,
one numba cache per worker and the longest tests first."""

import os
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

REPOSITORY = Path(__file__).resolve().parents[1]

# Two processes compiling the same kernel into one numba cache can corrupt it (numba
# issue 4807). Each xdist worker (and every Snakemake build a workflow test starts from
# it, which inherits the variable) gets a cache of its own, set before numba is imported.
_WORKER = os.environ.get("PYTEST_XDIST_WORKER")
if _WORKER:
    os.environ["NUMBA_CACHE_DIR"] = str(REPOSITORY / ".pytest_cache" / "numba" / _WORKER)


LONGEST = ("test_ci_config_builds_every_target_with_provenance",)
"""The longest tests (the whole ci build), started before every other."""


def pytest_collection_modifyitems(config, items):
    """The whole ci build first, then the other end-to-end builds, then the other slow
    tests: with two workers the longest test starts at once, and the short ones fill the
    end instead of one long build running alone."""

    def rank(item):
        if item.originalname in LONGEST:
            return -1
        slow = item.get_closest_marker("slow") is not None
        workflow = item.get_closest_marker("workflow") is not None
        return 0 if slow and workflow else 1 if slow else 2

    items.sort(key=rank)


@pytest.fixture(scope="session")
def repository() -> Path:
    return REPOSITORY
