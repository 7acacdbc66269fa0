"""``kinetic.gpu.first_pair``/``next_pair``: the grid-stride walk over (row, index) pairs
that the GPU kernels use instead of a 64-bit division per element (the cooperative
inhomogeneous step's particles and cells) visits exactly the pairs
divmod(k, n) of k = start, start + stride, ..., whatever the stride against the row."""

import os

os.environ.setdefault("NUMBA_ENABLE_CUDASIM", "1")

import pytest

pytest.importorskip("numba.cuda")

from kinetic import gpu

pytestmark = pytest.mark.cuda


@pytest.mark.parametrize(
    ("n", "stride", "rows"),
    [(14, 128, 129), (129, 8, 3), (30_000, 128 * 396, 7), (5, 5, 4), (1, 3, 9), (1000, 999, 3)],
)
def test_the_walk_visits_the_pairs_of_the_flat_indices(n, stride, rows):
    first_pair, next_pair = gpu.first_pair.py_func, gpu.next_pair.py_func
    for start in {0, 1, stride - 1, n - 1}:
        if not 0 <= start < stride:
            continue
        walked = []
        q, i, dq, di = first_pair(start, n, stride)
        while q < rows:
            walked.append((q, i))
            q, i = next_pair(q, i, dq, di, n)
        assert walked == [divmod(k, n) for k in range(start, rows * n, stride)]
