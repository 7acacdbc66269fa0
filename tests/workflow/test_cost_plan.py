"""The workflow's resource requests and budget check against kinetic.plan and kinetic.cost."""

import copy
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from _snakemake import CI_CONFIG, REPOSITORY, snakemake

from kinetic import cost, plan
from kinetic.config import validate_config

pytestmark = pytest.mark.workflow


def _planned(path):
    config = yaml.safe_load(Path(path).read_text())
    validate_config(config)
    return plan.plan_jobs(config)


def _dry_run_requests(output):
    """{first output: (rule, runtime, mem_mb)} of every job of a dry run's listing."""
    requests = {}
    for block in re.split(r"\n(?=rule \w+:\n)", output):
        rule = re.match(r"rule (\w+):\n", block)
        files = re.search(r"^    output: ([^,\n]+)", block, flags=re.MULTILINE)
        resources = re.search(r"^    resources: (.*)$", block, flags=re.MULTILINE)
        if rule and files and resources:
            values = dict(re.findall(r"(\w+)=([^,]*)", resources.group(1)))
            requests[files.group(1)] = (rule.group(1), values.get("runtime"), values.get("mem_mb"))
    return requests


def test_every_simulation_job_asks_for_its_planned_resources(tmp_path):
    """The dry run's simulation jobs are exactly kinetic.plan's, with its requests."""
    result = snakemake(tmp_path, "--configfile", str(CI_CONFIG), "--dry-run")
    output = result.stdout + result.stderr
    assert result.returncode == 0, output
    jobs = _planned(CI_CONFIG)
    assert "estimated cost of the config's" in output
    assert plan.summary_line(jobs) in output
    requests = _dry_run_requests(output)
    planned_rules = {job.rule for job in jobs}
    simulated = {path for path, (rule, _, _) in requests.items() if rule in planned_rules}
    assert simulated == {job.output for job in jobs}
    for job in jobs:
        rule, runtime, mem_mb = requests[job.output]
        assert rule == job.rule
        assert runtime == str(cost.runtime_minutes(job.estimate))
        assert mem_mb == str(cost.mem_mb(job.estimate))


@pytest.mark.parametrize(
    ("override", "expected"),
    [
        (  # cloning's transient grows like e^λ
            "visco2008:\n  cloning:\n    kernels:\n      hard_disks:\n"
            "        lambdas: [0.0, 20.0]\n        populations: [1000]\n",
            r"hard_disks/lam\+20\.000/N1000/batch0000\.nc: estimated [0-9.e+]+ CPU-hours",
        ),
        (
            "visco2008:\n  md:\n    n_particles: 10000000\n",
            r"md/rho1e-3/batch0000\.nc: estimated [0-9.]+ CPU-hours .*max_job_cpu_hours = 12",
        ),
        (
            "montanero2007:\n  protocol:\n    n_particles: 100000000\n",
            r"dsmc/alpha030/batch0000\.nc: would ask for [0-9.]+ GB of memory",
        ),
        (  # a configurable limit
            "limits:\n  max_total_cpu_hours: 0.01\n",
            r"estimated [0-9.]+ CPU-hours in all > limits\.max_total_cpu_hours = 0\.01",
        ),
    ],
)
def test_unaffordable_requests_are_refused_before_any_job(tmp_path, override, expected):
    extra = tmp_path / "override.yaml"
    extra.write_text(override)
    result = snakemake(tmp_path, "--configfile", str(CI_CONFIG), str(extra), "--cores", "1")
    output = result.stdout + result.stderr
    assert result.returncode != 0
    assert "refused before any job" in output
    assert re.search(expected, output), output
    assert not (tmp_path / "results").exists()


def test_plan_command_prints_the_table_and_refuses_what_the_workflow_refuses(tmp_path):
    command = [sys.executable, "-m", "kinetic.plan", "--configfile", str(CI_CONFIG)]
    result = subprocess.run(command, capture_output=True, text=True, check=True, cwd=REPOSITORY)
    assert plan.summary_table(_planned(CI_CONFIG)) in result.stdout
    extra = tmp_path / "override.yaml"
    extra.write_text("limits:\n  max_job_cpu_hours: 1.0e-6\n")
    refused = subprocess.run([*command, str(extra)], capture_output=True, text=True)
    assert refused.returncode == 1
    assert "max_job_cpu_hours = 1e-06" in refused.stderr


