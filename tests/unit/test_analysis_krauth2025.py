"""kinetic.analysis.krauth2025's summary of where the precisions part (chaos_table.csv)."""

import math

import numpy as np
import pandas as pd
import pytest

from kinetic.analysis.krauth2025 import parting_summary


def _table(parting_events):
    """Random starts of one comparison, each parting at its event (NaN: not within 300)."""
    return pd.DataFrame(
        {
            "start": np.arange(1, len(parting_events) + 1),
            "start_kind": "random",
            "comparison": "float32 against float64",
            "parting_event": parting_events,
            "pair_collisions_per_disk": np.asarray(parting_events, dtype=float) / 4.0,
            "events_compared": 300,
        }
    )


def test_every_start_parted_gives_the_mean_and_its_error():
    (row,) = parting_summary(_table([50.0, 60.0, 70.0]))
    assert row["parting_event"] == pytest.approx(60.0)
    assert row["parting_event_sem"] == pytest.approx(10.0 / math.sqrt(3.0))
    assert row["pair_collisions_per_disk"] == pytest.approx(15.0)
    assert (row["starts_parted"], row["starts"], row["events_compared"]) == (3, 3, 300)


def test_a_start_that_did_not_part_leaves_no_mean():
    """The start still together after 300 events would part later: the mean of the other
    two (55) would be biased low, so none is given."""
    (row,) = parting_summary(_table([50.0, 60.0, math.nan]))
    assert math.isnan(row["parting_event"]) and math.isnan(row["parting_event_sem"])
    assert math.isnan(row["pair_collisions_per_disk"])
    assert (row["starts_parted"], row["starts"]) == (2, 3)


def test_naive_pin_acceptance_is_the_pooled_ratio():
    """The pins table's naive-pin acceptance is all realizations' samples over all their
    starts (a mean of the realizations' own ratios keeps one realization's bias, (1 − p)
    /samples relative), within Student's band of Eq. (4.6)."""
    from kinetic.analysis.checks import tolerance_factor
    from kinetic.analysis.krauth2025 import pins_table
    from kinetic.samplers import sample_line
    from kinetic.theory.krauth2025 import line_dataset, naive_acceptance

    n, length, sigma, samples, realizations = 3, 6.0, 0.5, 40, 64
    naive = sample_line(
        "naive",
        n_pins=n,
        length=length,
        sigma=sigma,
        samples=samples,
        realizations=realizations,
        bins=10,
        seed=3,
    )
    table = pins_table([naive], [line_dataset(n, length, sigma, 10)])
    (row,) = table.itertuples()
    started = naive["started"].values
    assert started.std() > 0  # the realizations' ratios differ
    assert row.acceptance == pytest.approx(samples * realizations / started.sum(), rel=1e-12)
    band = tolerance_factor(4.0, realizations - 1) * row.acceptance_sem
    assert abs(row.acceptance - naive_acceptance(n, length, sigma)) < band
