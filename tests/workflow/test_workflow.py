"""The Snakemake workflow: target selection, early config rejection, and a real ci run."""

import json
import os
import re
import shlex
import shutil
import subprocess
import sys

import pandas as pd
import pytest
import xarray as xr
import yaml
from _browser import report_panels
from _snakemake import CI_CONFIG, REPOSITORY, snakemake

from kinetic import DOCUMENTS, plan
from kinetic.config import validate_config


def _snakemake(workdir, *args, check=True):
    return snakemake(workdir, *args, check=check, timeout=1500)


def _planned_rules(workdir, *targets):
    result = _snakemake(workdir, *targets, "--dry-run", "--configfile", CI_CONFIG)
    return result.stdout + result.stderr


@pytest.mark.workflow
def test_one_figure_builds_only_what_it_needs(tmp_path):
    plan = _planned_rules(tmp_path, "results/ci/visco2008/fig03.pdf")
    assert "visco2008_fig03" in plan
    assert "visco2008_theory" in plan
    for unrelated in ("visco2008_fig11", "visco2008_table1"):
        assert unrelated not in plan


@pytest.mark.workflow
def test_readme_figures_command_plans_every_artefact(tmp_path):
    """``make figures`` (the README's first command) as a dry run: its snakemake line
    parses, and the default config plans every registered figure and table."""
    printed = subprocess.run(
        ["make", "-n", "figures"], cwd=REPOSITORY, capture_output=True, text=True, check=True
    ).stdout
    (line,) = [line for line in printed.splitlines() if "/snakemake " in line]
    command = shlex.split(line)
    command = command[command.index("--") + 1 :]  # after kinetic.docs timed's arguments
    assert command[1] == "all"  # a target after --configfile would be read as a config file
    result = snakemake(tmp_path, *command[1:], "--dry-run", cwd=REPOSITORY)
    plan = result.stdout + result.stderr
    assert result.returncode == 0, plan
    for rule in ("visco2008_fig01", "visco2008_fig12", "montanero2007_fig07", "visco2008_table1"):
        assert rule in plan


@pytest.mark.workflow
def test_lint_finds_nothing_but_the_missing_software_environments(tmp_path):
    """snakemake --lint: rule files hold only rules (helpers in common.smk files), every
    rule has a log; the one lint left asks for a conda environment or a container per
    rule, which the build machines cannot reach."""
    result = _snakemake(tmp_path, "--lint", "--configfile", CI_CONFIG, check=False)
    output = result.stdout + result.stderr
    titles = set(re.findall(r"^\s+\* (.+?):?$", output, re.MULTILINE))
    assert titles == {"Specify a conda environment or container for each rule."}, output


