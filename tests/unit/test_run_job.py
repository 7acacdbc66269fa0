"""``kinetic.simulation_job.run_job``, the one simulation script: a job of several points
(``kinetic.cloning.simulate_points`` on the GPU) writes each point's dataset to its own rule
output, stamped with that point's seed."""

import json
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


def _group_job(tmp_path, points):
    """A fake Snakemake object for montanero2007's job of a family's runs."""
    outputs = [str(tmp_path / f"run{k}" / "batch0000.nc") for k in range(len(points))]
    code = tmp_path / "code.py"
    code.parent.mkdir(parents=True, exist_ok=True)
    if not code.exists():
        code.write_text("# the job's code input\n")
    return SimpleNamespace(
        input=[str(code)],
        output=outputs,
        log=[str(tmp_path / "job.log")],
        threads=1024,  # numba's pool as it is: the kernels run here launch its threads
        rule="montanero2007_simulate_dsmc_scan",
        config={"seed": 7},
        params=SimpleNamespace(
            front="kinetic.studies.montanero2007_front:simulate_batches",
            job={"points": points, "label": "scan"},
            parameters={},
        ),
    )


def test_a_stopped_job_of_several_runs_keeps_the_runs_it_finished(tmp_path, monkeypatch):
    """montanero2007's runs of one family share a job on ``cuda`` (here on the cpu, the same
    front): a job stopped in its third run keeps the two it finished, and its rerun runs
    the third only and writes the numbers of a job never stopped; a point's kept file is
    not loaded by a job whose code or point differ."""
    from kinetic.dsmc import homogeneous

    monkeypatch.setattr(simulation_job, "warm_engines", lambda log, front=None: None)
    monkeypatch.setattr(sys, "excepthook", sys.excepthook)
    run = {
        "n_particles": 100,
        "time_step": 0.02,
        "force_step": "euler",
        "selection": "ntc",
        "splitting": "lie",
        "reduced_field": 0.05,
        "duration": 0.8,
        "steady_from": 0.4,
        "sample_interval": 0.4,
        "sample_stride": 5,
        "cx_max": 4.0,
        "cx_bins": 20,
        "restitution": 0.8,
    }
    points = [
        {
            "run": run | {"restitution": alpha},
            "seed": seed,
            "first": 0,
            "count": 2,
            "label": f"alpha {alpha}",
            "parameters": {"run": f"alpha{alpha}", "family": "scan", "setting": ""},
        }
        for alpha, seed in ((0.9, 3), (0.8, 4), (0.7, 5))
    ]
    engine = homogeneous.simulate_homogeneous
    ran = []

    def stopped_in_third(**arguments):
        if not arguments.get("validate_only"):
            ran.append(arguments["label"])
            if len(ran) == 3:
                raise KeyboardInterrupt
        return engine(**arguments)

    stopped = _group_job(tmp_path / "stopped", points)
    monkeypatch.setattr(homogeneous, "simulate_homogeneous", stopped_in_third)
    with pytest.raises(KeyboardInterrupt):
        simulation_job.run_job(stopped)
    kept = [simulation_job.resume_file(path) for path in stopped.output]
    assert [file.exists() for file in kept] == [True, True, False]
    assert not any(Path(path).exists() for path in stopped.output)

    ran.clear()
    monkeypatch.setattr(
        homogeneous, "simulate_homogeneous", lambda **a: ran.append(1) or engine(**a)
    )
    simulation_job.run_job(stopped)
    assert len(ran) == 2  # the third point's check and run: the first two were loaded
    assert not any(file.exists() for file in kept)
    whole = _group_job(tmp_path / "whole", points)
    simulation_job.run_job(whole)
    for resumed, fresh in zip(stopped.output, whole.output, strict=True):
        a, b = io.read_dataset(resumed), io.read_dataset(fresh)
        for name in set(a.data_vars) - {"cpu_seconds"}:
            xr.testing.assert_equal(a[name], b[name])
        assert io.parameters_of(a) == io.parameters_of(b)
        assert (
            a.attrs["seed"] == b.attrs["seed"]
            and a.attrs["steady_from_tau"] == b.attrs["steady_from_tau"]
        )

    # a kept point of other code, or of another point, is run again
    io.write_dataset(io.read_dataset(whole.output[0]).assign_attrs(resume_key="other"), kept[0])
    ran.clear()
    simulation_job.run_job(stopped)
    assert len(ran) == 2 * 3  # every point checked and run
    assert not kept[0].exists()


def test_a_file_is_stamped_with_its_documents_config_only(tmp_path, monkeypatch):
    """The ``config`` attribute of a file under <results>/<document>/ holds the shared keys
    and that document's section: another document's section did not make it, and its
    edits rerun nothing here, so stamping it would misstate the file's provenance."""
    from kinetic.workflow_support import output_config, write_output

    monkeypatch.chdir(tmp_path)
    config = {
        "seed": 7,
        "results": "results/ci",
        "visco2008": {"md": {"n_particles": 100}},
        "montanero2007": {"alphas": [0.5]},
        "limits": {"memory": 1},
    }
    path = "results/ci/visco2008/md/rho1e-2/batch0000.nc"
    snakemake = SimpleNamespace(output=[path], config=config)
    dataset = xr.Dataset({"k": ((), 1.0, {"units": "1", "long_name": "k"})})
    write_output(snakemake, dataset, seed=3, parameters={})
    stamped = json.loads(io.read_dataset(path).attrs["config"])
    assert stamped == {key: config[key] for key in ("seed", "results", "visco2008", "limits")}
    # outside every document's directory (or the results root): the whole config
    assert output_config(config, "results/ci/workflow/jobs.nc") == config
    assert output_config(config, str(tmp_path / "elsewhere.nc")) == config
