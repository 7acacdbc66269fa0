"""Splitting the realizations of a run into jobs, and joining the jobs' datasets back.

One vocabulary for every engine: a run has ``realizations`` independent realizations,
cut into jobs of at most ``realizations_per_job``; job j simulates the realizations
``first_realization .. first_realization + n_realizations - 1``. Realization k always uses
stream row k of the run's seed (``kinetic.rng.stream_states``), so the data do not depend
on how the realizations are cut into jobs, and a stopped run resumes job by job.

    for job in plan(realizations=10, realizations_per_job=4):
        job.first_realization, job.n_realizations      # (0, 4), (4, 4), (8, 2)
    run = combine([read_dataset(path) for path in batch_files])
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

if TYPE_CHECKING:  # the workflow plans jobs from this module while parsing: no xarray then
    import xarray as xr

__all__ = ["Job", "batch_name", "check_disjoint", "combine", "plan"]

REALIZATION = "realization"
"""Name of the dimension (and coordinate) that numbers the realizations of a run."""


class Job(NamedTuple):
    """One job of a run: its index and the realizations it simulates."""

    index: int
    first_realization: int
    n_realizations: int


def plan(*, realizations: int, realizations_per_job: int) -> list[Job]:
    """The jobs of a run of ``realizations`` cut into jobs of ``realizations_per_job``."""
    for name, value in (
        ("realizations", realizations),
        ("realizations_per_job", realizations_per_job),
    ):
        if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
            raise ValueError(f"{name} must be an integer >= 1, got {value!r}")
    count = math.ceil(realizations / realizations_per_job)
    return [
        Job(
            index=job,
            first_realization=job * realizations_per_job,
            n_realizations=min(realizations_per_job, realizations - job * realizations_per_job),
        )
        for job in range(count)
    ]


def batch_name(job: int) -> str:
    """File stem of job ``job``'s dataset: ``batch0000``, ``batch0001``, ..."""
    return f"batch{job:04d}"


COUNTS = ("n_realizations", "realizations")
"""Parameter names under which an engine records how many realizations a dataset holds
(the EDMD front takes ``realizations``, the others ``n_realizations``)."""


def _parameters(dataset: xr.Dataset) -> dict:
    """The physics parameters of a batch, without the ones that differ between batches."""
    parameters = json.loads(dataset.attrs.get("parameters_json", "{}"))
    for key in ("first_realization", *COUNTS):
        parameters.pop(key, None)
    return parameters


def check_disjoint(datasets: Sequence[xr.Dataset], names: Sequence[str]) -> None:
    """Raise ``ValueError`` naming both batches if a realization appears in two of them."""
    seen: dict[int, str] = {}
    for name, dataset in zip(names, datasets, strict=True):
        for k in np.asarray(dataset[REALIZATION].values).tolist():
            if k in seen:
                raise ValueError(
                    f"realization {k} appears in both {seen[k]} and {name}: the batches "
                    "overlap (files of two different job plans?); delete the stale one"
                )
            seen[k] = name


def combine(datasets: Sequence[xr.Dataset], *, names: Sequence[str] | None = None) -> xr.Dataset:
    """Concatenate the batches of one run along ``realization``.

    Every batch must carry the same parameters (apart from its realization range) and the
    same seed, and no realization may appear twice; the error names the batches (by
    ``names``, e.g. their file paths, or by position). Variables without the realization
    dimension are taken from the first batch. The result's attributes are the first
    batch's, with ``n_realizations`` and ``first_realization`` of the whole run and
    ``source_git_revisions``, every revision that simulated a batch
    (``kinetic.io.source_revisions``).
    """
    import xarray as xr

    from kinetic.io import source_revisions

    if not datasets:
        raise ValueError("combine needs at least one batch")
    names = list(names) if names is not None else [f"batch {i}" for i in range(len(datasets))]
    reference = _parameters(datasets[0])
    for name, dataset in zip(names[1:], datasets[1:], strict=True):
        if _parameters(dataset) != reference:
            different = sorted(
                key
                for key in set(reference) | set(_parameters(dataset))
                if reference.get(key) != _parameters(dataset).get(key)
            )
            raise ValueError(
                f"{name} and {names[0]} belong to different runs: parameters {different} differ"
            )
        if dataset.attrs.get("seed") != datasets[0].attrs.get("seed"):
            raise ValueError(f"{name} and {names[0]} have different seeds")
    check_disjoint(datasets, names)
    per_realization = [
        dataset[[v for v in dataset.data_vars if REALIZATION in dataset[v].dims]]
        for dataset in datasets
    ]
    combined = xr.concat(per_realization, dim=REALIZATION, combine_attrs="override")
    combined = combined.sortby(REALIZATION)
    for name, variable in datasets[0].data_vars.items():
        if REALIZATION not in variable.dims:
            combined[name] = variable
    realizations = combined[REALIZATION].values
    attrs = dict(datasets[0].attrs)
    whole_run = {"first_realization": int(realizations.min()), "n_realizations": len(realizations)}
    attrs.update(whole_run)
    revisions = source_revisions(datasets)
    if revisions:  # the code that simulated the batches, not the first batch's alone
        attrs["source_git_revisions"] = revisions
    if "parameters_json" in attrs:
        parameters = json.loads(attrs["parameters_json"])
        parameters.update(whole_run)
        if "realizations" in parameters:  # the EDMD front's name for the count
            parameters["realizations"] = whole_run["n_realizations"]
        attrs["parameters_json"] = json.dumps(parameters, sort_keys=True, default=str)
    return combined.assign_attrs(attrs)
