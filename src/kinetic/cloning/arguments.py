"""Argument checks of the cloning Monte Carlo, without the engine: numpy only.

``kinetic.cloning.simulate`` calls ``validate_parameters`` before any work, and the
workflow calls it on every visco2008 cloning job while it reads the config (no compiled
kernel is loaded for that); ``kinetic.cost`` plans GPU jobs with
``default_control_interval`` and ``MAX_TRANSIENT_BLOCKS``.
"""

from __future__ import annotations

import math
import numbers

from kinetic import backends, validate
from kinetic.gas import HARD_SPHERES, MAXWELL

__all__ = [
    "CONTROL_WEIGHT_VARIANCE",
    "KERNELS",
    "LAMBDA_MAX",
    "LAMBDA_MIN",
    "MAX_CONTROL_INTERVAL",
    "MAX_CUDA_HISTOGRAM_BINS",
    "MAX_SINGLE_REALIZATION_LAMBDA",
    "MAX_TRANSIENT_BLOCKS",
    "MAX_WEIGHT_VARIANCE_PER_CLONE",
    "MIN_COMPENSATIONS",
    "MIN_KEPT_COLLISIONS",
    "MIN_SINGLE_REALIZATION_BLOCK",
    "default_control_interval",
    "validate_parameters",
]

KERNELS = {"hard_spheres": HARD_SPHERES, "maxwell": MAXWELL}
"""Collision kernels: hard spheres (rate ∝ (g·σ̂)⁺; hard disks in d = 2) and Maxwell
molecules (constant rate)."""

LAMBDA_MIN = -4.0
"""Most negative supported tilt. Below it the time-rescaled dynamics (Eq. 56) needs
2e^{-λ} - 1 > 108 events per collision time, most of them duplications, and the
finite-population bias of the hard-sphere kernel (≈ -0.45/N_c in μ at λ = -1.5) has not
been validated against the reference solution."""

LAMBDA_MAX = 20.0
"""Largest supported tilt. The transient criterion (``MIN_KEPT_COLLISIONS``) asks for at
least e^λ/r_min mean free times of discarded transient, about as many collisions a
member: 6.9 × 10⁸ at λ = 20 for hard spheres, over a minute a member on one core at the
engine's 10⁷ events/s, hours for a population of 100; beyond it the transient alone
passes 10⁹ collisions a member (at the former bound of 30, 1.5 × 10¹³). The documents go
up to λ = 8."""

MIN_KEPT_COLLISIONS = 1.0
"""Each member must keep at least this many collisions on average during the discarded
transient (transient · e^{-λ} · r_min >= 1, with r_min = 1/√2 for hard spheres, 1 for
Maxwell molecules). At large λ almost every collision annihilates, the population only
selects among the velocities it already holds and clones of a few slow members take
over (diversity collapse); without renewal it still remembers its initial bath sample."""


MIN_SINGLE_REALIZATION_BLOCK = 10.0
"""Shortest block (``duration``/``n_blocks``, mean free times) of a run of one realization,
whose error bars come from its blocks: block means must be nearly independent. Measured
(hard disks, N_c = 100, one realization of 3000 mean free times, re-blocked): at λ = 1 the
standard error of T from blocks of 1, 3, 10, 30 and 100 mean free times is 2.0, 3.0, 4.0,
4.4 and 4.0 × 10⁻³ (μ's 1.25, 1.34, 1.31, 1.43, 1.53 × 10⁻³); at λ = −1 T's is flat from 10
on. Blocks of 10⁻¹³ gave μ = 0 ± 0 at λ = −0.5 (the exact value is 0.67). At large λ T
correlates longer still (λ = 4: 1.7 × 10⁻³ at 10, 3.5 × 10⁻³ at 100): there several
realizations are the error bar to trust."""

MAX_SINGLE_REALIZATION_LAMBDA = 1.0
"""Largest λ of a run of one realization. Its error bars come from its blocks, whose
correlation grows with λ: against the spread of 48 independent realizations (hard disks,
N_c = 200, 10 blocks of 10 mean free times) the block errors of μ, T and μ_rate were 0.98,
0.93 and 0.89 of the true ones at λ = 1, 0.61, 0.45 and 0.42 at λ = 3, 0.62, 0.26 and 0.24
at λ = 4. Above it, several realizations give the error bar."""

MIN_COMPENSATIONS = 10.0
"""Fewest compensation events (annihilations at λ > 0, duplications at λ < 0) a realization
is expected to make in its measured time at the slowest rate, |e^{-λ} − 1| r_min N_c t:
a run of 10⁻⁶ mean free times made one candidate and returned μ = 0 ± 0 (exact 0.665).
With 10 or more, every realization making none has a chance below e^{-10} each, and the
realizations' spread is an error bar (a wide one: the numbers are for tests, not
production, whose runs make 10⁵ and more)."""

CONTROL_WEIGHT_VARIANCE = 0.5
"""The ``cuda`` backend's control interval Δ keeps the relative variance of a clone's
weight e^{-λK} below this value for a Poisson count K of mean Δ (the count of a clone at
rest in a hard-sphere bath, r(0) = 1/√2, is slower; fast clones are more variable):
exp(Δ (e^{-λ} - 1)²) - 1 <= CONTROL_WEIGHT_VARIANCE, and Δ <= ``MAX_CONTROL_INTERVAL``."""

