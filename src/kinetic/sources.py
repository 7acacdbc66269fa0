"""The source files a compiled kernel depends on (numpy-free: the workflow reads them while
it parses the Snakefile).

One list serves two consumers that must agree:

- numba's on-disk cache (``kinetic.jit``): a cached kernel is fresh only while the code of
  none of the files it depends on changed. numba itself checks only the file that defines
  the kernel; the helpers an engine inlines live in other files of the engine and in
  ``kinetic.rng``.
- the simulation rules (``workflow/rules/common.smk``): they rerun when the code of these
  files changes, and the first of them compiles the kernels again (``kinetic.jit.warm``).

Both judge a file by its ``code_fingerprint``, so an edit of comments or docstrings
neither reruns nor recompiles anything.

An engine's kernels depend on the files of its package and on the shared modules below.
Compiled code elsewhere (the benchmarks call into several engines) depends on every file
of ``kinetic``.

The rules that join, analyse and plot results depend on the package files their script
imports (``script_sources``), read from the import statements without importing anything.
A simulation job depends on its engines' sources and on the other package files its front
runs (``front_sources``: the theory a sampler starts from, the statistics a front stores),
except the bookkeeping modules that name, write and log results.

The rules do not take those files themselves as inputs but their stamps (``code_stamps``):
one small file per source whose modification time moves only when the source's code
changes, not its comments, docstrings or layout. An edit of a docstring thus reruns
nothing, while an edit of one statement reruns what runs it.
"""

from __future__ import annotations

import ast
import contextlib
import fcntl
import hashlib
import os
import re
import socket
import time
from functools import cache
from pathlib import Path

__all__ = [
    "BOOKKEEPING",
    "ENGINES",
    "PACKAGE",
    "SHARED",
    "STAMPS",
    "code_fingerprint",
    "code_stamps",
    "engine_sources",
    "fingerprint_memo",
    "forget_earlier_codes",
    "front_sources",
    "kernel_sources",
    "refresh_stamps",
    "remembered_fingerprint",
    "script_sources",
]

PACKAGE = Path(__file__).resolve().parent
"""The ``kinetic`` package directory."""

ENGINES = ("cloning", "dsmc", "edmd", "event_disks", "samplers")
"""Subpackages whose compiled kernels call only themselves and the shared modules."""

SHARED = ("rng", "seeds", "jit", "validate", "gas")
"""Top-level modules every engine depends on (``rng`` and ``jit`` hold compiled code)."""

BOOKKEEPING = (
    "__init__",
    "config",
    "cost",
    "io",
    "lazy",
    "progress",
    "simulation_job",
    "sources",
    "studies/__init__",
    "workflow_support",
)
"""Modules that validate, name, estimate, write and log results but compute no simulated
number: an edit of them reruns no simulation, nor does an edit of what only they import
(the cost model's imports, say, which a study loads to plan its jobs). ``studies/__init__``
(the job type and its helpers) is the package on the way to montanero2007's front module:
as an input, a one-line edit of it scheduled all 57 of that document's simulations."""


def engine_sources(engine: str) -> list[Path]:
    """Every ``*.py`` file of subpackage ``engine`` and the shared modules, sorted."""
    if engine not in ENGINES:
        raise ValueError(f"unknown engine {engine!r}: one of {', '.join(ENGINES)}")
    files = list((PACKAGE / engine).rglob("*.py"))
    files += [PACKAGE / f"{module}.py" for module in SHARED]
    return sorted(files)


def kernel_sources(py_file: str | Path) -> list[Path]:
    """The files whose change must invalidate the compiled code defined in ``py_file``
    (a file of the package): its engine's sources, the shared modules for a shared
    module, every file of the package otherwise."""
    relative = Path(py_file).resolve().relative_to(PACKAGE)
    if len(relative.parts) > 1 and relative.parts[0] in ENGINES:
        return engine_sources(relative.parts[0])
    if len(relative.parts) == 1 and relative.stem in SHARED:
        return sorted(PACKAGE / f"{module}.py" for module in SHARED)
    return sorted(PACKAGE.rglob("*.py"))


