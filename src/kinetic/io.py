"""Datasets, netCDF files and tables: the only module that knows file formats.

Conventions every dataset of the project follows (checked by ``check_conventions``):

- every data variable and coordinate has the attributes ``units`` and ``long_name``;
- every dimension has a coordinate;
- the global attributes hold the run's ``parameters`` (one attribute each, plus the
  whole set as JSON in ``parameters_json``), its ``seed``, the ``config`` it was made
  from (JSON: the shared keys and its document's section,
  ``workflow_support.output_config``), the package ``kinetic_version`` and the
  ``git_revision`` of the source tree that wrote the file; a file made from simulated
  files (an aggregate of a run's batches, a run read and written again) also names, in
  ``source_git_revisions``, the revisions that
  simulated its numbers (space-separated, sorted; several where batches of one run were
  simulated by different revisions);
- netCDF attributes hold only strings, numbers and numeric arrays: booleans become
  ints, ``None`` becomes an empty string, anything else nested becomes JSON.

Files (datasets and tables) are written to a hidden temporary name, flushed to disk and
renamed, so a file under its final name is always complete: an interrupted job leaves no
truncated result behind, and the temporary files of killed writers are removed at the
start of the next build (``remove_orphans``). A file that cannot be read is reported by
name with the advice to delete it (``CorruptFileError``).
"""

from __future__ import annotations

import functools
import json
import os
import subprocess
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from kinetic import __version__

__all__ = [
    "CorruptFileError",
    "check_conventions",
    "git_revision",
    "make_dataset",
    "read_dataset",
    "read_run",
    "read_table",
    "remove_orphans",
    "stamp",
    "write_dataset",
    "write_table",
    "write_text",
]

Variable = tuple[tuple[str, ...] | str, Any, str, str]
"""``(dims, values, units, long_name)`` of one data variable or coordinate."""


def make_dataset(
    data_vars: Mapping[str, Variable],
    coords: Mapping[str, Variable] | None = None,
    attrs: Mapping[str, Any] | None = None,
) -> xr.Dataset:
    """Build a dataset whose every variable carries ``units`` and ``long_name``.

    Each entry is ``name: (dims, values, units, long_name)``; ``dims`` may be a single
    dimension name or ``()`` for a scalar.
    """

    def to_variable(spec: Variable) -> xr.Variable:
        dims, values, units, long_name = spec
        dims = (dims,) if isinstance(dims, str) else tuple(dims)
        return xr.Variable(dims, np.asarray(values), {"units": units, "long_name": long_name})

    dataset = xr.Dataset(
        {name: to_variable(spec) for name, spec in data_vars.items()},
        coords={name: to_variable(spec) for name, spec in (coords or {}).items()},
        attrs=dict(attrs or {}),
    )
    check_conventions(dataset)
    return dataset


def check_conventions(dataset: xr.Dataset) -> None:
    """Raise ``ValueError`` naming every variable or dimension that breaks the conventions."""
    problems = []
    for name, variable in dataset.variables.items():
        missing = [key for key in ("units", "long_name") if key not in variable.attrs]
        if missing:
            problems.append(f"variable {name!r} lacks {', '.join(missing)}")
    problems += [
        f"dimension {dim!r} has no coordinate" for dim in dataset.dims if dim not in dataset.coords
    ]
    if problems:
        raise ValueError("dataset breaks the conventions of kinetic.io: " + "; ".join(problems))


@functools.cache
def git_revision() -> str:
    """The git revision of the source tree (``KINETIC_GIT_REVISION`` overrides), or 'unknown'.

    A ``-dirty`` suffix marks uncommitted changes.
    """
    if revision := os.environ.get("KINETIC_GIT_REVISION"):
        return revision
    here = Path(__file__).resolve().parent
    try:
        revision = subprocess.run(
            ["git", "describe", "--always", "--dirty", "--abbrev=12"],
            cwd=here,
            capture_output=True,
            text=True,
            check=True,
            timeout=10,
        ).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return revision or "unknown"


