"""Open a Snakemake report in headless Chromium (Debian's package) and read what it shows.

``report_panels(html)`` loads a copy of the report with a script appended that, once the
report's own app has rendered, opens the information panel of every result in turn
(``app.showResultInfo``, what a click on a result does) and records the text the page
shows: the front page, and per result its path, caption, size and rule. The dump of the
page after the scripts ran (``--dump-dom``) carries the record out.
"""

from __future__ import annotations

import html
import json
import os
import re
import shutil
import subprocess
import time
from pathlib import Path

import pytest

PROBE = """
<script>
window.addEventListener("load", function () {
  setTimeout(function () {
    var shown = {front: document.getElementById("app").innerText};
    var paths = Object.keys(results);
    function next(i) {
      if (i >= paths.length) {
        var record = document.createElement("pre");
        record.id = "kinetic-report-check";
        record.textContent = JSON.stringify(shown);
        document.body.appendChild(record);
        return;
      }
      app.showResultInfo(paths[i]);
      setTimeout(function () {
        shown[paths[i]] = document.getElementById("app").innerText;
        next(i + 1);
      }, 50);
    }
    next(0);
  }, 500);
});
</script>
"""

FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--virtual-time-budget=120000",
]

INSTALLING = Path("/tmp/kinetic-chromium-installing")
"""Present while .ci/run installs Chromium in the background."""


def chromium() -> str:
    """Debian's chromium. Waits while .ci/run is still installing it; without it the test
    is skipped, unless KINETIC_REQUIRE_BROWSER is set (CI), where that is a failure."""
    deadline = time.monotonic() + 900
    while INSTALLING.exists() and shutil.which("chromium") is None:
        if time.monotonic() > deadline:
            break
        time.sleep(5)
    found = shutil.which("chromium")
    if found is None:
        message = "Debian's chromium is not installed (apt-get install chromium)"
        if os.environ.get("KINETIC_REQUIRE_BROWSER"):
            pytest.fail(message)
        pytest.skip(message)
    return found


def report_panels(report: Path, workdir: Path) -> dict[str, str]:
    """{'front': text of the front page, <result path>: text of its panel}."""
    probe = workdir / "report-probe.html"
    probe.write_text(report.read_text() + PROBE)
    profile = f"--user-data-dir={workdir / 'chromium-profile'}"
    result = subprocess.run(
        [chromium(), *FLAGS, profile, "--dump-dom", probe.as_uri()],
        capture_output=True,
        text=True,
        timeout=300,
    )
    found = re.search(r'<pre id="kinetic-report-check">(.*?)</pre>', result.stdout, re.DOTALL)
    assert found, f"the report did not render in Chromium:\n{result.stderr[-2000:]}"
    return json.loads(html.unescape(found.group(1)))