def _module_files(dotted: str) -> list[Path]:
    """The files that ``import dotted`` runs inside the package: the ``__init__.py`` of
    every package on the way, then the module itself (empty when it is not a module)."""
    parts = dotted.split(".")[1:]
    files = [PACKAGE / "__init__.py"]
    for depth in range(1, len(parts) + 1):
        path = PACKAGE.joinpath(*parts[:depth])
        if (path / "__init__.py").is_file():
            files.append(path / "__init__.py")
        elif path.with_suffix(".py").is_file() and depth == len(parts):
            files.append(path.with_suffix(".py"))
        else:
            return []
    return files


def _import_statements(tree: ast.Module):
    """The import statements of a module, at any depth of its statements (function and
    class bodies, branches, handlers), without walking its expressions, which cannot hold
    one: a tenth of the nodes ``ast.walk`` visits."""
    blocks = [tree.body]
    while blocks:
        for statement in blocks.pop():
            if isinstance(statement, ast.Import | ast.ImportFrom):
                yield statement
                continue
            if _type_checking_only(statement):  # for annotations: never run
                blocks.append(statement.orelse)
                continue
            for field in ("body", "orelse", "finalbody", "handlers", "cases"):
                children = getattr(statement, field, None)
                if isinstance(children, list):
                    blocks.append(children)


def _type_checking_only(statement: ast.stmt) -> bool:
    """An ``if TYPE_CHECKING:`` (or ``typing.TYPE_CHECKING``) statement, whose body only a
    type checker reads."""
    if not isinstance(statement, ast.If):
        return False
    test = statement.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


_TYPE_CHECKING_BLOCK = re.compile(
    r"^([ \t]*)if[ \t]+(?:typing\.)?TYPE_CHECKING[ \t]*:[^\n]*\n(?:(?:\1[ \t]+[^\n]*)?\n)*",
    re.MULTILINE,
)
"""An ``if TYPE_CHECKING:`` line and the lines indented under it (blank ones included): the
imports there are for annotations, and a module's code inputs leave them out (the
studies' cost-model annotation made every reading script of two documents depend on
the cost model and the cloning engine's argument checks)."""


_PACKAGE_IMPORT = re.compile(
    r"^[ \t]*(from[ \t]+kinetic\b[\w.]*[ \t]+import[ \t]+(?:\([^)]*\)|[^\n]*)"
    r"|import[ \t]+kinetic\b[^\n]*)",
    re.MULTILINE,
)
"""A statement that imports from the package, at any indentation: ``from kinetic...
import`` (a parenthesised list may span lines) or ``import kinetic...``."""


def _package_imports(path: Path) -> list[ast.Import | ast.ImportFrom]:
    """The import statements of ``path`` that name the package, parsed one by one from the
    lines that start them: parsing whole modules took 0.34 s for the package and the
    workflow's scripts, this 0.04 s, and the workflow reads them each time Snakemake starts.
    A line that only looks like one (a module docstring's usage example) is parsed too: it
    can add a dependency, never lose one (tests/unit/test_script_sources.py checks that
    every script's and front's files are those of the whole-module reading). Where a
    statement does not parse alone (a parenthesis in a comment), the whole module is."""
    text = path.read_text()
    try:
        return [
            node
            for statement in _PACKAGE_IMPORT.findall(_TYPE_CHECKING_BLOCK.sub("", text))
            for node in ast.parse(statement).body
            if isinstance(node, ast.Import | ast.ImportFrom)
        ]
    except SyntaxError:
        return list(_import_statements(ast.parse(text, filename=str(path))))


@cache
def _imported_files(path: Path) -> tuple[Path, ...]:
    """Package files imported by the import statements of ``path`` (anywhere in it,
    function bodies included); ``from kinetic.x import name`` counts the submodule
    ``kinetic.x.name`` when there is one."""
    found = []
    for node in _package_imports(path):
        if isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "kinetic":
            found += _module_files(node.module)
            for alias in node.names:
                found += _module_files(f"{node.module}.{alias.name}")[-1:]
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "kinetic":
                    found += _module_files(alias.name)
    return tuple(dict.fromkeys(found))


DATA_FILES = {Path("plotting/__init__.py"): (Path("plotting/kinetic.mplstyle"),)}
"""Files that a package module reads when imported, by its path in the package: they are
code inputs wherever the module is (the style file's edit rerendered no figure)."""


