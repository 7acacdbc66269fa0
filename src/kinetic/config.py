"""Config validation with messages that name the key, the value and the allowed range.

The workflow validates ``config`` against ``workflow/schemas/config.schema.yaml`` with
``snakemake.utils.validate`` (which also fills the schema's defaults in place) before
any job starts; ``validate_config`` wraps it and rewrites jsonschema's error into one
sentence, e.g.::

    config key visco2008.md.n_particles = -5 is not allowed: must be >= 2
    (number of disks in the periodic box)
"""

from __future__ import annotations

import os
from collections.abc import MutableMapping
from pathlib import Path
from typing import Any

import jsonschema

__all__ = ["SCHEMA", "ConfigError", "explain", "validate_config"]

SCHEMA = Path(__file__).resolve().parents[2] / "workflow" / "schemas" / "config.schema.yaml"
"""The workflow's top-level schema (in a source checkout)."""


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


def validate_config(config: MutableMapping[str, Any], schema: str | os.PathLike = SCHEMA) -> None:
    """Validate ``config`` in place (filling defaults) or raise ``ConfigError``."""
    from snakemake.exceptions import WorkflowError
    from snakemake.utils import validate

    try:
        validate(config, str(Path(schema).resolve()))
    except WorkflowError as workflow_error:
        causes = [a for a in workflow_error.args if isinstance(a, jsonschema.ValidationError)]
        if not causes:
            raise
        raise ConfigError(explain(causes[0])) from None
