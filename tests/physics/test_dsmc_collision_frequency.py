"""Equilibrium collision frequency of each kernel against kinetic theory.

Hard spheres: ω = n S <|v1 - v2|> (visco2008 Eq. 7); Maxwell molecules: the same at the
reference temperature T = 1; very hard particles: ω_VHP = n Ω_d T (visco2008 Eq. B3).
Measured as 2 x collisions / (N t) in independent realizations with exact (Poisson)
event times; |mean - ω| within Student's 4 sigma for 8 realizations (8.5 sem: a normal
4 sem failed for one salted seed at 5.1).
"""

import numpy as np
import pytest

from kinetic import rng
from kinetic.analysis.checks import tolerance_factor
from kinetic.analysis.statistics import mean_and_sem
from kinetic.dsmc import kernels
from kinetic.gas import KERNELS, candidate_coefficient, equilibrium_collision_frequency
from kinetic.theory import visco2008

KERNEL_IDS = {
    "hard_spheres": kernels.HARD_SPHERES,
    "maxwell": kernels.MAXWELL,
    "very_hard": kernels.VERY_HARD,
}


@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize("kernel", KERNELS)
def test_equilibrium_collision_frequency(d, kernel):
    n, duration, density, realizations = 2000, 4.0, 0.7, 8
    frequencies = []
    for state in rng.stream_states(23, realizations):
        velocity = np.empty((d, n))
        kernels.maxwellian(velocity, state, 1.0)
        bounds = np.empty(d + 2)
        kernels.speed_bounds(velocity, 0, n, bounds)
        tally = np.zeros(4, dtype=np.int64)
        kernels.collide_range(
            velocity,
            0,
            n,
            state,
            kernels.Collisions(
                KERNEL_IDS[kernel],
                1.0,
                candidate_coefficient(kernel, d, density, n),
                duration,
                True,
                bounds,
                np.zeros(1),
                tally,
            ),
        )
        frequencies.append(2.0 * tally[kernels.TALLY_ACCEPTED] / (n * duration))
    mean, sem = mean_and_sem(frequencies)
    expected = equilibrium_collision_frequency(kernel, d, density)
    assert abs(mean - expected) < tolerance_factor(4.0, realizations - 1) * sem


def test_units_agree_with_visco2008_eq7():
    for d in (2, 3):
        omega = equilibrium_collision_frequency("hard_spheres", d, density=1.0)
        assert omega == pytest.approx(visco2008.collision_frequency(d, 1.0))
