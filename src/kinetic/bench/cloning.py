"""Speed of the cloning Monte Carlo: collision events per CPU-second.

``python -m kinetic.bench cloning`` writes ``results/benchmarks/cloning.json``.

A collision event is an accepted collision of a member (kept, annihilating or
duplicating); thinned candidates of the uniformised chain are work, not events. The
headline case is hard disks at λ = 1 (d = 2) with N_c = 10³ and 10⁵ members; Maxwell
molecules and hard spheres in d = 3 are reported beside it. The random-number bound
is the rate the kernel would reach if drawing its uniforms were the only cost: uniforms
per event (counted from the kernel's candidate/proposal/event counters and the known
draws of each step) times the measured cost of one xoshiro256+ uniform.
"""

from __future__ import annotations

import math
import time

import numpy as np

from kinetic.bench import median_rate
from kinetic.cloning import kernels
from kinetic.cloning.rates import TABLE_STEP, rate_table
from kinetic.jit import kernel
from kinetic.rng import stream_states, uniform

__all__ = ["run"]

TARGET_EVENTS_PER_SECOND = 5.0e6
#: the tight-bound targets: hard disks at lambda = 1 and N_c = 1e3, at most this many
#: candidates of the uniformised chain per collision event ...
TARGET_CANDIDATES_PER_EVENT = 1.5
#: ... at this rate (collision events per CPU-second)
TARGET_TIGHT_EVENTS_PER_SECOND = 1.5e7
_POLAR_UNIFORMS = 2.0 * 4.0 / math.pi  # uniforms per accepted disk point (polar method)


@kernel
def _draw_uniforms(state, count):
    total = 0.0
    for _ in range(count):
        total += uniform(state)
    return total


def _seconds_per_uniform(repeats: int) -> float:
    state = stream_states(1, 1)[0]
    count = 20_000_000
    _draw_uniforms(state, 1000)
    timings = []
    for _ in range(repeats):
        start = time.process_time()
        _draw_uniforms(state, count)
        timings.append((time.process_time() - start) / count)
    return float(np.median(timings))


def _uniforms_per_event(kernel_name, dimension, totals, population_speed_mean):
    """Uniform variates drawn per event, from the block counters.

    Per candidate 1 (member and channel); per hard-sphere proposal, channel A draws
    sin θ (d = 2) or a sphere point (d = 3), half a polar normal pair and the acceptance
    uniform; channel B a disk point (d = 2) or sphere point and one uniform for u (d = 3)
    and the acceptance uniform; per event one keep/compensate uniform (if λ > 0) and per
    compensation one for the other member. Maxwell: a direction and half a normal pair per
    elastic collision.
    """
    candidates, proposals, events, elastic = (
        totals["candidates"],
        totals["proposals"],
        totals["collision_events"],
        totals["elastic_collisions"],
    )
    compensations = events - elastic
    if kernel_name == "maxwell":
        per_collision = _POLAR_UNIFORMS + 0.5 * _POLAR_UNIFORMS  # direction + normal
        draws = candidates + events + compensations + elastic * per_collision
        return draws / events
    channel_a_rate = kernels.channel_a_rate(dimension) * population_speed_mean
    fraction_a = channel_a_rate / (channel_a_rate + 1.0 / math.sqrt(2.0))
    sphere = _POLAR_UNIFORMS
    if dimension == 2:
        cost_a = 1.0 + 0.5 * _POLAR_UNIFORMS + 1.0
        cost_b = _POLAR_UNIFORMS + 1.0
    else:
        cost_a = sphere + 0.5 * _POLAR_UNIFORMS + 1.0
        cost_b = sphere + 1.0 + 1.0
    per_proposal = fraction_a * cost_a + (1.0 - fraction_a) * cost_b
    draws = candidates + proposals * per_proposal + events + compensations
    return draws / events


