"""``python -m kinetic.bench cuda``'s memory-bound section runs (under numba's CUDA
simulator here: tiny sizes, no meaningful times), so that a GPU session's few minutes are
not spent finding a broken section."""

import os

os.environ.setdefault("NUMBA_ENABLE_CUDASIM", "1")

import sys

import pytest

pytest.importorskip("numba.cuda")

pytestmark = [
    pytest.mark.cuda,
    pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning"),
    pytest.mark.filterwarnings("ignore::numba.core.errors.NumbaPerformanceWarning"),
]


def test_memory_bound_times_every_pass_of_the_step():
    from kinetic.bench import cuda as bench

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-4)  # the simulator's barriers poll their threads
    try:
        report = bench._memory_bound(256, 2, 1)
    finally:
        sys.setswitchinterval(interval)
    assert set(report["passes"]) == {"permute", "collide", "force", "finish"}
    particles = 256 * 2
    assert report["copy_bytes_per_second"] == pytest.approx(48 * particles / report["copy_seconds"])
    for name, timed in report["passes"].items():
        assert timed["seconds"] > 0
        assert timed["bytes_per_particle"] == bench.PASS_BYTES.get(name, 0)
    step = report["step"]
    assert step["bound_seconds"] == pytest.approx(120 * particles / report["copy_bytes_per_second"])
    assert step["fraction_of_bound"] == pytest.approx(step["bound_seconds"] / step["seconds"])
