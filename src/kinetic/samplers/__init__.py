"""Direct and Markov-chain samplers of krauth2025 (§4.4.1: random clothes-pins).

Fronts that validate their arguments, run the numba kernels of
``kinetic.samplers.kernels`` in independent seeded realizations (a run of one sampler,
or one Markov chain) and return an ``xarray.Dataset`` (conventions of ``kinetic.io``)
whose densities carry the standard error of the realization means:

- ``sample_line``: pin-centre density n(x) = N π(x) of N pins on a washing line [0, L],
  by naive-pin (Alg. 4.6) or direct-pin (Alg. 4.7);
- ``sample_ring``: density of the other pins at forward distance r from a pin, N pins on
  a ring of circumference L, by local Markov-chain moves (independent chains);
- ``pin_snapshots``: a few direct-pin configurations (krauth2025 Fig. 4.10);
- ``sample_disks``: projected density η(y) of N hard disks in a box with walls (§4.3),
  by direct-disks (Alg. 4.4) or markov-disks (Alg. 4.5);
- ``disk_configuration``: one direct-disks configuration (the start of an MD run);
- ``lattice_configuration``: N disks on rows in the box, the start of markov-disks where
  direct-disks' legal configurations are too rare (``MIN_DIRECT_START_ACCEPTANCE``).

Lengths are in units of the pin width 2σ if σ = 1/2 (the configs' choice).
"""

from __future__ import annotations

import time

import numpy as np
import xarray as xr

from kinetic import io
from kinetic.analysis.statistics import mean_and_sem
from kinetic.progress import Progress
from kinetic.rng import stream_states
from kinetic.samplers import kernels
from kinetic.theory.krauth2025 import (
    check_direct_disks_starts,
    check_disk_box,
    check_naive_starts,
    check_pins,
    direct_disks_acceptance,
    naive_acceptance,
)
from kinetic.validate import real

__all__ = [
    "MIN_DIRECT_START_ACCEPTANCE",
    "disk_configuration",
    "lattice_configuration",
    "naive_acceptance",
    "pin_snapshots",
    "sample_disks",
    "sample_line",
    "sample_ring",
    "warmup",
]


MIN_DIRECT_START_ACCEPTANCE = 1e-6
"""Below this legal fraction of direct-disks starts (10⁶ starts a configuration, about a
hundredth of a CPU-s at four disks and growing with N), a markov-disks chain starts from
``lattice_configuration`` instead, and its ``burn_in`` sweeps carry it to equilibrium."""


def _positive_int(name: str, value, minimum: int = 1) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


def _density_dataset(
    counts: np.ndarray,
    per_sample: float,
    lower: float,
    upper: float,
    *,
    name: str,
    axis: str,
    what: str,
    extra: dict,
    parameters: dict,
    seed: int,
) -> xr.Dataset:
    """Dataset of a histogrammed density from independent realizations: ``counts``
    (realizations, bins) on [lower, upper), each realization of ``per_sample`` samples
    times its members; ``name`` (per unit length, mean of the realizations) and
    ``name_sem`` (standard error from their spread), the counts, the bin edges and
    ``extra`` variables (on the realization dimension)."""
    realizations, bins = counts.shape
    width = (upper - lower) / bins
    mean, sem = mean_and_sem(counts / (per_sample * width))
    edges = np.linspace(lower, upper, bins + 1)
    data = {
        name: (axis, mean, "1/length", what),
        f"{name}_sem": (
            axis,
            sem,
            "1/length",
            f"standard error of the {name.replace('_', ' ')} (spread of the realization means)",
        ),
        "counts": (("realization", axis), counts, "1", "samples counted per bin and realization"),
        "bin_edges": ("edge", edges, "length", "bin edges"),
        **extra,
    }
    coords = {
        axis: (axis, 0.5 * (edges[1:] + edges[:-1]), "length", f"{axis} (bin middle)"),
        "realization": ("realization", np.arange(realizations), "1", "independent realization"),
        "edge": ("edge", np.arange(bins + 1), "1", "bin edge index"),
    }
    return io.stamp(io.make_dataset(data, coords), parameters=parameters, seed=seed)


