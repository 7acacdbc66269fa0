"""numba's on-disk cache must not run stale helpers, nor recompile for nothing.

numba stamps a cached function with the source of the file that defines it. The
population draw of the cloning engine (``kinetic.cloning.kernels.draw_population``)
calls ``kinetic.rng.xoshiro_normal_pair`` from another file; after an edit of that file alone,
the next process must run the edited helper, not the machine code cached before. An edit
of a file the kernel does not depend on (the plotting helpers), and an edit of the
comments and docstrings of one it does depend on, keep the cache."""

import os
import shutil
import subprocess
import sys

import pytest

from kinetic.sources import ENGINES, PACKAGE, SHARED, engine_sources, kernel_sources

PROBE = """
import numpy as np
from kinetic.cloning.kernels import draw_population
from kinetic.rng import stream_states
velocity = np.zeros((2, 4))
draw_population(velocity, np.zeros(4), stream_states(1, 1)[0])
print(repr(float(velocity.sum())))
"""

#: a helper that draws nothing: every component of the population becomes 0.5
EDIT = (
    "\n\n@kernel\ndef xoshiro_normal_pair(s0, s1, s2, s3):\n    return 0.5, 0.5, s0, s1, s2, s3\n"
)


#: run first in the probe of a read-only installation: no ``__pycache__`` can be written
READ_ONLY_TREE = """
from numba.core import caching
_ensure = caching._CacheLocator.ensure_cache_path
def _refuse_in_tree(self):
    if "__pycache__" in self.get_cache_path():
        raise OSError("read-only installation")
    return _ensure(self)
caching._CacheLocator.ensure_cache_path = _refuse_in_tree
"""


def _run(package_root, cache, read_only):
    environment = {key: value for key, value in os.environ.items() if key != "NUMBA_CACHE_DIR"}
    environment |= {"PYTHONPATH": str(package_root), "NUMBA_DEBUG_CACHE": "1"}
    if read_only:  # numba falls back to the user's cache directory
        environment["XDG_CACHE_HOME"] = str(cache)
    else:
        environment["NUMBA_CACHE_DIR"] = str(cache)
    result = subprocess.run(
        [sys.executable, "-c", (READ_ONLY_TREE if read_only else "") + PROBE],
        env=environment,
        capture_output=True,
        text=True,
        check=True,
    )
    lines = result.stdout.strip().splitlines()
    loaded = any("data loaded" in line and "draw_population" in line for line in lines)
    return float(lines[-1]), loaded


@pytest.mark.slow
@pytest.mark.parametrize("read_only", [False, True], ids=["NUMBA_CACHE_DIR", "read-only tree"])
def test_an_edited_helper_in_another_file_invalidates_the_cached_kernel(
    repository, tmp_path, read_only, annotate
):
    shutil.copytree(
        repository / "src" / "kinetic",
        tmp_path / "kinetic",
        ignore=shutil.ignore_patterns("__pycache__"),
    )
    cache = tmp_path / "cache"

    drawn, loaded = _run(tmp_path, cache, read_only)
    assert not loaded  # compiled: the cache was empty
    assert drawn != 4.0
    assert any(cache.rglob("*draw_population*.nbi")), "the kernel was not cached there"
    assert not any((tmp_path / "kinetic").rglob("*.nbi"))
    again, loaded = _run(tmp_path, cache, read_only)
    assert loaded, "an unchanged package must load its kernels from the cache"
    assert again == drawn

    with open(tmp_path / "kinetic" / "plotting" / "__init__.py", "a") as source:
        source.write("\n# an edit outside the engines' sources\n")
    unrelated, loaded = _run(tmp_path, cache, read_only)
    assert loaded, "an edit the kernel does not depend on recompiled it"
    assert unrelated == drawn

    annotate(tmp_path / "kinetic" / "rng.py")
    annotated, loaded = _run(tmp_path, cache, read_only)
    assert loaded, "an edit of the helper's comments and docstrings recompiled the kernel"
    assert annotated == drawn

    with open(tmp_path / "kinetic" / "rng.py", "a") as source:
        source.write(EDIT)
    edited, loaded = _run(tmp_path, cache, read_only)
    assert not loaded, "the kernel was loaded from a cache compiled before the edit"
    assert edited == 8 * 0.5


