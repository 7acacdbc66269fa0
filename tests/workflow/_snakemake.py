"""How the workflow tests run Snakemake: the repository's Snakefile in a directory of the
test's own, with a headless matplotlib and the output captured; and the ci config with
a test's changes."""

import os
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import yaml

REPOSITORY = Path(__file__).resolve().parents[2]
SNAKEMAKE = [sys.executable, "-m", "snakemake", "--snakefile", str(REPOSITORY / "Snakefile")]
CI_CONFIG = REPOSITORY / "config" / "ci.yaml"


def snakemake(
    workdir: Path,
    *args: str | os.PathLike,
    timeout: float = 600,
    check: bool = False,
    cwd: Path | None = None,
) -> subprocess.CompletedProcess:
    """``snakemake --directory workdir *args``. Targets go before ``--configfile`` (after
    it Snakemake 9 reads them as more config files). ``check``: an AssertionError with
    Snakemake's output if it fails."""
    result = subprocess.run(
        [*SNAKEMAKE, "--directory", str(workdir), *map(str, args)],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=timeout,
        env={**os.environ, "MPLBACKEND": "Agg"},
        check=False,
    )
    if check and result.returncode != 0:
        raise AssertionError(f"snakemake failed:\n{result.stdout}\n{result.stderr}")
    return result


def ci_config(directory: Path, edit: Callable[[dict], object] | None = None) -> Path:
    """The ci config, changed by ``edit(config)`` where given, written to
    ``directory/config.yaml``; returns that path."""
    config = yaml.safe_load(CI_CONFIG.read_text())
    if edit is not None:
        edit(config)
    path = directory / "config.yaml"
    path.write_text(yaml.safe_dump(config))
    return path