def _attribute_value(value: Any) -> Any:
    """Encode one attribute value into what netCDF accepts."""
    if value is None:
        return ""
    if isinstance(value, bool | np.bool_):
        return int(value)
    if isinstance(value, str | int | float | np.integer | np.floating):
        return value
    if isinstance(value, np.ndarray) and value.dtype.kind in "iuf":
        return value
    if (
        isinstance(value, list | tuple)
        and value
        and all(isinstance(item, int | float) and not isinstance(item, bool) for item in value)
    ):
        return np.asarray(value)
    return json.dumps(value, sort_keys=True, default=str)


def stamp(
    dataset: xr.Dataset,
    *,
    parameters: Mapping[str, Any],
    seed: int | None,
    config: Mapping[str, Any] | None = None,
) -> xr.Dataset:
    """Return ``dataset`` with the provenance attributes set (see the module docstring)."""
    attrs = dict(dataset.attrs)
    for key, value in parameters.items():
        attrs[key] = _attribute_value(value)
    attrs["parameters_json"] = json.dumps(dict(parameters), sort_keys=True, default=str)
    attrs["seed"] = -1 if seed is None else int(seed)
    attrs["config"] = json.dumps(dict(config or {}), sort_keys=True, default=str)
    simulated_by = attrs.get("source_git_revisions") or attrs.get("git_revision")
    if simulated_by:  # written before: keep the revisions that made its numbers
        attrs["source_git_revisions"] = simulated_by
    attrs["kinetic_version"] = __version__
    attrs["git_revision"] = git_revision()
    return dataset.assign_attrs(attrs)


def source_revisions(datasets) -> str:
    """The sorted, space-separated revisions that simulated ``datasets`` (each one's
    ``source_git_revisions``, or its ``git_revision`` where it was written by a simulation
    job); "" where none records one."""
    found = set()
    for dataset in datasets:
        value = dataset.attrs.get("source_git_revisions") or dataset.attrs.get("git_revision")
        found.update(str(value).split() if value else ())
    return " ".join(sorted(found))


def _replace_atomically(path: Path, write) -> Path:
    """Write through ``write(temporary_path)`` to a hidden temporary file beside ``path``,
    flush it to disk, then rename it: a file under its final name is always complete.
    A killed writer leaves a ``.<name>.<pid>.tmp`` that ``remove_orphans`` deletes."""
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(f".{path.name}.{os.getpid()}{TEMPORARY_SUFFIX}")
    try:
        write(temporary)
        with open(temporary, "rb+") as handle:
            os.fsync(handle.fileno())
        os.replace(temporary, path)
    finally:
        temporary.unlink(missing_ok=True)
    return path


TEMPORARY_SUFFIX = ".tmp"
"""Suffix of the hidden files written before the rename (``.<name>.<pid>.tmp``)."""


