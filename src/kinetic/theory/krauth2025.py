"""Exact results of krauth2025 §4.4.1: random clothes-pins (hard rods) on a line and a ring.

N pins of width 2σ (centres x, hard-core distance 2σ) on a washing line [0, L] between two
posts (centres in [σ, L − σ]), all legal configurations equally likely.

- ``partition_function``: Eq. (4.6), Z_{N,L} = (L − 2Nσ)^N for L > 2Nσ, else 0 (labelled
  pins: the legal configurations map onto N free points on a line of length L − 2Nσ).
- ``pin_density``: Eq. (4.7), the probability density π(x) of one given pin at x: k pins
  to its left in the space x − σ, N − 1 − k to its right in L − x − σ,

      π(x) = Σ_k C(N−1, k) Z_{k, x−σ} Z_{N−1−k, L−x−σ} / Z_{N,L},   ∫ π dx = 1;

  the density of pins is N π(x). Evaluated with logarithms (no overflow for large N).
- ``ring_pair_density``: N pins on a ring of circumference L. Cutting the ring at one pin
  leaves N − 1 pins on a line of length L − 2σ (krauth2025 Fig. 4.13: a pair of pins on
  the circle is a single pin on a washing line), so the density of other pins at distance
  r (measured forwards along the ring) from a given pin is (N − 1) π_{N−1, L−2σ}(r − σ).
- ``bin_average``: a density averaged over histogram bins, for comparisons with sampled
  histograms without a discretisation bias.

Hard disks in a box (§4.4.3): ``wall_speed_averages`` (Eq. 4.13) and
``pair_speed_averages`` (Eq. 4.14, with the correction of its part a) for velocities on
the sphere Σ v² = R², and ``wall_value`` (a density at the wall from histogram bins, for
the thermodynamic pressure βP = contact density).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from kinetic import validate

__all__ = [
    "CLASSIC_START",
    "MAX_DIRECT_DISKS_STARTS",
    "MAX_NAIVE_STARTS",
    "MAX_SNAPSHOTS",
    "bin_average",
    "check_classic_start",
    "check_direct_disks_starts",
    "check_disk_box",
    "check_naive_starts",
    "check_pins",
    "check_snapshots",
    "direct_disks_acceptance",
    "line_dataset",
    "naive_acceptance",
    "pair_speed_averages",
    "partition_function",
    "pin_density",
    "ring_dataset",
    "ring_pair_density",
    "snapshot_count",
    "wall_speed_averages",
    "wall_value",
]

CLASSIC_START = {
    "sigma": 0.15,
    "box": (1.0, 1.0),
    "positions": ((0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)),
    "velocities": ((0.21, 0.12), (0.71, 0.18), (-0.23, -0.79), (0.78, 0.1177)),
}
"""The start of Krauth's own event-disks program (four disks of radius 0.15 in the unit
box), the snapshots readers of the book and the lecture know."""


def check_classic_start(n_disks: int, sigma: float, box) -> None:
    """Refuse (``ValueError``) disks other than :data:`CLASSIC_START`'s for that start."""
    expected = (len(CLASSIC_START["positions"]), CLASSIC_START["sigma"], CLASSIC_START["box"])
    given = (n_disks, float(sigma), tuple(float(side) for side in box))
    if given != expected:
        raise ValueError(
            f"the classic start is {expected[0]} disks of radius {expected[1]} in the box "
            f"{expected[2]}; got n_disks = {n_disks}, sigma = {sigma}, box = {tuple(box)}"
        )


#: most configurations naive-pin may be expected to start in one call (about an hour)
MAX_NAIVE_STARTS = 1e10


