"""The EDMD bench's cost split (kinetic.bench.edmd.fit_event_cost): ns per collision as a
cost per event plus a cost per pair test, fitted over runs with different cell sizes."""

import numpy as np
import pytest

from kinetic.bench.edmd import fit_event_cost


def test_recovers_the_event_and_pair_test_costs_of_an_exact_mix():
    # the event and pair-test mixes of the 2D, N = 1e3, rho sigma^2 = 1e-2 case at cell
    # occupancies 1, 2, 5, 8 (measured), priced at 140 ns an event and 7 ns a test
    events = [9.89, 7.44, 5.30, 4.53]
    tests = [49.7, 82.4, 171.1, 259.7]
    ns = [140.0 * e + 7.0 * p for e, p in zip(events, tests, strict=True)]
    fit = fit_event_cost(ns, events, tests)
    assert fit["event_ns"] == pytest.approx(140.0)
    assert fit["pair_test_ns"] == pytest.approx(7.0)
    assert np.max(np.abs(fit["relative_residuals"])) < 1e-12


def test_residuals_show_a_cost_the_split_does_not_hold():
    events = [9.89, 7.44, 5.30, 4.53]
    tests = [49.7, 82.4, 171.1, 259.7]
    # one run 10 % dearer than the mix says: the fit cannot absorb it
    ns = [140.0 * e + 7.0 * p for e, p in zip(events, tests, strict=True)]
    ns[1] *= 1.1
    fit = fit_event_cost(ns, events, tests)
    assert np.max(np.abs(fit["relative_residuals"])) > 0.02
