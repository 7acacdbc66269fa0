"""The collision groups of the CUDA homogeneous DSMC, on the CPU, against the whole box:
``python -m kinetic.experimental.column_groups [N] [steps]``.

The homogeneous cooling state of d = 3 hard spheres (α = 0.5, no field, the energy
rescaled to its start after every step) with the engine's own collision stage
(``kernels.collide_range``, NTC) run four ways in the same loop:

- ``whole``: one group of all N particles (the CPU engine's collisions);
- ``permuted``: groups of N/G >= 128 consecutive particles of a random permutation drawn
  every step (the GPU's first regrouping, ``feistel``, since removed, with a Fisher-Yates
  shuffle in its place);
- ``columns``: group g takes from each column j the particle of row (g + s_j) mod G, the
  shifts drawn every step (``kernels.column_particle``), each group against its own
  majorant (the GPU's ``columns`` regrouping, since removed);
- ``in_place``: the same groups (the shifts of a key drawn every step,
  ``kernels.column_shift``), each collided in place by ``kernels.collide_members``
  against the whole gas's majorant (twice its largest speed), as the GPU's ``sparse``
  collisions do.

A group's pair coefficient is the whole box's times (N - 1)/(m - 1), as on the GPU. The
cooling rate ζ (per unit time, from the energy lost in a step) and a2 (from <c⁴>) are
averaged over the steps after the first tenth, their errors from 40 blocks of steps. Two
particles of one column never share a group, which the homogeneous gas should not feel:
this measures whether it does.
"""

from __future__ import annotations

import math
import sys

import numpy as np

from kinetic import rng
from kinetic.dsmc import kernels
from kinetic.dsmc.state import HomogeneousSettings, new_gas, realization_streams
from kinetic.jit import kernel

__all__ = ["GROUPINGS", "cooling_state", "main"]

GROUPINGS = {"whole": 0, "permuted": 1, "columns": 2, "in_place": 3}

_GROUP_SIZE = 128
"""Fewest particles of a group: ``kinetic.dsmc.gpu.GROUP_SIZE`` (not imported here, as
that module loads numba-cuda)."""


