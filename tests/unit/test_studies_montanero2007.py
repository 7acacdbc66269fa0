"""kinetic.studies.montanero2007: run plan from the config, batches, combining batches."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
import yaml

from kinetic import batches, io
from kinetic.analysis import montanero2007 as analysis
from kinetic.config import validate_config
from kinetic.studies import montanero2007 as study

REPOSITORY = Path(__file__).resolve().parents[2]
SCHEMA = REPOSITORY / "workflow" / "schemas" / "config.schema.yaml"


def _section(name="config.yaml"):
    config = yaml.safe_load((REPOSITORY / "config" / name).read_text())
    validate_config(config, SCHEMA)
    return config["montanero2007"]


def test_alpha_keys():
    assert study.alpha_key(0.3) == "alpha030"
    assert study.alpha_key(1.0) == "alpha100"
    assert study.alpha_key(0.35) == "alpha035"
    with pytest.raises(ValueError, match="two decimals"):
        study.alpha_key(0.333)


@pytest.mark.parametrize("name", ["config.yaml", "ci.yaml", "paper.yaml"])
def test_plan_of_every_shipped_config(name):
    section = _section(name)
    plan = study.run_plan(section)
    for alpha in section["alphas"]:
        run = plan[study.alpha_key(alpha)]
        assert run["family"] == "scan"
        assert run["reduced_field"] == section["protocol"]["reduced_field"]
    assert all(run["reduced_field"] == 0.0 for run in plan.values() if run["family"] == "hcs")
    for name_, run in plan.items():
        jobs = batches.plan(
            realizations=run["realizations"], realizations_per_job=run["realizations_per_job"]
        )
        assert sum(job.n_realizations for job in jobs) == run["realizations"], name_


def test_paper_config_is_the_papers_protocol():
    protocol = _section("paper.yaml")["protocol"]
    assert protocol["n_particles"] == 200_000
    assert protocol["time_step"] == 0.003
    assert protocol["realizations"] == 200
    assert protocol["reduced_field"] == 0.025
    assert protocol["force_step"] == "euler"
    alphas = _section("paper.yaml")["alphas"]
    assert min(alphas) == 0.3 and max(alphas) == 1.0


def test_inconsistent_sections_are_refused_with_the_key():
    section = copy.deepcopy(_section())
    section["figures"]["fig05_alphas"] = [0.95]
    with pytest.raises(ValueError, match=r"figures\.fig05_alphas"):
        study.run_plan(section)
    section = copy.deepcopy(_section())
    section["figures"]["fig07_alphas"] = [1.0, 0.5]  # the caption quotes 0.3 too
    with pytest.raises(ValueError, match=r"figures\.fig07_alphas .* must hold \[0\.3\]"):
        study.run_plan(section)
    section = copy.deepcopy(_section())
    section["protocol"]["time_step"] = 0.007
    with pytest.raises(ValueError, match="sample_interval / time_step"):
        study.run_plan(section)
    section = copy.deepcopy(_section())
    section["protocol"]["steady_from"] = 500
    with pytest.raises(ValueError, match="steady_from"):
        study.run_plan(section)


def test_values_the_engine_front_refuses_stop_the_parse():
    """The front's own checks (kinetic.dsmc.arguments) run on every run's arguments while
    the config is read: a steady_from that rounds up to the duration, or a field too large
    for the time step, used to pass here and fail every job at its start."""
    section = copy.deepcopy(_section("ci.yaml"))
    section["protocol"]["steady_from"] = 23.5  # 40 windows of 0.6 τ: rounds up to 24
    with pytest.raises(ValueError, match=r"run alpha030: histogram_start = 24.0 τ.*steady_from"):
        study.run_plan(section)
    section = copy.deepcopy(_section("ci.yaml"))
    section["protocol"].update(time_step=0.3, sample_stride=2)
    section["extreme"]["reduced_fields"] = [0.2]
    with pytest.raises(ValueError, match=r"run extreme_field200_alpha100: .*too large a force"):
        study.run_plan(section)


def _run():
    return {
        "n_particles": 200,
        "time_step": 0.02,
        "force_step": "euler",
        "selection": "ntc",
        "splitting": "lie",
        "reduced_field": 0.05,
        "duration": 2.0,
        "steady_from": 0.9,
        "sample_interval": 0.4,
        "sample_stride": 5,
        "realizations": 3,
        "realizations_per_job": 2,
        "cx_max": 4.0,
        "cx_bins": 40,
        "restitution": 0.8,
        "family": "scan",
    }


def test_batching_does_not_change_the_data(tmp_path):
    run = _run()
    whole = study.simulate_batch(run, seed=11, first=0, count=3, label="whole")
    paths = []
    jobs = batches.plan(realizations=3, realizations_per_job=2)
    for index, first, count in jobs:
        batch = study.simulate_batch(run, seed=11, first=first, count=count, label="part")
        batch = io.stamp(batch, parameters={**io.parameters_of(batch), "run": "x"}, seed=11)
        paths.append(io.write_dataset(batch, tmp_path / f"batch{index}.nc"))
    combined = io.read_run(paths[::-1])
    assert list(combined.realization.values) == [0, 1, 2]
    np.testing.assert_array_equal(combined["moments"].values, whole["moments"].values)
    np.testing.assert_array_equal(combined["cx_counts"].values, whole["cx_counts"].values)
    # the histograms start at the first window boundary at or after steady_from
    assert combined.attrs["steady_from_tau"] == pytest.approx(1.2)
    assert io.parameters_of(combined)["n_realizations"] == 3
    # the joined run, written once, is what the figures read back, named by its run
    joined = io.write_dataset(combined, tmp_path / "x.nc")
    assert list(analysis.load_runs([joined])) == ["x"]
    np.testing.assert_array_equal(analysis.load_runs([joined])["x"]["moments"], whole["moments"])
    with pytest.raises(ValueError, match="read twice"):
        analysis.load_runs([joined, joined])


def test_schema_defaults_are_the_default_config():
    defaults = {"seed": 1}
    validate_config(defaults, SCHEMA)
    assert defaults["montanero2007"] == _section("config.yaml")


def test_runs_sharing_a_job_give_what_they_give_alone():
    """``simulate_batches`` (a family's runs in one job with ``backend: cuda``) gives each
    run the numbers of its own ``simulate_batch`` call and stamps the run's name, family
    and setting, which the analyses read back (``load_runs``); a bad point is refused
    before the first one runs. Here on the cpu: the same front for either backend."""
    first = _run()
    second = {**_run(), "restitution": 0.5, "reduced_field": 0.0}
    points = [
        {"run": first, "seed": 3, "first": 0, "count": 2, "label": "a"},
        {"run": second, "seed": 4, "first": 1, "count": 1, "label": "b"},
    ]
    stamps = [
        {"run": "alpha080", "family": "scan", "setting": ""},
        {"run": "hcs_alpha050", "family": "hcs", "setting": ""},
    ]
    together = study.simulate_batches(
        [point | {"parameters": stamp} for point, stamp in zip(points, stamps, strict=True)]
    )
    for point, stamp, dataset in zip(points, stamps, together, strict=True):
        alone = study.simulate_batch(**point)
        for name in set(alone.data_vars) - {"cpu_seconds"}:
            np.testing.assert_array_equal(dataset[name].values, alone[name].values, err_msg=name)
        assert dataset.attrs["steady_from_tau"] == alone.attrs["steady_from_tau"]
        parameters = io.parameters_of(dataset)
        assert parameters == {**io.parameters_of(alone), **stamp}
    from kinetic.dsmc import homogeneous

    runs = []
    engine = homogeneous.simulate_homogeneous

    def counted(**arguments):
        if not arguments.get("validate_only"):
            runs.append(arguments["label"])
        return engine(**arguments)

    bad = {**_run(), "time_step": 0.3}  # not a divisor of the sample interval
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(homogeneous, "simulate_homogeneous", counted)
        with pytest.raises(ValueError, match="sample_interval"):
            study.simulate_batches(
                [
                    points[0] | {"parameters": stamps[0]},
                    {**points[1], "run": bad, "parameters": stamps[1]},
                ]
            )
    assert runs == []  # the first point did not run either


def test_cuda_groups_a_familys_runs_with_their_own_arguments_seeds_and_stamps():
    """With ``backend: cuda`` every run is in exactly one family's job, in plan order, with
    the arguments, seed and stamps its own job would have (the realizations all in one
    batch), and the job writes each run's one batch file; on the cpu no run is grouped."""
    config = yaml.safe_load((REPOSITORY / "config" / "paper.yaml").read_text())
    validate_config(config, SCHEMA)
    section = config["montanero2007"]
    assert study.dsmc_groups(section, "cpu") == {}
    assert study.single_runs(section, "cpu") == list(study.run_plan(section))
    assert study.single_runs(section, "cuda") == []
    groups = study.dsmc_groups(section, "cuda")
    plan = study.run_plan(section)
    assert sorted(name for names in groups.values() for name in names) == sorted(plan)
    for group, names in groups.items():
        assert names == [name for name, run in plan.items() if run["family"] == group]
    cpu = {job.output: job for job in study.jobs(config | {"backend": "cpu"})}
    cuda = study.jobs(config | {"backend": "cuda"})
    assert [job.rule for job in cuda] == [study.group_rule(group) for group in groups]
    for job, (group, names) in zip(cuda, groups.items(), strict=True):
        assert job.gpus == 1
        assert list(job.files) == study.group_files(names)
        for name, point in zip(names, job.arguments["points"], strict=True):
            alone = cpu[f"montanero2007/dsmc/{name}/batch0000.nc"]
            assert point["seed"] == alone.arguments["seed"] and point["backend"] == "cuda"
            assert point["run"] == alone.arguments["run"]
            assert point["first"] == 0 and point["count"] == plan[name]["realizations"]
            assert point["parameters"] == alone.parameters
            assert alone.parameters["family"] == group


def test_more_realizations_leave_the_finished_batches_as_they_are():
    """A job's arguments (its rule's params) hold only what its numbers depend on: doubling
    the protocol's realizations adds batches and leaves every existing batch's arguments,
    so Snakemake reruns none of them (the whole run dict, realizations included, reran
    them all)."""
    config = yaml.safe_load((REPOSITORY / "config" / "config.yaml").read_text())
    validate_config(config, SCHEMA)
    more = copy.deepcopy(config)
    more["montanero2007"]["protocol"]["realizations"] *= 2
    before = {job.output: job.arguments for job in study.jobs(config)}
    after = {job.output: job.arguments for job in study.jobs(more)}
    assert set(before) < set(after)
    for output, arguments in before.items():
        assert after[output] == arguments, output
    # what a job carries (ENGINE_KEYS) is all that the engine's arguments are made of
    from kinetic.studies.montanero2007_front import engine_arguments, engine_run

    for run in study.run_plan(config["montanero2007"]).values():
        batch = {"seed": 1, "first": 0, "count": 2, "label": "x"}
        assert engine_arguments(engine_run(run), **batch) == engine_arguments(run, **batch)