def script_sources(script: str | Path) -> list[Path]:
    """Every package file a script runs: what it imports, and what those files import in
    turn, sorted. Names that a package's ``__init__`` loads on first use
    (``kinetic.edmd``'s lazy fronts) are not followed; scripts that join, analyse and plot
    results do not call them."""
    seen: set[Path] = set()
    todo = list(_imported_files(Path(script).resolve()))
    while todo:
        path = todo.pop()
        if path not in seen:
            seen.add(path)
            todo += _imported_files(path)
    for path in list(seen):
        seen.update(PACKAGE / data for data in DATA_FILES.get(path.relative_to(PACKAGE), ()))
    return sorted(seen)


@cache
def _lazy_exports(init: Path) -> dict[str, str]:
    """The ``_EXPORTS`` mapping of a package's ``__init__.py`` (``kinetic.lazy``: public
    name -> the submodule that defines it), read from its syntax tree; {} without one."""
    for node in ast.parse(init.read_text()).body:
        targets = node.targets if isinstance(node, ast.Assign) else []
        if any(isinstance(t, ast.Name) and t.id == "_EXPORTS" for t in targets):
            return ast.literal_eval(node.value)
    return {}


def front_sources(front: str, engines) -> list[Path]:
    """Files whose edit must rerun a simulation job that calls ``front`` (``module:function``,
    a ``kinetic.studies.Job``'s) with ``engines``: the engines' sources, the front's module
    and the packages on the way to it, and every package file they import, bookkeeping
    aside."""
    module, _, function = front.partition(":")
    bookkeeping = {PACKAGE / f"{name}.py" for name in BOOKKEEPING}
    files = {path for engine in engines for path in engine_sources(engine)}
    own = _module_files(module)
    if not own:
        raise ValueError(f"{module} is not a module of the package")
    lazy = _lazy_exports(own[-1]) if own[-1].name == "__init__.py" else {}
    if function in lazy:  # a name the package loads on first use: the module defining it
        own += _module_files(f"{module}.{lazy[function]}")[-1:]
    seen: set[Path] = set()
    todo = list(own)
    while todo:
        path = todo.pop()
        if path not in seen:
            seen.add(path)
            if path not in bookkeeping:  # what only bookkeeping imports is not the job's
                todo += _imported_files(path)
    files.update(path for path in seen if path not in bookkeeping)
    return sorted(files)


def _drop_inert_strings(tree: ast.Module) -> ast.Module:
    """Remove, from every statement list of ``tree``, the statements that are a constant
    alone: docstrings, the attribute docstrings under assignments, a stray ``...``."""
    for node in ast.walk(tree):
        for field in ("body", "orelse", "finalbody"):
            statements = getattr(node, field, None)
            if isinstance(statements, list):
                statements[:] = [
                    statement
                    for statement in statements
                    if not (
                        isinstance(statement, ast.Expr)
                        and isinstance(statement.value, ast.Constant)
                    )
                ]
    return tree


def code_fingerprint(path: str | Path) -> str:
    """SHA-256 of what ``path`` (a Python file) computes: its syntax tree without comments,
    docstrings, line numbers or layout. A file that does not parse is fingerprinted by its
    bytes (the job that imports it fails with the syntax error)."""
    data = Path(path).read_bytes()
    try:
        tree = _drop_inert_strings(ast.parse(data, filename=str(path)))
    except (SyntaxError, ValueError):
        return "bytes:" + hashlib.sha256(data).hexdigest()
    return hashlib.sha256(ast.dump(tree).encode()).hexdigest()


def _seen(status: os.stat_result) -> str:
    """What a memo or a stamp records of its source: modification time and size."""
    return f"{status.st_mtime_ns} {status.st_size}"


def _write_atomically(path: Path, text: str, times: tuple[int, int] | None = None) -> None:
    """Write ``text`` to ``path`` through a temporary file of this process and a rename (with
    access and modification ``times`` in ns, if given): a process reading it at the same
    time sees the old file or the new one, never a part."""
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_name(f".{path.name}.{socket.gethostname()}.{os.getpid()}.tmp")
    partial.write_text(text)
    if times is not None:
        os.utime(partial, ns=times)
    os.replace(partial, path)


