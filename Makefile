# Two entry points, each creating its own virtual environment first:
#   make figures   build every available figure and table with config/config.yaml
#   make test      lint and run the whole test suite (what CI runs)
#   make test-fast lint and run the tests not marked slow (minutes, for editing)
#   make docs      after make figures and the benches: the README's and docs/' numbers,
#                  thumbnails and tables from results/ (python -m kinetic.docs)
#   make gpu-wheels  the wheels a GPU machine without network needs for
#                  tests/gpu/check-on-gpu.sh, into .whl/ (docs/gpu.md)
# make figures and make test record their duration in results/timings/ (kinetic.docs timed).
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
CORES ?= all
# pytest-xdist workers of make test / test-fast (each with its own numba cache)
TEST_WORKERS ?= 2
CONFIG ?= config/config.yaml
# extra snakemake options, e.g. SNAKEMAKE_ARGS=-n for a dry run
SNAKEMAKE_ARGS ?=

TIMED = $(BIN)/python -m kinetic.docs timed
FIGURES_TIMING = results/timings/figures-$(basename $(notdir $(CONFIG))).json

.PHONY: install figures test test-fast lint docs clean-results gpu-wheels

install: $(VENV)/.installed

# uv (pinned in environment-pip.txt) installs the pins and compiles their bytecode (41 s
# in all, against 87 s with pip, on 2 cores); pip only installs uv itself.
$(VENV)/.installed: environment-pip.txt pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check $$(grep '^uv==' environment-pip.txt)
	$(BIN)/uv pip install --quiet --compile-bytecode --python $(BIN)/python -r environment-pip.txt
	$(BIN)/uv pip install --quiet --python $(BIN)/python --no-deps -e .
	touch $@

# a build with SNAKEMAKE_ARGS (a dry run, a forced rerun) is not timed: its duration would
# replace the recorded build's in the README (make docs)
figures: install
	$(BIN)/python -m kinetic.config $(CONFIG)
	$(if $(strip $(SNAKEMAKE_ARGS)),,$(TIMED) $(FIGURES_TIMING) --) $(BIN)/snakemake all --cores $(CORES) --configfile $(CONFIG) $(SNAKEMAKE_ARGS)

lint: install
	$(BIN)/ruff check src workflow tests
	$(BIN)/ruff format --check src workflow tests
	$(BIN)/snakefmt --check Snakefile workflow

test: lint
	$(TIMED) results/timings/test.json -- $(BIN)/python -m pytest -n $(TEST_WORKERS) --maxschedchunk 1

test-fast: lint
	$(BIN)/python -m pytest -n $(TEST_WORKERS) --maxschedchunk 1 -m "not slow and not cluster"

docs: install
	$(BIN)/python -m kinetic.docs collect
	$(BIN)/python -m kinetic.docs render

# CPython 3.12 x86-64 wheels of the pins a GPU machine lacks or has in other versions: numpy
# (numba-cuda 0.30 does not compile on numpy >= 2.5), numba-cuda, jsonschema with its
# dependencies (kinetic.config) and netCDF4 with its (kinetic.io: the H100 of b66ff5b had
# none); attrs and the rest are on the lent machines.
GPU_WHEELS = numpy numba-cuda jsonschema jsonschema-specifications referencing rpds-py \
	netCDF4 cftime certifi
GPU_PLATFORMS = manylinux_2_28_x86_64 manylinux_2_27_x86_64 manylinux_2_24_x86_64 \
	manylinux_2_17_x86_64 manylinux2014_x86_64

gpu-wheels: install
	$(BIN)/python -m pip download --quiet --no-deps --only-binary=:all: --python-version 3.12 \
		--implementation cp $(addprefix --platform ,$(GPU_PLATFORMS)) -d .whl \
		$$($(BIN)/python -m pip freeze | grep -i $(foreach wheel,$(GPU_WHEELS),-e '^$(wheel)=='))

clean-results:
	rm -rf results logs .snakemake
