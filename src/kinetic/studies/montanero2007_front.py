"""The job fronts of montanero2007's simulations (``simulate_batch``, and
``simulate_batches`` for a family's runs in one ``cuda`` job): a run's settings turned into
``kinetic.dsmc.simulate_homogeneous``'s arguments. They live apart from the planning in
``kinetic.studies.montanero2007`` because a front's module is a code input of every job
that runs it: a planning edit there reran every montanero2007 simulation (all 57 of the
default config, 15 CPU-hours of paper.yaml's)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

__all__ = ["ENGINE_KEYS", "engine_arguments", "engine_run", "simulate_batch", "simulate_batches"]


def engine_arguments(
    run: Mapping[str, Any],
    *,
    seed: int,
    first: int,
    count: int,
    label: str,
    backend: str = "cpu",
) -> dict[str, Any]:
    """``simulate_homogeneous``'s arguments for realizations ``first .. first+count-1`` of
    one run: the histograms of c_x start at ``steady_from`` rounded up to a window
    boundary, the same windows the steady-state time averages use."""
    histogram_start = (
        math.ceil(run["steady_from"] / run["sample_interval"] - 1e-9) * run["sample_interval"]
    )
    return {
        "n_particles": int(run["n_particles"]),
        "restitution": float(run["restitution"]),
        "duration": float(run["duration"]),
        "time_step": float(run["time_step"]),
        "sample_interval": float(run["sample_interval"]),
        "seed": int(seed),
        "n_realizations": int(count),
        "first_realization": int(first),
        "dimension": 3,
        "reduced_field": float(run["reduced_field"]),
        "force_step": str(run["force_step"]),
        "selection": str(run["selection"]),
        "splitting": str(run["splitting"]),
        "sample_stride": int(run["sample_stride"]),
        "histogram_start": float(histogram_start),
        "cx_max": float(run["cx_max"]),
        "n_cx_bins": int(run["cx_bins"]),
        "label": label,
        **({"backend": backend} if backend != "cpu" else {}),
    }


ENGINE_KEYS = (
    "n_particles",
    "restitution",
    "duration",
    "time_step",
    "sample_interval",
    "reduced_field",
    "force_step",
    "selection",
    "splitting",
    "sample_stride",
    "steady_from",
    "cx_max",
    "cx_bins",
)
"""The keys of a run that ``engine_arguments`` reads: a job's ``run`` holds these only, so
that adding realizations (or renaming a family) leaves the finished batches' parameters,
and so the batches, as they are."""


def engine_run(run: Mapping[str, Any]) -> dict[str, Any]:
    """The part of ``run`` that a batch's numbers depend on (:data:`ENGINE_KEYS`)."""
    return {key: run[key] for key in ENGINE_KEYS}


def simulate_batch(run: Mapping[str, Any], **batch: Any):
    """Realizations ``first .. first+count-1`` of one run (an xarray.Dataset), on the
    ``backend`` of ``simulate_homogeneous``: ``batch`` is ``engine_arguments``' keywords
    (``seed``, ``first``, ``count``, ``label``, ``backend``)."""
    from kinetic.dsmc import simulate_homogeneous

    arguments = engine_arguments(run, **batch)
    dataset = simulate_homogeneous(**arguments)
    return dataset.assign_attrs(steady_from_tau=arguments["histogram_start"])


simulate_batch.engine_front = "kinetic.dsmc:simulate_homogeneous"
"""The engine function a job of this front runs: its jobs compile only that function's
kernels (``kinetic.simulation_job.warm_engines``)."""


def simulate_batches(
    points: Sequence[Mapping[str, Any]], *, label: str | None = None, finished=None
):
    """Several runs' batches in one job (``cuda``: one process, one CUDA context, the runs
    one after the other, ``kinetic.dsmc.simulate_homogeneous_points``): each point is
    ``simulate_batch``'s keyword arguments and ``parameters``, the run's name, family
    and setting that its own job would stamp (``jobs``); every point is checked before
    the first runs. Returns a dataset a point, the numbers of ``simulate_batch``;
    ``finished(k, dataset)`` (if given) gets each as its run ends
    (``kinetic.simulation_job`` keeps it, so that a stopped job resumes)."""
    from kinetic import io
    from kinetic.dsmc import simulate_homogeneous_points

    points = [dict(point) for point in points]
    stamps = [point.pop("parameters") for point in points]
    arguments = [engine_arguments(**point) for point in points]

    def stamped(k: int, dataset):
        engine = arguments[k]
        dataset = io.stamp(
            dataset, parameters={**io.parameters_of(dataset), **stamps[k]}, seed=engine["seed"]
        )
        return dataset.assign_attrs(steady_from_tau=engine["histogram_start"])

    def report(k: int, dataset) -> None:
        finished(k, stamped(k, dataset))

    datasets = simulate_homogeneous_points(
        arguments, label=label, finished=None if finished is None else report
    )
    return [stamped(k, dataset) for k, dataset in enumerate(datasets)]


simulate_batches.engine_front = "kinetic.dsmc:simulate_homogeneous"