def sample_line(
    method: str,
    *,
    n_pins: int,
    length: float,
    sigma: float,
    samples: int,
    realizations: int,
    bins: int,
    seed: int,
) -> xr.Dataset:
    """Pin-centre density on [σ, L − σ] from ``realizations`` independent runs of
    ``samples`` configurations each (``method`` 'naive' or 'direct').

    Returns ``density`` (pins per unit length, the mean of the realizations), its
    standard error ``density_sem``, the ``counts`` per realization and, for naive-pin,
    the configurations ``started`` per realization (their accepted fraction estimates
    Z_{N,L}/(L − 2σ)^N).
    """
    if method not in ("naive", "direct"):
        raise ValueError(f"method must be 'naive' or 'direct', got {method!r}")
    check_pins(n_pins, length, sigma)
    n_pins, length, sigma = int(n_pins), float(length), float(sigma)  # the compiled types
    samples = _positive_int("samples", samples)
    realizations = _positive_int("realizations", realizations, 2)
    bins = _positive_int("bins", bins)
    if method == "naive":
        check_naive_starts(n_pins, length, sigma, samples * realizations)
    lower, upper = sigma, length - sigma
    states = stream_states(seed, realizations)
    counts = np.zeros((realizations, bins), dtype=np.int64)
    started = np.zeros(realizations, dtype=np.int64)
    positions = np.zeros(n_pins)
    cpu = np.zeros(realizations)
    progress = Progress(
        realizations, label=f"{method}-pin N={n_pins} L={length:g}", unit="realizations"
    )
    # load the compiled kernel before the clock runs (no samples, no draws)
    kernel = kernels.naive_pin if method == "naive" else kernels.direct_pin
    kernel(n_pins, length, sigma, 0, states[0].copy(), positions, counts[0], lower, upper)
    for r in range(realizations):
        begin = time.process_time()
        arguments = (n_pins, length, sigma, samples, states[r], positions, counts[r], lower, upper)
        if method == "naive":
            started[r] = kernels.naive_pin(*arguments)[0]
        else:
            kernels.direct_pin(*arguments)
            started[r] = samples
        cpu[r] = time.process_time() - begin
        progress.update(1)
    parameters = {
        "method": method,
        "n_pins": n_pins,
        "length": float(length),
        "sigma": float(sigma),
        "samples": samples,
        "realizations": realizations,
        "bins": bins,
    }
    extra = {
        "started": (
            "realization",
            started,
            "1",
            "configurations started (naive-pin: incl. rejected)",
        ),
        "cpu_seconds": ("realization", cpu, "s", "CPU time per realization"),
    }
    return _density_dataset(
        counts,
        samples,
        lower,
        upper,
        name="density",
        axis="x",
        what="pin centres per unit length",
        extra=extra,
        parameters=parameters,
        seed=seed,
    )


