"""Collisions relax any velocity distribution to the Maxwellian."""

import numpy as np
from scipy import stats

from kinetic.analysis.statistics import mean_and_sem
from kinetic.edmd import HardSphereSystem


def test_velocities_relax_to_maxwellian_from_a_single_speed():
    # arrange: every particle with speed √2 (T = 1) in a random direction: a2 = −1/2
    n, realizations = 2000, 4
    samples, kurtosis = [], []
    for seed in range(realizations):
        angle = np.random.default_rng(seed).uniform(0, 2 * np.pi, n)
        velocities = np.sqrt(2.0) * np.column_stack([np.cos(angle), np.sin(angle)])
        system = HardSphereSystem(
            n_particles=n, density=0.01, velocities=velocities, positions=None, seed=seed
        )
        # act: 15 collisions per particle
        system.run(collisions=15 * n // 2)
        v = system.velocities()
        speed2 = np.sum(v**2, axis=1)
        kurtosis.append(np.mean(speed2**2) / (2 * np.mean(speed2) ** 2) - 1)  # a2 in d = 2
        samples.append(v.ravel() / np.sqrt(np.mean(speed2) / 2))
    # assert: Sonine coefficient a2 = 0 within 4 standard errors ...
    a2, a2_sem = mean_and_sem(kurtosis)
    assert abs(a2) < 4 * a2_sem + 1e-3, (a2, a2_sem)
    # ... and the components follow N(0, 1): chi-square over 20 equiprobable bins
    pooled = np.concatenate(samples)
    edges = stats.norm.ppf(np.linspace(0, 1, 21))
    observed, _ = np.histogram(pooled, edges)
    expected = pooled.size / 20
    chi2 = np.sum((observed - expected) ** 2 / expected)
    assert chi2 < stats.chi2.ppf(0.999, 19), chi2
