# dhfield: two commands for a fresh machine (only python3 needed).
#   make report   build .venv if missing, then run the verification report into out/
#   make test     build .venv if missing, then run the whole test suite
PYTHON ?= python3
VENV   := .venv
STAMP  := $(VENV)/.dhfield-installed
REPORT_ARGS ?=

.PHONY: report quick-report test bench clean

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
	$(VENV)/bin/python -m pytest -q

bench: $(STAMP)
	$(VENV)/bin/python -m verification.bench_analytic

clean:
	rm -rf out .pytest_cache
