#!/usr/bin/env bash
# The GPU checks of docs/gpu.md in one call, on a machine with an NVIDIA GPU and no
# network (numba, numba-cuda, xarray, netCDF4, scipy installed there):
#
#   bash tests/gpu/check-on-gpu.sh [WHEELS_DIR] [bench options, e.g. --sections cloning_speed]
#
# WHEELS_DIR (optional) holds wheels installed first, without network and ahead of the
# machine's own packages: the project's pinned numpy (numba-cuda 0.30 does not compile on
# numpy >= 2.5) and numba-cuda, if the machine has other versions. Runs the GPU tests on the
# GPU (not the simulator) and `python -m kinetic.bench cuda`; writes into $OUT (default
# results/benchmarks): gpu-tests.xml, gpu-tests.log, cuda.json (rewritten after every bench
# section, so a run stopped at a time limit keeps what it measured).
# KINETIC_GIT_REVISION names the revision in the report where the copy has no .git.
set -uo pipefail
wheels=""
if [[ $# -gt 0 && -d "$1" ]]; then
    wheels=$1
    shift
fi
out=${OUT:-results/benchmarks}
mkdir -p "$out"
site=$(mktemp -d)
if [[ -n "$wheels" ]]; then
    python -m pip install --quiet --no-index --no-deps --target "$site" "$wheels"/*.whl || exit 1
fi
export PYTHONPATH="$site:$PWD/src${PYTHONPATH:+:$PYTHONPATH}"
export NUMBA_ENABLE_CUDASIM=0
export KINETIC_GIT_REVISION=${KINETIC_GIT_REVISION:-$(git rev-parse --short HEAD 2>/dev/null || echo unknown)}
python -c "import numpy, numba; from numba import cuda; print('numpy', numpy.__version__, 'numba', numba.__version__, cuda.get_current_device().name.decode() if isinstance(cuda.get_current_device().name, bytes) else cuda.get_current_device().name)" || exit 1
timeout "${TESTS_SECONDS:-240}" python -m pytest -q -o addopts="" -p no:cacheprovider \
    tests/gpu --junitxml "$out/gpu-tests.xml" >"$out/gpu-tests.log" 2>&1
echo "GPU tests: exit $? (tail of $out/gpu-tests.log below)"
tail -n 5 "$out/gpu-tests.log"
timeout "${BENCH_SECONDS:-420}" python -m kinetic.bench cuda --out "$out" "$@"
echo "bench: exit $?"
