"""The inhomogeneous DSMC's cells with room to spare (``inhomogeneous_kernels``): whichever
way a step brings the cells up to date (the particles that change cell moved one by one,
the layout redone when a cell runs out of room, every particle sorted when many change
cell), every particle is in exactly one slot of the cell its position lies in, and the
cells' moments are the sums over their particles.

The moments are summed before the collisions; an elastic collision keeps its cell's Σw
and Σ|w|² (both partners are in the cell), so at α = 1 they are the sums over the cell's
particles after the step too, to the rounding of its collisions."""

import numpy as np
import pytest

from kinetic.dsmc import CoolingModesSettings, new_cooling_gas, realization_streams
from kinetic.dsmc import inhomogeneous as front
from kinetic.dsmc import inhomogeneous_kernels as kernels

# N = 400 real disks at nσ² = 0.05 (λ = 7.1, L = 89), Λ = 5: 2000 simulated particles
GAS = dict(n_particles=400, density=0.05, restitution=1.0, drag_rate=0.02, fictive_factor=5)
ROUTES = {
    # 6 x 6 cells of 2.1 λ (55 particles each), Δτ = 0.2: about 2 % change cell a step
    "one by one": (dict(cells_per_side=6, time_step=0.2), None),
    # the same with one free slot a cell: the cells run out of room every few steps
    "out of room": (dict(cells_per_side=6, time_step=0.2), 1),
    # 40 x 40 cells of 0.3 λ (1.25 particles each), Δτ = 0.5: about 35 % change cell
    "sorting": (dict(cells_per_side=40, time_step=0.5), None),
}


def _check_layout(gas):
    settings = gas.settings
    n = settings.n_simulated
    m = settings.cells_per_side
    start, count = gas.start, gas.count
    slots = gas.position.shape[1]
    assert np.all(start[:-1] + count <= start[1:]) and start[0] >= 0 and start[-1] <= slots
    assert count.sum() == n
    assert np.array_equal(np.sort(gas.identities()), np.arange(n))
    positions = gas.positions()
    assert np.all((positions >= 0) & (positions < settings.box_side))
    cell = np.minimum((positions * (m / settings.box_side)).astype(int), m - 1)
    assert np.array_equal(cell[:, 1] * m + cell[:, 0], np.repeat(np.arange(m * m), count))
    # the cells' moments against their particles' sums (elastic: kept by the collisions)
    w = gas.velocities()
    first = np.concatenate([[0], np.cumsum(count)[:-1]])
    occupied = count > 0
    sums = [np.add.reduceat(x, first[occupied]) for x in (w[:, 0], w[:, 1], (w**2).sum(1))]
    moments = gas.cell_moments[occupied]
    scale = 1e-11 * max(1.0, float((w**2).sum()))
    for column, total in enumerate(sums):
        np.testing.assert_allclose(moments[:, column], total, rtol=0, atol=scale)
    assert np.all(gas.cell_moments[~occupied, :3] == 0.0)


@pytest.mark.parametrize("route", ROUTES)
def test_every_particle_stays_in_one_slot_of_its_cell(route, monkeypatch):
    cells, slack = ROUTES[route]
    if slack is not None:
        monkeypatch.setattr(front, "slack_per_cell", lambda mean, changing, room=slack: room)
    settings = CoolingModesSettings(**GAS, **cells, collision_rule="paper")
    gas = new_cooling_gas(settings, realization_streams(11, 0, 1)[0])
    _check_layout_before_any_step(gas)
    for _ in range(4):
        gas.advance(50)
        _check_layout(gas)
    tally = gas.tally
    moved = tally[kernels.TALLY_MOVED] / (tally[kernels.TALLY_STEPS] * settings.n_simulated)
    layouts = tally[kernels.TALLY_LAYOUTS]
    assert tally[kernels.TALLY_COLLISIONS] > settings.n_simulated  # the cells collide
    if route == "one by one":
        assert 0.005 < moved < kernels.RESORT_FRACTION
        assert layouts <= 2
    elif route == "out of room":
        assert layouts >= 20
    else:
        assert moved > kernels.RESORT_FRACTION
        assert layouts >= 199  # every step after the first sorts