def check_pins(n_pins: int, length: float, sigma: float) -> None:
    """Raise ``ValueError`` unless N ≥ 1 pins of half-width σ > 0 fit on a line of length L
    (L > 2Nσ: the legal configurations then have a positive volume)."""
    if isinstance(n_pins, bool) or not isinstance(n_pins, int | np.integer) or n_pins < 1:
        raise ValueError(f"n_pins must be an integer >= 1, got {n_pins!r}")
    for name, value in (("sigma", sigma), ("length", length)):
        if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
            raise TypeError(f"{name} must be a real number, got {value!r}")
    if not (np.isfinite(sigma) and sigma > 0):
        raise ValueError(f"sigma (half the pin width) must be finite and > 0, got {sigma!r}")
    if not (np.isfinite(length) and length > 2 * n_pins * sigma):
        raise ValueError(
            f"a line of length {length!r} cannot hold {n_pins} pins of width 2 sigma = "
            f"{2 * sigma:g}: it needs length > {2 * n_pins * sigma:g}"
        )


MAX_SNAPSHOTS = 10**7
"""Most stroboscopic snapshots of one event-disks realization (paper.yaml takes 10⁶). At
each the kernel bins every disk; an interval of 10⁻¹² asked for 10¹⁵ (about 500 days),
and one below the duration's rounding never advanced the clock."""


def snapshot_count(duration: float, snapshot_interval: float) -> int:
    """The stroboscopic snapshots of an event-disks run: those at (j + 1/2) ×
    ``snapshot_interval`` < ``duration``, j = 0, 1, ..., with the float arithmetic of the
    kernel's clock (``kinetic.event_disks.kernels.observe``)."""
    count = max(0, math.ceil(duration / snapshot_interval - 0.5))
    while count > 0 and (count - 1 + 0.5) * snapshot_interval >= duration:
        count -= 1
    while (count + 0.5) * snapshot_interval < duration:
        count += 1
    return count


def check_snapshots(duration: float, snapshot_interval: float) -> None:
    """Raise ``ValueError`` unless ``snapshot_interval`` fits in ``duration`` at most
    ``MAX_SNAPSHOTS`` times (and at least once)."""
    if snapshot_interval > duration:
        raise ValueError(f"snapshot_interval = {snapshot_interval} exceeds the duration {duration}")
    if duration / snapshot_interval > MAX_SNAPSHOTS:
        raise ValueError(
            f"snapshot_interval = {snapshot_interval} gives {duration / snapshot_interval:.3g} "
            f"snapshots of a realization of duration {duration}: at most {MAX_SNAPSHOTS:.0e} "
            f"(snapshot_interval >= {duration / MAX_SNAPSHOTS:.3g})"
        )


def check_disk_box(n_disks: int, sigma: float, box) -> tuple[float, float]:
    """Raise ``ValueError`` unless N ≥ 1 disks of radius σ > 0 can stand in the box with
    walls ``box`` = (L_x, L_y) (each side above 2σ, the disks covering at most 90 % of the
    area); returns the sides as floats. Whether direct-disks finds the legal
    configurations in reasonable time is :func:`check_direct_disks_starts`'s question."""
    validate.integer("n_disks", n_disks, 1)
    sigma = validate.real("sigma (disk radius)", sigma, 0.0, math.inf, low_open=True)
    sides = tuple(box) if isinstance(box, list | tuple | np.ndarray) else (box,)
    if len(sides) != 2:
        raise ValueError(f"box must be the two sides (L_x, L_y), got {box!r}")
    box_x, box_y = (validate.real("box side", side, 0.0, math.inf) for side in sides)
    if min(box_x, box_y) <= 2 * sigma:
        raise ValueError(f"box {box!r} cannot hold a disk of radius {sigma}")
    if n_disks * math.pi * sigma**2 > 0.9 * box_x * box_y:
        raise ValueError(
            f"{n_disks} disks of radius {sigma} cover more than 90 % of the box {box!r}"
        )
    return box_x, box_y


MAX_DIRECT_DISKS_STARTS = 1e10
"""Most configurations direct-disks may be expected to start in one call (minutes at four
disks, about 10⁸ starts per CPU-s, most of them refused at the second disk; the
configs take 5 × 10⁷ and, paper.yaml, 2 × 10⁹)."""


