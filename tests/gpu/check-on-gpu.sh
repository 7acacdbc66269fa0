#!/usr/bin/env bash
# The GPU checks of docs/gpu.md in one call, on a machine with an NVIDIA GPU and no
# network (numba, numba-cuda, xarray, scipy installed there):
#
#   bash tests/gpu/check-on-gpu.sh [WHEELS_DIR] [bench options, e.g. --sections cloning_speed]
#
# WHEELS_DIR (optional) holds wheels installed first, without network and ahead of the
# machine's own packages: the project's pinned numpy (numba-cuda 0.30 does not compile on
# numpy >= 2.5), numba-cuda, and what the package imports that the machine lacks
# (jsonschema and its own dependencies): `make gpu-wheels` downloads them into .whl/.
#
# First `python -m kinetic.bench cuda` (what only a GPU can measure; its sections in the
# order given, none started after KINETIC_BENCH_BUDGET seconds, default 20 s before
# BENCH_SECONDS, the bench's timeout), then the GPU
# tests on the GPU (not the simulator; but the PTX compile checks, which need no GPU and
# took the end of the time of the run of 5836ea7) with the time left of TOTAL_SECONDS
# (default 560),
# reusing the kernels the bench compiled into the numba cache. Writes into $OUT (default
# results/benchmarks): cuda.json (rewritten after every bench section, so a run stopped at
# a time limit keeps what it measured), bench.log, gpu-tests.log (verbose, so a cut-off
# run still says which tests passed), gpu-tests.xml. Exits with the bench's status if it
# failed, else the tests'.
# KINETIC_GIT_REVISION names the revision in the report where the copy has no .git.
set -uo pipefail
start=$SECONDS
total=${TOTAL_SECONDS:-560}
wheels=""
if [[ $# -gt 0 && -d "$1" ]]; then
    wheels=$1
    shift
fi
out=${OUT:-results/benchmarks}
mkdir -p "$out"
site=$(mktemp -d)
if [[ -n "$wheels" ]]; then
    python -m pip install --quiet --no-index --no-deps --no-compile --target "$site" "$wheels"/*.whl || exit 1
fi
export PYTHONPATH="$site:$PWD/src${PYTHONPATH:+:$PYTHONPATH}"
export PYTHONUNBUFFERED=1
export NUMBA_ENABLE_CUDASIM=0
export KINETIC_GIT_REVISION=${KINETIC_GIT_REVISION:-$(git rev-parse --short HEAD 2>/dev/null || echo unknown)}
python -c "import numpy, numba; from numba import cuda; print('numpy', numpy.__version__, 'numba', numba.__version__, cuda.get_current_device().name)" || exit 1
python -c "from kinetic.bench import cuda; cuda.preflight()" || exit 1
nvidia-smi --query-gpu=name,memory.total,clocks.max.sm,clocks.max.mem,pcie.link.gen.max --format=csv 2>/dev/null
bench_seconds=${BENCH_SECONDS:-$((total - 100))}
# no section starts in the last 20 s of the bench's time; one still running at the
# timeout gets SIGTERM, which the bench turns into a report of what it had measured
# (its "partial"), so a late start loses nothing
export KINETIC_BENCH_BUDGET=${KINETIC_BENCH_BUDGET:-$((bench_seconds > 40 ? bench_seconds - 20 : bench_seconds / 2))}
timeout -k 20 "$bench_seconds" python -m kinetic.bench cuda --out "$out" "$@" >"$out/bench.log" 2>&1
bench_rc=$?
echo "bench: exit $bench_rc after $((SECONDS - start)) s (tail of $out/bench.log below)"
tail -n 5 "$out/bench.log"
left=$((total - (SECONDS - start) - 10))
if ((left > 30)); then
    # the PTX compile checks (test_kernels_compile.py, 21 s of NVVM) run on any machine
    # with the toolkit; here the kernels compile for the GPU itself as the tests run them
    timeout "$left" python -m pytest -v -o addopts="" -p no:cacheprovider --durations=15 \
        tests/gpu --ignore tests/gpu/test_kernels_compile.py \
        --junitxml "$out/gpu-tests.xml" >"$out/gpu-tests.log" 2>&1
    tests_rc=$?
    echo "GPU tests: exit $tests_rc after $((SECONDS - start)) s (tail of $out/gpu-tests.log below)"
    tail -n 25 "$out/gpu-tests.log"
else
    tests_rc=0
    echo "GPU tests: not run, $left s left"
fi
# the first failure's status: the bench's, else the tests'
exit $((bench_rc != 0 ? bench_rc : tests_rc))
