"""krauth2025's disk study: whether the configured box can be sampled at all.

The direct-disks sampler (Alg. 4.4) draws every disk uniformly and starts again on any
overlap; when legal configurations are too rare it never returns. ``check_disks`` proves
that the box of the config is samplable before any job starts: after the geometric checks
the sampler's front makes too (``theory.krauth2025.check_disk_box``), it draws candidate
configurations in vectorized chunks, disk by disk, and keeps those still free of
overlaps, with numpy alone (the workflow calls it while parsing the Snakefile, where
loading numba would cost a second).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from kinetic.theory.krauth2025 import check_disk_box

__all__ = ["check_disks"]


def _legal_configuration(n_disks, sigma, box, tries, rng, chunk=20_000) -> bool:
    """True if one of ``tries`` tabula-rasa draws of ``n_disks`` disks is free of overlaps."""
    low = np.array([sigma, sigma])
    high = np.array(box, dtype=float) - sigma
    for start in range(0, tries, chunk):
        alive = np.empty((min(chunk, tries - start), 0, 2))
        for _ in range(n_disks):
            new = rng.uniform(low, high, size=(alive.shape[0], 1, 2))
            gap = np.sum((alive - new) ** 2, axis=-1)
            free = np.all(gap > (2.0 * sigma) ** 2, axis=1)
            alive = np.concatenate([alive[free], new[free]], axis=1)
            if alive.shape[0] == 0:
                break
        if alive.shape[0] > 0:
            return True
    return False


def check_disks(disks: Mapping[str, Any], tries: int = 10**6, seed: int = 0) -> None:
    """Raise ``ValueError`` unless direct-disks can sample ``disks`` (config
    ``krauth2025.disks``: ``n_disks``, ``sigma``, ``box``) within ``tries`` draws."""
    n_disks, sigma = disks["n_disks"], float(disks["sigma"])
    box = check_disk_box(n_disks, sigma, disks["box"])
    if not _legal_configuration(n_disks, sigma, box, tries, np.random.default_rng(seed)):
        raise ValueError(
            f"direct-disks found no legal configuration of {n_disks} disks of radius "
            f"{sigma} in {tries} tries: too dense for tabula-rasa sampling"
        )
