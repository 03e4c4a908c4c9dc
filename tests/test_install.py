"""The install (issue 40): ``pip install .`` is a user install; the README builds what ``make`` expects.

* The run-time dependencies of pyproject.toml hold no test or documentation tool; those are the
  ``test`` and ``docs`` extras, and the Makefile installs ``-e '.[test]'``.
* The README's "Without make" command builds the environment the Makefile's stamp rule builds: the
  same ``.venv``, the same ``-e '.[test]'`` install, and the stamp file the Makefile checks, so
  that ``make`` does not rebuild it.  The README names ``pip install .`` as the user install.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
#: Distributions that only tests or the documentation build need.
DEV_TOOLS = ("pytest", "hypothesis", "compliance-checker", "pandas", "sphinx", "numpydoc", "sphinx-gallery",
             "pydata-sphinx-theme", "sphinx-argparse")


def _pyproject():
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover
        tomllib = pytest.importorskip("tomli")
    return tomllib.loads((ROOT / "pyproject.toml").read_text())


def _name(req):
    return re.split(r"[<>=!~;\[ ]", req, maxsplit=1)[0].strip().lower()


def test_user_install_has_no_test_or_docs_tools():
    project = _pyproject()["project"]
    runtime = {_name(r) for r in project["dependencies"]}
    assert not runtime & set(DEV_TOOLS), sorted(runtime & set(DEV_TOOLS))
    extras = project["optional-dependencies"]
    assert {"pytest", "hypothesis"} <= {_name(r) for r in extras["test"]}
    assert {"sphinx", "numpydoc"} <= {_name(r) for r in extras["docs"]}


def _make_vars():
    text = (ROOT / "Makefile").read_text()
    venv = re.search(r"^VENV\s*:=\s*(\S+)", text, re.M).group(1)
    stamp = re.search(r"^STAMP\s*:=\s*(\S+)", text, re.M).group(1).replace("$(VENV)", venv)
    recipe = text[text.index("$(STAMP):"):].split("\n\n")[0]
    return venv, stamp, recipe


def test_readme_without_make_builds_what_make_expects():
    venv, stamp, recipe = _make_vars()
    assert "-e '.[test]'" in recipe and "touch $(STAMP)" in recipe
    readme = (ROOT / "README.md").read_text()
    para = readme[readme.index("Without `make`"):]
    cmd = re.search(r"`(python3 -m venv [^`]+)`", para).group(1)
    steps = [s.strip() for s in cmd.split("&&")]
    assert steps[0] == f"python3 -m venv {venv}"
    assert any(re.fullmatch(rf"{re.escape(venv)}/bin/(python -m pip|pip) install -e '\.\[test\]'", s) for s in steps)
    assert steps[-1] == f"touch {stamp}", steps


def test_readme_names_the_user_install():
    readme = (ROOT / "README.md").read_text()
    assert re.search(r"`pip install \.`", readme)
