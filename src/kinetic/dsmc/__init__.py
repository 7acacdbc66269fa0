"""Homogeneous DSMC engine (Bird's method): hard spheres, Maxwell molecules, very hard
particles, restitution α, the heat-flux force and thermostat of montanero2007, and a
continuous-time variant with free-flight observers (visco2008). Fronts: ``homogeneous``
(``simulate_homogeneous``) and ``free_flights`` (``simulate_free_flights``); the gas
state and stepping they share: ``state``; numba kernels: ``kernels`` (shared with the
inhomogeneous engine). CUDA backend of ``simulate_homogeneous`` (``backend="cuda"``):
``gpu``, imported only by such a run (it imports ``numba.cuda`` through ``kinetic.gpu``).

Inhomogeneous engine (costantini2010, d = 2): ``simulate_cooling_modes`` (and, on the GPU,
``simulate_cooling_modes_points``: the runs of several α in the same launches) in
``inhomogeneous`` (front) and ``inhomogeneous_kernels`` (numba kernels): fictive
particles in M x M collision cells, in the stationary representation of the
homogeneous cooling state, with the transverse-mode observers."""

from __future__ import annotations

from kinetic.lazy import lazy_exports

_EXPORTS = {
    "simulate_free_flights": "free_flights",
    "simulate_homogeneous": "homogeneous",
    "simulate_homogeneous_points": "homogeneous",
    "CoolingModesGas": "inhomogeneous",
    "CoolingModesSettings": "inhomogeneous",
    "new_cooling_gas": "inhomogeneous",
    "simulate_cooling_modes": "inhomogeneous",
    "simulate_cooling_modes_points": "inhomogeneous",
    "MOMENT_NAMES": "state",
    "HomogeneousGas": "state",
    "HomogeneousSettings": "state",
    "Samples": "state",
    "advance_gas": "state",
    "maxwellian_starts": "state",
    "new_gas": "state",
    "realization_streams": "state",
}
"""Public names and the module that defines each: loaded on first use, so that importing
``kinetic.dsmc.arguments`` (the numpy-only checks the workflow runs while it reads the
config) loads neither numba nor the kernels."""

__all__ = [
    "MOMENT_NAMES",
    "CoolingModesGas",
    "CoolingModesSettings",
    "HomogeneousGas",
    "HomogeneousSettings",
    "Samples",
    "advance_gas",
    "new_cooling_gas",
    "new_gas",
    "realization_streams",
    "simulate_cooling_modes",
    "simulate_cooling_modes_points",
    "simulate_free_flights",
    "simulate_homogeneous",
    "simulate_homogeneous_points",
    "warmup",
]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())


def _warm_homogeneous() -> None:
    """``simulate_homogeneous``'s kernels: a tiny gas in d = 2 and 3, with the NTC and
    Poisson clocks, the Euler and exact force steps, Lie and Strang splitting."""
    from kinetic import dsmc  # its lazy names: the package file imports no kernel

    for dimension in (2, 3):
        for selection, force_step, splitting in (
            ("ntc", "euler", "lie"),
            ("poisson", "exact", "strang"),
        ):
            settings = dsmc.HomogeneousSettings(
                n_particles=8,
                restitution=0.9,
                time_step=0.01,
                dimension=dimension,
                reduced_field=0.05,
                force_step=force_step,
                selection=selection,
                splitting=splitting,
            )
            gas = dsmc.new_gas(settings, dsmc.realization_streams(0, 0, 1)[0])
            dsmc.advance_gas(gas, 2, dsmc.Samples(stride=1, histogram=True))
    dsmc.maxwellian_starts(3, 8, dsmc.realization_streams(0, 0, 2))  # the cuda backend's starts


def _warm_free_flights() -> None:
    """``simulate_free_flights``'s kernels, d = 2 and 3."""
    from kinetic import dsmc

    for dimension in (2, 3):
        dsmc.simulate_free_flights(
            n_particles=8, duration=0.5, seed=0, dimension=dimension, chunk=0.5
        )


def _warm_cooling_modes() -> None:
    """``simulate_cooling_modes``'s kernels: both collision rules, with and without drag."""
    from kinetic import dsmc

    for rule in ("paper", "majorant"):
        for restitution, drag_rate in ((1.0, 0.0), (0.8, 0.001)):
            dsmc.simulate_cooling_modes(
                n_particles=8,
                density=0.05,
                restitution=restitution,
                drag_rate=drag_rate,
                equilibration=0.5,
                sample_interval=0.5,
                n_samples=2,
                seed=0,
                fictive_factor=2,
                cells_per_side=2,
                time_step=0.5,
                collision_rule=rule,
            )


WARMUPS = {
    "simulate_homogeneous": _warm_homogeneous,
    "simulate_free_flights": _warm_free_flights,
    "simulate_cooling_modes": _warm_cooling_modes,
    "simulate_cooling_modes_points": _warm_cooling_modes,
}
"""The kernels each front runs, compiled by ``kinetic.jit.warm('dsmc', front)`` before a
job of that front (13, 6 and 11 s of the 39 s of :func:`warmup` on the development
machine)."""


def warmup() -> None:
    """Compile (or load from numba's cache) every kernel with the production argument types:
    those of every front (``WARMUPS``) and the inhomogeneous engine's stepping, observers
    and collision stage called alone (as the tests and benchmarks do)."""
    from kinetic import dsmc

    for compile_kernels in dict.fromkeys(WARMUPS.values()):
        compile_kernels()
    settings = dsmc.CoolingModesSettings(
        n_particles=8,
        density=0.05,
        restitution=0.9,
        drag_rate=0.0,
        fictive_factor=1,
        cells_per_side=1,
        time_step=0.5,
        collision_rule="majorant",
    )
    gas = dsmc.new_cooling_gas(settings, dsmc.realization_streams(0, 0, 1)[0])
    gas.advance(1)
    gas.observables()
    dsmc.inhomogeneous_kernels.collide_cells(
        gas.velocity,
        gas.labels,
        gas.cells(),
        gas.rng,
        settings.step(),
        gas.tally,
        gas.energy,
    )
