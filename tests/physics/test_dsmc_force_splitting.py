"""Which time step the heat-flux force needs (the paper's Euler step and the exact one).

The force integrator is not what limits δt: the Euler step (4.1) and the exact
integration differ by O(ε² δt²) per step, invisible at ε* <= 0.05. What biases the
steady heat flux is the splitting of collisions and force: the paper's order
(collisions, then force and thermostat: Lie) has an O(δt) bias, about +0.3 δt/τ in
κ'/κ0 at α = 1, while the symmetric (Strang) splitting is O(δt²) and unbiased within
1-2 % up to δt = 0.4 τ, a hundred times the paper's 0.003 τ.
"""

from math import hypot

from kinetic.analysis.checks import tolerance_factor
from kinetic.analysis.statistics import mean_and_sem
from kinetic.dsmc import simulate_homogeneous

FIELD_BIAS = 0.012
"""κ′/κ0's relative O(ε*²) bias at ε* = 0.05, α = 1 (docs/reproduced.md, montanero2007)."""
KAPPA_PER_FLUX = -0.48144  # κ'/κ0 = -(v0 λ ν0 / T)(4/15) q/ε* in d = 3 (ν0 τ = 8/(5√π))
REALIZATIONS = 32
"""With 12 the Lie bias (+0.10-0.12) stood only 5-6 of its errors clear, and a seed that
drew it at 0.103 against an error of 0.021 failed the 5-error claim; 32 make it about
sqrt(32/12) times more errors (9), and the agreements use Student's 4 sigma (4.7 errors)."""


def _kappa_ratio(time_step, splitting, force_step="exact"):
    interval = time_step * max(1, round(1.0 / time_step))
    run = simulate_homogeneous(
        n_particles=10000,
        restitution=1.0,
        reduced_field=0.05,
        time_step=time_step,
        sample_interval=interval,
        duration=interval * round(24 / interval),
        seed=91,
        n_realizations=REALIZATIONS,
        sample_stride=max(1, round(0.05 / time_step)),
        force_step=force_step,
        splitting=splitting,
    )
    steady = run.where(run.time > 6, drop=True)
    return mean_and_sem(KAPPA_PER_FLUX * steady.heat_flux.mean("time").values / 0.05)


def test_lie_splitting_is_biased_at_large_steps_and_strang_is_not():
    reference, reference_sem = _kappa_ratio(0.03, "strang")
    lie, lie_sem = _kappa_ratio(0.4, "lie")
    strang, strang_sem = _kappa_ratio(0.4, "strang")
    euler, euler_sem = _kappa_ratio(0.4, "strang", force_step="euler")
    band = tolerance_factor(4.0, REALIZATIONS - 1)
    assert lie - reference > 5 * hypot(lie_sem, reference_sem)  # O(δt) bias, ~ +0.12
    assert abs(strang - reference) < band * hypot(strang_sem, reference_sem)
    assert abs(euler - strang) < band * hypot(euler_sem, strang_sem)
    # the elastic κ/κ0 with the field's O(ε*²) bias at ε* = 0.05 (κ′/κ0 1.0402 ± 0.0024
    # there and 1.0275 ± 0.0015 at ε* → 0 at the documents' statistics: +1.2 %); resolved
    # to ± 0.034 here, a consistency check (tests/physics/test_montanero2007_elastic_*)
    expected = 1.025218 * (1.0 + FIELD_BIAS)
    assert abs(reference - expected) < band * reference_sem
