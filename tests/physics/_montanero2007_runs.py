"""Small fixed-seed runs shared by the montanero2007 physics tests (not a test module)."""

from kinetic.analysis import montanero2007 as analysis
from kinetic.studies.montanero2007 import simulate_batch

SIGMAS = 4.0


def steady_run(
    *,
    restitution,
    reduced_field,
    n_particles,
    realizations,
    duration,
    seed,
    time_step=0.01,
    force_step="euler",
    steady_from=10.0,
):
    """Steady-state summary (kinetic.analysis.montanero2007.steady_summary_of) of one run.

    ``duration`` and ``steady_from`` are in tau, whole multiples of the 0.6 tau windows.
    """
    run = {
        "n_particles": n_particles,
        "time_step": time_step,
        "force_step": force_step,
        "selection": "ntc",
        "splitting": "lie",
        "reduced_field": reduced_field,
        "duration": duration,
        "steady_from": steady_from,
        "sample_interval": 0.6,
        "sample_stride": max(1, round(0.15 / time_step)),
        "realizations": realizations,
        "realizations_per_job": realizations,
        "cx_max": 5.0,
        "cx_bins": 40,
        "restitution": restitution,
        "family": "scan",
    }
    dataset = simulate_batch(run, seed=seed, first=0, count=realizations, label="test run")
    return analysis.steady_summary_of(dataset)


def tolerance(summary, key="kappa_ratio_err"):
    """SIGMAS standard errors, widened to Student's t for the realizations behind them."""
    return analysis.tolerance_factor(SIGMAS, summary["realizations"] - 1) * summary[key]