MAX_CONTROL_INTERVAL = 1.0
"""Longest control interval of the ``cuda`` backend, in mean free times."""

MAX_WEIGHT_VARIANCE_PER_CLONE = 0.5
"""Largest v/N_c of a control interval given explicitly (v = exp(Δ (e^{-λ} - 1)²) - 1, the
relative variance of a clone's weight, as in ``CONTROL_WEIGHT_VARIANCE``): the selection's
bias in μ, about -v/(2 N_c Δ), is first order in v/N_c only while that is small. The GPU
tests run Maxwell molecules at v/N_c = 0.25 and 0.4 (16 clones at λ = 1, Δ = 4 and 5), the
bench's study of Δ at 0.0012 (10³ clones, λ = 1, Δ = 2); Δ = 1 at λ = -2 with 32 clones
(v = 5 × 10¹⁷) gave μ = 4.49 ± 0.29 against e² - 1 = 6.39, and no error but an after-run
collapse warning said so."""


def default_control_interval(lam: float) -> float:
    """Control interval Δ of the ``cuda`` backend at tilt ``lam`` (see
    ``CONTROL_WEIGHT_VARIANCE``): Δ = ln(1 + v)/(e^{-λ} - 1)², at most
    ``MAX_CONTROL_INTERVAL``."""
    spread = math.expm1(-lam) ** 2
    if spread == 0.0:
        return MAX_CONTROL_INTERVAL
    return min(MAX_CONTROL_INTERVAL, math.log1p(CONTROL_WEIGHT_VARIANCE) / spread)


MAX_CUDA_HISTOGRAM_BINS = 1024
"""Most velocity-histogram bins of the ``cuda`` backend (one shared-memory histogram per
thread block)."""


MAX_TRANSIENT_BLOCKS = 50
"""The discarded transient is split into at most this many blocks."""


def _slowest_rate(kernel: str) -> float:
    return 1.0 / math.sqrt(2.0) if kernel == "hard_spheres" else 1.0


def _check_integer(name, value, minimum, maximum=None):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    if value < minimum or (maximum is not None and value > maximum):
        upper = f" and <= {maximum}" if maximum is not None else ""
        raise ValueError(f"{name} must be >= {minimum}{upper}, got {value}")
    return int(value)


def _check_real(name, value, *, minimum=None, strictly_positive=False):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value}")
    if strictly_positive and value <= 0.0:
        raise ValueError(f"{name} must be > 0, got {value}")
    if minimum is not None and value < minimum:
        raise ValueError(f"{name} must be >= {minimum}, got {value}")
    return value


