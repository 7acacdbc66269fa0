"""The workflow through SLURM, with Snakemake's own executor (snakemake-executor-plugin-slurm)
and the project's profile workflow/profiles/slurm, on a one-node SLURM cluster started on
this machine by tests/cluster/start_slurm.sh (Debian's munge, slurmctld, slurmd).

- a ``ci``-sized target set gives the same numbers (every table column and netCDF data
  variable but the measured CPU times) as a local run with the same seeds;
- a job cancelled with ``scancel`` while it runs is reported with its log, leaves no
  output, and the rerun builds only what is missing without touching finished outputs;
- a second invocation in the same directory is refused by Snakemake's lock;
- a job SLURM kills at its time limit is followed by a line naming the resource to raise.

Run: ``pytest -m cluster tests/cluster`` as root (it installs the Debian packages if they
are missing; skipped where SLURM cannot be installed). Only the daemons it started are
stopped afterwards.
"""

import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr

REPOSITORY = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
SNAKEMAKE = [sys.executable, "-m", "snakemake", "--snakefile", str(REPOSITORY / "Snakefile")]
CI_CONFIG = str(REPOSITORY / "config" / "ci.yaml")
TARGETS = [
    "results/ci/krauth2025/pins_table.csv",
    "results/ci/visco2008/dsmc/maxwell_free_paths.nc",
]
SLURM_OPTIONS = [
    "--workflow-profile",
    str(REPOSITORY / "workflow" / "profiles" / "slurm"),
    "--jobs",
    "4",
    "--latency-wait",
    "5",
    "--slurm-init-seconds-before-status-checks",
    "1",
]

pytestmark = [pytest.mark.cluster, pytest.mark.workflow]


@pytest.fixture(scope="module")
def slurm(tmp_path_factory):
    """A running one-node SLURM; stops on exit only the daemons this fixture started."""
    if os.geteuid() != 0:
        pytest.skip("the local SLURM cluster needs root (tests/cluster/start_slurm.sh)")
    if shutil.which("slurmctld") is None and shutil.which("apt-get") is None:
        pytest.skip("slurmctld is not installed and apt-get is not available to install it")
    started = tmp_path_factory.mktemp("slurm") / "started"
    env = {**os.environ, "STARTED_FILE": str(started)}
    result = subprocess.run(
        ["timeout", "-k", "10", "900", "bash", str(HERE / "start_slurm.sh")],
        capture_output=True,
        text=True,
        env=env,
    )
    if result.returncode != 0:
        stop = subprocess.run(["bash", str(HERE / "stop_slurm.sh")], env=env, check=False)
        pytest.skip(
            f"could not start a local SLURM cluster (exit {result.returncode}, stop "
            f"{stop.returncode}):\n{result.stdout[-2000:]}\n{result.stderr[-2000:]}"
        )
    yield
    subprocess.run(["bash", str(HERE / "stop_slurm.sh")], env=env, check=True, timeout=120)


def _snakemake(workdir, *args, check=True, timeout=900, background=False):
    env = {**os.environ, "MPLBACKEND": "Agg", "KINETIC_SLURM_PARTITION": "debug"}
    command = ["timeout", "-k", "10", str(timeout), *SNAKEMAKE, "--directory", str(workdir)]
    command += list(args)
    if background:
        return subprocess.Popen(
            command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env
        )
    result = subprocess.run(command, capture_output=True, text=True, env=env)
    if check and result.returncode != 0:
        raise AssertionError(f"snakemake failed:\n{result.stdout}\n{result.stderr}")
    return result


def _measured(name):
    """Variables and columns holding measured times, which differ between runs."""
    return "cpu" in name or "wall" in name


def _assert_same_numbers(local, remote):
    tables = sorted(p.relative_to(local) for p in (local / "results" / "ci").rglob("*.csv"))
    datasets = sorted(p.relative_to(local) for p in (local / "results" / "ci").rglob("*.nc"))
    assert tables and datasets
    for relative in tables:
        mine, theirs = pd.read_csv(local / relative), pd.read_csv(remote / relative)
        columns = [c for c in mine.columns if not _measured(c)]
        assert list(mine.columns) == list(theirs.columns), relative
        pd.testing.assert_frame_equal(mine[columns], theirs[columns], check_exact=True)
    for relative in datasets:
        with (
            xr.open_dataset(local / relative) as mine,
            xr.open_dataset(remote / relative) as theirs,
        ):
            assert set(mine.data_vars) == set(theirs.data_vars), relative
            for name in mine.data_vars:
                if not _measured(name):
                    np.testing.assert_array_equal(
                        mine[name].values, theirs[name].values, err_msg=f"{relative}:{name}"
                    )


def test_slurm_run_gives_the_numbers_of_a_local_run(slurm, tmp_path):
    local, remote = tmp_path / "local", tmp_path / "slurm"
    _snakemake(local, *TARGETS, "--configfile", CI_CONFIG, "--cores", "2")
    begin = time.monotonic()
    result = _snakemake(remote, *TARGETS, "--configfile", CI_CONFIG, *SLURM_OPTIONS)
    elapsed = time.monotonic() - begin
    log = result.stdout + result.stderr
    submitted = re.findall(r"has been submitted with SLURM jobid", log)
    assert len(submitted) >= 7, log  # every job of the target set went through sbatch
    _assert_same_numbers(local, remote)
    print(f"SLURM run of {len(TARGETS)} targets: {elapsed:.0f} s")


