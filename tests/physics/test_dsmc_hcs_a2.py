"""HCS fourth cumulant a2(α) against montanero2007 Eq. (2.16).

Eq. (2.16) is an approximation (linear in a2, a3 neglected). Measured relative to a2
itself it is off by about 6 % at α = 0.5 and 8 % at α = 0.9 (an independent plain-numpy
DSMC gives the same values), and a2 changes sign at α = 1/√2, so the claim is checked on
the fourth moment <c⁴> ∝ 1 + a2 (Eq. 2.13): |a2 - a2(2.16)| < 4 sem + 0.005, i.e. the
fourth moment within half a per cent. The zero-field HCS run is free of time-step error
(the hard-sphere dynamics is scale invariant), so the largest allowed step is used.
"""

import pytest

from kinetic.analysis.statistics import mean_and_sem
from kinetic.dsmc import simulate_homogeneous
from kinetic.theory.montanero2007 import hcs_a2


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
    assert abs(a2 - float(hcs_a2(alpha, 3))) < 4 * sem + 0.005
