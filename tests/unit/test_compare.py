"""kinetic.compare: two results trees are identical or the differences are named."""

import numpy as np
import pandas as pd
import xarray as xr

from kinetic.compare import compare_trees, main


def _tree(root, value=1.0, cpu=3.0, extra=False):
    (root / "doc").mkdir(parents=True)
    table = {"alpha": [0.5, 1.0], "k": [value, 2.0], "name": ["a", "b"]}
    pd.DataFrame({**table, "inefficiency": [cpu, cpu]}).to_csv(
        root / "doc" / "table.csv", index=False
    )
    (root / "workflow").mkdir()
    pd.DataFrame({"rule": [f"rule_{cpu}"], "measured_s": [cpu]}).to_csv(
        root / "workflow" / "jobs.csv", index=False
    )
    xr.Dataset(
        {"mu": ("x", np.array([value, np.nan])), "cpu_seconds": ("x", np.array([cpu, cpu]))},
        attrs={"git_revision": str(cpu)},
    ).to_netcdf(root / "doc" / "run.nc")
    if extra:
        (root / "doc" / "more.csv").write_text("a\n1\n")
    return root


def test_identical_trees_differ_only_in_timings_and_provenance(tmp_path, capsys):
    a = _tree(tmp_path / "a")
    b = _tree(tmp_path / "b", cpu=9.0)  # another run: other timings and attributes
    report = compare_trees(a, b)
    assert report.identical and report.compared == 2
    assert main([str(a), str(b)]) == 0
    assert "2 files compared in both trees: identical" in capsys.readouterr().out


def test_a_changed_number_or_a_missing_file_is_reported(tmp_path):
    a = _tree(tmp_path / "a")
    b = _tree(tmp_path / "b", value=1.0 + 1e-12, extra=True)
    report = compare_trees(a, b)
    assert not report.identical
    text = "\n".join(report.differences)
    assert "table.csv: column k" in text and "run.nc: variable mu" in text
    assert "more.csv: only in" in text
    assert main([str(a), str(b)]) == 1
    # within a tolerance the numbers agree; the extra file still differs
    assert len(compare_trees(a, b, rtol=1e-9).differences) == 1


def test_a_renamed_dimension_is_the_same_numbers_only_when_mapped(tmp_path):
    a = _tree(tmp_path / "a")
    b = _tree(tmp_path / "b")
    renamed = xr.open_dataset(b / "doc" / "run.nc").load().rename({"x": "realization"})
    renamed.to_netcdf(b / "doc" / "run.nc")
    assert "dimensions ('x',) against ('realization',)" in "\n".join(
        compare_trees(a, b).differences
    )
    assert compare_trees(a, b, renames={"x": "realization"}).identical
    assert main([str(a), str(b), "--rename", "x=realization"]) == 0
    # the map renames names only: a changed number still shows
    c = _tree(tmp_path / "c", value=2.0)
    assert not compare_trees(c, b, renames={"x": "realization"}).identical
