"""montanero2007 Fig. 1 and Section 4: the heat flux is linear in the field up to
eps* = 0.05 (kappa' at 0.025 and 0.05 agree), and the Euler (Eq. 4.1) and exact force
steps give the same kappa' at the same time step (they differ at O(eps^2))."""

import numpy as np
from _montanero2007_runs import SIGMAS, steady_run

from kinetic.analysis import montanero2007 as analysis


def _difference_tolerance(first, second):
    error = np.hypot(first["kappa_ratio_err"], second["kappa_ratio_err"])
    dof = min(first["realizations"], second["realizations"]) - 1
    return abs(first["kappa_ratio"] - second["kappa_ratio"]), analysis.tolerance_factor(
        SIGMAS, dof
    ) * error


def test_kappa_prime_is_independent_of_a_small_field():
    weak = steady_run(
        restitution=0.3,
        reduced_field=0.025,
        n_particles=4000,
        realizations=16,
        duration=42.0,
        seed=3,
    )
    strong = steady_run(
        restitution=0.3,
        reduced_field=0.05,
        n_particles=4000,
        realizations=16,
        duration=42.0,
        seed=4,
    )
    difference, tolerance = _difference_tolerance(weak, strong)
    assert difference <= tolerance


def test_euler_and_exact_force_steps_agree():
    euler = steady_run(
        restitution=0.5,
        reduced_field=0.05,
        n_particles=4000,
        realizations=16,
        duration=42.0,
        seed=5,
        time_step=0.1,
        force_step="euler",
    )
    exact = steady_run(
        restitution=0.5,
        reduced_field=0.05,
        n_particles=4000,
        realizations=16,
        duration=42.0,
        seed=6,
        time_step=0.1,
        force_step="exact",
    )
    difference, tolerance = _difference_tolerance(euler, exact)
    assert difference <= tolerance


def test_a_large_field_leaves_linear_response():
    # extreme case eps* = 0.2: kappa' grows by tens of per cent (results/montanero2007/
    # extreme.csv: +50 % at alpha = 1) and the pressure tensor becomes anisotropic, O(eps^2)
    # 16 realizations each: with 8 the Student band (8.5 errors) made the check pass or
    # fail with the seed (0.50 against 0.52 once); with 16 (5.5 errors) the difference
    # stood 1.5-2.3 bands clear over six seed pairs
    weak = steady_run(
        restitution=1.0,
        reduced_field=0.025,
        n_particles=4000,
        realizations=16,
        duration=30.0,
        seed=7,
    )
    # heavy velocity tails at eps* = 0.2: realizations scatter widely unless N is large
    strong = steady_run(
        restitution=1.0,
        reduced_field=0.2,
        n_particles=20000,
        realizations=16,
        duration=30.0,
        seed=8,
    )
    difference, tolerance = _difference_tolerance(weak, strong)
    assert strong["kappa_ratio"] > weak["kappa_ratio"] and difference > tolerance
    factor = analysis.tolerance_factor(SIGMAS, strong["realizations"] - 1)
    assert strong["anisotropy"] > factor * strong["anisotropy_err"]
