"""Event-driven molecular dynamics of hard disks (d = 2) and spheres (d = 3).

- ``HardSphereSystem``: the state and its event loop (periodic or hard-wall box,
  restitution, velocity-rescaling thermostat, inelastic-collapse report);
- ``Observers``: collision counts in windows, free flights, samples, wall hits, records;
- ``simulate`` (module ``equilibrium``): the equilibrium protocol of visco2008 (independent
  realizations -> ``xarray.Dataset``);
- ``warmup``: compile (or load from numba's cache) every kernel with production types.

krauth2025's few disks in a box with walls run on the lecture's O(N²)-per-event
event-disks, an engine of its own (``kinetic.event_disks``).
"""

from kinetic.lazy import lazy_exports

_EXPORTS = {
    "HardSphereSystem": "system",
    "InelasticCollapseError": "system",
    "Observers": "observers",
    "simulate": "equilibrium",
    "simulate_cooling_modes": "cooling",
}
"""Public names and the module that defines each: loaded on first use, so that importing
``kinetic.edmd.arguments`` (the numpy-only checks the workflow runs while it reads the
config) loads neither numba nor the kernels."""

__all__ = [
    "HardSphereSystem",
    "InelasticCollapseError",
    "Observers",
    "simulate",
    "simulate_cooling_modes",
    "warmup",
]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())


def warmup() -> None:
    """Compile every kernel with the argument types production uses (numba cache=True:
    later processes load the machine code instead of compiling)."""
    import numpy as np

    from kinetic.edmd import cooling
    from kinetic.edmd.observers import Observers
    from kinetic.edmd.system import HardSphereSystem

    for dimension, walls in ((2, False), (2, True), (3, False)):
        n = 8 if dimension == 2 else 27
        system = HardSphereSystem(
            n_particles=n,
            box=[8.0] * dimension,
            dimension=dimension,
            walls=walls,
            seed=0,
            restitution=0.9,
            rescale_every=5,
        )
        observers = Observers.create(
            n,
            window_lengths=[1.0],
            count_bins=8,
            flight_bins=4,
            path_bins=4,
            sample_times=[0.5, 1.0],
            record_capacity=4,
        )
        observers.start(system)
        system.run(collisions=20, observers=observers)
        system.sort_particles(observers)
        system.run(until=system.time + 1.0, scale=1.01)
        system.min_distance()
        system.kinetic_temperature()
        if dimension == 2 and not walls:  # the cooling gas's observers
            terms = np.empty((4, system.n_particles))
            cooling._observe(system.phase, 0.0, 8.0, terms, np.empty(len(cooling._OBSERVED)))
