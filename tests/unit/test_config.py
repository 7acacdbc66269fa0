"""Config validation: bad values are refused before any job, with the key, value and range."""

import copy
from pathlib import Path

import pytest
import yaml

from kinetic.config import ConfigError, validate_config

REPOSITORY = Path(__file__).resolve().parents[2]
SCHEMA = REPOSITORY / "workflow" / "schemas" / "config.schema.yaml"


def _load(name="config.yaml"):
    return yaml.safe_load((REPOSITORY / "config" / name).read_text())


@pytest.mark.parametrize("name", ["config.yaml", "ci.yaml", "paper.yaml"])
def test_shipped_configs_are_valid(name):
    validate_config(_load(name), SCHEMA)


@pytest.mark.parametrize("name", ["config.yaml", "ci.yaml", "paper.yaml"])
def test_checks_that_stop_a_build_are_at_four_sigma(name):
    """A document in fail_on_checks stops a correct build when one of its checks fails by
    chance: at 3 sigma (0.27 % a check) visco2008's 61 checks stop one build in 7, at 4
    (6.3e-5) one in 260. Every document's config names its band."""
    config = _load(name)
    validate_config(config, SCHEMA)
    for document in ("visco2008", "montanero2007", "krauth2025", "costantini2010"):
        assert "sigmas" in _load(name)[document]["checks"], document
    for document in config["fail_on_checks"]:
        assert config[document]["checks"]["sigmas"] >= 4, document


def test_defaults_are_filled_in():
    config = {"seed": 3}
    validate_config(config, SCHEMA)
    assert config["targets"] == "all"
    assert config["visco2008"]["theory"]["rate_points"] == 141


def _set(config, dotted, value):
    keys = dotted.split(".")
    node = config
    for key in keys[:-1]:
        node = node.setdefault(key, {})
    node[keys[-1]] = value


# (key, bad value, fragments the message must contain)
BAD_VALUES = [
    ("seed", 1.5, ["seed", "1.5", "integer"]),
    ("seed", "abc", ["seed", "'abc'", "integer"]),
    ("seed", -4, ["seed", "-4", ">= 0"]),
    ("visco2008.theory.rate_points", 0, ["visco2008.theory.rate_points", "0", ">= 11"]),
    ("visco2008.theory.rate_points", -5, ["visco2008.theory.rate_points", "-5", ">= 11"]),
    ("visco2008.theory.time_max", 0.0, ["visco2008.theory.time_max", "0.0", "> 0"]),
    ("targets", ["visco2008/Fig 3"], ["targets.0", "visco2008/Fig 3", "matching"]),
    # NaN and infinities pass every JSON Schema bound: refused beforehand, key named
    ("visco2008.theory.time_max", float("nan"), ["visco2008.theory.time_max", "nan", "finite"]),
    ("visco2008.md.densities.rho1e-3", float("nan"), ["visco2008.md.densities.rho1e-3", "finite"]),
    ("montanero2007.alphas", [1.0, float("nan")], ["montanero2007.alphas[1]", "finite"]),
    ("costantini2010.density", float("inf"), ["costantini2010.density", "inf", "finite"]),
    ("costantini2010.restitutions", [float("nan")], ["costantini2010.restitutions[0]"]),
    ("krauth2025.pins.sigma", float("-inf"), ["krauth2025.pins.sigma", "finite"]),
    ("visco2008.cloning.transient", float("nan"), ["visco2008.cloning.transient", "finite"]),
    # 7.0 counts as an integer for JSON Schema, not for us
    ("seed", 7.0, ["seed", "7.0", "integer", "decimal point"]),
    ("costantini2010.realizations", 4.0, ["costantini2010.realizations", "integer"]),
    ("costantini2010.particles", [1000.0], ["costantini2010.particles[0]", "integer"]),
]


@pytest.mark.parametrize(("key", "value", "fragments"), BAD_VALUES, ids=[c[0] for c in BAD_VALUES])
def test_bad_values_are_refused_with_key_value_and_range(key, value, fragments):
    config = copy.deepcopy(_load())
    _set(config, key, value)
    with pytest.raises(ConfigError) as error:
        validate_config(config, SCHEMA)
    message = str(error.value)
    for fragment in fragments:
        assert fragment in message, message


def test_misspelt_key_is_refused():
    config = copy.deepcopy(_load())
    config["visco2008"]["theory"]["rate_pionts"] = 10
    with pytest.raises(ConfigError, match="rate_pionts"):
        validate_config(config, SCHEMA)


def test_references_inside_a_section_file_survive_inlining(tmp_path):
    """A section file's own ``#/$defs/...`` references resolve against that file."""
    (tmp_path / "section.schema.yaml").write_text(
        yaml.safe_dump(
            {
                "$defs": {"count": {"type": "integer", "minimum": 1, "default": 7}},
                "type": "object",
                "default": {},
                "properties": {"n": {"$ref": "#/$defs/count"}},
            }
        )
    )
    (tmp_path / "root.schema.yaml").write_text(
        yaml.safe_dump(
            {
                "$schema": "https://json-schema.org/draft/2020-12/schema",
                "type": "object",
                "properties": {"section": {"$ref": "section.schema.yaml", "default": {}}},
            }
        )
    )
    config = {}
    validate_config(config, tmp_path / "root.schema.yaml")
    assert config == {"section": {"n": 7}}
    with pytest.raises(ConfigError, match=r"section\.n"):
        validate_config({"section": {"n": 0}}, tmp_path / "root.schema.yaml")


def test_the_command_checks_a_layer_over_its_base(capsys, tmp_path):
    """``python -m kinetic.config`` merges its files as ``--configfile`` does: the GPU layer
    alone lacks the base's keys, over paper.yaml it is valid; a syntax error names its
    file and line."""
    from kinetic.config import main

    layer, base = REPOSITORY / "config" / "paper-gpu.yaml", REPOSITORY / "config" / "paper.yaml"
    assert main([str(layer)]) == 1
    assert "'seed' is a required property" in capsys.readouterr().out
    assert main([str(base), str(layer)]) == 0
    assert capsys.readouterr().out.strip().endswith("paper-gpu.yaml: valid")
    broken = tmp_path / "broken.yaml"
    broken.write_text("seed: 1\nvisco2008: [\n")
    assert main([str(base), str(broken)]) == 1
    assert str(broken) in capsys.readouterr().out
    with pytest.raises(SystemExit) as usage:  # --help is help, not a missing file
        main(["--help"])
    assert usage.value.code == 0
    assert "merged in order" in capsys.readouterr().out


def test_a_root_remembers_the_config_that_built_there_last(tmp_path):
    """The marker holds the config; a build under the same root with other settings is
    told which, so that a copied config that kept the root is noticed (targets aside)."""
    from kinetic.config import ROOT_MARKER, claim_root

    root = tmp_path / "results" / "ci"
    first = {"seed": 1, "results": "results/ci", "targets": "all", "krauth2025": {"n": 3}}
    assert claim_root(root, first) == []  # a new root
    assert (root / ROOT_MARKER).is_file()
    assert claim_root(root, first | {"targets": ["krauth2025/fig04_13"]}) == []
    changed = first | {"krauth2025": {"n": 4}, "backend": "cuda"}
    assert claim_root(root, changed) == ["backend: None -> 'cuda'", "krauth2025.n: 3 -> 4"]
    assert claim_root(root, changed) == []  # the marker now holds the new settings
    (root / ROOT_MARKER).write_text("")  # a marker of an older version: empty
    assert claim_root(root, first) == []
