"""Engine packages that load their public names on first use (``kinetic.edmd``,
``kinetic.dsmc``, ``kinetic.cloning``)."""

from __future__ import annotations

import importlib

__all__ = ["lazy_exports"]


def lazy_exports(package: str, exports: dict[str, str], namespace: dict):
    """``(__getattr__, __dir__)`` of an engine package that loads its public names on first
    use: ``exports`` maps each name to the submodule that defines it, and any other name
    is tried as a submodule (``kinetic.dsmc.kernels`` after a bare ``import
    kinetic.dsmc``); ``namespace`` (the package's ``globals()``) keeps what was loaded.
    Importing the package's numpy-only ``arguments`` module thus loads neither numba nor
    the kernels (the workflow's parse runs those checks)."""

    def __getattr__(name: str):
        if name in exports:
            value = getattr(importlib.import_module(f"{package}.{exports[name]}"), name)
        else:
            try:
                value = importlib.import_module(f"{package}.{name}")
            except ModuleNotFoundError:
                raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
        namespace[name] = value
        return value

    def __dir__():
        return sorted(set(namespace) | set(exports))

    return __getattr__, __dir__