def direct_disks_acceptance(
    n_disks: int,
    sigma: float,
    box,
    *,
    population: int = 4096,
    max_rounds: int = 256,
    seed: int = 0,
) -> float:
    """An estimate of the probability that a direct-disks start (N disks uniform in
    [σ, L_x − σ] × [σ, L_y − σ], started again on any overlap) is legal, Z_N/A^N, without
    drawing 1/Z_N starts. A population of legal k-disk configurations gets a uniform
    (k+1)-th disk each, round after round until a quarter of a population is left legal
    (or ``max_rounds``); the fraction left legal estimates the conditional acceptance
    p_k, and the next population is drawn from the legal ones (sequential Monte Carlo:
    the product of the fractions estimates Π p_k without bias, to a few per cent at four
    disks). 0.0 when a stage leaves nothing legal, p_k below about
    1/(``population`` × ``max_rounds``): legal configurations are too rare to be found."""
    box_x, box_y = check_disk_box(n_disks, sigma, box)
    return _acceptance(int(n_disks), float(sigma), box_x, box_y, population, max_rounds, seed)


@functools.cache
def _acceptance(n_disks, sigma, box_x, box_y, population, max_rounds, seed) -> float:
    """``direct_disks_acceptance`` of a checked box, once a box (the workflow's parse asks
    for it twice: the check and the cost)."""
    rng = np.random.default_rng(seed)
    low, high = np.array([sigma, sigma]), np.array([box_x - sigma, box_y - sigma])
    alive = np.empty((population, 0, 2))
    acceptance = 1.0
    for _ in range(n_disks):
        legal, drawn, found = [], 0, 0
        while found < population // 4 and drawn < population * max_rounds:
            new = rng.uniform(low, high, size=(population, 1, 2))
            free = np.all(np.sum((alive - new) ** 2, axis=-1) > (2.0 * sigma) ** 2, axis=1)
            legal.append(np.concatenate([alive, new], axis=1)[free])
            drawn += population
            found += int(np.count_nonzero(free))
        if found == 0:
            return 0.0
        acceptance *= found / drawn
        legal = np.concatenate(legal)
        alive = legal[rng.integers(found, size=population)]
    return acceptance


def check_direct_disks_starts(n_disks: int, sigma: float, box, configurations: int) -> float:
    """Raise ``ValueError`` if direct-disks would be expected to start more than
    :data:`MAX_DIRECT_DISKS_STARTS` configurations to draw ``configurations`` legal ones
    (at :func:`direct_disks_acceptance`), or if no legal configuration turns up; returns
    the acceptance."""
    acceptance = direct_disks_acceptance(n_disks, sigma, box)
    if acceptance <= 0.0:
        raise ValueError(
            f"direct-disks found no legal configuration of {n_disks} disks of radius {sigma} "
            f"in the box {tuple(box)}: too dense for tabula-rasa sampling"
        )
    expected = configurations / acceptance
    if expected > MAX_DIRECT_DISKS_STARTS:
        raise ValueError(
            f"direct-disks would start about {expected:.2g} configurations for "
            f"{configurations} legal ones of {n_disks} disks of radius {sigma} in the box "
            f"{tuple(box)} (acceptance {acceptance:.2g}), more than "
            f"{MAX_DIRECT_DISKS_STARTS:.0e}: use fewer samples, markov-disks, a larger box "
            "or smaller disks"
        )
    return acceptance


def naive_acceptance(n_pins: int, length: float, sigma: float) -> float:
    """Probability that a naive-pin configuration gets through: Z_{N,L} / (L − 2σ)^N."""
    return ((length - 2 * n_pins * sigma) / (length - 2 * sigma)) ** n_pins


def check_naive_starts(n_pins: int, length: float, sigma: float, samples: int) -> None:
    """Raise ``ValueError`` if naive-pin would be expected to start more than
    ``MAX_NAIVE_STARTS`` configurations for ``samples`` accepted ones."""
    acceptance = naive_acceptance(n_pins, length, sigma)
    expected = samples / acceptance
    if expected > MAX_NAIVE_STARTS:
        raise ValueError(
            f"naive-pin would start about {expected:.2g} configurations for {samples} "
            f"samples of {n_pins} pins on length {length} (acceptance {acceptance:.2g}); "
            f"use direct-pin, fewer samples or a longer line"
        )


