"""The event calendar always yields the earliest event and holds every particle once."""

import numpy as np

from kinetic.edmd import HardSphereSystem, kernels


def _calendar(n, n_buckets):
    phase = np.zeros((n, 8))
    links = np.zeros((n, 4), dtype=np.int32)
    heads = np.full(n_buckets + 1, -1, dtype=np.int32)
    heap_time = np.full(n, np.inf)
    heap_index = np.zeros(n, dtype=np.int32)
    calendar = np.array([0.0, 1.0])
    cursor = np.zeros(kernels.N_CURSOR, dtype=np.int64)  # with the prefetch pipeline
    return phase, links, heads, heap_time, heap_index, calendar, cursor


def assert_every_particle_once(phase, links, heads, heap_time, heap_index, calendar, cursor):
    """Each particle sits in exactly one place (heap or one list), with consistent links,
    heap order and bucket bounds."""
    n = phase.shape[0]
    seen = np.zeros(n, dtype=int)
    size = int(cursor[1])
    for position in range(size):
        i = heap_index[position]
        seen[i] += 1
        assert links[i, kernels.L_PLACE] == kernels.PLACE_HEAP
        assert links[i, kernels.L_HEAP] == position
        assert heap_time[position] == min(phase[i, 6], phase[i, 7])
        if position > 0:
            parent = (position - 1) // 2
            assert (heap_time[parent], heap_index[parent]) < (heap_time[position], i)
    n_buckets = heads.shape[0] - 1
    for bucket in range(n_buckets + 1):
        previous = -1
        i = heads[bucket]
        while i >= 0:
            seen[i] += 1
            assert seen[i] == 1
            assert links[i, kernels.L_PLACE] == bucket
            assert links[i, kernels.L_PREV] == previous
            assert bucket > cursor[0]  # the current and earlier buckets are poured out
            q = (min(phase[i, 6], phase[i, 7]) - calendar[0]) * calendar[1]
            assert q >= bucket if bucket == n_buckets else bucket <= q < bucket + 1
            previous = i
            i = links[i, kernels.L_NEXT]
    np.testing.assert_array_equal(seen, 1)


def test_next_is_the_earliest_after_random_updates():
    rng = np.random.default_rng(2)
    n = 37
    state = _calendar(n, n_buckets=16)
    phase, links, heads, heap_time, heap_index, calendar, cursor = state
    phase[:, 6] = rng.exponential(size=n)
    phase[:, 7] = np.inf
    ints = np.zeros((n, 8), dtype=np.int64)  # cells and partners: only prefetched
    members = np.zeros((1, 16), dtype=np.int32)
    occupancy = np.zeros(1, dtype=np.int32)
    grid = np.ones(kernels.N_GRID, dtype=np.int64)
    kernels.calendar_build(*state)
    assert_every_particle_once(*state)
    now = 0.0
    for step in range(3000):
        i = kernels.calendar_next(phase, ints, members, occupancy, np.zeros(n), grid, *state[1:])
        keys = np.minimum(phase[:, 6], phase[:, 7])
        if not np.isfinite(keys).any():
            assert i == -1
            phase[:, 6] = now + rng.exponential(size=n)
            kernels.calendar_build(*state)
            continue
        assert heap_time[0] == keys.min() and keys[i] == keys.min()
        assert i == np.flatnonzero(keys == keys.min())[0]  # ties: lowest particle first
        now = keys[i]
        # the event's particle and sometimes a random one get new times ≥ now
        for p in {i, int(rng.integers(n))} if step % 3 else {i}:
            u = rng.random()
            phase[p, 6] = np.inf if u < 0.1 else now + (0.0 if u < 0.15 else rng.exponential())
            kernels.calendar_reschedule(
                p,
                min(phase[p, 6], phase[p, 7]),
                links,
                heads,
                heap_time,
                heap_index,
                calendar,
                cursor,
            )
        assert_every_particle_once(*state)


def test_running_system_keeps_every_particle_once():
    system = HardSphereSystem(n_particles=500, density=0.02, seed=3, rescale_every=300)
    for _ in range(5):
        system.run(collisions=700)
        assert_every_particle_once(system.phase, *system._calendar_arrays())