def _check_layout_before_any_step(gas):
    """The initial layout: the particles in their cells, the moments zeroed (no momentum
    to remove before the first step)."""
    assert np.all(gas.cell_moments == 0.0)
    assert gas.count.sum() == gas.settings.n_simulated
    assert np.array_equal(np.sort(gas.identities()), np.arange(gas.settings.n_simulated))


def test_routes_give_the_same_physics():
    """The same gas with room (one by one) and without (the layout redone every few
    steps) takes different random pairs, but the same collision rate and temperature:
    the elastic gas with drag heats at the same rate whichever way its cells are kept."""
    settings = CoolingModesSettings(**GAS, cells_per_side=6, time_step=0.2, collision_rule="paper")
    results = {}
    for slack in (None, 1):
        temperatures, rates = [], []
        for stream in realization_streams(5, 0, 4):
            with pytest.MonkeyPatch.context() as patch:
                if slack is not None:
                    patch.setattr(front, "slack_per_cell", lambda mean, changing, room=slack: room)
                gas = new_cooling_gas(settings, stream)
            gas.advance(400)
            temperatures.append(gas.observables()["temperature"])
            rates.append(gas.collisions / (gas.time * settings.n_simulated))
        results[slack] = np.array(temperatures), np.array(rates)
    # T grows as e^{2 ω0 t} exactly (elastic collisions keep the energy): same in both
    expected = np.exp(2 * GAS["drag_rate"] * 400 * 0.2)
    for temperatures, _ in results.values():
        np.testing.assert_allclose(temperatures, expected, rtol=1e-9)
    (_, a), (_, b) = results.values()
    error = np.hypot(a.std(ddof=1) / 2, b.std(ddof=1) / 2)
    assert abs(a.mean() - b.mean()) < 4 * error


def test_a_step_streams_each_particle_by_the_drags_exact_flight():
    """dr/dτ = w, dw/dτ = ω0 w over a step: w grows by e^{ω0Δτ} and r moves by w (e^{ω0Δτ}
    − 1)/ω0 (w after the removal of the centre-of-mass velocity), wrapped into the box.
    Checked particle by particle on the particles the step's collisions left alone (their
    direction unchanged): a displacement 5 % long passed every physics test of the engine
    (τ_c within its ±20 % band)."""
    settings = CoolingModesSettings(**GAS, cells_per_side=6, time_step=0.2, collision_rule="paper")
    gas = new_cooling_gas(settings, realization_streams(3, 0, 1)[0])
    gas.advance(3)  # the centre-of-mass velocity removed from here on: its round-off only
    order = np.argsort(gas.identities())
    before_r, before_w = gas.positions()[order], gas.velocities()[order]
    centre = before_w.mean(axis=0)
    gas.advance(1)
    order = np.argsort(gas.identities())
    after_r, after_w = gas.positions()[order], gas.velocities()[order]
    w = before_w - centre
    growth = np.exp(GAS["drag_rate"] * 0.2)
    cross = w[:, 0] * after_w[:, 1] - w[:, 1] * after_w[:, 0]
    alone = np.abs(cross) <= 1e-12 * np.hypot(*w.T) * np.hypot(*after_w.T)
    assert 0.5 < alone.mean() < 1.0  # most particles do not collide in a step; some do
    np.testing.assert_allclose(after_w[alone], w[alone] * growth, rtol=1e-12, atol=1e-14)
    moved = after_r[alone] - before_r[alone]
    side = settings.box_side
    moved -= side * np.round(moved / side)  # unwrapped by the periodic box
    expected = w[alone] * np.expm1(GAS["drag_rate"] * 0.2) / GAS["drag_rate"]
    np.testing.assert_allclose(moved, expected, rtol=0, atol=1e-9 * side)
    assert np.abs(expected).max() > 1e-3 * side  # the step moves them measurably
