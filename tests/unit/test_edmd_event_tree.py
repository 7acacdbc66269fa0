"""The tournament tree always has the earliest event at its root."""

import numpy as np

from kinetic.edmd import kernels


def test_root_is_the_minimum_after_random_updates():
    rng = np.random.default_rng(2)
    n = 37
    leaves = 64
    keys = rng.exponential(size=n)
    tree_time = np.full(2 * leaves, np.inf)
    tree_index = np.zeros(2 * leaves, dtype=np.int32)
    kernels.tree_build(tree_time, tree_index, keys)
    for _ in range(2000):
        i = int(rng.integers(n))
        keys[i] = rng.exponential() if rng.random() < 0.9 else np.inf
        kernels.tree_update(tree_time, tree_index, i, keys[i])
        assert tree_time[1] == keys.min()
        assert keys[tree_index[1]] == keys.min()