def sample_ring(
    *,
    n_pins: int,
    length: float,
    sigma: float,
    step: float,
    sweeps: int,
    burn_in: int,
    realizations: int,
    bins: int,
    seed: int,
) -> xr.Dataset:
    """Pair density on a ring from ``realizations`` independent Markov chains.

    Each chain starts from equally spaced pins, runs ``burn_in`` sweeps (N attempted moves
    of a uniform step in [−δ, δ], δ = ``step``), then ``sweeps`` sweeps after each of which
    it records every forward pair distance. Returns ``pair_density`` (other pins per unit
    length at distance r from a pin, integrating to N − 1; the mean of the chains), its
    standard error ``pair_density_sem`` and each chain's ``acceptance``.
    """
    check_pins(n_pins, length, sigma)
    if n_pins < 2:
        raise ValueError("a pair density needs n_pins >= 2")
    n_pins, length, sigma = int(n_pins), float(length), float(sigma)
    step = real("step", step, 0.0, length / 2, low_open=True)  # at most half the ring
    sweeps = _positive_int("sweeps", sweeps)
    burn_in = _positive_int("burn_in", burn_in, 0)
    realizations = _positive_int("realizations", realizations, 2)
    bins = _positive_int("bins", bins)
    states = stream_states(seed, realizations)
    counts = np.zeros((realizations, bins), dtype=np.int64)
    acceptance = np.zeros(realizations)
    cpu = np.zeros(realizations)
    progress = Progress(realizations, label=f"ring N={n_pins} L={length:g}", unit="realizations")
    kernels.ring_markov(  # load the compiled kernel before the clock runs
        n_pins,
        length,
        sigma,
        step,
        0,
        0,
        states[0].copy(),
        np.arange(n_pins) * (length / n_pins),
        counts[0],
    )
    for r in range(realizations):
        positions = np.arange(n_pins) * (length / n_pins)
        begin = time.process_time()
        accepted = kernels.ring_markov(
            n_pins, length, sigma, step, sweeps, burn_in, states[r], positions, counts[r]
        )
        cpu[r] = time.process_time() - begin
        acceptance[r] = accepted / ((sweeps + burn_in) * n_pins)
        progress.update(1)
    parameters = {
        "method": "markov",
        "n_pins": n_pins,
        "length": float(length),
        "sigma": float(sigma),
        "step": float(step),
        "sweeps": sweeps,
        "burn_in": burn_in,
        "realizations": realizations,
        "bins": bins,
    }
    extra = {
        "acceptance": ("realization", acceptance, "1", "accepted fraction of the moves"),
        "cpu_seconds": ("realization", cpu, "s", "CPU time per realization"),
    }
    return _density_dataset(
        counts,
        sweeps * n_pins,
        0.0,
        length,
        name="pair_density",
        axis="r",
        what="other pins per unit length at forward distance r from a pin",
        extra=extra,
        parameters=parameters,
        seed=seed,
    )


def pin_snapshots(*, n_pins: int, length: float, sigma: float, count: int, seed: int) -> xr.Dataset:
    """``count`` independent direct-pin configurations (pin centres, increasing)."""
    check_pins(n_pins, length, sigma)
    n_pins, length, sigma = int(n_pins), float(length), float(sigma)
    count = _positive_int("count", count)
    state = stream_states(seed, 1)[0]
    positions = np.zeros((count, n_pins))
    for s in range(count):
        kernels.direct_pin_configuration(n_pins, length, sigma, state, positions[s])
    data = {"position": (("snapshot", "pin"), positions, "length", "pin centre")}
    coords = {
        "snapshot": ("snapshot", np.arange(count), "1", "configuration"),
        "pin": ("pin", np.arange(n_pins), "1", "pin, from the left"),
    }
    parameters = {"n_pins": n_pins, "length": float(length), "sigma": float(sigma)}
    return io.stamp(io.make_dataset(data, coords), parameters=parameters, seed=seed)


