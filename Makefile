# dhfield: two commands for a fresh machine (only python3 needed).
#   make report   build .venv if missing, then run the verification report into out/
#   make test     build .venv if missing, then run the whole test suite (pytest-xdist: one worker
#                 per core, each test file on one worker so its module fixtures are built once)
#   make docs     install the docs extra, then build the documentation site into docs/_build/html
#                 (warnings are errors; the gallery's examples run)
PYTHON ?= python3
VENV   := .venv
STAMP  := $(VENV)/.dhfield-installed
REPORT_ARGS ?=

DOCS_STAMP := $(VENV)/.dhfield-docs-installed

.PHONY: report quick-report test bench docs clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/python -m pip install --quiet --upgrade pip
	$(VENV)/bin/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

report: $(STAMP)
	$(VENV)/bin/python -m verification.report --out out $(REPORT_ARGS)

quick-report: $(STAMP)
	$(VENV)/bin/python -m verification.report --out out --quick

test: $(STAMP)
	$(VENV)/bin/python -m pytest -q -n auto --dist loadfile

$(DOCS_STAMP): $(STAMP) pyproject.toml
	$(VENV)/bin/python -m pip install --quiet -e '.[docs]'
	touch $(DOCS_STAMP)

docs: $(DOCS_STAMP)
	MPLBACKEND=Agg $(VENV)/bin/python -m sphinx -b html -W --keep-going docs docs/_build/html

bench: $(STAMP)
	$(VENV)/bin/python -m verification.bench_analytic

clean:
	rm -rf out .pytest_cache
