"""Combine batches of DSMC realizations into the numbers that figures plot (with errors)."""

from __future__ import annotations

from collections.abc import Sequence

import xarray as xr

from kinetic import io
from kinetic.analysis.statistics import mean_and_sem
from kinetic.batches import combine

__all__ = ["combine_free_flights"]


def combine_free_flights(batches: Sequence[xr.Dataset]) -> xr.Dataset:
    """Free-flight densities over every realization of ``simulate_free_flights`` batches.

    The batches must share their parameters except the realization range, and hold
    distinct realizations (two or more in all). Returns a dataset with the densities
    ``time_pdf``/``path_pdf`` (mean over realizations) and their standard errors
    ``time_pdf_sem``/``path_pdf_sem`` on the bin centres ``flight_time`` (1/ω) and
    ``free_path`` (l), the per-realization densities, the measured collision frequency
    (mean and sem), and totals of flights, unresolved paths and CPU seconds.
    """
    run = combine(list(batches))  # one run's parameters and seed, distinct realizations
    realizations = run.realization.values
    time_pdf = run.time_pdf.values
    path_pdf = run.path_pdf.values
    frequency = run.collision_frequency.values
    time_mean, time_sem = mean_and_sem(time_pdf)
    path_mean, path_sem = mean_and_sem(path_pdf)
    frequency_mean, frequency_sem = mean_and_sem(frequency)

    def total(name: str):
        return sum(batch[name].values.sum() for batch in batches)

    dataset = io.make_dataset(
        {
            "time_pdf": (
                "flight_time",
                time_mean,
                "omega",
                "free-flight time density P_FFT, mean over realizations",
            ),
            "time_pdf_sem": ("flight_time", time_sem, "omega", "standard error of time_pdf"),
            "path_pdf": (
                "free_path",
                path_mean,
                "1/l",
                "free-path density P_FPL, mean over realizations",
            ),
            "path_pdf_sem": ("free_path", path_sem, "1/l", "standard error of path_pdf"),
            "time_pdf_by_realization": (
                ("realization", "flight_time"),
                time_pdf,
                "omega",
                "free-flight time density of each realization",
            ),
            "path_pdf_by_realization": (
                ("realization", "free_path"),
                path_pdf,
                "1/l",
                "free-path density of each realization",
            ),
            "time_edges": (
                "flight_time_edge",
                run.time_edges.values,
                "1/omega",
                "flight-time bin edges",
            ),
            "path_edges": ("free_path_edge", run.path_edges.values, "l", "free-path bin edges"),
            "collision_frequency": (
                (),
                frequency_mean,
                "omega",
                "measured collisions per particle per unit time",
            ),
            "collision_frequency_sem": (
                (),
                frequency_sem,
                "omega",
                "standard error of collision_frequency",
            ),
            "flights": ((), total("flights"), "1", "recorded free flights, all realizations"),
            "unresolved_paths": (
                (),
                total("unresolved_paths"),
                "1",
                "open flights of unknown free path, all realizations",
            ),
            "cpu_seconds": ((), total("cpu_seconds"), "s", "CPU time of all realizations"),
        },
        coords={
            "realization": ("realization", realizations, "1", "realization index"),
            "flight_time": (
                "flight_time",
                run.flight_time.values,
                "1/omega",
                "free-flight time (bin centre)",
            ),
            "free_path": ("free_path", run.free_path.values, "l", "free path (bin centre)"),
            "flight_time_edge": (
                "flight_time_edge",
                run.flight_time_edge.values,
                "1/omega",
                "bin edge",
            ),
            "free_path_edge": ("free_path_edge", run.free_path_edge.values, "l", "bin edge"),
        },
        attrs={"engine": "kinetic.dsmc", "units": run.attrs["units"]},
    )
    parameters = io.parameters_of(run)
    parameters.pop("first_realization", None)
    return io.stamp(dataset, parameters=parameters, seed=int(run.attrs["seed"]))
