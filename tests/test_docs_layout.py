"""The documentation's layout for a user (issue 40), without building the site.

* The API reference (``api/index.rst``) lists the entry points a user calls, grouped by task; every
  other public module is on the developer reference (``api/internals.rst``), and every public module
  is on exactly one of the two.
* Developer material (the package layout, the before/after figure gallery) is under
  ``docs/developer/``, out of the user guide's toctree.
* The user guide has a template page for the user's own material, with a placeholder for each
  input and the commands that use them.

The full build with warnings as errors is ``tests/test_docs.py``.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"


@pytest.fixture(scope="module")
def ext():
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        import dhfield_docs
    finally:
        sys.path.remove(str(DOCS / "_ext"))
    return dhfield_docs


@pytest.fixture(scope="module")
def api_pages(ext, tmp_path_factory):
    out = tmp_path_factory.mktemp("api")
    ext.write_api(out)
    return out


def _listed(page: Path) -> list[str]:
    return re.findall(r"^   \* - :doc:`([\w.]+)`", page.read_text(), re.M)


def test_api_reference_lists_the_entry_points_and_internals_the_rest(ext, api_pages):
    user, internal = _listed(api_pages / "index.rst"), _listed(api_pages / "internals.rst")
    public = ext.public_modules()
    assert set(user) | set(internal) == set(public) and not set(user) & set(internal)
    assert user[0] == "dhfield" and {"dhfield.analysis.compare", "dhfield.analysis.dimensional", "dhfield.analysis.fit"} <= set(user)
    # the building blocks are not in the user's list
    assert not {"dhfield.core.elliptic", "dhfield.models.dh_elliptic_fields", "dhfield.analysis.eq30", "dhfield.bem.operator"} & set(user)
    assert len(user) <= 20 < len(public), (len(user), len(public))
    assert "developer reference </api/internals>" in (api_pages / "index.rst").read_text()


def test_developer_material_is_out_of_the_user_guide():
    howto = (DOCS / "howto" / "index.rst").read_text()
    assert "figure_gallery" not in howto and "your_material" in howto
    assert (DOCS / "developer" / "figure_gallery.rst").is_file() and not (DOCS / "howto" / "figure_gallery.rst").exists()
    dev = (DOCS / "developer" / "index.rst").read_text()
    assert all(p in dev for p in ("layout", "/api/internals", "figure_gallery"))
    index = (DOCS / "index.rst").read_text()
    toc = index[index.index(".. toctree::"):]
    assert toc.strip().splitlines()[-1].strip() == "developer/index"   # last, after the user's pages
    assert "\n   layout\n" not in toc


def test_template_page_has_a_placeholder_for_each_input_and_the_commands():
    text = (DOCS / "howto" / "your_material.rst").read_text()
    for name in ("``E``", "``NU``", "``R``", "``ANGLE``", "``DGAMMA``", "``SIGMA0``"):
        assert name in text, name
    assert text.count("FILL_IN") >= 6
    for cmd in ("dhfield pulloff $MAT", "dhfield compare $MAT", "dhfield fit $MAT", "dhfield solve $MAT"):
        assert cmd in text, cmd


def test_template_commands_parse(tmp_path):
    """Every command of the template, with the placeholders filled in (PDMS), is one the CLI accepts."""
    import shlex

    from dhfield.cli import build_parser

    values = {"E": "1.8e6", "NU": "0.49", "R": "3e-3", "ANGLE": "60", "DGAMMA": "0.045", "SIGMA0": "3e5"}
    text = (DOCS / "howto" / "your_material.rst").read_text()
    mat = re.search(r'MAT="([^"]+)"', text).group(1)
    commands = [ln.strip() for ln in text.splitlines() if ln.strip().startswith("dhfield ")]
    assert len(commands) >= 6
    parser = build_parser()
    for cmd in commands:
        line = cmd.replace("$MAT", mat).replace("FILL_IN", "-7e-4")
        for k, v in sorted(values.items(), key=lambda kv: -len(kv[0])):
            line = line.replace(f"${k}", v)
        parser.parse_args(shlex.split(line)[1:])
