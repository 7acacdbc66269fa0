"""The montanero2007 part of the workflow: targets build only their runs; bad configs stop early."""

import pytest
from _snakemake import CI_CONFIG, ci_config, snakemake


@pytest.mark.workflow
def test_fig05_plans_only_its_two_runs(tmp_path):
    result = snakemake(
        tmp_path, "results/ci/montanero2007/fig05.pdf", "--dry-run", "--configfile", CI_CONFIG
    )
    assert result.returncode == 0, result.stderr
    plan = result.stdout + result.stderr
    assert "montanero2007_fig05" in plan
    assert "dsmc/alpha100/batch0000.nc" in plan and "dsmc/alpha090/batch0000.nc" in plan
    for unrelated in ("dsmc/alpha030/", "dsmc/hcs_", "dsmc/error_", "montanero2007_fig03"):
        assert unrelated not in plan


@pytest.mark.workflow
def test_bad_montanero2007_values_stop_before_any_job(tmp_path):
    def negative_step(config):
        config["montanero2007"]["protocol"]["time_step"] = -0.01

    result = snakemake(tmp_path, "--cores", "1", "--configfile", ci_config(tmp_path, negative_step))
    assert result.returncode != 0
    assert "montanero2007.protocol.time_step = -0.01" in result.stdout + result.stderr
    assert not (tmp_path / "results").exists()


@pytest.mark.workflow
def test_figure_alpha_outside_the_scan_is_named(tmp_path):
    def stray_alpha(config):
        config["montanero2007"]["figures"]["fig06_alphas"] = [0.7, 0.45]

    config = ci_config(tmp_path, stray_alpha)
    result = snakemake(tmp_path, "--cores", "1", "--dry-run", "--configfile", config)
    assert result.returncode != 0
    assert "montanero2007.figures.fig06_alphas" in result.stdout + result.stderr