def test_kernel_sources_cover_the_engine_and_the_shared_modules():
    shared = {PACKAGE / f"{module}.py" for module in SHARED}
    for engine in ENGINES:
        files = set(engine_sources(engine))
        assert shared <= files
        assert PACKAGE / engine / "__init__.py" in files
        assert not any(path.is_relative_to(PACKAGE / "plotting") for path in files)
        assert set(kernel_sources(PACKAGE / engine / "kernels.py")) == files
    assert set(kernel_sources(PACKAGE / "rng.py")) == shared
    # compiled code outside the engines (the benchmarks) depends on everything
    assert set(kernel_sources(PACKAGE / "bench" / "edmd.py")) == set(PACKAGE.rglob("*.py"))
    with pytest.raises(ValueError, match="unknown engine"):
        engine_sources("plotting")


WARM = """
import sys
from kinetic import jit
seconds = jit.warm("samplers", *sys.argv[1:])
print("warm", seconds, "imported" if "kinetic.samplers" in sys.modules else "skipped")
"""


def _warm_processes(package_root, cache, count, *front):
    """``count`` processes warming the samplers' cache at once (of ``front`` alone, if
    given): their numba cache lines."""
    environment = {**os.environ, "PYTHONPATH": str(package_root), "NUMBA_CACHE_DIR": str(cache)}
    environment["NUMBA_DEBUG_CACHE"] = "1"
    processes = [
        subprocess.Popen(
            [sys.executable, "-c", WARM, *front],
            env=environment,
            stdout=subprocess.PIPE,
            text=True,
        )
        for _ in range(count)
    ]
    outputs = [process.communicate()[0] for process in processes]
    assert all(process.returncode == 0 for process in processes)
    return outputs


@pytest.mark.slow
def test_parallel_jobs_compile_a_front_once_and_an_edit_warms_again(repository, tmp_path, annotate):
    """kinetic.jit.warm: of jobs of one front starting together, one compiles that front's
    kernels (and no other's) into the cache while the others wait for it; a job of
    another front compiles the rest; with the cache filled for these sources, jobs do
    nothing, also after an edit of the comments and docstrings of a file the kernels
    depend on; after an edit of its code, the next job compiles again."""
    shutil.copytree(
        repository / "src" / "kinetic",
        tmp_path / "kinetic",
        ignore=shutil.ignore_patterns("__pycache__"),
    )
    cache = tmp_path / "cache"
    first = _warm_processes(tmp_path, cache, 3, "sample_ring")
    saving = [output for output in first if "data saved" in output]
    assert len(saving) == 1, "exactly one job compiles into the cache"
    assert "ring_markov" in saving[0] and "disks" not in saving[0], saving[0]
    # the others waited for the lock, then found the marker of the finished warm-up
    assert all("skipped" in output for output in first if output not in saving)

    (whole,) = _warm_processes(tmp_path, cache, 1)  # every kernel: the ring's are loaded
    saved = "".join(line for line in whole.splitlines() if "data saved" in line)
    assert "direct_disks" in saved and "ring_markov" not in saved, saved
    assert len(list(cache.rglob("kinetic-warm-samplers-*.done"))) == 1
    for front in ((), ("sample_ring",), ("sample_disks",)):
        (again,) = _warm_processes(tmp_path, cache, 1, *front)
        assert "warm 0.0 skipped" in again and "data" not in again  # the marker: nothing to do

    annotate(tmp_path / "kinetic" / "rng.py")  # the same code: still nothing to do
    (annotated,) = _warm_processes(tmp_path, cache, 1)
    assert "warm 0.0 skipped" in annotated and "data" not in annotated

    with open(tmp_path / "kinetic" / "rng.py", "a") as source:
        source.write("\n_EDITED = True  # an edit of a helper every engine inlines\n")
    (edited,) = _warm_processes(tmp_path, cache, 1)
    assert "data saved" in edited, "the kernels were not compiled again after the edit"
    assert len(list(cache.rglob("kinetic-warm-samplers-*.done"))) == 1  # the old marker went