@kernel
def _run(velocity, grouping, n_steps, pair_base, duration, restitution, state, group_size):
    """``n_steps`` steps of collisions in the ``grouping``'s groups (module docstring),
    each followed by the rescaling to the starting energy: the per-step cooling rates and
    <c⁴>/<c²>², and the summed tally. ``state`` (4,) is the run's xoshiro256+ stream."""
    d, n = velocity.shape
    n_rows = max(1, n // group_size) if grouping > 0 else 1
    n_columns = -(-n // n_rows)
    full_rows = n - (n_columns - 1) * n_rows
    states = np.empty((n_rows, 4), dtype=np.uint64)
    for g in range(n_rows):
        s0, s1, s2, s3 = rng.thread_state(state[0], state[1], state[2], state[3], g)
        rng.store_state(states[g], s0, s1, s2, s3)
    bounds = np.zeros((n_rows, d + 2))
    carry = np.zeros((n_rows, 1))
    tally = np.zeros((n_rows, 4), dtype=np.int64)
    scratch = np.empty((d, n_columns))
    members = np.empty(n_columns, dtype=np.int64)
    order = np.arange(n)
    shifts = np.empty(n_columns, dtype=np.int64)
    zeta = np.empty(n_steps)
    kurtosis = np.empty(n_steps)
    for step in range(n_steps):
        if grouping == 1:
            for i in range(n - 1, 0, -1):
                k = min(int(rng.uniform(state) * (i + 1)), i)
                order[i], order[k] = order[k], order[i]
        elif grouping == 2:
            for j in range(n_columns):
                shifts[j] = min(int(rng.uniform(state) * n_rows), n_rows - 1)
        key = np.uint64(rng.uniform(state) * 2.0**53) if grouping == 3 else np.uint64(0)
        before = 0.0
        for i in range(n):
            for k in range(d):
                before += velocity[k, i] * velocity[k, i]
        top = 0.0  # the whole gas's largest speed (its mean velocity is 0 here)
        for i in range(n if grouping == 3 else 0):
            speed_sq = 0.0
            for k in range(d):
                speed_sq += velocity[k, i] * velocity[k, i]
            top = max(top, speed_sq)
        top = math.sqrt(top)
        for g in range(n_rows):
            group = (n_rows, n_columns, full_rows, g, key)
            size = 0
            if grouping == 3:  # in place, against the whole gas's majorant
                size = kernels.group_size(group)
                bounds[g, :d] = 0.0
                bounds[g, d] = top
                bounds[g, d + 1] = top
            else:  # copied out in member order, against the group's own majorant
                if grouping == 0:
                    for i in range(n):
                        members[size] = i
                        size += 1
                elif grouping == 1:
                    for q in range(g * n // n_rows, (g + 1) * n // n_rows):
                        members[size] = order[q]
                        size += 1
                else:
                    for j in range(n_columns):
                        p = kernels.column_particle(j, g, shifts[j], n_rows, n_columns, full_rows)
                        if p >= 0:
                            members[size] = p
                            size += 1
                for q in range(size):
                    for k in range(d):
                        scratch[k, q] = velocity[k, members[q]]
                kernels.speed_bounds(scratch, 0, size, bounds[g])
            carry[g, 0] = rng.uniform(state)
            collisions = kernels.Collisions(
                kernels.HARD_SPHERES,
                restitution,
                pair_base / (size - 1),
                duration,
                False,
                bounds[g],
                carry[g],
                tally[g],
            )
            if grouping == 3:
                kernels.collide_members(velocity, 0, size, group, states[g], collisions)
                continue
            kernels.collide_range(scratch, 0, size, states[g], collisions)
            for q in range(size):
                for k in range(d):
                    velocity[k, members[q]] = scratch[k, q]
        mean = np.zeros(d)
        for i in range(n):
            for k in range(d):
                mean[k] += velocity[k, i] / n
        after = 0.0
        fourth = 0.0
        for i in range(n):
            c2 = 0.0
            for k in range(d):
                c2 += (velocity[k, i] - mean[k]) ** 2
            after += c2
            fourth += c2 * c2
        zeta[step] = -math.log(after / before) / duration
        kurtosis[step] = fourth * n / (after * after)
        scale = math.sqrt(before / after)
        for i in range(n):
            for k in range(d):
                velocity[k, i] = (velocity[k, i] - mean[k]) * scale
    return zeta, kurtosis, tally.sum(axis=0)


def _block_mean(values: np.ndarray, blocks: int = 40) -> tuple[float, float]:
    """Mean and standard error from ``blocks`` consecutive blocks."""
    usable = len(values) // blocks * blocks
    means = values[:usable].reshape(blocks, -1).mean(axis=1)
    return float(means.mean()), float(means.std(ddof=1) / math.sqrt(blocks))


def cooling_state(
    grouping: str,
    n_particles: int = 20_000,
    n_steps: int = 20_000,
    time_step: float = 0.1,
    restitution: float = 0.5,
    seed: int = 3,
    group_size: int = _GROUP_SIZE,
) -> dict[str, float]:
    """ζ (per τ) and a2 of the homogeneous cooling state with the collision groups of
    ``grouping`` (one of ``GROUPINGS``), each with its standard error, and the collisions."""
    settings = HomogeneousSettings(
        n_particles=n_particles, restitution=restitution, time_step=time_step, dimension=3
    )
    stream = realization_streams(seed, 0, 1)[0]
    velocity = np.ascontiguousarray(new_gas(settings, stream).velocity)
    duration = settings.time_step * settings.tau
    zeta, kurtosis, tally = _run(
        velocity,
        GROUPINGS[grouping],
        n_steps,
        settings.pair_coefficient * (n_particles - 1),
        duration,
        restitution,
        stream.copy(),
        group_size,
    )
    burn = n_steps // 10
    zeta_mean, zeta_err = _block_mean(zeta[burn:] * settings.tau)
    # d = 3: <c⁴>/<c²>² = (d + 2)/d (1 + a2)
    a2_mean, a2_err = _block_mean(kurtosis[burn:] * 3.0 / 5.0 - 1.0)
    return {
        "grouping": grouping,
        "zeta": zeta_mean,
        "zeta_err": zeta_err,
        "a2": a2_mean,
        "a2_err": a2_err,
        "collisions": int(tally[kernels.TALLY_ACCEPTED]),
    }


def main(argv: list[str] | None = None) -> None:
    argv = sys.argv[1:] if argv is None else argv
    n_particles = int(argv[0]) if argv else 20_000
    n_steps = int(argv[1]) if len(argv) > 1 else 20_000
    for grouping in GROUPINGS:
        row = cooling_state(grouping, n_particles, n_steps)
        print(
            f"{grouping:9s} zeta {row['zeta']:.6f} ± {row['zeta_err']:.6f}  "
            f"a2 {row['a2']:.5f} ± {row['a2_err']:.5f}  collisions {row['collisions']}",
            flush=True,
        )


if __name__ == "__main__":
    main()
