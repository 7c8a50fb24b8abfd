# zwidth: `make run` starts the program, `make test` runs the tests, the linters and the docs build.
SHELL := /bin/bash
.SHELLFLAGS := -euo pipefail -c

PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed
PROFILE ?= resources/profiles/hbfd.json
# The documentation, warnings as errors; -E rebuilds every page so that a warning in an unchanged
# page (or a changed docstring) still fails.
SPHINX := $(VENV)/bin/sphinx-build -E -W --keep-going -q -b html docs docs/_build/html

# Bytecode is written (into the ignored __pycache__ folders, which `make clean` removes) even where the
# shell sets PYTHONDONTWRITEBYTECODE: without it every test process compiled the project and
# assertion-rewrote the 225 test modules again, 7-10 CPU-s per process and per run.
unexport PYTHONDONTWRITEBYTECODE

# The test runner: headless, on every core (pytest-xdist), no pytest cache in the tree.
PYTEST := QT_QPA_PLATFORM=offscreen $(PY) -m pytest -q -n auto --dist worksteal -p no:cacheprovider
# One process: the second-kernel numerics run beside the suite's workers, so a worker pool of
# their own would only add its start-up and collection (about 16 s of CPU per worker).
PYTEST_ONE := QT_QPA_PLATFORM=offscreen $(PY) -m pytest -q -p no:cacheprovider
# The numerics tests (fitting, identification) run under another OpenBLAS kernel than the CPU's
# own, so that a test which holds only on one CPU's floating-point path fails here and not on a
# contributor's machine (issue 21): `make test` runs them under SECOND_KERNEL, `make test-all`
# (CI) under the CPU's own kernel too.  Sandybridge has AVX but no FMA: other roundings than the
# Haswell/Zen/SkylakeX kernels, and it runs on every x86-64 CPU that CI uses.
SECOND_KERNEL ?= Sandybridge

.PHONY: setup venv system-deps run test test-collect test-suite test-kernel bench-quick test-all lint lint-imports docs package clean distclean

# Check (and as root install) the system libraries Qt needs; create the venv; install the
# project editable with its test extra, again only when pyproject.toml changes.
setup venv: system-deps $(STAMP)

system-deps:
	bash packaging/system-deps.sh

$(PY):
	$(PYTHON) -m venv $(VENV)

$(STAMP): pyproject.toml | $(PY)
	$(PY) -m pip install -e '.[test]'
	touch $(STAMP)

run: setup
	$(VENV)/bin/zwidth $(PROFILE)

# The everyday tier: under five minutes on two cores.  The lints first (seconds), then side by side
# (make -j, output kept per target, any failure fails `make test`): the suite (every test once,
# the numerics ones excepted), the numerics tests under the second kernel, the documentation and
# the quick benchmarks.  Side by side, not one after the other: the four jobs keep both cores busy
# to the end, where the numerics tests alone (a few long fits) left one core idle for a minute.
test: setup
	$(VENV)/bin/ruff check analysis app tests
	# the layering contracts in pyproject.toml ([tool.importlinter])
	$(VENV)/bin/lint-imports --no-cache
	$(MAKE) --no-print-directory -j4 -Otarget test-suite test-kernel docs bench-quick

# One collection first, beside the docs and the benchmarks: it compiles the project and writes pytest's
# assertion-rewritten test modules once, so that the suite's workers and the numerics process start
# from them instead of each rewriting all 225 modules again (about 9 CPU-s per process on a fresh clone).
test-collect: setup
	QT_QPA_PLATFORM=offscreen $(PY) -m pytest -q -p no:cacheprovider --collect-only -m "not slow and not package" tests > /dev/null

# Every test once, except the numerics (test-kernel), slow (test-all) and package (package) ones.
test-suite: setup test-collect
	$(PYTEST) -m "not slow and not package and not numerics"

# The fitting and identification tests (the `numerics` marker, in tests/test_identify_*.py) under
# the second OpenBLAS kernel.
test-kernel: setup test-collect
	OPENBLAS_CORETYPE=$(SECOND_KERNEL) $(PYTEST_ONE) -m "numerics and not slow" tests/test_identify_*.py

# The benchmarks once, quickly: timing targets are reported, never failed on; a crash fails.
bench-quick: setup
	QT_QPA_PLATFORM=offscreen $(VENV)/bin/zwidth bench --quick

# Everything `make test` runs, then the numerics tests under the CPU's own kernel and the slow
# tier (a 1500-step seeded state-machine run, the 12 x 60 hypothesis state machine run, the full coverage
# replicates).  CI (.ci/run) runs this and `make package`.
test-all: test
	$(PYTEST) -m "numerics and not slow" tests/test_identify_*.py
	$(PYTEST) -m "slow and not package"

lint: setup
	$(VENV)/bin/ruff check analysis app tests
	$(VENV)/bin/lint-imports --no-cache

lint-imports: setup
	$(VENV)/bin/lint-imports --no-cache

# The Sphinx user guide and API reference into docs/_build/html/index.html.
docs: setup
	$(SPHINX)

# The standalone one-folder application (dist/zwidth/zwidth) with PyInstaller, then its test.
# build.py fails a build over 250 MB or one that freezes a test/docs package; with
# ZWIDTH_PACKAGE_TEST=1 the frozen-app tests fail, not skip, when there is no build.
package: setup
	$(PY) -m pip install -e '.[test,package]'
	$(PY) packaging/build.py
	ZWIDTH_PACKAGE_TEST=1 QT_QPA_PLATFORM=offscreen $(PY) -m pytest -q -p no:cacheprovider tests/test_packaging.py

clean:
	rm -rf build dist *.egg-info .pytest_cache .ruff_cache .hypothesis .import_linter_cache docs/_build $(STAMP)
	find analysis app tests -name __pycache__ -type d -prune -exec rm -rf {} +

distclean: clean
	rm -rf $(VENV)
