"""Config validation with messages that name the key, the value and the allowed range.

The workflow validates ``config`` against ``workflow/schemas/config.schema.yaml`` before
any job starts, filling the schema's defaults in place as ``snakemake.utils.validate``
does; ``validate_config`` rewrites jsonschema's error into one sentence, e.g.::

    config key visco2008.md.n_particles = -5 is not allowed: must be >= 2
    (number of disks in the periodic box)
"""

from __future__ import annotations

import copy
import math
import os
from collections.abc import Mapping, MutableMapping
from pathlib import Path, PurePosixPath
from typing import Any

import jsonschema
import yaml

__all__ = [
    "ROOT_MARKER",
    "SCHEMA",
    "ConfigError",
    "claim_root",
    "explain",
    "load_config_file",
    "load_configs",
    "main",
    "results_root",
    "root_files",
    "validate_config",
]

SCHEMA = Path(__file__).resolve().parents[2] / "workflow" / "schemas" / "config.schema.yaml"
"""The workflow's top-level schema (in a source checkout)."""

_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
"""libyaml's loader where available: the schemas are read at every workflow parse."""


class ConfigError(ValueError):
    """A config value that the schema rejects."""


def _allowed(schema: dict[str, Any]) -> str:
    """Describe the allowed values of one (sub)schema in words."""
    parts = []
    if "enum" in schema:
        parts.append("one of " + ", ".join(repr(v) for v in schema["enum"]))
    if "type" in schema:
        kinds = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
        parts.append(" or ".join(kinds))
    bounds = {
        "minimum": ">=",
        "exclusiveMinimum": ">",
        "maximum": "<=",
        "exclusiveMaximum": "<",
    }
    parts += [f"{symbol} {schema[key]}" for key, symbol in bounds.items() if key in schema]
    if "minItems" in schema:
        parts.append(f"at least {schema['minItems']} item(s)")
    if "pattern" in schema:
        parts.append(f"matching {schema['pattern']}")
    return ", ".join(parts)


def explain(error: jsonschema.ValidationError) -> str:
    """One-sentence description of a jsonschema validation error."""
    # the most specific error of an anyOf/oneOf is the most useful one
    if error.context:
        error = max(error.context, key=lambda e: len(e.absolute_path))
    path = ".".join(str(part) for part in error.absolute_path) or "<top level>"
    schema = error.schema if isinstance(error.schema, dict) else {}
    if error.validator == "additionalProperties":
        return f"config section {path}: {error.message} (check the spelling of the key)"
    if error.validator == "required":
        return f"config section {path}: {error.message}"
    allowed = _allowed(schema)
    description = schema.get("description", "")
    sentence = f"config key {path} = {error.instance!r} is not allowed: {error.message}"
    if allowed:
        sentence += f"; allowed: {allowed}"
    if description:
        sentence += f" ({description.strip()})"
    return sentence


def compose_schema(path: str | os.PathLike) -> dict[str, Any]:
    """Load a schema and inline every ``$ref``, recursively.

    Each section's schema lives in its own file. jsonschema validates a referenced file
    with a fresh validator of that file's dialect, which would skip the default-filling
    extension of ``snakemake.utils.validate``; inlining keeps one validator throughout.
    A reference to a sibling file (``md.schema.yaml``) is replaced by that file's
    schema; a reference inside a file (``#/$defs/count``) by the node it points to in
    that same file, so it still resolves once the file is inlined elsewhere.
    Recursive definitions are not supported (none of the schemas needs one).
    """
    path = Path(path).resolve()
    document = yaml.load(path.read_text(), Loader=_LOADER)

    def pointer(reference: str) -> Any:
        node: Any = document
        for part in reference.removeprefix("#").strip("/").split("/"):
            if not part:
                continue
            part = part.replace("~1", "/").replace("~0", "~")
            node = node[int(part)] if isinstance(node, list) else node[part]
        return node

    def inline(node: Any, depth: int = 0) -> Any:
        if depth > 50:
            raise ValueError(f"{path}: $ref nesting deeper than 50 (a recursive definition?)")
        if isinstance(node, dict):
            reference = node.get("$ref")
            node = {key: inline(value, depth) for key, value in node.items() if key != "$ref"}
            if isinstance(reference, str):
                if reference.startswith("#"):
                    target = inline(pointer(reference), depth + 1)
                else:
                    target = compose_schema(path.parent / reference)
                    target.pop("$schema", None)
                node = {**target, **node}
            return node
        if isinstance(node, list):
            return [inline(item, depth) for item in node]
        return node

    return inline(document)


