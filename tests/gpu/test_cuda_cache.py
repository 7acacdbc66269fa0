"""numba-cuda's on-disk cache of the package's GPU kernels (``kinetic.gpu.kernel``) is keyed
on every file the kernels depend on, as the CPU kernels' cache is (``kinetic.jit``): the
engine's package and the shared modules, and ``kinetic/gpu.py``, whose reductions and
scans every kernel inlines. numba-cuda's own locator looks at the kernel's file alone, so
an edit of ``kinetic/cloning/kernels.py`` (the collision rules the GPU kernels compile as
device twins) would otherwise leave the old machine code in use.

Runs without a GPU: it checks the locator numba-cuda picks for a kernel's function, not a
compilation (the simulator compiles nothing; the cache itself is exercised on a GPU by
``python -m kinetic.bench cuda``)."""

import inspect
import os

os.environ.setdefault("NUMBA_ENABLE_CUDASIM", "1")

import pytest

pytest.importorskip("numba.cuda")

from kinetic import gpu, jit
from kinetic.sources import PACKAGE

pytestmark = pytest.mark.cuda


def _locator(function):
    from numba.cuda.core import caching

    path = inspect.getfile(function)
    for locator_class in caching.CacheImpl._locator_classes:
        locator = locator_class.from_function(function, path)
        if locator is not None:
            return locator
    raise AssertionError(f"no cache locator for {path}")


def test_gpu_kernels_are_cached_under_a_stamp_of_all_their_sources():
    from numba.cuda.core import caching

    assert gpu._install_cache_locators()
    before = list(caching.CacheImpl._locator_classes)
    assert gpu._install_cache_locators()  # installing twice changes nothing
    assert caching.CacheImpl._locator_classes == before
    from kinetic.cloning import gpu as cloning_gpu
    from kinetic.dsmc import inhomogeneous_gpu

    for module, engine in ((cloning_gpu, "cloning"), (inhomogeneous_gpu, "dsmc")):
        function = module._seed.py_func if hasattr(module._seed, "py_func") else module._seed.fn
        locator = _locator(function)
        assert type(locator).__name__.startswith("Package")
        stamp = locator.get_source_stamp()
        files = (PACKAGE / engine / "__init__.py", (PACKAGE / "gpu.py",))
        assert stamp == jit.source_stamp(*files)
        assert stamp != jit.source_stamp(PACKAGE / engine / "__init__.py")  # gpu.py counts


def test_functions_outside_the_package_keep_numba_cudas_own_locator(tmp_path):
    script = tmp_path / "outside.py"
    script.write_text("def f(x):\n    return x\n")
    namespace: dict = {}
    exec(compile(script.read_text(), str(script), "exec"), namespace)
    assert gpu._install_cache_locators()
    assert not type(_locator(namespace["f"])).__name__.startswith("Package")
