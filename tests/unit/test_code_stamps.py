"""kinetic.sources.code_stamps: the code inputs of the workflow's rules move their
modification time when a source's code changes, and only then; an edit of comments,
docstrings or layout reruns nothing. ``remembered_fingerprint`` (numba's cache stamps, and
the code stamps of a new build) reads a file's fingerprint from its memo while the file is
untouched."""

import os
import time
from pathlib import Path

import pytest

from kinetic.sources import (
    PACKAGE,
    code_fingerprint,
    code_stamps,
    fingerprint_memo,
    forget_earlier_codes,
    remembered_fingerprint,
)

MODULE = '''"""A module."""

import math

SCALE = 2.0
"""The scale (an attribute docstring)."""


def area(radius):
    """The area."""
    return math.pi * radius**2 * SCALE  # a comment


class Disk:
    """A disk."""

    def __init__(self, radius):
        self.radius = radius
'''

SAME_CODE = {
    "a comment": MODULE + "# an edit\n",
    "a module docstring": MODULE.replace('"""A module."""', '"""A module, described."""'),
    "a function docstring": MODULE.replace('"""The area."""', '"""The area of a disk."""'),
    "a class docstring": MODULE.replace('"""A disk."""', "'''A round disk.'''"),
    "an attribute docstring": MODULE.replace("(an attribute docstring)", "(its docstring)"),
    "the layout": MODULE.replace(
        "math.pi * radius**2 * SCALE", "(math.pi\n    * radius ** 2 * SCALE)"
    ),
    "a removed docstring": MODULE.replace('    """The area."""\n', ""),
}

OTHER_CODE = {
    "a constant": MODULE.replace("SCALE = 2.0", "SCALE = 2.5"),
    "an operator": MODULE.replace("radius**2", "radius**3"),
    "a statement": MODULE + "\nSCALE = 1.0\n",
    "a string that is used": MODULE.replace("SCALE = 2.0", 'SCALE = float("2.0")'),
    "a name": MODULE.replace("self.radius = radius", "self.size = radius"),
}


@pytest.mark.parametrize("edit", sorted(SAME_CODE))
def test_comments_docstrings_and_layout_keep_the_fingerprint(tmp_path, edit):
    before, after = tmp_path / "before.py", tmp_path / "after.py"
    before.write_text(MODULE)
    after.write_text(SAME_CODE[edit])
    assert code_fingerprint(after) == code_fingerprint(before)


@pytest.mark.parametrize("edit", sorted(OTHER_CODE))
def test_a_code_edit_changes_the_fingerprint(tmp_path, edit):
    before, after = tmp_path / "before.py", tmp_path / "after.py"
    before.write_text(MODULE)
    after.write_text(OTHER_CODE[edit])
    assert code_fingerprint(after) != code_fingerprint(before)


def test_a_file_that_does_not_parse_is_fingerprinted_by_its_bytes(tmp_path):
    source = tmp_path / "broken.py"
    source.write_text("def f(:\n    pass\n")
    first = code_fingerprint(source)
    source.write_text("def f(:\n    pass\n# a comment\n")
    assert first.startswith("bytes:") and code_fingerprint(source) != first


def test_every_package_file_parses():
    """No stamp of the package falls back to the bytes (which a comment would change)."""
    for path in sorted(PACKAGE.rglob("*.py")):
        assert not code_fingerprint(path).startswith("bytes:"), path


def _set_mtime(path, seconds):
    os.utime(path, (seconds, seconds))


