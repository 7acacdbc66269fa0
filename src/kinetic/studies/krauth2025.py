"""The krauth2025 study: its simulation jobs (``jobs``), and whether the configured box
can be sampled at all.

The direct-disks sampler (Alg. 4.4) draws every disk uniformly and starts again on any
overlap; when legal configurations are rare it runs for hours. ``check_disks`` estimates
the fraction of legal starts (``theory.krauth2025.direct_disks_acceptance``, numpy alone:
the workflow calls it while parsing the Snakefile, where loading numba would cost a
second) and stops before any job when the configured samples would take more than
``MAX_DIRECT_DISKS_STARTS`` starts, as the sampler's front does.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from kinetic.studies import Job, benchmark_file
from kinetic.theory.krauth2025 import (
    check_direct_disks_starts,
    check_snapshots,
    direct_disks_acceptance,
)

__all__ = [
    "LINE_RUNS",
    "check",
    "check_disks",
    "disk_bins",
    "jobs",
    "line_bins",
    "line_name",
    "ring_bins",
]


def check_disks(disks: Mapping[str, Any]) -> float:
    """Raise ``ValueError`` unless direct-disks can draw the configurations of ``disks``
    (config ``krauth2025.disks``: ``n_disks``, ``sigma``, ``box``, ``direct_samples``,
    ``sampler_realizations``) in reasonable time; returns its acceptance."""
    configurations = disks["direct_samples"] * disks["sampler_realizations"]
    return check_direct_disks_starts(disks["n_disks"], disks["sigma"], disks["box"], configurations)


LINE_RUNS = (("direct", "length"), ("naive", "naive_length"), ("direct", "naive_length"))
"""The washing-line samples: (method, length key of config krauth2025.pins)."""


def line_name(method: str, length: float) -> str:
    """File stem of a washing-line sample: ``direct_L20``."""
    return f"{method}_L{length:g}"


def line_bins(pins: Mapping[str, Any], length: float) -> int:
    """Bins of a line's histogram over [sigma, length - sigma): width about bin_width."""
    return max(1, round((length - 2 * pins["sigma"]) / pins["bin_width"]))


def ring_bins(ring: Mapping[str, Any]) -> int:
    """Bins of the ring's histogram over [0, length): width about bin_width."""
    return max(1, round(ring["length"] / ring["bin_width"]))


def disk_bins(disks: Mapping[str, Any]) -> int:
    """Bins of the disks' y-histograms across the box."""
    return max(1, round((disks["box"][1] - 2 * disks["sigma"]) / disks["bin_width"]))


def check(config: Mapping[str, Any]) -> None:
    """Stop before any job on values the schema cannot judge alone: lines and rings too
    short for their pins, a naive-pin run that would take forever, a box that cannot hold
    the disks (:func:`check_disks`)."""
    from kinetic.theory.krauth2025 import check_classic_start, check_naive_starts, check_pins

    section = config.get("krauth2025")
    if not section:
        return
    pins, ring = section["pins"], section["ring"]
    try:
        for key in ("length", "naive_length"):
            check_pins(pins["n_pins"], pins[key], pins["sigma"])
        check_pins(ring["n_pins"], ring["length"], ring["sigma"])
    except ValueError as error:
        raise ValueError(f"config krauth2025: {error}") from None
    if ring["step"] > ring["length"] / 2:
        raise ValueError(
            f"config krauth2025.ring.step = {ring['step']} exceeds half the ring length"
        )
    try:
        samples = pins["naive_samples"] * pins["realizations"]
        check_naive_starts(pins["n_pins"], pins["naive_length"], pins["sigma"], samples)
    except ValueError as error:
        raise ValueError(f"config krauth2025.pins (naive_length): {error}") from None
    try:
        check_disks(section["disks"])
    except ValueError as error:
        raise ValueError(f"config krauth2025.disks: {error}") from None
    disks = section["disks"]
    try:
        check_snapshots(disks["md_duration"], disks["snapshot_interval"])
    except ValueError as error:
        raise ValueError(f"config krauth2025.disks (md_duration): {error}") from None
    if disks["start"] == "classic":
        try:
            check_classic_start(disks["n_disks"], disks["sigma"], disks["box"])
        except ValueError as error:
            raise ValueError(
                f"config krauth2025.disks: start = classic: {error} (use another start or "
                "those values)"
            ) from None


