"""Front of the cloning Monte Carlo: validate, run the kernel in chunks, return a Dataset.

    from kinetic.cloning import simulate
    ds = simulate(kernel="hard_spheres", dimension=2, lam=1.0, population=1000,
                  duration=200.0, transient=20.0, n_realizations=4, seed=7)
    ds["mu"], ds["mu_err"]          # μ(λ) and its standard error over the realizations

Realisation k uses row k of ``kinetic.rng.stream_states(seed, ...)``, so a batch with
``first_realization = k0`` reproduces exactly the realizations k0, k0+1, ... of a single
larger call.
"""

from __future__ import annotations

import inspect
import logging
import math
import time

import numpy as np

from kinetic import backends, io
from kinetic.analysis.statistics import mean_and_sem
from kinetic.batches import REALIZATION
from kinetic.cloning import kernels
from kinetic.cloning.arguments import (
    KERNELS,
    LAMBDA_MAX,
    LAMBDA_MIN,
    MAX_TRANSIENT_BLOCKS,
    MIN_KEPT_COLLISIONS,
    validate_parameters,
)
from kinetic.cloning.estimators import realization_observables, summarize_realizations
from kinetic.cloning.rates import TABLE_STEP, rate_table
from kinetic.progress import Progress
from kinetic.rng import stream_states

__all__ = [
    "KERNELS",
    "LAMBDA_MAX",
    "LAMBDA_MIN",
    "MIN_DISTINCT_FRACTION",
    "MIN_DISTINCT_VELOCITIES",
    "MIN_KEPT_COLLISIONS",
    "is_collapsed",
    "kernel_label",
    "simulate",
    "simulate_points",
]

logger = logging.getLogger("kinetic")

MIN_DISTINCT_VELOCITIES = 10
MIN_DISTINCT_FRACTION = 0.03
"""A realization that ends with fewer distinct velocities than the larger of 10 and 3% of its
members (and than half of them), or with one, has collapsed onto a few clones (diversity
collapse, large λ): T and a2 are flagged (``diversity_collapse`` attribute). Calibration,
8 realizations of 1000 Maxwell molecules: with 10 distinct velocities (λ = 6) T came out
0.74 ± 0.08 instead of 1; with 31 (λ = 5), 1.08 ± 0.11. Hard disks at N_c = 1000: 75
distinct at λ = 3, 25 at λ = 4."""


def is_collapsed(distinct_velocities, population):
    """True if a realization ending with ``distinct_velocities`` distinct member velocities out of
    ``population`` members has collapsed onto a few clones."""
    threshold = max(MIN_DISTINCT_VELOCITIES, MIN_DISTINCT_FRACTION * population)
    # a population of fewer than 20 members is judged by half of it (below 10 members the
    # fixed threshold flagged every run, λ = 0 included, where nothing is cloned); one
    # velocity left is a collapse at any size (2 members: half of it is 1, and 1 < 1 let
    # it through)
    return bool(distinct_velocities <= 1 or distinct_velocities < min(threshold, 0.5 * population))


DRIFT_SIGMAS = 4.0
"""Standard errors between the first and second halves of a run's measured time beyond which
it is reported as still relaxing (``drift_z_mu``, ``drift_z_temperature``)."""

_CHUNK_EVENTS = 3.0e7  # events per kernel call, so progress lines come every few seconds


def kernel_label(kernel: str, dimension: int) -> str:
    """Name used in tables: ``hard_disks`` (hard spheres in d = 2), ``hard_spheres``,
    ``maxwell``."""
    if kernel == "hard_spheres" and dimension == 2:
        return "hard_disks"
    return kernel


