"""Speed and physics of the ``cuda`` backends on one GPU: ``python -m kinetic.bench cuda``
writes ``results/benchmarks/cuda.json``.

It needs a GPU (``kinetic.backends.require('cuda')``; the command refuses numba's CUDA
simulator, ``precondition``); every section is timed through the
engines' fronts (``backend='cuda'``), so launches, seeding and copies count, and compile
time is excluded by a first call of the same types. The report is rewritten after every
section (a run stopped at a time limit keeps what it measured).

Cloning (visco2008 §IV.A): collision events per second of the untilted clones (ΣK_i) at
N_c = 10³, 10⁴, 10⁵, 10⁶ (hard disks at λ = 1 and -1, Maxwell molecules at λ = 1; N_c = 10³
also with 100 realizations in one launch), each on the path the engine picks (``path``:
the resident kernel up to ``RESIDENT_MAX_POPULATION`` clones, three launches per control
interval above), both paths at the paper config's shape (32 realizations of 10³ and 10⁴
clones: ``paths``), against the CPU engine on one core of the same machine; then the
physics: Maxwell μ(λ) = e^{-λ} - 1 at every λ of the paper config's Fig. 4, hard-disk
μ(1) extrapolated in 1/N_c against the Eq. 28 reference, T and a2 at N_c = 10³ against the
CPU engine, and the bias of μ(1) in the control interval Δ.

Job startup (``job_startup``): a small job of each GPU module in a fresh process,
three times over one empty numba cache directory (compiling, then loading the kernels),
with the numbers compared.

DSMC (montanero2007): collisions per second of the homogeneous engine at N = 2 × 10⁵
with 50 realizations in one launch, against the CPU engine on one core, and the HCS
cooling rate and a2 against the CPU engine (``dsmc_speed``); accepted collisions per
second at α = 1 and 0.5 for N = 2 × 10⁵ × 100, 2 × 10⁶ × 10, 2 × 10⁷ × 1, a snapshot
every 10 steps (``dsmc_scaling``); the same shapes at α = 1 with the velocities stored
either way (``kinetic.dsmc.gpu.STORAGE``: ``dsmc_storage``); one montanero2007 job of
paper.yaml (α = 0.3, N = 2 × 10⁵, δt = 0.003, 60 τ, 200 realizations) timed on the GPU
for 25 of its realizations and on one CPU core for one realization over a tenth of the
duration, both scaled to the whole job (``dsmc_paper_job``).

Memory bound (``memory_bound``): the GPU's coalesced copy bandwidth, and each pass
of the homogeneous DSMC's step (collisions, force, thermostat) launched alone at
montanero2007's paper settings, with its bytes per second; the step's time against the
time its least DRAM traffic (``SPARSE_PASS_BYTES``: 48 bytes a particle) takes at that
bandwidth (``sparse``).

Inhomogeneous DSMC (costantini2010, ``inhomogeneous_speed``): particle-steps and
collisions per second of ``simulate_cooling_modes(backend="cuda")`` at N = 3000 × Λ = 10
with 100 realizations in one batch and at N = 3 × 10⁶ (Λ = 1, one realization), both
collision rules, at the paper config's density (nσ² = 0.005), cells of 0.5 λ and a step of
0.025 mean free times, α = 0.8 with the drag ω0 = ζ(T0)/2; the same cases, shorter, on one
CPU core for the ratio; and the paper config's job shape (16 realizations, a sample every
4 steps) on both GPU paths: the steps between samples in one cooperative launch, and five
launches a step (``paths``); the six α of a grouped paper job in one batch (``grouped``).
Its bound (``inhomogeneous_bound``): each of the five phases of a step timed alone at the
grouped job's shape, with its bytes per second (``PHASE_BYTES``, 192 bytes a
particle-step), the cost of an empty launch, and the step on both paths against the
bandwidth bound.
"""

from __future__ import annotations

import ast
import contextlib
import math
import os
import time
import traceback
from collections.abc import Callable
from typing import Any
from unittest import mock

import numpy as np

__all__ = ["run"]

_BUDGET_SECONDS = float(os.environ.get("KINETIC_BENCH_BUDGET", "420"))
"""Sections not started after this many seconds are skipped (device leases are short)."""


_PARTIAL: dict[str, Any] = {}
"""The containers of the section that is running, registered by ``_keep`` as they are made
and filled in place: a section that fails keeps in its report (``partial``) what it had
measured before the failure."""


def _keep(**containers) -> None:
    """Register a running section's lists and dicts under the names of its report."""
    _PARTIAL.update(containers)


def precondition() -> None:
    """Refuse the simulator before anything runs (``python -m kinetic.bench cuda`` calls this):
    under ``NUMBA_ENABLE_CUDASIM=1`` the kernels run as Python on the CPU, and a report of
    its rates would read as a GPU's. The tests call ``run`` directly, under the simulator."""
    from kinetic.backends import BackendUnavailable, simulated

    if simulated():
        raise BackendUnavailable(
            "bench cuda times a GPU, but NUMBA_ENABLE_CUDASIM=1 runs the kernels as Python on "
            "the CPU; unset it and run on a machine with an NVIDIA GPU"
        )


def _device() -> dict[str, Any]:
    import logging

    import numba

    logging.getLogger("numba").setLevel(logging.WARNING)  # numba-cuda's allocation log
    from kinetic import backends, gpu

    info = {
        "device": backends.require("cuda"),
        "simulated": backends.simulated(),
        "numba": numba.__version__,
    }
    try:
        from importlib.metadata import version

        info["numba_cuda"] = version("numba-cuda")
    except Exception:  # pragma: no cover - metadata missing on a copied tree
        info["numba_cuda"] = "unknown"
    info["numpy"] = np.__version__
    info["block_threads"] = gpu.BLOCK
    return info


_CLONING_BLOCKS = 10
"""Measured blocks of every bench cloning point."""


def _cloning_arguments(kernel, lam, population, duration, realizations, backend, seed, **extra):
    """``kinetic.cloning.simulate``'s arguments for a bench point (d = 2, a transient of
    2 e^λ mean free times, at least 4, ten blocks)."""
    return {
        "kernel": kernel,
        "dimension": 2,
        "lam": lam,
        "population": population,
        "duration": duration,
        "transient": max(4.0, 2.0 * math.exp(lam)),
        "n_blocks": _CLONING_BLOCKS,
        "n_realizations": realizations,
        "seed": seed,
        "backend": backend,
        **extra,
    }


def _cloning(
    kernel, lam, population, duration, realizations=1, backend="cuda", seed=1, **extra
) -> dict[str, Any]:
    from kinetic.cloning import simulate

    arguments = _cloning_arguments(
        kernel, lam, population, duration, realizations, backend, seed, **extra
    )
    start = time.perf_counter()
    ds = simulate(**arguments)
    wall = time.perf_counter() - start
    elapsed = float(ds.elapsed_time.isel(realization=0).sum())
    interval = ds.attrs.get("control_interval")
    events = float(ds.elastic_collisions.sum()) if backend == "cuda" else None
    if backend == "cpu":
        events = float(ds.collision_events.sum())
    # the engine's clock (cuda: the launches and the GPU; cpu: process time), without the
    # host's initial populations, the count of distinct clones (a sort of the final
    # population) and the dataset, which at 10⁶ clones over 100 mean free times are a
    # good part of the wall time
    engine = float(ds.cpu_seconds.sum())
    return {
        "kernel": kernel,
        "lambda": lam,
        "population": population,
        "realizations": realizations,
        "duration": duration,
        "control_interval": interval,
        "wall_seconds": wall,
        "seconds_per_interval": wall / (elapsed / interval) if interval else None,
        "events": events,
        "events_per_second": events / wall,
        "engine_seconds": engine,
        "engine_events_per_second": events / engine if engine > 0 else None,
        "mu": float(ds.mu),
        "mu_err": float(ds.mu_err),
        "temperature": float(ds.temperature),
        "temperature_err": float(ds.temperature_err),
        "a2": float(ds.a2),
        "a2_err": float(ds.a2_err),
    }


@contextlib.contextmanager
def _cloning_path(resident: bool):
    """Force the cuda cloning backend's resident kernel (one thread block per realization)
    or its three launches per control interval, whatever the population."""
    from kinetic.cloning import gpu

    saved = gpu.RESIDENT_MAX_POPULATION
    gpu.RESIDENT_MAX_POPULATION = 2**62 if resident else 0
    try:
        yield
    finally:
        gpu.RESIDENT_MAX_POPULATION = saved