def test_a_stamp_moves_only_when_the_code_changes(tmp_path):
    root, stamps = tmp_path / "tree", tmp_path / "stamps"
    source = root / "src" / "module.py"
    source.parent.mkdir(parents=True)
    source.write_text(MODULE)
    _set_mtime(source, 1_000_000)
    (stamp,) = map(Path, code_stamps([source], root, stamps))
    assert stamp == stamps / "src" / "module.py.stamp"
    # a new stamp takes the source's time: a build from before the stamps reruns nothing
    assert stamp.stat().st_mtime == 1_000_000

    built = 2_000_000  # an output built after that
    source.write_text(SAME_CODE["a function docstring"] + "# and a comment\n")
    _set_mtime(source, 3_000_000)
    code_stamps([source], root, stamps)
    assert stamp.stat().st_mtime == 1_000_000 < built

    source.write_text(OTHER_CODE["a constant"])
    _set_mtime(source, 1_500_000)  # even a restored older file with its own, older time
    code_stamps([source], root, stamps)
    assert stamp.stat().st_mtime > built

    # a deleted stamp comes back with the source's time
    stamp.unlink()
    code_stamps([source], root, stamps)
    assert stamp.stat().st_mtime == 1_500_000


def test_a_source_outside_the_root_is_stamped_by_its_absolute_path(tmp_path):
    source = tmp_path / "installed" / "module.py"
    source.parent.mkdir()
    source.write_text(MODULE)
    (stamp,) = code_stamps([source], tmp_path / "tree", tmp_path / "stamps")
    assert Path(stamp) == tmp_path / "stamps" / f"external{source.resolve()}.stamp"
    assert Path(stamp).is_file()


def test_a_memo_stands_for_the_fingerprint_while_its_file_is_untouched(tmp_path):
    source = tmp_path / "module.py"
    source.write_text(MODULE)
    memo = fingerprint_memo(source)
    assert remembered_fingerprint(source) == code_fingerprint(source)
    fingerprint, seen = memo.read_text().splitlines()
    # the memo is read, not the file: a memo of the same time and size is believed
    memo.write_text(f"{'0' * 64}\n{seen}\n")
    assert remembered_fingerprint(source) == "0" * 64
    # an edit changes the size (or the time): the file is parsed again, the memo renewed
    source.write_text(MODULE + "RADIUS = 1.0\n")
    assert remembered_fingerprint(source) == code_fingerprint(source) != fingerprint
    assert memo.read_text().splitlines()[0] == code_fingerprint(source)


def test_the_memo_lies_beside_its_source_and_serves_the_stamps_too(tmp_path):
    """The fingerprint is kept in ``__pycache__`` beside the file, and a stamp written in a
    new directory reads it there instead of parsing the file."""
    source = tmp_path / "tree" / "module.py"
    source.parent.mkdir()
    source.write_text(MODULE)
    assert remembered_fingerprint(source) == code_fingerprint(source)
    memo = fingerprint_memo(source)
    assert memo == tmp_path / "tree" / "__pycache__" / "module.py.fingerprint"
    seen = memo.read_text().splitlines()[1]
    memo.write_text(f"{'1' * 64}\n{seen}\n")  # what only the memo can have told
    (stamp,) = code_stamps([source], tmp_path / "tree", tmp_path / "another build")
    assert Path(stamp).read_text().splitlines()[0] == "1" * 64


def test_an_unwritable_memo_only_costs_the_parse(tmp_path):
    source = tmp_path / "module.py"
    source.write_text(MODULE)
    (tmp_path / "__pycache__").write_text("")  # a file where the memo's directory should be
    assert remembered_fingerprint(source) == code_fingerprint(source)
    assert remembered_fingerprint(source) == code_fingerprint(source)


