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


def test_timed_records_the_command_and_passes_its_exit_code_on(tmp_path):
    out = tmp_path / "timing.json"
    code = docs.timed(out, [sys.executable, "-c", "import sys; sys.exit(3)"])
    assert code == 3
    record = json.loads(out.read_text())
    assert record["exit_code"] == 3 and record["wall_seconds"] > 0
    assert record["machine"]["git_revision"]