def validate_parameters(
    *,
    kernel,
    dimension,
    lam,
    population,
    duration,
    transient,
    n_blocks,
    n_realizations,
    first_realization,
    seed,
    histogram_half_width,
    histogram_bins,
    backend="cpu",
    control_interval=None,
):
    """Check every argument of ``simulate``; return them normalised to Python types.

    Raises ``TypeError``/``ValueError`` naming the bad value and the allowed range.
    """
    if kernel not in KERNELS:
        raise ValueError(f"kernel must be one of {sorted(KERNELS)}, got {kernel!r}")
    dimension = _check_integer("dimension", dimension, 2, 3)
    lam = _check_real("lam", lam)
    if not LAMBDA_MIN <= lam <= LAMBDA_MAX:
        reason = (
            "below it the time-rescaled duplication dynamics (Eq. 56) is not validated"
            if lam < LAMBDA_MIN
            else "beyond it the transient the population needs to forget its start costs "
            "more than 1e9 collisions a member (LAMBDA_MAX)"
        )
        raise ValueError(f"lam must be in [{LAMBDA_MIN}, {LAMBDA_MAX}] ({reason}), got {lam}")
    population = _check_integer("population", population, 2, 10**8)
    duration = _check_real("duration", duration, strictly_positive=True)
    transient = _check_real("transient", transient, minimum=0.0)
    n_blocks = _check_integer("n_blocks", n_blocks, 1, 10**6)
    n_realizations = _check_integer("n_realizations", n_realizations, 1, 10**6)
    first_realization, _ = validate.realizations(
        first_realization, n_realizations, count_name="n_realizations"
    )
    seed = validate.seed(seed)
    if n_realizations == 1 and n_blocks < 2:
        raise ValueError("a single realization needs n_blocks >= 2 for a block error bar, got 1")
    if n_realizations == 1 and duration / n_blocks < MIN_SINGLE_REALIZATION_BLOCK:
        raise ValueError(
            f"a single realization's error bar comes from its blocks, and blocks of "
            f"duration/n_blocks = {duration / n_blocks:.3g} mean free times are correlated "
            f"(shorter than {MIN_SINGLE_REALIZATION_BLOCK:g}, see "
            f"MIN_SINGLE_REALIZATION_BLOCK): use n_realizations >= 2, n_blocks <= "
            f"{max(1, math.floor(duration / MIN_SINGLE_REALIZATION_BLOCK))} or duration >= "
            f"{MIN_SINGLE_REALIZATION_BLOCK * n_blocks:g}"
        )
    if n_realizations == 1 and lam > MAX_SINGLE_REALIZATION_LAMBDA:
        raise ValueError(
            f"a single realization's error bar comes from its blocks, which are correlated "
            f"beyond their length at lam = {lam:g} (their errors came out 2-4 times too small "
            f"at lam = 3-4; MAX_SINGLE_REALIZATION_LAMBDA = {MAX_SINGLE_REALIZATION_LAMBDA:g}): "
            "use n_realizations >= 2"
        )
    expected = abs(math.expm1(-lam)) * _slowest_rate(kernel) * population * duration
    if lam != 0.0 and expected < MIN_COMPENSATIONS:
        raise ValueError(
            f"duration = {duration:g} is too short at lam = {lam:g}: a realization of "
            f"{population} members would make about {expected:.3g} compensation events in it "
            f"(|e^-lam - 1| r_min N_c duration), fewer than {MIN_COMPENSATIONS:g}, and mu "
            "would come from a handful of them (a run of 1e-6 gave mu = 0 +- 0); use "
            f"duration >= {MIN_COMPENSATIONS / (expected / duration):.4g}"
        )
    histogram_half_width = _check_real(
        "histogram_half_width", histogram_half_width, strictly_positive=True
    )
    histogram_bins = _check_integer("histogram_bins", histogram_bins, 1, 10**6)
    backends.check(backend)
    backends.check_realizations(backend, n_realizations)
    # the host's arrays: a population (~200 B a member with a cloning step's parents and
    # offspring; on cuda the final velocities of every realization, 32 B a member, the
    # populations living on the GPU: kinetic.cost) and the per-block results
    members = 32.0 * n_realizations if backend == "cuda" else 200.0
    validate.fits_in_memory(
        f"population = {population}, n_realizations = {n_realizations}, n_blocks = "
        f"{n_blocks} and histogram_bins = {histogram_bins}",
        members * population + 8.0 * n_realizations * (8 * n_blocks + histogram_bins),
    )
    if backend == "cuda" and histogram_bins > MAX_CUDA_HISTOGRAM_BINS:
        raise ValueError(
            f"histogram_bins must be <= {MAX_CUDA_HISTOGRAM_BINS} with backend 'cuda' "
            f"(a shared-memory histogram per thread block), got {histogram_bins}"
        )
    if control_interval is not None:
        if backend != "cuda":
            raise ValueError(
                f"control_interval = {control_interval!r} is for backend 'cuda' only: the "
                "CPU engine's continuous-time algorithm selects at every collision and has "
                "no control interval (leave it None)"
            )
        control_interval = _check_real("control_interval", control_interval, strictly_positive=True)
        spread = math.expm1(-lam) ** 2  # 0 at λ = 0: every weight is 1, any interval holds
        largest = math.log1p(MAX_WEIGHT_VARIANCE_PER_CLONE * population) / max(spread, 1e-300)
        if spread > 0.0 and control_interval > largest:
            raise ValueError(
                f"control_interval = {control_interval:g} is too long at lam = {lam:g} for "
                f"{population} clones: a clone's weight would vary by v = exp(interval "
                f"(e^-lam - 1)^2) - 1 = {math.expm1(min(control_interval * spread, 700.0)):.3g}, "
                f"and the selection's bias is small only while v/N_c <= "
                f"{MAX_WEIGHT_VARIANCE_PER_CLONE:g} (MAX_WEIGHT_VARIANCE_PER_CLONE): use "
                f"control_interval <= {largest:.4g} (default {default_control_interval(lam):.4g})"
            )
    kept = transient * math.exp(-lam) * _slowest_rate(kernel)
    # (a transient chosen as exactly MIN_KEPT_COLLISIONS e^λ/r_min gives kept within
    # rounding of the bound: not refused)
    if kept < MIN_KEPT_COLLISIONS * (1.0 - 1e-12):
        needed = MIN_KEPT_COLLISIONS / (math.exp(-lam) * _slowest_rate(kernel))
        raise ValueError(
            f"transient={transient:g} is too short at lam={lam:g}: a member keeps on average "
            f"{kept:.3g} collisions during it (fraction e^-lam = {math.exp(-lam):.3g} of its "
            f"collisions), fewer than {MIN_KEPT_COLLISIONS:g}; the population would still "
            f"hold clones of its initial bath sample (diversity collapse). "
            f"Use transient >= {needed:.4g}."
        )
    checked = {
        "kernel": kernel,
        "dimension": dimension,
        "lam": lam,
        "population": population,
        "duration": duration,
        "transient": transient,
        "n_blocks": n_blocks,
        "n_realizations": n_realizations,
        "first_realization": first_realization,
        "seed": seed,
        "histogram_half_width": histogram_half_width,
        "histogram_bins": histogram_bins,
        "backend": backend,
    }
    if backend == "cuda":  # the CPU engine's algorithm has no control interval
        checked["control_interval"] = control_interval or default_control_interval(lam)
    return checked
