"""kinetic.bench.sidebyside: a revision's package imported under another name beside the
working tree's, and the per-round ratios of their rates."""

import importlib
import sys

import pytest

from kinetic.bench.sidebyside import rename_package, round_ratios


def test_a_renamed_copy_imports_itself_not_the_original(tmp_path):
    source = tmp_path / "src" / "kinetic"
    (source / "sub").mkdir(parents=True)
    (source / "__init__.py").write_text('"""kinetic itself."""\nfrom kinetic.sub import where\n')
    (source / "sub" / "__init__.py").write_text(
        "from kinetic.sub.leaf import WHERE as where\n"
        "MODULE = 'kinetic.sub.leaf'\nWORD = 'kinetics'\n"
    )
    (source / "sub" / "leaf.py").write_text("import kinetic\nWHERE = __name__\n")
    rename_package(source, tmp_path / "copy", "kinetic_copy_for_test")
    sys.path.insert(0, str(tmp_path / "copy"))
    try:
        package = importlib.import_module("kinetic_copy_for_test")
        sub = importlib.import_module("kinetic_copy_for_test.sub")
    finally:
        sys.path.remove(str(tmp_path / "copy"))
    assert package.where == "kinetic_copy_for_test.sub.leaf"
    assert sub.MODULE == "kinetic_copy_for_test.sub.leaf"  # module paths in strings too
    assert sub.WORD == "kinetics"  # another word is left alone
    for name in [m for m in sys.modules if m.startswith("kinetic_copy_for_test")]:
        del sys.modules[name]


def test_ratios_are_taken_round_by_round():
    # a slow second round slows both: its ratio is that of the others
    ratios = round_ratios([10.0, 5.0, 10.0], [11.0, 5.5, 11.0])
    assert ratios["median"] == pytest.approx(1.1)
    assert ratios["min"] == pytest.approx(1.1) and ratios["max"] == pytest.approx(1.1)
    with pytest.raises(ValueError):
        round_ratios([1.0, 2.0], [1.0])


def test_a_revision_git_cannot_read_is_refused_by_name(tmp_path, monkeypatch, capsys):
    from kinetic.bench.sidebyside import main

    monkeypatch.chdir(tmp_path)  # no repository here
    with pytest.raises(SystemExit):
        main(["HEAD", "--root", str(tmp_path / "copies"), "--out", str(tmp_path / "out")])
    said = capsys.readouterr().err
    assert "cannot read revision 'HEAD' with git" in said
    assert not (tmp_path / "copies").exists() and not (tmp_path / "out").exists()