def simulate(
    *,
    kernel: str = "hard_spheres",
    dimension: int = 2,
    lam: float,
    population: int,
    duration: float,
    transient: float,
    n_blocks: int = 20,
    n_realizations: int = 4,
    first_realization: int = 0,
    seed: int,
    histogram_half_width: float = 6.0,
    histogram_bins: int = 120,
    backend: str = "cpu",
    control_interval: float | None = None,
    label: str | None = None,
):
    """Run the cloning Monte Carlo of visco2008 §IV.A and return an ``xarray.Dataset``.

    Parameters (keyword-only; units m = 1, T0 = 1, time in mean free times 1/ω)
    ----------
    kernel : {'hard_spheres', 'maxwell'}
        Collision kernel (hard spheres are hard disks in d = 2).
    dimension : {2, 3}
    lam : float
        Tilt λ in [LAMBDA_MIN, LAMBDA_MAX].
    population : int
        Number of members N_c >= 2.
    duration : float > 0
        Measured time per realization, cut into ``n_blocks`` blocks.
    transient : float >= 0
        Discarded time per realization before measuring (rounded up to whole blocks); must let
        each member keep ``MIN_KEPT_COLLISIONS`` collisions (see that constant).
    n_blocks, n_realizations, first_realization, seed : int
        Blocks per realization; independent realizations, which use rows
        ``first_realization ...`` of ``stream_states(seed, ...)``; root seed of the streams.
    histogram_half_width, histogram_bins
        Range [-w, w) and bin count of the velocity-component histogram.
    backend : {'cpu', 'cuda'}
        ``cpu``: the continuous-time algorithm of ``kinetic.cloning.kernels``, one
        realization after the other. ``cuda``: the discrete-time algorithm of
        ``kinetic.cloning.gpu``, one GPU thread per member, all realizations in one launch;
        refused before any work where there is no GPU.
    control_interval : float, optional
        ``cuda`` only (refused with ``cpu``): longest interval between two selections
        (default ``default_control_interval(lam)``); each block is cut into whole intervals.
    label : str, optional
        Prefix of the progress lines.

    Returns a Dataset with per-block sums (dims ``realization``, ``block``), estimates
    per realization, the population's velocity-component density, and the summary
    ``mu``, ``mu_err``, ``temperature``, ``temperature_err``, ``a2``, ``a2_err``.
    """
    p = validate_parameters(
        kernel=kernel,
        dimension=dimension,
        lam=lam,
        population=population,
        duration=duration,
        transient=transient,
        n_blocks=n_blocks,
        n_realizations=n_realizations,
        first_realization=first_realization,
        seed=seed,
        histogram_half_width=histogram_half_width,
        histogram_bins=histogram_bins,
        backend=backend,
        control_interval=control_interval,
    )
    device = backends.require(p["backend"])  # before any work
    run = _Plan(p, label)
    progress = Progress(run.simulated_time, label=run.label, unit="collision times")
    if p["backend"] == "cuda":
        from kinetic.cloning.gpu import run as engine
    else:
        engine = _run_cpu
    results = engine(p, run.durations, run.n_transient, run.states, progress)
    return run.dataset(results, device)


def simulate_points(points, *, label: str | None = None):
    """Several points of the ``cuda`` backend (``simulate``'s keyword arguments each, with
    ``backend='cuda'``; one kernel, dimension, population and histogram, any λ, duration,
    transient, seeds) in the same GPU launches: up to
    ``kinetic.cloning.gpu.RESIDENT_MAX_POPULATION`` clones each realization of each point
    is one thread block of the same launch, so that small populations fill the GPU. Every
    point is validated before any work; returns a list of the datasets ``simulate`` would
    return for the points one at a time (the same numbers)."""
    defaults = {
        name: parameter.default
        for name, parameter in inspect.signature(simulate).parameters.items()
        if parameter.default is not inspect.Parameter.empty and name != "label"
    }
    checked = [validate_parameters(**(defaults | dict(point))) for point in points]
    if not checked:
        raise ValueError("simulate_points needs at least one point")
    shared = ("kernel", "dimension", "population", "histogram_bins", "histogram_half_width")
    for key in ("backend", *shared):
        values = {p[key] for p in checked}
        if len(values) > 1:
            raise ValueError(f"the points of one launch must share {key}, got {sorted(values)}")
    if checked[0]["backend"] != "cuda":
        raise ValueError("simulate_points runs the cuda backend only; use simulate on the cpu")
    backends.check_realizations("cuda", sum(p["n_realizations"] for p in checked))
    device = backends.require("cuda")  # before any work
    runs = [_Plan(p, None) for p in checked]
    text = label or f"cloning {len(runs)} points N={checked[0]['population']}"
    progress = Progress(sum(run.simulated_time for run in runs), label=text, unit="collision times")
    from kinetic.cloning.gpu import run_points

    results = run_points(
        [(run.p, run.durations, run.n_transient, run.states) for run in runs], progress
    )
    return [run.dataset(result, device) for run, result in zip(runs, results, strict=True)]


