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

.PHONY: setup venv system-deps run test lint lint-imports docs package clean distclean

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

test: setup
	QT_QPA_PLATFORM=offscreen $(PY) -m pytest -q
	$(VENV)/bin/ruff check analysis app tests
	# the layering contracts in pyproject.toml ([tool.importlinter])
	$(VENV)/bin/lint-imports --no-cache
	# the user guide and API reference (docs/), warnings as errors
	$(SPHINX)
	# the benchmarks once, quickly: timing targets are reported, never failed on; a crash fails
	QT_QPA_PLATFORM=offscreen $(VENV)/bin/zwidth bench --quick

lint: setup
	$(VENV)/bin/ruff check analysis app tests
	$(VENV)/bin/lint-imports --no-cache

lint-imports: setup
	$(VENV)/bin/lint-imports --no-cache

# The Sphinx user guide and API reference into docs/_build/html/index.html.
docs: setup
	$(SPHINX)

# The standalone one-folder application (dist/zwidth/zwidth) with PyInstaller, then its test.
package: setup
	$(PY) -m pip install -e '.[test,package]'
	$(PY) packaging/build.py
	QT_QPA_PLATFORM=offscreen $(PY) -m pytest -q tests/test_packaging.py

clean:
	rm -rf build dist *.egg-info .pytest_cache .ruff_cache .hypothesis .import_linter_cache docs/_build $(STAMP)
	find analysis app tests -name __pycache__ -type d -prune -exec rm -rf {} +

distclean: clean
	rm -rf $(VENV)