def _case(kernel_name, dimension, lam, population, duration, repeats, seconds_per_uniform):
    code = kernels.HARD_SPHERES if kernel_name == "hard_spheres" else kernels.MAXWELL
    table = rate_table(kernel_name, dimension)
    state = np.ascontiguousarray(stream_states(2024, 1)[0])
    velocity = np.empty((dimension, population))
    speed = np.empty(population)
    kernels.draw_population(velocity, speed, state)
    histogram = np.zeros(60)
    # relax to the tilted population first
    relax = np.zeros((1, len(kernels.BLOCK_FIELDS)))
    kernels.run_blocks(
        code,
        lam,
        velocity,
        speed,
        state,
        10.0,
        kernels.Observers(relax, 6.0, histogram, table, TABLE_STEP),
    )
    totals = dict.fromkeys(kernels.BLOCK_FIELDS, 0.0)

    def work():
        blocks = np.zeros((1, len(kernels.BLOCK_FIELDS)))
        kernels.run_blocks(
            code,
            lam,
            velocity,
            speed,
            state,
            duration,
            kernels.Observers(blocks, 6.0, histogram, table, TABLE_STEP),
        )
        for k, name in enumerate(kernels.BLOCK_FIELDS):
            totals[name] += blocks[0, k]
        return blocks[0, kernels.BLOCK_FIELDS.index("collision_events")]

    timing = median_rate(work, repeats=repeats)
    speed_mean = float(np.mean(np.sqrt((velocity**2).sum(axis=0))))
    uniforms = _uniforms_per_event(kernel_name, dimension, totals, speed_mean)
    bound = 1.0 / (uniforms * seconds_per_uniform)
    events = totals["collision_events"]
    return {
        "kernel": kernel_name,
        "dimension": dimension,
        "lambda": lam,
        "population": population,
        "events_per_cpu_second": timing["rate_per_cpu_second"],
        "events_per_wall_second": timing["rate_per_wall_second"],
        "cpu_rates": timing["cpu_rates"],
        "candidates_per_event": totals["candidates"] / events,
        "proposals_per_event": totals["proposals"] / events,
        "uniforms_per_event": uniforms,
        "random_number_bound_events_per_second": bound,
        "fraction_of_random_number_bound": timing["rate_per_cpu_second"] / bound,
        "meets_target": bool(timing["rate_per_cpu_second"] >= TARGET_EVENTS_PER_SECOND),
    }


def run(quick: bool) -> dict:
    """Time the kernels; returns the report written to results/benchmarks/cloning.json."""
    repeats = 3 if quick else 7
    seconds_per_uniform = _seconds_per_uniform(repeats)
    target_events = 2.0e6 if quick else 1.0e7
    cases = [
        ("hard_spheres", 2, 1.0, 1000),
        ("hard_spheres", 2, 1.0, 100_000),
        ("maxwell", 2, 1.0, 1000),
        ("maxwell", 2, 1.0, 100_000),
        ("hard_spheres", 3, 1.0, 1000),
        ("hard_spheres", 3, 1.0, 100_000),
        ("hard_spheres", 2, -1.5, 1000),
    ]
    results = []
    for kernel_name, dimension, lam, population in cases:
        factor, _, _ = kernels.compensation_parameters(lam)
        duration = target_events / (population * factor)
        results.append(
            _case(kernel_name, dimension, lam, population, duration, repeats, seconds_per_uniform)
        )
    headline = {
        f"hard_disks_lambda1_N{case['population']}": case["events_per_cpu_second"]
        for case in results[:2]
    }
    disks = results[0]  # hard disks, lambda = 1, N_c = 1e3
    return {
        "unit": "collision events per CPU-second (one core)",
        "target_events_per_cpu_second": TARGET_EVENTS_PER_SECOND,
        "tight_bound_targets": {
            "case": "hard disks, lambda = 1, N_c = 1000",
            "candidates_per_event_max": TARGET_CANDIDATES_PER_EVENT,
            "candidates_per_event": disks["candidates_per_event"],
            "proposals_per_event": disks["proposals_per_event"],
            "events_per_cpu_second_min": TARGET_TIGHT_EVENTS_PER_SECOND,
            "events_per_cpu_second": disks["events_per_cpu_second"],
            "candidates_met": bool(disks["candidates_per_event"] <= TARGET_CANDIDATES_PER_EVENT),
            "rate_met": bool(disks["events_per_cpu_second"] >= TARGET_TIGHT_EVENTS_PER_SECOND),
        },
        "headline": headline,
        "seconds_per_uniform": seconds_per_uniform,
        "cases": results,
    }
