"""The krauth2025 part of the workflow: a figure plans only its samples; configs that no
line or ring can satisfy stop before any job."""

import pytest
from _snakemake import CI_CONFIG, ci_config, snakemake


@pytest.mark.workflow
def test_ring_figure_plans_only_the_ring(tmp_path):
    result = snakemake(
        tmp_path, "results/ci/krauth2025/fig04_13.pdf", "--dry-run", "--configfile", CI_CONFIG
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
    config = ci_config(tmp_path, lambda config: config["krauth2025"][section].update(changes))
    result = snakemake(tmp_path, "--cores", "1", "--configfile", config)
    assert result.returncode != 0
    assert message in result.stdout + result.stderr
    assert not (tmp_path / "results").exists()
