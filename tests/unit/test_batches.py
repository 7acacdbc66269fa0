"""kinetic.batches: job plans and the joining of batch datasets."""

import numpy as np
import pytest

from kinetic import batches, io


def batch(first, count, *, seed=5, restitution=0.8):
    realizations = np.arange(first, first + count)
    dataset = io.make_dataset(
        {
            "value": ("realization", realizations * 1.5, "1", "a value per realization"),
            "grid_value": ("grid", np.arange(3.0), "1", "a value without realizations"),
        },
        coords={
            "realization": ("realization", realizations, "1", "realization number"),
            "grid": ("grid", np.arange(3), "1", "grid"),
        },
    )
    parameters = {
        "restitution": restitution,
        "first_realization": first,
        "n_realizations": count,
    }
    return io.stamp(dataset, parameters=parameters, seed=seed)


def test_plan_covers_every_realization_once():
    jobs = batches.plan(realizations=10, realizations_per_job=4)
    assert [(j.first_realization, j.n_realizations) for j in jobs] == [(0, 4), (4, 4), (8, 2)]
    assert [batches.batch_name(j.index) for j in jobs] == ["batch0000", "batch0001", "batch0002"]


@pytest.mark.parametrize("bad", [0, -1, 2.5, True, "4"])
def test_plan_refuses_non_positive_or_non_integer_counts(bad):
    with pytest.raises(ValueError, match="realizations_per_job"):
        batches.plan(realizations=4, realizations_per_job=bad)


def test_combine_orders_realizations_and_updates_the_range():
    run = batches.combine([batch(2, 2), batch(0, 2)])
    np.testing.assert_array_equal(run.realization, [0, 1, 2, 3])
    np.testing.assert_array_equal(run.value, [0.0, 1.5, 3.0, 4.5])
    np.testing.assert_array_equal(run.grid_value, [0.0, 1.0, 2.0])
    assert run.attrs["n_realizations"] == 4
    assert io.parameters_of(run)["first_realization"] == 0


def test_a_run_names_the_revisions_that_simulated_its_batches():
    """A joined run records the code of its numbers (``source_git_revisions``), not only
    the join's (``git_revision``), also where its batches were simulated by two revisions;
    writing the run again keeps them."""
    first, second = batch(0, 2), batch(2, 2)
    assert "source_git_revisions" not in first.attrs  # a simulation's first write
    first.attrs["git_revision"] = "bbb2222"
    second.attrs["git_revision"] = "aaa1111"
    run = batches.combine([first, second])
    assert run.attrs["source_git_revisions"] == "aaa1111 bbb2222"
    again = io.stamp(run, parameters=io.parameters_of(run), seed=5)
    assert again.attrs["source_git_revisions"] == "aaa1111 bbb2222"
    assert again.attrs["git_revision"] == io.git_revision()
    alone = io.stamp(first, parameters=io.parameters_of(first), seed=5)
    assert alone.attrs["source_git_revisions"] == "bbb2222"


def test_combine_names_overlapping_batches():
    with pytest.raises(ValueError, match=r"realization 1 appears in both a\.nc and b\.nc"):
        batches.combine([batch(0, 2), batch(1, 2)], names=["a.nc", "b.nc"])


def test_combine_refuses_batches_of_different_runs():
    with pytest.raises(ValueError, match=r"b\.nc and a\.nc belong to different runs.*restitution"):
        batches.combine([batch(0, 2), batch(2, 2, restitution=0.7)], names=["a.nc", "b.nc"])
    with pytest.raises(ValueError, match="different seeds"):
        batches.combine([batch(0, 2), batch(2, 2, seed=6)], names=["a.nc", "b.nc"])


def test_read_run_names_overlapping_files(tmp_path):
    first, second = tmp_path / "batch0000.nc", tmp_path / "batch0001.nc"
    io.write_dataset(batch(0, 2), first)
    io.write_dataset(batch(1, 2), second)
    with pytest.raises(ValueError, match=r"batch0000\.nc and .*batch0001\.nc"):
        io.read_run([first, second])
    io.write_dataset(batch(2, 2), second)
    assert io.read_run([second, first]).sizes["realization"] == 4
