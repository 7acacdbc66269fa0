"""``kinetic.workflow_support.run_job``, the one simulation script: a job of several points
(``kinetic.cloning.simulate_points`` on the GPU) writes each point's dataset to its own rule
output, stamped with that point's seed."""

import sys
from types import SimpleNamespace

import xarray as xr

from kinetic import io, studies, workflow_support


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
    monkeypatch.setattr(workflow_support, "warm_engines", lambda log: None)
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
    workflow_support.run_job(snakemake)
    for path, point in zip(outputs, points, strict=True):
        written = io.read_dataset(path)
        assert float(written.mu) == point["lam"]
        assert int(written.attrs["seed"]) == point["seed"]
        assert int(written.attrs["root_seed"]) == 7
    log = (tmp_path / "job.log").read_text()
    assert all(path in log for path in outputs)
