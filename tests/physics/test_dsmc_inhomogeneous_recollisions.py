"""Molecular chaos in small cells (costantini2010 Fig 1): recollisions of the same pair.

The fraction of collisions whose two partners' previous collisions were with each
other grows when the cells shrink at Λ = 1 (fewer collision partners per cell: N/M² =
100, 6.25, 0.64 real particles) and falls when the fictive particles multiply at a
fixed cell size (Λ = 10). Elastic gas, rule "majorant"; each comparison must hold by
4 standard errors (Poisson errors of the recollision counts).
"""

import math

import pytest

from kinetic.dsmc import simulate_cooling_modes


def recollision_fraction(fictive_factor: int, cells_per_side: int) -> tuple[float, float]:
    dataset = simulate_cooling_modes(
        n_particles=400,
        density=0.05,
        restitution=1.0,
        drag_rate=0.0,
        equilibration=0.0,
        sample_interval=200.0,
        n_samples=2,
        seed=7,
        fictive_factor=fictive_factor,
        cells_per_side=cells_per_side,
        time_step=0.25,
        collision_rule="majorant",
        n_realizations=4,
    )
    repeated = int(dataset.repeated_collisions.sum())
    collisions = int(dataset.collisions.sum())
    return repeated / collisions, math.sqrt(repeated) / collisions


@pytest.fixture(scope="module")
def fractions():
    return {key: recollision_fraction(*key) for key in ((1, 2), (1, 8), (1, 25), (10, 25))}


def more(a: tuple[float, float], b: tuple[float, float]) -> bool:
    """a's fraction exceeds b's by 4 combined standard errors."""
    return a[0] - b[0] > 4 * math.hypot(a[1], b[1])


def test_smaller_cells_at_lambda_one_recollide_more(fractions):
    assert more(fractions[1, 8], fractions[1, 2])
    assert more(fractions[1, 25], fractions[1, 8])


def test_more_fictive_particles_recollide_less(fractions):
    assert more(fractions[1, 25], fractions[10, 25])