def _log_partition(n: int, length, sigma: float) -> np.ndarray:
    """log Z_{n, length} (−inf where no legal configuration), elementwise in ``length``;
    Z_{0, ℓ} = 1 for ℓ ≥ 0 (an empty stretch, including one of zero length)."""
    length = np.asarray(length, dtype=float)
    if n == 0:
        return np.where(length >= 0.0, 0.0, -np.inf)
    free = length - 2.0 * n * sigma
    return np.where(free > 0.0, n * np.log(np.where(free > 0.0, free, 1.0)), -np.inf)


def partition_function(n_pins: int, length: float, sigma: float) -> float:
    """Z_{N,L} of Eq. (4.6) for labelled pins: (L − 2Nσ)^N if L > 2Nσ, else 0."""
    free = length - 2.0 * n_pins * sigma
    return float(free**n_pins) if free > 0 else 0.0


def pin_density(x, n_pins: int, length: float, sigma: float) -> np.ndarray:
    """π(x) of Eq. (4.7): probability density of one given pin's centre at x (0 outside
    [σ, L − σ]); multiply by N for the density of pins."""
    check_pins(n_pins, length, sigma)
    x = np.asarray(x, dtype=float)
    log_total = n_pins * np.log(length - 2.0 * n_pins * sigma)
    terms = []
    for k in range(n_pins):
        log_binomial = math.lgamma(n_pins) - math.lgamma(k + 1) - math.lgamma(n_pins - k)
        left = _log_partition(k, x - sigma, sigma)
        right = _log_partition(n_pins - 1 - k, length - x - sigma, sigma)
        terms.append(log_binomial + left + right - log_total)
    terms = np.array(terms)
    peak = np.max(terms, axis=0)
    finite = np.isfinite(peak)
    safe_peak = np.where(finite, peak, 0.0)
    with np.errstate(invalid="ignore"):
        total = np.exp(safe_peak) * np.sum(np.exp(terms - safe_peak), axis=0)
    inside = (x >= sigma) & (x <= length - sigma)
    return np.where(finite & inside, total, 0.0)


def ring_pair_density(r, n_pins: int, length: float, sigma: float) -> np.ndarray:
    """Density of the other pins at forward distance r ∈ [0, L) from a given pin, for N
    pins on a ring of circumference L: (N − 1) π_{N−1, L−2σ}(r − σ); it integrates to
    N − 1. For N = 1 it is 0."""
    check_pins(n_pins, length, sigma)
    r = np.asarray(r, dtype=float)
    if n_pins == 1:
        return np.zeros_like(r)
    return (n_pins - 1) * pin_density(r - sigma, n_pins - 1, length - 2.0 * sigma, sigma)


def bin_average(density, edges, points_per_bin: int = 64) -> np.ndarray:
    """Mean of the function ``density`` over each bin [edges[b], edges[b + 1]) (Gauss-
    Legendre quadrature with ``points_per_bin`` nodes: the densities above are piecewise
    polynomials of degree < 2N with kinks at multiples of 2σ, so use enough nodes)."""
    edges = np.asarray(edges, dtype=float)
    nodes, weights = np.polynomial.legendre.leggauss(points_per_bin)
    lower, upper = edges[:-1, None], edges[1:, None]
    points = 0.5 * (upper - lower) * nodes[None, :] + 0.5 * (upper + lower)
    values = density(points.ravel()).reshape(points.shape)
    return 0.5 * (values * weights[None, :]).sum(axis=1)


# ---------------------------------------------------------------- hard disks, §4.4.3
def _gamma_ratio(n_disks: int) -> float:
    """Γ(N + 1/2)/Γ(N) (→ √N)."""
    return math.exp(math.lgamma(n_disks + 0.5) - math.lgamma(n_disks))