def _strict_numbers(value: Any, schema: Any, path: str) -> None:
    """Refuse what JSON Schema lets through: NaN and infinities pass every numeric bound
    (comparisons with NaN are false), and 7.0 counts as an integer."""
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ConfigError(
                f"config key {path} = {value!r} is not allowed: must be a finite number"
            )
        kinds = schema.get("type") if isinstance(schema, dict) else None
        kinds = kinds if isinstance(kinds, list) else [kinds]
        if "integer" in kinds and "number" not in kinds:
            raise ConfigError(
                f"config key {path} = {value!r} is not allowed: must be an integer "
                "(written without a decimal point)"
            )
        return
    schema = schema if isinstance(schema, dict) else {}
    if isinstance(value, dict):
        properties = schema.get("properties", {})
        extra = schema.get("additionalProperties")
        for key, item in value.items():
            child = properties.get(key, extra if isinstance(extra, dict) else {})
            _strict_numbers(item, child, f"{path}.{key}" if path else str(key))
    elif isinstance(value, list):
        items = schema.get("items", {})
        for index, item in enumerate(value):
            _strict_numbers(item, items, f"{path}[{index}]")


def validate_config(config: MutableMapping[str, Any], schema: str | os.PathLike = SCHEMA) -> None:
    """Validate ``config`` in place (filling defaults) or raise ``ConfigError``.

    Beyond the schema: no NaN or infinite number anywhere, and no float (7.0) where the
    schema asks for an integer, each refused with its key."""
    composed_schema = compose_schema(schema)
    _strict_numbers(config, composed_schema, "")
    try:
        _DefaultFillingValidator(composed_schema).validate(config)
    except jsonschema.ValidationError as error:
        raise ConfigError(explain(error)) from None


def _fill_defaults(validator, properties, instance, schema):
    """The 'properties' keyword, which first sets every missing key that has a default
    (the schema is fully inlined, so one validator sees every level)."""
    if isinstance(instance, dict):
        for name, subschema in properties.items():
            if isinstance(subschema, dict) and "default" in subschema:
                instance.setdefault(name, copy.deepcopy(subschema["default"]))
    yield from jsonschema.Draft202012Validator.VALIDATORS["properties"](
        validator, properties, instance, schema
    )


_DefaultFillingValidator = jsonschema.validators.extend(
    jsonschema.Draft202012Validator, {"properties": _fill_defaults}
)
"""Draft 2020-12 validation that fills defaults, as ``snakemake.utils.validate`` does,
without its round trip through a schema file (the parse of every dry run pays it)."""


ROOT_MARKER = ".kinetic-results"
"""File that marks a directory as one config's results root (written at the start of a
build, holding the config: :func:`claim_root`): tools that walk a root
(``kinetic.io.remove_orphans``, ``kinetic.compare``) leave out the roots of other configs
nested in it (``results/ci`` inside ``results``)."""


def _leaves(value: Any, prefix: str = "") -> dict[str, Any]:
    """{dotted key: value} of every leaf of a nested mapping."""
    if not isinstance(value, Mapping):
        return {prefix: value}
    found: dict[str, Any] = {}
    for key, item in value.items():
        found |= _leaves(item, f"{prefix}.{key}" if prefix else str(key))
    return found