def jobs(config: Mapping[str, Any]) -> list[Job]:
    """The simulation jobs of the config's krauth2025 section (``kinetic.studies``): the
    washing-line samples, the ring's chains and the snapshots (``kinetic.samplers``), and
    the four disks by event-disks, direct-disks and markov-disks, and the chaos run. Each
    job runs all its realizations."""
    from kinetic import cost
    from kinetic.seeds import derive_seed

    section = config.get("krauth2025")
    if not section:
        return []
    pins, ring, disks = section["pins"], section["ring"], section["disks"]

    def job(rule, output, front, arguments, estimate, engines, benchmark=True):
        seed = derive_seed(config["seed"], f"krauth2025/{output.removesuffix('.nc')}")
        return Job(
            document="krauth2025",
            rule=rule,
            output=f"krauth2025/{output}",
            front=front,
            arguments=arguments | {"seed": seed},
            estimate=estimate,
            engines=engines,
            benchmark=benchmark_file(f"krauth2025/{output}") if benchmark else None,
        )

    found = []
    for method, key in LINE_RUNS:
        length = float(pins[key])
        arguments = {
            "method": method,
            "n_pins": pins["n_pins"],
            "length": length,
            "sigma": pins["sigma"],
            "samples": pins[f"{method}_samples"],
            "realizations": pins["realizations"],
            "bins": line_bins(pins, length),
        }
        estimate = cost.sampler_line(
            method,
            n_pins=pins["n_pins"],
            length=length,
            sigma=pins["sigma"],
            samples=pins[f"{method}_samples"],
            realizations=pins["realizations"],
        )
        found.append(
            job(
                "krauth2025_simulate_line",
                f"pins/{line_name(method, length)}.nc",
                "kinetic.samplers:sample_line",
                arguments,
                estimate,
                ("samplers",),
            )
        )
    keys = ("n_pins", "length", "sigma", "step", "sweeps", "burn_in", "realizations")
    found.append(
        job(
            "krauth2025_simulate_ring",
            "pins/ring.nc",
            "kinetic.samplers:sample_ring",
            {key: ring[key] for key in keys} | {"bins": ring_bins(ring)},
            cost.sampler_ring(**ring),
            ("samplers",),
        )
    )
    found.append(
        job(
            "krauth2025_simulate_pin_snapshots",
            "pins/snapshots.nc",
            "kinetic.samplers:pin_snapshots",
            {
                "n_pins": pins["n_pins"],
                "length": pins["length"],
                "sigma": pins["sigma"],
                "count": pins["snapshots"],
            },
            cost.small_job(),
            ("samplers",),
            benchmark=False,
        )
    )
    found.append(
        job(
            "krauth2025_simulate_md",
            "disks/md.nc",
            "kinetic.event_disks:simulate_box",
            {
                "n_disks": disks["n_disks"],
                "sigma": disks["sigma"],
                "box": disks["box"],
                "duration": disks["md_duration"],
                "snapshot_interval": disks["snapshot_interval"],
                "bins": disk_bins(disks),
                "realizations": disks["realizations"],
                "velocity_bins": disks["velocity_bins"],
            },
            cost.edmd_box(
                n_disks=disks["n_disks"],
                duration=disks["md_duration"],
                realizations=disks["realizations"],
            ),
            ("event_disks", "samplers"),
        )
    )
    acceptance = direct_disks_acceptance(disks["n_disks"], disks["sigma"], disks["box"])
    for method, samples in (("direct", "direct_samples"), ("markov", "markov_sweeps")):
        found.append(
            job(
                "krauth2025_simulate_disks",
                f"disks/{method}.nc",
                "kinetic.samplers:sample_disks",
                {
                    "method": method,
                    "n_disks": disks["n_disks"],
                    "sigma": disks["sigma"],
                    "box": disks["box"],
                    "samples": disks[samples],
                    "realizations": disks["sampler_realizations"],
                    "bins": disk_bins(disks),
                    "step": disks["markov_step"],
                    "burn_in": disks["burn_in"],
                },
                cost.sampler_disks(
                    method,
                    n_disks=disks["n_disks"],
                    samples=disks[samples],
                    realizations=disks["sampler_realizations"],
                    burn_in=disks["burn_in"] if method == "markov" else 0,
                    acceptance=acceptance,
                ),
                ("samplers",),
            )
        )
    found.append(
        job(
            "krauth2025_simulate_chaos",
            "disks/chaos.nc",
            "kinetic.event_disks:chaos",
            {
                "n_disks": disks["n_disks"],
                "sigma": disks["sigma"],
                "box": disks["box"],
                "events": max(disks["chaos_events"], disks["snapshot_events"]),
                "start": disks["start"],
                "extra_starts": disks["chaos_starts"],
            },
            cost.small_job(),
            ("event_disks", "samplers"),
            benchmark=False,
        )
    )
    return found
