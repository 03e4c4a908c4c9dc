"""Every numbered equation of the paper that dhfield implements carries ``# Eq. (n)``.

This keeps the code traceable to the paper: a required equation missing from every
comment in ``dhfield/`` fails here, and so does a module that cites equations but has
no test module of its own.
"""
import re
from pathlib import Path

PKG = Path(__file__).resolve().parents[1] / "dhfield"
TESTS = Path(__file__).resolve().parent

#: Equations that define the implemented model (Eq. 1 is a definition, 17-19 and 9 are
#: assumptions cited where they are applied, 28-29 the definitions behind Eqs. 30-31).
REQUIRED = ({str(n) for n in range(2, 9)} | {str(n) for n in range(10, 17)} | {str(n) for n in range(20, 28)}
            | {"30", "31", "32", "33", "34", "35", "36", "A1", "A2", "B1", "B2", "B3"})

_TAG = re.compile(r"Eqs?\. \(([0-9AB]+)[a-c]?\)")


def _cited():
    found = {}
    for path in PKG.rglob("*.py"):
        for line in path.read_text().splitlines():
            if "#" not in line:
                continue
            comment = line.split("#", 1)[1]
            for eq in _TAG.findall(comment):
                found.setdefault(eq, set()).add(path)
    return found


def test_every_required_equation_is_cited_in_code():
    missing = REQUIRED - set(_cited())
    assert not missing, f"equations without a '# Eq. (n)' line: {sorted(missing)}"


def test_every_module_citing_equations_has_a_test_module():
    modules = {p for paths in _cited().values() for p in paths}
    lacking = []
    for p in modules:
        name = p.stem.lstrip("_")
        if p.parent.name in ("io", "bem", "sweep"):  # subpackages: tests/test_<package>_<module>.py
            name = f"{p.parent.name}_{name}" if p.stem != "__init__" else p.parent.name
        if not (TESTS / f"test_{name}.py").exists():
            lacking.append(str(p.relative_to(PKG.parent)))
    assert not lacking, f"modules without tests/test_<module>.py: {sorted(lacking)}"