def claim_root(root: str | os.PathLike, config: Mapping[str, Any]) -> list[str]:
    """Mark ``root`` as this config's results root (:data:`ROOT_MARKER`, which holds the
    config as JSON) and return the settings in which the config that built there last
    differs from this one: ``key: its value -> this one``, ``targets`` left out (it
    chooses what is built, not how). Empty for a new root, an old empty marker or the same
    settings. A config of its own writes under a root of its own; the same root with other
    settings rebuilds, there, the jobs those settings change, replacing their files."""
    import json

    marker = Path(root, ROOT_MARKER)
    mine = {key: value for key, value in config.items() if key != "targets"}
    text = json.dumps(mine, sort_keys=True, default=str)
    try:
        before = json.loads(marker.read_text() or "null")
    except (OSError, ValueError):
        before = None
    changes = []
    if isinstance(before, Mapping):
        old, new = _leaves(before), _leaves(json.loads(text))
        for key in sorted(set(old) | set(new)):
            if old.get(key) != new.get(key):
                changes.append(f"{key}: {old.get(key)!r} -> {new.get(key)!r}")
    from kinetic import io  # at a build's start only: xarray is not loaded to parse

    io.write_text(marker, text + "\n")  # atomic: a reader sees the old marker or the new
    return changes


def results_root(config: Mapping[str, Any]) -> str:
    """The directory this config builds under (key ``results``, default ``results``),
    normalised: ``results/ci/`` is ``results/ci``."""
    return PurePosixPath(config.get("results", "results")).as_posix()


def root_files(directory: str | os.PathLike, pattern: str = "*") -> list[Path]:
    """The files under results root ``directory`` whose name matches ``pattern``, leaving
    out the roots of other configs nested in it (those holding a :data:`ROOT_MARKER`)."""
    import fnmatch

    found = []
    for folder, subfolders, files in os.walk(directory):
        subfolders[:] = sorted(
            name for name in subfolders if not Path(folder, name, ROOT_MARKER).exists()
        )
        found += [Path(folder, name) for name in sorted(fnmatch.filter(files, pattern))]
    return found


def load_config_file(path: str | os.PathLike) -> dict[str, Any]:
    """Read one YAML config file; a syntax error names the file, line and column."""
    path = Path(path)
    try:
        loaded = yaml.safe_load(path.read_text())
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        where = f"{path}:{mark.line + 1}:{mark.column + 1}" if mark else str(path)
        problem = getattr(error, "problem", None) or str(error)
        raise ConfigError(f"{where}: not valid YAML ({problem})") from None
    if not isinstance(loaded, dict):
        raise ConfigError(f"{path}: a config file must hold a mapping of keys, got {loaded!r}")
    return loaded


def load_configs(paths) -> dict[str, Any]:
    """Config files merged in order as Snakemake's ``--configfile`` merges them (later files
    update earlier ones key by key), validated with the defaults filled in."""
    config: dict[str, Any] = {}
    for path in paths:
        _merge(config, load_config_file(path))
    validate_config(config)
    return config


def _merge(base: dict[str, Any], update: Mapping[str, Any]) -> None:
    for key, value in update.items():
        if isinstance(value, Mapping) and isinstance(base.get(key), dict):
            _merge(base[key], value)
        else:
            base[key] = value


def main(argv: list[str] | None = None) -> int:
    """``python -m kinetic.config FILE...``: check a config before a build (syntax with file
    and line, then the schema). Several files are merged in order, as Snakemake's
    ``--configfile A B`` merges them, so that a layer such as ``paper-gpu.yaml`` is checked
    over its base; prints one line, exits 1 on a bad config (2 on bad usage)."""
    import argparse

    parser = argparse.ArgumentParser(
        prog="python -m kinetic.config",
        description="Check a workflow config before a build: YAML syntax (file, line and "
        "column), then the schema, with the key, value and allowed range.",
    )
    parser.add_argument(
        "files",
        nargs="+",
        metavar="FILE",
        help="config file(s), merged in order as snakemake's --configfile merges them",
    )
    paths = parser.parse_args(argv).files
    name = " + ".join(str(path) for path in paths)
    try:
        load_configs(paths)
    except ConfigError as error:
        text = str(error)
        print(text if any(text.startswith(str(path)) for path in paths) else f"{name}: {text}")
        return 1
    print(f"{name}: valid")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
