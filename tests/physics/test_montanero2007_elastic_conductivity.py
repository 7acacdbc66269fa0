"""montanero2007 Fig. 3, alpha = 1: kappa'/kappa0 agrees with the higher-order Sonine value
1.025218 of elastic hard spheres (paper's Ref. [37]).

A regression guard of the heat-flux force and the kappa' estimator, resolved to about 3 %
(Student's 4 errors of 32 realizations: 0.03). That catches a wrong force, normalisation
or estimator (each moves kappa' by far more) but separates neither the first Sonine
value 1 nor the field's O(eps*^2) bias at eps* = 0.05 (+1.2 %, docs/reproduced.md) from
1.025218: resolving those takes the documents' statistics, where the build's check at
eps* -> 0 gives 1.0275 +- 0.0015 (a test at that precision would cost minutes)."""

from _montanero2007_runs import steady_run, tolerance

from kinetic.theory import montanero2007 as theory

TIME_STEP = 0.01
# first-order time-splitting bias (results/montanero2007/error_vs_time): about +0.35 dt/tau
SPLITTING_BIAS = 0.35 * TIME_STEP


def test_elastic_kappa_prime_is_the_higher_sonine_value():
    summary = steady_run(
        restitution=1.0,
        reduced_field=0.05,
        n_particles=5000,
        realizations=32,
        duration=60.0,
        seed=1,
        time_step=TIME_STEP,
    )
    expected = theory.KAPPA_ELASTIC_HIGHER_SONINE * (1 + SPLITTING_BIAS)
    assert abs(summary["kappa_ratio"] - expected) <= tolerance(summary)
    assert tolerance(summary) < 0.04  # the resolution the docstring states
