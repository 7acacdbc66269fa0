"""Speed of the clothes-pin samplers of krauth2025 (``python -m kinetic.bench samplers``).

Configurations per CPU-second for direct-pin and naive-pin (N = 15 pins of width 1; lines
of length 20 and 40, the configs' values) with the pins histogrammed, and sweeps per
CPU-second of the ring's Markov chain; beside each, the random-number bound: the rate if
drawing its uniforms (N per direct-pin configuration; for naive-pin the draws of the
configurations started, counted by the kernel) were the only cost, at the measured cost of one
xoshiro256+ uniform (``kinetic.bench.cloning``'s loop).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from kinetic.bench import median_rate
from kinetic.bench.cloning import _seconds_per_uniform
from kinetic.rng import stream_states
from kinetic.samplers import kernels

__all__ = ["run"]

N_PINS = 15
SIGMA = 0.5


def _direct(length: float, samples: int, repeats: int, uniform_seconds: float) -> dict[str, Any]:
    state = stream_states(1, 1)[0]
    positions = np.zeros(N_PINS)
    histogram = np.zeros(200, dtype=np.int64)

    def work():
        kernels.direct_pin(
            N_PINS, length, SIGMA, samples, state, positions, histogram, SIGMA, length - SIGMA
        )
        return samples

    timing = median_rate(work, repeats=repeats)
    bound = 1.0 / (N_PINS * uniform_seconds)
    return {
        "length": length,
        "configurations_per_cpu_second": timing["rate_per_cpu_second"],
        "ns_per_configuration": 1e9 / timing["rate_per_cpu_second"],
        "random_number_bound_per_second": bound,
        "measured_over_bound": timing["rate_per_cpu_second"] / bound,
        "repeat_rates": timing["cpu_rates"],
    }


def _naive(length: float, samples: int, repeats: int, uniform_seconds: float) -> dict[str, Any]:
    state = stream_states(2, 1)[0]
    positions = np.zeros(N_PINS)
    histogram = np.zeros(200, dtype=np.int64)

    def work():
        kernels.naive_pin(
            N_PINS, length, SIGMA, samples, state, positions, histogram, SIGMA, length - SIGMA
        )
        return samples

    timing = median_rate(work, repeats=repeats)
    started, draws = kernels.naive_pin(
        N_PINS, length, SIGMA, samples, state, positions, histogram, SIGMA, length - SIGMA
    )
    bound = samples / (draws * uniform_seconds)
    return {
        "length": length,
        "configurations_per_cpu_second": timing["rate_per_cpu_second"],
        "started_per_configuration": started / samples,
        "uniforms_per_configuration": draws / samples,
        "started_per_cpu_second": timing["rate_per_cpu_second"] * started / samples,
        "random_number_bound_per_second": bound,
        "measured_over_bound": timing["rate_per_cpu_second"] / bound,
        "repeat_rates": timing["cpu_rates"],
    }


def _ring(sweeps: int, repeats: int) -> dict[str, Any]:
    state = stream_states(3, 1)[0]
    length = 20.0
    positions = np.arange(N_PINS) * (length / N_PINS)
    histogram = np.zeros(200, dtype=np.int64)

    def work():
        kernels.ring_markov(N_PINS, length, SIGMA, 0.5, sweeps, 0, state, positions, histogram)
        return sweeps

    timing = median_rate(work, repeats=repeats)
    return {
        "length": length,
        "sweeps_per_cpu_second": timing["rate_per_cpu_second"],
        "ns_per_attempted_move": 1e9 / (timing["rate_per_cpu_second"] * N_PINS),
        "repeat_rates": timing["cpu_rates"],
    }


def run(quick: bool) -> dict[str, Any]:
    """Benchmark report (see the module docstring); ``quick`` runs fewer repeats."""
    repeats = 3 if quick else 7
    uniform_seconds = _seconds_per_uniform(repeats)
    return {
        "description": __doc__.strip().splitlines()[0],
        "units": "configurations or sweeps per CPU-second (process time, one core)",
        "n_pins": N_PINS,
        "pin_width": 2 * SIGMA,
        "seconds_per_uniform": uniform_seconds,
        "direct_pin": [
            _direct(length, 500_000, repeats, uniform_seconds) for length in (20.0, 40.0)
        ],
        "naive_pin": [_naive(40.0, 2_000, repeats, uniform_seconds)],
        "ring_markov": _ring(50_000, repeats),
    }