class _Plan:
    """The blocks of a validated point's run (the transient in at most
    ``MAX_TRANSIENT_BLOCKS`` blocks, never shorter than a measured block, so that a long
    transient at large λ does not inflate the output), its realizations' stream states,
    and the dataset of its results."""

    def __init__(self, p, label):
        self.p = p
        n, d = p["population"], p["dimension"]
        block_duration = p["duration"] / p["n_blocks"]
        transient_block = max(block_duration, p["transient"] / MAX_TRANSIENT_BLOCKS)
        n_transient = math.ceil(p["transient"] / transient_block - 1e-9) if p["transient"] else 0
        total_blocks = n_transient + p["n_blocks"]
        self.n_transient = n_transient
        self.durations = np.where(
            np.arange(total_blocks) < n_transient, transient_block, block_duration
        )
        first, count = p["first_realization"], p["n_realizations"]
        self.states = stream_states(p["seed"], count, first)
        self.simulated_time = count * self.durations.sum()
        self.label = label or f"cloning {kernel_label(p['kernel'], d)} lam={p['lam']:g} N={n}"

    def dataset(self, results, device):
        """The point's dataset from the engine's ``(blocks, histograms, distinct,
        cpu_seconds)``."""
        p, n, d = self.p, self.p["population"], self.p["dimension"]
        blocks, histograms, distinct, cpu_seconds = results
        measured = np.arange(self.durations.size) >= self.n_transient
        per_realization = realization_observables(blocks, measured, n, d, p["lam"])
        summary = summarize_realizations(blocks, measured, n, d, p["lam"])
        collapsed = is_collapsed(min(distinct), n)
        if collapsed:
            logger.warning(
                "[%s] diversity collapse: a realization ended with only %d distinct velocities "
                "among %d members; T and a2 describe a few clones and are not estimates of the "
                "eigenfunction, mu stays usable (biased low by r(v*) - r(0) of the surviving "
                "clone, a few 1e-3 at lam = 8)",
                self.label,
                int(min(distinct)),
                n,
            )
        dataset = _to_dataset(
            p,
            blocks,
            measured,
            self.durations,
            self.n_transient,
            histograms,
            distinct,
            cpu_seconds,
            per_realization,
            summary,
        )
        dataset.attrs["diversity_collapse"] = int(collapsed)
        dataset.attrs.update(self._drift(blocks, measured))
        dataset.attrs["device"] = device
        label = kernel_label(p["kernel"], d)
        return io.stamp(dataset, parameters={**p, "kernel_label": label}, seed=p["seed"])

    def _drift(self, blocks, measured) -> dict[str, float]:
        """``drift_z_mu``, ``drift_z_temperature``: the first half of the measured blocks
        against the second, the mean over realizations of their difference in its standard
        errors (NaN for one realization or one measured block). A population still
        relaxing when the measurement starts (a transient too short, at large λ) drifts:
        a warning beyond ``DRIFT_SIGMAS``."""
        p, n, d = self.p, self.p["population"], self.p["dimension"]
        indices = np.flatnonzero(measured)
        out = {"drift_z_mu": math.nan, "drift_z_temperature": math.nan}
        if blocks.shape[0] < 2 or indices.size < 2:
            return out
        halves = []
        for part in np.array_split(indices, 2):
            mask = np.zeros(measured.size, dtype=bool)
            mask[part] = True
            halves.append(realization_observables(blocks, mask, n, d, p["lam"]))
        for key, k in (("drift_z_mu", 0), ("drift_z_temperature", 1)):
            difference, error = mean_and_sem(halves[0][k] - halves[1][k])
            out[key] = float(difference / error) if error > 0 else 0.0
        worst = max(abs(out["drift_z_mu"]), abs(out["drift_z_temperature"]))
        if worst > DRIFT_SIGMAS:
            logger.warning(
                "[%s] the first half of the measured time differs from the second by %.1f "
                "standard errors (mu %+.1f, T %+.1f): the population may still relax after "
                "the transient of %g mean free times; a longer transient is safer",
                self.label,
                worst,
                out["drift_z_mu"],
                out["drift_z_temperature"],
                p["transient"],
            )
        return out


