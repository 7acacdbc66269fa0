"""Checks of the event-driven MD shared by its physics tests (not a test module)."""

import numpy as np


def all_pairs_min_distance(system) -> float:
    """The closest pair's distance over every pair and the nearest periodic image (the
    engine's own ``min_distance`` looks in the neighbour cells it keeps, so a particle
    filed in the wrong cell would escape it)."""
    x = system.positions()
    gap = x[:, None, :] - x[None, :, :]
    periodic = ~np.broadcast_to(np.asarray(system.walls, dtype=bool), (system.dimension,))
    box = system.box[: system.dimension]
    gap[..., periodic] -= box[periodic] * np.round(gap[..., periodic] / box[periodic])
    distance = np.sqrt((gap**2).sum(axis=-1))
    return float(distance[np.triu_indices(len(x), 1)].min())
