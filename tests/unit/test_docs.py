"""The front page and docs/: short, linked, and every quoted number generated from the
files the build and the bench write (kinetic.docs)."""

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from kinetic import docs

REPOSITORY = Path(__file__).resolve().parents[2]
PAGES = ("reproduced", "engines", "benchmarks", "configs", "cluster", "reproducibility", "layout")


def test_generated_blocks_match_their_sources():
    """README.md and docs/*.md hold exactly what kinetic.docs renders from
    docs/data/summary.json (collected from a build) and the configs (the cost plans)."""
    result = subprocess.run(
        [sys.executable, "-m", "kinetic.docs", "check"], capture_output=True, text=True
    )
    assert result.returncode == 0, result.stderr
    summary = json.loads((REPOSITORY / docs.SUMMARY).read_text())
    made = docs.blocks(summary)
    texts = [path.read_text() for path in docs.documents_with_blocks()]
    names = {match.group("name") for text in texts for match in docs.BLOCK.finditer(text)}
    assert {"agreement", "timings", "checks", "benchmarks", "plan-paper"} <= names
    assert names <= set(made)


def test_a_stale_number_is_caught():
    summary = json.loads((REPOSITORY / docs.SUMMARY).read_text())
    readme = (REPOSITORY / "README.md").read_text()
    check = summary["documents"]["montanero2007"]["checks"]["headlines"][0]
    check["value"] += 10 * check["error"]
    assert docs.apply_blocks(readme, docs.blocks(summary)) != readme


def test_readme_is_a_front_page():
    readme = (REPOSITORY / "README.md").read_text()
    lines = readme.splitlines()
    assert len(lines) <= 150
    first_screen = "\n".join(lines[:30])
    assert "make figures" in first_screen and "make test" in first_screen
    for page in PAGES:
        assert f"(docs/{page}.md)" in readme, page
        assert (REPOSITORY / "docs" / f"{page}.md").is_file()
    for image in re.findall(r"\]\((docs/gallery/[\w.]+\.png)\)", readme):
        path = REPOSITORY / image
        assert 5_000 < path.stat().st_size < 150_000, image
    assert len(re.findall(r"docs/gallery/\w+\.png", readme)) == len(docs.DOCUMENTS)


def test_every_link_between_pages_resolves():
    for path in docs.documents_with_blocks():
        for target in re.findall(r"\]\(([^)#:]+)(?:#[^)]*)?\)", path.read_text()):
            assert (path.parent / target).exists(), f"{path.name} links to {target}"


@pytest.mark.parametrize(
    ("value", "error", "text"),
    [
        (1.02649, 0.00641, "1.0265 ± 0.0064"),
        (0.1904, 0.041, "0.190 ± 0.041"),
        (10.8279, 0.159, "10.83 ± 0.16"),
        (3.0, 0.0, "3"),
        (1234.5, 56.0, "1234 ± 56"),
    ],
)
def test_measurements_are_quoted_to_their_error(value, error, text):
    assert docs.measurement(value, error) == text


def test_the_readme_quotes_a_timings_outcome_and_benchmarks_md_its_history():
    summary = json.loads((REPOSITORY / docs.SUMMARY).read_text())
    record = summary["timings"]["test"] | {"summary": "OUTCOME", "note": "HISTORY"}
    summary["timings"] = {"test": record}
    made = docs.blocks(summary)
    short, detail = made["timings"], made["timings-detail"]
    assert "OUTCOME" in short and "HISTORY" not in short
    assert "OUTCOME; HISTORY" in detail
    assert "`make figures` (" in short and "not measured yet" in short


def test_earlier_runs_are_folded_into_benchmarks_md_and_kept_by_collect(tmp_path):
    summary = json.loads((REPOSITORY / docs.SUMMARY).read_text())
    record = summary["timings"]["test"] | {"earlier": "OLD RUNS"}
    summary["timings"] = {"test": record}
    made = docs.blocks(summary)
    assert "OLD RUNS" not in made["timings"]
    folded = made["timings-detail"].split("<details>", 1)[1]
    assert "OLD RUNS" in folded and "</details>" in folded
    # collect rewrites the records from results/timings and keeps the hand-written history
    out = tmp_path / "summary.json"
    out.write_text(json.dumps({"timings": {"test": {"earlier": "OLD RUNS"}}}))
    timings = tmp_path / "timings"
    docs.timed(timings / "test.json", [sys.executable, "-c", "pass"])
    made = docs.collect(tmp_path / "results", tmp_path / "none", timings, out, gallery=None)
    assert made["timings"]["test"]["earlier"] == "OLD RUNS"
    # a record of another revision that a new one replaces heads the history
    record = made["timings"]["test"] | {"git_revision": "0123456789", "note": "THE RUN BEFORE"}
    out.write_text(json.dumps({"timings": {"test": record}}))
    made = docs.collect(tmp_path / "results", tmp_path / "none", timings, out, gallery=None)
    earlier = made["timings"]["test"]["earlier"]
    assert earlier.startswith("Earlier, 0123456's record") and "THE RUN BEFORE" in earlier
    assert earlier.endswith("OLD RUNS")