def _median_run(*arguments, **keywords) -> dict[str, Any]:
    """The median of three seeds' runs by events per second, with all three rates."""
    runs = [_cloning(*arguments, **keywords, seed=s) for s in range(3)]
    best = sorted(runs, key=lambda r: r["events_per_second"])[1]
    return best | {"rates": [r["events_per_second"] for r in runs]}


def _kernel_resources(kernel) -> dict[str, Any]:
    """Registers per thread and the most threads a block can have, of a kernel's compiled
    variant (its first, on the current device): what decides how many of its thread
    blocks a multiprocessor holds at once."""
    out: dict[str, Any] = {}
    for key, method in (
        ("registers_per_thread", "get_regs_per_thread"),
        ("max_threads_per_block", "get_max_threads_per_block"),
        ("shared_memory_bytes", "get_shared_mem_per_block"),
    ):
        try:
            value = getattr(kernel, method)()
        except Exception as error:  # the simulator has none of them
            out[key] = f"unavailable: {error}"
            continue
        out[key] = next(iter(value.values())) if isinstance(value, dict) else value
    return out


def _cloning_grouped(population: int, duration: float, realizations: int = 32) -> dict[str, Any]:
    """The shape of a grouped paper job (``simulate_points``): every hard-disk λ of
    paper.yaml's Fig. 3 × ``realizations`` of ``population`` clones in the same launches
    (resident up to ``RESIDENT_MAX_POPULATION`` clones, launched above), each point
    ``duration`` long after its transient. Events per second over the job, and the wall
    time ``kinetic.cost.cloning_points`` plans for it (startup excluded)."""
    from kinetic import cost
    from kinetic.cloning import gpu, simulate_points

    lambdas = _paper_lambdas("hard_disks")
    points = [
        _cloning_arguments("hard_spheres", lam, population, duration, realizations, "cuda", 100 + k)
        for k, lam in enumerate(lambdas)
    ]
    start = time.perf_counter()
    datasets = simulate_points(points)
    wall = time.perf_counter() - start
    events = float(sum(ds.elastic_collisions.sum() for ds in datasets))
    planned = cost.cloning_points(points).cpu_seconds - cost.GPU_JOB_STARTUP_SECONDS
    resident = population <= gpu.RESIDENT_MAX_POPULATION
    return {
        "kernel": "hard_spheres",
        "population": population,
        "points": len(points),
        "realizations": realizations * len(points),
        "duration": duration,
        "path": "grouped" if resident else "grouped_launched",
        "wall_seconds": wall,
        "planned_seconds": planned,
        "events": events,
        "events_per_second": events / wall,
    }


def cloning_speed(quick: bool) -> dict[str, Any]:
    """Events per second against N_c (each population on the engine's own path), the
    resident kernel against the three launches per interval at the paper config's
    populations, the resident kernel's thread count (``RESIDENT_THREADS`` = 128 to 1024:
    32 realizations of 10³ and 10⁴ clones, and a grouped paper job's shape of 41 λ × 32
    realizations of 10³ clones: ``resident_threads``), and the CPU engine on one core."""
    from kinetic.cloning import gpu

    for resident in (True, False):  # compile both paths (same types as every case)
        with _cloning_path(resident):
            _cloning("hard_spheres", 1.0, 256, 4.0, 2)
    _cloning("hard_spheres", 1.0, 256, 4.0, 2, backend="cpu")
    cases = []
    _keep(gpu=cases)
    sizes = [
        (1000, 1, 100.0),  # one realization: blocks of 10 (MIN_SINGLE_REALIZATION_BLOCK)
        (1000, 100, 100.0),
        (10_000, 32, 100.0),
        (100_000, 1, 100.0),
        (1_000_000, 1, 100.0),
    ]
    for kernel, lam in (("hard_spheres", 1.0), ("hard_spheres", -1.0), ("maxwell", 1.0)):
        for population, realizations, duration in sizes[: 2 if quick else None]:
            case = _median_run(kernel, lam, population, duration, realizations)
            resident = population <= gpu.RESIDENT_MAX_POPULATION
            cases.append(case | {"path": "resident" if resident else "launched"})
    paths = []
    _keep(paths=paths)
    for population, duration in ((1000, 2000.0), (10_000, 200.0))[: 1 if quick else None]:
        for resident in (True, False):
            with _cloning_path(resident):
                case = _median_run("hard_spheres", 1.0, population, duration, 32)
            paths.append(case | {"path": "resident" if resident else "launched"})
    # a grouped job of 10⁴ clones (paper.yaml's largest): the launched path's rows shared
    paths.append(_cloning_grouped(10_000, 2.0 if quick else 10.0))
    threads = []
    kernel = _kernel_resources(gpu._resident)
    _keep(resident_threads=threads, resident_kernel=kernel)
    for count in (128, 256, 512, 1024)[: 2 if quick else None]:
        limit = kernel.get("max_threads_per_block")
        if isinstance(limit, int) and count > limit:
            threads.append({"threads": count, "skipped": "more than the kernel can launch"})
            continue
        with _cloning_path(True), mock.patch.object(gpu, "RESIDENT_THREADS", count):
            for population, duration in ((1000, 2000.0), (10_000, 200.0))[: 1 if quick else None]:
                case = _median_run("hard_spheres", 1.0, population, duration, 32)
                threads.append(case | {"path": "resident", "threads": count})
            threads.append(_cloning_grouped(1000, 10 if quick else 100) | {"threads": count})
    cpu = [_cloning("hard_spheres", 1.0, 1000, 2000.0, 1, backend="cpu", seed=s) for s in range(3)]
    cpu_rate = float(np.median([r["events_per_second"] for r in cpu]))
    for case in cases + paths + threads:
        if "events_per_second" in case:  # not the thread counts the kernel cannot launch
            case["speedup_over_one_core"] = case["events_per_second"] / cpu_rate
    return {
        "gpu": cases,
        "paths": paths,
        "resident_threads": threads,
        "resident_kernel": kernel,
        "resident_max_population": gpu.RESIDENT_MAX_POPULATION,
        "cpu_one_core_events_per_second": cpu_rate,
        "cpu_runs": cpu,
    }


def _paper_config() -> dict[str, Any]:
    """config/paper.yaml of the repository, validated with the schema's defaults."""
    from pathlib import Path

    from kinetic.config import load_configs

    return load_configs([Path(__file__).resolve().parents[3] / "config" / "paper.yaml"])


def _paper_lambdas(kernel: str) -> list[float]:
    """The counting fields of the paper config's cloning figures for ``kernel``."""
    return list(_paper_config()["visco2008"]["cloning"]["kernels"][kernel]["lambdas"])


def _paper_restitutions() -> tuple[float, ...]:
    """paper.yaml's costantini2010 restitutions: the runs of one
    ``costantini2010_simulate_dsmc_grid_n<N>`` job."""
    return tuple(float(alpha) for alpha in _paper_config()["costantini2010"]["restitutions"])


def _z_score(difference: float, error: float) -> float | None:
    """``difference / error``; 0 where both are 0 (Maxwell molecules at λ = 0: every clone
    has the same weight, μ = 0 exactly with no spread), None where only the error is."""
    if error > 0.0:
        return difference / error
    return 0.0 if difference == 0.0 else None


