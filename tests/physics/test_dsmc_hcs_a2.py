"""HCS fourth cumulant a2(α) against montanero2007 Eq. (2.16).

Eq. (2.16) is an approximation (linear in a2, a3 neglected). Measured relative to a2
itself it is off by 4, 9.5, 9.4 and 7 % at α = 0.5, 0.6, 0.8 and 0.9 (seed 51; an
independent plain-numpy DSMC gives the same values), so the claim is checked within
``SONINE_ALLOWANCE`` of |a2(2.16)| plus 4 errors (the samples are 8 mean free times
apart). At α = 1 a2 = 0 exactly (the Maxwellian): there only the errors remain (seed 51:
+0.0005 ± 0.0006). The zero-field HCS run is free
of time-step error (the hard-sphere dynamics is scale invariant), so the largest allowed
step is used.
"""

import pytest

from kinetic.analysis.statistics import mean_and_sem
from kinetic.dsmc import simulate_homogeneous
from kinetic.theory.montanero2007 import hcs_a2

#: Eq. (2.16)'s error relative to a2 (measured: at most 9.5 %)
SONINE_ALLOWANCE = 0.12


@pytest.mark.parametrize("alpha", [0.5, 0.6, 0.8, 0.9, 1.0])
def test_hcs_a2_against_eq_2_16(alpha):
    run = simulate_homogeneous(
        n_particles=20000,
        restitution=alpha,
        duration=160.0,
        time_step=0.4,
        sample_interval=8.0,
        seed=51,
        n_realizations=2,
        sample_stride=1,
    )
    a2, sem = mean_and_sem(run.a2.isel(time=slice(2, None)).values.ravel())
    assert sem < 1e-3
    expected = float(hcs_a2(alpha, 3))
    assert abs(a2 - expected) < 4 * sem + SONINE_ALLOWANCE * abs(expected)
