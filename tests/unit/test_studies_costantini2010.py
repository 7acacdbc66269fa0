"""kinetic.studies.costantini2010: runs from the config, units, and refusals before any job."""

import math
from pathlib import Path

import pytest
import yaml

from kinetic.studies import costantini2010 as study

CONFIG = Path(__file__).resolve().parents[2] / "config"


def section(name="config.yaml"):
    return yaml.safe_load((CONFIG / name).read_text())["costantini2010"]


@pytest.mark.parametrize("name", ["ci.yaml", "config.yaml", "paper.yaml"])
def test_every_shipped_config_gives_named_runs_and_passes_the_checks(name):
    settings = section(name)
    study.check({"costantini2010": settings})
    runs = study.runs(settings)
    assert len(runs) == len(set(runs))
    for name_, run in runs.items():
        assert run.name == name_
        assert "/" not in name_


def test_families_share_runs_with_the_same_parameters():
    settings = section()
    names = {run.name for run in study.grid_runs(settings)}
    figure = {run.name for run in study.figure_runs(settings)}
    n, alpha = settings["figures"]["particles"], settings["figures"]["restitution"]
    assert f"n{n}-alpha{alpha:g}-md" in names & figure
    assert len(study.runs(settings)) < len(study.grid_runs(settings)) + len(
        study.figure_runs(settings)
    ) + len(study.convergence_runs(settings))


def test_engine_units():
    settings = section()
    run = study.Run("dsmc", 1000, 0.8, 10, cell_side=0.5, time_step=0.05)
    arguments = run.engine_arguments(settings)
    density = settings["density"]
    mean_free_time = 1.0 / (2.0 * density * math.sqrt(math.pi))
    assert arguments["time_step"] == pytest.approx(0.05 * mean_free_time)
    assert arguments["sample_interval"] == pytest.approx(
        settings["sample_interval"] * mean_free_time
    )
    side = math.sqrt(1000 / density)  # 447 sigma, 6.3 mean free paths
    assert arguments["cells_per_side"] == round(side / (0.5 / (2 * math.sqrt(2) * density)))
    assert 5 < run.real_particles_per_cell(density) < 8
    assert (
        study.Run("dsmc", 1000, 0.8, 1, cell_side=0.1, time_step=0.05).real_particles_per_cell(
            density
        )
        < 1
    )


def test_unstable_sizes_are_refused_with_the_bound():
    settings = section() | {"density": 0.01, "restitutions": [1.0, 0.5], "particles": [3000]}
    with pytest.raises(ValueError, match=r"L_c|critical|unstable"):
        study.check({"costantini2010": settings})


def test_a_sample_interval_the_time_step_does_not_divide_is_refused():
    settings = section()
    settings["dsmc"] = settings["dsmc"] | {"time_step": 0.03}
    with pytest.raises(ValueError, match="whole multiple"):
        study.check({"costantini2010": settings})


def test_keys_that_contradict_each_other_are_refused():
    settings = section() | {"fit_start": 10, "max_lag": 3}
    with pytest.raises(ValueError, match="fit_start = 10 l/v_s starts the tail fit"):
        study.check({"costantini2010": settings})


def test_cuda_groups_the_grid_runs_of_each_n_with_their_own_arguments_and_seeds():
    """With ``backend: cuda`` every DSMC run is in exactly one place: a grid group of its N
    (every α of the config, in order) or a job of its own; a grouped run gets the
    arguments and seed its own job would have (so its file is the same), and the job
    table lists every file of the group's job."""
    from kinetic import plan
    from kinetic.config import load_configs

    config = load_configs([CONFIG / "paper.yaml"])
    paper = config["costantini2010"]
    groups = study.dsmc_groups(paper, "cuda")
    assert study.dsmc_groups(paper, "cpu") == {}
    assert list(groups) == [f"n{n}" for n in paper["particles"]]
    for name, runs in groups.items():
        assert [run.restitution for run in runs] == paper["restitutions"]
        assert {run.n_particles for run in runs} == {int(name[1:])}
    grouped = [run.name for runs in groups.values() for run in runs]
    dsmc = [name for name, run in study.runs(paper).items() if run.engine == "dsmc"]
    assert sorted(grouped + study.single_dsmc_runs(paper, "cuda")) == sorted(dsmc)
    assert study.single_dsmc_runs(paper, "cpu") == dsmc

    cpu_jobs = study.jobs(config | {"backend": "cpu"})
    cuda_jobs = study.jobs(config | {"backend": "cuda"})
    own = {job.output: job.arguments for job in cpu_jobs if job.output.endswith("batch0000.nc")}
    table = {row["output"]: row for row in plan.job_table(".", cuda_jobs)}
    for name in groups:
        (job,) = [job for job in cuda_jobs if job.rule == study.group_rule(name)]
        assert table[job.output]["outputs"].split() == list(job.files)
        for path, point in zip(job.files, job.arguments["points"], strict=True):
            alone = own[path]  # the cpu job of the run's first realizations
            assert point["seed"] == alone["seed"] and point["backend"] == "cuda"
            for key in set(alone) - {"label", "n_realizations", "backend"}:
                assert point[key] == alone[key], (path, key)
            assert point["n_realizations"] == paper["realizations"]
