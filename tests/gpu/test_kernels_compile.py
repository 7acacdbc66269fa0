"""The CUDA kernels of kinetic.dsmc.gpu, kinetic.dsmc.inhomogeneous_gpu, kinetic.cloning.gpu
and kinetic.gpu compile for a Hopper GPU
(sm_90), checked without a GPU: ``numba.cuda.compile_ptx`` of every kernel with the
argument types the engine launches it with. The simulator (``NUMBA_ENABLE_CUDASIM=1``)
runs the kernels as Python and checks none of the typing, so this runs only outside it,
where the CUDA toolkit (NVVM, NVRTC) is installed. Where nvJitLink is installed too (the
``numba-cuda[cu13]`` wheels), each kernel's PTX is also linked to sm_90 machine code, its
registers a thread printed (``-s``) and its spills held to none, and a kernel that
syncs its grid is marked for a cooperative launch (``COOPERATIVE``), e.g.::

    NUMBA_ENABLE_CUDASIM=0 python -m pytest -o addopts="" tests/gpu/test_kernels_compile.py

environment-pip.txt pins those wheels, so every install has them, and the test suite, which
runs under the simulator, runs this file in subprocesses outside it
(test_kernels_compile_without_a_gpu.py).
"""

import re

import pytest

pytest.importorskip("numba.cuda")

from kinetic import backends

pytestmark = [
    pytest.mark.cuda,
    pytest.mark.skipif(backends.simulated(), reason="the CUDA simulator compiles nothing"),
]


def _signatures():
    from numba import float64, int64, types, uint64

    f3, f1 = float64[:, :, ::1], float64[::1]
    i2 = int64[:, ::1]
    u3, u2 = uint64[:, :, ::1], uint64[:, ::1]
    a2, a1 = types.Array(float64, 2, "A"), types.Array(float64, 1, "A")
    observers = types.Tuple((f1, float64, i2, float64, a1))
    plan, order, run = float64[:, ::1], int64[::1], types.Tuple((int64, float64))
    cloning = {
        "_seed": (u3, f3, u2),
        "_advance": (f3, f3, u3, i2, i2, f3, run, plan, order, int64),
        "_weigh": (i2, i2, i2, i2, f3, u2, a2, int64[::1], plan, order, int64),
        "_select": (f3, f3, i2, i2, i2, u2, f3, observers, plan, order, int64),
        "_fold_snapshot": (f3, a2, plan),
        "_settle": (f3, f3, plan),
        "_resident": (
            f3,
            f3,
            u3,
            i2,
            u2,
            a2,
            types.Tuple((f1, float64, i2, float64)),
            types.Tuple((int64, float64)),
            float64[:, ::1],
        ),
    }
    return (
        {("cloning", name): signature for name, signature in cloning.items()}
        | {("dsmc", name): signature for name, signature in _dsmc_signatures().items()}
        | {
            ("dsmc_inhomogeneous", name): signature
            for name, signature in _inhomogeneous_signatures().items()
        }
        | {("gpu", "stream_copy"): (f1, f1)}
    )


MODULES = {
    "cloning": "kinetic.cloning.gpu",
    "dsmc": "kinetic.dsmc.gpu",
    "dsmc_inhomogeneous": "kinetic.dsmc.inhomogeneous_gpu",
    "gpu": "kinetic.gpu",
}


def _dsmc_signatures():
    from numba import boolean, float64, int64, uint64
    from numba.core.types import Tuple, UniTuple

    f3, f2, f1 = float64[:, :, ::1], float64[:, ::1], float64[::1]
    i3, i2, i1 = int64[:, :, ::1], int64[:, ::1], int64[::1]
    u3, u2 = uint64[:, :, ::1], uint64[:, ::1]
    over_particles = {
        "_collide_sparse": (u3, f3, f3, i3, f1, i1, u2, i1, f2, boolean),
        "_force": (f3, i1, float64, int64, f2, boolean, i1, Tuple((f2, f1, i1, boolean, u2))),
        "_observe": (f3, UniTuple(i2, 3), f1, i1, boolean, f2, boolean, boolean),
    }
    # each a copy for each storage (``_BY_PARTICLE``), both given a C-layout store
    return {
        "_seed_groups": (u2, u3, u2),
        "_store_by_particle": (f3, f3),
        "_fold_moments": (f3, int64, f2, float64),
        "_sum_accepted": (i3, i2),
        "_fold_lanes": (i2, i1),
    } | {
        f"{name}[{storage}]": (f3, *rest)
        for name, rest in over_particles.items()
        for storage in ("components", "particles")
    }


def _inhomogeneous_signatures():
    from numba import float64, int64, types, uint64

    f3, f2 = float64[:, :, ::1], float64[:, ::1]
    i3, i2 = int64[:, :, ::1], int64[:, ::1]
    u3, u2 = uint64[:, :, ::1], uint64[:, ::1]
    buffers = types.Tuple((f3, f3, i3))
    cells = types.Tuple((f3, f2, u3, i3, f2))
    stream = types.Tuple((float64, float64, int64))
    step = types.Tuple((int64, float64, float64, float64))
    plan = types.UniTuple(int64, 2)
    work = types.Tuple((i2, i2, i2, i2))
    return {
        "_seed": (u2, u3),
        "_centre": (f3, f2, i2, float64),
        "_stream": (f3, f3, i2, i2, f2, f2, stream),
        "_scan": (i2, i2),
        "_scatter": (i2, i2, i2),
        "_collide": (buffers, buffers, i2, i2, cells, f2, step),
        "_advance_together": (buffers, buffers, work, cells, f2, f2, stream, step, float64, plan),
        "_observe": (f3, f3, f3, float64),
        "_finish": (f3, int64, f2, f2, int64, f3, f2, int64),
    }


