"""The DSMC part of the workflow: Fig. 12 plans only its own DSMC jobs."""

import pytest
from _snakemake import CI_CONFIG, snakemake


@pytest.mark.workflow
def test_fig12_plans_the_maxwell_jobs_only(tmp_path):
    result = snakemake(
        tmp_path, "results/ci/visco2008/fig12.pdf", "--dry-run", "--configfile", CI_CONFIG
    )
    plan = result.stdout + result.stderr
    assert result.returncode == 0, plan
    assert "results/ci/visco2008/dsmc/maxwell_free_paths/batch0000.nc" in plan
    assert "results/ci/visco2008/dsmc/maxwell_free_paths/batch0001.nc" in plan  # 8 = 2 x 4
    assert "batch0002" not in plan
    assert "free_flight_times" not in plan
    for rule in (
        "visco2008_simulate_dsmc",
        "visco2008_aggregate_dsmc",
        "visco2008_theory",
        "visco2008_fig12",
    ):
        assert rule in plan
