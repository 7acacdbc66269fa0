"""Re-sorting the particles in memory (Z-order of their cells) is a pure relabelling: the
collision sequence, the per-particle observers and the read-outs are those of an unsorted
run."""

import numpy as np

from kinetic.edmd import HardSphereSystem, Observers, kernels
from kinetic.edmd.system import morton_code


def _run(sorting, seed, walls):
    """6000 collisions in chunks of 750 (the same chunks, hence the same rebasing of the
    clock, with and without sorting), re-sorted after each chunk if ``sorting``."""
    system = HardSphereSystem(n_particles=1500, density=0.03, seed=seed, walls=walls)
    observers = Observers.create(
        system.n_particles,
        window_lengths=[0.7, 2.1],
        count_bins=12,
        flight_bins=30,
        flight_bin_width=1.0,
        path_bins=30,
        path_bin_width=1.0,
        record_capacity=6000,
    )
    observers.start(system)
    for _ in range(8):
        system.run(collisions=750, observers=observers)
        if sorting:
            system.sort_particles(observers)
    return system, observers


def test_sorted_run_has_the_same_collisions_and_observations():
    for seed, walls in ((5, False), (6, True)):
        plain, plain_observers = _run(False, seed, walls)
        sorted_, sorted_observers = _run(True, seed, walls)
        assert not np.array_equal(sorted_.label, np.arange(sorted_.n_particles))
        a = plain_observers.collision_records(plain)
        b = sorted_observers.collision_records(sorted_)
        np.testing.assert_array_equal(np.sort(a["pair"], axis=1), np.sort(b["pair"], axis=1))
        np.testing.assert_array_equal(a["time"], b["time"])
        for name in ("window_histogram", "window_overflow", "flight_histogram", "path_histogram"):
            np.testing.assert_array_equal(
                getattr(plain_observers, name), getattr(sorted_observers, name)
            )
        # the open windows' per-particle counts belong to the same physical particles
        counts = np.empty_like(sorted_observers.window_count)
        counts[sorted_.label] = sorted_observers.window_count
        np.testing.assert_array_equal(plain_observers.window_count, counts)
        np.testing.assert_allclose(plain.positions(), sorted_.positions(), atol=1e-9)
        np.testing.assert_allclose(plain.velocities(), sorted_.velocities(), atol=1e-9)
        assert plain.counters()["collisions"] == sorted_.counters()["collisions"]


def test_morton_code_interleaves_the_axes():
    cells = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [2, 0, 0], [0, 0, 1]])
    np.testing.assert_array_equal(morton_code(cells), [0, 1, 2, 3, 8, 4])


def test_prefetching_does_not_change_the_dynamics():
    """The prefetch pipeline (bucket-list walks, cells, candidates) only hints the caches:
    the same collisions at the same times with it as without it, in a periodic and a
    walled box."""
    for walls in (False, True):
        runs = []
        for prefetch in (0, 2):
            system = HardSphereSystem(
                n_particles=1500, density=0.03, seed=9, walls=walls, prefetch=prefetch
            )
            observers = Observers.create(system.n_particles, record_capacity=20_000)
            observers.start(system)
            system.run(collisions=20_000, observers=observers)
            runs.append((system, observers.collision_records(system)))
        (plain, a), (hinted, b) = runs
        assert hinted.grid[kernels.I_PREFETCH] == 2
        np.testing.assert_array_equal(a["pair"], b["pair"])
        np.testing.assert_array_equal(a["time"], b["time"])
        assert plain.counters() == hinted.counters()


def test_periodic_sorting_keeps_the_collisions():
    """``sort_every`` re-sorts between kernel calls without changing the collision
    sequence (both runs in the same chunks of 1600 collisions: the clock is rebased after
    each kernel call, which changes round-off)."""
    runs = []
    for sort_every in (0, 1600):
        system = HardSphereSystem(n_particles=1500, density=0.03, seed=4, sort_every=sort_every)
        observers = Observers.create(system.n_particles, record_capacity=8000)
        observers.start(system)
        for _ in range(5):
            system.run(collisions=1600, observers=observers)
        runs.append((system, observers.collision_records(system)))
    (plain, a), (sorted_, b) = runs
    assert not np.array_equal(sorted_.label, np.arange(sorted_.n_particles))
    np.testing.assert_array_equal(np.sort(a["pair"], axis=1), np.sort(b["pair"], axis=1))
    np.testing.assert_array_equal(a["time"], b["time"])
    assert plain.counters() == sorted_.counters()
