"""kinetic.io: dataset conventions, provenance attributes, netCDF round trip, tables."""

import json
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

from kinetic import io


def _dataset(values):
    return io.make_dataset(
        {"pdf": ("time", values, "omega", "free flight time density")},
        coords={"time": ("time", np.arange(values.size) * 0.5, "1/omega", "time")},
    )


def test_round_trip_keeps_values_units_and_provenance(tmp_path):
    values = np.random.default_rng(0).random(11)
    dataset = io.stamp(
        _dataset(values),
        parameters={
            "density": 0.01,
            "n_particles": 1000,
            "thermostat": True,
            "kernel": None,
            "windows": [10, 50],
        },
        seed=1234,
        config={"seed": 1, "visco2008": {"md": {"n_particles": 1000}}},
    )
    path = io.write_dataset(dataset, tmp_path / "run.nc")
    back = io.read_dataset(path)
    np.testing.assert_array_equal(back["pdf"].values, values)
    assert back["pdf"].attrs["units"] == "omega"
    assert back["time"].attrs["long_name"] == "time"
    assert back.attrs["seed"] == 1234
    assert back.attrs["density"] == 0.01
    assert back.attrs["thermostat"] == 1
    assert json.loads(back.attrs["config"])["visco2008"]["md"]["n_particles"] == 1000
    assert io.parameters_of(back)["windows"] == [10, 50]
    assert back.attrs["kinetic_version"]
    assert back.attrs["git_revision"]
    assert not list(tmp_path.glob(".*tmp"))


def test_missing_units_are_refused():
    import xarray as xr

    bare = xr.Dataset({"x": ("i", np.zeros(3))}, coords={"i": np.arange(3)})
    with pytest.raises(ValueError, match="'x' lacks units, long_name"):
        io.write_dataset(bare, "never-written.nc")


def test_dimension_without_coordinate_is_refused():
    with pytest.raises(ValueError, match="dimension 'time' has no coordinate"):
        io.make_dataset({"pdf": ("time", np.zeros(3), "1", "density")})


def test_same_input_gives_identical_files(tmp_path):
    values = np.linspace(0, 1, 5)
    stamped = io.stamp(_dataset(values), parameters={"a": 1}, seed=7)
    first = io.read_dataset(io.write_dataset(stamped, tmp_path / "a.nc"))
    second = io.read_dataset(io.write_dataset(stamped, tmp_path / "b.nc"))
    assert first.identical(second)


def test_table_csv_and_markdown(tmp_path):
    frame = pd.DataFrame(
        {"source": ["MD", "Poisson"], "k2": [1.1228, 1.0], "k2_err": [0.004, None]}
    )
    io.write_table(frame, tmp_path / "t.csv", tmp_path / "t.md", float_format=".4f")
    back = io.read_table(tmp_path / "t.csv")
    assert list(back.columns) == ["source", "k2", "k2_err"]
    assert np.isnan(back["k2_err"][1])
    markdown = (tmp_path / "t.md").read_text().splitlines()
    assert markdown[0] == "| source | k2 | k2_err |"
    assert markdown[3] == "| Poisson | 1.0000 |  |"


def test_tables_are_written_atomically_and_orphans_removed(tmp_path):
    frame = pd.DataFrame({"a": [1.0, np.nan], "b": ["x", "y"]})
    io.write_table(frame, tmp_path / "t.csv", tmp_path / "t.md")
    assert io.read_table(tmp_path / "t.csv")["b"].tolist() == ["x", "y"]
    assert (tmp_path / "t.md").read_text().startswith("| a | b |")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.csv", "t.md"]  # no temporary
    dead = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    orphan = tmp_path / "sub" / f".t.csv.{dead}.tmp"  # what a killed writer leaves
    orphan.parent.mkdir()
    orphan.write_text("half a tab")
    with subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"]) as writer:
        try:  # a writer of another build on this machine, still running: not an orphan
            busy = tmp_path / "sub" / f".u.csv.{writer.pid}.tmp"
            busy.write_text("being written")
            assert io.remove_orphans(tmp_path) == [orphan]
            assert busy.exists()
        finally:
            writer.kill()
    assert not orphan.exists()
    assert (tmp_path / "t.csv").exists()


def test_a_truncated_dataset_is_named_with_the_advice_to_delete_it(tmp_path):
    path = tmp_path / "batch0000.nc"
    io.write_dataset(_dataset(np.arange(3.0)), path)
    path.write_bytes(path.read_bytes()[:500])
    with pytest.raises(io.CorruptFileError, match=r"batch0000\.nc cannot be read.*delete it"):
        io.read_dataset(path)
