"""Cloning rules of the workflow: target selection, early config rejection, a tiny real
run that writes cloning.csv with the columns other tools read, and resumption."""

import pandas as pd
import pytest
from _snakemake import CI_CONFIG, snakemake

# populations well above the diversity-collapse threshold (10 distinct velocities): at
# N_c = 20 and λ = 1 the fewest distinct velocities left is 9-11 depending on the stream,
# and a collapsed point has no extrapolation row
TINY = """seed: 3
visco2008:
  cloning:
    kernels:
      hard_disks: {lambdas: [0.5, 1.0], populations: [40, 80]}
      maxwell: {lambdas: [1.0], populations: [20]}
    collisions_per_realization: 5.0e+3
    realizations: 4
    realizations_per_job: 2
    n_blocks: 2
    transient: 5
"""


def run(workdir, *args, check=True):
    """Snakemake's output, stdout and stderr; with ``check``, a failure raises."""
    result = snakemake(workdir, *args, check=check, timeout=900)
    return result.stdout + result.stderr


@pytest.mark.workflow
def test_fig05_plans_only_the_hard_disk_scan(tmp_path):
    """The hard disks' points, their join and the reference; not the Maxwell points (Fig.
    4's), nor the whole scan's table, nor the error study."""
    plan = run(tmp_path, "results/ci/visco2008/fig05.pdf", "--dry-run", "--configfile", CI_CONFIG)
    assert "rule visco2008_simulate_cloning:" in plan
    assert "rule visco2008_cloning_kernel_table:" in plan
    assert "visco2008_theory_cloning_reference" in plan
    assert "cloning/scan/hard_disks/" in plan and "cloning/scan/maxwell" not in plan
    assert "rule visco2008_cloning_table:" not in plan
    assert "error_vs_time" not in plan
    for unrelated in ("visco2008_fig04", "visco2008_fig07", "visco2008_fig03"):
        assert f"rule {unrelated}:" not in plan


@pytest.mark.workflow
def test_bad_cloning_config_is_refused_before_any_job(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(TINY.replace("populations: [40, 80]", "populations: [1, 80]"))
    result = run(tmp_path, "--configfile", str(bad), "--cores", "1", check=False)
    assert "visco2008.cloning.kernels.hard_disks.populations.0 = 1" in result
    assert not (tmp_path / "results").exists()


@pytest.mark.workflow
@pytest.mark.slow
def test_tiny_scan_writes_the_table_and_resumes(tmp_path):
    config = tmp_path / "tiny.yaml"
    config.write_text(TINY)
    target = "results/visco2008/cloning.csv"
    run(tmp_path, target, "--configfile", str(config), "--cores", "2")
    table = pd.read_csv(tmp_path / target)
    assert list(table.columns) == [
        "kernel",
        "lambda",
        "mu",
        "mu_err",
        "T",
        "T_err",
        "a2",
        "a2_err",
        "n_c",
    ]
    assert set(table["kernel"]) == {"hard_disks", "maxwell"}
    assert table["n_c"].isna().sum() == 2  # extrapolations at λ = 0.5 and 1
    assert (table["mu_err"] > 0).all()
    # a run stopped before one batch and the aggregate finished resumes with just those
    batch = tmp_path / "results/visco2008/cloning/scan/hard_disks/lam+1.000/N80/batch0001.nc"
    batch.unlink()
    (tmp_path / target).unlink()
    plan = run(tmp_path, target, "--configfile", str(config), "--dry-run")
    assert plan.count("rule visco2008_simulate_cloning:") == 1
    assert "batch0001.nc" in plan and "rule visco2008_cloning_table:" in plan
