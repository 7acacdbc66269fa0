"""Combining DSMC batches: the same numbers as one job, and refusal of foreign batches."""

import numpy as np
import pytest

from kinetic.analysis.collision_statistics import combine_free_flights
from kinetic.dsmc import simulate_free_flights

RUN = dict(
    n_particles=100,
    duration=5.0,
    seed=9,
    max_flight_time=5.0,
    n_time_bins=10,
    max_free_path=5.0,
    n_path_bins=10,
)


def test_batches_combine_to_the_single_job():
    whole = combine_free_flights([simulate_free_flights(n_realizations=4, **RUN)])
    parts = combine_free_flights(
        [
            simulate_free_flights(n_realizations=3, first_realization=1, **RUN),
            simulate_free_flights(n_realizations=1, **RUN),
        ]
    )
    for name in ("time_pdf", "time_pdf_sem", "path_pdf", "collision_frequency", "flights"):
        np.testing.assert_array_equal(whole[name].values, parts[name].values)
    assert parts.attrs["n_realizations"] == 4
    # every populated bin has an error bar from the scatter of the four realizations
    populated = parts.time_pdf.values > 0
    assert populated.any() and np.all(parts.time_pdf_sem.values[populated] > 0)


def test_foreign_or_overlapping_batches_are_refused():
    first = simulate_free_flights(n_realizations=2, **RUN)
    other = simulate_free_flights(n_realizations=2, first_realization=2, **{**RUN, "seed": 10})
    with pytest.raises(ValueError, match="different seeds"):
        combine_free_flights([first, other])
    denser = simulate_free_flights(
        n_realizations=2, first_realization=2, **{**RUN, "n_particles": 50}
    )
    with pytest.raises(ValueError, match=r"parameters \['n_particles'\] differ"):
        combine_free_flights([first, denser])
    with pytest.raises(ValueError, match="overlap"):
        combine_free_flights([first, first])
    # the aggregate names the files it read
    with pytest.raises(ValueError, match=r"b\.nc.*a\.nc|a\.nc.*b\.nc"):
        combine_free_flights([first, first], names=["a.nc", "b.nc"])
