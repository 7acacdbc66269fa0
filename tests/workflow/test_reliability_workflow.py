"""A config means exactly what it says, bad values stop before any job with their key, and
a build killed mid-way resumes without losing or trusting anything half-written."""

import os
import signal
import subprocess
import sys
import time

import pytest
import yaml
from _snakemake import REPOSITORY, SNAKEMAKE, ci_config
from _snakemake import snakemake as _run

from kinetic import io
from kinetic.config import load_config_file, validate_config


def _snakemake(workdir, *args):
    # from the repository, where config/config.yaml would be found and merged by a
    # relative path
    return _run(workdir, *args, cwd=REPOSITORY)


@pytest.mark.workflow
@pytest.mark.parametrize(
    ("name", "root"),
    [("ci.yaml", "results/ci"), ("paper.yaml", "results/paper"), (None, "results")],
)
def test_effective_config_is_the_file_plus_schema_defaults(tmp_path, name, root):
    """No key of the default config leaks into a config given with --configfile, and each
    shipped config builds under a results root of its own."""
    arguments = [f"{root}/workflow/config.yaml", "--cores", "1"]
    if name is not None:
        arguments += ["--configfile", str(REPOSITORY / "config" / name)]
    result = _snakemake(tmp_path, *arguments)
    assert result.returncode == 0, result.stdout + result.stderr
    effective = yaml.safe_load((tmp_path / root / "workflow/config.yaml").read_text())
    expected = load_config_file(REPOSITORY / "config" / (name or "config.yaml"))
    validate_config(expected)
    assert effective == expected


BAD_CONFIGS = [
    ("seed: 7\ncostantini2010:\n  density: .nan\n", "costantini2010.density = nan"),
    ("seed: 7.0\n", "seed = 7.0 is not allowed: must be an integer"),
    ("seed: 7\nmontanero2007:\n  alphas: [1.0, .nan]\n", "montanero2007.alphas[1] = nan"),
    ("seed: 7\nmontanero2007:\n  alphas: [1.0, 0.305]\n", "montanero2007.alphas[1] = 0.305"),
]
"""Through the workflow; the whole table of bad values is tests/unit/test_config.py's."""


@pytest.mark.workflow
@pytest.mark.parametrize(("text", "message"), BAD_CONFIGS, ids=[m for _, m in BAD_CONFIGS])
def test_bad_configs_stop_before_any_job(tmp_path, text, message):
    bad = tmp_path / "bad.yaml"
    bad.write_text(text)
    result = _snakemake(tmp_path / "run", "--configfile", str(bad), "--cores", "1")
    assert result.returncode != 0
    assert message in result.stdout + result.stderr
    assert not (tmp_path / "run" / "results").exists()


def test_yaml_syntax_errors_name_file_and_line(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("seed: 7\ncostantini2010:\n  particles: [1000, 2000\n")
    result = subprocess.run(
        [sys.executable, "-m", "kinetic.config", str(bad)], capture_output=True, text=True
    )
    assert result.returncode == 1
    assert f"{bad}:4:1: not valid YAML" in result.stdout


RUN = "results/ci/costantini2010/dsmc/n1000-alpha1-f10-cell0.5-step0.05"
"""A costantini2010 DSMC run of two jobs of about 5 s each (``_start_build``'s config)."""


def _start_build(workdir, output):
    """Start Snakemake in the background, in a session of its own, on ``output`` of
    ``RUN`` under a ci config of two such jobs; returns ``(process, target arguments)``."""
    config = ci_config(
        workdir,
        lambda settings: settings["costantini2010"].update(
            {"realizations": 2, "realizations_per_job": 1, "min_duration": 600}
        ),
    )
    target = [output, "--cores", "1", "--configfile", str(config)]
    process = subprocess.Popen(
        [*SNAKEMAKE, "--directory", str(workdir), *target],
        cwd=REPOSITORY,
        env={**os.environ, "MPLBACKEND": "Agg"},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    return process, target


@pytest.mark.workflow
@pytest.mark.slow
def test_killed_build_resumes_without_losing_or_trusting_half_written_files(tmp_path):
    """kill -9 of the whole build while its second job runs: the first job's file is kept
    and not rebuilt, nothing half-written is under a final name, the lock is lifted with
    --unlock, and the rerun builds only what is missing (and removes the orphans)."""
    # two jobs of about 5 s each, so that the second is surely running when killed
    run = RUN
    process, target = _start_build(tmp_path, f"{run}.nc")
    batch_files = [tmp_path / run / f"batch{index:04d}.nc" for index in (0, 1)]
    logs = [
        tmp_path / "results/ci/logs" / run.removeprefix("results/ci/") / f"batch{i:04d}.log"
        for i in (0, 1)
    ]
    deadline = time.monotonic() + 300
    # Snakemake picks the order of the two jobs: wait until one is done and the other runs
    # (its job has opened its log), then kill at once: a job takes seconds, and on a fast
    # machine a pause here would let the second finish too (it did, at 2 s, on a Xeon)
    while time.monotonic() < deadline and process.poll() is None:
        done = [path.exists() for path in batch_files]
        if done.count(True) == 1 and all(log.exists() for log in logs):
            break
        time.sleep(0.05)
    os.killpg(process.pid, signal.SIGKILL)
    process.wait()
    done = [path.exists() for path in batch_files]
    assert done.count(True) == 1, f"expected one finished job when killed, got {done}"
    first, second = batch_files if done[0] else batch_files[::-1]
    kept = first.stat().st_mtime_ns
    io.read_dataset(first)  # complete
    assert not second.exists()  # the killed job left nothing under its final name
    locked = _snakemake(tmp_path, *target)
    assert locked.returncode != 0 and "unlock" in (locked.stdout + locked.stderr).lower()
    assert _snakemake(tmp_path, *target, "--unlock").returncode == 0
    resumed = _snakemake(tmp_path, *target)
    assert resumed.returncode == 0, resumed.stdout + resumed.stderr
    assert first.stat().st_mtime_ns == kept  # finished work was not redone
    io.read_dataset(second)
    io.read_dataset(tmp_path / f"{run}.nc")
    assert not list((tmp_path / "results").rglob("*.tmp"))


@pytest.mark.workflow
@pytest.mark.slow
def test_a_job_that_outlived_its_killed_build_is_rerun_by_a_plain_snakemake(tmp_path):
    """kill -9 of Snakemake alone while a job runs: the job finishes and writes its file,
    which Snakemake had marked incomplete. After --unlock, a plain ``snakemake`` (no
    --rerun-incomplete) reruns that job instead of refusing to start."""
    run = RUN
    process, target = _start_build(tmp_path, f"{run}/batch0000.nc")
    batch = tmp_path / run / "batch0000.nc"
    log = tmp_path / "results/ci/logs" / run.removeprefix("results/ci/") / "batch0000.log"
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline and process.poll() is None and not log.exists():
        time.sleep(0.05)
    assert process.poll() is None and log.exists(), "the job did not start"
    assert not batch.exists(), "the job finished before Snakemake could be killed"
    process.kill()  # Snakemake only: its job runs on
    process.wait()
    while time.monotonic() < deadline and not batch.exists():
        time.sleep(0.1)
    written = batch.stat().st_mtime_ns
    io.read_dataset(batch)
    assert _snakemake(tmp_path, *target, "--unlock").returncode == 0
    resumed = _snakemake(tmp_path, *target)
    assert resumed.returncode == 0, resumed.stdout + resumed.stderr
    assert batch.stat().st_mtime_ns != written  # rerun, not trusted
    io.read_dataset(batch)