@pytest.mark.workflow
def test_bad_config_is_refused_before_any_job(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("seed: 1\nvisco2008:\n  theory:\n    rate_points: -3\n")
    result = _snakemake(tmp_path, "--configfile", str(bad), "--cores", "1", check=False)
    assert result.returncode != 0
    output = result.stdout + result.stderr
    assert "visco2008.theory.rate_points = -3" in output
    assert not (tmp_path / "results").exists()


@pytest.mark.workflow
def test_a_target_no_rule_file_registers_is_refused_with_the_registered_ones(tmp_path):
    """The target ids come from one registry (provide() in the rule files): the schema
    checks only their form, the workflow refuses an unknown id before any job."""
    config = tmp_path / "targets.yaml"
    config.write_text("seed: 1\ntargets: [visco2008/fig03, visco2008/fig99]\n")
    result = _snakemake(tmp_path, "--configfile", str(config), "--dry-run", check=False)
    output = result.stdout + result.stderr
    assert result.returncode != 0
    assert "['visco2008/fig99'], which this checkout cannot build" in output
    for registered in ("visco2008/fig03", "visco2008/checks", "krauth2025/checks"):
        assert f"'{registered}'" in output
    assert not (tmp_path / "results").exists()


TOY_RULE = """

provide("krauth2025/figtoy", *figure_files("krauth2025", "figtoy"))


rule krauth2025_figtoy:
    input:
        theory=results_file("krauth2025/theory/ring.nc"),
        code=script_code("krauth2025_figtoy"),
    output:
        pdf=results_file("krauth2025/figtoy.pdf"),
        png=report(
            results_file("krauth2025/figtoy.png"),
            caption="../../report/krauth2025_figtoy.rst",
            category="krauth2025",
        ),
    log:
        log_file("krauth2025/figtoy.log"),
    script:
        "../../scripts/krauth2025_figtoy.py"
"""

TOY_SCRIPT = """from kinetic import io, plotting
from kinetic.workflow_support import start

start(snakemake)
theory = io.read_dataset(snakemake.input.theory)
fig, ax = plotting.figure()
ax.plot(theory["r_curve"], theory["pair_density_curve"], "-")
plotting.save(fig, snakemake.output.pdf)
"""


@pytest.mark.workflow
def test_a_new_figure_needs_a_rule_entry_a_script_and_a_caption(tmp_path):
    """docs/layout.md's recipe on a copy of the workflow: a rule that registers its files
    (provide), a script and a caption, nothing else edited (no schema, no target list, no
    Snakefile). The id is then a config target, rule all builds it, and a build of the id
    alone runs only the rules it needs."""
    tree = tmp_path / "tree"
    tree.mkdir()
    shutil.copy(REPOSITORY / "Snakefile", tree / "Snakefile")
    for name in ("workflow", "config"):
        shutil.copytree(REPOSITORY / name, tree / name)
    with open(tree / "workflow" / "rules" / "krauth2025" / "rules.smk", "a") as rules:
        rules.write(TOY_RULE)
    (tree / "workflow" / "scripts" / "krauth2025_figtoy.py").write_text(TOY_SCRIPT)
    (tree / "workflow" / "report" / "krauth2025_figtoy.rst").write_text("A toy figure.\n")
    ci = yaml.safe_load(CI_CONFIG.read_text())
    config = tmp_path / "toy.yaml"
    config.write_text(yaml.safe_dump({**ci, "targets": ["krauth2025/figtoy"]}))
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(tree / "Snakefile")]

    def in_tree(*args):
        result = subprocess.run(
            [*command, "--directory", str(tmp_path), *args, "--configfile", str(config)],
            capture_output=True,
            text=True,
            timeout=600,
            env={**os.environ, "MPLBACKEND": "Agg"},
        )
        assert result.returncode == 0, result.stdout + result.stderr
        return result.stdout + result.stderr

    built = in_tree("--cores", "1")
    assert set(re.findall(r"^(?:local)?rule (\w+):", built, re.MULTILINE)) == {
        "krauth2025_theory_ring",
        "krauth2025_figtoy",
        "all",
    }
    assert (tmp_path / "results" / "ci" / "krauth2025" / "figtoy.png").stat().st_size > 0
    config.write_text(yaml.safe_dump({**ci, "targets": "all"}))
    assert "krauth2025_figtoy" not in in_tree("--dry-run")  # rule all: built already
    assert "krauth2025/figtoy.pdf" in in_tree("--dry-run", "--forceall")