def _read_record(path: Path) -> tuple[str | None, str | None]:
    """The fingerprint and the source's ``_seen`` that a memo or a stamp holds; (None,
    None) for a missing or unreadable one."""
    try:
        fingerprint, seen = path.read_text().splitlines()[:2]
    except (OSError, ValueError):
        return None, None
    return fingerprint, seen


def fingerprint_memo(source: str | Path) -> Path:
    """Where ``remembered_fingerprint`` keeps the fingerprint of ``source``:
    ``__pycache__/<name>.fingerprint`` beside it, as Python keeps a module's bytecode."""
    source = Path(source)
    return source.parent / "__pycache__" / f"{source.name}.fingerprint"


def remembered_fingerprint(source: str | Path) -> str:
    """``code_fingerprint(source)``, kept in its memo (:func:`fingerprint_memo`) with the
    source's modification time and size: read from there while they are unchanged, so
    that a process parses only the files edited since.
    Every reader shares the memos: numba's cache stamps (``kinetic.jit``; the 14 files of
    the DSMC engine take 0.15-0.3 s to parse, their memos a few ms to read) and the
    workflow's code stamps, which a build in a new working directory would otherwise
    compute by parsing every script and package file (1.3-1.7 s of each Snakemake start).
    Where the memo cannot be written (a read-only installation), the fingerprint is
    computed each time."""
    source = Path(source)
    memo = fingerprint_memo(source)
    seen = _seen(source.stat())
    fingerprint, recorded = _read_record(memo)
    if recorded == seen:
        return fingerprint
    fingerprint = code_fingerprint(source)
    with contextlib.suppress(OSError):
        _write_atomically(memo, f"{fingerprint}\n{seen}\n")
    return fingerprint


STAMPS = Path(".snakemake/kinetic/code")
"""Where the workflow keeps the stamps of its code inputs (:func:`code_stamps`), relative
to its working directory."""

EARLIER = "earlier"
"""The tag of a stamp's lines after the first two: ``earlier <fingerprint> <time ns>``, a
code the source held since the last build started and the stamp's time then."""


def _earlier(stamp: Path) -> dict[str, int]:
    """{fingerprint: the stamp's modification time in ns while it held it} of the codes
    ``stamp``'s source held since the last build started (:func:`forget_earlier_codes`)."""
    try:
        lines = stamp.read_text().splitlines()[2:]
    except OSError:
        return {}
    found = {}
    for line in lines:
        tag, fingerprint, time_ns = [*line.split(), "", "", ""][:3]
        if tag == EARLIER and time_ns.isdigit():
            found[fingerprint] = int(time_ns)
    return found


def _stamp_text(fingerprint: str, seen: str, earlier: dict[str, int]) -> str:
    lines = [fingerprint, seen] + [f"{EARLIER} {key} {value}" for key, value in earlier.items()]
    return "\n".join(lines) + "\n"


@contextlib.contextmanager
def _locked(directory: Path):
    """Hold an exclusive ``flock`` on ``directory`` (the folder of the stamps about to be
    read and rewritten): a stamp's update is a read, a change and a write, and a build's
    job forgetting the earlier codes (:func:`forget_earlier_codes`) between a dry run's
    read and write of the same stamp was undone by that write, which put the forgotten
    codes back (a later return to one of them then restored a time older than the job's
    outputs, and they were not rerun). Where the folder cannot be locked (a file system
    without locks), the update goes on unlocked, as before."""
    directory.mkdir(parents=True, exist_ok=True)
    try:
        handle = os.open(directory, os.O_RDONLY)
    except OSError:
        yield
        return
    try:
        with contextlib.suppress(OSError):
            fcntl.flock(handle, fcntl.LOCK_EX)
        yield
    finally:
        os.close(handle)  # releases the lock


def _refresh_stamp(source: Path, status: os.stat_result, seen: str, stamp: Path) -> None:
    """:func:`_refresh_stamp_locked` under the lock of the stamp's folder (:func:`_locked`)."""
    with _locked(stamp.parent):
        _refresh_stamp_locked(source, status, seen, stamp)


