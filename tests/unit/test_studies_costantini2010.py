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
