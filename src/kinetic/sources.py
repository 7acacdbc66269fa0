"""The source files a compiled kernel depends on (numpy-free: the workflow reads them while
it parses the Snakefile).

One list serves two consumers that must agree:

- numba's on-disk cache (``kinetic.jit``): a cached kernel is fresh only while none of the
  files it depends on changed. numba itself checks only the file that defines the kernel;
  the helpers an engine inlines live in other files of the engine and in ``kinetic.rng``.
- rule ``warm_numba`` and the simulation rules (``workflow/rules/common.smk``): they rerun
  when these files change, so the kernels are compiled once, before parallel jobs load
  them, whenever the cache went stale.

An engine's kernels depend on the files of its package and on the shared modules below.
Compiled code elsewhere (the benchmarks call into several engines) depends on every file
of ``kinetic``.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["ENGINES", "PACKAGE", "SHARED", "engine_sources", "kernel_sources"]

PACKAGE = Path(__file__).resolve().parent
"""The ``kinetic`` package directory."""

ENGINES = ("cloning", "dsmc", "edmd", "samplers")
"""Subpackages whose compiled kernels call only themselves and the shared modules."""

SHARED = ("rng", "seeds", "jit", "validate", "gas")
"""Top-level modules every engine depends on (``rng`` and ``jit`` hold compiled code)."""


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