def _running_jobs():
    printed = subprocess.run(
        ["squeue", "-h", "-t", "RUNNING", "-o", "%i"], capture_output=True, text=True, check=True
    ).stdout
    return printed.split()


def test_scancel_loses_nothing_finished_and_the_rerun_builds_only_what_is_missing(slurm, tmp_path):
    # four DSMC jobs of 10-30 s, one at a time
    override = tmp_path / "longer.yaml"
    override.write_text(
        "visco2008:\n  dsmc:\n    maxwell_free_paths:\n      n_particles: 4000\n"
        "      duration: 20000\n      realizations: 8\n      realizations_per_job: 2\n"
    )
    target = "results/ci/visco2008/dsmc/maxwell_free_paths.nc"
    batches = tmp_path / "results" / "ci" / "visco2008" / "dsmc" / "maxwell_free_paths"
    configs = ["--configfile", CI_CONFIG, str(override)]
    run = _snakemake(
        tmp_path,
        target,
        *configs,
        *SLURM_OPTIONS,
        "--jobs",
        "1",
        "--retries",
        "0",
        background=True,
    )
    try:
        # with --jobs 1 a job starts after the previous one is finished for Snakemake: wait
        # for a batch file, then for the next job to start, and cancel that one at once
        # (a job takes seconds: anything done between seeing it and cancelling it, such
        # as the lock check below, which takes as long, lets it finish on a fast machine)
        deadline, running_at_first_file = time.monotonic() + 600, None
        while time.monotonic() < deadline:
            running = _running_jobs()
            if running_at_first_file is None and batches.exists() and any(batches.iterdir()):
                running_at_first_file = set(running)
                # a second invocation in the same directory is refused by Snakemake's lock
                second = _snakemake(tmp_path, target, *configs, "--cores", "1", check=False)
                assert second.returncode != 0
                assert "cannot be locked" in second.stdout + second.stderr
            elif running_at_first_file is not None and set(running) - running_at_first_file:
                break
            assert run.poll() is None, run.communicate()[0]
            time.sleep(0.2)
        else:
            raise AssertionError("no job started after the first batch finished")
        (cancelled,) = set(running) - running_at_first_file
        subprocess.run(["scancel", cancelled], check=True)
        finished = sorted(batches.glob("batch*.nc"))
        kept = {path: path.stat().st_mtime_ns for path in finished}
        output = run.communicate(timeout=600)[0]
    finally:
        if run.poll() is None:
            run.kill()
    assert run.returncode != 0, output
    assert "CANCELLED" in output, output
    # the failure names the job's log
    assert "results/ci/logs/visco2008/dsmc/maxwell_free_paths/batch" in output, output
    for path, mtime in kept.items():
        assert path.stat().st_mtime_ns == mtime
    done = set(batches.glob("batch*.nc"))
    missing = {batches / f"batch{k:04d}.nc" for k in range(4)} - done
    assert missing, "the cancelled job's output survived"
    # the rerun plans exactly the missing batches and the aggregate
    plan = _snakemake(tmp_path, target, *configs, "--cores", "2", "--dry-run", "--quiet", "rules")
    planned = plan.stdout + plan.stderr
    counts = dict(re.findall(r"^(\w+)\s+(\d+)$", planned, flags=re.MULTILINE))
    assert counts.get("visco2008_simulate_dsmc") == str(len(missing)), planned
    assert counts.get("visco2008_aggregate_dsmc") == "1", planned
    _snakemake(tmp_path, target, *configs, "--cores", "2")
    for path, mtime in kept.items():
        assert path.stat().st_mtime_ns == mtime
    assert all(path.exists() for path in missing)
    assert (tmp_path / target).exists()


def test_a_job_killed_at_its_time_limit_is_told_to_raise_its_runtime(slurm, tmp_path):
    # one DSMC job of ~100 s given a 1-minute limit
    override = tmp_path / "long.yaml"
    override.write_text(
        "visco2008:\n  dsmc:\n    maxwell_free_paths:\n      n_particles: 4000\n"
        "      duration: 30000\n      realizations: 16\n      realizations_per_job: 16\n"
    )
    result = _snakemake(
        tmp_path,
        "results/ci/visco2008/dsmc/maxwell_free_paths/batch0000.nc",
        "--configfile",
        CI_CONFIG,
        str(override),
        *SLURM_OPTIONS,
        "--retries",
        "0",
        "--set-resources",
        "visco2008_simulate_dsmc:runtime=1",
        check=False,
    )
    output = result.stdout + result.stderr
    assert result.returncode != 0
    assert "SLURM status is: 'TIMEOUT'" in output, output
    assert "was killed by SLURM (TIMEOUT): raise its runtime" in output, output
    assert "results/ci/logs/visco2008/dsmc/maxwell_free_paths/batch0000.log" in output
    assert not (tmp_path / "results/ci/visco2008/dsmc/maxwell_free_paths/batch0000.nc").exists()