def test_cuda_jobs_ask_for_one_gpu_and_run_each_point_in_one_job(tmp_path):
    """backend: cuda (parsed on a machine without a GPU): the cloning, montanero2007 DSMC
    and costantini2010 DSMC jobs ask the scheduler for one GPU (resources gpu=1, the SLURM
    executor's --gpus=1), hold every realization of their point or run, and carry
    backend='cuda'; every other simulation job asks for none. The cloning points of a study,
    kernel and population up to ``visco2008_cloning.GROUPED_MAX_POPULATION`` (all of the ci
    config's) share one job of their group's rule, which writes each point's file; so do
    costantini2010's grid DSMC runs of one N (every α) and montanero2007's runs of one
    family."""
    from kinetic.studies import costantini2010 as costantini2010_study
    from kinetic.studies import montanero2007 as montanero2007_study
    from kinetic.studies import visco2008_cloning as cloning_plan

    extra = tmp_path / "cuda.yaml"
    cut = {"visco2008": {"cloning": {"realizations_per_job": 1}}}  # several CPU jobs a point
    extra.write_text(yaml.safe_dump({"backend": "cuda", **cut}))
    result = snakemake(tmp_path, "--configfile", str(CI_CONFIG), str(extra), "--dry-run")
    output = result.stdout + result.stderr
    assert result.returncode == 0, output
    config = yaml.safe_load(CI_CONFIG.read_text())
    config["visco2008"]["cloning"]["realizations_per_job"] = 1
    cpu_config = copy.deepcopy(config)
    config["backend"] = "cuda"
    validate_config(config)
    jobs = plan.plan_jobs(config)
    gpus, written = {}, {}
    for block in re.split(r"\n(?=rule \w+:\n)", output):
        files = re.search(r"^    output: (.+)$", block, flags=re.MULTILINE)
        resources = re.search(r"^    resources: (.*)$", block, flags=re.MULTILINE)
        if files and resources:
            paths = files.group(1).split(", ")
            gpus[paths[0]] = dict(re.findall(r"(\w+)=([^,]*)", resources.group(1)))
            written[paths[0]] = paths
    on_gpu = [job for job in jobs if job.gpus]
    groups = [("scan", "hard_disks"), ("scan", "maxwell"), ("error_vs_time", "hard_disks")]
    section = config["costantini2010"]
    sizes = [f"n{n}" for n in section["particles"]]
    families = ("scan", "field", "bias", "hcs", "error", "extreme")
    assert set(montanero2007_study.dsmc_groups(config["montanero2007"], "cuda")) == set(families)
    assert {job.rule for job in on_gpu} == {
        *(cloning_plan.group_rule(study, kernel) for study, kernel in groups),
        *(costantini2010_study.group_rule(size) for size in sizes),
        *(montanero2007_study.group_rule(family) for family in families),
        "costantini2010_simulate_dsmc",
    }
    for size in sizes:  # one job of every alpha
        (job,) = [job for job in on_gpu if job.rule == costantini2010_study.group_rule(size)]
        restitutions = [point["restitution"] for point in job.arguments["points"]]
        assert restitutions == [float(alpha) for alpha in section["restitutions"]]
    for job in jobs:
        assert gpus[job.output].get("gpu", "0") == str(job.gpus), job.output
        assert written[job.output] == list(job.files), job.output
        points = job.arguments.get("points", [job.arguments])
        assert all((point.get("backend") == "cuda") == bool(job.gpus) for point in points)
    validate_config(cpu_config)
    cpu_jobs = [job for job in plan.plan_jobs(cpu_config) if job.estimate.gpus == 0]
    runs = {
        job.output.rsplit("/", 1)[0]
        for job in cpu_jobs
        if job.rule
        in {"visco2008_simulate_cloning", "montanero2007_simulate_dsmc", *(j.rule for j in on_gpu)}
    }
    files = [path for job in on_gpu for path in job.files]
    assert sorted(files) == sorted(f"{run}/batch0000.nc" for run in runs)  # each once
    cloning = [job for job in on_gpu if job.rule.startswith("visco2008_simulate_cloning")]
    sizes = {(job.rule, job.arguments["points"][0]["population"]) for job in cloning}
    assert len(cloning) == len(sizes) < len(files)  # one job a study, kernel and N_c
