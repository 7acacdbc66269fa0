"""kinetic.trace: the pipeline of a figure is the one Snakemake plans, shown file by file."""

import inspect
import re

import pytest

import kinetic.trace
from kinetic import dsmc, edmd
from kinetic.config import load_configs
from kinetic.trace import front_modules, main, trace

pytestmark = pytest.mark.workflow
FIG03 = "results/ci/montanero2007/fig03.pdf"


@pytest.fixture(scope="module")
def fig03(repository):
    return trace(FIG03, ["config/ci.yaml"], repository)


def test_montanero2007_fig03_runs_simulation_then_join_then_figure(repository, fig03):
    result = fig03
    rules = [step.rule for step in result.steps]
    assert rules == [
        "montanero2007_simulate_dsmc",
        "montanero2007_aggregate_dsmc",
        "montanero2007_fig03",
    ]
    simulate, _, figure = result.steps
    assert simulate.script == "workflow/scripts/simulate.py"  # the one simulate script
    # the jobs' front (the study's batch of a run), and the engine front behind it
    assert simulate.modules[0] == "src/kinetic/studies/montanero2007_front.py"
    engine = inspect.getsourcefile(dsmc.simulate_homogeneous)
    assert str(repository / simulate.modules[-1]) == engine
    assert "src/kinetic/theory/montanero2007.py" in figure.modules
    # the datasets between the stages: batches, the joined runs the figure reads, the figure
    aggregate = result.steps[1]
    batch = r"results/ci/montanero2007/dsmc/\w+/batch\d{4}\.nc"
    assert all(re.fullmatch(batch, f) for f in simulate.outputs)
    assert all(re.fullmatch(r"results/ci/montanero2007/dsmc/\w+\.nc", f) for f in aggregate.outputs)
    assert len(simulate.outputs) >= len(aggregate.outputs) > 1
    assert figure.outputs[0] == "results/ci/montanero2007/fig03.pdf"
    assert not any("dsmc" in module for module in aggregate.modules)  # joins, runs no engine
    assert "src/kinetic/analysis/montanero2007.py" in figure.modules
    assert result.files[0] == "config/ci.yaml"
    assert len(result.files) == len(set(result.files))
    config = (repository / "config/ci.yaml").read_text().splitlines()
    assert config[result.config_line - 1].startswith("montanero2007:")


def test_every_rule_of_the_whole_build_is_located(repository):
    """Each rule of the ci build is found where the tracer says, with its script."""
    result = trace("all", ["config/ci.yaml"], repository)
    assert len(result.steps) > 40
    for step in result.steps:
        lines = (repository / step.rule_file).read_text().splitlines()
        assert re.match(rf"(rule|checkpoint) {step.rule}:", lines[step.line - 1])
        assert step.script is None or (repository / step.script).is_file()
        assert all((repository / module).is_file() for module in step.modules)


def test_re_exported_engine_fronts_resolve_to_their_defining_files(repository):
    config = load_configs([repository / "config/ci.yaml"])
    for engine, front in (
        ("dsmc", dsmc.simulate_cooling_modes),
        ("md", edmd.simulate_cooling_modes),
    ):
        defining = inspect.getsourcefile(front)
        assert not defining.endswith("__init__.py")  # the module that writes the front
        modules = front_modules(f"costantini2010_simulate_{engine}", config, repository)
        assert [str(repository / module) for module in modules] == [defining]


def test_command_prints_the_reading_list(fig03, capsys, monkeypatch):
    calls = []
    monkeypatch.setattr(kinetic.trace, "trace", lambda *args: calls.append(args) or fig03)
    assert main([FIG03, "--configfile", "config/ci.yaml", "config/more.yaml"]) == 0
    assert calls == [(FIG03, ["config/ci.yaml", "config/more.yaml"], ".")]
    out = capsys.readouterr().out
    assert "rule     montanero2007_simulate_dsmc" in out and "rule     montanero2007_fig03" in out
    assert "writes results/ci/montanero2007/fig03.pdf (+2 more)" in out
    match = re.search(r"^(\d+) files:$", out, re.MULTILINE)
    assert int(match.group(1)) == len(fig03.files) == len(out[match.end() :].split())