def _run_cpu(p, durations, n_transient, states, progress):
    """The continuous-time algorithm, one realization after the other: per-block sums
    (realization, block, field), velocity-component densities, distinct final velocities
    and process time per realization."""
    rate_factor, _, _ = kernels.compensation_parameters(p["lam"])

    count, n, d = states.shape[0], p["population"], p["dimension"]
    total_blocks = durations.size
    transient_block, block_duration = durations[0], durations[-1]
    blocks = np.zeros((count, total_blocks, len(kernels.BLOCK_FIELDS)))
    histograms = np.zeros((count, p["histogram_bins"]))
    distinct = np.zeros(count)
    cpu_seconds = np.zeros(count)
    code = KERNELS[p["kernel"]]
    table = rate_table(p["kernel"], d)
    segments = []  # (first block, end block, block duration, measured?)
    for lo, hi, duration, measured_segment in (
        (0, n_transient, transient_block, False),
        (n_transient, total_blocks, block_duration, True),
    ):
        chunk = max(1, int(_CHUNK_EVENTS / (rate_factor * n * duration * 1.5)))
        segments += [
            (start, min(start + chunk, hi), duration, measured_segment)
            for start in range(lo, hi, chunk)
        ]
    for r in range(count):
        cpu_start = time.process_time()
        state = np.ascontiguousarray(states[r])
        velocity = np.empty((d, n))
        speed = np.empty(n)
        kernels.draw_population(velocity, speed, state)
        scratch = np.zeros(p["histogram_bins"])  # transient snapshots are discarded
        weight = 0.0
        for lo, hi, duration, measured_segment in segments:
            added = kernels.run_blocks(
                code,
                p["lam"],
                velocity,
                speed,
                state,
                duration,
                kernels.Observers(
                    blocks[r, lo:hi],
                    p["histogram_half_width"],
                    histograms[r] if measured_segment else scratch,
                    table,
                    TABLE_STEP,
                ),
            )
            if measured_segment:
                weight += added
            progress.update((hi - lo) * duration)
        bin_width = 2.0 * p["histogram_half_width"] / p["histogram_bins"]
        histograms[r] /= weight * d * n * bin_width
        distinct[r] = np.unique(velocity[0]).size
        cpu_seconds[r] = time.process_time() - cpu_start

    return blocks, histograms, distinct, cpu_seconds