def test_a_return_to_the_code_no_build_has_left_restores_the_stamps_time(tmp_path):
    """An edit seen by a dry run (or a branch checked out and back), then reverted, reruns
    nothing; once a build has started on the edited code, the return reruns what it made."""
    root, stamps = tmp_path / "tree", tmp_path / "stamps"
    source = root / "module.py"
    source.parent.mkdir(parents=True)
    source.write_text(MODULE)
    _set_mtime(source, 1_000_000)
    (stamp,) = map(Path, code_stamps([source], root, stamps))
    built = 2_000_000  # outputs of the original code

    def visit(text, seconds):
        source.write_text(text)
        _set_mtime(source, seconds)
        code_stamps([source], root, stamps)
        return stamp.stat().st_mtime

    assert visit(OTHER_CODE["a constant"], 3_000_000) > built  # the dry run plans reruns
    assert visit(OTHER_CODE["an operator"], 3_000_001) > built  # another edit, another look
    assert visit(MODULE + "# back\n", 3_000_002) == 1_000_000 < built  # reverted: nothing

    edited = visit(OTHER_CODE["a constant"], 3_000_003)
    assert edited > built
    assert forget_earlier_codes(stamps) == 1  # a build starts on the edited code
    assert stamp.stat().st_mtime == edited  # its time is kept
    assert visit(MODULE, 3_000_004) > edited  # the return reruns what it made


def test_a_job_on_code_edited_since_the_parse_marks_its_stamps(tmp_path, monkeypatch):
    """A build parses on code A, the file is edited to B while it runs, a job starts on B
    (its start refreshes its own stamps, then forgets), a dry run looks, the edit is
    reverted: the return to A must rerun what the job made from B."""
    from kinetic.sources import STAMPS, refresh_stamps

    monkeypatch.chdir(tmp_path)
    root = tmp_path / "tree"
    source = root / "module.py"
    source.parent.mkdir(parents=True)
    source.write_text(MODULE)
    _set_mtime(source, 1_000_000)
    (stamp,) = code_stamps([source], root, STAMPS)  # the build's parse, on A
    forget_earlier_codes(STAMPS)  # its onstart
    source.write_text(OTHER_CODE["a constant"])  # B, during the build
    _set_mtime(source, 3_000_000)
    refresh_stamps([stamp], root)  # the job's start
    forget_earlier_codes(STAMPS)
    # (the job writes its output from B now)
    code_stamps([source], root, STAMPS)  # a dry run
    source.write_text(MODULE)  # reverted
    _set_mtime(source, 3_000_002)
    reverted = time.time_ns()
    code_stamps([source], root, STAMPS)
    # now, after the output: not the parse's time, 1_000_000, which the dry run had
    # remembered for A when the job had not marked B
    assert Path(stamp).stat().st_mtime_ns >= reverted


def test_a_build_forgetting_during_a_dry_runs_refresh_is_not_undone(tmp_path, monkeypatch):
    """A dry run refreshes a stamp (read, change, write) while a job of a running build
    forgets every stamp's earlier codes: the forget waits for the refresh, rather than
    being overwritten by it. Before the lock, the dry run wrote back the code A that the
    job had forgotten, and a return to A restored a time older than the job's outputs."""
    import threading

    from kinetic import sources

    root, stamps = tmp_path / "tree", tmp_path / "stamps"
    source = root / "module.py"
    source.parent.mkdir(parents=True)
    source.write_text(MODULE)
    _set_mtime(source, 1_000_000)
    (stamp,) = map(Path, code_stamps([source], root, stamps))  # code A
    source.write_text(OTHER_CODE["a constant"])  # B: the stamp remembers A as earlier
    _set_mtime(source, 3_000_000)
    code_stamps([source], root, stamps)
    assert sources._earlier(stamp)

    forgetting = []
    fingerprint = sources.remembered_fingerprint

    def slow_fingerprint(path):  # the dry run's refresh, between its read and its write
        job = threading.Thread(target=lambda: forgetting.append(forget_earlier_codes(stamps)))
        job.start()
        job.join(timeout=0.5)  # a forget that does not wait has finished by now
        forgetting.append(job)
        return fingerprint(path)

    monkeypatch.setattr(sources, "remembered_fingerprint", slow_fingerprint)
    source.write_text(OTHER_CODE["an operator"])  # C, seen by the dry run
    _set_mtime(source, 3_000_001)
    code_stamps([source], root, stamps)
    job = next(item for item in forgetting if isinstance(item, threading.Thread))
    job.join()
    assert not sources._earlier(stamp), "the refresh wrote back the codes the job forgot"
