"""The montanero2007 part of the workflow: targets build only their runs; bad configs stop early."""

import os
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

REPOSITORY = Path(__file__).resolve().parents[2]
SNAKEMAKE = [sys.executable, "-m", "snakemake", "--snakefile", str(REPOSITORY / "Snakefile")]


def _snakemake(workdir, *args):
    env = {**os.environ, "MPLBACKEND": "Agg"}
    return subprocess.run(
        [*SNAKEMAKE, "--directory", str(workdir), *args],
        capture_output=True,
        text=True,
        timeout=600,
        env=env,
        check=False,
    )


def _ci_config(tmp_path, change=None):
    config = yaml.safe_load((REPOSITORY / "config" / "ci.yaml").read_text())
    if change:
        change(config["montanero2007"])
    path = tmp_path / "config.yaml"
    path.write_text(yaml.safe_dump(config))
    return path


@pytest.mark.workflow
def test_fig05_plans_only_its_two_runs(tmp_path):
    result = _snakemake(
        tmp_path,
        "results/ci/montanero2007/fig05.pdf",
        "--configfile",
        str(_ci_config(tmp_path)),
        "--dry-run",
    )
    assert result.returncode == 0, result.stderr
    plan = result.stdout + result.stderr
    assert "montanero2007_fig05" in plan
    assert "runs/alpha100/batch0000.nc" in plan and "runs/alpha090/batch0000.nc" in plan
    for unrelated in ("runs/alpha030/", "runs/hcs_", "runs/error_", "montanero2007_fig03"):
        assert unrelated not in plan


@pytest.mark.workflow
def test_bad_montanero2007_values_stop_before_any_job(tmp_path):
    def negative_step(section):
        section["protocol"]["time_step"] = -0.01

    result = _snakemake(
        tmp_path, "--configfile", str(_ci_config(tmp_path, negative_step)), "--cores", "1"
    )
    assert result.returncode != 0
    assert "montanero2007.protocol.time_step = -0.01" in result.stdout + result.stderr
    assert not (tmp_path / "results").exists()


@pytest.mark.workflow
def test_figure_alpha_outside_the_scan_is_named(tmp_path):
    def stray_alpha(section):
        section["figures"]["fig06_alphas"] = [0.7, 0.45]

    result = _snakemake(
        tmp_path,
        "--configfile",
        str(_ci_config(tmp_path, stray_alpha)),
        "--cores",
        "1",
        "--dry-run",
    )
    assert result.returncode != 0
    assert "montanero2007.figures.fig06_alphas" in result.stdout + result.stderr