def wall_speed_averages(n_disks: int, radius: float) -> dict[str, float]:
    """Eq. (4.13): averages over wall collisions of 1/|v⊥| and |v⊥| for N disks whose
    velocities lie uniformly on the sphere Σ v² = R² in 2N dimensions (a wall collision
    weighs each velocity by its flux |v⊥|)."""
    ratio = _gamma_ratio(n_disks)
    return {
        "inverse": math.sqrt(math.pi) / radius * ratio,  # (4.13a)
        "mean": radius * math.sqrt(math.pi) / (2 * n_disks) * ratio,  # (4.13b)
    }


def pair_speed_averages(n_disks: int, radius: float) -> dict[str, float]:
    """Eq. (4.14): averages over pair collisions of 1/|Δv⊥| and |Δv⊥|.

    Δv⊥ = (v_i − v_j)·ê is √2 times one velocity component, so with the same flux weight
    as at a wall ⟨1/|Δv⊥|⟩ = (√π/(√2 R)) Γ(N+1/2)/Γ(N) (→ √(π mβ)/2) and ⟨|Δv⊥|⟩ =
    (R√π/(√2 N)) Γ(N+1/2)/Γ(N). The lecture's (4.14a) prints √(2π)/R, twice this (its
    limit √(π mβ) likewise): ``inverse_printed`` keeps that value for comparison; the
    event-disks runs measure the corrected one (tests/physics)."""
    ratio = _gamma_ratio(n_disks)
    return {
        "inverse": math.sqrt(math.pi / 2) / radius * ratio,
        "inverse_printed": math.sqrt(2 * math.pi) / radius * ratio,  # (4.14a) as printed
        "mean": radius * math.sqrt(math.pi) / (math.sqrt(2) * n_disks) * ratio,  # (4.14b)
    }


def sphere_velocity_marginal(u, n_disks: int):
    """Density of u = v_a/R, one velocity component over R, when the 2N components are
    uniform on the sphere Σ v² = R² (§4.2.1): Γ(N)/(√π Γ(N − 1/2)) (1 − u²)^(N − 3/2)."""
    u = np.asarray(u, dtype=float)
    norm = math.exp(math.lgamma(n_disks) - math.lgamma(n_disks - 0.5)) / math.sqrt(math.pi)
    return norm * np.clip(1.0 - u * u, 0.0, None) ** (n_disks - 1.5)


def maxwell_velocity_marginal(u, n_disks: int):
    """The Maxwell limit of :func:`sphere_velocity_marginal`: v_a Gaussian with
    ⟨v_a²⟩ = R²/(2N), i.e. √(N/π) exp(−N u²)."""
    u = np.asarray(u, dtype=float)
    return math.sqrt(n_disks / math.pi) * np.exp(-n_disks * u * u)


def rate_pressure_factors(n_disks: int, radius: float) -> dict[str, float]:
    """βP per unit rate of wall hits n̂ (hits per unit wall length and time), Eqs. (4.9c, d)
    and (4.10c, d) times β.

    The wall rift gives βP = 2⟨1/|v⊥|⟩ n̂ (4.9b) and the kinematic estimator P = 2m⟨|v⊥|⟩ n̂
    (4.10b); with Eq. (4.13) and the microcanonical β = 2N/(mR²) both become
    ``finite`` = (2√π/R) Γ(N+1/2)/Γ(N) (4.9c, and β times 4.10c), whose N → ∞ form is
    ``limit`` = √(2πβm) = 2√(πN)/R (4.9d, and β times 4.10d). The lecture prints
    (4.10d) as √(2πβm) n̂, which is the limit of βP_x, not of P_x = √(2πm/β) n̂. Their
    ratio Γ(N+1/2)/(Γ(N)√N) is 0.969 at N = 4.
    """
    ratio = _gamma_ratio(n_disks)
    return {
        "finite": 2 * math.sqrt(math.pi) / radius * ratio,
        "limit": 2 * math.sqrt(math.pi * n_disks) / radius,
        "finite_over_limit": ratio / math.sqrt(n_disks),
    }