def cloning_physics(quick: bool) -> dict[str, Any]:
    """Maxwell exactness, hard-disk μ(1) extrapolated, T/a2 against the CPU engine, Δ bias.

    Maxwell molecules: μ(λ) = e^{-λ} - 1 at every λ of the paper's figure, 32
    realizations of 10⁴ clones each, a seed of its own a λ (with one seed for all λ,
    neighbouring λ shared their random numbers and so their deviations: on the H200 run
    of 5a93630, 10 realizations each, λ = 3 to 4.5 all came out 0.6-1.3 × 10⁻³ high), and
    ``maxwell_chi2``, Σz² over them against its degrees of freedom (the λ with an error):
    ``chi2`` with each λ's error from its 32 realizations, ``chi2_expected`` with the
    estimator's own bias and error at that N_c and Δ
    (``theory.visco2008.poisson_cloning_estimator``: exact errors, and the bias, 1.8 to
    7.5 × 10⁻⁴ at λ ≤ -1, taken out; on the H100 of b66ff5b: 38.3 and 33.3 for 24)."""
    from kinetic.cloning import extrapolate_population
    from kinetic.theory.visco2008 import poisson_cloning_estimator
    from kinetic.theory.visco2008_exact import reference_solution

    out: dict[str, Any] = {}
    maxwell = []
    _keep(maxwell_mu=maxwell, results=out)
    population, duration, realizations = 10_000, 40.0, 32
    for k, lam in enumerate(_paper_lambdas("maxwell")[:: 4 if quick else 1]):
        r = _cloning("maxwell", lam, population, duration, realizations, seed=7 + k)
        exact = math.expm1(-lam)
        block = duration / _CLONING_BLOCKS  # each cut into intervals of at most Δ
        interval = block / math.ceil(block / r["control_interval"] - 1e-9)
        bias, spread = poisson_cloning_estimator(lam, population, interval, duration)
        expected = float(spread) / math.sqrt(realizations)
        maxwell.append(
            r
            | {
                "exact": exact,
                "z": _z_score(r["mu"] - exact, r["mu_err"]),
                "expected_bias": float(bias),
                "expected_error": expected,
                "z_expected": _z_score(r["mu"] - exact - float(bias), expected),
            }
        )
    out["maxwell_mu"] = maxwell
    scores = [r["z"] for r in maxwell if r["mu_err"] > 0 and r["z"] is not None]
    expected = [r["z_expected"] for r in maxwell if r["expected_error"] > 0]
    out["maxwell_chi2"] = {
        "chi2": float(sum(z * z for z in scores)),
        "dof": len(scores),
        "chi2_expected": float(sum(z * z for z in expected)),
        "dof_expected": len(expected),
    }
    points = [(1000, 64), (10_000, 16), (100_000, 8), (1_000_000, 4)]
    disks = [_cloning("hard_spheres", 1.0, n, 100.0, r, seed=11) for n, r in points]
    fit = extrapolate_population(
        [d["population"] for d in disks], [d["mu"] for d in disks], [d["mu_err"] for d in disks]
    )
    reference = reference_solution([1.0], 2)
    out["hard_disks_mu_1"] = {
        "points": disks,
        "extrapolation": fit._asdict(),
        "reference_mu": float(reference[0][0]),
        "reference_temperature": float(reference[1][0]),
        "reference_a2": float(reference[2][0]),
        "difference": fit.intercept - float(reference[0][0]),
    }
    gpu = _cloning("hard_spheres", 1.0, 1000, 400.0, 64, seed=13)
    cpu = _cloning("hard_spheres", 1.0, 1000, 400.0, 8, backend="cpu", seed=13)
    out["hard_disks_n1000_gpu_vs_cpu"] = {"gpu": gpu, "cpu": cpu}
    bias = []
    _keep(control_interval_study=bias)
    for interval in (0.1, 0.25, 0.5, 1.0, 2.0):
        bias.append(
            _cloning("hard_spheres", 1.0, 1000, 200.0, 64, seed=17, control_interval=interval)
        )
    out["control_interval_study"] = bias
    return out


