"""``kinetic.simulation_job.run_job``, the one simulation script: a job of several points
(``kinetic.cloning.simulate_points`` on the GPU) writes each point's dataset to its own rule
output, stamped with that point's seed."""

import os
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest
import xarray as xr

from kinetic import io, simulation_job, studies


@pytest.fixture(autouse=True)
def _job_threads_left_behind():
    """A job caps numba's threads to its own (``workflow_support.start``: the variable and
    the pool); the test worker gets its own back, or the CUDA simulator of a later test
    in it stops on NUMBA_NUM_THREADS changed after its threads were launched."""
    before = os.environ.get("NUMBA_NUM_THREADS")
    yield
    if before is None:
        os.environ.pop("NUMBA_NUM_THREADS", None)
    else:
        os.environ["NUMBA_NUM_THREADS"] = before
    if "numba" in sys.modules:
        import numba

        numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)


def test_a_job_of_several_points_writes_each_to_its_output(tmp_path, monkeypatch):
    def front(points, label):  # as kinetic.cloning.simulate_points: a stamped dataset each
        return [
            io.stamp(
                xr.Dataset({"mu": ((), float(point["lam"]), {"units": "1", "long_name": "mu"})}),
                parameters={"lam": point["lam"]},
                seed=point["seed"],
            )
            for point in points
        ]

    monkeypatch.setattr(studies, "front", lambda name: front)
    monkeypatch.setattr(simulation_job, "warm_engines", lambda log, front=None: None)
    monkeypatch.setattr(sys, "excepthook", sys.excepthook)  # run_job installs its own
    outputs = [str(tmp_path / f"lam{k}" / "batch0000.nc") for k in range(3)]
    points = [{"lam": lam, "seed": seed} for lam, seed in ((-1.0, 11), (0.5, 12), (2.0, 13))]
    snakemake = SimpleNamespace(
        output=outputs,
        log=[str(tmp_path / "job.log")],
        threads=1,
        rule="visco2008_simulate_cloning_scan_maxwell",
        config={"seed": 7},
        params=SimpleNamespace(
            front="kinetic.cloning:simulate_points",
            job={"points": points, "label": "three points"},
            parameters={},
        ),
    )
    simulation_job.run_job(snakemake)
    for path, point in zip(outputs, points, strict=True):
        written = io.read_dataset(path)
        assert float(written.mu) == point["lam"]
        assert int(written.attrs["seed"]) == point["seed"]
        assert int(written.attrs["root_seed"]) == 7
    log = (tmp_path / "job.log").read_text()
    assert all(path in log for path in outputs)


def test_a_job_warms_the_kernels_of_the_engine_function_its_front_runs(monkeypatch):
    """Every simulation job's front, through kinetic.studies.jobs: the engine it runs is
    warmed (even where the front imports it only when called, as montanero2007's), with
    the engine function's name, which the engine maps to its kernels (WARMUPS); the other
    engines the job declares, whole."""
    import logging
    from importlib import import_module

    from kinetic import jit
    from kinetic.config import load_config_file, validate_config

    calls = []
    monkeypatch.setattr(jit, "warm", lambda engine, front=None: calls.append((engine, front)) or 0)
    log = logging.getLogger("test")
    fronts = {}
    for backend in ("cpu", "cuda"):  # the GPU backend's fronts of several points too
        config = load_config_file(Path(__file__).parents[2] / "config" / "ci.yaml")
        config["backend"] = backend
        validate_config(config)
        fronts |= {job.front: job.engines for job in studies.jobs(config)}
    assert "kinetic.studies.montanero2007_front:simulate_batch" in fronts
    for name, engines in fronts.items():
        calls.clear()
        simulation_job.warm_engines(log, studies.front(name))
        warmed = dict(calls)
        assert set(engines) <= set(warmed), (name, calls)  # the event-disks start: samplers
        own = engines[0]
        listed = getattr(import_module(f"kinetic.{own}"), "WARMUPS", {})
        if listed:  # the engine lists its fronts: this one is among them
            assert warmed[own] in listed, (name, warmed)
        assert all(warmed[engine] is None for engine in engines[1:]), (name, warmed)
    assert studies.front("kinetic.studies.montanero2007_front:simulate_batch").engine_front == (
        "kinetic.dsmc:simulate_homogeneous"
    )
