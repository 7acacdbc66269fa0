"""What a user needs to install, reuse and cite the project: the declared dependencies are
the pinned ones, the licence is there, and CITATION.cff is valid Citation File Format."""

import json
import re
import tomllib
from pathlib import Path

import jsonschema
import yaml

REPOSITORY = Path(__file__).resolve().parents[2]


def _name(requirement: str) -> str:
    """A distribution's normalised name (PEP 503) from a requirement line."""
    return re.sub(r"[-_.]+", "-", re.split(r"[<>=!~ ;\[]", requirement.strip())[0]).lower()


def test_pyproject_declares_exactly_the_pinned_packages():
    project = tomllib.loads((REPOSITORY / "pyproject.toml").read_text())["project"]
    declared = [*project["dependencies"]]
    for group in project["optional-dependencies"].values():
        declared += group
    lines = (REPOSITORY / "environment-pip.txt").read_text().splitlines()
    pinned = [line for line in lines if line.strip() and not line.startswith("#")]
    assert all("==" in line for line in pinned), "every direct dependency is pinned exactly"
    assert sorted(map(_name, declared)) == sorted(map(_name, pinned))


def test_every_runtime_dependency_is_imported_by_the_package():
    """A runtime dependency nothing imports (tqdm was one) is dead weight."""
    project = tomllib.loads((REPOSITORY / "pyproject.toml").read_text())["project"]
    modules = {"pyyaml": "yaml", "netcdf4": "netCDF4"}
    sources = "\n".join(path.read_text() for path in (REPOSITORY / "src").rglob("*.py"))
    for requirement in project["dependencies"]:
        module = modules.get(_name(requirement), _name(requirement))
        if module == "netCDF4":  # xarray's engine="netcdf4" loads it
            assert 'engine="netcdf4"' in sources
            continue
        assert re.search(rf"^\s*(import|from) {module}\b", sources, re.MULTILINE), module


def test_license_and_citation():
    assert "BSD 3-Clause License" in (REPOSITORY / "LICENSE").read_text()
    # the Citation File Format 1.2.0 schema, as cffconvert ships it (cffconvert itself
    # requires jsonschema < 4, which the workflow's pins exclude)
    schema = json.loads(
        (REPOSITORY / "tests/data/citation-file-format-1.2.0.schema.json").read_text()
    )
    citation = yaml.safe_load((REPOSITORY / "CITATION.cff").read_text())
    validator = jsonschema.Draft7Validator(
        schema, format_checker=jsonschema.Draft7Validator.FORMAT_CHECKER
    )
    assert not list(validator.iter_errors(citation))
    titles = " ".join(reference["title"] for reference in citation["references"])
    for words in ("hard-sphere gas", "Chapman–Enskog", "Newtonian to Boltzmann", "Monte Carlo"):
        assert words in titles  # the four reproduced documents
