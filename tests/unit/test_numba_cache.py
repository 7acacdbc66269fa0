"""numba's on-disk cache must not run stale helpers.

numba stamps a cached function with the source of the file that defines it. The
population draw of the cloning engine (``kinetic.cloning.kernels.draw_population``)
inlines ``kinetic.rng.normal_pair`` from another file; after an edit of that file alone,
the next process must run the edited helper, not the machine code cached before."""

import os
import shutil
import subprocess
import sys

import pytest

PROBE = """
import numpy as np
from kinetic.cloning.kernels import draw_population
from kinetic.rng import stream_states
velocity = np.zeros((2, 4))
draw_population(velocity, np.zeros(4), stream_states(1, 1)[0])
print(repr(float(velocity.sum())))
"""

#: a helper that draws nothing: every component of the population becomes 0.5
EDIT = "\n\n@inline\ndef normal_pair(state):\n    return 0.5, 0.5\n"


def _run(package_root, cache):
    environment = {
        **os.environ,
        "PYTHONPATH": str(package_root),
        "NUMBA_CACHE_DIR": str(cache),
        "NUMBA_DEBUG_CACHE": "1",
    }
    result = subprocess.run(
        [sys.executable, "-c", PROBE],
        env=environment,
        capture_output=True,
        text=True,
        check=True,
    )
    lines = result.stdout.strip().splitlines()
    loaded = any("data loaded" in line and "draw_population" in line for line in lines)
    return float(lines[-1]), loaded


@pytest.mark.slow
def test_an_edited_helper_in_another_file_invalidates_the_cached_kernel(repository, tmp_path):
    shutil.copytree(
        repository / "src" / "kinetic",
        tmp_path / "kinetic",
        ignore=shutil.ignore_patterns("__pycache__"),
    )
    cache = tmp_path / "cache"

    drawn, loaded = _run(tmp_path, cache)
    assert not loaded  # compiled: the cache was empty
    assert drawn != 4.0
    again, loaded = _run(tmp_path, cache)
    assert loaded, "an unchanged package must load its kernels from the cache"
    assert again == drawn

    with open(tmp_path / "kinetic" / "rng.py", "a") as source:
        source.write(EDIT)
    edited, loaded = _run(tmp_path, cache)
    assert not loaded, "the kernel was loaded from a cache compiled before the edit"
    assert edited == 8 * 0.5
