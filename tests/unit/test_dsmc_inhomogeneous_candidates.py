"""Rule "majorant": a step's candidates depend on the cells' present state only.

From one state, each cell's candidates in a step of Δτ number x_c = Δτ/spacing_c on
average, spacing_c = 1/(pair_coefficient x count(count - 1)/2 x (top1 + top2)), whatever
the cell carried from its earlier steps (``Cells.carry``, which rule "majorant" leaves
alone): the count is floor(x_c + u) with a fresh uniform u. The state is restored before
every call, and the carried fractions are set to 0 for half the calls and to 0.999 for
the other half; counting from the carried fraction (the code before 2026-11-30) gave
Σ floor(x_c) from 0, 9.75 candidates a step below Σ x_c here. Elastic collisions, a
step short enough that a collision rarely raises a cell's bound within it. Each half's
mean must lie within 4 standard errors of Σ x_c, the error of the Bernoulli rounding
Σ f_c(1 - f_c) known exactly.
"""

import math

import numpy as np

from kinetic.dsmc import CoolingModesSettings, new_cooling_gas, realization_streams
from kinetic.dsmc import inhomogeneous_kernels as kernels
from kinetic.dsmc.kernels import BOUND_SAFETY

CALLS = 2000


def test_candidates_of_a_step_do_not_depend_on_the_carried_fraction():
    settings = CoolingModesSettings(
        n_particles=300,
        density=0.05,
        restitution=1.0,
        drag_rate=0.0,
        fictive_factor=1,
        cells_per_side=10,
        time_step=0.2,
        collision_rule="majorant",
    )
    gas = new_cooling_gas(settings, realization_streams(13, 0, 1)[0])
    gas.advance(40)  # particles scattered over the cells by their own streaming
    cells, step = gas.cells(), settings.step()
    velocity = gas.velocity.copy()
    labels = gas.labels.copy()

    def one_call(carried):
        gas.velocity[:] = velocity
        gas.labels[:] = labels
        gas.carry[:] = carried
        before = gas.tally[kernels.TALLY_CANDIDATES]
        kernels.collide_cells(gas.velocity, gas.labels, cells, gas.rng, step, gas.tally, gas.energy)
        return gas.tally[kernels.TALLY_CANDIDATES] - before

    counts = {carried: [one_call(carried) for _ in range(CALLS)] for carried in (0.0, 0.999)}

    # the expected count from the cells' moments (filled by the call from the restored state)
    count = gas.count.astype(float)
    bound = (np.sqrt(gas.cell_moments[:, 3]) + np.sqrt(gas.cell_moments[:, 4])) * BOUND_SAFETY
    x = settings.time_step * settings.pair_coefficient * 0.5 * count * (count - 1.0) * bound
    fraction = x - np.floor(x)
    expected = x.sum()
    sem = math.sqrt(np.sum(fraction * (1.0 - fraction)) / CALLS)
    assert 0.1 * count.size < expected < 0.6 * count.size  # cells of ~3 particles, x_c < 1
    for carried, values in counts.items():
        assert abs(np.mean(values) - expected) < 4 * sem, carried
    # the rounding's spread is Bernoulli's, not a deterministic count
    assert np.var(counts[0.0]) > 0.5 * np.sum(fraction * (1.0 - fraction))
