"""Homogeneous cooling at early times follows Haff's law T(t) = T0 / (1 + t/t0)².

For smooth inelastic disks with a Maxwellian distribution, the energy lost per collision
is (1 − α²)(g·σ̂)²/4 with ⟨(g·σ̂)²⟩_coll = 4T, so dT/dt = −(1 − α²) ω(T) T / d with
ω(T) = ω0 √(T/T0) (Enskog, χ included), hence t0 = 2d / ((1 − α²) ω0). The cooling-state
correction (1 + 3 a2/16), |a2| < 0.03 at α = 0.9, changes T by < 0.2 % over the range:
measured, T stands 0.1-0.6 % below this Haff curve at every time for some seeds. So the
band is that 0.2 % plus Student's 4 sigma of 16 realizations (5.5 errors): with the
normal 4 sigma of 4 realizations and no allowance one seed in six failed.
"""

import numpy as np

from kinetic.analysis.checks import tolerance_factor
from kinetic.analysis.statistics import mean_and_sem
from kinetic.edmd import HardSphereSystem, Observers
from kinetic.edmd.system import enskog_collision_frequency


def test_temperature_follows_haff_law_at_early_times():
    # arrange
    restitution, density, n, dimension = 0.9, 0.01, 2000, 2
    omega0 = enskog_collision_frequency(density, dimension)
    t0 = 2 * dimension / ((1 - restitution**2) * omega0)
    times = np.arange(1, 11) / omega0  # up to ten initial mean free times
    temperatures = []
    for seed in range(16):
        system = HardSphereSystem(
            n_particles=n, density=density, restitution=restitution, seed=40 + seed
        )
        observers = Observers.create(n, sample_times=times)
        observers.start(system)
        # act
        system.run(until=times[-1] + 1e-9, observers=observers)
        temperatures.append(observers.sample_temperature.copy())
    mean, sem = mean_and_sem(np.array(temperatures))
    haff = 1.0 / (1.0 + times / t0) ** 2
    # assert: within the band at every time, and cooling is visible (T < 0.6)
    band = tolerance_factor(4.0, len(temperatures) - 1) * sem + 0.002 * haff
    assert np.all(np.abs(mean - haff) < band), np.column_stack([mean, sem, haff])
    assert mean[-1] < 0.6