def wall_value(edges, averages, terms: int = 3, bins: int = 4) -> float:
    """Value at ``edges[0]`` of the polynomial (``terms`` coefficients) whose averages over
    the first ``bins`` bins fit the histogram ``averages`` best (least squares): the
    density at a wall from a histogram, without the bias of the first bin's average."""
    edges = np.asarray(edges, dtype=float)
    a, b = edges[:bins] - edges[0], edges[1 : bins + 1] - edges[0]
    design = np.array([(b ** (k + 1) - a ** (k + 1)) / ((k + 1) * (b - a)) for k in range(terms)]).T
    coefficients = np.linalg.lstsq(design, np.asarray(averages, dtype=float)[:bins], rcond=None)[0]
    return float(coefficients[0])


# ------------------------------------------------------------------ curves for the figures
def line_dataset(n_pins: int, length: float, sigma: float, bins: int, curve_points: int = 2001):
    """The exact pin density of N pins on a line (Eq. 4.7) on the samplers' bins
    (``density_exact``, bin averages over [σ, L − σ) cut in ``bins``) and on a fine grid
    (``density_curve``), with the naive-pin acceptance (Eq. 4.6): what Figs 4.11 and the
    pins table draw beside the samples."""
    from kinetic import io

    check_pins(n_pins, length, sigma)
    edges = np.linspace(sigma, length - sigma, bins + 1)
    curve = np.linspace(sigma, length - sigma, curve_points)

    def exact(x):
        return n_pins * pin_density(x, n_pins, length, sigma)

    return io.make_dataset(
        {
            "density_exact": (
                "x",
                bin_average(exact, edges),
                "1/length",
                "N pi(x) of Eq. 4.7 averaged over the bin",
            ),
            "density_curve": ("x_curve", exact(curve), "1/length", "N pi(x) of Eq. 4.7"),
            "acceptance_exact": (
                (),
                naive_acceptance(n_pins, length, sigma),
                "1",
                "naive-pin acceptance Z_{N,L} / (L - 2 sigma)^N (Eq. 4.6)",
            ),
            "bin_edges": ("edge", edges, "length", "bin edges"),
        },
        {
            "x": ("x", 0.5 * (edges[1:] + edges[:-1]), "length", "pin centre (bin middle)"),
            "x_curve": ("x_curve", curve, "length", "pin centre"),
            "edge": ("edge", np.arange(bins + 1), "1", "bin edge index"),
        },
        attrs={"n_pins": n_pins, "length": float(length), "sigma": float(sigma)},
    )


def ring_dataset(n_pins: int, length: float, sigma: float, bins: int, curve_points: int = 4001):
    """The exact density of the other pins at forward distance r from a pin on a ring of
    length L, (N − 1) π_{N−1, L−2σ}(r − σ), on the ring sampler's bins over [0, L)
    (``pair_density_exact``) and on a fine grid (``pair_density_curve``): Fig. 4.13."""
    from kinetic import io

    edges = np.linspace(0.0, length, bins + 1)
    curve = np.linspace(0.0, length, curve_points)

    def exact(r):
        return ring_pair_density(r, n_pins, length, sigma)

    return io.make_dataset(
        {
            "pair_density_exact": (
                "r",
                bin_average(exact, edges),
                "1/length",
                "(N - 1) pi_{N-1, L-2 sigma}(r - sigma) averaged over the bin",
            ),
            "pair_density_curve": (
                "r_curve",
                exact(curve),
                "1/length",
                "(N - 1) pi_{N-1, L-2 sigma}(r - sigma)",
            ),
            "bin_edges": ("edge", edges, "length", "bin edges"),
        },
        {
            "r": ("r", 0.5 * (edges[1:] + edges[:-1]), "length", "forward distance (bin middle)"),
            "r_curve": ("r_curve", curve, "length", "forward distance"),
            "edge": ("edge", np.arange(bins + 1), "1", "bin edge index"),
        },
        attrs={"n_pins": n_pins, "length": float(length), "sigma": float(sigma)},
    )
