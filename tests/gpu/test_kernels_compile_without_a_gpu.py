"""Every CUDA kernel compiles for sm_90, links without spills, in every run of the test
suite: test_kernels_compile.py, which the simulator cannot run (it types nothing), runs
here in a subprocess outside it, one engine a process, with the CUDA compiler of the
pinned wheels (NVVM, NVRTC, nvJitLink: environment-pip.txt). On a GPU machine
(tests/gpu/check-on-gpu.sh) the kernels compile as the other tests launch them, and this
file is skipped.

No kernel had been compiled for a GPU outside a lent GPU session before: the simulator
accepts what NVVM refuses (Python objects, unsupported numpy, exceptions with formatted
strings), so a kernel could pass every test here and fail at its first launch there.
"""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from kinetic import backends

pytestmark = [
    pytest.mark.cuda,
    pytest.mark.slow,
    pytest.mark.skipif(not backends.simulated(), reason="on a GPU the kernels compile as they run"),
]

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("engine", ["cloning", "dsmc", "dsmc_inhomogeneous", "gpu"])
def test_every_kernel_compiles_for_sm90_without_spills(engine, tmp_path):
    environment = {
        **os.environ,
        "NUMBA_ENABLE_CUDASIM": "0",
        "KINETIC_COMPILE_ENGINES": engine,
        "NUMBA_CACHE_DIR": str(tmp_path),
    }
    finished = subprocess.run(
        [
            sys.executable,
            "-m",
            "pytest",
            "-q",
            "-s",
            "-rs",
            "-o",
            "addopts=",
            "-p",
            "no:cacheprovider",
            "tests/gpu/test_kernels_compile.py",
        ],
        cwd=ROOT,
        env=environment,
        capture_output=True,
        text=True,
        timeout=900,
    )
    output = finished.stdout + finished.stderr
    print(output[-4000:])  # each kernel's registers and spills, shown with -s or on failure
    assert finished.returncode == 0, output[-4000:]
    summary = output.strip().splitlines()[-1]
    assert re.search(r"\d+ passed", summary) and "skipped" not in summary, summary
    # every kernel was linked to machine code: nvJitLink and the device runtime were there
    linked = re.findall(r"^\S+\.\S+: \d+ registers, 0 B spilled$", output, re.MULTILINE)
    assert len(linked) == int(re.search(r"(\d+) passed", summary).group(1)), output[-4000:]
