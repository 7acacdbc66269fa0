"""Two independent exact pair selections give the same homogeneous cooling state.

``kernels.collide_range`` draws uniform pairs under one bound for the whole gas;
``speed_classes.collide_speed_classes`` draws i ∝ |v_i - c| through speed classes with a
bound per pair, and returns the particles in another order. Both must produce the same
scaled homogeneous cooling state of inelastic hard spheres (α = 0.5, d = 3): its fourth
cumulant a2 and its cooling rate per collision, each compared between the two within
4.5 combined standard errors of fixed-seed runs, and a2 against the Sonine estimate of
van Noije & Ernst (a first-order estimate, good to about 20 % at this α).
"""

import numpy as np
import pytest

from kinetic import rng
from kinetic.dsmc import kernels
from kinetic.experimental.speed_classes import SpeedClasses, collide_speed_classes

D = 3
N = 4000
ALPHA = 0.5
CALLS = 400
BURN_IN = 40
COLLISIONS_PER_CALL = 0.5  # per particle


def _cooling_state(selection: str, seed: int):
    state = rng.stream_states(seed, 1)[0].copy()
    velocity = np.empty((D, N))
    kernels.maxwellian(velocity, state, 1.0)
    bounds = np.empty(D + 2)
    kernels.speed_bounds(velocity, 0, N, bounds)
    coefficient = 1.0 / (N - 1)  # a particle collides at about <|g|> = 2.26 per unit time
    duration = 2.0 * COLLISIONS_PER_CALL / 2.26
    work = SpeedClasses(N)
    carry = np.zeros(1)
    tally = np.zeros(4, dtype=np.int64)
    a2, loss_per_collision = [], []
    for call in range(CALLS):
        energy = float(np.sum(velocity**2))
        before = int(tally[kernels.TALLY_ACCEPTED])
        if selection == "uniform":
            kernels.collide_range(
                velocity,
                0,
                N,
                state,
                kernels.Collisions(
                    kernels.HARD_SPHERES, ALPHA, coefficient, duration, False, bounds, carry, tally
                ),
            )
        else:
            collide_speed_classes(
                velocity,
                state,
                kernels.Collisions(
                    kernels.HARD_SPHERES, ALPHA, coefficient, duration, False, bounds, carry, tally
                ),
                work.arrays(),
            )
        collisions = int(tally[kernels.TALLY_ACCEPTED]) - before
        lost = 1.0 - float(np.sum(velocity**2)) / energy
        # back to T = 1 (the scaled HCS): momentum is conserved, so only a rescale
        kernels.force_and_thermostat(velocity, 0.0, False, D * N * 1.0, bounds)
        if call >= BURN_IN:
            c2 = np.sum(velocity**2, axis=0)
            a2.append(D * np.mean(c2**2) / ((D + 2) * np.mean(c2) ** 2) - 1.0)
            loss_per_collision.append(lost * N / collisions)
    assert tally[kernels.TALLY_EXCEEDED] == 0
    return np.array(a2), np.array(loss_per_collision)


def _mean_and_error(series, batches: int = 12):
    means = np.array([b.mean() for b in np.array_split(series, batches)])
    return means.mean(), means.std(ddof=1) / np.sqrt(batches)


@pytest.mark.slow
def test_uniform_pairs_and_speed_classes_give_the_same_cooling_state():
    results = {s: _cooling_state(s, seed) for s, seed in (("uniform", 21), ("classes", 22))}
    for index in range(2):
        (m1, e1), (m2, e2) = (_mean_and_error(results[s][index]) for s in results)
        assert abs(m1 - m2) < 4.5 * np.hypot(e1, e2), (index, m1, e1, m2, e2)
    # a2 of the HCS, Sonine first order (van Noije & Ernst 1998), d = 3
    sonine = (16 * (1 - ALPHA) * (1 - 2 * ALPHA**2)) / (
        9 + 24 * D - ALPHA * (41 - 8 * D) + 30 * (1 - ALPHA) * ALPHA**2
    )
    for name, (a2, _) in results.items():
        mean, error = _mean_and_error(a2)
        assert abs(mean - sonine) < 0.2 * abs(sonine) + 4.5 * error, (name, mean, error, sonine)