COOPERATIVE = {("dsmc_inhomogeneous", "_advance_together")}
"""Kernels that synchronise their whole grid (``cuda.cg.this_grid().sync()``, inside a
device function NVVM inlines): numba-cuda marks a kernel for a cooperative launch only
where the compiled code says it syncs the grid, and a grid sync launched otherwise is
undefined behaviour on the GPU, not an error here."""


def _needs_cooperative_launch(kernel, signature) -> bool:
    """Whether numba-cuda would launch ``kernel`` cooperatively (its code library's
    ``use_cooperative``, which device functions pass on to the kernels that call them)."""
    from numba.core import types
    from numba.cuda.compiler import compile_cuda

    compiled = compile_cuda(
        kernel.py_func, types.void, signature, nvvm_options={"opt": 3}, cc=(9, 0)
    )
    return compiled.library.use_cooperative


@pytest.fixture(scope="module")
def compile_ptx():
    from numba import cuda, float64

    def probe(x):
        x[0] = 1.0

    try:
        cuda.compile_ptx(probe, (float64[::1],), cc=(9, 0))
    except Exception as error:  # any missing piece of the toolkit
        pytest.skip(f"no CUDA toolkit to compile with: {error}")
    return cuda.compile_ptx


def _selected():
    """Every kernel, or those of the engines in ``KINETIC_COMPILE_ENGINES`` (comma-separated
    keys of ``MODULES``: test_kernels_compile_without_a_gpu.py runs one engine a process)."""
    import os

    chosen = os.environ.get("KINETIC_COMPILE_ENGINES")
    keys = sorted(_signatures())
    return [key for key in keys if not chosen or key[0] in chosen.split(",")]


@pytest.mark.parametrize(("engine", "name"), _selected())
def test_kernel_compiles_for_sm90(compile_ptx, engine, name, monkeypatch):
    import importlib
    from types import SimpleNamespace

    from numba.cuda import dispatcher

    # numba-cuda compiles the @overload functions a kernel calls (cuda.cg.this_grid) for
    # the current device's compute capability: a machine without a driver has none
    monkeypatch.setattr(
        dispatcher, "get_current_device", lambda: SimpleNamespace(compute_capability=(9, 0))
    )
    module = importlib.import_module(MODULES[engine])
    signature = _signatures()[(engine, name)]
    kernel = getattr(module, name.split("[")[0])
    if isinstance(kernel, dict):  # "name[label]": one of the kernel's compiled copies
        kernel = kernel[name.split("[")[1].rstrip("]")]
    ptx, _ = compile_ptx(kernel.py_func, signature, cc=(9, 0))
    assert ".entry" in ptx
    if (engine, name) in COOPERATIVE:
        assert _needs_cooperative_launch(kernel, signature), f"{name} syncs its grid"
    resources = _machine_code_resources(ptx, name, kernel.targetoptions.get("max_registers"))
    if resources is None:
        return
    print(f"{engine}.{name}: {resources['registers']} registers, {resources['spills']} B spilled")
    assert resources["spills"] == 0, f"{name} spills {resources['spills']} bytes to local memory"


_LINE = re.compile(r"(\d+) bytes spill stores|Used (\d+) registers")


def _machine_code_resources(ptx: str, name: str, limit: int | None) -> dict[str, int] | None:
    """What ptxas makes of ``ptx`` for sm_90 (nvJitLink, no GPU needed), within the
    kernel's ``limit`` of registers if it has one: the registers a thread and the bytes
    spilled to local memory; None where nvJitLink (the ``cu13``
    toolkit's wheels) is missing. A kernel that spills loads and stores its live values
    through local memory; one that needs more registers runs fewer threads at once (the
    homogeneous DSMC's collisions take 124 on nvJitLink 13.5: 16 of a multiprocessor's
    64 warps)."""
    try:
        from cuda.bindings import nvjitlink
    except ImportError:
        return None
    from numba.cuda.cudadrv.libs import get_cudalib

    options = ["-arch=sm_90", "-verbose"]
    if limit:  # the kernel's own max_registers (``kinetic.gpu.kernel_within``)
        options.append(f"-maxrregcount={limit}")
    handle = nvjitlink.create(len(options), options)
    try:
        data = ptx.encode()
        nvjitlink.add_data(handle, nvjitlink.InputType.PTX, data, len(data), name)
        # the device runtime, for the grid-wide barrier of the cooperative kernels
        library = get_cudalib("cudadevrt", static=True)
        nvjitlink.add_file(handle, nvjitlink.InputType.LIBRARY, library)
        nvjitlink.complete(handle)
        log = bytearray(nvjitlink.get_info_log_size(handle))
        nvjitlink.get_info_log(handle, log)
    finally:
        nvjitlink.destroy(handle)
    registers, spills = 0, 0
    for stores, used in _LINE.findall(log.decode(errors="replace")):
        spills += int(stores or 0)
        registers = max(registers, int(used or 0))
    return {"registers": registers, "spills": spills}
