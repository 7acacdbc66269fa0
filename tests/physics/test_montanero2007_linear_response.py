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
    # extreme.csv: +50 % at alpha = 1) and the pressure tensor becomes anisotropic, O(eps^2).
    # At 0.2 the heat flux has no variance (a power-law tail), so the mean's standard
    # error there means nothing: one realization in 16 came out at 3.3 against 1.4-1.6 for
    # the others, and the band of the difference of means swallowed it. The claim is
    # checked realization by realization instead: even the lowest kappa' at 0.2 (1.37-1.45
    # over eight seed pairs) lies above the 0.025 mean by more than that mean's Student
    # band (4 sigma of 16 realizations: 5.5 errors, 0.17-0.22)
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
    lowest = np.min(strong["per_realization"]["kappa_ratio"])
    band = analysis.tolerance_factor(SIGMAS, weak["realizations"] - 1) * weak["kappa_ratio_err"]
    assert lowest - weak["kappa_ratio"] > band
    factor = analysis.tolerance_factor(SIGMAS, strong["realizations"] - 1)
    assert strong["anisotropy"] > factor * strong["anisotropy_err"]
