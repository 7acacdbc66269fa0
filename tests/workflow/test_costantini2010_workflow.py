"""The costantini2010 part of the workflow: a figure plans only its runs; a box at or
beyond the shear instability, or a sample interval the DSMC steps do not divide, stops
before any job."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

REPOSITORY = Path(__file__).resolve().parents[2]
SNAKEMAKE = [sys.executable, "-m", "snakemake", "--snakefile", str(REPOSITORY / "Snakefile")]


def _snakemake(workdir, config_path, *args):
    # targets before --configfile: after it they would be read as more config files
    return subprocess.run(
        [*SNAKEMAKE, "--directory", str(workdir), *args, "--configfile", str(config_path)],
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "MPLBACKEND": "Agg"},
        check=False,
    )


def _ci_config(tmp_path, **changes):
    config = yaml.safe_load((REPOSITORY / "config" / "ci.yaml").read_text())
    config["costantini2010"].update(changes)
    path = tmp_path / "config.yaml"
    path.write_text(yaml.safe_dump(config))
    return path


@pytest.mark.workflow
def test_convergence_figure_plans_only_elastic_dsmc_runs(tmp_path):
    result = _snakemake(
        tmp_path, _ci_config(tmp_path), "results/ci/costantini2010/convergence.pdf", "--dry-run"
    )
    plan = result.stdout + result.stderr
    assert result.returncode == 0, plan
    rules = set(re.findall(r"^rule (\w+):", plan, re.MULTILINE))
    outputs = re.findall(r"^\s+output: (.+)$", plan, re.MULTILINE)
    assert "costantini2010_simulate_dsmc" in rules and outputs
    assert not rules & {"costantini2010_simulate_md", "costantini2010_fig01"}, rules
    assert all(rule.startswith("costantini2010_") for rule in rules)
    assert not any("alpha0.7" in output for output in outputs)  # elastic runs only


@pytest.mark.workflow
@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"density": 0.01, "particles": [3000], "restitutions": [0.5]}, "shear-unstable"),
        ({"sample_interval": 0.07}, "whole multiple"),
        ({"fit_start": 10, "max_lag": 3}, "fit_start = 10 l/v_s starts the tail fit"),
    ],
)
def test_impossible_costantini2010_configs_stop_before_any_job(tmp_path, changes, message):
    result = _snakemake(tmp_path, _ci_config(tmp_path, **changes), "--cores", "1")
    assert result.returncode != 0
    assert message in result.stdout + result.stderr
    assert not (tmp_path / "results").exists()
