"""visco2008 §III.B: at λ = 0 the eigenfunction is the bath Maxwellian, μ(0) = 0,
T(0) = T0 = 1, a2(0) = 0, for hard disks and hard spheres (this checks the exact
thinning and the elastic collision rule: any error in either heats, cools or deforms the
stationary population)."""

import numpy as np
import pytest
from scipy import special, stats

from kinetic.analysis.checks import tolerance_factor
from kinetic.cloning import simulate

REALIZATIONS = 24
BAND = tolerance_factor(4, REALIZATIONS - 1)
"""The two-sided probability of 4 Gaussian sigmas for an error estimated from 24
realizations (Student's t, 23 degrees of freedom): 5.0 errors. The tests ran 6
realizations 4 times as long before (the same simulated time), where that band is 12.3
errors and the 4 they asserted fails about 1 % of seeds a check."""


@pytest.fixture(scope="module", params=[2, 3])
def equilibrium(request):
    return simulate(
        kernel="hard_spheres",
        dimension=request.param,
        lam=0.0,
        population=1000,
        duration=50.0,
        transient=5.0,
        n_blocks=5,
        n_realizations=REALIZATIONS,
        seed=77,
    )


def test_no_compensation_at_lambda_zero(equilibrium):
    # every collision is kept: none duplicates or annihilates a clone, in every block
    assert float(equilibrium.mu) == 0.0
    assert np.all(equilibrium.net_compensations.values == 0)
    assert np.array_equal(
        equilibrium.elastic_collisions.values, equilibrium.collision_events.values
    )
    assert float(equilibrium.collision_events.sum()) > 0


def test_temperature_and_kurtosis_of_the_bath(equilibrium):
    assert abs(float(equilibrium.temperature) - 1.0) < BAND * float(equilibrium.temperature_err)
    assert abs(float(equilibrium.a2)) < BAND * float(equilibrium.a2_err)


def test_velocity_histogram_is_the_maxwellian(equilibrium):
    # members are independent at λ = 0 and snapshots are 40 collision times apart, so
    # the pooled counts are multinomial: a chi-square goodness-of-fit test on |v| < 3
    ds = equilibrium
    snapshots = int(ds.measured.sum()) * ds.sizes["realization"]
    width = float(ds.velocity[1] - ds.velocity[0])
    samples = snapshots * int(ds.attrs["dimension"]) * int(ds.attrs["population"])
    counts = ds.velocity_density.mean("realization").values * samples * width
    v = ds.velocity.values
    bin_probability = np.diff(erf_cdf(np.append(v - width / 2, v[-1] + width / 2)))
    inside = np.abs(v) < 3.0
    expected = samples * bin_probability[inside]
    chi2 = float((((counts[inside] - expected) ** 2) / expected).sum())
    dof = int(inside.sum())
    # χ²'s 10⁻⁴ quantile, 109.5 for 60 bins, where dof + 5 √(2 dof) (114.8, a false alarm
    # of 2.7 × 10⁻⁵) stood; seeds 77-81 gave 29-86 in d = 2 and 3, as χ²₆₀ scatters
    assert chi2 < stats.chi2.isf(1e-4, dof), (chi2, dof)


def erf_cdf(x):
    """Standard normal cumulative distribution."""
    return 0.5 * (1.0 + special.erf(np.asarray(x) / np.sqrt(2.0)))
