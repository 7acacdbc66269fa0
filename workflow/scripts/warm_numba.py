"""Compile one engine's numba kernels into the on-disk cache (rule warm_numba)."""

import importlib
import time

from kinetic.workflow_support import start

log = start(snakemake)
engine = snakemake.wildcards.engine
begin = time.perf_counter()
importlib.import_module(f"kinetic.{engine}").warmup()
log.info("compiled kinetic.%s kernels in %.1f s", engine, time.perf_counter() - begin)
