"""CPU time and memory of one simulation job, estimated from its parameters.

One function per kind of job, taking the same keyword arguments as the engine front the
job calls (the dictionaries the workflow rules pass as ``params``), returning an
:class:`Estimate`: the expected CPU seconds of the computation and its peak memory.
:func:`runtime_minutes` and :func:`mem_mb` turn an estimate into the ``runtime`` and
``mem_mb`` a scheduler (SLURM) is asked for, with the safety factors below.

Every coefficient is the inverse of a measured speed and says where it comes from:

- "README" numbers are the medians of ``python -m kinetic.bench <engine>`` quoted in the
  README's engine table (one core of the 2-core development machine, shared with other
  work, 2026-11-23);
- "front" numbers time the engine fronts themselves (import and compilation excluded)
  on the same machine, 2026-11-24, for what the benches do not report (per-step cost
  of the DSMC protocol, the continuous-time DSMC, the samplers); those runs were 1.5 to
  2.5 times faster than the README's on a busier machine, so their speeds are halved
  here to the README's level;
- memory per particle is the growth of the peak resident set between N = 10³ and
  N = 10⁶ (2 × 10⁶ for the DSMC), doubled.

The estimates are meant to be upper bounds for a job on a loaded core of a similar
machine, not predictions to 10 %: the workflow test checks that they bound the measured
runtime and peak memory (Snakemake's ``benchmark:`` files) of the ``ci`` jobs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from kinetic.cloning.arguments import MAX_TRANSIENT_BLOCKS, default_control_interval
from kinetic.gas import cell_changing_fraction

__all__ = [
    "BASE_MEMORY_MB",
    "JOB_OVERHEAD_SECONDS",
    "MEMORY_SAFETY",
    "MIN_RUNTIME_MINUTES",
    "RUNTIME_SAFETY",
    "Estimate",
    "cloning_batch",
    "dsmc_free_flights",
    "dsmc_homogeneous",
    "edmd_box",
    "edmd_periodic",
    "mem_mb",
    "requested_seconds",
    "runtime_minutes",
    "sampler_disks",
    "sampler_line",
    "sampler_ring",
    "small_job",
]

# ------------------------------------------------------------------ job-level constants
JOB_OVERHEAD_SECONDS = 10.0
"""Start and end of a job: Python, imports, loading the compiled kernels from numba's
cache, writing the netCDF file (1-2 s per ci job in its benchmark file), and Snakemake's
own per-job work (about 1 s locally, 5-8 s through SLURM: submission and polling)."""

BASE_MEMORY_MB = 1000.0
"""Memory of a job without particles: the script process (numpy, numba, xarray, netCDF4
and the compiled kernels: peak 200-260 MB measured, 410 MB when it compiles) plus the
Snakemake process that runs it inside a SLURM allocation (~200 MB), rounded up."""

RUNTIME_SAFETY = 3.0
"""Runtime asked for = overhead + RUNTIME_SAFETY x estimated CPU time: covers slower or
shared cores and the spread of the bench repeats (up to 10 % same day, x2.5 across load)."""

MEMORY_SAFETY = 2.0
"""Memory asked for = BASE_MEMORY_MB + MEMORY_SAFETY x estimated particle memory."""

MIN_RUNTIME_MINUTES = 2
"""Shortest runtime asked for (SLURM rounds to minutes; a ci job takes seconds)."""


@dataclass(frozen=True)
class Estimate:
    """Estimated cost of one job.

    cpu_seconds : expected CPU time of the computation (one core), start-up excluded; for
        a GPU job its wall time (the core that launches the kernels is busy throughout)
    memory_mb : expected peak memory of the particles and observers, base excluded
    work : what is counted, e.g. '4.0e+08 collisions'
    gpus : GPUs the job runs on (1 for a ``backend='cuda'`` job)
    """

    cpu_seconds: float
    memory_mb: float
    work: str
    gpus: int = 0

    @property
    def cpu_hours(self) -> float:
        return self.cpu_seconds / 3600.0

    @property
    def job_seconds(self) -> float:
        """Expected wall time of the job on one core, start-up included."""
        return JOB_OVERHEAD_SECONDS + self.cpu_seconds

    @property
    def peak_mb(self) -> float:
        """Expected peak memory of the job (base included)."""
        return BASE_MEMORY_MB + self.memory_mb


def requested_seconds(estimate: Estimate) -> float:
    """Wall seconds a job of ``estimate`` may take before its request is exceeded: the
    overhead, plus RUNTIME_SAFETY x (its CPU time and the compilation of the slowest
    engine's kernels, which the first job after an edit does while the others wait)."""
    compilation = max(COMPILE_SECONDS.values())
    return JOB_OVERHEAD_SECONDS + RUNTIME_SAFETY * (compilation + estimate.cpu_seconds)


def runtime_minutes(estimate: Estimate, attempt: int = 1) -> int:
    """SLURM ``runtime`` (minutes) for ``estimate`` (:func:`requested_seconds`, at least
    MIN_RUNTIME_MINUTES); doubled on every retry."""
    minutes = max(MIN_RUNTIME_MINUTES, math.ceil(requested_seconds(estimate) / 60.0))
    return int(minutes * 2 ** (max(1, int(attempt)) - 1))


def mem_mb(estimate: Estimate, attempt: int = 1) -> int:
    """SLURM ``mem_mb`` for ``estimate`` (rounded up to 100 MB); doubled on every retry."""
    megabytes = BASE_MEMORY_MB + MEMORY_SAFETY * estimate.memory_mb
    return int(100 * math.ceil(megabytes / 100.0) * 2 ** (max(1, int(attempt)) - 1))


def _interpolate(x: float, table: dict[float, float]) -> float:
    """Piecewise log-log interpolation of ``table`` (x -> y), extrapolated with the slope
    of the last interval above the table and held constant below it."""
    points = sorted(table.items())
    if x <= points[0][0]:
        return points[0][1]
    index = next((k for k in range(1, len(points)) if x <= points[k][0]), len(points) - 1)
    (x0, y0), (x1, y1) = points[index - 1], points[index]
    slope = math.log(y1 / y0) / math.log(x1 / x0)
    return y0 * math.exp(slope * math.log(x / x0))


def _mb(bytes_count: float) -> float:
    return bytes_count / 1e6


# ------------------------------------------------------------------ event-driven MD
EDMD_COLLISIONS_PER_SECOND = {
    0.01: {1e3: 7.6e5, 1e4: 5.8e5, 1e5: 3.3e5},  # bench edmd: 2D, rho sigma^2 = 1e-2
    0.001: {1e3: 3.5e5, 1e4: 2.5e5, 1e5: 1.4e5},  # bench edmd: 2D, rho sigma^2 = 1e-3
}
"""Collisions per CPU-second of kinetic.edmd (2D) against N at two densities
(``python -m kinetic.bench edmd``, AMD EPYC, fb817f1, 2026-11-27; the table before held
the speeds from before a69f86e compiled the event loop without reference counting, 1.3
times slower, and the default build's MD jobs took 0.53-0.61 of their estimates). Above
N = 10⁵ the 10⁴ -> 10⁵ slope is extended. Only 2D runs are planned (visco2008); 3D at
packing 0.01 is about as fast as 2D at ρσ² = 10⁻³ (3.9 / 2.8 / 1.3 × 10⁵)."""

EDMD_OBSERVER_FACTOR = 1.2
"""visco2008's observers (windowed counts, flight and path histograms) on top of the
bare collisions: the default build's MD took 1240 CPU-s where the bench speeds give 1036."""

EDMD_BYTES_PER_PARTICLE = 450.0
"""Front: peak RSS 205 MB at N = 10³, 425 MB at N = 10⁶ (220 B per disk), doubled."""


def _edmd_speed(n_particles: float, density: float) -> float:
    low = _interpolate(n_particles, EDMD_COLLISIONS_PER_SECOND[0.001])
    high = _interpolate(n_particles, EDMD_COLLISIONS_PER_SECOND[0.01])
    # log-linear in the density between the two measured ones, held above 1e-2 and
    # extended below 1e-3 (dilute gases spend more time per collision on cell crossings)
    slope = math.log(high / low) / math.log(10.0)
    exponent = math.log10(min(max(density, 1e-12), 0.01) / 0.001)
    return low * 10.0 ** (slope * exponent)


def edmd_periodic(
    *,
    n_particles: int,
    density: float,
    realizations: int,
    equilibration: float,
    duration: float,
    **_: object,
) -> Estimate:
    """One batch of kinetic.edmd.simulate: ``realizations`` x (equilibration collisions
    per particle + ``duration`` mean free times) of N hard disks, N/2 collisions per
    mean free time."""
    collisions = realizations * n_particles / 2.0 * (equilibration + duration)
    seconds = EDMD_OBSERVER_FACTOR * collisions / _edmd_speed(n_particles, density)
    memory = _mb(EDMD_BYTES_PER_PARTICLE * n_particles)
    return Estimate(seconds, memory, f"{collisions:.2e} collisions")


EDMD_BOX_EVENTS_PER_SECOND = 2.1e6
"""event-disks (kinetic.event_disks, O(N²) per event) at N = 4: front 4.2 × 10⁶ events/s,
halved. The cost of an event grows like N² beyond that."""

EDMD_BOX_EVENTS_PER_DISK_TIME = 8.0
"""Events per disk per unit time for krauth2025's disks (σ = 0.15 in the unit box,
βm = 1): front 31.6 events per unit time with 4 disks."""


def edmd_box(*, n_disks: int, duration: float, realizations: int, **_: object) -> Estimate:
    """kinetic.event_disks.simulate_box: ``realizations`` runs of ``duration``."""
    events = realizations * duration * EDMD_BOX_EVENTS_PER_DISK_TIME * n_disks
    seconds = events / EDMD_BOX_EVENTS_PER_SECOND * max(1.0, (n_disks / 4.0) ** 2)
    return Estimate(seconds, _mb(1e4 * n_disks), f"{events:.2e} events")


GPU_JOB_STARTUP_SECONDS = 4.2
"""Wall seconds of a ``cuda`` job's process with its kernels loaded from numba-cuda's
cache (``kinetic.gpu``): Python, the package's imports, the CUDA context and a tiny job.
Measured on an H100 machine (bench cuda ``job_startup``, revision 5836ea7): 3.8 s
(cloning), 3.8 s (homogeneous DSMC), 4.2 s (inhomogeneous DSMC), the same numbers as the
first process, which compiled into the empty cache in 36, 85 and 23 s (not in this
constant: once per edit); at 2984f74, 4.0, 4.6 and 5.6 s."""


# ------------------------------------------------------------------ costantini2010
COOLING_DSMC_SECONDS_PER_PARTICLE_STEP = 4.6e-9
"""kinetic.dsmc.simulate_cooling_modes on the CPU, a particle-step of the step itself
(streaming, the cells brought up to date, collisions at paper.yaml's Δτ), with
``COOLING_DSMC_SECONDS_PER_CHANGED_CELL`` times the fraction of the particles expected to
change cell a step (``kinetic.gas.cell_changing_fraction``: the particles moved one by
one, or the sort where more than 15 % move) and the two constants below. Until revision
654b818, which sorted every particle every step, a single 1.08 × 10⁻⁸, fitted with the
two constants below to paper.yaml's costantini2010 DSMC jobs timed on the Intel Xeon (2
cores): the job of N = 3000, Λ = 10, α = 0.7 alone (1.19 × 10¹⁰ particle-steps, 172.8
CPU-s), and 192 jobs of N = 1000, two at a time (12 runs: Λ = 1, 10, 100, one cell, cell
sides 0.125-1 and Δτ 0.025-0.1 mean free times; each run's CPU time 0.87-1.12 times the
estimate). The two constants of the particle-step were refitted to those 13 run types
timed with both engines in one process on the AMD EPYC (2026-11-29, each shortened to
about 2 s; the old engine's estimates scaled by the new engine's time over the old
one's): the estimates are 0.78-1.29 times those times, 1.08 for the production run (cells
of 0.5 mean free paths, Δτ = 0.025)."""

COOLING_DSMC_SECONDS_PER_CHANGED_CELL = 3.2e-8
"""The same, a particle-step times the fraction of the particles that change cell: moving
one costs about seven plain particle-steps."""

COOLING_DSMC_SECONDS_PER_CELL_STEP = 5.1e-8
"""The same, a collision cell and step: the per-cell loops (the counts, the prefix sum, the
centre-of-mass sum, the collision stage's set-up). The cell side of 0.125 mean free paths
has 16 times the cells of the production 0.5."""

COOLING_DSMC_SECONDS_PER_PARTICLE_SAMPLE = 1.16e-8
"""The same, a simulated particle and sample: the observer (``inhomogeneous_kernels.observe``:
the modes, T and the momentum; 8.9 ns a particle alone, 268 µs a sample of 3 × 10⁴), every
fourth step at the production Δτ, every step at Δτ = 0.1 mean free times."""

GPU_H100_PER_H200 = 1.19
"""How much slower an H100 is taken to be than the H200 where a constant below was
measured on an H200: the ratio of the copy bandwidths bench cuda measured on each (2.80
against 2.34 TB/s, ``memory_bound`` of docs/data/cuda-h200-361e2ca.json and
cuda-h100-5836ea7.json). Both chips have 132 SMs at 1980 MHz, so work bound by latency or
arithmetic runs about as fast on either: the factor is a ceiling on the H100's extra
time, which the plan takes to stay on the safe side."""

COOLING_DSMC_GPU_TOGETHER_SECONDS_PER_STEP = 4.5e-5 * GPU_H100_PER_H200
"""``cuda`` backend of simulate_cooling_modes, the steps between two samples in one
cooperative launch (``inhomogeneous_gpu._advance_together``): the fixed cost of one step,
five grid-wide barriers and the latency of the phases when the GPU has little to do.
Fitted with ``COOLING_DSMC_GPU_PARTICLE_STEPS_PER_SECOND`` to two timings on an H200 at
revision 5a93630 (bench cuda ``inhomogeneous_speed``, N = 3000, Λ = 10, 4000 steps with
their samples; docs/data/cuda-h200-5a93630.json): 16 realizations in 0.174 ms a step and
96 (``grouped``, six α) in 0.815 ms, that is 4.5 × 10⁻⁵ s a step and 3.74 × 10⁹
particle-steps/s; times ``GPU_H100_PER_H200``."""

COOLING_DSMC_GPU_SECONDS_PER_SAMPLE = 3.0e-4
"""``cuda`` backend of simulate_cooling_modes on the cooperative path: the launches of a
sample interval (the steps' launch, the observer and its fold: three of about 90 µs). A
model."""

COOLING_DSMC_GPU_PARTICLE_STEPS_PER_SECOND = 3.74e9 / GPU_H100_PER_H200
"""``cuda`` backend of simulate_cooling_modes, every realization in the same launches:
particle-steps per second beyond the fixed cost of a step (samples included). Fitted on an
H200 at revision 5a93630 with ``COOLING_DSMC_GPU_TOGETHER_SECONDS_PER_STEP``: 3.74 × 10⁹,
divided by ``GPU_H100_PER_H200``. The whole-step rate at costantini2010's shape (100
realizations, 2000 steps) was 3.69 × 10⁹ on that H200, where the cells' phase runs a warp
per cell (``inhomogeneous_gpu.CELL_THREADS``); an H100 at 5836ea7, with one thread a cell,
did 1.72 × 10⁹ (its cells' phase 1.54 of the step's 1.72 ms; on the H200 now 0.86 of
1.18 ms on the launched path)."""

COOLING_DSMC_BYTES_PER_PARTICLE = 120.0
"""Positions, velocities, sort keys and scratch of one simulated particle (``cuda``)."""

COOLING_DSMC_CPU_BYTES_PER_PARTICLE = 184.0
"""The CPU engine's bound: 48 bytes a slot (positions, velocities, identities) for at most
2 N_sim + 5 M² slots (``slack_per_cell``), the 56-byte buffer of the particles that change
cell and the observer's 32 bytes of mode terms."""

COOLING_DSMC_CPU_BYTES_PER_CELL = 312.0
"""The same, a cell: its at most 5 free slots of the bound above and its ranges, carried
fraction and moments."""

COOLING_MD_SECONDS_PER_COLLISION = 1.9e-6
"""kinetic.edmd.simulate_cooling_modes: a collision of 10³–3 × 10³ disks at nσ² = 0.005
(with ``COOLING_MD_SECONDS_PER_PARTICLE_SEGMENT``, fitted to four paper.yaml jobs; the
two are nearly collinear there, since a segment's collisions grow with N)."""

COOLING_MD_SECONDS_PER_PARTICLE_SEGMENT = 6e-8
"""Per particle and segment of rescaled time: clock rebase, velocity scaling and calendar
rebuild (one pass, without reference counting), and the observers (one compiled pass,
the Fourier factors a vectorized loop, ``kinetic.fourier``). Measured as the CPU time of
4000 segments less that of 500 over the same duration, medians of 3: 6.0 × 10⁻⁸ at
N = 3000, α = 0.7 and 5.4 × 10⁻⁸ at N = 10³, α = 1 (8.8 and 9.9 × 10⁻⁸ the same day with
libm's cos and sin in the observer; 2.5 × 10⁻⁷ before the rebase scaled the velocities
and the rebuild went without reference counting). paper.yaml's jobs, CPU-s measured
(planned): N = 10³, α = 0.7: 3.16 (2.85); N = 2000, α = 0.5: 16.6 (17.0); N = 3000,
α = 1: 19.7 (22.5); N = 3000, α = 0.7: 42.6 (46.1; 144 s three changes ago, the same
14 885 730 collisions)."""


def _cooling_dsmc_gpu(steps, n_samples, particle_steps, particles, runs=1) -> Estimate:
    """A ``cuda`` job of inhomogeneous DSMC: ``steps`` steps and ``n_samples`` samples of
    its longest run (the fixed cost of a step and of a sample, paid once for the runs
    sharing the launches), ``particle_steps`` of all its runs, ``particles`` simulated
    particles on the GPU at once."""
    seconds = (
        steps * COOLING_DSMC_GPU_TOGETHER_SECONDS_PER_STEP
        + n_samples * COOLING_DSMC_GPU_SECONDS_PER_SAMPLE
        + particle_steps / COOLING_DSMC_GPU_PARTICLE_STEPS_PER_SECOND
    )
    memory = _mb(COOLING_DSMC_BYTES_PER_PARTICLE * particles)
    runs_text = f" of {runs} runs" if runs > 1 else ""
    work = f"{particle_steps:.2e} particle-steps{runs_text} on one GPU"
    return Estimate(seconds + GPU_JOB_STARTUP_SECONDS, memory, work, gpus=1)


def cooling_modes_points(points) -> Estimate:
    """One ``cuda`` job of several inhomogeneous DSMC runs in the same launches
    (``kinetic.dsmc.simulate_cooling_modes_points``, ``points`` its keyword arguments):
    the steps and samples of the longest run, the particle-steps of all."""
    steps, n_samples, particle_steps, particles = 0.0, 0, 0.0, 0
    for point in points:
        simulated = point["fictive_factor"] * point["n_particles"]
        run_steps = point["n_samples"] * point["sample_interval"] / point["time_step"]
        steps = max(steps, run_steps)
        n_samples = max(n_samples, point["n_samples"])
        particle_steps += point["n_realizations"] * simulated * run_steps
        particles += simulated * point["n_realizations"]
    return _cooling_dsmc_gpu(steps, n_samples, particle_steps, particles, len(points))


def cooling_modes(
    *,
    engine: str,
    n_particles: int,
    n_samples: int,
    sample_interval: float,
    density: float,
    n_realizations: int,
    fictive_factor: int = 1,
    cells_per_side: int = 1,
    time_step: float | None = None,
    backend: str = "cpu",
    **_: object,
) -> Estimate:
    """One job of costantini2010 (kinetic.dsmc or kinetic.edmd simulate_cooling_modes,
    engine units): ``n_realizations`` runs of ``n_samples`` sample intervals; a DSMC job
    on the ``cuda`` backend advances them all in the same launches, the steps between two
    samples in one cooperative launch."""
    duration = n_samples * sample_interval
    samples_bytes = 80.0 * n_samples * n_realizations
    if engine == "dsmc":
        simulated = fictive_factor * n_particles
        particle_steps = n_realizations * simulated * duration / time_step
        if backend == "cuda":
            return _cooling_dsmc_gpu(
                duration / time_step, n_samples, particle_steps, simulated * n_realizations
            )
        steps = n_realizations * duration / time_step
        box_side = math.sqrt(n_particles / density)
        changing = cell_changing_fraction(2, time_step, box_side, cells_per_side)
        seconds = (
            (
                COOLING_DSMC_SECONDS_PER_PARTICLE_STEP
                + COOLING_DSMC_SECONDS_PER_CHANGED_CELL * changing
            )
            * particle_steps
            + COOLING_DSMC_SECONDS_PER_CELL_STEP * cells_per_side**2 * steps
            + COOLING_DSMC_SECONDS_PER_PARTICLE_SAMPLE * simulated * n_samples * n_realizations
        )
        memory = _mb(
            COOLING_DSMC_CPU_BYTES_PER_PARTICLE * simulated
            + COOLING_DSMC_CPU_BYTES_PER_CELL * cells_per_side**2
            + samples_bytes
        )
        return Estimate(seconds, memory, f"{particle_steps:.2e} particle-steps")
    collision_frequency = 2.0 * density * math.sqrt(math.pi)  # at T0 = 1
    collisions = n_realizations * n_particles / 2.0 * collision_frequency * duration
    seconds = (
        COOLING_MD_SECONDS_PER_COLLISION * collisions
        + COOLING_MD_SECONDS_PER_PARTICLE_SEGMENT * n_particles * n_samples * n_realizations
    )
    memory = _mb(EDMD_BYTES_PER_PARTICLE * n_particles + samples_bytes)
    return Estimate(seconds, memory, f"{collisions:.2e} collisions")


# ------------------------------------------------------------------ DSMC
DSMC_COLLISIONS_PER_SECOND = {1e4: 1.39e7, 2e5: 9.8e6}
"""README: accepted NTC collisions per CPU-second of kinetic.dsmc (d = 3, α = 1;
8.7 × 10⁶ at α = 0.5, N = 2 × 10⁵, which the safety factor covers)."""

DSMC_SECONDS_PER_PARTICLE_STEP = 2.2e-9
"""Force, thermostat and moments per particle and time step (montanero2007's protocol):
bench dsmc's paper step 1.55 ns at N = 2 × 10⁵ (exact force, collisions included; 3.4 ns
before the thermostat was deferred into the next force update, 2026-11-27), the front
2.0-2.6 ns with its snapshot every 50 steps. paper.yaml's job montanero2007/dsmc/alpha050
batch0001 (2 × 10¹⁰ particle-steps) took 50.7 CPU-s on the Intel Xeon (2026-11-28), 2.1 ns
a particle-step beside the model's other terms (8.6 s); this constant plans it at 52.7 s
(3e-9, twice the bench, planned 68.7 s until then). Three other shapes, measured
(planned): extreme_field100_alpha100 37.9 (39.5), error_exact030n2000_alpha050 3.8 (4.7),
error_strang030_alpha050 5.0 (4.3) CPU-s."""

DSMC_SECONDS_PER_STEP = 4e-6
"""Fixed cost of a time step (front: 4.7 ns per particle-step at N = 2000, 2.4 at 2 × 10⁴),
doubled."""

DSMC_SECONDS_PER_SAMPLED_PARTICLE = 1.2e-8
"""Snapshot observers (c_x and speed histograms, the Laguerre moments of b'_k) at every
``sample_stride``-th step, per particle: 11 ns measured at N = 2 × 10⁴ with a snapshot
every step (Strang, δt = 0.1 τ: 0.20 µs per particle-τ in all, 2026-11-24)."""

DSMC_STRANG_FACTOR = 1.5
"""Strang splitting does two half force steps per step."""

DSMC_COLLISIONS_PER_PARTICLE_TAU = 2.0 / math.sqrt(math.pi)
"""Collisions per particle per τ = λ/v0 of hard spheres at the reference temperature."""

DSMC_BYTES_PER_PARTICLE = 100.0
"""Front: peak RSS 247 MB at N = 2 × 10⁶ against ~200 MB at 2000 (24 B per particle:
three velocity components), with histograms and scratch, rounded up."""


DSMC_GPU_SECONDS_PER_LAUNCH = 1.1e-4
"""``cuda`` backend: host seconds of one kernel launch of a step through numba's
dispatcher (its arguments' checks and marshalling), the floor of a step when the GPU has
little to do: a Lie step is 2 launches, a Strang step 3, a snapshot 2 more. On an H200 at
5a93630 the montanero2007 paper job with 25 realizations (5 × 10⁶ particles, whose GPU
work takes 0.07 ms) ran 0.222 ms a Lie step with a snapshot every 50th (bench cuda
``dsmc_paper_job``, docs/data/cuda-h200-5a93630.json); on an H100 at 2984f74, 0.52 ms a
Strang step with a snapshot each (5 launches)."""

DSMC_GPU_SECONDS_PER_SAMPLED_PARTICLE = 2.8e-10
"""``cuda`` backend, one H100: seconds per particle of a snapshot (moments, histograms):
bench cuda's 1.8-2.1 × 10⁹ particle-steps/s with Strang and a snapshot every step, less
the step itself."""

DSMC_GPU_SECONDS_PER_PARTICLE_STEP = (
    2.04e-11 * GPU_H100_PER_H200 - DSMC_GPU_SECONDS_PER_SAMPLED_PARTICLE / 50
)
"""``cuda`` backend: seconds per particle-step once the launches are full, Lie splitting,
the ``sparse`` collisions; times DSMC_STRANG_FACTOR for Strang. Measured on an H200 at
revision 361e2ca (bench cuda ``dsmc_paper_job``: montanero2007's α = 0.3 run, its 200
realizations of 2 × 10⁵ in one batch, a tenth of its 2 × 10⁴ steps;
docs/data/cuda-h200-361e2ca.json): 16.3 s for the whole run, the Maxwellian starts and the
dataset included (13.2 s on the engine's clock), 2.04 × 10⁻¹¹ s a particle-step; times
``GPU_H100_PER_H200``, less the snapshots' share (``DSMC_GPU_SECONDS_PER_SAMPLED_PARTICLE``
at its stride of 50). A step timed alone, launch to synchronisation, takes longer (0.33-
0.50 ms for 10⁷ particles on that H200, ``memory_bound``): the job's launches run ahead of
the GPU, and 20 steps launched back to back took 0.20-0.33 ms a step (the
docs/data/cuda-h200-fold-ab.jsonl A/B, where the force pass with the fused fold, 5a93630,
and the separate fold of 5836ea7 took the same time to within the H200's drift between
processes, up to 50 %)."""

DSMC_GPU_BYTES_PER_PARTICLE = 80.0
"""``cuda`` backend, a job's host memory: the velocities of every realization built on the
host (24 bytes a particle) and, in a job of several runs, the next run's built beside
them (``dsmc.gpu.prefetch_starts``: 24 more a particle of the larger run), the
majorant's scratch (8), 56 in all, rounded up; the GPU holds the 24 bytes and about 1 a
particle of per-group state."""


def dsmc_homogeneous(
    *,
    n_particles: int,
    duration: float,
    time_step: float,
    realizations: int,
    sample_stride: int = 10,
    splitting: str = "lie",
    backend: str = "cpu",
    **_: object,
) -> Estimate:
    """``realizations`` runs of kinetic.dsmc.simulate_homogeneous (montanero2007); with
    ``backend='cuda'`` all in the same launches: each step the larger of its launches'
    host cost and its particle-steps at the GPU's rate (the launches run ahead of the
    GPU)."""
    steps = math.ceil(duration / time_step - 1e-9)
    particle_steps = steps * n_particles
    if backend == "cuda":
        work = realizations * particle_steps
        per_particle_step = DSMC_GPU_SECONDS_PER_PARTICLE_STEP * (
            DSMC_STRANG_FACTOR if splitting == "strang" else 1.0
        ) + DSMC_GPU_SECONDS_PER_SAMPLED_PARTICLE / max(1, sample_stride)
        step_work = realizations * n_particles * per_particle_step
        launches = (3 if splitting == "strang" else 2) + 2 / max(1, sample_stride)
        seconds = steps * max(launches * DSMC_GPU_SECONDS_PER_LAUNCH, step_work)
        memory = _mb(DSMC_GPU_BYTES_PER_PARTICLE * n_particles * realizations)
        work = f"{work:.2e} particle-steps on one GPU"
        return Estimate(seconds + GPU_JOB_STARTUP_SECONDS, memory, work, gpus=1)
    collisions = n_particles / 2.0 * DSMC_COLLISIONS_PER_PARTICLE_TAU * duration
    step_cost = DSMC_SECONDS_PER_PARTICLE_STEP
    if splitting == "strang":
        step_cost *= DSMC_STRANG_FACTOR
    per_run = (
        particle_steps * step_cost
        + steps * DSMC_SECONDS_PER_STEP
        + particle_steps / max(1, sample_stride) * DSMC_SECONDS_PER_SAMPLED_PARTICLE
        + collisions / _interpolate(n_particles, DSMC_COLLISIONS_PER_SECOND)
    )
    return Estimate(
        realizations * per_run,
        _mb(DSMC_BYTES_PER_PARTICLE * n_particles),
        f"{realizations * particle_steps:.2e} particle-steps",
    )


def dsmc_homogeneous_points(runs, *, backend: str = "cpu", **_: object) -> Estimate:
    """One job of several montanero2007 runs one after the other in one process
    (``kinetic.studies.montanero2007_front.simulate_batches``; ``runs``: ``dsmc_homogeneous``'s
    keyword arguments each): the runs' times with one process's startup, the largest
    run's memory."""
    estimates = [dsmc_homogeneous(**run, backend=backend) for run in runs]
    startup = GPU_JOB_STARTUP_SECONDS if backend == "cuda" else 0.0
    seconds = sum(estimate.cpu_seconds - startup for estimate in estimates) + startup
    memory = max(estimate.memory_mb for estimate in estimates)
    particle_steps = sum(
        math.ceil(run["duration"] / run["time_step"] - 1e-9)
        * run["n_particles"]
        * run["realizations"]
        for run in runs
    )
    where = " on one GPU" if backend == "cuda" else ""
    work = f"{particle_steps:.2e} particle-steps of {len(runs)} runs{where}"
    gpus = max(estimate.gpus for estimate in estimates)
    return Estimate(seconds, memory, work, gpus=gpus)


DSMC_FLIGHTS_PER_SECOND = {4e3: 1.0e7, 1e4: 8.7e6, 1e6: 2.0e6}
"""Continuous-time DSMC with free-flight recording (kinetic.dsmc.simulate_free_flights,
d = 2, hard disks) against N: paper.yaml's free_flight_times run of N = 10⁴ (16 jobs of
16 realizations, 2.56 × 10⁹ flights in 292 CPU-s, two jobs at a time on the Intel Xeon:
8.76 × 10⁶ a second); the front's 1.3 × 10⁷ at N = 4000 and 2.0 × 10⁶ at N = 10⁶ (the
bath no longer fits in the cache), less a quarter at 4000. Until then the front's rates
halved, which planned that run at 1.8 times its time."""

DSMC_FLIGHTS_MAXWELL_SPEEDUP = 1.4
"""Maxwell molecules: flights per CPU-second over the hard disks' at the same N (every
candidate collides). paper.yaml's maxwell_free_paths run: 2.56 × 10⁹ flights in 205 CPU-s,
1.25 × 10⁷ a second, 1.43 times free_flight_times' rate."""


def dsmc_free_flights(
    *, n_particles: int, duration: float, n_realizations: int, kernel: str, **_: object
) -> Estimate:
    """``n_realizations`` runs of kinetic.dsmc.simulate_free_flights: one flight per
    particle per mean free time."""
    flights = n_realizations * n_particles * duration
    rate = _interpolate(n_particles, DSMC_FLIGHTS_PER_SECOND)
    if kernel == "maxwell":
        rate *= DSMC_FLIGHTS_MAXWELL_SPEEDUP
    seconds = flights / rate
    return Estimate(seconds, _mb(DSMC_BYTES_PER_PARTICLE * n_particles), f"{flights:.2e} flights")


# ------------------------------------------------------------------ cloning
CLONING_EVENTS_PER_SECOND = {1e3: 1.1e7, 1e4: 1.0e7, 1e5: 8.0e6, 1e6: 2.0e6}
"""Collision events of hard disks per CPU-second of kinetic.cloning against N_c. Three
paper.yaml scan jobs of 8.4 × 10⁸ planned events (Intel Xeon, one job at a time):
N_c = 10³, λ = 1.25: 68.4 CPU-s (1.23 × 10⁷ planned events a second); 3000, λ = −1.125:
83.4 s (1.01 × 10⁷); 10⁴, λ = 1: 75.1 s (1.12 × 10⁷). Until then 7.1 × 10⁶ at 10³ and
5.3 × 10⁶ at 10⁵, measured before the event loop went without reference counting: the
plan asked 1.6-1.8 times those jobs' time. At 10⁵ the bench's 9.1 × 10⁶ (kernel only,
AMD EPYC), less a tenth; at 10⁶ the front's 4 × 10⁶, halved."""

CLONING_MAXWELL_SPEEDUP = 3.5
"""Maxwell molecules collide every candidate (no acceptance test, no speed bound): events
per CPU-second over the hard disks' at the same N_c. Bench: 3.5 at N_c = 10³, 3.6 at 10⁵;
paper.yaml's Maxwell scan job of N_c = 10⁴, λ = 1.5: 21.2 CPU-s for 8.4 × 10⁸ events
(3.97 × 10⁷ a second, 3.9 times the hard disks' job of that N_c)."""

CLONING_BYTES_PER_MEMBER = 200.0
"""Front: peak RSS 262 MB at N_c = 10⁶ against 223 MB at 10³ (40 B per member), x5 for
the parent and offspring arrays of a cloning step."""


CLONING_GPU_SECONDS_PER_INTERVAL = 4.0e-4
"""``cuda`` backend, one H100: wall seconds of one control interval's launches when the
GPU has little to do (bench cuda: 0.28-0.43 ms from 10³ to 3 × 10⁵ clones a launch,
numba's dispatch of about 90 µs a launch). Measured with four launches an interval; three
since the interval's close moved into ``_weigh`` (2a3fd50), not yet timed: kept."""

CLONING_GPU_EVENTS_PER_SECOND = 2.5e9
"""``cuda`` backend, one H100: collision events per second of the untilted clones beyond
the launch cost (bench cuda: hard disks at λ = 1, 4 × 10⁶ clones, 2.2 × 10⁹ events per
wall second with the launches included)."""

CLONING_GPU_RESIDENT_MAX_POPULATION = 5_000
"""``kinetic.cloning.gpu.RESIDENT_MAX_POPULATION`` (a unit test keeps the two equal): up to
this N_c a realization's control intervals run in one thread block, one launch per block
of the run, without the launches of every interval."""

CLONING_GPU_THREADS_PER_BLOCK = 256
"""``kinetic.cloning.gpu.RESIDENT_THREADS`` on a GPU: the threads that share a resident
realization's clones (the ``RESIDENT_*`` constants are fitted at this count)."""

CLONING_GPU_RESIDENT_SECONDS_PER_EVENT = 4.4e-6
"""``cuda`` backend, resident kernel, 256 threads a realization: wall seconds of one
collision event of the untilted dynamics in one thread (an exponential, a uniform, a
square root and the proposal's Gaussian pair in float64). With
``CLONING_GPU_RESIDENT_SECONDS_PER_MEMBER`` and ``_PER_INTERVAL``, the three constants
that reproduce the three shapes timed with 256 threads on the H100 (revision 5836ea7,
bench cuda ``cloning_speed``'s ``resident_threads``, hard disks, Δ the default): 71.6 µs
an interval at N_c = 10³ (Δ = 1, 32 realizations), 655 µs at 10⁴ (Δ = 1) and 61.1 µs for
the grouped job's slowest realization (λ = 8, Δ = 0.406, 14 940 intervals of 10³ clones;
the job took 0.913 s). Three constants from three numbers: a fit with nothing left over
to check it. At 128 threads (revision 2984f74) the same model fitted 7.2 µs an event,
6.1 µs a clone and no interval cost."""

CLONING_GPU_RESIDENT_SECONDS_PER_MEMBER = 11.8e-6
"""``cuda`` backend, resident kernel: wall seconds one thread spends on each of its clones
every control interval besides the events (the weight, the scan, the copy into the new
population, the snapshot sums), from the same fit."""

CLONING_GPU_RESIDENT_SECONDS_PER_INTERVAL = 6.8e-6
"""``cuda`` backend, resident kernel: the block barriers and trees of one control interval
beyond the per-clone costs (256 threads), from the same fit."""

CLONING_GPU_HOST_BYTES_PER_MEMBER = 32.0
"""``cuda`` backend, host memory (a job's ``mem_mb``): the final velocities copied back
(up to 3 float64 components a member, for the count of distinct clones), rounded up."""


CLONING_GPU_RESIDENT_BLOCKS = 132
"""Resident-kernel thread blocks (one per realization of a point) an H100 runs at once:
132 SMs x 1 block of 256 threads. The H100 run of revision 5836ea7 reported ``_resident``
at 144 registers a thread (at most 384 threads a block): 36 864 a block of 256, and a
multiprocessor has 65 536. More blocks than this run one after another as blocks finish
(``cloning_points``)."""


CLONING_GPU_GROUPED_MAX_POPULATION = 100_000
"""With the ``cuda`` backend, the points of a (study, kernel, N_c) with N_c up to this run
in one job and the same launches (``kinetic.cloning.simulate_points``), on either path:
one job's startup instead of one per point, and the launched path's fixed cost of an
interval (``CLONING_GPU_SECONDS_PER_INTERVAL``) paid once for all the points' rows. 41
points of 32 realizations of 10⁵ clones hold 1.3 × 10⁸ clones: 16 GB of GPU memory at
120 bytes a clone (two velocity buffers, the stream, the count and the scan; an 80 GB
H100 holds it, a 16 GB card would not), 4 GB of host memory. A point of 10⁶ clones
fills the GPU alone."""


def _cloning_blocks(duration: float, transient: float, n_blocks: int) -> list[float]:
    """The block durations of a cloning realization, as the front cuts them
    (``kinetic.cloning.simulate``): the transient in blocks no shorter than a measured
    block, at most ``MAX_TRANSIENT_BLOCKS`` of them (the front's), then ``n_blocks`` measured."""
    block = duration / n_blocks
    transient_block = max(block, transient / MAX_TRANSIENT_BLOCKS)
    count = math.ceil(transient / transient_block - 1e-9) if transient else 0
    return [transient_block] * count + [block] * n_blocks


def _cloning_elapsed(duration: float, transient: float, n_blocks: int) -> float:
    """Simulated time of a cloning realization: the measured ``duration`` and the
    transient rounded up to whole blocks."""
    return sum(_cloning_blocks(duration, transient, n_blocks))


def _cloning_gpu(lam, population, elapsed, n_realizations, control_interval=None):
    """``cuda`` cloning of one point: (the latency of a realization, the collision
    events). Up to ``CLONING_GPU_RESIDENT_MAX_POPULATION`` clones the latency is that of one
    thread block running every interval (its barriers plus one thread's share of the
    events); above, the intervals' launches."""
    interval = control_interval or default_control_interval(lam)
    events = n_realizations * population * elapsed
    intervals = elapsed / interval
    if population <= CLONING_GPU_RESIDENT_MAX_POPULATION:
        per_thread = math.ceil(population / CLONING_GPU_THREADS_PER_BLOCK)
        latency = intervals * (
            per_thread
            * (
                CLONING_GPU_RESIDENT_SECONDS_PER_MEMBER
                + interval * CLONING_GPU_RESIDENT_SECONDS_PER_EVENT
            )
            + CLONING_GPU_RESIDENT_SECONDS_PER_INTERVAL
        )
    else:
        latency = intervals * CLONING_GPU_SECONDS_PER_INTERVAL
    return latency, events


def _launched_intervals(points) -> int:
    """Control intervals the launched path runs for ``points`` in the same launches: in
    each block of the run, as many as the point with the most (the others idle)."""
    per_point = []
    for point in points:
        interval = point.get("control_interval") or default_control_interval(point["lam"])
        blocks = _cloning_blocks(point["duration"], point["transient"], point["n_blocks"])
        per_point.append([max(1, math.ceil(block / interval - 1e-9)) for block in blocks])
    longest = max(len(steps) for steps in per_point)
    return sum(
        max(steps[b] if b < len(steps) else 0 for steps in per_point) for b in range(longest)
    )


def cloning_points(points) -> Estimate:
    """One ``cuda`` job of several cloning points in the same launches
    (``kinetic.cloning.simulate_points``, ``points`` its keyword arguments). Up to
    ``CLONING_GPU_RESIDENT_MAX_POPULATION`` clones every realization of every point is a
    thread block of the same launches, so the job lasts as long as its slowest realization,
    or all the realizations' latencies shared among the blocks the GPU holds at once, or
    the events at the GPU's rate, whichever is longest (the grouped shape of 41 λ × 32
    realizations of 10³ clones took 1.09 s with 128 threads at 5836ea7, its slowest
    realization's modelled 1.08; "waves × the slowest", the model before, planned 4.3);
    above, the launches of every interval of the point
    with the most in each block of the run plus every point's events at the GPU's rate.
    Plus one job's startup."""
    latency, total, events, members = 0.0, 0.0, 0.0, 0.0
    for point in points:
        elapsed = _cloning_elapsed(point["duration"], point["transient"], point["n_blocks"])
        one, count = _cloning_gpu(
            point["lam"],
            point["population"],
            elapsed,
            point["n_realizations"],
            point.get("control_interval"),
        )
        latency = max(latency, one)
        total += one * point["n_realizations"]
        events += count
        members += point["population"] * point["n_realizations"]
    if points[0]["population"] <= CLONING_GPU_RESIDENT_MAX_POPULATION:
        # a block starts as soon as one ends: the longest realization, or every
        # realization's latency shared among the blocks the GPU runs at once
        seconds = max(
            latency,
            total / CLONING_GPU_RESIDENT_BLOCKS,
            events / CLONING_GPU_EVENTS_PER_SECOND,
        )
    else:
        seconds = (
            _launched_intervals(points) * CLONING_GPU_SECONDS_PER_INTERVAL
            + events / CLONING_GPU_EVENTS_PER_SECOND
        )
    work = f"{events:.2e} collision events of {len(points)} points on one GPU"
    memory = _mb(CLONING_GPU_HOST_BYTES_PER_MEMBER * members)
    return Estimate(seconds + GPU_JOB_STARTUP_SECONDS, memory, work, gpus=1)


def cloning_batch(
    *,
    lam: float,
    population: int,
    duration: float,
    transient: float,
    n_blocks: int,
    n_realizations: int,
    histogram_bins: int = 120,
    backend: str = "cpu",
    control_interval: float | None = None,
    kernel: str = "hard_spheres",
    **_: object,
) -> Estimate:
    """``n_realizations`` realizations of kinetic.cloning.simulate: N_c c_λ events per unit
    time (c_λ = 1 for λ >= 0, 2e^{-λ} - 1 below) over the transient, rounded up to whole blocks, and
    the measured ``duration``. At large λ the transient (e^λ mean free times for a member
    to keep a few collisions) dominates. With ``backend='cuda'`` the untilted clones
    collide at the bath's rate (c = 1) and every realization runs in the same launches.
    Up to ``CLONING_GPU_RESIDENT_MAX_POPULATION`` clones, one thread block per realization
    runs all its intervals (the blocks in parallel): each interval costs its barriers plus
    the events of one thread's share of the clones, one after the other; larger
    populations cost the intervals' launches plus the events at the GPU's rate. On the
    CPU, ``kernel`` = "maxwell" runs ``CLONING_MAXWELL_SPEEDUP`` times the hard spheres'
    events a second."""
    rate_factor = 1.0 if lam >= 0 else 2.0 * math.exp(-lam) - 1.0
    elapsed = _cloning_elapsed(duration, transient, n_blocks)
    if backend == "cuda":
        latency, events = _cloning_gpu(lam, population, elapsed, n_realizations, control_interval)
        if population <= CLONING_GPU_RESIDENT_MAX_POPULATION:
            waves = math.ceil(n_realizations / CLONING_GPU_RESIDENT_BLOCKS)
            seconds = max(waves * latency, events / CLONING_GPU_EVENTS_PER_SECOND)
        else:
            seconds = latency + events / CLONING_GPU_EVENTS_PER_SECOND
        memory = _mb(CLONING_GPU_HOST_BYTES_PER_MEMBER * population * n_realizations)
        work = f"{events:.2e} collision events on one GPU"
        return Estimate(seconds + GPU_JOB_STARTUP_SECONDS, memory, work, gpus=1)
    events = n_realizations * population * rate_factor * elapsed
    rate = _interpolate(population, CLONING_EVENTS_PER_SECOND)
    if kernel == "maxwell":
        rate *= CLONING_MAXWELL_SPEEDUP
    seconds = events / rate
    memory = _mb(CLONING_BYTES_PER_MEMBER * population + 8.0 * histogram_bins * n_blocks * 4)
    return Estimate(seconds, memory, f"{events:.2e} collision events")


# ------------------------------------------------------------------ samplers
DIRECT_PIN_CONFIGURATIONS_PER_SECOND = 2.1e6
"""README: direct-pin configurations of 15 pins per CPU-second (cost grows like N)."""

NAIVE_PIN_TRIES_PER_SECOND = 1.6e4 / 1.3e-3
"""README: naive-pin 1.6 × 10⁴ accepted configurations/s at acceptance 1.3 × 10⁻³."""

RING_SWEEPS_PER_SECOND = 8e5
"""Front: 1.6 × 10⁶ sweeps of 15 pins per second (local moves on the ring), halved."""

DIRECT_DISKS_PER_SECOND = 8e5
"""Front: direct-disks 1.6 × 10⁶ configurations of 4 disks (σ = 0.15, unit box) per
second, halved, at :data:`DIRECT_DISKS_ACCEPTANCE`; a configuration costs about the
inverse of its acceptance."""

DIRECT_DISKS_ACCEPTANCE = 0.0365
"""The legal fraction of direct-disks starts at 4 disks, σ = 0.15, unit box
(``theory.krauth2025.direct_disks_acceptance``)."""

MARKOV_DISKS_SWEEPS_PER_SECOND = 3e6
"""Front: markov-disks 1.3 × 10⁷ sweeps of 4 disks per second, divided by 4."""


def sampler_line(
    method: str,
    *,
    n_pins: int,
    length: float,
    sigma: float,
    samples: int,
    realizations: int,
    **_: object,
) -> Estimate:
    """kinetic.samplers.sample_line: ``samples`` x ``realizations`` configurations."""
    configurations = samples * realizations
    if method == "naive":
        free = length - 2 * n_pins * sigma
        acceptance = (free / (length - 2 * sigma)) ** n_pins if free > 0 else 0.0
        tries = configurations / acceptance if acceptance > 0 else math.inf
        seconds = tries / NAIVE_PIN_TRIES_PER_SECOND * n_pins / 15.0
        return Estimate(seconds, 10.0, f"{tries:.2e} naive-pin tries")
    seconds = configurations / DIRECT_PIN_CONFIGURATIONS_PER_SECOND * n_pins / 15.0
    return Estimate(seconds, 10.0, f"{configurations:.2e} configurations")


def sampler_ring(
    *, n_pins: int, sweeps: int, burn_in: int, realizations: int, **_: object
) -> Estimate:
    """kinetic.samplers.sample_ring: ``realizations`` x (burn_in + sweeps) sweeps."""
    total = realizations * (sweeps + burn_in)
    seconds = total / RING_SWEEPS_PER_SECOND * n_pins / 15.0
    return Estimate(seconds, 10.0, f"{total:.2e} sweeps")


def sampler_disks(
    method: str,
    *,
    n_disks: int,
    samples: int,
    realizations: int,
    burn_in: int = 0,
    acceptance: float = DIRECT_DISKS_ACCEPTANCE,
    **_: object,
) -> Estimate:
    """kinetic.samplers.sample_disks: direct-disks configurations (each about
    1/``acceptance`` starts) or markov-disks sweeps."""
    if method == "markov":
        total = realizations * (samples + burn_in)
        seconds = total / MARKOV_DISKS_SWEEPS_PER_SECOND * n_disks / 4.0
        return Estimate(seconds, 10.0, f"{total:.2e} sweeps")
    total = realizations * samples
    seconds = total / DIRECT_DISKS_PER_SECOND * (n_disks / 4.0) ** 2
    seconds *= DIRECT_DISKS_ACCEPTANCE / max(acceptance, 1e-300)
    return Estimate(seconds, 10.0, f"{total:.2e} configurations")


# ------------------------------------------------------------------ fixed-size jobs
COMPILE_SECONDS = {
    "edmd": 18.0,
    "event_disks": 7.0,
    "dsmc": 18.0,
    "cloning": 5.4,
    "samplers": 2.5,
}
"""Compiling one engine's kernels into numba's cache (``kinetic.jit.warm``, in the first
simulation job after an edit), measured in a default build from a clean clone on the
development machine (2026-11-24, the other core busy); edmd's 25 s then included
event-disks, split 0.71 : 0.29 as the two warmups took in one fresh cache (2026-11-26)."""


def small_job(seconds: float = 10.0, **_: object) -> Estimate:
    """A job of a few seconds whatever the config (snapshots, a few hundred events)."""
    return Estimate(float(seconds), 10.0, "fixed")