def _writer_alive(temporary: Path) -> bool:
    """Whether the process named in ``temporary`` (``.<name>.<pid>.tmp``) runs on this
    machine: a second build of the same results root with other targets (Snakemake locks
    files, not roots) writes there while the first starts. A writer on another machine of
    a cluster is not seen: run one build per results root there."""
    pid = temporary.name[: -len(TEMPORARY_SUFFIX)].rpartition(".")[2]
    if not pid.isdigit() or int(pid) == os.getpid():
        return False
    try:
        os.kill(int(pid), 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    except OSError:
        return False
    return True


def remove_orphans(directory: str | os.PathLike) -> list[Path]:
    """Delete the temporary files that killed writers left under ``directory`` (call it
    at the start of a build); returns them. A file whose writer still runs on this machine
    (:func:`_writer_alive`) is no orphan and stays.
    The results roots of other configs nested in it (``kinetic.config.ROOT_MARKER``) are
    left alone: another build may be writing there."""
    from kinetic.config import root_files

    orphans = [
        path
        for path in root_files(directory, f".*{TEMPORARY_SUFFIX}")
        if path.name.count(".") >= 3 and not _writer_alive(path)
    ]
    for path in orphans:
        path.unlink(missing_ok=True)
    return orphans


def write_dataset(dataset: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``dataset`` to netCDF atomically (temporary file, fsync, rename)."""
    check_conventions(dataset)
    encoded = dataset.assign_attrs({k: _attribute_value(v) for k, v in dataset.attrs.items()})
    return _replace_atomically(
        Path(path), lambda temporary: encoded.to_netcdf(temporary, engine="netcdf4")
    )


class CorruptFileError(OSError):
    """A result file that cannot be read (truncated or corrupted): delete it and rerun."""


def read_dataset(path: str | os.PathLike) -> xr.Dataset:
    """Read a netCDF file written by ``write_dataset`` fully into memory and close it.

    Raises ``CorruptFileError`` naming the file if it cannot be read (truncated,
    corrupted, not netCDF), with the advice to delete it so that the rerun rebuilds it.
    """
    try:
        with xr.open_dataset(path, engine="netcdf4") as dataset:
            return dataset.load()
    except FileNotFoundError:
        raise
    except (OSError, ValueError, RuntimeError) as error:
        raise CorruptFileError(
            f"{path} cannot be read ({error}): it is truncated or corrupted; delete it and "
            "rerun, and Snakemake rebuilds it (and only what depends on it)"
        ) from error


def read_run(paths) -> xr.Dataset:
    """The batch files of one run (every realization once, the same parameters and seed),
    read and joined along ``realization`` (``kinetic.batches.combine``, whose errors name
    the files)."""
    from kinetic import batches

    paths = [str(path) for path in paths]
    return batches.combine([read_dataset(path) for path in paths], names=paths)


def parameters_of(dataset: xr.Dataset) -> dict[str, Any]:
    """The run parameters stored by ``stamp``."""
    return json.loads(dataset.attrs["parameters_json"])


def _markdown(frame: pd.DataFrame, float_format: str) -> str:
    def cell(value: Any) -> str:
        if value is None or (isinstance(value, float) and np.isnan(value)):
            return ""
        if isinstance(value, float | np.floating):
            return format(value, float_format)
        return str(value).replace("|", "\\|")  # a pipe inside a cell would end it

    header = "| " + " | ".join(frame.columns) + " |"
    rule = "| " + " | ".join("---" for _ in frame.columns) + " |"
    rows = ["| " + " | ".join(cell(v) for v in row) + " |" for row in frame.itertuples(False)]
    return "\n".join([header, rule, *rows]) + "\n"


def write_table(
    frame: pd.DataFrame,
    csv_path: str | os.PathLike,
    markdown_path: str | os.PathLike | None = None,
    *,
    float_format: str = ".6g",
    markdown_note: str = "",
) -> None:
    """Write a table as CSV (empty cells for missing values) and optionally a Markdown
    twin (followed by ``markdown_note``, e.g. the table's caption), each atomically
    (temporary file, fsync, rename)."""
    _replace_atomically(
        Path(csv_path),
        lambda temporary: frame.to_csv(temporary, index=False, float_format="%.10g", na_rep=""),
    )
    if markdown_path is not None:
        text = _markdown(frame, float_format) + (f"\n{markdown_note}" if markdown_note else "")
        _replace_atomically(Path(markdown_path), lambda temporary: temporary.write_text(text))


def write_text(path: str | os.PathLike, text: str) -> None:
    """Write a text file atomically (temporary file, fsync, rename)."""
    _replace_atomically(Path(path), lambda temporary: temporary.write_text(text))


def read_table(path: str | os.PathLike) -> pd.DataFrame:
    """Read a CSV written by ``write_table``."""
    return pd.read_csv(path)
