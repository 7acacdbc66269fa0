"""Variants of the engines that no document's simulation runs, kept for the benchmarks and
the tests that compare them with the engines (an edit here reruns no simulation: the
workflow's simulation rules depend only on the engine packages and what their fronts
import).

- ``speed_classes``: DSMC with an exact majorant per pair drawn through speed classes,
  against the engine's uniform pairs (``kinetic.bench.dsmc``,
  ``tests/physics/test_dsmc_pair_selections_agree.py``).
- ``column_groups``: the CUDA homogeneous DSMC's collision groups on the CPU, against the
  whole box (``tests/physics/test_dsmc_gpu_groupings_match_the_whole_box.py``; its one
  kernel, 14 s of compilation, is in :func:`warmup`, so the test suite's seed caches hold
  it).
"""


def warmup() -> None:
    """Compile the variants with the argument types the benchmarks and tests use (numba
    cache=True: later processes load the machine code)."""
    import numpy as np

    from kinetic import rng
    from kinetic.dsmc import kernels
    from kinetic.experimental.speed_classes import SpeedClasses, collide_speed_classes

    for d in (2, 3):
        state = rng.stream_states(0, 1)[0].copy()
        velocity = np.empty((d, 64))
        kernels.maxwellian(velocity, state, 1.0)
        bounds = np.empty(d + 2)
        kernels.speed_bounds(velocity, 0, 64, bounds)
        tally = np.zeros(4, dtype=np.int64)
        collisions = kernels.Collisions(
            kernels.HARD_SPHERES, 0.9, 1.0 / 63, 0.1, False, bounds, np.zeros(1), tally
        )
        collide_speed_classes(velocity, state, collisions, SpeedClasses(64).arrays())
    # the GPU's collision groups on the CPU (14 s of compilation, one kernel for all groupings)
    from kinetic.experimental.column_groups import cooling_state

    cooling_state("whole", n_particles=256, n_steps=400)
