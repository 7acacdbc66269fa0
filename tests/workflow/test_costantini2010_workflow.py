"""The costantini2010 part of the workflow: a figure plans only its runs; a box at or
beyond the shear instability, or a sample interval the DSMC steps do not divide, stops
before any job."""

import re

import pytest
from _snakemake import CI_CONFIG, ci_config, snakemake


@pytest.mark.workflow
def test_convergence_figure_plans_only_elastic_dsmc_runs(tmp_path):
    result = snakemake(
        tmp_path,
        "results/ci/costantini2010/convergence.pdf",
        "--dry-run",
        "--configfile",
        CI_CONFIG,
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
    config = ci_config(tmp_path, lambda config: config["costantini2010"].update(changes))
    result = snakemake(tmp_path, "--cores", "1", "--configfile", config)
    assert result.returncode != 0
    assert message in result.stdout + result.stderr
    assert not (tmp_path / "results").exists()