@pytest.mark.workflow
def test_md_config_is_refused_by_the_fronts_own_checks_before_any_job(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(
        "seed: 1\nvisco2008:\n  md:\n    duration: 30\n    checkpoints: [10, 30]\n"
        "    windows: [1, 10, 50]\n    table_windows: [10]\n    ldf_windows: [10]\n"
        "    extrapolation_windows: [1, 10]\n    error_window: 10\n"
    )
    result = _snakemake(tmp_path, "--configfile", str(bad), "--cores", "1", check=False)
    assert result.returncode != 0
    output = result.stdout + result.stderr
    assert "config section visco2008.md: run rho1e-3: the longest window 50" in output
    assert not (tmp_path / "results").exists()


@pytest.mark.workflow
@pytest.mark.slow
def test_ci_config_builds_every_target_with_provenance(tmp_path):
    _snakemake(tmp_path, "--configfile", CI_CONFIG, "--cores", "2")
    results = tmp_path / "results" / "ci"
    for name in ("fig03", "fig11"):
        assert (results / "visco2008" / f"{name}.pdf").stat().st_size > 1000
        assert (results / "visco2008" / f"{name}.png").stat().st_size > 1000
    table = pd.read_csv(results / "visco2008" / "table1.csv")
    # the original columns come first and keep their names; new ones follow
    assert list(table.columns)[:9] == [
        "source",
        "rho",
        "t",
        "k1",
        "k2",
        "k3",
        "k1_err",
        "k2_err",
        "k3_err",
    ]
    assert {"Poisson", "Gaussian", "Sonine"} <= set(table["source"])
    assert {"paper_k2", "z_k2", "z_sonine_k2", "paper_row_density"} <= set(table.columns)
    assert set(table["kind"]) == {"md", "extrapolated", "dilute", "theory"}
    assert set(table.loc[table["kind"] == "dilute", "rho"]) == {0.0}
    assert (results / "visco2008" / "table1.caption.rst").stat().st_size > 100
    costantini = pd.read_csv(results / "costantini2010" / "table1.csv")
    assert list(costantini.columns) == [
        "method",
        "alpha",
        "n_particles",
        "fictive_factor",
        "tau_c",
        "tau_c_err",
        "amplitude",
        "amplitude_err",
        "nu_star",
        "nu_star_err",
        "nu_bar_star",
        "nu_bar_star_err",
        "ratio",
        "ratio_err",
        "zeta_star",
        "zeta_star_err",
    ]
    assert set(costantini["method"]) == {"theory", "md", "dsmc", "dsmc_homogeneous"}
    simulated = costantini[costantini["method"] != "theory"]
    assert simulated["nu_star_err"].gt(0).all()  # every simulated point has an error bar
    assert simulated["n_particles"].isna().any()  # the 1/N -> 0 rows
    # every dataset carries units and provenance
    for path in results.rglob("*.nc"):
        with xr.open_dataset(path) as dataset:
            for name, variable in dataset.variables.items():
                assert "units" in variable.attrs, f"{path}:{name}"
            stamped = json.loads(dataset.attrs["config"])
            assert stamped["seed"] == 7
            # the file's own document's section, no other (kinetic.workflow_support.output_config)
            document = path.relative_to(results).parts[0]
            assert set(stamped) & set(DOCUMENTS) == {document}, path
            assert dataset.attrs["git_revision"]
            # one provenance writer (kinetic.workflow_support.write_output) for every file
            provenance = {"seed", "root_seed", "config", "kinetic_version", "parameters_json"}
            assert provenance <= set(dataset.attrs), f"{path}: {sorted(dataset.attrs)}"
            assert dataset.attrs["root_seed"] == 7, path
    # every simulation job ran within the runtime and memory it asked for (kinetic.cost)
    config = yaml.safe_load(CI_CONFIG.read_text())
    validate_config(config)
    checked, overruns = plan.benchmark_overruns(tmp_path, plan.plan_jobs(config))
    assert checked >= 40, checked
    assert not overruns, overruns
    # a rerun has nothing to do, and the report renders every figure built
    rerun = _snakemake(
        tmp_path,
        "--configfile",
        CI_CONFIG,
        "--cores",
        "2",
        "--dry-run",
    )
    assert "Nothing to be done" in rerun.stdout + rerun.stderr
    report = _snakemake(
        tmp_path,
        "--configfile",
        CI_CONFIG,
        "--report",
        str(tmp_path / "report.html"),
    )
    assert (tmp_path / "report.html").stat().st_size > 10_000
    # every caption is valid reStructuredText (docutils reports ERROR/3 and WARNING/2 lines)
    assert "ERROR/" not in report.stderr and "WARNING/" not in report.stderr, report.stderr
    # the report as a browser shows it: the front page with each document's agreement,
    # and every figure and table of the build behind a click, with its caption
    panels = report_panels(tmp_path / "report.html", tmp_path)
    front = panels.pop("front")
    assert "Agreement with the documents" in front
    for document in ("visco2008", "montanero2007", "krauth2025", "costantini2010"):
        assert re.search(rf"{document}\t\d+\t\d+\t\d+\t\d+", front), front
    shown = {path for path, text in panels.items() if f"PATH\n{path}\nDESCRIPTION\n" in text}
    figures = {path.relative_to(tmp_path).as_posix() for path in results.rglob("*.png")}
    checks = {path.relative_to(tmp_path).as_posix() for path in results.glob("*/checks.csv")}
    assert figures | checks <= shown, sorted((figures | checks) - shown)
    for path in figures:
        caption = panels[path].split("DESCRIPTION\n", 1)[1].split("\nSIZE\n", 1)[0]
        assert len(caption.strip()) > 40, (path, caption)
