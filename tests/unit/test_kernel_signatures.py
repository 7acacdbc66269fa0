"""Compiled entry points take named bundles, not long positional lists: every kernel that
Python calls (decorated ``kernel`` or ``refcount_free`` in ``kinetic.jit``, name without a
leading underscore) takes at most 10 parameters. Helpers that only compiled code calls
(``inline`` ones, ``_``-prefixed ones: scalar arithmetic on a pair, a cell, an event) are
exempt."""

import ast

from kinetic.sources import PACKAGE

LIMIT = 10
ENTRY_DECORATORS = {"kernel", "refcount_free"}


def _entry_points():
    for path in sorted(PACKAGE.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
            if not isinstance(node, ast.FunctionDef) or node.name.startswith("_"):
                continue
            names = {ast.unparse(d).split("(")[0].split(".")[-1] for d in node.decorator_list}
            if names & ENTRY_DECORATORS:
                yield path.relative_to(PACKAGE).as_posix(), node.name, len(node.args.args)


def test_no_compiled_entry_point_takes_more_than_ten_parameters():
    found = list(_entry_points())
    assert len(found) > 40  # the walk sees the engines' kernels
    assert {"dsmc/kernels.py", "edmd/events.py", "cloning/kernels.py"} <= {f for f, _, _ in found}
    long = [(file, name, count) for file, name, count in found if count > LIMIT]
    assert not long, long
