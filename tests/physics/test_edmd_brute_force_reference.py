"""Cell lists + event tree find exactly the collisions an all-pairs search finds.

Lock-step comparison over thousands of collisions: after every collision of the engine, an
independent brute-force reference (numpy, every pair, every periodic image, every wall)
starts from the engine's state and computes the next collision by itself (executing wall
bounces on the way); the engine's next collision must be the same pair at the same time
(to round-off). Comparing from a common state at every step sidesteps the chaotic growth
of round-off differences (krauth2025 §4.1.2), which would otherwise make two correct
codes diverge after some tens of collisions per particle.
"""

import itertools

import numpy as np
import pytest

from kinetic.edmd import HardSphereSystem, Observers


def brute_force_next_collision(x, v, box, walls, sigma, reach=2):
    """Earliest pair collision from positions x (N, d), velocities v (N, d): every pair,
    the periodic images of shifts −reach L to reach L, numpy-vectorized. (A pair can
    meet several boxes on before any other collision where the box is a few σ and holds
    few particles: three disks in a box of 3.01σ flew 3-6 boxes between collisions, and
    shifts of ±L alone expected a later pair 13 times in 1000 collisions.)

    Executes the wall reflections (hard walls at σ/2 from the box faces) that come first.
    Returns (time from now, i, j) with i < j.
    """
    x = x.copy()
    v = v.copy()
    n, d = x.shape
    first, second = np.triu_indices(n, 1)
    images = (
        np.array(
            list(
                itertools.product(
                    *[(0,) if walls[k] else range(-reach, reach + 1) for k in range(d)]
                )
            )
        )
        * box
    )
    elapsed = 0.0
    while True:
        dr = (x[second] - x[first])[None, :, :] + images[:, None, :]  # (image, pair, d)
        dv = (v[second] - v[first])[None, :, :]
        b = np.sum(dr * dv, axis=-1)
        c = np.sum(dr * dr, axis=-1) - sigma**2
        disc = b * b - np.sum(dv * dv, axis=-1) * c
        hit = (b < 0) & (disc > 0)
        times = np.full(b.shape, np.inf)
        times[hit] = np.maximum(c[hit] / (np.sqrt(disc[hit]) - b[hit]), 0.0)
        image, pair = np.unravel_index(np.argmin(times), times.shape)
        pair_time = times[image, pair]
        wall_time, wall_particle, wall_axis = np.inf, -1, -1
        for k in range(d):
            if not walls[k]:
                continue
            with np.errstate(divide="ignore", invalid="ignore"):
                t_up = np.where(v[:, k] > 0, (box[k] - sigma / 2 - x[:, k]) / v[:, k], np.inf)
                t_down = np.where(v[:, k] < 0, (sigma / 2 - x[:, k]) / v[:, k], np.inf)
            t_wall = np.minimum(t_up, t_down)
            i = int(np.argmin(t_wall))
            if t_wall[i] < wall_time:
                wall_time, wall_particle, wall_axis = t_wall[i], i, k
        if pair_time <= wall_time:
            return elapsed + pair_time, int(first[pair]), int(second[pair])
        x += v * wall_time
        v[wall_particle, wall_axis] *= -1.0
        elapsed += wall_time


@pytest.mark.parametrize(
    ("dimension", "walls", "n_particles", "box", "collisions", "occupancy", "capacity", "reach"),
    [
        (2, False, 24, [12.0, 9.0], 2000, 0.5, None, 2),
        (2, True, 20, [10.0, 11.0], 1500, 0.5, None, 2),
        (3, False, 20, [6.0, 5.0, 7.0], 1000, 0.5, None, 2),
        (2, False, 40, [12.0, 12.0], 1500, 2.5, 4, 2),
        (2, False, 3, [3.01, 3.01], 1000, 0.5, None, 8),
    ],
    ids=["2d-periodic", "2d-walls", "3d-periodic", "2d-rows-grow", "2d-narrow"],
)
def test_same_collision_sequence_as_all_pairs_search(
    dimension, walls, n_particles, box, collisions, occupancy, capacity, reach
):
    # arrange: a small box with several cells per side, so cell lists matter; rows of 4
    # slots overflow and are grown while running in "2d-rows-grow"; "2d-narrow" has the
    # fewest cells a periodic axis allows and flights across several boxes
    system = HardSphereSystem(
        n_particles=n_particles,
        box=box,
        dimension=dimension,
        walls=walls,
        seed=11,
        cell_occupancy=occupancy,
        cell_capacity=capacity,
    )
    assert np.all(system.cells_per_side >= 3)
    observers = Observers.create(n_particles, record_capacity=1)
    wall_flags = [walls] * dimension
    box = np.asarray(box)
    # act and assert, collision by collision
    for _ in range(collisions):
        x, v, now = system.positions(), system.velocities(), system.time
        expected_time, i, j = brute_force_next_collision(x, v, box, wall_flags, 1.0, reach)
        system.run(collisions=1, observers=observers)
        record = observers.collision_records(system)
        pair = tuple(sorted(int(p) for p in record["pair"][-1]))
        assert pair == (i, j)
        assert record["time"][-1] - now == pytest.approx(expected_time, rel=1e-9, abs=1e-9)
    if capacity is not None:
        assert system.members.shape[1] > capacity
