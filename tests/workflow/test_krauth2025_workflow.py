"""The krauth2025 part of the workflow: a figure plans only its samples; configs that no
line or ring can satisfy stop before any job."""

import os
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


def _ci_config(tmp_path, section=None, **changes):
    config = yaml.safe_load((REPOSITORY / "config" / "ci.yaml").read_text())
    if section:
        config["krauth2025"][section].update(changes)
    path = tmp_path / "config.yaml"
    path.write_text(yaml.safe_dump(config))
    return path


@pytest.mark.workflow
def test_ring_figure_plans_only_the_ring(tmp_path):
    result = _snakemake(
        tmp_path, _ci_config(tmp_path), "results/ci/krauth2025/fig04_13.pdf", "--dry-run"
    )
    plan = result.stdout + result.stderr
    assert result.returncode == 0, plan
    assert "krauth2025_simulate_ring" in plan
    for unrelated in (
        "krauth2025_simulate_line",
        "krauth2025_simulate_pin_snapshots",
        "edmd",
        "dsmc",
    ):
        assert unrelated not in plan


@pytest.mark.workflow
@pytest.mark.parametrize(
    ("section", "changes", "message"),
    [
        ("pins", {"length": 12}, "cannot hold 15 pins"),
        ("ring", {"step": 15}, "exceeds half the ring length"),
        ("pins", {"naive_length": 20}, "(naive_length): naive-pin would start about"),
        ("disks", {"n_disks": 40}, "cover more than 90 %"),
        ("disks", {"sigma": 0.245}, "too dense for tabula-rasa sampling"),
    ],
)
def test_impossible_pin_configs_stop_before_any_job(tmp_path, section, changes, message):
    result = _snakemake(tmp_path, _ci_config(tmp_path, section, **changes), "--cores", "1")
    assert result.returncode != 0
    assert message in result.stdout + result.stderr
    assert not (tmp_path / "results").exists()