def lattice_configuration(n_disks: int, sigma: float, box=(1.0, 1.0)) -> np.ndarray:
    """(N, 2) centres of N disks of radius σ on rows in the box with walls, legal (no
    overlap, centres in [σ, L − σ]): of the square and the staggered (every other row
    shifted by half a spacing) layouts of every row count, the one whose closest pair is
    farthest apart. ``ValueError`` if none holds N disks (the box is denser than rows
    allow). Not an equilibrium sample: a Markov chain's burn-in starts from it."""
    box_x, box_y = check_disk_box(n_disks, sigma, box)
    n_disks, sigma = int(n_disks), float(sigma)
    width, height = box_x - 2.0 * sigma, box_y - 2.0 * sigma
    best, best_gap = None, -1.0
    for rows in range(1, n_disks + 1):
        columns = -(-n_disks // rows)
        dy = height / (rows - 1) if rows > 1 else np.inf
        for staggered in (False, True) if rows > 1 and columns > 1 else (False,):
            if columns == 1:
                dx = np.inf
            elif staggered:  # the shifted rows need half a spacing of room
                dx = width / (columns - 0.5)
            else:
                dx = width / (columns - 1)
            # staggered: neighbours in the next row, and the row after it right above
            gap = min(np.hypot(0.5 * dx, dy), 2.0 * dy) if staggered else dy
            gap = min(dx, gap)
            if gap > best_gap:
                best_gap, best = gap, (rows, columns, dx, dy, staggered)
    rows, columns, dx, dy, staggered = best
    if best_gap < 2.0 * sigma * (1.0 - 1e-12):
        raise ValueError(
            f"{n_disks} disks of radius {sigma} do not fit on rows in the box "
            f"({box_x}, {box_y}): the closest pair would be {best_gap:.4g} apart"
        )
    sites = []
    for row in range(rows):
        shift = 0.5 * dx if staggered and row % 2 else 0.0
        for column in range(columns):
            x = sigma + (column * dx if columns > 1 else 0.5 * width) + shift
            y = sigma + (row * dy if rows > 1 else 0.5 * height)
            sites.append((x, y))
    return np.array(sites[:n_disks])


def disk_configuration(
    n_disks: int, sigma: float, box=(1.0, 1.0), *, state: np.ndarray, max_starts: int = 10**8
) -> np.ndarray:
    """(N, 2) centres of one direct-disks configuration drawn with the stream ``state``;
    ``ValueError`` if ``max_starts`` tries do not produce one (too dense for Alg. 4.4)."""
    box_x, box_y = check_disk_box(n_disks, sigma, box)
    n_disks, sigma = int(n_disks), float(sigma)
    positions = np.zeros((n_disks, 2))
    if (
        kernels.direct_disks_configuration(
            n_disks, sigma, box_x, box_y, state, positions, max_starts
        )
        < 0
    ):
        raise ValueError(
            f"direct-disks found no legal configuration of {n_disks} disks of radius "
            f"{sigma} in {max_starts} tries: too dense for tabula-rasa sampling"
        )
    return positions


def sample_disks(
    method: str,
    *,
    n_disks: int,
    sigma: float,
    box=(1.0, 1.0),
    samples: int,
    realizations: int,
    bins: int,
    seed: int,
    step: float = 0.1,
    burn_in: int = 1000,
) -> xr.Dataset:
    """Projected density η(y) (disk centres per unit length of y, summed over x) of N
    disks of radius σ in a box with walls, on [σ, L_y − σ], from ``realizations``
    independent runs: ``samples`` direct-disks configurations (``method`` 'direct') or ``samples``
    recorded sweeps of one markov-disks chain (``method`` 'markov', moves uniform in
    [−step, step]², after ``burn_in`` sweeps from a direct-disks start, or from
    ``lattice_configuration`` where direct-disks' starts are legal less often than
    ``MIN_DIRECT_START_ACCEPTANCE``: the dataset's ``start`` parameter says which)."""
    if method not in ("direct", "markov"):
        raise ValueError(f"method must be 'direct' or 'markov', got {method!r}")
    box_x, box_y = check_disk_box(n_disks, sigma, box)
    n_disks, sigma = int(n_disks), float(sigma)
    samples = _positive_int("samples", samples)
    realizations = _positive_int("realizations", realizations, 2)
    bins = _positive_int("bins", bins)
    burn_in = _positive_int("burn_in", burn_in, 0)
    step = real("step", step, 0.0, min(box_x, box_y), low_open=True)
    # direct-disks draws all its samples by starting again on any overlap: refuse a box
    # whose legal configurations are too rare for that; a chain starts from a lattice
    # there (and so from a legal state whatever the density)
    if method == "direct":
        check_direct_disks_starts(n_disks, sigma, (box_x, box_y), samples * realizations)
        lattice = False
    else:
        acceptance = direct_disks_acceptance(n_disks, sigma, (box_x, box_y))
        lattice = acceptance < MIN_DIRECT_START_ACCEPTANCE
        first = lattice_configuration(n_disks, sigma, (box_x, box_y)) if lattice else None
    lower, upper = sigma, box_y - sigma
    states = stream_states(seed, realizations)
    counts = np.zeros((realizations, bins), dtype=np.int64)
    started = np.zeros(realizations, dtype=np.int64)
    cpu = np.zeros(realizations)
    progress = Progress(realizations, label=f"{method}-disks N={n_disks}", unit="realizations")

    def run(count, burn, state, positions, histogram):
        """``count`` samples (recorded sweeps) into ``histogram``: configurations started or
        moves accepted."""
        if method == "direct":
            return kernels.direct_disks(
                n_disks, sigma, box_x, box_y, count, state, positions, histogram, lower, upper
            )
        return kernels.markov_disks(
            kernels.Box(int(n_disks), float(sigma), float(box_x), float(box_y)),
            kernels.Chain(float(step), int(count), int(burn)),
            state,
            positions,
            histogram,
            lower,
            upper,
        )

    for r in range(realizations):
        # the start and the loading of the compiled kernel stay out of the CPU time
        if lattice:
            positions = first.copy()
        else:
            positions = disk_configuration(n_disks, sigma, (box_x, box_y), state=states[r])
        if r == 0:
            run(0, 0, states[0].copy(), positions.copy(), counts[0])
        begin = time.process_time()
        started[r] = run(samples, burn_in, states[r], positions, counts[r])
        cpu[r] = time.process_time() - begin
        if started[r] < 0:
            raise RuntimeError(
                f"direct-disks needed more than {kernels.MAX_CONFIGURATION_STARTS:.0e} starts "
                f"for one configuration of {n_disks} disks of radius {sigma} in the box "
                f"({box_x}, {box_y}): too dense for tabula-rasa sampling"
            )
        progress.update(1)
    parameters = {
        "method": method,
        "n_disks": n_disks,
        "sigma": float(sigma),
        "box_x": box_x,
        "box_y": box_y,
        "samples": samples,
        "realizations": realizations,
        "bins": bins,
        "step": float(step),
        "burn_in": burn_in,
        "start": "lattice" if method == "markov" and lattice else "direct",
    }
    extra = {
        "work": (
            "realization",
            started,
            "1",
            "configurations started (direct) or moves accepted (markov)",
        ),
        "cpu_seconds": ("realization", cpu, "s", "CPU time per realization"),
    }
    return _density_dataset(
        counts,
        samples,
        lower,
        upper,
        name="density",
        axis="y",
        what="disk centres per unit length of y",
        extra=extra,
        parameters=parameters,
        seed=seed,
    )


def _warm_line() -> None:
    for method in ("direct", "naive"):
        sample_line(
            method, n_pins=2, length=4.0, sigma=0.5, samples=2, realizations=2, bins=4, seed=0
        )


def _warm_ring() -> None:
    sample_ring(
        n_pins=2,
        length=4.0,
        sigma=0.5,
        step=0.5,
        sweeps=2,
        burn_in=1,
        realizations=2,
        bins=4,
        seed=0,
    )


def _warm_snapshots() -> None:
    pin_snapshots(n_pins=2, length=4.0, sigma=0.5, count=1, seed=0)


def _warm_disks() -> None:
    for method in ("direct", "markov"):
        sample_disks(method, n_disks=2, sigma=0.1, samples=2, realizations=2, bins=4, seed=0)


WARMUPS = {
    "sample_line": _warm_line,
    "sample_ring": _warm_ring,
    "pin_snapshots": _warm_snapshots,
    "sample_disks": _warm_disks,
}
"""The kernels each front runs, compiled by ``kinetic.jit.warm('samplers', front)`` before a
job of that front."""


def warmup() -> None:
    """Compile every kernel with the argument types production uses (numba cache=True)."""
    for compile_kernels in WARMUPS.values():
        compile_kernels()