def _refresh_stamp_locked(source: Path, status: os.stat_result, seen: str, stamp: Path) -> None:
    """Bring ``stamp`` up to date with ``source`` (its ``status``, and ``seen``: its
    modification time and size). The stamp holds the source's fingerprint and ``seen``,
    which spare the parse while the file is untouched. Its own modification time is

    - the source's when the stamp is new (a build from before the stamps reruns only what
      the sources' times would rerun);
    - kept when the fingerprint is unchanged;
    - when the fingerprint changed, the time it had when it last held the new code, if no
      build has started since (the stamp remembers the codes it held since then,
      :func:`forget_earlier_codes`): an edit looked at with a dry run, or a branch checked
      out and back, then reverted reruns nothing, since no output was made from the edited
      code;
    - now otherwise (also for a source that an older version replaced with its own, older
      time)."""
    fingerprint, recorded = _read_record(stamp)
    if recorded == seen:
        return
    new = remembered_fingerprint(source)
    earlier = _earlier(stamp) if fingerprint is not None else {}
    if fingerprint is None:
        times = (status.st_atime_ns, status.st_mtime_ns)
    elif new == fingerprint:
        old = stamp.stat()
        times = (old.st_atime_ns, old.st_mtime_ns)
    else:
        earlier[fingerprint] = stamp.stat().st_mtime_ns
        back = earlier.pop(new, None)
        now = time.time_ns()
        times = (now, now) if back is None else (now, back)
    # atomic: jobs that parse the workflow at once agree
    _write_atomically(stamp, _stamp_text(new, seen, earlier), times)


def refresh_stamps(stamps, root: str | Path) -> None:
    """Bring the code stamps ``stamps`` (a job's inputs under :data:`STAMPS`, relative to
    the working directory) up to date with their sources under ``root`` (the workflow's
    directory; ``external/...`` stamps name their source by its absolute path). A job
    calls it as it starts: a source edited since the build parsed the workflow is one the
    job runs, so its stamp must say so before :func:`forget_earlier_codes`, or a later
    return to the earlier code would restore a time older than the job's outputs."""
    root = Path(root)
    for stamp in map(Path, stamps):
        try:
            name = stamp.relative_to(STAMPS).as_posix()
        except ValueError:
            continue
        if not name.endswith(".stamp"):
            continue
        name = name.removesuffix(".stamp")
        external = name.startswith("external/")
        source = Path(name.removeprefix("external")) if external else root / name
        with contextlib.suppress(OSError):
            status = source.stat()
            _refresh_stamp(source, status, _seen(status), stamp)


def forget_earlier_codes(directory: str | Path) -> int:
    """Drop the earlier codes of every stamp under ``directory`` (keeping its time): a
    build starts (Snakemake's ``onstart``), and what it makes may come from the codes the
    sources hold now, so a later return to an earlier code must rerun them. Returns the
    number of stamps changed."""
    changed = 0
    for stamp in sorted(Path(directory).rglob("*.stamp")):
        if not _earlier(stamp):  # unlocked: most stamps have none, and they are not locked
            continue
        with _locked(stamp.parent):  # read again under the lock: a refresh may have run
            fingerprint, seen = _read_record(stamp)
            if fingerprint is None or not _earlier(stamp):
                continue
            with contextlib.suppress(OSError):  # another process replaced it meanwhile
                old = stamp.stat()
                _write_atomically(
                    stamp,
                    _stamp_text(fingerprint, seen, {}),
                    (old.st_atime_ns, old.st_mtime_ns),
                )
                changed += 1
    return changed


_STAMPED: dict[Path, str] = {}
"""{stamp: the source's (modification time, size)} of the stamps this process brought up
to date: every rule of the workflow names some of the same files."""


def code_stamps(paths, root: str | Path, directory: str | Path) -> list[str]:
    """The stamp of each file of ``paths``, brought up to date: the code inputs of the
    workflow's rules. A file under ``root`` (the workflow's directory) has its stamp at the
    same relative path under ``directory``; another (an installed package) under
    ``directory``/external by its absolute path."""
    root, directory = Path(root).resolve(), Path(directory)
    stamps = []
    for path in paths:
        source = Path(path).resolve()
        try:
            name = source.relative_to(root).as_posix()
        except ValueError:
            name = "external" + source.as_posix()
        stamp = directory / f"{name}.stamp"
        status = source.stat()
        seen = _seen(status)
        if _STAMPED.get(stamp) != seen or not stamp.is_file():
            _refresh_stamp(source, status, seen, stamp)
            _STAMPED[stamp] = seen
        stamps.append(str(stamp))
    return stamps
