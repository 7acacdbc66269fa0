"""Compile one engine's numba kernels into the on-disk cache (rule warm_numba).

Two builds from one checkout (two users, or two results trees) share numba's cache: an
exclusive lock on a file beside the cache makes the second wait and then load what the
first compiled, instead of both writing the same cache files at once."""

import fcntl
import importlib
import os
import time
from pathlib import Path

import kinetic
from kinetic.workflow_support import start

log = start(snakemake)
engine = snakemake.wildcards.engine
cache = Path(os.environ.get("NUMBA_CACHE_DIR") or Path(kinetic.__file__).parent / "__pycache__")
cache.mkdir(parents=True, exist_ok=True)
begin = time.perf_counter()
with open(cache / f"kinetic-warm-{engine}.lock", "w") as lock:
    fcntl.flock(lock, fcntl.LOCK_EX)
    waited = time.perf_counter() - begin
    importlib.import_module(f"kinetic.{engine}").warmup()
log.info(
    "compiled kinetic.%s kernels in %.1f s (%.1f s waiting for another build's compilation)",
    engine,
    time.perf_counter() - begin - waited,
    waited,
)