def test_collect_replaces_the_rows_of_the_engines_timed_again_and_keeps_the_rest(tmp_path):
    """A bench report in results/benchmarks replaces its engine's rows of the summary; an
    engine timed elsewhere (the GPU's report, kept in docs/data) keeps its rows; with
    ``benchmarks_only`` the documents and timings of the summary stay as they were."""
    summary = json.loads((REPOSITORY / docs.SUMMARY).read_text())
    out = tmp_path / "summary.json"
    out.write_text(json.dumps(summary))
    engines = {row["engine"] for row in summary["benchmarks"]}
    assert {"edmd", "cuda"} <= engines
    old_edmd = [row for row in summary["benchmarks"] if row["engine"] == "edmd"]
    report = {
        "engine": "edmd",
        "machine": old_edmd[0] | {"git_revision": "fedcba9", "load_average_1min": 0.1},
        "cases": [
            {
                "dimension": 2,
                "n_particles": 1000,
                "density": 0.01,
                "collisions_per_cpu_second": 1.5e6,
            }
        ],
    }
    benchmarks = tmp_path / "benchmarks"
    benchmarks.mkdir()
    (benchmarks / "edmd.json").write_text(json.dumps(report))
    made = docs.collect(
        tmp_path / "no-build", benchmarks, tmp_path / "none", out, None, benchmarks_only=True
    )
    edmd = [row for row in made["benchmarks"] if row["engine"] == "edmd"]
    assert [(row["rate"], row["revision"]) for row in edmd] == [(1.5e6, "fedcba9")]
    for engine in engines - {"edmd"}:
        kept = [row for row in summary["benchmarks"] if row["engine"] == engine]
        assert [row for row in made["benchmarks"] if row["engine"] == engine] == kept
    assert made["documents"] == summary["documents"] and made["timings"] == summary["timings"]
    assert json.loads(out.read_text()) == made
    # a whole collect from an empty build keeps the rows of engines it has no report of too
    made = docs.collect(tmp_path / "no-build", tmp_path / "none", tmp_path / "none", out, None)
    assert {row["engine"] for row in made["benchmarks"]} == engines


def test_timed_records_the_command_and_passes_its_exit_code_on(tmp_path):
    out = tmp_path / "timing.json"
    code = docs.timed(out, [sys.executable, "-c", "import sys; sys.exit(3)"])
    assert code == 3
    record = json.loads(out.read_text())
    assert record["exit_code"] == 3 and record["wall_seconds"] > 0
    assert record["machine"]["git_revision"]


@pytest.mark.parametrize("report", sorted((REPOSITORY / "docs" / "data").glob("cuda-*.json")))
def test_each_gpu_case_has_a_row_of_its_own(report):
    """Every GPU run kept in docs/data gives rows with distinct cases: the homogeneous DSMC
    labelled by α, shape, splitting and δt, the runs of one shape that differ only in their
    seed folded into one row."""
    from kinetic.bench.summary import rows

    cases = [row["case"] for row in rows(json.loads(report.read_text()))]
    assert len(cases) == len(set(cases))


def test_a_gpu_dsmc_row_is_the_engine_rate_or_the_median_of_the_seeds():
    from kinetic.bench.summary import rows

    machine = {"cpu": "x", "load_average_1min": 0.0, "git_revision": "abc", "date": "d"}
    shape = {"n_particles": 200_000, "realizations": 50, "restitution": 0.9}
    scaling = {"n_particles": 200_000, "realizations": 100, "restitution": 1.0}
    report = {
        "engine": "cuda",
        "machine": machine,
        "gpu": {"device": "GPU"},
        "sections": {
            "dsmc_speed": {"gpu": [shape | {"collisions_per_second": r} for r in (1, 2, 9)]},
            "dsmc_scaling": {
                "gpu": [
                    scaling | {"engine_collisions_per_second": 5.0, "collisions_per_second": 1.0}
                ]
            },
        },
    }
    made = {row["case"]: (row["rate"], row["unit"]) for row in rows(report)}
    assert made == {
        "homogeneous DSMC on GPU, alpha = 1, N = 2e+05 x 100 realizations, strang splitting, "
        "dt = 0.1 tau": (5.0, "accepted collisions per engine-s"),
        "homogeneous DSMC on GPU, alpha = 0.9, N = 2e+05 x 50 realizations, "
        "a snapshot every step": (2.0, "collisions per wall-s"),
    }
