"""montanero2007 Eqs. (4.1)-(4.2): the thermostat restores zero momentum and the initial
energy exactly (to round-off) after every step, with either force step, also far from
linear response and with strong dissipation."""

import pytest

from kinetic.analysis import montanero2007 as analysis
from kinetic.studies.montanero2007 import simulate_batch


@pytest.mark.parametrize(
    ("restitution", "reduced_field", "force_step"),
    [(0.5, 0.025, "euler"), (0.3, 0.2, "exact"), (1.0, 0.2, "euler")],
)
def test_every_window_has_zero_momentum_and_the_initial_energy(
    restitution, reduced_field, force_step
):
    run = {
        "n_particles": 400,
        "time_step": 0.01,
        "force_step": force_step,
        "selection": "ntc",
        "splitting": "lie",
        "reduced_field": reduced_field,
        "duration": 3.0,
        "steady_from": 1.5,
        "sample_interval": 0.1,
        "sample_stride": 1,
        "realizations": 2,
        "realizations_per_job": 2,
        "cx_max": 5.0,
        "cx_bins": 20,
        "restitution": restitution,
        "family": "scan",
    }
    dataset = simulate_batch(run, seed=4, first=0, count=2, label="thermostat test")
    summary = analysis.steady_summary_of(dataset)
    # every step is sampled (stride 1): |<c_x>| and |<c^2> - 3/2| over 600 snapshots
    assert summary["max_abs_cx"] < 1e-13
    assert summary["max_abs_energy_error"] < 1e-13
    assert int(dataset["collisions"].sum()) > 1000
