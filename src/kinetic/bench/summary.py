"""One row per measured case of a bench report (``results/benchmarks/<engine>.json``), for
the generated docs/benchmarks.md and the engines' speed lines (``kinetic.docs``).

Each row: engine, case, rate, unit, headline (the case quoted in docs/engines.md), and
where and when it was measured (date, CPU, 1-minute load average, git revision).
"""

from __future__ import annotations

import statistics
from typing import Any

__all__ = ["rows"]


def _dsmc(report: dict[str, Any]):
    for case in report["collision_stage"]:
        n, alpha = case["n_particles"], case["restitution"]
        yield (
            f"homogeneous, collision stage, N = {n:.0e}, alpha = {alpha:g}",
            case["accepted_collisions_per_cpu_second"],
            "accepted collisions per CPU-s",
            n == 200_000,
        )
    for case in report["inhomogeneous_cooling_modes"]:
        simulated = case["simulated_particles"]
        yield (
            f"inhomogeneous, {case['collision_rule']} rule, {simulated} simulated particles",
            case["particle_steps_per_cpu_second"],
            "particle-steps per CPU-s",
            case["collision_rule"] == "majorant",
        )


def _edmd(report: dict[str, Any]):
    for case in report["cases"]:
        d, n, density = case["dimension"], case["n_particles"], case["density"]
        where = (
            f"rho sigma^2 = {density:g}" if d == 2 else f"packing {case['packing_fraction']:.2g}"
        )
        yield (
            f"d = {d}, N = {n:.0e}, {where}",
            case["collisions_per_cpu_second"],
            "collisions per CPU-s",
            d == 2 and n == 1000 and abs(density - 1e-2) < 1e-12,
        )


def _cloning(report: dict[str, Any]):
    for case in report["cases"]:
        kernel = (
            "hard disks"
            if case["kernel"] == "hard_spheres" and case["dimension"] == 2
            else ("hard spheres" if case["kernel"] == "hard_spheres" else "Maxwell")
        )
        yield (
            f"{kernel}, lambda = {case['lambda']:g}, N_c = {case['population']:.0e}",
            case["events_per_cpu_second"],
            "collision events per CPU-s",
            kernel == "hard disks" and case["lambda"] == 1.0 and case["population"] == 1000,
        )


def _samplers(report: dict[str, Any]):
    for case in report["direct_pin"]:
        yield (
            f"direct-pin, {report['n_pins']} pins, L = {case['length']:g}",
            case["configurations_per_cpu_second"],
            "configurations per CPU-s",
            case["length"] == 20.0,
        )
    for case in report["naive_pin"]:
        yield (
            f"naive-pin, {report['n_pins']} pins, L = {case['length']:g}",
            case["configurations_per_cpu_second"],
            "configurations per CPU-s",
            False,
        )
    ring = report["ring_markov"]
    yield (
        f"Markov pins on a ring, L = {ring['length']:g}",
        ring["sweeps_per_cpu_second"],
        "sweeps per CPU-s",
        False,
    )


def _cuda(report: dict[str, Any]):
    """The GPU cases of ``python -m kinetic.bench cuda``, on the report's GPU: the cloning
    per wall second through the front, the DSMC per second of the engine's clock (its
    launches and the GPU, without the host's initial states and the dataset) unless a
    case says wall; a section that failed or did not run gives no row."""
    device = report.get("gpu", {}).get("device", "GPU")
    cloning = report["sections"].get("cloning_speed", {})
    for case in cloning.get("gpu", []):
        kernel = "hard disks" if case["kernel"] == "hard_spheres" else "Maxwell"
        yield (
            f"cloning on {device}, {kernel}, lambda = {case['lambda']:g}, "
            f"N_c = {case['population']:.0e} x {case['realizations']} realizations",
            case["events_per_second"],
            "collision events per wall-s",
            kernel == "hard disks" and case["lambda"] == 1.0 and case["population"] == 10**6,
        )
    yield from _homogeneous_dsmc(report["sections"], device)
    inhomogeneous = report["sections"].get("inhomogeneous_speed", {})
    for case in inhomogeneous.get("gpu", []):
        yield (
            f"inhomogeneous DSMC on {device}, {case['collision_rule']} rule, "
            f"N = {case['n_particles']:.0e} x Lambda = {case['fictive_factor']} x "
            f"{case['realizations']} realizations",
            case["particle_steps_per_second"],  # the kernels' time: launches and GPU
            "particle-steps per engine-s",
            False,
        )


def _homogeneous_dsmc(sections: dict[str, Any], device: str):
    """The homogeneous DSMC's cases: ``dsmc_scaling``'s (issue 27's target: accepted
    collisions per second of the engine's clock, the steps' launches and the GPU, a
    snapshot every 10 steps), then ``dsmc_speed``'s (per wall second through the front, a
    snapshot every step, the host's Maxwellian starts and the dataset included; the
    median of the runs of one shape, which differ only in their seed)."""
    for case in sections.get("dsmc_scaling", {}).get("gpu", []):
        n, realizations = case["n_particles"], case["realizations"]
        splitting = case.get("splitting", "strang")  # reports before 97c94b5 ran only Strang
        label = (
            f"homogeneous DSMC on {device}, alpha = {case['restitution']:g}, "
            f"N = {n:.0e} x {realizations} realizations, {splitting} splitting, "
            f"dt = {case.get('time_step', 0.1):g} tau"
        )
        target = (n, realizations) in {(200_000, 100), (2_000_000, 10)}
        if "engine_collisions_per_second" in case:
            yield (
                label,
                case["engine_collisions_per_second"],
                "accepted collisions per engine-s",
                target,
            )
        else:  # reports before the engine's clock, every step sampled
            yield label, case["collisions_per_second"], "collisions per wall-s", target
    shapes: dict[str, list[float]] = {}
    for case in sections.get("dsmc_speed", {}).get("gpu", []):
        label = (
            f"homogeneous DSMC on {device}, alpha = {case.get('restitution', 0.9):g}, "
            f"N = {case['n_particles']:.0e} x {case['realizations']} realizations, "
            "a snapshot every step"
        )
        shapes.setdefault(label, []).append(case["collisions_per_second"])
    for label, rates in shapes.items():
        yield label, statistics.median(rates), "collisions per wall-s", False


EXTRACTORS = {
    "dsmc": _dsmc,
    "edmd": _edmd,
    "cloning": _cloning,
    "samplers": _samplers,
    "cuda": _cuda,
}
"""Engine -> the cases of its report."""


def rows(report: dict[str, Any]) -> list[dict[str, Any]]:
    """The rows of one bench report (empty for an engine without an extractor)."""
    extractor = EXTRACTORS.get(report["engine"])
    if extractor is None:
        return []
    machine = report["machine"]
    return [
        {
            "engine": report["engine"],
            "case": case,
            "rate": float(rate),
            "unit": unit,
            "headline": bool(headline),
            "date": machine.get("date", ""),
            "cpu": machine["cpu"],
            "load": machine["load_average_1min"],
            "revision": machine["git_revision"],
            "quick": bool(report.get("quick", False)),
        }
        for case, rate, unit, headline in extractor(report)
    ]