def _dsmc(n, realizations, duration, backend, seed=13, **extra) -> dict[str, Any]:
    """One montanero2007-like run: d = 3 hard spheres, α = 0.9, Strang splitting and the
    exact force step at δt = 0.1 τ (zero field: the HCS)."""
    from kinetic.dsmc import simulate_homogeneous

    arguments = {
        "n_particles": n,
        "n_realizations": realizations,
        "restitution": 0.9,
        "reduced_field": 0.0,
        "time_step": 0.1,
        "duration": duration,
        "sample_interval": duration / 10,
        "sample_stride": 1,
        "splitting": "strang",
        "force_step": "exact",
        "seed": seed,
        "backend": backend,
        **extra,
    }
    start = time.perf_counter()
    ds = simulate_homogeneous(**arguments)
    wall = time.perf_counter() - start
    steady = ds.isel(time=slice(ds.sizes["time"] // 2, None))
    zeta = steady.cooling_rate.mean("time")
    a2 = steady.a2.mean("time")
    flux = steady.heat_flux.mean("time")
    collisions = float(ds.collisions.sum())
    # the engine's clock: the steps' launches and the GPU (on the CPU, the realizations'
    # process time), without the host's Maxwellian starts and the dataset, which a run of
    # a few hundred steps spends as long on as on its steps (paper jobs: 2 × 10⁴ steps)
    engine = float(ds.cpu_seconds.sum())
    particle_steps = n * realizations * duration / arguments["time_step"]
    sem = realizations**0.5
    return {
        "n_particles": n,
        "realizations": realizations,
        "restitution": arguments["restitution"],
        "backend": backend,
        "storage": _storage() if backend == "cuda" else None,
        "regrouping": ds.attrs.get("collision_groups"),
        "reduced_field": arguments["reduced_field"],
        "sample_stride": arguments["sample_stride"],
        "splitting": arguments["splitting"],
        "force_step": arguments["force_step"],
        "time_step": arguments["time_step"],
        "wall_seconds": wall,
        "collisions": collisions,
        "acceptance": collisions / float(ds.candidates.sum()),
        "engine_seconds": engine,
        "collisions_per_second": collisions / wall,
        "particle_steps_per_second": particle_steps / wall,
        "engine_collisions_per_second": collisions / engine,
        "engine_particle_steps_per_second": particle_steps / engine,
        "cooling_rate": float(zeta.mean()),
        "cooling_rate_err": float(zeta.std(ddof=1) / sem) if realizations > 1 else None,
        "a2": float(a2.mean()),
        "a2_err": float(a2.std(ddof=1) / sem) if realizations > 1 else None,
        "heat_flux": float(flux.mean()),
        "heat_flux_err": float(flux.std(ddof=1) / sem) if realizations > 1 else None,
    }


def _storage() -> str:
    """How the homogeneous DSMC's GPU batches store their velocities now."""
    from kinetic.dsmc import gpu as dsmc_gpu

    return dsmc_gpu.STORAGE


def dsmc_storage(quick: bool) -> dict[str, Any]:
    """The homogeneous DSMC with its velocities stored by component ((R, d, N), the
    default) and by particle ((R, N, d)): ``dsmc_scaling``'s shapes (2 × 10⁷
    particle-steps a step as 100 × 2 × 10⁵, 10 × 2 × 10⁶, 1 × 2 × 10⁷) at α = 1, δt = 0.1
    τ, a snapshot every 10 steps, with Strang splitting and the exact force step, then
    the documents' Lie and Euler; the two storages one after the other on each case (the
    same process, the same seed: the same collisions, which ``same_numbers`` checks).
    ``particles_over_components``: each case's ratio of the engine-clock collision
    rates. The storage moves a candidate pair's 6 components from 6 scattered 32-byte
    sectors to 2-4; a pass over every particle moves the same bytes either way."""
    from kinetic.dsmc import gpu as dsmc_gpu

    saved = dsmc_gpu.STORAGE
    lie = {"splitting": "lie", "force_step": "euler"}
    cases: list[dict[str, Any]] = []
    ratios: list[dict[str, Any]] = []
    _keep(gpu=cases, particles_over_components=ratios)
    try:
        for storage in dsmc_gpu._STORAGES:  # a tiny run of each: each storage has its
            dsmc_gpu.STORAGE = storage  # own compiled copy of the kernels over particles
            _dsmc(2000, 2, 1.0, "cuda", restitution=1.0)
        for scheme in ({}, lie):
            for n, realizations in SCALING_SHAPES[: 1 if quick else None]:
                pair = {}
                for storage in dsmc_gpu._STORAGES:
                    dsmc_gpu.STORAGE = storage
                    pair[storage] = _dsmc(
                        n, realizations, 10.0, "cuda", restitution=1.0, sample_stride=10, **scheme
                    )
                    cases.append(pair[storage])
                by_component, by_particle = pair["components"], pair["particles"]
                ratios.append(
                    {
                        "n_particles": n,
                        "realizations": realizations,
                        "splitting": by_component["splitting"],
                        "ratio": by_particle["engine_collisions_per_second"]
                        / by_component["engine_collisions_per_second"],
                        "same_numbers": by_particle["collisions"] == by_component["collisions"]
                        and by_particle["cooling_rate"] == by_component["cooling_rate"],
                    }
                )
    finally:
        dsmc_gpu.STORAGE = saved
    return {
        "gpu": cases,
        "particles_over_components": ratios,
        "registers_per_thread": _registers_by_storage(dsmc_gpu),
    }


def _registers_by_storage(dsmc_gpu) -> dict[str, Any]:
    """Registers a thread of the homogeneous DSMC's kernels over particles, the copy for
    each storage (``_BY_PARTICLE``), as this GPU's compiler made them."""
    out: dict[str, Any] = {}
    for name in ("_collide_sparse", "_force", "_observe"):
        out[name] = {}
        for storage, kernel in getattr(dsmc_gpu, name).items():
            try:
                registers = kernel.get_regs_per_thread()
            except Exception as error:  # the simulator has none
                registers = f"unavailable: {error}"
            if isinstance(registers, dict):  # one compiled signature: its count
                registers = next(iter(registers.values()), None)
            out[name][storage] = registers
    return out


def dsmc_speed(quick: bool) -> dict[str, Any]:
    """Homogeneous DSMC: collisions per second at N = 2 × 10⁵ × 50 realizations (and one
    realization, and 2 × 10⁶ × 5), the CPU engine on one core, and the HCS cooling rate and
    a2 (α = 0.9) and the heat flux at ε* = 0.025 on the GPU (each case names its
    ``regrouping``, the dataset's ``collision_groups``)."""
    _dsmc(2000, 2, 1.0, "cuda")  # compile
    gpu: list[dict[str, Any]] = []
    physics: dict[str, Any] = {}
    _keep(gpu=gpu, physics=physics)
    gpu += [_dsmc(200_000, 50, 20.0, "cuda", seed=s) for s in range(2)]
    gpu += [_dsmc(200_000, 1, 20.0, "cuda"), _dsmc(2_000_000, 5, 20.0, "cuda")]
    _dsmc(2000, 1, 1.0, "cpu")
    cpu = _dsmc(200_000, 1, 2.0, "cpu")
    physics["hcs"] = _dsmc(20_000, 16, 60.0, "cuda", seed=21)
    physics["forced"] = _dsmc(20_000, 48, 60.0, "cuda", seed=22, reduced_field=0.025)
    for case in gpu:
        case["speedup_over_one_core"] = case["collisions_per_second"] / cpu["collisions_per_second"]
        case["engine_speedup_over_one_core"] = (
            case["engine_collisions_per_second"] / cpu["engine_collisions_per_second"]
        )
    return {"gpu": gpu, "cpu_one_core": cpu, "physics": physics}


def _cooling_points(
    n, fictive, realizations, steps, backend, rule, seed=17, samples=10, alphas=(0.8,)
) -> list[dict[str, Any]]:
    """The keyword arguments of a costantini2010-like run for each of ``alphas`` (paper
    density nσ² = 0.005, cells of 0.5 λ, a step of 0.025 mean free times, the drag ω0 =
    ζ(T0)/2): ``steps`` steps, a sample every steps/samples, seeds ``seed``, ``seed`` + 1,
    ..."""
    from kinetic.theory.costantini2010 import zeta_star

    density = 0.005
    mean_free_time = 1.0 / (2.0 * density * math.sqrt(math.pi))
    mean_free_path = 1.0 / (2.0 * math.sqrt(2.0) * density)
    time_step = 0.025 * mean_free_time
    cells = max(1, round(math.sqrt(n / density) / (0.5 * mean_free_path)))
    stride = max(1, steps // samples)
    return [
        {
            "n_particles": n,
            "density": density,
            "restitution": restitution,
            "drag_rate": 0.5 * float(zeta_star(restitution)) * density * math.sqrt(2.0),
            "equilibration": 0.0,
            "sample_interval": stride * time_step,
            "n_samples": steps // stride + 1,
            "seed": seed + k,
            "fictive_factor": fictive,
            "cells_per_side": cells,
            "time_step": time_step,
            "collision_rule": rule,
            "n_realizations": realizations,
            "backend": backend,
        }
        for k, restitution in enumerate(alphas)
    ]


def _inhomogeneous(
    n, fictive, realizations, steps, backend, rule, seed=17, samples=10, alphas=(0.8,)
) -> dict[str, Any]:
    """One costantini2010-like run of the inhomogeneous DSMC (``_cooling_points``): with
    several ``alphas``, a run of ``realizations`` for each, all in the same launches
    (``simulate_cooling_modes_points``). The rates divide by the kernels' time
    (``cpu_seconds``: on the GPU the batch's wall time, launches and device included,
    compilation and the initial states excluded; on the CPU the process time)."""
    import xarray as xr

    from kinetic.dsmc import simulate_cooling_modes, simulate_cooling_modes_points

    points = _cooling_points(n, fictive, realizations, steps, backend, rule, seed, samples, alphas)
    cells = points[0]["cells_per_side"]
    start = time.perf_counter()
    if len(points) > 1:
        ds = xr.concat(simulate_cooling_modes_points(points), "realization")
    else:
        ds = simulate_cooling_modes(**points[0])
    wall = time.perf_counter() - start
    kernel_seconds = float(ds.cpu_seconds.sum())
    particle_steps = float(ds.particle_steps.sum())
    collisions = float(ds.collisions.sum())
    amplitude = (ds.mode_real**2 + ds.mode_imag**2) / ds.mode_norm
    return {
        "n_particles": n,
        "fictive_factor": fictive,
        "simulated_particles": n * fictive,
        "cells_per_side": cells,
        "realizations": realizations * len(alphas),
        "restitutions": list(alphas),
        "collision_rule": rule,
        "backend": backend,
        "steps": int(ds.particle_steps.values[0]) // (n * fictive),
        "wall_seconds": wall,
        "kernel_seconds": kernel_seconds,
        "particle_steps": particle_steps,
        "collisions": collisions,
        "particle_steps_per_second": particle_steps / kernel_seconds,
        "collisions_per_second": collisions / kernel_seconds,
        "collisions_per_particle_step": collisions / particle_steps,
        "repeated_fraction": float(ds.repeated_collisions.sum()) / max(collisions, 1.0),
        "final_temperature": float(ds.temperature.isel(time=-1).mean()),
        "mode_amplitude": float(amplitude.isel(time=slice(1, None)).mean()),
        "max_momentum": float(abs(ds.momentum).max()),
    }


def _inhomogeneous_path(together: bool):
    """Force the cuda inhomogeneous DSMC's cooperative launch per sample interval or its
    five launches a step (a context manager)."""
    from kinetic.dsmc import inhomogeneous_gpu

    return mock.patch.object(inhomogeneous_gpu, "TOGETHER", together)


def inhomogeneous_speed(quick: bool) -> dict[str, Any]:
    """Inhomogeneous DSMC: particle-steps and collisions per second at N = 3000 × Λ = 10
    × 100 realizations and N = 3 × 10⁶ × Λ = 1, both rules, on the GPU and on one CPU
    core (shorter runs), and the ratio; then the paper config's job shape (16 realizations
    of 3000 × Λ = 10, a sample every 4 steps) with the steps between samples in one
    cooperative launch and with five launches a step (``paths``), and the six α of a
    paper config's grouped job in one batch (``grouped``: 96 realizations)."""
    from kinetic.dsmc import inhomogeneous_gpu

    scale = 10 if quick else 1
    for together in (True, False):  # compile both paths (the front's own tiny batch)
        with _inhomogeneous_path(together):
            _inhomogeneous(3000, 10, 2, 20, "cuda", "paper")
    _inhomogeneous(300, 1, 1, 4, "cpu", "paper")
    gpu, cpu = [], []
    _keep(gpu=gpu, cpu_one_core=cpu)
    for rule in ("paper", "majorant"):
        gpu.append(_inhomogeneous(3000, 10, 100, 2000 // scale, "cuda", rule))
        gpu.append(_inhomogeneous(3_000_000, 1, 1, 1000 // scale, "cuda", rule))
        cpu.append(_inhomogeneous(3000, 10, 1, 400 // scale, "cpu", rule))
        cpu.append(_inhomogeneous(3_000_000, 1, 1, 10 // scale, "cpu", rule))
    for case in gpu:
        same = next(
            c
            for c in cpu
            if c["n_particles"] == case["n_particles"]
            and c["collision_rule"] == case["collision_rule"]
        )
        case["speedup_over_one_core"] = (
            case["particle_steps_per_second"] / same["particle_steps_per_second"]
        )
        case["path"] = "together" if inhomogeneous_gpu.TOGETHER else "launched"
    paths = []
    _keep(paths=paths)
    for together in (True, False):
        with _inhomogeneous_path(together):
            steps = 4000 // scale
            case = _inhomogeneous(3000, 10, 16, steps, "cuda", "paper", samples=steps // 4)
        case["path"] = "together" if together else "launched"
        case["seconds_per_step"] = case["kernel_seconds"] / case["steps"]
        paths.append(case)
    steps = 4000 // scale  # the six α of N = 3000 in one batch, as a grouped paper job
    grouped = _inhomogeneous(
        3000, 10, 16, steps, "cuda", "paper", samples=steps // 4, alphas=_paper_restitutions()
    )
    grouped["path"] = "together" if inhomogeneous_gpu.TOGETHER else "launched"
    grouped["seconds_per_step"] = grouped["kernel_seconds"] / grouped["steps"]
    return {"gpu": gpu, "cpu_one_core": cpu, "paths": paths, "grouped": grouped}


SCALING_SHAPES = [(200_000, 100), (2_000_000, 10), (20_000_000, 1)]
"""(N, realizations) of ``dsmc_scaling`` and ``dsmc_storage``: 2 × 10⁷ particles a step
each."""


def _dsmc_median(repeats: int, *arguments, **keywords) -> dict[str, Any]:
    """``_dsmc`` with seeds 13, 14, ... ``repeats`` times: the run of the median engine rate,
    with every run's ``engine_rates`` (one run: itself, with its one rate)."""
    runs = [_dsmc(*arguments, **keywords, seed=13 + k) for k in range(repeats)]
    median = sorted(runs, key=lambda run: run["engine_collisions_per_second"])[repeats // 2]
    return median | {"engine_rates": [run["engine_collisions_per_second"] for run in runs]}


def dsmc_scaling(quick: bool) -> dict[str, Any]:
    """Homogeneous DSMC at α = 1 and 0.5: accepted collisions per second at the same
    particle-steps (2 × 10⁹) spread as N = 2 × 10⁵ × 100 realizations, 2 × 10⁶ × 10 and
    2 × 10⁷ × 1, groups re-dealt every step, a snapshot every 10 steps (1 τ; the
    documents sample every 0.15-1 τ): the collision engine's rate, which a snapshot of
    every particle at every step (``dsmc_speed``; this section until revision a2a5eb2)
    would hide. First with ``_dsmc``'s Strang splitting and exact force step (3 launches
    and two passes over every particle a step), then at N = 2 × 10⁵ × 100 and 2 × 10⁶ ×
    10 with montanero2007's Lie splitting and Euler force step (``lie``: 2 launches, one
    pass; every run of paper.yaml's montanero2007 but the error study's), and last the
    Lie case of 100 × 2 × 10⁵ at δt = 0.005 τ, nearly without collisions: the step's
    floor (its force pass, snapshots and launches). Each case says its ``time_step`` and
    ``acceptance`` (collisions per candidate pair); the Lie cases at δt = 0.1 τ, the
    issue's headline, are the median of three seeds (``engine_rates``: all three)."""
    _dsmc(2000, 2, 1.0, "cuda", restitution=1.0)  # compile (same types as every case)
    lie = {"splitting": "lie", "force_step": "euler"}
    _dsmc(2000, 2, 1.0, "cuda", restitution=1.0, **lie)
    sizes = SCALING_SHAPES
    cases = []
    _keep(gpu=cases)
    for scheme, shapes in (({}, sizes), (lie, sizes[:2])):
        for restitution in (1.0, 0.5):
            for n, realizations in shapes[: 1 if quick else None]:
                # the Lie cases are the headline (issue target 5 × 10⁸ a second): the
                # median of three seeds, with all three rates; the others once (2 s each)
                repeats = 3 if scheme else 1
                cases.append(
                    _dsmc_median(
                        repeats,
                        n,
                        realizations,
                        10.0,
                        "cuda",
                        restitution=restitution,
                        sample_stride=10,
                        **scheme,
                    )
                )
    # the step's floor: the same Lie steps with 20 times fewer collisions a step (δt =
    # 0.005 τ), so that the δt = 0.1 τ case less this one is the collisions' own time
    cases.append(
        _dsmc(200_000, 100, 1.0, "cuda", restitution=1.0, sample_stride=10, time_step=0.005, **lie)
    )
    return {"gpu": cases}


def _paper_job(backend: str) -> tuple[dict[str, Any], Any, float]:
    """The first montanero2007 run of the paper config with ``backend`` (α = 0.3,
    N = 2 × 10⁵, the paper's δt and duration; with ``cuda`` its family's job holds it as
    its first point): ``simulate_batch``'s arguments for its first job (every
    realization on ``cuda``), the front, and the seconds ``kinetic.cost`` plans for them
    (one job's startup included)."""
    from kinetic import cost
    from kinetic.studies import montanero2007

    config = _paper_config() | {"backend": backend}
    first = montanero2007.jobs(config)[0]
    arguments = dict(first.arguments)
    if "points" in arguments:  # cuda: the family's job, its first run on its own
        arguments = {k: v for k, v in arguments["points"][0].items() if k != "parameters"}
    extra = {"backend": backend} if backend != "cpu" else {}
    planned = cost.dsmc_homogeneous(
        **{**arguments["run"], "realizations": arguments["count"], **extra}
    ).cpu_seconds
    return arguments, montanero2007.simulate_batch, planned


def dsmc_paper_job(quick: bool) -> dict[str, Any]:
    """One montanero2007 run of paper.yaml on the GPU (all its realizations in one batch,
    as the job runs them, over a tenth of the duration) and on one CPU core (one
    realization over a tenth of the duration); both scaled to the whole run (on the GPU,
    the steps; the Maxwellian starts and the dataset come once a run). Fewer
    realizations would not do: at 25 x 2 × 10⁵ particles a step's GPU work (about 0.1 ms
    on an H200) is no longer than the host's two launches, so the time would be the
    host's. ``gpu_engine_job_seconds`` is the GPU's on the engine's clock (the steps,
    without the host's Maxwellian starts and the dataset); ``planned_gpu_seconds`` is
    ``kinetic.cost``'s for the run as a job of its own (its startup included)."""
    arguments, front, planned = _paper_job("cuda")
    run = arguments["run"]
    steps = run["duration"] / run["time_step"]
    count = arguments["count"]
    fraction = 50 if quick else 10  # whole windows (montanero2007: 100 in a run)
    gpu_run = {**run, "duration": run["duration"] / fraction}
    gpu_run["steady_from"] = gpu_run["duration"] / 2
    warm = {**run, "duration": run["sample_interval"], "steady_from": 0.0}
    front(**{**arguments, "count": 2, "run": warm})  # compile
    start = time.perf_counter()
    timed = front(**{**arguments, "run": gpu_run})
    gpu_wall = time.perf_counter() - start
    engine = float(timed.cpu_seconds.sum())
    cpu_arguments, cpu_front, _ = _paper_job("cpu")
    cpu_run = {**run, "duration": run["duration"] / 10, "steady_from": run["duration"] / 20}
    warm = {**cpu_run, "duration": run["sample_interval"], "steady_from": 0.0}
    cpu_front(**{**cpu_arguments, "count": 1, "run": warm})  # compile
    start = time.perf_counter()
    cpu_front(**{**cpu_arguments, "count": 1, "run": cpu_run})
    cpu_wall = time.perf_counter() - start
    gpu_job = gpu_wall + engine * (fraction - 1)  # the starts and the dataset once
    cpu_job_seconds = cpu_wall * count * 10
    return {
        "label": arguments["label"],
        "n_particles": run["n_particles"],
        "restitution": run["restitution"],
        "time_step": run["time_step"],
        "duration": run["duration"],
        "steps": steps,
        "job_realizations": count,
        "gpu_fraction_of_duration_timed": 1 / fraction,
        "gpu_wall_seconds": gpu_wall,
        "gpu_job_seconds": gpu_job,
        "gpu_engine_job_seconds": engine * fraction,
        "cpu_one_core_wall_seconds_per_tenth_realization": cpu_wall,
        "cpu_one_core_job_seconds": cpu_job_seconds,
        "speedup_over_one_core": cpu_job_seconds / gpu_job,
        "planned_gpu_seconds": planned,
    }


SPARSE_PASS_BYTES = {"collide_sparse": 0, "force": 48}
"""Least DRAM bytes per particle of each pass of a Lie step of the homogeneous DSMC
(kinetic.dsmc.gpu, float64 velocities, d = 3) with its ``sparse`` collisions: one thread
a group reads and writes only its candidate pairs in place (about 0.5 % of the particles
a step at montanero2007's δt = 0.003 τ: left out), then the force pass reads and writes
every particle, finds the majorant of the next step (its largest speed) and, in its last
block a realization, closes the thermostat: 48 bytes a particle-step, the least a step
that moves every particle can touch."""


def _launch_seconds(launch, repeats: int) -> float:
    """Median wall seconds of ``launch()`` to the GPU's completion, after one untimed call."""
    from kinetic.gpu import synchronize

    launch()
    synchronize()
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        launch()
        synchronize()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def _copy_seconds(elements: int, repeats: int) -> float:
    """Median seconds of ``kinetic.gpu.stream_copy`` over ``elements`` float64 numbers."""
    from kinetic import gpu as device

    source = device.device_zeros(elements)
    target = device.device_zeros(elements)
    blocks = min(device.grid(elements), 4096)
    return _launch_seconds(
        lambda: device.stream_copy[blocks, device.BLOCK](source, target), repeats
    )


def _memory_bound(n: int, realizations: int, repeats: int) -> dict[str, Any]:
    """The memory-bandwidth bound under the homogeneous DSMC at montanero2007's paper job
    settings (α = 0.3, ε* = 0.025, δt = 0.003 τ, Euler force step, Lie splitting) for
    ``realizations`` x ``n`` particles: the GPU's coalesced copy bandwidth over arrays of
    the velocities' size; each pass of a step with the ``sparse`` collisions launched
    alone and the whole step, with the passes' bytes (``SPARSE_PASS_BYTES``) over their
    time and the step's time against the time its 48 bytes a particle would take at the
    copy bandwidth, and the candidates a particle-step (``sparse``)."""
    from kinetic.dsmc import gpu as dsmc_gpu
    from kinetic.dsmc.state import HomogeneousSettings, Samples, realization_streams

    settings = HomogeneousSettings(
        n_particles=n,
        restitution=0.3,
        time_step=0.003,
        reduced_field=0.025,
        force_step="euler",
        splitting="lie",
    )
    samples = Samples(stride=50)
    particles = n * realizations
    copy = _copy_seconds(3 * particles, repeats)
    copy_bandwidth = 2 * 8 * 3 * particles / copy
    field_step = settings.half_field_step
    out: dict[str, Any] = {
        "n_particles": n,
        "realizations": realizations,
        "copy_seconds": copy,
        "copy_bytes_per_second": copy_bandwidth,
    }
    batch = dsmc_gpu._Batch(settings, samples, realization_streams(3, 0, realizations))
    sparse = {
        "collide_sparse": lambda: batch._collide_sparse(),
        "force": lambda: batch._force_and_thermostat(field_step, end_of_step=True),
    }
    out["sparse"] = {"passes": {}}
    for name, launch in sparse.items():
        seconds = _launch_seconds(launch, repeats)
        out["sparse"]["passes"][name] = _traffic(
            seconds, SPARSE_PASS_BYTES.get(name, 0), particles, copy_bandwidth
        )
    step = _launch_seconds(lambda: batch.step(sample=False, histogram=False), repeats)
    out["sparse"]["step"] = _against_bound(
        step, sum(SPARSE_PASS_BYTES.values()), particles, copy_bandwidth
    )
    # the collision stages run: each timing's untimed first launch and its repeats, twice
    tally = batch.tally.copy_to_host().sum(axis=(0, 1))
    candidates = int(tally[dsmc_gpu.kernels.TALLY_CANDIDATES])
    out["sparse"]["candidates_per_particle_step"] = candidates / (particles * 2 * (repeats + 1))
    out["sparse"]["acceptance"] = int(tally[dsmc_gpu.kernels.TALLY_ACCEPTED]) / max(candidates, 1)
    return out


def _traffic(seconds, bytes_per_particle, particles, copy_bandwidth) -> dict[str, float]:
    """A pass (phase) of ``seconds`` over ``particles`` that moves at least
    ``bytes_per_particle`` each: its bytes per second, against the copy bandwidth."""
    moved = bytes_per_particle * particles
    return {
        "seconds": seconds,
        "seconds_per_particle": seconds / particles,
        "bytes_per_particle": bytes_per_particle,
        "bytes_per_second": moved / seconds,
        "fraction_of_copy_bandwidth": moved / seconds / copy_bandwidth,
    }


def _against_bound(seconds, bytes_per_particle, particles, copy_bandwidth) -> dict[str, float]:
    """A whole step of ``seconds`` against the time its least traffic
    (``bytes_per_particle`` each) takes at the copy bandwidth."""
    bound = bytes_per_particle * particles / copy_bandwidth
    return {
        "seconds": seconds,
        "particle_steps_per_second": particles / seconds,
        "bound_seconds": bound,
        "bound_particle_steps_per_second": particles / bound,
        "fraction_of_bound": bound / seconds,
    }


def memory_bound(quick: bool) -> dict[str, Any]:
    """How far the homogeneous DSMC's step is from the GPU's memory bandwidth (the bound of
    montanero2007's paper runs): ``_memory_bound`` at N = 2 × 10⁵ with 50 realizations
    (10⁷ particles, 240 MB of velocities: far beyond the L2 cache)."""
    return _memory_bound(200_000, 10 if quick else 50, 5 if quick else 20)


PHASE_BYTES = {"centre": 0, "stream": 72, "scan": 0, "scatter": 16, "collide": 104}
"""Least DRAM bytes per simulated particle of each phase of an inhomogeneous DSMC step
(kinetic.dsmc.inhomogeneous_gpu, d = 2, float64 positions and velocities, int64 labels
and indices): the streaming reads and writes a particle's position and velocity (64) and
writes its cell (8); the scatter reads the cell and writes the particle's index into its
slot (16); the collision phase reads the index (8), gathers the position, velocity and
labels from scattered addresses (48) and writes them in cell order (48); the collided
pairs (about 4 % of the particles a step at costantini2010's δt) are left out. The centre
of mass and the scan touch a few numbers per cell. 192 bytes a particle-step in all (the
counts' integer atomics aside, which go to the L2 cache)."""


def _inhomogeneous_phases(points, repeats: int) -> dict[str, Any]:
    """Each phase of an inhomogeneous DSMC step (the launched path: five launches) timed
    alone within whole steps of the batch of ``points`` (``_cooling_points``: one run a
    restitution, as a grouped paper job), against its bytes (``PHASE_BYTES``) at the GPU's
    copy bandwidth; an empty launch (what a launch costs through numba's dispatcher,
    included in every phase's time), a whole launched step and a step of the cooperative
    path."""
    from kinetic import gpu as device
    from kinetic.dsmc import inhomogeneous_gpu as engine
    from kinetic.dsmc.inhomogeneous import CoolingModesSettings, realization_streams

    fields = CoolingModesSettings.__dataclass_fields__
    rows = [
        (
            CoolingModesSettings(**{key: point[key] for key in fields}),
            realization_streams(point["seed"], 0, point["n_realizations"]),
        )
        for point in points
    ]
    batch = engine._Batch(rows, 1)
    count = batch.count
    particles = count * batch.n
    copy = _copy_seconds(4 * particles, repeats)  # positions and velocities
    copy_bandwidth = 2 * 8 * 4 * particles / copy
    one = (device.device_zeros(1), device.device_zeros(1))
    empty = _launch_seconds(lambda: device.stream_copy[1, device.BLOCK](*one), repeats)
    times: dict[str, list[float]] = {name: [] for name in PHASE_BYTES}

    def timed(name, launch):
        device.synchronize()
        start = time.perf_counter()
        launch()
        device.synchronize()
        times[name].append(time.perf_counter() - start)

    batch.launched_step(count)  # an untimed step first
    for _ in range(repeats):
        batch.launched_step(count, timed)
    out: dict[str, Any] = {
        "simulated_particles": batch.n,
        "cells_per_side": batch.settings.cells_per_side,
        "realizations": count,
        "restitutions": [point["restitution"] for point in points],
        "copy_bytes_per_second": copy_bandwidth,
        "empty_launch_seconds": empty,
        "phases": {},
    }
    for name, seconds in times.items():
        median = float(np.median(seconds))
        out["phases"][name] = _traffic(median, PHASE_BYTES[name], particles, copy_bandwidth)
    step_bytes = sum(PHASE_BYTES.values())
    launched = _launch_seconds(lambda: batch.launched_step(count), repeats)
    out["step"] = _against_bound(launched, step_bytes, particles, copy_bandwidth)
    if batch.together:
        steps = 4
        together = _launch_seconds(lambda: batch.advance(steps, count), repeats) / steps
        out["step_together"] = {
            "steps_per_launch": steps,
            **_against_bound(together, step_bytes, particles, copy_bandwidth),
        }
    return out


def inhomogeneous_bound(quick: bool) -> dict[str, Any]:
    """Where the inhomogeneous DSMC's step spends its time at the shape of paper.yaml's
    grouped costantini2010 job (the six α of N = 3000 × Λ = 10, 16 realizations each: 2.9
    × 10⁶ simulated particles), phase by phase against the memory bandwidth
    (``_inhomogeneous_phases``)."""
    points = _cooling_points(3000, 10, 16, 4, "cuda", "paper", alphas=_paper_restitutions())
    return _inhomogeneous_phases(points, 3 if quick else 10)


_STARTUP_JOBS = {
    "cloning": (
        "from kinetic.cloning import simulate as front\n"
        "ds = front(kernel='hard_spheres', lam=1.0, population=1000, duration=20.0,"
        " transient=4.0, n_blocks=2, n_realizations=8, seed=3, backend='cuda')\n"
        "values = [ds.mu_per_realization, ds.temperature_per_realization]\n"
    ),
    "dsmc": (
        "from kinetic.dsmc import simulate_homogeneous as front\n"
        "ds = front(n_particles=20000, n_realizations=4, restitution=0.9, time_step=0.1,"
        " duration=2.0, sample_interval=1.0, seed=3, dimension=3, backend='cuda')\n"
        "values = [ds.moments, ds.collisions]\n"
    ),
    "dsmc_inhomogeneous": (
        "import math\n"
        "from kinetic.dsmc import simulate_cooling_modes as front\n"
        "tau = 1.0 / (2.0 * 0.005 * math.sqrt(math.pi))\n"
        "ds = front(n_particles=3000, density=0.005, restitution=0.8, drag_rate=0.0,"
        " equilibration=0.0, sample_interval=10 * 0.025 * tau, n_samples=3, seed=3,"
        " fictive_factor=10, cells_per_side=11, time_step=0.025 * tau, n_realizations=4,"
        " collision_rule='paper',"
        " backend='cuda')\n"
        "values = [ds.temperature, ds.collisions]\n"
    ),
}
"""A small job of each GPU module, as a fresh Snakemake job runs it (a new process)."""

_STARTUP_FOOTER = (
    "import hashlib, json, time\n"
    "digest = hashlib.sha256(b''.join(v.values.tobytes() for v in values)).hexdigest()\n"
    "print(json.dumps({'seconds': time.perf_counter() - START, 'digest': digest}))\n"
)


def job_startup(quick: bool) -> dict[str, Any]:
    """What a GPU job costs before its work: a small job of each GPU module in a fresh
    process (imports, CUDA context, kernels), three times over one empty numba cache
    directory: the first compiles and fills the cache, the next two load from it. The
    numbers must not depend on where the kernels came from (``same_numbers``)."""
    import json
    import os
    import subprocess
    import sys
    import tempfile

    out: dict[str, Any] = {}
    _keep(jobs=out)
    for name, body in _STARTUP_JOBS.items():
        code = "import time\nSTART = time.perf_counter()\n" + body + _STARTUP_FOOTER
        with tempfile.TemporaryDirectory() as cache:
            environment = {**os.environ, "NUMBA_CACHE_DIR": cache}
            runs = []
            for _ in range(2 if quick else 3):
                begin = time.perf_counter()
                done = subprocess.run(
                    [sys.executable, "-c", code],
                    env=environment,
                    capture_output=True,
                    text=True,
                    timeout=600,
                )
                wall = time.perf_counter() - begin
                if done.returncode != 0:
                    runs.append({"error": done.stderr[-2000:], "process_seconds": wall})
                    break
                result = json.loads(done.stdout.strip().splitlines()[-1])
                runs.append({"process_seconds": wall, **result})
        digests = {run.get("digest") for run in runs}
        out[name] = {
            "runs": runs,
            "same_numbers": len(digests) == 1 and None not in digests,
            "first_seconds": runs[0]["process_seconds"],
            "cached_seconds": min(run["process_seconds"] for run in runs[1:]) if runs[1:] else None,
        }
    return out


_DOCUMENT_JOB = """
import pickle, sys, time
START = time.perf_counter()
from types import SimpleNamespace
from kinetic.simulation_job import run_job
job = pickle.load(open(sys.argv[1], "rb"))
params = SimpleNamespace(front=job["front"], job=job["arguments"], parameters=job["parameters"])
snakemake = SimpleNamespace(rule=job["rule"], params=params, config=job["config"], threads=1,
                            output=[f"{sys.argv[2]}/{k}.nc" for k in range(job["files"])], log=[])
_, result = run_job(snakemake)
datasets = result if isinstance(result, list) else [result]
engine = sum(float(dataset["cpu_seconds"].sum()) for dataset in datasets)
print(repr({"seconds": time.perf_counter() - START, "engine_seconds": engine,
            "files": len(datasets)}))
"""
"""A GPU job in a process of its own: the workflow's own ``run_job`` (its fronts, its
writes, its logging to standard error) on the job's arguments, with a stand-in for the
``snakemake`` object of ``workflow/scripts/simulate.py`` (one thread, as the rules run)."""


def _document(document: str, quick: bool) -> dict[str, Any]:
    """``document``'s GPU jobs at paper.yaml's statistics on this GPU, as
    ``snakemake <document> --configfile config/paper.yaml --config backend=cuda`` runs
    them: each job in a process of its own, like a Snakemake job (imports, CUDA context,
    the kernels from numba's cache, the runs, their netCDF files written to a scratch
    folder), after a process for each of the jobs' fronts that fills the cache
    (``compile``, once per code version: the front's first job cut to its first run,
    shrunk to seconds by ``_SHRINK``), against ``kinetic.cost``'s plan of each job. The
    joins, analyses and figures (CPU, seconds) and the document's CPU jobs are left out.

    ``KINETIC_DOCUMENT_RULES`` (``scan,hcs``: the ends of rule names) keeps those rules'
    jobs only, to time a document over several calls. A job that would end past
    ``KINETIC_DOCUMENT_SECONDS`` (default 540) after the section's start, by its plan
    times the pace of the jobs done (measured over planned), is skipped and reported so;
    ``quick`` runs the two smallest jobs."""
    import pickle
    import subprocess
    import sys
    import tempfile

    deadline = float(os.environ.get("KINETIC_DOCUMENT_SECONDS", "540"))
    config = _paper_config() | {"backend": "cuda"}
    jobs = _document_jobs(document, config)
    if quick:
        jobs = sorted(jobs, key=lambda job: job.estimate.cpu_seconds)[:2]
    started = time.perf_counter()
    out: dict[str, Any] = {
        "rules": list(dict.fromkeys(job.rule for job in jobs)),
        "jobs": [],
        "planned_seconds": 0.0,
    }
    _keep(jobs=out["jobs"])

    def process(job, folder):
        path = f"{folder}/job.pickle"
        with open(path, "wb") as stream:
            pickle.dump(
                {
                    "rule": job.rule,
                    "front": job.front,
                    "arguments": dict(job.arguments),
                    "parameters": dict(job.parameters),
                    "files": len(job.files),
                    "config": config,
                },
                stream,
            )
        begin = time.perf_counter()
        done = subprocess.run(
            [sys.executable, "-c", _DOCUMENT_JOB, path, folder],
            capture_output=True,
            text=True,
            timeout=max(60.0, deadline),
        )
        wall = time.perf_counter() - begin
        if done.returncode != 0:
            return {"error": done.stderr[-2000:], "process_seconds": wall}
        return {"process_seconds": wall, **ast.literal_eval(done.stdout.strip().splitlines()[-1])}

    with tempfile.TemporaryDirectory() as folder:
        firsts: dict[str, Any] = {}  # each front's first job
        for job in jobs:
            firsts.setdefault(job.front, job)
        out["compile"] = [
            {"front": front} | process(_compile_job(document, job), folder)
            for front, job in firsts.items()
        ]
        print(f"{document}_document: compile", out["compile"], flush=True)
        begin = time.perf_counter()
        pace, timed, timed_planned = 1.0, 0.0, 0.0  # measured against planned, so far
        for job in jobs:
            planned = job.estimate.cpu_seconds
            out["planned_seconds"] += planned
            row = {
                "rule": job.rule,
                "output": job.output,
                "runs": len(job.files),
                "planned_seconds": planned,
            }
            if time.perf_counter() - started + planned * pace > deadline:
                out["jobs"].append(row | {"skipped": "past KINETIC_DOCUMENT_SECONDS by its plan"})
                continue
            out["jobs"].append(row | process(job, folder))
            print(f"{document}_document:", out["jobs"][-1], flush=True)  # if cut off
            if "error" not in out["jobs"][-1]:
                timed += out["jobs"][-1]["process_seconds"]
                timed_planned += planned
                pace = timed / timed_planned
        out["jobs_seconds"] = time.perf_counter() - begin
    done = [row for row in out["jobs"] if "process_seconds" in row and "error" not in row]
    out["complete"] = len(done) == len(jobs)
    out["timed_seconds"] = sum(row["process_seconds"] for row in done)
    out["timed_planned_seconds"] = sum(row["planned_seconds"] for row in done)
    return out


def _document_jobs(document: str, config) -> list:
    """The GPU jobs of ``document`` under ``config``, those whose rule ends in a name of
    ``KINETIC_DOCUMENT_RULES`` (comma-separated) where it is set; a name that ends no
    rule raises ``ValueError``."""
    import importlib

    study = importlib.import_module(f"kinetic.studies.{document}")
    jobs = [job for job in study.jobs(config) if job.gpus]
    names = os.environ.get("KINETIC_DOCUMENT_RULES")
    if not names:
        return jobs
    wanted = names.split(",")
    unmatched = [n for n in wanted if not any(j.rule.endswith(f"_{n}") for j in jobs)]
    if unmatched:
        raise ValueError(
            f"KINETIC_DOCUMENT_RULES: no {document} GPU job's rule ends in {unmatched}"
        )
    return [job for job in jobs if any(job.rule.endswith(f"_{n}") for n in wanted)]


def _shrink_montanero2007(point):
    run = point["run"]
    window = float(run["sample_interval"])
    shrunk = {"n_particles": min(int(run["n_particles"]), 2000), "duration": 2 * window}
    return point | {"run": {**run, **shrunk, "steady_from": window}, "count": 2}


def _shrink_visco2008(point):
    # the transient stays (it must keep collisions at its λ); blocks of a mean free time
    # (shorter ones cut the transient into more blocks too, each a launch)
    return point | {
        "population": min(int(point["population"]), 64),
        "duration": 2.0,
        "n_blocks": 2,
        "n_realizations": 2,
    }


def _shrink_costantini2010(point):
    return point | {"n_samples": 2, "n_realizations": 2, "equilibration": 0.0}


_SHRINK = {
    "montanero2007": _shrink_montanero2007,
    "visco2008": _shrink_visco2008,
    "costantini2010": _shrink_costantini2010,
}
"""A run of each document's GPU jobs cut to seconds with the same argument types (so
the same kernels): the job that fills numba's cache before the timed ones."""


def _compile_job(document, job):
    """``job`` cut to its first run, shrunk by ``_SHRINK[document]`` (montanero2007's
    smallest job whole, 23.6 s by its plan on an H100, filled the cache until d9134f3)."""
    import dataclasses

    shrink = _SHRINK[document]
    if "points" in job.arguments:
        arguments = {**job.arguments, "points": [shrink(job.arguments["points"][0])]}
        return dataclasses.replace(job, arguments=arguments, outputs=job.files[:1])
    return dataclasses.replace(job, arguments=shrink(dict(job.arguments)))


def montanero2007_document(quick: bool) -> dict[str, Any]:
    """montanero2007's 6 family jobs (``montanero2007_simulate_dsmc_<family>``) of
    paper.yaml on this GPU (``_document``): 546 s by the plan on an H100; timed over two
    calls on the H100 of b66ff5b and the H200 of d9134f3 (docs/gpu-runs.md)."""
    return _document("montanero2007", quick)


def visco2008_document(quick: bool) -> dict[str, Any]:
    """visco2008's 13 cloning jobs of paper.yaml on this GPU (``_document``): 466 s by
    the plan on an H100 (the three hard-disk scans of 41 λ, 317 s)."""
    return _document("visco2008", quick)


def costantini2010_document(quick: bool) -> dict[str, Any]:
    """costantini2010's 17 DSMC jobs of paper.yaml on this GPU (``_document``): 1191 s by
    the plan on an H100, so three calls of a 15-minute lease (``KINETIC_DOCUMENT_RULES``:
    ``dsmc`` for the 12 runs of their own, 247 s; ``grid_n3000``, 446 s; the other grids,
    498 s)."""
    return _document("costantini2010", quick)


OPTIONAL_SECTIONS: dict[str, Callable[[bool], dict[str, Any]]] = {
    "montanero2007_document": montanero2007_document,
    "visco2008_document": visco2008_document,
    "costantini2010_document": costantini2010_document,
}
"""Sections run only when named (``--sections``): too long for the default run."""


SECTIONS: dict[str, Callable[[bool], dict[str, Any]]] = {
    "cloning_physics": cloning_physics,
    "dsmc_paper_job": dsmc_paper_job,
    "inhomogeneous_bound": inhomogeneous_bound,
    "memory_bound": memory_bound,
    "inhomogeneous_speed": inhomogeneous_speed,
    "cloning_speed": cloning_speed,
    "dsmc_speed": dsmc_speed,
    "dsmc_scaling": dsmc_scaling,
    "dsmc_storage": dsmc_storage,
    "job_startup": job_startup,
}
"""In the order a short device lease should spend its minutes: what no GPU has run yet
first (``cloning_physics``' Maxwell check with 32 realizations and a seed a λ), then the
issue's targets (the montanero2007 paper job; the inhomogeneous step and speed), then
the rest; the whole default run took 374 s on the H200 of 5a93630."""


PREFLIGHT_MODULES = (
    "kinetic.config",
    "kinetic.studies",
    "kinetic.cloning",
    "kinetic.cloning.gpu",
    "kinetic.dsmc",
    "kinetic.dsmc.gpu",
    "kinetic.dsmc.inhomogeneous_gpu",
    "kinetic.theory.costantini2010",
    "kinetic.theory.visco2008_exact",
    "netCDF4",  # the document sections write their jobs' files (missing on the H100 of b66ff5b)
)
"""Every module a section imports. ``preflight`` imports them before the first section,
so that a package missing on the GPU machine stops the bench in seconds instead of failing
its sections one by one after minutes of GPU time (an H100 lease lost four sections to a
missing jsonschema, revision 2984f74)."""


def preflight() -> None:
    """Import ``PREFLIGHT_MODULES`` and read the paper config: raise ``ImportError`` naming
    every missing package at once."""
    import importlib

    missing = []
    for module in PREFLIGHT_MODULES:
        try:
            importlib.import_module(module)
        except ImportError as error:
            missing.append(f"{module}: {error}")
    if missing:
        raise ImportError(
            "bench cuda cannot run its sections here; carry these packages as wheels "
            "(docs/gpu.md, 'Measuring on a GPU'):\n  " + "\n  ".join(missing)
        )
    _paper_config()


def run(quick: bool = False, checkpoint=None, sections=None) -> dict[str, Any]:
    """Every section in ``SECTIONS``' order, or those named in ``sections`` in the order
    named; ``checkpoint(report)`` is called after each one. A failing section records its
    traceback and what it had measured (``partial``), and the next runs."""
    known = SECTIONS | OPTIONAL_SECTIONS
    unknown = set(sections or ()) - set(known)
    if unknown:
        raise ValueError(f"unknown sections {sorted(unknown)}; known: {list(known)}")
    preflight()
    started = time.perf_counter()
    report: dict[str, Any] = {"gpu": _device(), "sections": {}}
    stopped = None
    with _terminated_raises():
        for name in sections or SECTIONS:
            section = known[name]
            if stopped or time.perf_counter() - started > _BUDGET_SECONDS:
                report["sections"][name] = {"skipped": stopped or "time budget spent"}
                continue
            begin = time.perf_counter()
            _PARTIAL.clear()
            try:
                result = section(quick)
            except _Terminated:
                stopped = "the bench was terminated (SIGTERM) during an earlier section"
                result = {"error": "terminated (SIGTERM)", "partial": dict(_PARTIAL)}
            except Exception:
                result = {"error": traceback.format_exc(), "partial": dict(_PARTIAL)}
            result["section_seconds"] = time.perf_counter() - begin
            report["sections"][name] = result
            if checkpoint is not None:
                checkpoint(report)
    return report


class _Terminated(BaseException):
    """SIGTERM during a section (the device script's ``timeout``): not an ``Exception``, so
    a section's own handlers let it through to ``run``."""


@contextlib.contextmanager
def _terminated_raises():
    """While ``run`` runs, SIGTERM raises ``_Terminated`` (Python's default ends the process
    at once, and the running section's ``partial`` was lost); restored after."""
    import signal

    def stop(signum, frame):
        raise _Terminated

    try:
        previous = signal.signal(signal.SIGTERM, stop)
    except ValueError:  # not the main thread: keep the default
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
