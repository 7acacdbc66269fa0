"""Kernels of the cloning Monte Carlo: the exact thinning reproduces r(v) of visco2008 Eq. 6.

A population whose members all have the same speed v0 keeps that speed forever when
every collision annihilates (λ large) and is compensated by a clone: then the measured
compensation rate is exactly r(v0) (times 1 - e^{-λ}), whatever the directions. This
checks the two-channel majorant, the acceptance step, the bound on |v| and ω = 1.
"""

import math

import numpy as np
import pytest

from kinetic.cloning import kernels
from kinetic.cloning.rates import TABLE_STEP, rate_table
from kinetic.rng import stream_states
from kinetic.theory.visco2008 import collision_rate


def fixed_speed_rate(kernel, dimension, speed, population=2000, duration=40.0, seed=11):
    state = stream_states(seed, 1)[0]
    velocity = np.empty((dimension, population))
    work = np.empty(population)
    kernels.draw_population(velocity, work, state)
    norms = np.sqrt((velocity**2).sum(axis=0))
    velocity *= speed / norms
    # 40 blocks: the standard error from 10 would itself scatter by ~25%
    blocks = np.zeros((40, len(kernels.BLOCK_FIELDS)))
    name = "maxwell" if kernel == kernels.MAXWELL else "hard_spheres"
    kernels.run_blocks(
        kernel,
        40.0,
        velocity,
        work,
        state,
        duration / 40,
        kernels.Observers(blocks, 6.0, np.zeros(10), rate_table(name, dimension), TABLE_STEP),
    )
    column = kernels.BLOCK_FIELDS.index
    rates = -blocks[:, column("net_compensations")] / (population * blocks[:, 0])
    assert np.allclose(np.sqrt((velocity**2).sum(axis=0)), speed)  # speeds never change
    return rates.mean(), rates.std(ddof=1) / math.sqrt(rates.size)


@pytest.mark.parametrize("dimension", [2, 3])
@pytest.mark.parametrize("speed", [0.0, 0.7, 1.5, 3.0, 5.5])
def test_hard_sphere_thinning_gives_the_exact_collision_rate(dimension, speed):
    rate, error = fixed_speed_rate(kernels.HARD_SPHERES, dimension, speed)
    assert abs(rate - collision_rate(speed, dimension)) < 4 * error + 1e-12


def test_maxwell_rate_is_omega():
    rate, _ = fixed_speed_rate(kernels.MAXWELL, 2, 2.0)
    assert rate == pytest.approx(1.0, abs=1e-12)


def test_compensation_parameters_implement_eq56():
    factor, keep, duplicating = kernels.compensation_parameters(-1.0)
    assert duplicating and factor == pytest.approx(2 * math.e - 1)
    # kept collisions e^{-λ} r and duplications (e^{-λ} - 1) r per unit time
    assert factor * keep == pytest.approx(math.e)
    assert factor * (1 - keep) == pytest.approx(math.e - 1)
    assert kernels.compensation_parameters(0.7)[:2] == pytest.approx((1.0, math.exp(-0.7)))


def test_the_bound_follows_the_fastest_member_down():
    """One member starts 30 times faster than thermal; its first collisions slow it down.
    Within one long block the hard-disk bound K1 v_max + 1/√2 must follow the population's
    current maximum (rescanned every n/4 events), not keep v_max = 30: with the stale
    bound a collision event would cost about (K1·30 + 1/√2)/ω ≈ 18 candidates, with a
    tracked one about 3 (v_max ≈ 3.7, the largest of 1000 Maxwellian speeds: K1·v_max + 1/√2
    ≈ 2.8 candidates per unit collision rate)."""
    population, lam = 1000, 0.0
    state = stream_states(5, 1)[0]
    velocity = np.empty((2, population))
    speed = np.empty(population)
    kernels.draw_population(velocity, speed, state)
    velocity[:, 0] = (30.0, 0.0)
    blocks = np.zeros((1, len(kernels.BLOCK_FIELDS)))
    kernels.run_blocks(
        kernels.HARD_SPHERES,
        lam,
        velocity,
        speed,
        state,
        50.0,
        kernels.Observers(blocks, 6.0, np.zeros(10), rate_table("hard_spheres", 2), TABLE_STEP),
    )
    fields = kernels.BLOCK_FIELDS
    row = blocks[0]
    assert row[fields.index("max_speed")] >= 30.0  # the bound started at the fast member
    assert row[fields.index("collision_events")] > 10 * population
    assert row[fields.index("candidates")] / row[fields.index("collision_events")] < 5.0
