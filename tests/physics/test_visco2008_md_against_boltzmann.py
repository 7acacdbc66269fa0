"""visco2008 Table I: the collision count of MD against the Boltzmann equation's.

Eq. (28) solved at a window of t = 10 mean free times gives k2 = ⟨N²⟩_c/⟨N⟩ = 1.12476
(``kinetic.theory.visco2008_exact.window_cumulants``). A periodic MD gas of N disks falls
short of it by (1.64 ± 0.25)/N + 0.0007 ± 0.0003 at ρσ² = 10⁻³: the size of the system and
its finite density (fitted to N = 250, 1000, 4000 with seeds 11-13 and the default build,
docs/data/visco2008-md-size.json; this test's seed is not among them). At N = 250 the
shortfall is 0.0073 ± 0.0011, about nine times the error of 32 realizations (0.0008): MD
and the Boltzmann solver, two independent routes, agree once the shortfall is allowed, and
disagree without it (Student's 4σ for 31 degrees of freedom either way).
"""

import math

import pytest

from kinetic.analysis.checks import tolerance_factor
from kinetic.analysis.collision_statistics import cumulant_dataset
from kinetic.edmd import simulate
from kinetic.theory.visco2008_exact import window_cumulants

N, DENSITY, REALIZATIONS = 250, 0.001, 32
SHORTFALL = 1.64 / N + 0.0007
"""Expected Boltzmann-minus-MD k2 at t = 10 (fit of docs/data/visco2008-md-size.json)."""
SHORTFALL_ERROR = math.hypot(0.25 / N, 0.0003)


@pytest.mark.slow
def test_md_k2_at_t10_is_the_boltzmann_value_less_the_finite_size_shortfall():
    run = simulate(
        n_particles=N,
        density=DENSITY,
        equilibration=10,
        duration=6000,
        windows=[1, 2, 5, 10, 20, 50],
        checkpoints=[6000],
        flight_time_max=20,
        flight_time_bins=20,
        free_path_max=20,
        free_path_bins=20,
        cell_occupancy=2.0,
        seed=21,
        realizations=REALIZATIONS,
    )
    cumulants = cumulant_dataset(run, [10])
    k2 = float(cumulants["scaled_cumulant"].sel(order=2).item())
    error = float(cumulants["scaled_cumulant_sem"].sel(order=2).item())
    boltzmann = float(window_cumulants([10.0])[0, 1])
    assert error < 0.001  # the run resolves the shortfall
    band = tolerance_factor(4.0, REALIZATIONS - 1) * error
    assert abs((boltzmann - k2) - SHORTFALL) < band + SHORTFALL_ERROR, (k2, error, boltzmann)
    assert boltzmann - k2 > band  # without the shortfall MD and Eq. (28) disagree
