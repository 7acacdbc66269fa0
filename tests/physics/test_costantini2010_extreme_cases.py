"""Strong dissipation in a large box: α = 0.5 at N = 3000 (N nσ² = 15, below the shear
instability's 19.7) over long runs stays finite, stationary and at zero momentum, in DSMC
and in MD (where the drag multiplies round-off momentum by e^{ω0 τ}, about e^{190} here,
unless it is removed)."""

import numpy as np
import pytest

from kinetic import dsmc, edmd
from kinetic.studies.costantini2010 import mean_free_time
from kinetic.theory import costantini2010 as theory

DENSITY = 0.005
MEAN_FREE_TIME = mean_free_time(DENSITY)


def check_stationary(dataset):
    temperature = dataset.temperature.values
    assert np.all(np.isfinite(temperature))
    assert np.all(np.isfinite(dataset.mode_real.values))
    assert float(np.abs(dataset.momentum).max()) < 1e-10
    late = temperature[:, temperature.shape[1] // 2 :]
    assert abs(late.mean() - 1.0) < 0.1  # T_s = T0 up to the first-Sonine error of ζ


@pytest.mark.slow
def test_dsmc_at_strong_dissipation_over_a_long_run():
    drag = theory.drag_rate(0.5, DENSITY)
    dataset = dsmc.simulate_cooling_modes(
        n_particles=3000,
        density=DENSITY,
        restitution=0.5,
        drag_rate=drag,
        equilibration=0.0,
        sample_interval=1.0 * MEAN_FREE_TIME,
        n_samples=3000,
        fictive_factor=1,
        cells_per_side=22,
        time_step=0.05 * MEAN_FREE_TIME,
        collision_rule="majorant",
        seed=3,
    )
    assert drag * 3000 * MEAN_FREE_TIME > 150  # e^{ω0 τ} would overflow a float64 square
    check_stationary(dataset)


@pytest.mark.slow
def test_md_at_strong_dissipation_over_a_long_run():
    drag = theory.drag_rate(0.5, DENSITY)
    dataset = edmd.simulate_cooling_modes(
        n_particles=3000,
        density=DENSITY,
        restitution=0.5,
        drag_rate=drag,
        equilibration=0.0,
        sample_interval=1.0 * MEAN_FREE_TIME,
        n_samples=600,
        seed=3,
    )
    assert drag * 600 * MEAN_FREE_TIME > 25
    check_stationary(dataset)
