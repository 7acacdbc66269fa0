"""The GPU tests run their kernels under numba's CUDA simulator, which runs every thread
of a block as a Python thread. ``kinetic.gpu`` makes it usable for every user of the
simulator: a block's shared arrays are looked up under a lock, and a block's threads are
greenlets that take turns between barriers instead of operating-system threads polled
for the GIL, and a device function's module is pointed at the launch's fake ``cuda``
once per launch instead of at every call (``tests/gpu/test_simulator.py``; the
directory's tests: 397 CPU-s with numba's threads, their polls paused, 96 CPU-s now, on
two workers)."""

import pytest

from kinetic import backends


@pytest.fixture
def assert_cpu_layout():
    """Check that a ``cuda`` dataset has its CPU twin's layout: the same variables and
    coordinates with the same dims, shapes, dtypes and units, the same coordinate values,
    the same attributes but for backend, device, revision and the collision groups, and
    the device recorded."""

    def check(cuda, cpu):
        import numpy as np

        assert set(cuda.data_vars) == set(cpu.data_vars)
        assert set(cuda.coords) == set(cpu.coords)
        for name in list(cpu.data_vars) + list(cpu.coords):
            assert cuda[name].dims == cpu[name].dims, name
            assert cuda[name].shape == cpu[name].shape, name
            assert cuda[name].dtype == cpu[name].dtype, name
            assert cuda[name].attrs["units"] == cpu[name].attrs["units"], name
        for name in cpu.coords:
            np.testing.assert_array_equal(cuda[name].values, cpu[name].values)
        assert "per realization" in cuda.cpu_seconds.attrs["long_name"]
        assert cuda.attrs["backend"] == "cuda" and cpu.attrs["backend"] == "cpu"
        assert cuda.attrs["device"] == backends.require("cuda")
        assert cpu.attrs["device"] == "cpu"
        for key, value in cpu.attrs.items():
            if key not in ("backend", "device", "git_revision", "collision_groups"):
                assert cuda.attrs[key] == value, key

    return check