def _to_dataset(
    p,
    blocks,
    measured,
    durations,
    n_transient,
    histograms,
    distinct,
    cpu_seconds,
    per_realization,
    summary,
):
    field_meta = {
        "elapsed_time": ("1/omega", "time covered by the block"),
        "net_compensations": ("1", "duplications minus annihilations in the block"),
        "elastic_collisions": ("1", "kept (elastic) collisions in the block"),
        "collision_events": ("1", "collisions in the block, kept or compensated"),
        "candidates": ("1", "candidates of the uniformised chain in the block"),
        "proposals": ("1", "candidates reaching the collision acceptance test"),
        "integral_v2": ("(sqrt(T0/m))^2 / omega", "time integral of sum_i |v_i|^2"),
        "integral_v4": ("(sqrt(T0/m))^4 / omega", "time integral of sum_i |v_i|^4"),
        "integral_rate": ("1", "time integral of sum_i r(|v_i|) (collisions expected)"),
        "max_speed": ("sqrt(T0/m)", "largest speed bound used in the block"),
    }
    data_vars = {
        name: ((REALIZATION, "block"), blocks[:, :, k], *field_meta[name])
        for k, name in enumerate(kernels.BLOCK_FIELDS)
    }
    data_vars.update(
        measured=("block", measured.astype(np.int8), "1", "1 after the discarded transient"),
        velocity_density=(
            (REALIZATION, "velocity"),
            histograms,
            "1/sqrt(T0/m)",
            "time-averaged density of a velocity component of the population",
        ),
        cpu_seconds=(
            REALIZATION,
            cpu_seconds,
            "s",
            "process time of the realization, transient included (machine-dependent, not "
            "reproducible)",
        ),
        distinct_velocities=(
            REALIZATION,
            distinct,
            "1",
            "number of distinct member velocities at the end of the realization (lineages)",
        ),
        mu_per_realization=(REALIZATION, per_realization[0], "omega", "mu(lambda)"),
        temperature_per_realization=(REALIZATION, per_realization[1], "T0", "T(lambda)"),
        a2_per_realization=(REALIZATION, per_realization[2], "1", "a2(lambda)"),
        mu_rate_per_realization=(
            REALIZATION,
            per_realization[3],
            "omega",
            "(e^-lambda - 1) <r>",
        ),
        mu=((), summary["mu"], "omega", "mu(lambda): net compensation rate per member"),
        mu_err=((), summary["mu_err"], "omega", "standard error of mu"),
        temperature=(
            (),
            summary["temperature"],
            "T0",
            "T(lambda): population variance per component",
        ),
        temperature_err=((), summary["temperature_err"], "T0", "standard error of T"),
        a2=((), summary["a2"], "1", "a2(lambda): fourth-cumulant (kurtosis) coefficient"),
        a2_err=((), summary["a2_err"], "1", "standard error of a2"),
        mu_rate=(
            (),
            summary["mu_rate"],
            "omega",
            "mu(lambda) as (e^-lambda - 1) <r(v)> over the population (same mean)",
        ),
        mu_rate_err=((), summary["mu_rate_err"], "omega", "standard error of mu_rate"),
    )
    edges = np.linspace(
        -p["histogram_half_width"], p["histogram_half_width"], p["histogram_bins"] + 1
    )
    coords = {
        REALIZATION: (
            REALIZATION,
            np.arange(p["first_realization"], p["first_realization"] + p["n_realizations"]),
            "1",
            "realisation index (row of the seed's stream states)",
        ),
        "block": (
            "block",
            np.concatenate([[0.0], np.cumsum(durations)[:-1]]) - durations[:n_transient].sum(),
            "1/omega",
            "nominal start time of the block after the transient",
        ),
        "velocity": (
            "velocity",
            0.5 * (edges[1:] + edges[:-1]),
            "sqrt(T0/m)",
            "velocity component (bin centre)",
        ),
    }
    attrs = {
        "title": "cloning Monte Carlo of visco2008 section IV.A",
        "error_method": summary["error_method"],
        "block_duration": float(durations[-1]),
        "transient_block_duration": float(durations[0]),
        "units_note": "m = 1, T0 = 1, time in mean free times of the bath (omega = 1)",
    }
    return io.make_dataset(data_vars, coords, attrs)
